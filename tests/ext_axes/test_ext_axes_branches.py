"""External axes inside if, while and for.

An if's arms each start from the axis values before it and must end at one value; a while body
must end where it started; a for loop is unrolled, each round from the values the last left.
Witnesses: the rest-to-rest trapezoid time written here from the cell's speed and acceleration
(d / v + v / a, or 2 sqrt(d / a) when the top speed is never reached) against the IR's and the
plan's durations, and the axis values read back from the RAPID text with a regular expression.
Anything else is E606 at the if or while, naming the axis and both values."""

from __future__ import annotations

import math
import re

import pytest
from ext_axes_witness import CELL_HEAD

from rmot.backends import BACKENDS
from rmot.compiler.frontend import load_text
from rmot.compiler.plan import plan_program
from rmot.lang import ir
from rmot.lang.ir_tree import walk

HEAD = CELL_HEAD + "  tool torch = none tcp pose(z=300mm) mass 1 kg on r1\n}\nprogram p on r1 with rail, pos {\n  tool torch\n" \
    "  move joint joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg)\n"
HOME_J = "joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg)"
PROGRAM_LINE = HEAD.count("\n") - 2  # the line of `program p ...`


def trapezoid_s(delta: float, speed: float, accel: float) -> float:
    d = abs(delta)
    return 2 * math.sqrt(d / accel) if speed * speed / accel >= d else d / speed + speed / accel


def load(body: str):  # type: ignore[no-untyped-def]
    front = load_text(HEAD + body + "}\n", "/tmp/ext_axes_branches.rmot")
    return front, [(d.code.id, d.span.start.line if d.span else None, d.message) for d in front.diagnostics if d.is_error]


def test_each_arm_of_an_if_starts_from_the_values_before_it() -> None:
    """Both arms turn pos.2 from 0 to 90 deg: the else arm's move is timed from 0 (1 s), not
    from the then arm's 90 (no motion)."""
    front, errors = load("  if in[1] {\n    move axes pos to (0deg, 90deg)\n  } else {\n    move axes pos to (0deg, 90deg)\n  }\n"
                         "  move axes pos to (0deg, 0deg)\n")
    assert errors == [] and front.program is not None
    moves = [i for i in walk(front.program.tasks[0].body) if isinstance(i, ir.Move) and i.axes_only]
    assert len(moves) == 3
    want = trapezoid_s(90.0, 180.0, 360.0)
    assert want == pytest.approx(1.0)
    for move in moves:
        assert move.motion.min_duration == pytest.approx(want)


def test_arms_that_leave_the_axes_apart_are_refused_at_the_if() -> None:
    _, errors = load("  if in[1] {\n    move axes pos to (0deg, 90deg)\n  } else {\n"
                     f"    move joint {HOME_J} ext(rail=1200mm)\n  }}\n")
    (error,) = errors
    assert error[:2] == ("E606", PROGRAM_LINE + 3)
    assert "'rail' 0 mm after one arm, 1200 mm after the other" in error[2]
    assert "'pos.2' 90 deg after one arm, 0 deg after the other" in error[2]


def test_a_while_body_that_returns_its_axes_is_planned_and_counted() -> None:
    """One pass on the main path (awaited inputs arrive at once): 0 -> (20, 180) -> (0, 0) deg,
    each move as long as its slowest axis (the turn: 180 deg, 1.5 s)."""
    front, errors = load("  while in[2] {\n    move axes pos to (20deg, 180deg)\n    move axes pos to (0deg, 0deg)\n  }\n")
    assert errors == [] and front.program is not None
    plan = plan_program(front.program)
    assert not [d for d in plan.diagnostics if d.is_error]
    body = [i for i in walk(front.program.tasks[0].body) if isinstance(i, ir.Move) and i.axes_only]
    slowest = max(trapezoid_s(20.0, 90.0, 180.0), trapezoid_s(180.0, 180.0, 360.0))
    assert slowest == pytest.approx(1.5)
    assert [m.motion.min_duration for m in body] == pytest.approx([slowest, slowest])
    records = [plan.tasks[0].record(m.uid) for m in body]
    assert all(r is not None and r.t_end - r.t_start >= slowest - 1e-3 for r in records)


def test_a_while_body_that_moves_the_axes_away_is_refused_at_the_while() -> None:
    _, errors = load("  while in[2] {\n    move axes pos to (20deg, 180deg)\n  }\n")
    (error,) = errors
    assert error[:2] == ("E606", PROGRAM_LINE + 3)
    assert "'pos.1' 0 deg at its start, 20 deg at its end" in error[2]


def test_a_for_loop_is_unrolled_each_round_from_the_last() -> None:
    front, errors = load(f"  for i in 1 .. 4 {{\n    move axes pos to (0deg, i * 90deg)\n    move joint {HOME_J}\n  }}\n")
    assert errors == [] and front.program is not None
    plan = plan_program(front.program)
    result = BACKENDS["rapid"]().emit(plan)
    assert not result.has_errors, [d.message for d in result.diagnostics if d.is_error]
    text = "\n".join(result.files.values())
    turns = [float(v) for v in re.findall(r"jointtarget jext\w*:=\[\[[^\]]*\],\[[-\d.]+,[-\d.]+,([-\d.]+),", text)]
    assert turns == [90.0, 180.0, 270.0]
    times = [float(t) for t in re.findall(r"MoveExtJ \w+, vmax\\T:=([\d.]+), fine;", text)]
    assert times == pytest.approx([trapezoid_s(90.0, 180.0, 360.0)] * 3, abs=1e-3)
