"""Findings in every picture kind: the bodies of a finding marked around its worst instant.

The collision example (examples/collision.rmot: the gripper drags through the bench's front
edge) is planned and verified once; its pictures are checked by pixel colour, its SVG by
its elements, its animation frame by frame. `events` is checked on hand-made findings.
"""

from __future__ import annotations

import dataclasses
import json
import re
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from PIL import Image

from rmot.compiler.cli import cli
from rmot.compiler.frontend import load_program
from rmot.compiler.plan import plan_program
from rmot.lang.diagnostics import Amount, Code, Diagnostic, Severity
from rmot.lang.source import Pos, SourceFile, Span
from rmot.sim.render.camera import Camera
from rmot.sim.render.findings import events, unproject, verified_markings
from rmot.sim.render.pipeline import draw
from rmot.sim.render.scene import prepare

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
ROBOT_HIT = Code("E302", "robot-collision", "two robots touch on the shared timeline")
SIZE = (320, 240)


def red_pixels(img: np.ndarray) -> np.ndarray:
    img = img.astype(int)
    return (img[..., 0] > 140) & (img[..., 1] < 80) & (img[..., 2] < 80)


@pytest.fixture(scope="module")
def collision():  # type: ignore[no-untyped-def]
    plan = plan_program(load_program(str(EXAMPLES / "collision.rmot"), require_program=True).program)
    rs = prepare(plan)
    marks, found = verified_markings(rs)
    return rs, marks, found


