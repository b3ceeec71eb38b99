"""External axes in the front end: the cell syntax, `on`, `with`, `ext(...)`, `move axes`, and
the diagnostics of bad input, each at its line (lang/REFERENCE.md §15).

Witness for target resolution: the base-frame target the IR holds is recomputed from the
numbers of the cell text with plain numpy rotation matrices (ext_axes_witness.py, not
rmot.lang.ir_axes)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from ext_axes_witness import CELL, at, robot_base, rot, work_frame

from rmot.lang import ir
from rmot.compiler.frontend import load_text

HOME = "  move joint joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg)\n"


def _load(program: str, cell: str = CELL) -> tuple[ir.Program | None, list[tuple[str, int]]]:
    result = load_text(cell + program, "/tmp/ext_axes_test.rmot")
    return result.program, [(d.code.id, d.span.start.line if d.span else 0) for d in result.diagnostics]


def test_the_cell_places_what_rides_at_home() -> None:
    program, codes = _load("program p on r1 with rail, pos {\n" + HOME + "}\n")
    assert codes == [] and program is not None
    cell = program.cell
    assert cell.robots[0].base.position == pytest.approx((0.0, 0.0, 0.25))
    jig = next(f for f in cell.fixtures if f.name == "jig")
    assert jig.pose.position == pytest.approx((1.8, 0.0, 0.72))
    assert cell.external is not None
    assert [a.name for m in cell.external.mechanisms for a in m.axes] == ["rail", "pos.1", "pos.2"]
    assert {(m.body, m.mechanism) for m in cell.external.mounts} == {("r1", "rail"), ("jig", "pos"), ("work", "pos")}


def test_targets_resolve_with_the_axes_at_the_move() -> None:
    program, codes = _load("program p on r1 with rail, pos {\n  tool torch\n" + HOME +
                           "  move joint pose(x=100mm, y=20mm, z=50mm, rx=180deg) frame work ext(rail=1200mm, pos=(30deg, 90deg))\n"
                           "  move linear pose(x=-100mm, z=50mm, rx=180deg) frame work\n"
                           "  move axes pos to (0deg, 180deg)\n"
                           "  move joint pose(z=80mm, rx=180deg) frame work ext(rail=900mm)\n}\n")
    assert codes == [] and program is not None
    moves = [i for i in program.tasks[0].body if isinstance(i, ir.Move)]
    expected = [  # (rail mm, tilt deg, turn deg, target in work) for the moves after home
        (1200, 30, 90, at(0.1, 0.02, 0.05) @ rot("x", 180)),
        (1200, 30, 90, at(-0.1, 0.0, 0.05) @ rot("x", 180)),
        (900, 0, 180, at(z=0.08) @ rot("x", 180)),
    ]
    for move, (rail, tilt, turn, local) in zip([moves[1], moves[2], moves[4]], expected, strict=True):
        want = np.linalg.inv(robot_base(rail)) @ work_frame(tilt, turn) @ local
        assert isinstance(move.target, ir.CartesianTarget)
        assert np.allclose(move.target.pose.matrix(), want, atol=1e-9)
    axes_move = moves[3]
    assert axes_move.axes_only and dict(axes_move.ext) == pytest.approx({"rail": 1.2, "pos.1": 0.0, "pos.2": math.pi})
    # the arm holds its pose in its base frame while the part turns under it
    assert isinstance(axes_move.target, ir.CartesianTarget) and isinstance(moves[2].target, ir.CartesianTarget)
    assert np.allclose(axes_move.target.pose.matrix(), moves[2].target.pose.matrix(), atol=1e-12)


def test_a_move_that_moves_axes_lasts_at_least_the_axes_time() -> None:
    program, _ = _load("program p on r1 with rail, pos {\n" + HOME +
                       "  move joint joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg) ext(rail=1200mm) zone 20 mm\n}\n")
    assert program is not None
    move = [i for i in program.tasks[0].body if isinstance(i, ir.Move)][1]
    # 1200 mm at 1500 mm/s and 2000 mm/s^2: 0.8 s cruising + 0.75 s of ramps (a trapezoid)
    assert move.motion.min_duration == pytest.approx(1.2 / 1.5 + 1.5 / 2.0)
    assert move.motion.zone.is_fine


@pytest.mark.parametrize(("cell_line", "code", "line"), [
    ("  track t2 = linear(axis x, range(4000mm, 0mm)) speed 1 m/s accel 1 m/s^2\n", "E601", 10),
    ("  track t2 = linear(axis w, range(0mm, 10mm)) speed 1 m/s accel 1 m/s^2\n", "E601", 10),
    ("  track t2 = revolute(axis z, range(0deg, 10deg)) speed 1 deg/s accel 1 deg/s^2\n", "E601", 10),
    ("  track t2 = linear(axis x, range(0mm, 1e400mm)) speed 1 m/s accel 1 m/s^2\n", "E601", 10),
    ("  track t2 = linear(axis x, range(0mm, 10mm)) speed 0 m/s accel 1 m/s^2\n", "E601", 10),
    ("  track t2 = linear(axis x, range(0mm, 1e9mm)) speed 1 m/s accel 1 m/s^2\n", "E601", 10),
    ("  positioner p2 = axes(revolute(axis z, range(0deg, 1e6deg)) speed 1 deg/s accel 1 deg/s^2)\n", "E601", 10),
    ("  track t2 = linear(axis x, range(0mm, 10mm)) accel 1 m/s^2\n", "E601", 10),
    ("  fixture box2 = box(1mm, 1mm, 1mm) on nowhere at pose()\n", "E602", 10),
    ("  robot r2 = kuka_kr16 on pos at pose()\n", "E602", 10),
])
def test_bad_cells_are_located_errors(cell_line: str, code: str, line: int) -> None:
    cell = CELL.replace("}\n", cell_line + "}\n")
    _, codes = _load("program p on r1 with rail, pos {\n" + HOME + "}\n", cell)
    assert (code, line) in codes


@pytest.mark.parametrize(("program", "code", "line"), [
    ("program p on r1 with pos {\n" + HOME + "}\n", "E603", 11),  # r1 rides on rail
    ("program p on r1 with rail, nowhere {\n" + HOME + "}\n", "E603", 11),
    ("program p on r1 with rail, pos {\n" + HOME + "  move joint joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg) ext(pos=10deg)\n}\n", "E604", 13),
    ("program p on r1 with rail, pos {\n" + HOME + "  move joint joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg) ext(arm=10deg)\n}\n", "E604", 13),
    ("program p on r1 with rail, pos {\n  move axes pos to (0deg, 10deg)\n}\n", "E606", 12),
    ("program p on r1 with rail, pos {\n" + HOME + "  move linear pose(x=1000mm, z=800mm, ry=180deg) frame world ext(pos=(0deg, 10deg))\n}\n",
     "E606", 13),
    # one arm leaves pos.2 at 10 deg, the other (empty) at 0: located at the if
    ("program p on r1 with rail, pos {\n" + HOME + "  if in[1] {\n    move axes pos to (0deg, 10deg)\n  }\n}\n", "E606", 13),
])
def test_bad_programs_are_located_errors(program: str, code: str, line: int) -> None:
    _, codes = _load(program)
    assert (code, line) in codes


def test_ext_without_with_is_an_error() -> None:
    cell = CELL.replace(" on rail at pose(z=250mm)", " at pose(z=250mm)")
    _, codes = _load("program p on r1 {\n" + HOME + "  move joint joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg) ext(pos=(0deg, 5deg))\n}\n", cell)
    assert ("E604", 13) in codes


def test_a_robot_on_a_track_in_a_task_block_is_an_error() -> None:
    cell = CELL.replace("}\n", "  robot r2 = kuka_kr16 at pose(y=3000mm)\n}\n")
    _, codes = _load("program p {\n  task r1 {\n" + HOME + "  }\n  task r2 {\n" + HOME + "  }\n}\n", cell)
    assert ("E603", 13) in codes


def test_a_unit_after_a_tuple_gives_it_to_each_plain_number() -> None:
    """`pos=(30, 90) deg` is `pos=(30deg, 90deg)`, as `joints(..) deg` gives its unit to each
    value; `move axes pos to (0, 180) deg` likewise; a value with its own unit keeps it."""
    moves = []
    for values in ("(30, 90) deg", "(30deg, 90deg)", "(30deg, 90) deg", "(0.5235987755982988, 90deg) rad"):
        program, codes = _load("program p on r1 with rail, pos {\n  tool torch\n" + HOME +
                               f"  move joint pose(x=100mm, z=50mm, rx=180deg) frame work ext(rail=1200mm, pos={values})\n"
                               "  move axes pos to (0, 180) deg\n}\n")
        assert codes == [] and program is not None, (values, codes)
        moves.append([i for i in program.tasks[0].body if isinstance(i, ir.Move)])
    want = np.linalg.inv(robot_base(1200)) @ work_frame(30, 90) @ at(0.1, 0.0, 0.05) @ rot("x", 180)
    for found in moves:
        assert isinstance(found[1].target, ir.CartesianTarget)
        assert np.allclose(found[1].target.pose.matrix(), want, atol=1e-9)
        assert dict(found[2].ext) == pytest.approx({"rail": 1.2, "pos.1": 0.0, "pos.2": math.pi})
    bad = "program p on r1 with rail, pos {\n" + HOME + "  move axes pos to (0, 180) parsecs\n}\n"
    _, codes = _load(bad)
    assert codes and codes[0] == ("E001", (CELL + bad).splitlines().index("  move axes pos to (0, 180) parsecs") + 1), codes
