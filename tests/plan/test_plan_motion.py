"""Planned motion against independent computations: paths, limits, durations, speeds, blends."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rmot.lang import ir
from rmot.compiler.plan import plan_program
from rmot.lang.diagnostics import Severity

from plan_helpers import Prog, pose, program, tcp_positions
from test_plan_timing import trapezoid_time

TOOL_DOWN = dict(rx=180, ry=0, rz=180)  # tool pointing down, a usual work orientation


def _line_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    d = (b - a) / np.linalg.norm(b - a)
    rel = p - a
    return np.linalg.norm(rel - (rel @ d)[:, None] * d, axis=1)


def _window(tp, rec):  # type: ignore[no-untyped-def]
    t = tp.trajectory.t
    return (t >= rec.t_start) & (t <= rec.t_end)


def _errors(plan):  # type: ignore[no-untyped-def]
    return [d for d in plan.diagnostics if d.severity is Severity.ERROR]


@pytest.fixture(scope="module")
def line_plan():  # type: ignore[no-untyped-def]
    p = Prog()
    p.joint(pose(300, -200, 300, **TOOL_DOWN))
    uid = p.linear(pose(300, 200, 350, **TOOL_DOWN), speed=200)
    p.linear(pose(420, 150, 250, **TOOL_DOWN), speed=500)
    return plan_program(program(p.task())), uid


class TestLinear:
    def test_tcp_stays_on_the_line_at_and_between_samples(self, line_plan, irb120) -> None:  # type: ignore[no-untyped-def]
        """Every sample and every midpoint of consecutive samples is within 0.1 mm of the line."""
        plan, uid = line_plan
        tp = plan.tasks[0]
        q = tp.trajectory.q[_window(tp, tp.record(uid))]
        mids = 0.5 * (q[1:] + q[:-1])
        a, b = np.array([0.3, -0.2, 0.3]), np.array([0.3, 0.2, 0.35])
        for qs in (q, mids):
            assert np.max(_line_distance(tcp_positions(irb120, qs), a, b)) < 1e-4

    def test_orientation_is_slerped(self, line_plan, irb120) -> None:  # type: ignore[no-untyped-def]
        """Start and end orientation equal: the tool keeps pointing down all along."""
        plan, uid = line_plan
        tp = plan.tasks[0]
        q = tp.trajectory.q[_window(tp, tp.record(uid))]
        z_axis = irb120.fk_batch(q)[:, :3, 2]
        assert np.allclose(z_axis, [0, 0, -1], atol=1e-4)

    def test_tcp_speed_is_the_programmed_speed_away_from_the_ends(self, line_plan, irb120) -> None:  # type: ignore[no-untyped-def]
        """200 mm/s within 1% in the middle 60% of a 403 mm line."""
        plan, uid = line_plan
        tp = plan.tasks[0]
        rec = tp.record(uid)
        t = tp.trajectory.t
        mid = (t > rec.t_start + 0.2 * (rec.t_end - rec.t_start)) & (t < rec.t_end - 0.2 * (rec.t_end - rec.t_start))
        p = tcp_positions(irb120, tp.trajectory.q[mid])
        speed = np.linalg.norm(np.diff(p, axis=0), axis=1) / plan.step
        assert np.allclose(speed, 0.2, rtol=0.01)

    def test_record_holds_target_joints_branch_and_poses(self, line_plan, irb120) -> None:  # type: ignore[no-untyped-def]
        """q_target reaches the programmed TCP pose; the branch is the start's (no flip)."""
        plan, uid = line_plan
        rec = plan.tasks[0].record(uid)
        assert np.allclose(irb120.fk(rec.q_target)[:3, 3], [0.3, 0.2, 0.35], atol=1e-9)
        assert rec.branch == irb120.branch(plan.tasks[0].trajectory.q[0])
        assert np.allclose(rec.flange_pose.matrix(), irb120.fk(rec.q_target))


