"""Reach maps as pictures: slices (PNG / SVG) and an interactive 3-D point cloud (HTML).

A slice panel shows one plane of the cell: every grid cell the TCP reaches, coloured by the
map's quality (manipulability / best on the map), the fixtures cut by the plane (their
triangle meshes intersected with it, dark red), the circle that bounds the reach (dashed
grey) and the robot's base (a cross).
"""

from __future__ import annotations

import base64
import html as html_text
import json
import math
from dataclasses import dataclass
from importlib import resources

import numpy as np

from rmot.compiler.design.figure import Figure, colormap
from rmot.compiler.design.reach import ReachMap

__all__ = ["FixtureMesh", "Panel", "panels_figure", "reach_html", "section"]

FIXTURE = (150, 30, 30)
GRID = (225, 225, 225)
PANEL = 440
MARGIN = 46


@dataclass(frozen=True, eq=False)
class FixtureMesh:
    """A fixture as world triangles (T, 3, 3) m, and its oriented box (8, 3) world corners."""

    name: str
    triangles: np.ndarray
    corners: np.ndarray


@dataclass(frozen=True, eq=False)
class Panel:
    title: str
    plane: str  # "xy" (top view, at z = level) or "xz" (side view, at y = level)
    level: float
    step: float
    reach: ReachMap


def section(triangles: np.ndarray, axis: int, level: float) -> np.ndarray:
    """The segments (S, 2, 3) where the plane coordinate[axis] = level cuts the triangles."""
    d = triangles[:, :, axis] - level
    out = []
    for a, b in ((0, 1), (1, 2), (2, 0)):
        da, db = d[:, a], d[:, b]
        cross = (da * db) < 0
        t = np.where(cross, da / np.where(cross, da - db, 1.0), np.nan)
        out.append(triangles[:, a] + (triangles[:, b] - triangles[:, a]) * t[:, None])
    pts = np.stack(out, axis=1)  # (T, 3 edges, 3)
    ok = np.isfinite(pts[:, :, 0])
    two = ok.sum(axis=1) == 2
    segs = [pts[i][ok[i]] for i in np.flatnonzero(two)]
    return np.array(segs).reshape(-1, 2, 3)


def _axes(plane: str) -> tuple[int, int]:
    return (0, 1) if plane == "xy" else (0, 2)