def test_one_event_from_pieces() -> None:
    """Eleven adjacent pieces of one robot-robot contact are one event with the worst amount."""
    pieces = [Diagnostic(ROBOT_HIT, Severity.ERROR, f"piece {k}", None, time_s=1.0 + 0.1 * k, end_time_s=1.08 + 0.1 * k,
                         bodies=("r1/link6", "r2/link4"), amount=Amount(float(k % 5), "mm"), peak_time_s=1.04 + 0.1 * k)
              for k in range(11)]
    other = Diagnostic(ROBOT_HIT, Severity.ERROR, "other pair", None, time_s=1.5, end_time_s=1.6, bodies=("r1/link5", "r2/link4"))
    later = dataclasses.replace(pieces[0], time_s=9.0, end_time_s=9.1, peak_time_s=9.05)
    source = SourceFile("two.rmot", "\n" * 30)
    for k in range(11):  # the contact spans two moves: pieces on lines 12 and 13 are still one event
        pieces[k] = dataclasses.replace(pieces[k], span=Span(source, Pos(12 + k // 6, 3), Pos(12 + k // 6, 9)))
    out = events(pieces + [other, later])
    assert len(out) == 3
    first = out[0]
    assert first.time_s == pytest.approx(1.0) and first.end_time_s == pytest.approx(2.08)
    assert first.amount.value == 4.0 and first.peak_time_s == pytest.approx(1.44)  # the first piece with 4 mm


def test_the_example_has_one_marked_event(collision) -> None:  # type: ignore[no-untyped-def]
    rs, marks, found = collision
    assert [d.code.id for d in found if d.is_error] == ["E300"]
    (m,) = marks
    assert set(m.bodies) == {"gripper", "table"} and m.contact is not None
    assert m.t0 <= m.worst <= m.t1
    assert m.caption.startswith("E300 line 41 t=")


def test_plain_render_at_the_worst_instant_shows_it_in_red(collision, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    rs, marks, _ = collision
    worst = marks[0].worst
    out = tmp_path / "at.png"
    result = CliRunner().invoke(cli, ["render", str(EXAMPLES / "collision.rmot"), "-o", str(out), "--at", f"{worst:.3f}",
                                      "--size", "320x240"])
    assert result.exit_code == 0, result.output
    img = np.asarray(Image.open(out).convert("RGB"))
    assert red_pixels(img[:-40]).sum() > 60  # the gripper and the hit edge of the bench
    assert img[-3:].max() < 60  # the caption band
    calm = tmp_path / "calm.png"  # long before the contact: nothing is red
    result = CliRunner().invoke(cli, ["render", str(EXAMPLES / "collision.rmot"), "-o", str(calm), "--at", "0.2",
                                      "--size", "320x240"])
    assert result.exit_code == 0, result.output
    assert red_pixels(np.asarray(Image.open(calm).convert("RGB"))).sum() == 0


def test_contact_region_not_the_whole_fixture(collision) -> None:  # type: ignore[no-untyped-def]
    """The table is strongly red only near the contact; the rest of it is a lighter tint."""
    from rmot.sim.render.still import still_image

    rs, marks, _ = collision
    img = still_image(rs, time=marks[0].worst, size=SIZE, aa=1, marks=marks).astype(int)
    plain = still_image(rs, time=marks[0].worst, size=SIZE, aa=1).astype(int)
    changed = np.any(img[:-40] != plain[:-40], axis=2)
    strong = red_pixels(img[:-40])
    assert changed.sum() > 2 * strong.sum() > 0  # most marked pixels are the tint, not the strong red


def test_unproject_lands_on_the_surface() -> None:
    """The world point under each pixel of a unit cube lies on the cube's surface."""
    lo, hi = -0.5, 0.5
    corners = np.array([[x, y, z] for x in (lo, hi) for y in (lo, hi) for z in (lo, hi)])
    faces = [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1), (2, 3, 7), (2, 7, 6), (0, 2, 6), (0, 6, 4),
             (1, 5, 7), (1, 7, 3)]
    tris = corners[np.array(faces)]
    camera = Camera(eye=(2.0, -1.6, 1.3), center=(0.0, 0.0, 0.0), fov_deg=45.0)
    picture = draw(tris, None, np.full((12, 3), 0.5), camera, (80, 60))
    points = unproject(picture)[picture.frame.covered]
    assert len(points) > 500
    assert np.all(np.abs(np.max(np.abs(points), axis=1) - 0.5) < 2e-3)


def test_svg_marks_the_bodies_and_captions(collision) -> None:  # type: ignore[no-untyped-def]
    from rmot.sim.render.svg import render_svg

    rs, marks, _ = collision
    svg = render_svg(rs, time=marks[0].worst, size=SIZE, marks=marks)
    assert re.search(r'<path id="table" [^>]*stroke="#d32f2f"', svg)
    assert 'class="contact"' in svg and 'class="finding"' in svg and "E300 line 41" in svg
    assert 'stroke="#0d6efd"' in svg  # the TCP path
    calm = render_svg(rs, time=0.2, size=SIZE, marks=marks)
    assert "#d32f2f" not in calm


def test_gif_marks_frames_around_the_event(collision, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    from rmot.sim.render.animate import frame_times, write_animation

    rs, marks, _ = collision
    out = tmp_path / "a.gif"
    write_animation(rs, str(out), fps=2, size=SIZE, marks=marks, progress=False)
    gif = Image.open(out)
    times = frame_times(rs.plan.cycle_time, 2)
    m = marks[0]
    boxes = []
    for k, t in enumerate(times):
        gif.seek(k)
        img = np.asarray(gif.convert("RGB"))
        inside = m.t0 - 0.3 <= t <= m.t1 + 0.3
        assert (red_pixels(img).sum() > 0) == inside, t
        assert (img[-3:].max() < 60) == inside, t  # the caption band
        if k:
            boxes.append(gif.tile[0][1] if gif.tile else (0, 0, 0, 0))
    # one palette for all frames: still parts keep their bytes, so most frames store only the
    # rectangle that changed (what keeps long GIFs small)
    full = (0, 0, SIZE[0], SIZE[1])
    assert sum(1 for b in boxes if tuple(b) != full) > len(boxes) // 2


def test_html_lists_the_findings(collision) -> None:  # type: ignore[no-untyped-def]
    from rmot.sim.render.html import render_html

    rs, marks, _ = collision
    page = render_html(rs, fps=5, marks=marks)
    data = json.loads(re.search(r'<script id="rmot-data" type="application/json">(.*?)</script>', page, re.S).group(1))
    (f,) = data["findings"]
    assert f["code"] == "E300" and f["line"] == 41 and f["t0"] <= f["worst"] <= f["t1"]
    assert sorted(data["bodies"][i]["name"] for i in f["bodies"]) == ["gripper", "table"]
