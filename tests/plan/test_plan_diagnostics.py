"""Planning errors and warnings: right code, right line, helpful words; planning goes on."""

from __future__ import annotations

import numpy as np
import pytest

from rmot.lang import ir
from rmot.compiler.plan import plan_program
from rmot.lang.diagnostics import Severity, render

from plan_helpers import Prog, pose, program

TOOL_DOWN = dict(rx=180, ry=0, rz=180)


def _found(plan) -> list[tuple[str, int]]:  # type: ignore[no-untyped-def]
    return [(d.code.id, d.span.start.line) for d in plan.diagnostics]


def _one(plan, code: str):  # type: ignore[no-untyped-def]
    found = [d for d in plan.diagnostics if d.code.id == code]
    assert len(found) == 1, _found(plan)
    return found[0]


class TestErrorsAtTheMove:
    def test_target_out_of_reach(self) -> None:
        """A pose 1.5 m away: E220 at that move, saying how far outside the workspace."""
        p = Prog()
        p.joint(pose(300, -150, 300, **TOOL_DOWN))
        bad = p.linear(pose(1500, 0, 300, **TOOL_DOWN))
        plan = plan_program(program(p.task()))
        d = _one(plan, "E220")
        assert d.span.start.line == bad and d.severity is Severity.ERROR
        assert "outside the workspace" in d.message and "mm" in d.message

    def test_branch_change_on_a_linear_move(self) -> None:
        """config(wrist=flip) on a linear move from a noflip pose: E222 naming the change and the fix."""
        p = Prog()
        p.joint(pose(300, -150, 300, **TOOL_DOWN))
        bad = p.linear(pose(300, 0, 300, **TOOL_DOWN), config=ir.Config(wrist=ir.Wrist.FLIP))
        plan = plan_program(program(p.task()))
        d = _one(plan, "E222")
        assert d.span.start.line == bad
        assert "wrist from noflip to flip" in d.message and "insert a joint move with config(wrist=flip)" in d.message

    def test_target_only_on_another_branch(self, irb120) -> None:  # type: ignore[no-untyped-def]
        """A linear move to a pose whose only in-limit solution flips the wrist: E222."""
        p = Prog()
        p.joint([0, 0, 0, 0, 20, 0])
        target = ir.Pose.from_matrix(irb120.fk(np.radians([0, 30, 10, 0, -20, 0])))
        bad = p.linear(target)
        d = _one(plan_program(program(p.task())), "E222")
        assert d.span.start.line == bad and "wrist from noflip to flip" in d.message

    def test_singular_line(self) -> None:
        """A line whose wrist centre crosses the J1 axis: E224 naming a shoulder singularity and where."""
        p = Prog()
        p.joint(pose(0, -60, 500, **TOOL_DOWN))
        bad = p.linear(pose(0, 60, 500, **TOOL_DOWN))
        d = _one(plan_program(program(p.task())), "E224")
        assert d.span.start.line == bad
        assert "shoulder singularity at (0.0, -0.0, 500.0) mm" in d.message or "shoulder singularity at (0.0, 0.0, 500.0) mm" in d.message

    def test_degenerate_arc(self) -> None:
        """Start, via and end on one line: E226 at the circular move."""
        p = Prog()
        p.joint(pose(300, -150, 300, **TOOL_DOWN))
        bad = p.circular(pose(350, -75, 300, **TOOL_DOWN), pose(400, 0, 300, **TOOL_DOWN))
        d = _one(plan_program(program(p.task())), "E226")
        assert d.span.start.line == bad and "collinear" in d.message

    def test_joint_target_out_of_limits_names_axis_value_and_bound(self) -> None:
        """joints(..., 200 deg, ...) on J5 (limit 120 deg): E223 with the axis, value and bound."""
        p = Prog()
        p.joint([0, 0, 0, 0, 30, 0])
        bad = p.joint([0, 0, 0, 0, 200, 0])
        d = _one(plan_program(program(p.task())), "E223")
        assert d.span.start.line == bad
        assert d.message == "joint 5 must be within [-120.0, 120.0] deg (got 200.0 deg)"