def test_limits_hold_at_every_sample(line_plan, irb120) -> None:  # type: ignore[no-untyped-def]
    """|qd| <= vmax (1+1e-6) and |qdd| <= amax (1+1e-3) at every output sample."""
    tr = line_plan[0].tasks[0].trajectory
    assert np.all(np.abs(tr.qd) <= irb120.velocity_limits * (1 + 1e-6))
    assert np.all(np.abs(tr.qdd) <= irb120.accel_limits * (1 + 1e-3))


def test_velocity_is_the_derivative_of_position(line_plan) -> None:  # type: ignore[no-untyped-def]
    """qd matches the central difference of q (consistent samples)."""
    tr = line_plan[0].tasks[0].trajectory
    diff = (tr.q[2:] - tr.q[:-2]) / (2 * line_plan[0].step)
    assert np.max(np.abs(diff - tr.qd[1:-1])) < 0.05


def test_single_joint_move_takes_the_analytic_time(irb120) -> None:  # type: ignore[no-untyped-def]
    """Joint 1 turning 90 deg at 50% speed: the trapezoid time within 1%."""
    p = Prog()
    p.joint([0, 0, 0, 0, 30, 0])
    uid = p.joint([90, 0, 0, 0, 30, 0], joint_speed=0.5)
    plan = plan_program(program(p.task()))
    rec = plan.tasks[0].record(uid)
    v, a = irb120.velocity_limits[0] * 0.5, irb120.accel_limits[0]
    expected = trapezoid_time(np.pi / 2, v, a)
    assert rec.t_end - rec.t_start == pytest.approx(expected, rel=0.01)
    assert np.max(np.abs(plan.tasks[0].trajectory.qd[:, 0])) == pytest.approx(v, rel=1e-6)


class TestCircular:
    def test_tcp_on_the_arc_and_via_solution_recorded(self, irb120) -> None:  # type: ignore[no-untyped-def]
        """The TCP stays within 0.1 mm of the circle; q_via reaches the via point."""
        p = Prog()
        p.joint(pose(350, -100, 300, **TOOL_DOWN))
        uid = p.circular(pose(450, 0, 300, **TOOL_DOWN), pose(350, 100, 300, **TOOL_DOWN), speed=150)
        plan = plan_program(program(p.task()))
        assert not _errors(plan)
        tp = plan.tasks[0]
        q = tp.trajectory.q[_window(tp, tp.record(uid))]
        for qs in (q, 0.5 * (q[1:] + q[:-1])):
            pts = tcp_positions(irb120, qs)
            r = np.linalg.norm(pts - [0.35, 0, 0.3], axis=1)
            assert np.max(np.abs(r - 0.1)) < 1e-4 and np.max(np.abs(pts[:, 2] - 0.3)) < 1e-4
        assert np.allclose(irb120.fk(tp.record(uid).q_via)[:3, 3], [0.45, 0, 0.3], atol=2e-3)


