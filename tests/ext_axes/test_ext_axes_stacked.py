"""A mechanism stacked on another: `positioner turn = axes(...) on rail at POSE`.

Witness: world poses composed with plain numpy from the cell text's numbers: the turntable's
base 900 mm along and 400 mm above the carriage, which is `rail` mm along x; the jig 100 mm out
on the turntable. Compared with the cell's placement, with the verifier's motion of the carried
bodies at the end of the program, and with the planned TCP of a target in a frame on the
turntable. Vendors refuse a stacked mechanism (E607): its chained kinematics are not verified."""

from __future__ import annotations

import numpy as np
import pytest
from ext_axes_witness import at, robot_base, rot

from rmot.backends import BACKENDS
from rmot.compiler.frontend import load_text
from rmot.compiler.plan import plan_program
from rmot.lang import ir
from rmot.sim.axes_collide import mechanism_motion

SOURCE = """cell c {
  track rail = linear(axis x, range(0mm, 4000mm)) speed 1500 mm/s accel 2000 mm/s^2 at pose(z=0mm)
  robot r1 = kuka_kr16 on rail at pose(z=250mm)
  positioner turn = axes(revolute(axis z, range(-360deg, 360deg)) speed 180 deg/s accel 360 deg/s^2) ON at pose(x=900mm, z=400mm)
  fixture jig = box(100mm, 100mm, 100mm) on turn at pose(x=100mm, z=50mm)
  frame work = turn * pose(z=100mm)
  tool torch = none tcp pose(z=300mm) mass 1 kg on r1
}
program p on r1 with rail, turn {
  tool torch
  move joint joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg)
  move joint pose(x=100mm, y=50mm, rx=180deg) frame work ext(rail=1000mm, turn=90deg)
}
"""


def turntable(rail_mm: float, turn_deg: float) -> np.ndarray:
    return at(x=rail_mm / 1000) @ at(0.9, 0.0, 0.4) @ rot("z", turn_deg)


def _front(source: str = SOURCE.replace("ON", "on rail")):  # type: ignore[no-untyped-def]
    front = load_text(source, "/tmp/ext_axes_stacked.rmot")
    return front, [(d.code.id, d.span.start.line if d.span else None, d.message) for d in front.diagnostics if d.is_error]


@pytest.mark.parametrize("rail_mm, turn_deg", [(0.0, 0.0), (1000.0, 90.0), (3500.0, -200.0)])
def test_the_stacked_positioner_rides_on_the_carriage(rail_mm: float, turn_deg: float) -> None:
    front, errors = _front()
    assert errors == [] and front.program is not None
    ext = front.program.cell.external
    assert ext is not None
    jig = ext.world("jig", {"rail": rail_mm / 1000, "turn": np.radians(turn_deg)})
    assert jig is not None
    np.testing.assert_allclose(jig.matrix(), turntable(rail_mm, turn_deg) @ at(0.1, 0, 0.05), atol=1e-9)


def test_plan_and_verifier_move_it_with_both_axes() -> None:
    front, _ = _front()
    assert front.program is not None
    plan = plan_program(front.program)
    assert not [d for d in plan.diagnostics if d.is_error]
    tp = plan.tasks[0]
    ext = plan.program.cell.external
    assert ext is not None
    end = tp.trajectory.t[-1:]
    jig_home = next(f for f in plan.program.cell.fixtures if f.name == "jig").pose.matrix()
    moved = mechanism_motion(end, tp, ext)["turn"][0] @ jig_home
    np.testing.assert_allclose(moved, turntable(1000, 90) @ at(0.1, 0, 0.05), atol=1e-9)
    move = [i for i in tp.task.body if isinstance(i, ir.Move)][-1]
    rec = tp.record(move.uid)
    assert rec is not None and rec.tcp_pose is not None
    tcp = robot_base(1000) @ rec.tcp_pose.matrix()
    want = turntable(1000, 90) @ at(z=0.1) @ at(0.1, 0.05, 0) @ rot("x", 180)
    np.testing.assert_allclose(tcp[:3, 3], want[:3, 3], atol=1e-5)
    np.testing.assert_allclose(tcp[:3, :3], want[:3, :3], atol=1e-6)


@pytest.mark.parametrize("vendor", ["rapid", "krl", "fanuc", "inform"])
def test_vendors_refuse_a_stacked_mechanism(vendor: str) -> None:
    front, _ = _front()
    assert front.program is not None
    result = BACKENDS[vendor]().emit(plan_program(front.program))
    errors = [d for d in result.diagnostics if d.is_error]
    assert [d.code.id for d in errors] == ["E607"] and result.has_errors
    assert "a mechanism stacked on another ('turn' on 'rail')" in errors[0].message
    assert errors[0].span is not None and errors[0].span.start.line == 11  # the first move that drives them


def test_on_an_unknown_mechanism_is_a_located_error() -> None:
    _, errors = _front(SOURCE.replace("ON", "on nowhere"))
    assert any(code == "E602" and line == 4 and "nowhere" in msg for code, line, msg in errors), errors
