"""`speed R %` on joint moves, TCP speeds where a move does not use them,
and joint turns fixed by `config(jN=n)` (front end, planner; the vendors' files are checked in
tests/backends/test_turns_emitted.py).

Joint-move durations are compared with a trapezoid computed here from the library's cited
speed and acceleration limits: a synchronised joint move rest to rest runs along the straight
line q0 + s*(q1 - q0), so s moves with speed at most V = min_j r*vmax_j/|dq_j| and acceleration
at most A = min_j amax_j/|dq_j|, and lasts 1/V + V/A (trapezoid) or 2/sqrt(A) (triangle).
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from rmot.lang import ir, ir_tree
from rmot.compiler.frontend import load_text
from rmot.compiler.plan import plan_program
from rmot.sim.robots.library import SPECS
from rmot.lang.diagnostics import Diagnostic

PATH = str(Path(__file__).resolve().parents[1] / "data" / "probe.rmot")
HOME = (0, 0, 0, 0, 30, 0)  # deg, the default cell's abb_irb1600
OTHER = (60, 20, -30, 90, 40, 200)
ROBOT = "abb_irb1600"  # the default cell's r1


def _load(body: str):  # type: ignore[no-untyped-def]
    return load_text(f"program p on r1 {{\n{body}}}\n", PATH)


def _planned(body: str) -> tuple[list[float], list[Diagnostic]]:
    """(duration of every move in order, every diagnostic of the front end and the planner)."""
    front = _load(body)
    assert front.program is not None, [d.message for d in front.diagnostics]
    plan = plan_program(front.program)
    tp = plan.tasks[0]
    moves = [n for n in ir_tree.walk(tp.task.body) if isinstance(n, ir.Move)]
    durations = []
    for m in moves:
        rec = tp.record(m.uid)
        durations.append(math.nan if rec is None else rec.t_end - rec.t_start)
    return durations, list(front.diagnostics) + list(plan.diagnostics)


def _trapezoid(q0: tuple[float, ...], q1: tuple[float, ...], ratio: float) -> float:
    spec = SPECS[ROBOT]
    dq = [abs(math.radians(b - a)) for a, b in zip(q0, q1)]
    v = min(ratio * math.radians(vm) / d for vm, d in zip(spec.speed_deg_s, dq) if d > 0)
    a = min(math.radians(am) / d for am, d in zip(spec.accel_deg_s2, dq) if d > 0)
    return 1 / v + v / a if v * v / a <= 1 else 2 / math.sqrt(a)


def _joints(q: tuple[float, ...]) -> str:
    return "joints(" + ", ".join(str(v) for v in q) + ") deg"


START = f"  target home = {_joints(HOME)}\n  target other = {_joints(OTHER)}\n  move joint home\n"


@pytest.mark.parametrize("ratio", [20, 55, 100])
def test_speed_percent_on_a_joint_move_is_joint_speed(ratio: int) -> None:
    """`speed R %` as a modifier and as a setting plans exactly as `joint_speed R %`, and both
    last what the trapezoid says."""
    as_speed, d1 = _planned(START + f"  move joint other speed {ratio} %\n")
    as_joint, d2 = _planned(START + f"  move joint other joint_speed {ratio} %\n")
    as_setting, d3 = _planned(START + f"  speed {ratio} %\n  move joint other\n")
    assert d1 == d2 == d3 == []
    assert as_speed[1] == as_joint[1] == as_setting[1]
    assert as_speed[1] == pytest.approx(_trapezoid(HOME, OTHER, ratio / 100), rel=2e-3)


def test_speed_percent_setting_leaves_the_tcp_speed_alone() -> None:
    """`speed 20 %` sets the joint share only: a following linear move keeps its TCP speed."""
    line = "  move linear pose(x=900mm, y=100mm, z=700mm, ry=180deg)\n"
    start = "  move joint pose(x=900mm, z=700mm, ry=180deg)\n"
    plain, _ = _planned(start + line)
    after, _ = _planned(start + "  speed 20 %\n" + line)
    assert after[1] == plain[1]


def test_tcp_speed_on_a_joint_move_warns_and_is_not_used() -> None:
    """A TCP speed modifier on a joint move: W170 at the modifier, the move timed as without it."""
    with_tcp, diags = _planned(START + "  move joint other speed 100 mm/s\n")
    plain, _ = _planned(START + "  move joint other\n")
    (w,) = diags
    assert w.code.id == "W170" and not w.is_error and "100 mm/s" in w.message
    assert (w.span.start.line, w.span.start.col) == (5, 20)
    assert with_tcp[1] == plain[1] == pytest.approx(_trapezoid(HOME, OTHER, 1.0), rel=2e-3)


def test_modal_tcp_speed_does_not_warn_on_joint_moves() -> None:
    """`speed 400 mm/s` as a setting is for the Cartesian moves after it: no warning."""
    _, diags = _planned(START + "  speed 400 mm/s\n  move joint other\n")
    assert diags == []


def test_joint_share_on_a_linear_move_warns_and_is_not_used() -> None:
    start = "  move joint pose(x=900mm, z=700mm, ry=180deg)\n"
    line = "  move linear pose(x=900mm, y=100mm, z=700mm, ry=180deg)"
    for mod in (" speed 20 %", " joint_speed 20 %"):
        durations, diags = _planned(start + line + mod + "\n")
        plain, _ = _planned(start + line + "\n")
        assert [d.code.id for d in diags if d.code.id != "W224"] == ["W171"]
        assert durations[1] == plain[1]


def test_wrong_dimension_speed_is_still_an_error() -> None:
    codes = [d.code.id for d in _load(START + "  move joint other speed 20 deg\n").diagnostics]
    assert codes == ["E104"]


# ----------------------------------------------------------------------------- turns

POSE = "pose(x=1000mm, z=800mm, ry=180deg) * pose(rz=90deg)"  # J6 = 90 deg on turn 0


def _turn_of_deg(q: float) -> int:
    return math.floor((q + 180) / 360)


def _j6(body: str) -> tuple[list[float], list[Diagnostic]]:
    front = _load(body)
    assert front.program is not None, [d.message for d in front.diagnostics]
    plan = plan_program(front.program)
    tp = plan.tasks[0]
    out = []
    for m in (n for n in ir_tree.walk(tp.task.body) if isinstance(n, ir.Move)):
        rec = tp.record(m.uid)
        out.append(
            math.nan
            if rec is None or rec.q_target is None
            else math.degrees(float(rec.q_target[5]))
        )
    return out, list(plan.diagnostics)


def test_joint_move_takes_the_fixed_turn() -> None:
    """IRB 1600 J6 is +-400 deg (ROS-I irb1600 macro, the library's source): a pose with J6 = 90
    deg lies on turn 0 (90) or turn -1 (-270); config(j6=-1) takes -270, config(j6=0) 90."""
    q6, diags = _j6(
        START + f"  move joint {POSE} config(wrist=noflip, j6=-1)\n"
        f"  move joint {POSE} config(wrist=noflip, j6=0)\n"
    )
    assert diags == []
    assert [_turn_of_deg(q) for q in q6[1:]] == [-1, 0]
    assert q6[1] == pytest.approx(-270, abs=1e-6) and q6[2] == pytest.approx(90, abs=1e-6)


def test_linear_move_keeps_the_turn_it_runs_on() -> None:
    q6, diags = _j6(
        START + f"  move joint {POSE} config(j6=-1)\n"
        f"  move linear shift({POSE}, z=-50mm) config(j6=-1)\n"
    )
    assert diags == [] and _turn_of_deg(q6[2]) == -1


def _codes(body: str) -> list[tuple[str, int]]:
    _, diags = _j6(body)
    return [(d.code.id, d.span.start.line) for d in diags if d.span is not None]


def test_turn_on_a_joint_of_360_deg_or_less_is_e172() -> None:
    """J1 +-180 (exactly 360 deg) and J5 +-115 have one turn for every value."""
    assert _codes(
        START + f"  move joint {POSE} config(j1=0)\n  move joint {POSE} config(j5=0)\n"
    ) == [("E172", 5), ("E172", 6)]


def test_turn_outside_the_limits_is_e173() -> None:
    _, diags = _j6(START + f"  move joint {POSE} config(j6=2)\n")
    (d,) = diags
    assert d.code.id == "E173" and "joint 6 turn 2" in d.message and "-1 to 1" in d.message


def test_turn_the_pose_cannot_reach_is_e174() -> None:
    """J6 = 90 deg on turn 1 would be 450 deg, beyond +400 (the flipped wrist's -90 deg could
    be 270 on turn 1: free wrist, that is taken with W220 naming the flip)."""
    _, diags = _j6(START + f"  move joint {POSE} config(wrist=noflip, j6=1)\n")
    (d,) = diags
    assert d.code.id == "E174" and "joint 6 on turn 1" in d.message and "turns -1, 0" in d.message


def test_linear_move_that_cannot_keep_the_turn_is_e174() -> None:
    _, diags = _j6(
        START + f"  move joint {POSE} config(j6=0)\n"
        f"  move linear shift({POSE}, z=-50mm) config(j6=-1)\n"
    )
    (d,) = diags
    assert d.code.id == "E174" and d.span.start.line == 6 and "turn -1" in d.message


def test_front_end_turn_errors() -> None:
    """A joint the robot does not have, a non-integer turn: E170/E171 at the argument."""
    found = [
        (d.code.id, d.span.start.col)
        for d in _load(
            f"  move joint {POSE} config(j9=1, j6=1.5, j6=-1 deg, wrist=flip)\n"
        ).diagnostics
    ]
    col = len(f"  move joint {POSE} config(") + 1
    assert found == [
        ("E170", col),
        ("E171", col + len("j9=1, j6=")),
        ("E171", col + len("j9=1, j6=1.5, j6=")),
    ]


def test_turn_reached_on_another_wrist_warns_about_the_flip() -> None:
    q6, diags = _j6(START + f"  move joint {POSE} config(j6=1)\n")
    assert [d.code.id for d in diags] == ["W220"] and "wrist" in diags[0].message
    assert q6[1] == pytest.approx(270, abs=1e-6)


def test_urdf_arm_with_numeric_ik_takes_the_fixed_turn() -> None:
    """examples/urdf_cell/arm6.urdf: J6 +-6.28 rad (its <limit>), IK numeric (one local solution,
    moved onto the fixed turn by whole turns): J6 = 60 deg on turn 0, -300 deg on turn -1."""
    cell_dir = Path(__file__).resolve().parents[2] / "examples" / "urdf_cell"
    target = "pose(x=400mm, z=800mm, ry=180deg) * pose(rz=60deg)"
    text = (f'use cell "cell.rmot"\nprogram p on r1 {{\n  move joint {_joints(HOME)}\n'
            f"  move joint {target} config(j6=-1)\n  move joint {target} config(j6=0)\n}}\n")
    front = load_text(text, str(cell_dir / "probe.rmot"))
    assert front.program is not None, [d.message for d in front.diagnostics]
    plan = plan_program(front.program)
    assert [d for d in plan.diagnostics if d.is_error] == []
    records = plan.tasks[0].records
    q6 = [math.degrees(float(r.q_target[5])) for r in records if r.q_target is not None]
    assert q6[1:] == [pytest.approx(-300, abs=1e-3), pytest.approx(60, abs=1e-3)]
