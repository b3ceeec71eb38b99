"""Runtime logic in the planner and the verifier: every loop iteration planned and
checked, findings naming the iteration, the while fixed-point rule, timeout paths and stop.

Independent witnesses: the palletiser's 36 slot poses and the iteration that must collide are
computed here from the cell's numbers by hand, not from the planner.
"""

from __future__ import annotations

import dataclasses
import itertools
from pathlib import Path

import numpy as np
import pytest
from rmot.lang import ir, ir_tree
from rmot.compiler.frontend import load_program, load_text
from rmot.compiler.plan import timeline
from rmot.compiler.plan.planner import plan_program
from rmot.sim.verification import verify

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"


def _plan_text(text: str, tmp_path: Path, name: str = "p.rmot"):  # type: ignore[no-untyped-def]
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    result = load_program(str(path))
    assert result.program is not None, [d.message for d in result.diagnostics]
    return result.program, plan_program(result.program)


# --------------------------------------------------------------------------- the palletiser


def test_palletizer_plans_all_36_placements() -> None:
    """examples/palletizing.rmot: the pallet frame is pallet_base (centre y = -1100 mm, top at
    z = 400 mm) moved to its -x,-y corner, i.e. world (-300, -1300, 400) mm; a slot's TCP is at
    x = 95 + 190 col, y = 45 + 90 row, z = 100 + 100 layer mm from there (cartons touching), tool down; the robot
    base is at z = 400 mm. Each of the 3 x 4 x 3 slots must be the target of exactly one planned
    move of the main timeline (the straight move down onto it)."""
    result = load_program(str(EXAMPLES / "palletizing.rmot"))
    assert result.program is not None
    plan = plan_program(result.program)
    assert [d for d in plan.diagnostics if d.is_error] == []
    (tp,) = plan.tasks
    reached = np.array(
        [
            r.tcp_pose.position
            for r in tp.records
            if r.variant == 0 and r.tcp_pose is not None and r.q_target is not None
        ]
    )
    expected = [
        (
            -0.300 + 0.095 + 0.190 * col,
            -1.300 + 0.045 + 0.090 * row,
            0.400 + 0.100 + 0.100 * layer - 0.400,
        )
        for layer, row, col in itertools.product(range(3), range(4), range(3))
    ]
    assert len(expected) == 36
    for slot in expected:
        hits = np.flatnonzero(np.linalg.norm(reached - np.array(slot), axis=1) < 1e-4)
        assert len(hits) == 1, (slot, len(hits))
    down = [
        r
        for r in tp.records
        if r.variant == 0
        and r.tcp_pose is not None
        and r.q_target is not None
        and any(
            np.linalg.norm(np.array(r.tcp_pose.position) - np.array(s)) < 1e-4 for s in expected
        )
    ]
    for r in down:  # tool pointing straight down: the TCP's z axis along -z of the base
        assert r.tcp_pose.matrix()[:3, 2] == pytest.approx([0.0, 0.0, -1.0], abs=1e-6)
    # the placements come in loop order: layer by layer, row by row, column by column
    order = [
        int(np.argmin(np.linalg.norm(np.array(expected) - np.array(r.tcp_pose.position), axis=1)))
        for r in sorted(down, key=lambda r: r.t_start)
    ]
    assert order == list(range(36))


# ------------------------------------------------------------ a collision in one iteration

_PEG_CELL = """
cell peg_cell {
  robot r1 = abb_irb1600 at pose(z=400mm)
  fixture table = box(600mm, 800mm, 750mm) at pose(x=850mm, z=375mm)
  fixture peg = box(40mm, 40mm, 100mm) at pose(x=PXmm, y=PYmm, z=800mm)
  tool gripper = box(90mm, 70mm, 120mm) at pose(z=120mm) tcp pose(z=180mm) mass 1.2 kg on r1
  frame top = table * pose(z=375mm)
}
program grid on r1 {
  tool gripper
  target home = joints(0, -10, 10, 0, 90, 0) deg
  target p0 = pose(x=-150mm, y=-150mm, z=30mm, rx=180deg)
  move joint home
  frame top
  for row in 0 .. 3 {
    for col in 0 .. 3 {
      move joint shift(p0, x=col * 150mm, y=row * 150mm, z=150mm) zone fine
      move linear shift(p0, x=col * 150mm, y=row * 150mm) speed 200 mm/s zone fine
      move linear shift(p0, x=col * 150mm, y=row * 150mm, z=150mm) speed 200 mm/s zone fine
    }
  }
  move joint home zone fine
}
"""


