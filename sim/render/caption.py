"""A text caption along the bottom of an image, in Pillow's built-in font (no font files)."""

from __future__ import annotations

import numpy as np
from PIL import Image, ImageDraw, ImageFont

__all__ = ["add_caption"]

BAND = (24, 26, 30)
TEXT = (250, 250, 250)
# The most of a picture's height the caption band may cover: the picture is what shows the
# finding; the full messages are in the command's output and the report.
MAX_BAND_SHARE = 0.2


def _font(height: int) -> ImageFont.ImageFont | ImageFont.FreeTypeFont:
    size = max(9, min(18, height // 26))
    try:
        return ImageFont.load_default(size=size)  # Pillow's bundled font, same on every machine
    except (TypeError, OSError):  # Pillow without FreeType: the fixed bitmap font
        return ImageFont.load_default()


def _wrap(draw: ImageDraw.ImageDraw, text: str, font: ImageFont.ImageFont | ImageFont.FreeTypeFont,
          width: int) -> list[str]:
    """Greedy word wrap to `width` pixels; a word longer than a line is cut by characters."""
    lines: list[str] = []
    for paragraph in text.splitlines() or [""]:
        line = ""
        for word in paragraph.split(" "):
            trial = f"{line} {word}" if line else word
            if draw.textlength(trial, font=font) <= width or not line:
                line = trial
            else:
                lines.append(line)
                line = word
        lines.append(line)
    return lines


def add_caption(image: np.ndarray, text: str, max_lines: int = 3) -> np.ndarray:
    """A copy of image (H, W, 3) uint8 with `text` in a dark band at the bottom, at most
    `max_lines` lines and MAX_BAND_SHARE of the height (at least one line)."""
    picture = Image.fromarray(np.ascontiguousarray(image))
    draw = ImageDraw.Draw(picture)
    font = _font(picture.height)
    pad = 6
    lines = _wrap(draw, text, font, picture.width - 2 * pad)
    ascent, descent = font.getmetrics() if hasattr(font, "getmetrics") else (11, 3)
    line_h = ascent + descent + 2
    max_lines = max(1, min(max_lines, int((picture.height * MAX_BAND_SHARE - 2 * pad) // line_h)))
    if len(lines) > max_lines:  # say that the text goes on rather than cutting it silently
        lines = lines[:max_lines]
        lines[-1] = lines[-1].rstrip()[:-1] + "…" if len(lines[-1]) > 1 else "…"
    band_h = line_h * len(lines) + 2 * pad
    draw.rectangle((0, picture.height - band_h, picture.width, picture.height), fill=BAND)
    for i, line in enumerate(lines):
        draw.text((pad, picture.height - band_h + pad + i * line_h), line, fill=TEXT, font=font)
    return np.asarray(picture, dtype=np.uint8).copy()
