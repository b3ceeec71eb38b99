"""Rotary axes with more than +-180 deg of range move to their absolute targets.

The positioner's turn axis has range(-720deg, 720deg). `move axes pos to (0deg, -10deg)` after
350 deg must turn it 360 deg back through 170 deg (not 20 deg forwards the shortest way), and
`move axes pos to (0deg, 700deg)` must turn it 710 deg. Witnesses: the durations of those moves
against the rest-to-rest trapezoid time written here from the axis' speed and acceleration
(d / v + v / a), the sampled axis values, and the absolute values each vendor's text states
(RAPID jointtarget eax_c, KRL E6AXIS E3, Fanuc GP2 J2, INFORM EC pulses), read with regular
expressions; each program's header checklist says the axis must not be an endless one."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
from ext_axes_plans import planned
from ext_axes_witness import CELL_HEAD

from rmot.backends import BACKENDS
from rmot.compiler.frontend import load_text
from rmot.compiler.plan import plan_program
from rmot.lang import ir
from rmot.lang.axis_motion import axis_samples, task_axes
from rmot.lang.plan_types import Plan

SOURCE = CELL_HEAD.replace("range(-360deg, 360deg)", "range(-720deg, 720deg)") + """  tool torch = none tcp pose(z=300mm) mass 1 kg on r1
}
program p on r1 with rail, pos {
  tool torch
  move joint joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg)
  move axes pos to (0deg, 350deg)
  move axes pos to (0deg, -10deg)
  move axes pos to (0deg, 700deg)
}
"""
TURN_SPEED, TURN_ACCEL = 180.0, 360.0  # deg/s, deg/s^2, as the cell declares
TURNS = [(0.0, 350.0), (350.0, -10.0), (-10.0, 700.0)]


def trapezoid_s(delta_deg: float) -> float:
    d = abs(delta_deg)
    if TURN_SPEED ** 2 / TURN_ACCEL >= d:
        return 2 * math.sqrt(d / TURN_ACCEL)
    return d / TURN_SPEED + TURN_SPEED / TURN_ACCEL


@pytest.fixture(scope="module")
def plan() -> Plan:
    assert SOURCE.count("range(-720deg, 720deg)") == 1
    return planned(SOURCE, "/tmp/ext_axes_unwind.rmot")


def test_each_turn_is_planned_through_the_programmed_difference(plan: Plan) -> None:
    tp = plan.tasks[0]
    (turn,) = [a for a in task_axes(tp.task, plan.program.cell.external) if a.name == "pos.2"]
    axes = task_axes(tp.task, plan.program.cell.external)
    k = axes.index(turn)
    moves = [i for i in tp.task.body if isinstance(i, ir.Move) and i.axes_only]
    assert len(moves) == len(TURNS)
    for move, (start, end) in zip(moves, TURNS, strict=True):
        rec = tp.record(move.uid)
        assert rec is not None
        assert rec.t_end - rec.t_start >= trapezoid_s(end - start) - 0.01
        t = np.linspace(rec.t_start, rec.t_end, 801)
        deg = np.degrees(axis_samples(tp, axes, t)[:, k])
        assert deg[0] == pytest.approx(start, abs=1e-6) and deg[-1] == pytest.approx(end, abs=1e-6)
        assert np.all(np.diff(deg) * math.copysign(1.0, end - start) >= -1e-9)  # one way, no wrap
    # 350 -> -10 passes 170 deg (the long way back), -10 -> 700 turns 710 deg
    assert trapezoid_s(360.0) == pytest.approx(2.5) and trapezoid_s(710.0) == pytest.approx(710 / 180 + 0.5)


@pytest.mark.parametrize("vendor, pattern", [
    ("rapid", r"jointtarget \w+:=\[\[[^\]]*\],\[[-\d.]+,[-\d.]+,([-\d.]+),"),
    ("krl", r"E6AXIS \w+=\{[^}]*E3 ([-\d.]+)"),
    ("fanuc", r"GP2:\s*\n[^\n]*\n\s*J1=\s+[-\d.]+\s+deg,\s+J2=\s+([-\d.]+)\s+deg"),
])
def test_vendors_state_the_absolute_targets_and_the_checklist_says_no_wrap(plan: Plan, vendor: str, pattern: str) -> None:
    result = BACKENDS[vendor]().emit(plan)
    assert not result.has_errors, [d.message for d in result.diagnostics if d.is_error]
    text = "\n".join(result.files.values())
    values = [float(v) for v in re.findall(pattern, text)]
    assert values[-3:] == [350.0, -10.0, 700.0], values
    assert "shortest-way" in text  # the checklist line (comment wrapping may split the others)


def test_inform_states_the_absolute_pulses() -> None:
    declared = SOURCE.replace("accel 360 deg/s^2)", "accel 360 deg/s^2 inform(pulses_per_deg=500))")
    front = load_text(declared, "/tmp/ext_axes_unwind.rmot")
    assert front.program is not None
    result = BACKENDS["inform"]().emit(plan_program(front.program))
    assert not result.has_errors
    (text,) = result.files.values()
    turns = [int(v.split(",")[1]) for v in re.findall(r"^EC\d{5}=(.*)$", text, re.M)]
    assert turns[-3:] == [350 * 500, -10 * 500, 700 * 500]
    assert "no shortest-way wrap" in "".join(ln[1:] for ln in text.splitlines() if ln.startswith("'"))
