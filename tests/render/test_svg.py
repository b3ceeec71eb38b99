"""The hidden-line wire-frame: valid SVG, feature edges only, hidden parts removed."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET

import numpy as np

from rmot.sim.render.camera import Camera
from rmot.sim.render.pipeline import depth_frame
from rmot.sim.render.svg import feature_edges, wireframe_svg
from rmot.sim.render.tessellate import box

SIZE = (200, 150)
CAMERA = Camera(eye=(5.0, -4.0, 3.0), center=(-0.5, 0.5, 0.5), fov_deg=35.0)
NS = "{http://www.w3.org/2000/svg}"


def _box_at(centre: tuple[float, float, float], size: float = 1.0) -> np.ndarray:
    return box((size, size, size)).vertices + np.asarray(centre)


FRONT, BACK = _box_at((0.0, 0.0, 0.5)), _box_at((-1.3, 1.1, 0.7))


def _strokes(svg: str) -> dict[str, list[tuple[float, float, float, float]]]:
    root = ET.fromstring(svg)
    out: dict[str, list[tuple[float, float, float, float]]] = {}
    for path in root.iter(f"{NS}path"):
        segs = re.findall(r"M([-\d.]+) ([-\d.]+)L([-\d.]+) ([-\d.]+)", path.get("d", ""))
        out[path.get("id", "")] = [tuple(map(float, s)) for s in segs]  # type: ignore[misc]
    return out


def _two_boxes(back_only: bool = False) -> str:
    verts = BACK if back_only else np.concatenate([FRONT, BACK])
    groups = np.zeros(len(BACK), int) + 1 if back_only else np.repeat([0, 1], [len(FRONT), len(BACK)])
    return wireframe_svg(verts, CAMERA, SIZE, groups=groups, names=("front", "back"))


def _length(strokes: list[tuple[float, float, float, float]]) -> float:
    return float(sum(np.hypot(x1 - x0, y1 - y0) for x0, y0, x1, y1 in strokes))


def test_svg_parses_with_one_path_per_body() -> None:
    """The output is well-formed SVG of the requested size, a <path id=body> per body."""
    svg = _two_boxes()
    root = ET.fromstring(svg)
    assert root.tag == f"{NS}svg" and (root.get("width"), root.get("height")) == ("200", "150")
    assert set(_strokes(svg)) == {"front", "back"}


def test_a_box_shows_its_nine_visible_edges_and_not_the_three_behind_it() -> None:
    """Feature edges of a box are its 12 edges (no face diagonals); the 3 on its far side are hidden."""
    edges, _ = feature_edges(FRONT, np.asarray(CAMERA.eye))
    assert len(edges) == 12
    assert len(_strokes(_two_boxes())["front"]) == 9


def test_lines_of_the_rear_box_behind_the_front_box_are_removed() -> None:
    """No stroke of the rear box crosses the inside of the front box's outline, yet part of the rear box is drawn."""
    frame, _ = depth_frame(FRONT, CAMERA, SIZE)
    inside = frame.covered.copy()
    for axis in (0, 1):  # shrink the silhouette by 2 px so strokes on its outline do not count
        for shift in (-2, -1, 1, 2):
            inside &= np.roll(frame.covered, shift, axis=axis)
    back = _strokes(_two_boxes())["back"]
    alone = _strokes(_two_boxes(back_only=True))["back"]
    for x0, y0, x1, y1 in back:
        for u in np.linspace(0.0, 1.0, 50):
            x, y = x0 + u * (x1 - x0), y0 + u * (y1 - y0)
            assert not inside[int(y), int(x)]
    assert 0.2 * _length(alone) < _length(back) < 0.9 * _length(alone)  # partly hidden, partly drawn


def test_same_scene_gives_the_same_svg_text() -> None:
    """Output is deterministic, byte for byte."""
    assert _two_boxes() == _two_boxes()
