"""The timeline: waits, I/O instants, runtime ifs, sync barriers, determinism, sampling."""

from __future__ import annotations

import numpy as np
import pytest

from rmot.compiler.plan import plan_program

from plan_helpers import Counter, Prog, pose, program

TOOL_DOWN = dict(rx=180, ry=0, rz=180)


def test_wait_holds_and_set_happens_when_the_move_ends() -> None:
    """`wait 0.5 s` holds still for 0.5 s; a `set` after a fine move happens at its stop."""
    p = Prog()
    p.joint([0, 0, 0, 0, 30, 0])
    m = p.joint([30, 0, 0, 0, 30, 0])
    s = p.set(1, True)
    w = p.wait(0.5)
    plan = plan_program(program(p.task()))
    tp = plan.tasks[0]
    assert tp.record(s).t_start == tp.record(m).t_end
    rec = tp.record(w)
    assert rec.t_end - rec.t_start == pytest.approx(0.5)
    held = (tp.trajectory.t > rec.t_start + 1e-9) & (tp.trajectory.t < rec.t_end - 1e-9)
    assert held.sum() >= 120 and np.all(tp.trajectory.qd[held] == 0)


def test_set_after_a_blended_move_happens_at_the_zone_entry() -> None:
    """`set` between two blended moves happens when the first one enters its zone, without stopping."""
    p = Prog()
    p.joint(pose(300, -150, 300, **TOOL_DOWN))
    a = p.linear(pose(300, 100, 300, **TOOL_DOWN), zone=20)
    s = p.set(1, True)
    p.linear(pose(450, 100, 300, **TOOL_DOWN))
    tp = plan_program(program(p.task())).tasks[0]
    t = tp.record(s).t_start
    assert t == tp.record(a).t_end
    i = int(np.argmin(np.abs(tp.trajectory.t - t)))
    assert np.max(np.abs(tp.trajectory.qd[i])) > 0.1  # still moving


def test_pulse_does_not_stop_the_robot_and_lasts_its_duration() -> None:
    """A pulse takes no robot time; its record lasts the pulse."""
    p = Prog()
    p.joint([0, 0, 0, 0, 30, 0])
    m = p.joint([30, 0, 0, 0, 30, 0])
    u = p.pulse(3, 0.2)
    n = p.joint([0, 0, 0, 0, 30, 0])
    tp = plan_program(program(p.task())).tasks[0]
    assert tp.record(u).t_start == tp.record(m).t_end == tp.record(n).t_start
    assert tp.record(u).t_end - tp.record(u).t_start == pytest.approx(0.2)


class TestSync:
    def _plan(self):  # type: ignore[no-untyped-def]
        c = Counter()
        a, b = Prog(c), Prog(c)
        a.joint([0, 0, 0, 0, 30, 0])
        a.joint([90, 0, 0, 0, 30, 0])  # long
        sa = a.sync("meet")
        ma = a.joint([0, 0, 0, 0, 30, 0])
        b.joint([0, 0, 0, 0, 30, 0])
        b.joint([10, 0, 0, 0, 30, 0])  # short
        sb = b.sync("meet")
        mb = b.joint([20, 0, 0, 0, 30, 0])
        prog = program(a.task("t1", "r1"), b.task("t2", "r2"),
                       robots={"r1": "abb_irb120", "r2": "abb_irb120"})
        return plan_program(prog), (sa, ma, sb, mb)

    def test_the_early_robot_holds_and_both_leave_together(self) -> None:
        """t2 arrives first and waits; after the barrier both tasks start their next move at once."""
        plan, (sa, ma, sb, mb) = self._plan()
        t1, t2 = plan.task("t1"), plan.task("t2")
        assert t2.record(sb).t_start < t1.record(sa).t_start
        assert t2.record(sb).t_end == pytest.approx(t1.record(sa).t_end)
        assert t1.record(ma).t_start == pytest.approx(t2.record(mb).t_start)
        tr = t2.trajectory
        held = (tr.t > t2.record(sb).t_start + 1e-9) & (tr.t < t2.record(sb).t_end - 1e-9)
        assert held.any() and np.all(tr.qd[held] == 0)
        assert np.allclose(tr.q[held], np.radians([10, 0, 0, 0, 30, 0]))

    def test_contradicting_barrier_orders_are_an_error(self) -> None:
        """t1 syncs a then b, t2 syncs b then a: E229 (a deadlock on the controllers)."""
        c = Counter()
        a, b = Prog(c), Prog(c)
        for prog, names in ((a, "ab"), (b, "ba")):
            prog.joint([0, 0, 0, 0, 30, 0])
            for n in names:
                prog.sync(n)
        plan = plan_program(program(a.task("t1", "r1"), b.task("t2", "r2"),
                                    robots={"r1": "abb_irb120", "r2": "abb_irb120"}))
        assert [d.code.id for d in plan.diagnostics] == ["E229"]


