"""The issue's cell as a robot programmer writes it from lang/REFERENCE.md §15: declarations that
span lines (a track as well as a positioner), the reference's own example checked clean, the
numbers a user checks by hand (a track move's trapezoid, a track past its range at its line, a
tool hit by the turning jig at the instant a python-fcl witness gives).

Witnesses: the trapezoid is computed here from distance, speed and acceleration; the jig's
contact with the torch is found by python-fcl (an independent collision library) on a box and a
cylinder placed with plain numpy from the cell text's numbers, the turntable's angle following
the hand trapezoid; the reference example is read from the markdown file itself."""

from __future__ import annotations

import math
import re
from pathlib import Path

import fcl
import numpy as np
import pytest
from click.testing import CliRunner

from ext_axes_witness import at, rot

from rmot.compiler.cli import cli
from rmot.compiler.frontend import load_text
from rmot.compiler.plan import plan_program
from rmot.lang import ir
from rmot.sim.verification import verify

REFERENCE = Path(__file__).resolve().parents[2] / "lang" / "REFERENCE.md"

# The declarations, the track broken over three lines as the positioner is over three.
CELL = """cell hidden {
  track rail = linear(axis x, range(0mm, 4000mm))
               speed 1500 mm/s accel 2000 mm/s^2
               at pose(z=0mm)
  robot r1 = kuka_kr16 on rail at pose(z=250mm)
  positioner pos = axes(revolute(axis y, range(-90deg, 90deg)) speed 90 deg/s accel 180 deg/s^2,
                        revolute(axis z, range(-360deg, 360deg)) speed 180 deg/s accel 360 deg/s^2)
                   at pose(x=1800mm, z=700mm)
  fixture jig = box(600mm, 400mm, 40mm) on pos at pose(z=20mm)
  frame work = pos * pose(z=40mm)          # rides on the positioner's flange
  tool torch = cylinder(r=15mm, h=200mm) at pose(z=100mm) tcp pose(z=300mm) on r1
}
"""
HOME = "joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg)"


def _plan(program: str, cell: str = CELL):  # type: ignore[no-untyped-def]
    front = load_text(cell + program, "/tmp/ext_axes_hidden.rmot")
    assert front.program is not None, [d.message for d in front.diagnostics]
    assert not [d for d in front.diagnostics if d.is_error], [d.message for d in front.diagnostics]
    return plan_program(front.program)


def _errors(plan) -> list:  # type: ignore[no-untyped-def,type-arg]
    return [d for d in (*plan.diagnostics, *verify(plan).diagnostics) if d.is_error]


def _record(plan, line: int):  # type: ignore[no-untyped-def]
    tp = plan.tasks[0]
    return next(r for r in tp.records if r.span is not None and r.span.start.line == line)


def trapezoid(distance: float, speed: float, accel: float) -> float:
    """Rest-to-rest time of a move over `distance` at most `speed` and `accel` (triangle if short)."""
    if distance * accel <= speed * speed:
        return 2 * math.sqrt(distance / accel)
    return distance / speed + speed / accel


# ------------------------------------------------------------------ the declarations


def test_a_track_declaration_spans_lines_like_a_positioner() -> None:
    one_line = CELL.replace("""linear(axis x, range(0mm, 4000mm))
               speed 1500 mm/s accel 2000 mm/s^2
               at pose(z=0mm)""", "linear(axis x, range(0mm, 4000mm)) speed 1500 mm/s accel 2000 mm/s^2 at pose(z=0mm)")
    assert one_line != CELL
    program = "program p on r1 with rail, pos {\n  move joint " + HOME + "\n}\n"
    spread, single = (load_text(c + program, "/tmp/t.rmot") for c in (CELL, one_line))
    assert not spread.diagnostics, [d.message for d in spread.diagnostics]
    assert spread.program is not None and single.program is not None
    def numbers(program: ir.Program) -> list[tuple]:  # type: ignore[type-arg]
        assert program.cell.external is not None
        return [(m.name, m.base, [(a.name, a.linear, a.direction, a.low, a.high, a.speed, a.accel) for a in m.axes])
                for m in program.cell.external.mechanisms]
    assert numbers(spread.program) == numbers(single.program)
    assert numbers(spread.program)[0] == ("rail", ir.Pose(), [("rail", True, (1.0, 0.0, 0.0), 0.0, 4.0, 1.5, 2.0)])


def test_every_axis_option_and_on_may_start_a_line() -> None:
    cell = """cell c {
  track rail = linear(axis x, range(0mm, 4000mm))
    speed 1500 mm/s
    accel 2000 mm/s^2
    solid(box(600mm, 500mm, 100mm), at=pose(z=150mm))
    mass 250 kg
    at pose(z=0mm)
  robot r1 = kuka_kr16 on rail at pose(z=250mm)
  positioner turn = axes(revolute(axis z, range(-360deg, 360deg)) speed 180 deg/s accel 360 deg/s^2)
    on rail
    at pose(x=900mm, z=400mm)
}
"""
    front = load_text(cell + "program p on r1 with rail, turn {\n  move joint " + HOME + "\n}\n", "/tmp/t.rmot")
    assert front.program is not None and not [d for d in front.diagnostics if d.is_error], [d.message for d in front.diagnostics]
    external = front.program.cell.external
    assert external is not None
    rail, turn = external.mechanisms
    assert (rail.axes[0].speed, rail.axes[0].accel, rail.axes[0].mass) == pytest.approx((1.5, 2.0, 250.0))
    assert "rail.solid1" in {f.name for f in front.program.cell.fixtures} and turn.on == "rail"


def test_a_speed_line_after_a_move_stays_a_speed_setting() -> None:
    """Only a track or positioner declaration continues on a line starting with `speed`."""
    plan = _plan("program p on r1 with rail, pos {\n  move joint " + HOME + "\n  speed 123 mm/s\n"
                 "  move linear pose(x=1000mm, z=800mm, ry=180deg)\n}\n")
    moves = [i for i in plan.tasks[0].task.body if isinstance(i, ir.Move)]
    assert moves[1].motion.tcp_speed == pytest.approx(0.123) != moves[0].motion.tcp_speed


# ------------------------------------------------------------------ the reference's example


def _reference_example() -> str:
    text = REFERENCE.read_text(encoding="utf-8")
    section = text[text.index("## 15. External axes"):]
    found = re.search(r"```rmot\n(.*?)```", section, re.S)
    assert found is not None
    return found.group(1)


def test_the_reference_example_checks_clean(tmp_path: Path) -> None:
    """`rmot check` of §15's first example: exit 0, no error or warning (the W603 note only)."""
    path = tmp_path / "weld_cell.rmot"
    path.write_text(_reference_example(), encoding="utf-8")
    result = CliRunner().invoke(cli, ["check", str(path)])
    assert result.exit_code == 0, result.output
    assert re.findall(r"(?:error|warning)\[(\w+)\]", result.output) == []