def test_hidden_collision_in_one_iteration_names_it(tmp_path: Path) -> None:
    """A 40 x 40 mm peg standing 100 mm on the bench (top at 850 mm) under one of the nine grid
    points. The bench top's centre is world (850, 0, 750) mm; grid point (row, col) is at x =
    850 - 150 + 150 col, y = -150 + 150 row, the TCP 30 mm above the bench, and the gripper body
    (90 x 70 mm, from the TCP upwards) goes down there. Computed here: the gripper overlaps the
    peg only where |dx| < 20 + 45 and |dy| < 20 + 35 mm; above the grid (TCP at 900 mm) it
    clears the peg's top. The collision must be found and name exactly that iteration."""
    px, py = 850.0, 150.0
    _, plan = _plan_text(_PEG_CELL.replace("PX", f"{px:g}").replace("PY", f"{py:g}"), tmp_path)
    assert [d for d in plan.diagnostics if d.is_error] == []
    colliding = [
        (row, col)
        for row, col in itertools.product(range(3), range(3))
        if abs(850 - 150 + 150 * col - px) < 65 and abs(-150 + 150 * row - py) < 55
    ]
    assert colliding == [(2, 1)]
    report = verify(plan)
    hits = [d for d in report.diagnostics if d.code.id == "E300"]
    assert hits, [d.message for d in report.diagnostics]
    assert all("peg" in d.message for d in hits)
    row, col = colliding[0]
    assert all(f"(in iteration row = {row}, col = {col})" in d.message for d in hits), [
        d.message for d in hits
    ]


# ------------------------------------------------------------ while: the fixed-point rule

_WHILE = """
program w on r1 {{
  target home = joints(0, -10, 10, 0, 90, 0) deg
  target a = joints(30, -10, 10, 0, 90, 0) deg
  move joint home
  while in[2] == on {{
{body}
  }}
  move joint home
}}
"""


def _moves_of(tp, prog: ir.Program, name: str) -> list:  # type: ignore[no-untyped-def]
    uids = {
        i.uid
        for i in ir_tree.walk(prog.tasks[0].body)
        if isinstance(i, ir.Move) and i.target.name == name
    }
    return [r for r in tp.records if r.uid in uids and r.variant == 0]


def test_while_returning_to_its_start_is_proved_after_one_iteration(tmp_path: Path) -> None:
    prog, plan = _plan_text(_WHILE.format(body="    move joint a\n    move joint home"), tmp_path)
    assert [d.code.id for d in plan.diagnostics if d.is_error] == []
    (tp,) = plan.tasks
    assert len(_moves_of(tp, prog, "a")) == 1  # one iteration ends where it started: done
    assert [v.arm for v in tp.variants] == [
        "no iteration"
    ]  # the code after it, from before the loop


def test_while_ending_elsewhere_reaches_its_fixed_point_in_the_second_iteration(
    tmp_path: Path,
) -> None:
    """Starting at home and ending at `a`: iteration 1 goes home -> a, iteration 2 a -> a (the
    state it started from), so two iterations are planned and the rule holds."""
    prog, plan = _plan_text(_WHILE.format(body="    move joint a"), tmp_path)
    assert [d.code.id for d in plan.diagnostics if d.is_error] == []
    (tp,) = plan.tasks
    moves = _moves_of(tp, prog, "a")
    assert (
        len(moves) == 2
        and moves[0].t_end > moves[0].t_start
        and moves[1].t_end == pytest.approx(moves[1].t_start)
    )