class TestIf:
    def test_otherwise_arm_is_a_variant_from_the_if_start(self) -> None:
        """The main timeline takes `then`; `otherwise` is Variant 1 starting at the if's time and joints."""
        c = Counter()
        p, then, other = Prog(c), Prog(c), Prog(c)
        p.joint([0, 0, 0, 0, 30, 0])
        p.joint([20, 0, 0, 0, 30, 0])
        t_uid = then.joint([40, 0, 0, 0, 30, 0])
        then.joint([20, 0, 0, 0, 30, 0])
        o_uid = other.joint([-20, 0, 0, 0, 30, 0])
        other.joint([20, 0, 0, 0, 30, 0])
        if_uid = p.if_(then, other)
        plan = plan_program(program(p.task()))
        tp = plan.tasks[0]
        (v,) = tp.variants
        assert (v.index, v.if_uid, v.arm) == (1, if_uid, "otherwise")
        assert v.trajectory.t[0] == pytest.approx(tp.record(if_uid).t_start)
        # `at` interpolates the 4 ms samples linearly: within a_max h^2 / 8 (69.8 rad/s^2: 1.4e-4 rad)
        # of the exact state when the robot is braking there
        assert np.allclose(v.trajectory.q[0], tp.trajectory.at(v.trajectory.t[0]), atol=2e-4)
        assert np.min(v.trajectory.q[:, 0]) == pytest.approx(np.radians(-20), abs=2e-4)  # 4 ms samples: a h^2 / 8
        assert tp.record(o_uid).variant == 1 and tp.record(t_uid).variant == 0
        assert plan.diagnostics == ()

    def test_arms_ending_apart_with_nothing_after_are_not_warned(self) -> None:
        """Arms ending in different joints alone are no warning: each path is planned to its end (W223 is per post-if move)."""
        c = Counter()
        p, then, other = Prog(c), Prog(c), Prog(c)
        p.joint([0, 0, 0, 0, 30, 0])
        then.joint([40, 0, 0, 0, 30, 0])
        other.joint([-20, 0, 0, 0, 30, 0])
        p.if_(then, other)
        plan = plan_program(program(p.task()))
        assert plan.diagnostics == ()
        (v,) = plan.tasks[0].variants
        assert np.allclose(v.trajectory.q[-1], np.radians([-20, 0, 0, 0, 30, 0]))


def test_same_program_gives_identical_arrays() -> None:
    """Determinism: planning twice gives byte-identical trajectories and records."""
    def build():  # type: ignore[no-untyped-def]
        p = Prog()
        p.joint(pose(300, -150, 300, **TOOL_DOWN))
        p.linear(pose(300, 100, 300, **TOOL_DOWN), zone=20)
        p.circular(pose(400, 150, 300, **TOOL_DOWN), pose(450, 100, 300, **TOOL_DOWN), zone=10)
        p.joint([0, 0, 0, 0, 30, 0])
        return plan_program(program(p.task()))

    a, b = build().tasks[0], build().tasks[0]
    for name in ("t", "q", "qd", "qdd"):
        assert getattr(a.trajectory, name).tobytes() == getattr(b.trajectory, name).tobytes()
    assert [(r.uid, r.t_start, r.t_end) for r in a.records] == [(r.uid, r.t_start, r.t_end) for r in b.records]


def test_samples_are_at_the_fixed_step_from_zero() -> None:
    """t = 0, step, 2 step, ... and the last sample covers the end of the motion."""
    p = Prog()
    p.joint([0, 0, 0, 0, 30, 0])
    p.joint([30, 0, 0, 0, 30, 0])
    plan = plan_program(program(p.task()), step=0.01)
    t = plan.tasks[0].trajectory.t
    assert t[0] == 0.0 and np.allclose(np.diff(t), 0.01)
    last = max(r.t_end for r in plan.tasks[0].records)
    assert t[-1] >= last > t[-1] - 0.01


def test_sync_in_a_lone_task_is_a_no_op_that_keeps_the_blend() -> None:
    """A one-task `sync` between blended moves neither stops the robot nor changes the timing."""
    def build(with_sync: bool):  # type: ignore[no-untyped-def]
        p = Prog()
        p.joint(pose(300, -150, 300, **TOOL_DOWN))
        a = p.linear(pose(300, 100, 300, **TOOL_DOWN), zone=20)
        s = p.sync("meet") if with_sync else None
        p.linear(pose(450, 100, 300, **TOOL_DOWN))
        return plan_program(program(p.task())).tasks[0], a, s

    plain, _, _ = build(False)
    tp, a, s = build(True)
    assert tp.trajectory.t[-1] == pytest.approx(plain.trajectory.t[-1], abs=1e-9)
    t = tp.record(s).t_start
    assert t == tp.record(s).t_end == tp.record(a).t_end
    i = int(np.argmin(np.abs(tp.trajectory.t - t)))
    assert np.max(np.abs(tp.trajectory.qd[i])) > 0.1  # still moving through the zone
