"""Solids and mass on external axes: `solid(GEOMETRY, at=POSE)` and `mass M` after an axis' accel.

Witness: the solids' world poses composed with plain numpy from the cell text's numbers
(ext_axes_witness.py: a tilt about y, then a turn about z, at (1800, 0, 700) mm), compared with
the cell's placement at any axis values; a tilt frame on axis 1 tilts but does not turn. The
collision check counts them: the arm on the track reaching the tilted turntable plate is E300
at the move that brings it there, and the same program without the plate is clean."""

from __future__ import annotations

import numpy as np
import pytest
from ext_axes_witness import at, positioner_flange, rot

from rmot.backends import BACKENDS
from rmot.compiler.frontend import load_text
from rmot.compiler.plan import plan_program
from rmot.lang import ir
from rmot.sim.verification import verify

PLATE = " solid(cylinder(r=300mm, h=30mm), at=pose(z=-15mm))"
CELL = """cell c {
  track rail = linear(axis x, range(0mm, 4000mm)) speed 1500 mm/s accel 2000 mm/s^2 """ \
    """solid(box(600mm, 500mm, 100mm), at=pose(z=150mm)) mass 250 kg at pose(z=0mm)
  robot r1 = kuka_kr16 on rail at pose(z=250mm)
  positioner pos = axes(revolute(axis y, range(-90deg, 90deg)) speed 90 deg/s accel 180 deg/s^2
                          solid(box(200mm, 900mm, 100mm), at=pose(z=-150mm)) mass 80 kg,
                        revolute(axis z, range(-360deg, 360deg)) speed 180 deg/s accel 360 deg/s^2""" + PLATE + """)
                   at pose(x=1800mm, z=700mm)
  tool torch = none tcp pose(z=300mm) mass 1 kg on r1
}
program p on r1 with rail, pos {
  tool torch
  move joint joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg)
  move axes pos to (30deg, 90deg)
  move joint joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg) ext(rail=1200mm)
}
"""


def _load(source: str):  # type: ignore[no-untyped-def]
    front = load_text(source, "/tmp/ext_axes_solids.rmot")
    return front, [(d.code.id, d.span.start.line if d.span else None, d.message) for d in front.diagnostics if d.is_error]


@pytest.mark.parametrize("values, tilt, turn", [((0.0, 0.0), 0.0, 0.0), ((30.0, 90.0), 30.0, 90.0), ((-60.0, 250.0), -60.0, 250.0)])
def test_each_solid_rides_through_the_axes_that_carry_it(values: tuple[float, float], tilt: float, turn: float) -> None:
    front, errors = _load(CELL)
    assert errors == [] and front.program is not None
    cell = front.program.cell
    ext = cell.external
    assert ext is not None
    axes = {"pos.1": np.radians(values[0]), "pos.2": np.radians(values[1]), "rail": 0.7}
    tilt_frame = ext.world("pos.1.solid1", axes)
    plate = ext.world("pos.2.solid1", axes)
    carriage = ext.world("rail.solid1", axes)
    assert tilt_frame is not None and plate is not None and carriage is not None
    np.testing.assert_allclose(tilt_frame.matrix(), at(1.8, 0, 0.7) @ rot("y", tilt) @ at(z=-0.15), atol=1e-9)
    np.testing.assert_allclose(plate.matrix(), positioner_flange(tilt, turn) @ at(z=-0.015), atol=1e-9)
    np.testing.assert_allclose(carriage.matrix(), at(x=0.7) @ at(z=0.15), atol=1e-9)
    # the cell's listing places them at home, as fixtures with their geometry
    fixtures = {f.name: f for f in cell.fixtures}
    assert isinstance(fixtures["pos.2.solid1"].geometry, ir.Cylinder) and isinstance(fixtures["rail.solid1"].geometry, ir.Box)
    np.testing.assert_allclose(fixtures["pos.1.solid1"].pose.matrix(), at(1.8, 0, 0.7) @ at(z=-0.15), atol=1e-9)
    assert [a.mass for a in ext.mechanisms[1].axes] == [80.0, 0.0] and ext.mechanisms[0].axes[0].mass == 250.0


def test_the_arm_reaching_the_tilted_plate_is_found_at_the_move_that_brings_it() -> None:
    def collisions(source: str) -> list[tuple[int | None, str]]:
        front, errors = _load(source)
        assert errors == [] and front.program is not None
        report = verify(plan_program(front.program))
        return [(d.span.start.line if d.span else None, d.message) for d in report.diagnostics if d.code.id == "E300"]
    found = collisions(CELL)
    assert found and all(line == 14 and "'pos.2.solid1'" in msg for line, msg in found)
    assert collisions(CELL.replace(PLATE, "")) == []


def test_the_checklist_states_each_axis_mass() -> None:
    front, _ = _load(CELL.replace(PLATE, ""))
    assert front.program is not None
    result = BACKENDS["krl"]().emit(plan_program(front.program))
    text = "\n".join(result.files.values())
    assert "moves 250 kg" in text and "moves 80 kg" in text
    (job,) = BACKENDS["inform"]().emit(plan_program(front.program)).files.values()
    comments = "".join(ln[1:] for ln in job.splitlines() if ln.startswith("'"))  # 32-character comment lines
    assert "moves 250 kg" in comments and "moves 80 kg" in comments


@pytest.mark.parametrize("old, new, code, message", [
    ("mass 80 kg", "mass -5 kg", "E601", "mass of axis 'pos.1' must be a finite number in 0..100000 kg (got -5 kg)"),
    ("mass 80 kg", "mass 80 mm", "E104", "mass of axis 'pos.1'"),
    ("solid(box(200mm, 900mm, 100mm), at=pose(z=-150mm))", "solid(5)", "E135", "solid() must hold a geometry"),
])
def test_bad_solids_and_masses_are_located_errors(old: str, new: str, code: str, message: str) -> None:
    _, errors = _load(CELL.replace(old, new))
    assert any(c.startswith(code) and line == 5 and message in msg for c, line, msg in errors), errors