def test_while_that_drifts_is_e240(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A body whose end depends on its start never repeats: here its move goes 0.05 rad further
    on joint 1 from wherever it starts (a relative move, put in for the test by wrapping the
    planner's segment builder), so no iteration ends where it started: E240 at the while."""
    real = timeline.build_segment

    def relative(robot, move, q_start):  # type: ignore[no-untyped-def]
        if move.target.name == "a":
            move = dataclasses.replace(
                move, target=ir.JointTarget(tuple(q_start + np.eye(len(q_start))[0] * 0.05), "a")
            )
        return real(robot, move, q_start)

    monkeypatch.setattr(timeline, "build_segment", relative)
    prog, plan = _plan_text(_WHILE.format(body="    move joint a"), tmp_path)
    errors = [d for d in plan.diagnostics if d.is_error]
    assert [d.code.id for d in errors] == ["E240"]
    assert (
        errors[0].span is not None
        and errors[0].span.start.line == 6
        and "line 6" in errors[0].message
    )
    (tp,) = plan.tasks
    assert len(_moves_of(tp, prog, "a")) == timeline.WHILE_BOUND


# --------------------------------------------------------------------------- timeouts and stop


def test_timeout_path_holds_then_runs_its_branch_and_stop_ends_it(tmp_path: Path) -> None:
    prog, plan = _plan_text(
        """
program t on r1 {
  target home = joints(0, -10, 10, 0, 90, 0) deg
  target a = joints(30, -10, 10, 0, 90, 0) deg
  target b = joints(-30, -10, 10, 0, 90, 0) deg
  move joint home
  wait until in[1] == on timeout 4 s else {
    move joint b
    stop
  }
  move joint a
}
""",
        tmp_path,
    )
    assert [d for d in plan.diagnostics if d.is_error] == []
    (tp,) = plan.tasks
    (variant,) = tp.variants
    assert variant.arm == "timeout"
    body = prog.tasks[0].body
    wait = body[1]
    assert isinstance(wait, ir.WaitInput)
    move_b, stop = wait.on_timeout
    move_a = body[2]
    on_path = {r.uid: r for r in tp.records if r.variant == variant.index}
    assert on_path[wait.uid].t_end - on_path[wait.uid].t_start == pytest.approx(4.0)
    assert on_path[move_b.uid].t_start >= on_path[wait.uid].t_end - 1e-9
    assert stop.uid in on_path and move_a.uid not in on_path  # nothing after stop on that path
    main = {r.uid for r in tp.records if r.variant == 0}
    assert move_a.uid in main and move_b.uid not in main


def test_if_whose_then_arm_stops_plans_the_other_path(tmp_path: Path) -> None:
    prog, plan = _plan_text(
        """
program t on r1 {
  target home = joints(0, -10, 10, 0, 90, 0) deg
  target a = joints(30, -10, 10, 0, 90, 0) deg
  var n = 0
  move joint home
  if n > 2 { stop }
  move joint a
}
""",
        tmp_path,
    )
    (tp,) = plan.tasks
    move_a = prog.tasks[0].body[-1]
    assert move_a.uid not in {r.uid for r in tp.records if r.variant == 0}  # the main path stopped
    assert [v.arm for v in tp.variants] == ["otherwise"]
    assert move_a.uid in {r.uid for r in tp.records if r.variant == tp.variants[0].index}


def test_machine_tending_example_checks_clean() -> None:
    result = load_program(str(EXAMPLES / "machine_tending.rmot"))
    assert result.program is not None and not any(d.is_error for d in result.diagnostics)
    plan = plan_program(result.program)
    report = verify(plan)
    assert [d.code.id for d in (*plan.diagnostics, *report.diagnostics) if d.is_error] == []
    assert sorted(v.arm for v in plan.tasks[0].variants) == ["no iteration", "timeout"]


def test_a_var_used_in_a_pose_is_refused_before_planning(tmp_path: Path) -> None:
    result = load_text(
        "program p on r1 {\n  var dz = 1\n  move joint pose(x=400mm, z=dz * 1mm)\n}\n",
        str(tmp_path / "p.rmot"),
    )
    assert [d.code.id for d in result.diagnostics] == ["E154"]


def test_first_move_inside_a_loop_is_the_task_start(tmp_path: Path) -> None:
    """The start of the task is the first move on the main timeline, also inside a loop: a
    linear first move there is W224 (an unknown start), at that move."""
    _, plan = _plan_text(
        """
program s on r1 {
  target a = pose(x=700mm, y=0mm, z=900mm, rx=180deg)
  for i in 0 .. 2 {
    move linear shift(a, y=i * 50mm)
  }
}
""",
        tmp_path,
    )
    w224 = [d for d in plan.diagnostics if d.code.id == "W224"]
    assert [d.span.start.line for d in w224 if d.span is not None] == [5]


def test_while_whose_body_stops_still_plans_the_code_after_it(tmp_path: Path) -> None:
    prog, plan = _plan_text(
        _WHILE.format(body="    move joint a\n    stop"),
        tmp_path,
    )
    (tp,) = plan.tasks
    last = prog.tasks[0].body[-1]
    assert last.uid not in {r.uid for r in tp.records if r.variant == 0}
    (variant,) = tp.variants
    assert variant.arm == "no iteration"
    assert last.uid in {r.uid for r in tp.records if r.variant == variant.index}


def test_a_finding_only_in_a_later_while_round_names_the_round(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The body's move turns joint 1 by 2 rad further from wherever it starts (a relative move,
    as in the drift test): round 1 ends at 2 rad (115 deg), inside the IRB 1600's +-180 deg;
    round 2 would end at 4 rad (229 deg), beyond it. That finding exists only in round 2, and
    says so."""
    real = timeline.build_segment

    def relative(robot, move, q_start):  # type: ignore[no-untyped-def]
        if move.target.name == "a":
            q = tuple(q_start + np.eye(len(q_start))[0] * 2.0)
            move = dataclasses.replace(move, target=ir.JointTarget(q, "a"))
        return real(robot, move, q_start)

    monkeypatch.setattr(timeline, "build_segment", relative)
    _, plan = _plan_text(_WHILE.format(body="    move joint a"), tmp_path)
    later = [d for d in plan.diagnostics if "(in round 2 of the while at line 6" in d.message]
    assert later and all(d.span is not None and d.span.start.line == 7 for d in later)
    assert not [d for d in plan.diagnostics if "round 1" in d.message]