class TestZones:
    def _plan(self, zone: float):  # type: ignore[no-untyped-def]
        p = Prog()
        p.joint(pose(300, -150, 300, **TOOL_DOWN))
        a = p.linear(pose(300, 100, 300, **TOOL_DOWN), zone=zone)
        b = p.linear(pose(450, 100, 300, **TOOL_DOWN), zone=zone)
        p.linear(pose(450, 100, 400, **TOOL_DOWN))
        return plan_program(program(p.task())), a, b

    def test_blend_stays_in_the_zone_sphere_and_off_the_corner(self, irb120) -> None:  # type: ignore[no-untyped-def]
        """Outside the 20 mm sphere the TCP is on one of the lines; it never touches the corner."""
        plan, a, _ = self._plan(20)
        tp = plan.tasks[0]
        assert tp.record(a).blend_radius == pytest.approx(0.02)
        pts = tcp_positions(irb120, tp.trajectory.q)
        corner = np.array([0.3, 0.1, 0.3])
        near = np.linalg.norm(pts - corner, axis=1)
        on_a = _line_distance(pts, np.array([0.3, -0.15, 0.3]), corner) < 1e-4
        on_b = _line_distance(pts, corner, np.array([0.45, 0.1, 0.3])) < 1e-4
        in_plane = np.abs(pts[:, 2] - 0.3) < 1e-4
        window = in_plane & (np.arange(len(pts)) < np.argmax(pts[:, 2] > 0.3001))
        assert np.all((on_a | on_b | (near <= 0.02 + 1e-9))[window])
        assert np.min(near) > 1e-3  # the corner itself is cut

    def test_blend_is_never_more_than_half_the_shorter_segment(self) -> None:
        """A 200 mm zone between 250 mm and 150 mm segments is cut to 75 mm."""
        plan, a, b = self._plan(200)
        assert plan.tasks[0].record(a).blend_radius == pytest.approx(0.075)
        assert plan.tasks[0].record(b).blend_radius == pytest.approx(0.05)

    def test_fine_is_an_exact_stop(self, irb120) -> None:  # type: ignore[no-untyped-def]
        """With zone fine the robot passes the corner exactly and stops there."""
        plan, a, _ = self._plan(0)
        tp = plan.tasks[0]
        rec = tp.record(a)
        assert rec.blend_radius == 0.0
        i = int(np.argmin(np.abs(tp.trajectory.t - rec.t_end)))
        assert np.allclose(tcp_positions(irb120, tp.trajectory.q[[i]])[0], [0.3, 0.1, 0.3], atol=1e-4)
        assert np.max(np.abs(tp.trajectory.qd[i])) < 0.05

    def test_blending_saves_time(self) -> None:
        """A blended corner is faster than two exact stops."""
        assert self._plan(20)[0].cycle_time < self._plan(0)[0].cycle_time


def test_time_modifier_fixes_the_duration() -> None:
    """`time 3 s` makes the move last 3 s; `time 0.05 s` is too short: E227 at that move."""
    p = Prog()
    p.joint([0, 0, 0, 0, 30, 0])
    slow = p.joint([40, 0, 0, 0, 30, 0], duration=3.0)
    fast = p.linear(pose(300, 0, 300, **TOOL_DOWN), duration=0.05)
    plan = plan_program(program(p.task()))
    rec = plan.tasks[0].record(slow)
    assert rec.t_end - rec.t_start == pytest.approx(3.0)
    errs = _errors(plan)
    assert [(d.code.id, d.span.start.line) for d in errs] == [("E227", fast)]


def test_urdf_arm_without_closed_form_follows_the_line() -> None:
    """A URDF UR5 (numeric IK, Newton steps from the previous point): TCP on the line, limits kept."""
    from pathlib import Path

    from rmot.sim.robots import load_robot

    urdf = str(Path(np.__file__).parents[1] / "cmeel.prefix/share/example-robot-data/robots/ur_description/urdf/ur5_robot.urdf")
    robot = load_robot(urdf)
    assert not robot.has_closed_form
    start = robot.fk(np.radians([0, -60, 60, -90, -90, 0]))
    end = start.copy()
    end[:3, 3] += [0.0, 0.1, -0.1]
    p = Prog()
    p.joint([0, -60, 60, -90, -90, 0])
    uid = p.linear(ir.Pose.from_matrix(end), speed=100)
    cell = ir.Cell("c", (ir.RobotInstance("r1", ir.RobotSource(ir.RobotSourceKind.URDF, urdf), ir.Pose(), 6),))
    plan = plan_program(ir.Program("t", cell, (p.task(),)))
    assert plan.diagnostics == ()
    tp = plan.tasks[0]
    q = tp.trajectory.q[_window(tp, tp.record(uid))]
    for qs in (q, 0.5 * (q[1:] + q[:-1])):
        assert np.max(_line_distance(tcp_positions(robot, qs), start[:3, 3], end[:3, 3])) < 1e-4
    assert np.all(np.abs(tp.trajectory.qd) <= robot.velocity_limits * (1 + 1e-6))


