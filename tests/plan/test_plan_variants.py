"""Runtime `if` variants: the otherwise arm plus the rest of the task after the if."""

from __future__ import annotations

import dataclasses
import re

import numpy as np
import pytest

from rmot.lang import ir
from rmot.compiler.plan import plan_program
from rmot.sim.robots import load_robot

from plan_helpers import Counter, Prog, pose, program

START = [0, 0, 0, 0, 30, 0]
THEN_END = [10, 0, 0, 0, 30, 0]
OTHER_END = [150, 0, 0, 0, 30, 0]
FINAL = [0, 60, 0, 0, 30, 0]


def _apart_program() -> tuple[ir.Program, dict[str, int]]:
    """Start, if (then: small turn / otherwise: half a turn), then two moves and a wait."""
    c = Counter()
    p, then, other = Prog(c), Prog(c), Prog(c)
    p.joint(START)
    then.joint(THEN_END)
    other.joint(OTHER_END)
    uids = {"if": p.if_(then, other)}
    uids["after1"] = p.joint(FINAL)
    uids["after2"] = p.linear(pose(400, 50, 200, rx=180, rz=180))
    uids["wait"] = p.wait(0.3)
    return program(p.task()), uids


class TestContinuation:
    def test_variant_runs_to_the_task_end_with_its_own_records(self) -> None:
        """The otherwise variant continues after the if to the end; its post-if records are variant 1
        with q_target whose FK is the move's target."""
        prog, uids = _apart_program()
        plan = plan_program(prog)
        tp = plan.tasks[0]
        (v,) = tp.variants
        robot = load_robot("abb_irb120")
        main_after = tp.record(uids["after1"])
        assert main_after.variant == 0  # TaskPlan.record keeps preferring the main timeline
        mine = {r.uid: r for r in tp.records if r.variant == v.index}
        assert {uids["after1"], uids["after2"], uids["wait"]} <= set(mine)
        # the variant's trajectory reaches the end of its own last record, holding the final joints
        assert v.trajectory.t[-1] >= mine[uids["wait"]].t_end - 1e-9
        assert mine[uids["wait"]].t_end - mine[uids["wait"]].t_start == pytest.approx(0.3)
        # it turns the base through 150 deg and back: longer than the main timeline after the if
        # (the 4 ms samples straddle the turning point: within a_max h^2 / 8 of it)
        assert np.max(v.trajectory.q[:, 0]) == pytest.approx(np.radians(150), abs=2e-4)
        assert v.trajectory.t[-1] > tp.trajectory.t[-1]
        assert np.allclose(mine[uids["after1"]].q_target, np.radians(FINAL))
        target = pose(400, 50, 200, rx=180, rz=180).matrix()
        assert np.allclose(robot.fk(mine[uids["after2"]].q_target), target, atol=1e-6)
        assert np.allclose(v.trajectory.q[-1], mine[uids["after2"]].q_target, atol=1e-9)
        # the post-if move in the variant starts where the otherwise arm ended
        at = v.trajectory.at(mine[uids["after1"]].t_start)
        assert np.allclose(at, np.radians(OTHER_END), atol=2e-4)  # linear interpolation of 4 ms samples

    def test_later_ifs_take_their_then_arm_in_a_continuation(self) -> None:
        """Two ifs in a row give two variants (not four); the first one's continuation takes the second's then arm."""
        c = Counter()
        p, then1, other1, then2, other2 = (Prog(c) for _ in range(5))
        p.joint(START)
        then1.joint(THEN_END)
        other1.joint(OTHER_END)
        if1 = p.if_(then1, other1)
        t2 = then2.joint([0, 20, 0, 0, 30, 0])
        o2 = other2.joint([0, -20, 0, 0, 30, 0])
        if2 = p.if_(then2, other2)
        tp = plan_program(program(p.task())).tasks[0]
        assert [(v.index, v.if_uid) for v in tp.variants] == [(1, if1), (2, if2)]
        first = {r.uid for r in tp.records if r.variant == 1}
        second = {r.uid for r in tp.records if r.variant == 2}
        assert t2 in first and o2 not in first
        assert o2 in second and t2 not in second
        # the second if's variant starts from the main timeline (after the first if's then arm)
        v2 = tp.variants[1]
        assert np.allclose(v2.trajectory.q[0], np.radians(THEN_END), atol=1e-9)

    def test_if_nested_in_an_otherwise_arm_starts_from_that_arm(self) -> None:
        """An if inside an otherwise arm gets its own variant, started in the outer variant, and continues after the outer if."""
        c = Counter()
        p, then, other, inner_then, inner_other = (Prog(c) for _ in range(5))
        p.joint(START)
        then.joint(THEN_END)
        other.joint(OTHER_END)
        inner_then.joint([150, 20, 0, 0, 30, 0])
        inner_other.joint([150, -20, 0, 0, 30, 0])
        other.if_(inner_then, inner_other)
        p.if_(then, other)
        after = p.joint(FINAL)
        tp = plan_program(program(p.task())).tasks[0]
        assert len(tp.variants) == 2
        inner = next(v for v in tp.variants if v.index == 2)
        assert np.allclose(inner.trajectory.q[0], np.radians(OTHER_END), atol=1e-9)
        assert np.min(inner.trajectory.q[:, 1]) == pytest.approx(np.radians(-20), abs=2e-4)  # 4 ms samples
        rec = next(r for r in tp.records if r.variant == 2 and r.uid == after)
        assert np.allclose(inner.trajectory.at(rec.t_start), np.radians([150, -20, 0, 0, 30, 0]), atol=2e-4)
        assert np.allclose(inner.trajectory.q[-1], np.radians(FINAL), atol=1e-9)