def _draw_panel(fig: Figure, x0: float, y0: float, panel: Panel, fixtures: list[FixtureMesh]) -> None:
    m = panel.reach
    iu, iv = _axes(panel.plane)
    centre = m.base[:3, 3]
    half = m.bound + panel.step
    scale = PANEL / (2 * half)

    def px(u: float, v: float) -> tuple[float, float]:
        return x0 + (u - centre[iu] + half) * scale, y0 + (centre[iv] + half - v) * scale

    fig.text(x0, y0 - 30, panel.title, 13)
    for k in range(-int(half // 0.5), int(half // 0.5) + 1):  # a light grid every 0.5 m, labelled
        u = round((centre[iu] + k * 0.5) / 0.5) * 0.5
        v = round((centre[iv] + k * 0.5) / 0.5) * 0.5
        (a, _), (_, b) = px(u, 0.0), px(0.0, v)
        if x0 <= a <= x0 + PANEL:
            fig.line(a, y0, a, y0 + PANEL, GRID)
            fig.text(a - 12, y0 + PANEL + 3, f"{u:.1f}", 10)
        if y0 <= b <= y0 + PANEL:
            fig.line(x0, b, x0 + PANEL, b, GRID)
            fig.text(x0 - 34, b - 6, f"{v:.1f}", 10)
    names = "xyz"
    fig.text(x0 + PANEL / 2 - 20, y0 + PANEL + 16, f"{names[iu]} (m)", 11)
    fig.text(x0 - 44, y0 - 14, f"{names[iv]} (m)", 11)
    colors = colormap(m.quality[m.reached])
    w = panel.step * scale
    for p, c in zip(m.points[m.reached], colors):
        cx, cy = px(p[iu], p[iv])
        fig.cell(cx - w / 2, cy - w / 2, w, w, (int(c[0]), int(c[1]), int(c[2])))
    ring = np.linspace(0, 2 * math.pi, 97)
    for a, b in zip(ring[:-1:2], ring[1::2]):  # dashed: every other arc piece
        p0 = px(centre[iu] + m.bound * math.cos(a), centre[iv] + m.bound * math.sin(a))
        p1 = px(centre[iu] + m.bound * math.cos(b), centre[iv] + m.bound * math.sin(b))
        fig.line(*p0, *p1, (150, 150, 150))
    axis = 2 if panel.plane == "xy" else 1
    for f in fixtures:
        for s in section(f.triangles, axis, panel.level - 1e-6):  # just below: a table top at the level shows
            fig.line(*px(s[0, iu], s[0, iv]), *px(s[1, iu], s[1, iv]), FIXTURE, 2)
    bx, by = px(centre[iu], centre[iv])
    fig.line(bx - 6, by, bx + 6, by, (0, 0, 0), 2)
    fig.line(bx, by - 6, bx, by + 6, (0, 0, 0), 2)
    for a, b, c, d in ((x0, y0, x0 + PANEL, y0), (x0, y0 + PANEL, x0 + PANEL, y0 + PANEL),
                       (x0, y0, x0, y0 + PANEL), (x0 + PANEL, y0, x0 + PANEL, y0 + PANEL)):
        fig.line(a, b, c, d, (60, 60, 60))


def panels_figure(panels: list[Panel], fixtures: list[FixtureMesh], caption: list[str]) -> Figure:
    """Slices side by side, a colour bar on the right, the caption lines underneath."""
    width = MARGIN + len(panels) * (PANEL + MARGIN) + 70
    height = 40 + PANEL + 40 + 16 * len(caption) + 10
    fig = Figure(width, height)
    for k, panel in enumerate(panels):
        _draw_panel(fig, MARGIN + k * (PANEL + MARGIN), 40, panel, fixtures)
    bar_x = MARGIN + len(panels) * (PANEL + MARGIN) - 10
    steps = 64
    colors = colormap(np.linspace(1, 0, steps))
    for i, c in enumerate(colors):
        fig.cell(bar_x, 40 + i * PANEL / steps, 16, PANEL / steps + 1, (int(c[0]), int(c[1]), int(c[2])))
    fig.text(bar_x + 20, 36, "1", 11)
    fig.text(bar_x + 20, 40 + PANEL - 10, "0", 11)
    fig.text(bar_x - 4, 40 + PANEL + 3, "quality", 10)
    for i, line in enumerate(caption):
        fig.text(MARGIN, 40 + PANEL + 34 + 16 * i, line, 11)
    return fig


def _b64(a: np.ndarray, dtype: str = "<f4") -> str:
    return base64.b64encode(np.ascontiguousarray(a, dtype=dtype).tobytes()).decode("ascii")


def reach_html(m: ReachMap, fixtures: list[FixtureMesh], title: str, caption: list[str]) -> str:
    """One self-contained page (no network): the reached points in 3-D, coloured by quality,
    the fixtures' boxes as wire frames; drag to turn, wheel to zoom, a slider cuts the cloud
    at a height. Same map, same bytes."""
    pts = m.points[m.reached]
    data = {
        "points": _b64(pts),
        "colors": _b64(colormap(m.quality[m.reached]), "u1"),
        "fixtures": [{"name": f.name, "corners": [[round(float(v), 5) for v in c] for c in f.corners]} for f in fixtures],
        "base": [round(float(v), 5) for v in m.base[:3, 3]],
        "bound": round(float(m.bound), 5),
        "caption": caption,
    }
    package = resources.files("rmot.compiler.design")
    page = (package / "reach_viewer.html").read_text(encoding="utf-8")
    text = json.dumps(data, sort_keys=True, separators=(",", ":")).replace("</", "<\\/")
    return page.replace("__TITLE__", html_text.escape(title)).replace("__DATA__", text)