@settings(max_examples=12, deadline=None, derandomize=True)
@given(st.tuples(st.floats(220, 420), st.floats(-250, 250), st.floats(150, 450)),
       st.tuples(st.floats(220, 420), st.floats(-250, 250), st.floats(150, 450)),
       st.floats(50, 800), st.sampled_from([0.0, 5.0, 30.0]))
def test_any_line_is_followed_or_reported(a, b, speed, zone) -> None:  # type: ignore[no-untyped-def]
    """Property: random lines either plan cleanly on the line within the limits, or get an E2xx
    diagnostic at a move; never an exception."""
    from rmot.sim.robots import load_robot

    robot = load_robot("abb_irb120")
    p = Prog()
    p.joint(pose(*a, **TOOL_DOWN))
    uid = p.linear(pose(*b, **TOOL_DOWN), speed=speed, zone=zone)
    p.linear(pose(*a, **TOOL_DOWN), speed=speed)
    plan = plan_program(program(p.task()))
    errors = _errors(plan)
    assert all(d.code.id.startswith("E2") and d.span is not None for d in errors)
    tr = plan.tasks[0].trajectory
    assert np.all(np.abs(tr.qd) <= robot.velocity_limits * (1 + 1e-6))
    assert np.all(np.abs(tr.qdd) <= robot.accel_limits * (1 + 1e-3))
    if errors or np.linalg.norm(np.subtract(a, b)) < 1:
        return
    tp = plan.tasks[0]
    rec = tp.record(uid)
    t = tp.trajectory.t
    q = tr.q[(t >= tp.record(uid).t_start) & (t <= rec.t_end)]
    pa, pb = np.array(a) / 1e3, np.array(b) / 1e3
    assert np.max(_line_distance(tcp_positions(robot, q), pa, pb)) < 1e-4


def test_linear_move_to_joint_values_ends_exactly_there(irb120) -> None:  # type: ignore[no-untyped-def]
    """`move linear joints(...)`: the TCP goes straight to FK(joints) and ends on those joints."""
    p = Prog()
    p.joint([0, 10, 10, 0, 40, 0])
    uid = p.linear([20, 20, 0, 10, 50, -10])
    plan = plan_program(program(p.task()))
    assert plan.diagnostics == ()
    rec = plan.tasks[0].record(uid)
    assert np.allclose(rec.q_target, np.radians([20, 20, 0, 10, 50, -10]), atol=1e-9)
    assert np.allclose(plan.tasks[0].trajectory.q[-1], rec.q_target, atol=1e-9)


def test_joint_speed_share_applies_to_the_joint_move_only(irb120) -> None:  # type: ignore[no-untyped-def]
    """A 5% joint move blended into a linear move: the joint move keeps 5% of vmax, the line
    still runs at its programmed 250 mm/s."""
    p = Prog()
    p.joint([0, 10, 10, 0, 60, 0])
    j = p.joint(pose(300, -150, 300, **TOOL_DOWN), joint_speed=0.05, zone=10)
    lin = p.linear(pose(300, 150, 300, **TOOL_DOWN), speed=250)
    plan = plan_program(program(p.task()))
    assert not _errors(plan)
    tp = plan.tasks[0]
    t = tp.trajectory.t
    during_joint = (t >= tp.record(j).t_start) & (t <= tp.record(j).t_end)
    assert np.all(np.abs(tp.trajectory.qd[during_joint]) <= 0.05 * irb120.velocity_limits * (1 + 1e-6))
    rec = tp.record(lin)
    mid = (t > rec.t_start + 0.3 * (rec.t_end - rec.t_start)) & (t < rec.t_end - 0.3 * (rec.t_end - rec.t_start))
    speed = np.linalg.norm(np.diff(tcp_positions(irb120, tp.trajectory.q[mid]), axis=0), axis=1) / plan.step
    assert np.allclose(speed, 0.25, rtol=0.01)
