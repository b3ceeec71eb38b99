"""`robot r1 = NAME speed S % accel A %`: a library arm calibrated to its real controller.

Witness: the planned time of a rest-to-rest joint move on its trapezoid. A move long enough to
reach its top speed takes d / v + v / a; with only the acceleration scaled by k, the time falls
by (v / a) (1 - 1 / k), computed here from the robot's own limits, not from the planner.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from rmot.compiler.cli import stages
from rmot.sim.robots import load_robot

CELL = """cell cal {{
  robot r1 = kuka_kr6_r900{shares} at pose()
  tool load = sphere(r=20mm) at pose(z=60mm) tcp pose(z=100mm) mass 1 kg on r1
}}

program p on r1 {{
  tool load
  move joint joints(-150, -90, 90, 0, 45, 0) deg zone fine
  move joint joints(150, -90, 90, 0, 45, 0) deg zone fine
}}
"""


def _front(tmp_path: Path, shares: str):  # type: ignore[no-untyped-def]
    path = tmp_path / "cal.rmot"
    path.write_text(CELL.format(shares=shares))
    return stages.load(str(path), use_cache=False)


def _move_time(tmp_path: Path, shares: str) -> float:
    front = _front(tmp_path, shares)
    assert front.program is not None, [str(d) for d in front.diagnostics]
    plan = stages.plan(front.program, use_cache=False)
    rec = max(plan.tasks[0].records, key=lambda r: r.t_end)
    return rec.t_end - rec.t_start


def test_accel_share_shortens_the_move_as_the_trapezoid_says(tmp_path: Path) -> None:
    robot = load_robot("kuka_kr6_r900")
    v, a = robot.velocity_limits[0], robot.accel_limits[0]  # A1 leads: 300 deg, nothing else moves
    d = math.radians(300.0)
    assert d >= v * v / a  # reaches its top speed
    plain, faster = _move_time(tmp_path, ""), _move_time(tmp_path, " accel 140 %")
    assert plain == pytest.approx(d / v + v / a, rel=0.02)
    assert faster == pytest.approx(d / v + v / (1.4 * a), rel=0.02)


def test_speed_share_and_the_sources_say_so(tmp_path: Path) -> None:
    front = _front(tmp_path, " speed 50 % accel 140 %")
    assert front.program is not None
    source = front.program.cell.robots[0].source
    assert (source.speed_share, source.accel_share) == pytest.approx((0.5, 1.4))
    robot = load_robot(source.load_key)
    np.testing.assert_allclose(robot.velocity_limits, 0.5 * load_robot("kuka_kr6_r900").velocity_limits)
    assert "calibration" in dict(robot.sources)["accel"] and "calibration" in dict(robot.sources)["speed"]


@pytest.mark.parametrize(("shares", "code"), [(" accel 140 mm", "E104"), (" accel 400 %", "E125"),
                                              (" accel 140 % accel 120 %", "E001")])
def test_bad_shares_are_located_errors(tmp_path: Path, shares: str, code: str) -> None:
    front = _front(tmp_path, shares)
    assert code in {d.code.id for d in front.diagnostics if d.is_error}, [str(d) for d in front.diagnostics]