def test_all_errors_are_reported_and_the_rest_is_planned() -> None:
    """Two bad moves give two errors; the good moves around them are still planned."""
    p = Prog()
    first = p.joint(pose(300, -150, 300, **TOOL_DOWN))
    bad1 = p.linear(pose(1500, 0, 300, **TOOL_DOWN))
    good = p.linear(pose(300, 100, 300, **TOOL_DOWN))
    bad2 = p.circular(pose(300, 150, 300, **TOOL_DOWN), pose(300, 200, 300, **TOOL_DOWN))
    last = p.joint([0, 0, 0, 0, 30, 0])
    plan = plan_program(program(p.task()))
    assert _found(plan) == [("W224", first), ("E220", bad1), ("E226", bad2)]
    tp = plan.tasks[0]
    assert tp.record(good).t_end > tp.record(good).t_start
    assert np.allclose(tp.trajectory.q[-1], np.radians([0, 0, 0, 0, 30, 0]))
    assert tp.record(last).t_end == pytest.approx(tp.cycle_time, abs=plan.step)


def test_joint_move_branch_change_is_warned_not_silent(irb120) -> None:  # type: ignore[no-untyped-def]
    """A joint move whose nearest solution flips the wrist: planned, with W220 naming the change."""
    p = Prog()
    p.joint([0, 0, 0, 0, 20, 0])
    target = ir.Pose.from_matrix(irb120.fk(np.radians([0, 30, 10, 0, -20, 0])))
    uid = p.joint(target)
    plan = plan_program(program(p.task()))
    d = _one(plan, "W220")
    assert d.span.start.line == uid and "config(wrist=flip)" in d.message
    assert plan.tasks[0].record(uid).branch.wrist is ir.Wrist.FLIP


def test_explicit_config_selects_the_branch_without_warning(irb120) -> None:  # type: ignore[no-untyped-def]
    """With config(wrist=flip) the same joint move is silent and lands on the flip branch."""
    p = Prog()
    p.joint([0, 0, 0, 0, 20, 0])
    target = ir.Pose.from_matrix(irb120.fk(np.radians([0, 30, 10, 0, -20, 0])))
    uid = p.joint(target, config=ir.Config(wrist=ir.Wrist.FLIP))
    plan = plan_program(program(p.task()))
    assert plan.diagnostics == ()
    assert plan.tasks[0].record(uid).branch.wrist is ir.Wrist.FLIP


def test_near_singularity_slows_down_with_a_warning(irb120) -> None:  # type: ignore[no-untyped-def]
    """A line passing 20 mm beside the J1 axis: W221 says where and how close; limits still hold."""
    p = Prog()
    p.joint(pose(60, 20, 450, **TOOL_DOWN))
    uid = p.linear(pose(-60, 20, 450, **TOOL_DOWN))
    plan = plan_program(program(p.task()))
    d = _one(plan, "W221")
    assert d.span.start.line == uid
    assert "condition number" in d.message and "mm/s" in d.message
    tr = plan.tasks[0].trajectory
    assert np.all(np.abs(tr.qd) <= irb120.velocity_limits * (1 + 1e-6))


def test_diagnostics_render_with_the_source_line() -> None:
    """Rendered like a compiler: file:line:col, error[code], the source line and carets."""
    p = Prog()
    p.joint(pose(300, -150, 300, **TOOL_DOWN))
    p.linear(pose(1500, 0, 300, **TOOL_DOWN))
    text = render(_one(plan_program(program(p.task())), "E220"))
    assert text.startswith("prog.rmot:2:1: error[E220]: target must be within the robot's reach")
    assert text.splitlines()[1] == " 2 | instruction 2"


def test_unknown_robot_is_a_diagnostic_not_an_exception() -> None:
    """A cell robot that cannot be loaded: E231, and the other tasks are still planned."""
    p = Prog()
    p.joint([0, 0, 0, 0, 30, 0])
    plan = plan_program(program(p.task(), robots={"r1": "no_such_robot"}))
    assert [d.code.id for d in plan.diagnostics] == ["E231"]
    assert plan.tasks == ()


