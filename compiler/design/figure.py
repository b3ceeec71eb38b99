"""A small 2-D figure as data (filled cells, line segments, text), drawn as PNG or as SVG.

Both writers draw the same primitive list, so the picture and the vector drawing agree;
coordinates are pixels, y down. Colours are (r, g, b) in 0..255.
"""

from __future__ import annotations

import html
from dataclasses import dataclass, field

import numpy as np

__all__ = ["Figure", "colormap", "to_png", "to_svg"]

Color = tuple[int, int, int]

# A perceptually ordered blue -> green -> yellow ramp (the end points and mid points of
# matplotlib's "viridis", https://bids.github.io/colormap/, as sRGB bytes); linear in between.
_RAMP = np.array([(68, 1, 84), (59, 82, 139), (33, 145, 140), (94, 201, 98), (253, 231, 37)], dtype=float)


def colormap(values: np.ndarray) -> np.ndarray:
    """values in [0, 1] (N,) -> (N, 3) uint8 colours on the ramp (0 = dark violet, 1 = yellow)."""
    v = np.clip(np.nan_to_num(np.asarray(values, dtype=float)), 0.0, 1.0) * (len(_RAMP) - 1)
    i = np.minimum(v.astype(int), len(_RAMP) - 2)
    f = (v - i)[:, None]
    return np.round(_RAMP[i] * (1 - f) + _RAMP[i + 1] * f).astype(np.uint8)


@dataclass
class Figure:
    width: int
    height: int
    cells: list[tuple[float, float, float, float, Color]] = field(default_factory=list)  # x, y, w, h
    lines: list[tuple[float, float, float, float, Color, float]] = field(default_factory=list)
    texts: list[tuple[float, float, str, int, Color]] = field(default_factory=list)  # x, y (top-left)

    def cell(self, x: float, y: float, w: float, h: float, color: Color) -> None:
        self.cells.append((x, y, w, h, color))

    def line(self, x0: float, y0: float, x1: float, y1: float, color: Color = (0, 0, 0), width: float = 1.0) -> None:
        self.lines.append((x0, y0, x1, y1, color, width))

    def text(self, x: float, y: float, s: str, size: int = 12, color: Color = (20, 20, 20)) -> None:
        self.texts.append((x, y, s, size, color))


def _font(size: int):  # type: ignore[no-untyped-def]
    from PIL import ImageFont  # late: PIL is heavy or optional, loaded only where used

    try:
        return ImageFont.load_default(size=size)  # Pillow's bundled font: the same on every machine
    except (TypeError, OSError):
        return ImageFont.load_default()


def to_png(fig: Figure) -> np.ndarray:
    """(H, W, 3) uint8."""
    from PIL import Image, ImageDraw  # late: PIL is heavy or optional, loaded only where used

    image = Image.new("RGB", (fig.width, fig.height), (255, 255, 255))
    draw = ImageDraw.Draw(image)
    for x, y, w, h, c in fig.cells:
        draw.rectangle((round(x), round(y), max(round(x + w) - 1, round(x)), max(round(y + h) - 1, round(y))), fill=c)
    for x0, y0, x1, y1, c, wd in fig.lines:
        draw.line((x0, y0, x1, y1), fill=c, width=max(1, round(wd)))
    for x, y, s, size, c in fig.texts:
        draw.text((x, y), s, fill=c, font=_font(size))
    return np.asarray(image, dtype=np.uint8).copy()


def _hex(c: Color) -> str:
    return "#%02x%02x%02x" % tuple(int(v) for v in c)


def to_svg(fig: Figure) -> str:
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{fig.width}" height="{fig.height}" '
           f'viewBox="0 0 {fig.width} {fig.height}" font-family="sans-serif">',
           f'<rect width="{fig.width}" height="{fig.height}" fill="#ffffff"/>']
    for x, y, w, h, c in fig.cells:
        out.append(f'<rect x="{x:.2f}" y="{y:.2f}" width="{w:.2f}" height="{h:.2f}" fill="{_hex(c)}"/>')
    for x0, y0, x1, y1, c, wd in fig.lines:
        out.append(f'<line x1="{x0:.2f}" y1="{y0:.2f}" x2="{x1:.2f}" y2="{y1:.2f}" stroke="{_hex(c)}" stroke-width="{wd:g}"/>')
    for x, y, s, size, c in fig.texts:
        out.append(f'<text x="{x:.2f}" y="{y + size:.2f}" font-size="{size}" fill="{_hex(c)}">{html.escape(s)}</text>')
    out.append("</svg>")
    return "\n".join(out) + "\n"
