"""Bodies that external axes carry move with them in the collision check: a torch held still
over a jig that a positioner tilts is hit at the `move axes` line, at the instant an
independent computation gives (the jig's top plane, tilted on the axis' trapezoid, reaching
the torch's tip disc); an arm on a track hits a pillar only once the carriage has brought it
there."""

from __future__ import annotations

import math

import pytest

from ext_axes_witness import CELL_HEAD

from rmot.compiler.frontend import load_text
from rmot.compiler.plan import plan_program
from rmot.sim.verification import verify

CELL = CELL_HEAD + """  tool torch = cylinder(10mm, 300mm) at pose(z=150mm) tcp pose(z=300mm) on r1
PILLAR}
program p on r1 with rail, pos {
  tool torch
  move joint joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg)
  move joint pose(x=250mm, y=0mm, z=50mm, rx=180deg) frame work ext(rail=1200mm)
TILT  move joint joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg)
}
"""


def _check(tilt: str = "", pillar: str = "") -> list:  # type: ignore[type-arg]
    front = load_text(CELL.replace("TILT", tilt).replace("PILLAR", pillar), "/tmp/ext_axes_sim.rmot")
    assert front.program is not None, [d.message for d in front.diagnostics]
    plan = plan_program(front.program)
    report = verify(plan)
    return [plan, [d for d in report.diagnostics if d.is_error]]


def contact_angle() -> float:
    """The tilt a (rad; the positioner at -a about y raises the torch's side) at which the jig's
    top plane first touches the torch's tip disc (radius 10 mm, centre 250 mm out along x and 90
    mm above the tilt axis; the top is 40 mm above it). The plane's normal is Ry(-a) z =
    (-sin a, 0, cos a): the tip's height above it is 0.09 cos a - 0.25 sin a - 0.04, and the
    disc's nearest edge is 0.01 sin a lower."""
    def gap(a: float) -> float:
        return 0.09 * math.cos(a) - 0.25 * math.sin(a) - 0.04 - 0.01 * math.sin(a)
    lo, hi = 0.0, math.radians(60)
    for _ in range(60):  # bisection: gap(0) > 0 > gap(60 deg)
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if gap(mid) > 0 else (lo, mid)
    return lo


def trapezoid_time(angle: float, speed: float, accel: float) -> float:
    """When a rest-to-rest trapezoid at full acceleration first reaches `angle`."""
    ramp = speed / accel
    if angle <= 0.5 * accel * ramp * ramp:
        return math.sqrt(2 * angle / accel)
    return ramp + (angle - 0.5 * accel * ramp * ramp) / speed


def test_a_torch_over_a_tilting_jig_is_hit_at_the_right_line_and_time() -> None:
    plan, errors = _check(tilt="  move axes pos to (-60deg, 0deg)\n")
    hits = [d for d in errors if d.code.id == "E300" and set(d.bodies) == {"torch", "jig"}]
    assert len(hits) == 1 and hits[0].span.start.line == 15
    tp = plan.tasks[0]
    rec = next(r for r in tp.records if r.span is not None and r.span.start.line == 15)
    # 60 deg at 90 deg/s and 180 deg/s^2: a trapezoid; contact when the tilt reaches contact_angle()
    t_contact = rec.t_start + trapezoid_time(contact_angle(), math.radians(90), math.radians(180))
    assert hits[0].time_s == pytest.approx(t_contact, abs=2 * plan.step)


def test_the_same_hold_without_the_tilt_is_clean() -> None:
    _, errors = _check(tilt="  move axes pos to (-5deg, 0deg)\n")  # tilted towards the torch, short of it (a < 10.7 deg)
    assert errors == []


def test_an_arm_on_the_track_meets_a_pillar_only_where_the_carriage_takes_it() -> None:
    # a pillar beside the track at x = 1200 mm: clear of the arm at rail 0 (where the cell
    # places it), in its way at rail 1200 mm
    pillar = "  fixture pillar = box(200mm, 200mm, 2000mm) at pose(x=1200mm, y=-300mm, z=1000mm)\n"
    _, errors = _check(pillar=pillar)
    hits = [d for d in errors if d.code.id == "E300" and "pillar" in d.bodies]
    assert hits and all(h.span.start.line in (14, 15) for h in hits)
    _, clean = _check(pillar=pillar.replace("x=1200mm", "x=3200mm"))
    assert not [d for d in clean if "pillar" in d.bodies]


def test_the_other_paths_of_an_if_are_said_to_be_unchecked() -> None:
    """W602: a program with an if whose axes-carried bodies are checked on the main path only."""
    branch = ("  if in[1] {\n    move joint joints(0deg, -80deg, 90deg, 0deg, 45deg, 0deg)\n  } else {\n"
              "    move joint joints(0deg, -85deg, 90deg, 0deg, 45deg, 0deg)\n  }\n")
    front = load_text(CELL.replace("TILT", branch).replace("PILLAR", ""), "/tmp/ext_axes_if.rmot")
    assert front.program is not None, [d.message for d in front.diagnostics]
    report = verify(plan_program(front.program))
    assert [d.code.id for d in report.diagnostics if d.code.id == "W602"] == ["W602"]
    _, errors = _check()
    assert errors == []