def test_timing_failure_is_a_diagnostic_and_the_robot_holds(monkeypatch) -> None:  # type: ignore[no-untyped-def]
    """If no timing is found for a lone move, E228 at the move and its time; the robot holds its place."""
    import rmot.compiler.plan.topp as topp

    def no_timing(*args, **kwargs):  # type: ignore[no-untyped-def]
        raise timing.TimingError("no feasible timing was found for the path")

    import rmot.compiler.plan.timing as timing

    monkeypatch.setattr(topp, "solve", no_timing)
    p = Prog()
    first = p.joint(pose(300, -150, 300, **TOOL_DOWN))
    bad = p.linear(pose(300, 100, 300, **TOOL_DOWN))
    after = p.joint([0, 0, 0, 0, 30, 0])
    plan = plan_program(program(p.task()))
    assert _found(plan) == [("W224", first), ("E228", bad)]
    tp = plan.tasks[0]
    assert tp.record(bad).t_end == tp.record(bad).t_start == 0.0
    assert tp.record(after).t_end > 0.0


def test_untimeable_chain_gets_exact_stops_not_dropped(monkeypatch) -> None:  # type: ignore[no-untyped-def]
    """A blended chain that cannot be timed as a whole: every corner becomes an exact stop
    with W225 at its move and time, and the plan lasts as long as the same program with
    `zone fine` (nothing vanishes, no 0 s hold)."""
    import rmot.compiler.plan.move_chain as chain

    real = chain.path_piece
    calls = []

    def fail_blended(wp, ss, *args, **kwargs):  # type: ignore[no-untyped-def]
        calls.append(1)
        if len(calls) == 1:
            raise chain.TimingError("no feasible timing was found for the path")
        return real(wp, ss, *args, **kwargs)

    def build(zone: float):  # type: ignore[no-untyped-def]
        p = Prog()
        p.joint([0, 0, 0, 0, 30, 0])
        uids = [p.joint(pose(350, -100, 300, **TOOL_DOWN), zone=zone),
                p.linear(pose(350, 100, 300, **TOOL_DOWN), zone=zone),
                p.linear(pose(400, 100, 250, **TOOL_DOWN))]
        return program(p.task()), uids

    prog, uids = build(0.0)
    fine = plan_program(prog)
    monkeypatch.setattr(chain, "path_piece", fail_blended)
    prog, uids = build(10.0)
    plan = plan_program(prog)
    warned = [(d.code.id, d.span.start.line, d.time_s) for d in plan.diagnostics if d.code.id == "W225"]
    tp = plan.tasks[0]
    assert [w[:2] for w in warned] == [("W225", uids[0]), ("W225", uids[1])]
    for (_, uid, t) in warned:
        assert t == pytest.approx(tp.record(uid).t_end)
        assert f"t = {t:.3f} s" in next(d.message for d in plan.diagnostics if d.span.start.line == uid)
    assert not [d for d in plan.diagnostics if d.severity is Severity.ERROR]
    assert tp.trajectory.t[-1] == pytest.approx(fine.tasks[0].trajectory.t[-1], abs=0.01)


def test_codes_are_registered_in_the_planner_range() -> None:
    """Every planner code is E220-E299 or W220-W299 (or E172-E179, joint turns, a range the
    planner shares with the front end, and E188, config(...) on an arm without branch names,
    from the robots-and-CAD range), with a kebab-case name."""
    from rmot.compiler.plan import codes
    from rmot.lang.diagnostics import Code

    found = [getattr(codes, n) for n in codes.__all__]
    assert all(isinstance(c, Code) for c in found)
    assert all(c.id[0] in "EW" and (220 <= int(c.id[1:]) <= 299 or c.id in ("E172", "E173", "E174", "E188"))
               for c in found)
    assert all(c.name == c.name.lower() and " " not in c.name for c in found)
    assert len({c.id for c in found}) == len(found)


def test_public_api() -> None:
    """rmot.compiler.plan exports exactly plan_program."""
    import rmot.compiler.plan as plan

    assert plan.__all__ == ["plan_program"]