class TestW223:
    def test_no_warning_when_the_moves_after_reach_the_same_joints(self) -> None:
        """Arms ending apart are fine when every post-if move reaches the same joints either way."""
        prog, _ = _apart_program()
        assert [d.code.id for d in plan_program(prog).diagnostics] == []

    def test_a_post_if_move_reaching_other_joints_is_warned_at_that_move(self) -> None:
        """A joint move to a pose after the if that, nearest to the otherwise arm's end, takes a
        joint 6 turn (+360 deg) instead of the main timeline's solution: W223 at that move."""
        c = Counter()
        p, then, other = Prog(c), Prog(c), Prog(c)
        p.joint([0, 0, 0, 0, 30, 0])
        then.joint([0, 0, 0, 0, 40, 0])
        other.joint([0, 0, 0, 0, 40, 300])
        if_uid = p.if_(then, other)
        after = p.joint(pose(350, 0, 400, rx=180, ry=-20, rz=180))
        plan = plan_program(program(p.task()))
        w223 = [d for d in plan.diagnostics if d.code.id == "W223"]
        assert [(d.span.start.line, d.notes[0][1].start.line) for d in w223] == [(after, if_uid)]
        assert [d.code.id for d in plan.diagnostics] == ["W223"]
        tp = plan.tasks[0]
        main = tp.record(after)
        var = next(r for r in tp.records if r.uid == after and r.variant == 1)
        assert np.degrees(var.q_target[5] - main.q_target[5]) == pytest.approx(360)
        assert "360.0 deg" in w223[0].message


def test_variant_holds_at_a_sync_after_the_if_like_the_main_timeline() -> None:
    """A sync after the if: the variant leaves the barrier when the main timeline does (if it arrives earlier)."""
    c = Counter()
    a, then, other = Prog(c), Prog(c), Prog(c)
    a.joint(START)
    then.joint([40, 0, 0, 0, 30, 0])
    other.joint(THEN_END)  # shorter than the then arm: arrives at the sync earlier
    a.if_(then, other)
    s = a.sync("go")
    after = a.joint(FINAL)
    b = Prog(c)
    b.joint(START)
    b.wait(3.0)
    b.sync("go")
    plan = plan_program(program(a.task("t1", "r1"), b.task("t2", "r2"),
                                robots={"r1": "abb_irb120", "r2": "abb_irb120"}))
    tp = plan.task("t1")
    main_sync = tp.record(s)
    var_sync = next(r for r in tp.records if r.uid == s and r.variant == 1)
    assert main_sync.t_end == pytest.approx(3.0)
    assert var_sync.t_end == pytest.approx(main_sync.t_end)
    var_after = next(r for r in tp.records if r.uid == after and r.variant == 1)
    assert var_after.t_start == pytest.approx(tp.record(after).t_start)


def test_a_fixture_hit_after_the_if_only_on_the_otherwise_path_is_found_at_that_move() -> None:
    """Through the simulator: a box hit by the post-if move only when the otherwise arm ran is
    reported at the post-if move, in the otherwise path, and not on the main timeline."""
    from rmot.sim import verify

    prog, uids = _apart_program()
    box = ir.Fixture("box", ir.Box((0.08, 0.08, 0.08)), ir.Pose((0.121, 0.452, 0.371)))
    prog = dataclasses.replace(prog, cell=dataclasses.replace(prog.cell, fixtures=(box,)))
    plan = plan_program(prog)
    assert [d.code.id for d in plan.diagnostics] == []
    report = verify(plan)
    hits = [d for d in report.diagnostics if "box" in d.message]
    assert hits, [d.message for d in report.diagnostics]
    assert {d.span.start.line for d in hits} == {uids["after1"]}
    assert all(re.search(r"\(on the path through the 'otherwise' arm of the if at line \d+\)$", d.message) for d in hits)


def test_variants_are_deterministic() -> None:
    """Planning twice gives identical variant trajectories and records."""
    a, b = (plan_program(_apart_program()[0]).tasks[0] for _ in range(2))
    for va, vb in zip(a.variants, b.variants, strict=True):
        assert va.trajectory.t.tobytes() == vb.trajectory.t.tobytes()
        assert va.trajectory.q.tobytes() == vb.trajectory.q.tobytes()
    ra = [(r.uid, r.variant, r.t_start, r.t_end, None if r.q_target is None else r.q_target.tobytes()) for r in a.records]
    rb = [(r.uid, r.variant, r.t_start, r.t_end, None if r.q_target is None else r.q_target.tobytes()) for r in b.records]
    assert ra == rb


def test_variant_without_motion_before_a_sync_holds_at_the_if_start() -> None:
    """An otherwise arm with no motion, then a sync: the variant holds at the if's start joints until the barrier."""
    c = Counter()
    a, then, other = Prog(c), Prog(c), Prog(c)
    a.joint(START)
    then.joint([40, 0, 0, 0, 30, 0])
    other.set(1, True)
    a.if_(then, other)
    s = a.sync("go")
    a.joint(FINAL)
    b = Prog(c)
    b.joint(START)
    b.wait(3.0)
    b.sync("go")
    plan = plan_program(program(a.task("t1", "r1"), b.task("t2", "r2"),
                                robots={"r1": "abb_irb120", "r2": "abb_irb120"}))
    tp = plan.task("t1")
    (v,) = tp.variants
    var_sync = next(r for r in tp.records if r.uid == s and r.variant == 1)
    assert var_sync.t_end == pytest.approx(3.0)
    held = v.trajectory.t < 3.0 - 1e-9
    assert np.allclose(v.trajectory.q[held], np.radians(START), atol=1e-12)
    assert v.trajectory.t[-1] == pytest.approx(tp.trajectory.t[-1], abs=plan.step)
