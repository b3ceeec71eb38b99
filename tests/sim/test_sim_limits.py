"""Joint position, velocity, acceleration and torque limits along a hand-made plan."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest
from simkit import arm3, cell, make_plan, source, task_plan

from rmot.lang import plan_types
from rmot.sim import codes
from rmot.sim.limits import check_limits, joint_torques
from rmot.sim.verification import verify_with


def _report(robot, waypoints, durations):
    file = source()
    c = cell([("r1", (0, 0, 0))])
    tp = task_plan("main", "r1", waypoints, durations, file)
    return verify_with(make_plan(c, [tp], file), robots={"r1": robot}), tp


def _codes(report, code):
    return [d for d in report.diagnostics if d.code.id == code.id]


def test_joint_limit_excess_at_the_right_move() -> None:
    """J2 driven past its 2 rad limit in move 2 (line 3): one E310 with the excess in degrees."""
    robot = arm3("r1")
    robot.joint_limits = np.tile([-2.0, 2.0], (3, 1))
    report, _ = _report(robot, [(0, 0, 0), (0, 1.0, 0), (0, 2.2, 0), (0, 1.0, 0)], [1.0, 1.0, 1.0])
    hits = _codes(report, codes.JOINT_POSITION)
    assert len(hits) == 1
    hit = hits[0]
    assert hit.span.start.line == 3 and hit.bodies == ("r1/joint2",)
    assert hit.amount.unit == "deg"
    assert hit.amount.value == pytest.approx(np.degrees(0.2), abs=0.01)
    assert "joint 2" in hit.message and "upper limit 114.6 deg" in hit.message


def test_velocity_excess_found_at_the_fast_move() -> None:
    """Only move 2 is too fast for a 1 rad/s joint: E311 at line 3 with the % excess."""
    robot = arm3("r1", vmax=1.0, amax=100)
    report, tp = _report(robot, [(0, 0, 0), (0.5, 0, 0), (2.0, 0, 0)], [1.0, 1.0])
    hits = _codes(report, codes.JOINT_VELOCITY)
    assert len(hits) == 1 and hits[0].span.start.line == 3
    peak = 1.875 * 1.5  # quintic: peak speed = 1.875 * distance / duration
    assert hits[0].amount.value == pytest.approx(np.degrees(peak - 1.0), rel=1e-3)
    assert f"by {round((peak - 1) * 100)}%" in hits[0].message
    rec = tp.records[1]
    assert rec.t_start <= hits[0].time_s <= hits[0].end_time_s <= rec.t_end


def test_acceleration_excess() -> None:
    """A short move exceeding 10 rad/s^2 gives one E312 per contiguous run."""
    robot = arm3("r1", vmax=100, amax=10.0)
    report, _ = _report(robot, [(0, 0, 0), (1.0, 0, 0)], [0.5])
    hits = _codes(report, codes.JOINT_ACCEL)
    # quintic acceleration peaks twice (speeding up, slowing down): two runs
    assert len(hits) == 2 and all(h.bodies == ("r1/joint1",) for h in hits)


def test_clean_plan_has_no_findings() -> None:
    """A slow move within all limits gives an empty report."""
    report, _ = _report(arm3("r1"), [(0, 0, 0), (0.5, 0.3, -0.2)], [2.0])
    assert report.diagnostics == ()
    assert report.cycle_time == pytest.approx(2.0)


def test_torque_matches_rnea_and_is_reported() -> None:
    """joint_torques equals pinocchio RNEA sample by sample; a low effort limit is exceeded."""
    robot = arm3("r1", effort=5.0)
    t = np.linspace(0, 1, 11)
    q = np.stack([np.zeros(11), np.linspace(0, 1.2, 11), np.zeros(11)], axis=1)
    traj = plan_types.Trajectory(t, q, np.zeros_like(q), np.zeros_like(q))
    tau = joint_torques(robot, traj)
    data = robot.model.createData()
    for k in (0, 5, 10):
        np.testing.assert_allclose(tau[k], pin.rnea(robot.model, data, q[k], np.zeros(3), np.zeros(3)))
    hits = [h for h in check_limits(robot, traj) if h.quantity == "torque"]
    assert hits and all(abs(h.value) > 5.0 for h in hits)


def test_payload_adds_gravity_torque() -> None:
    """A 2 kg payload 0.1 m out on the last joint of a horizontal arm adds its weight's moment."""
    robot = arm3("r1")
    q = np.array([[0.0, np.pi / 2, 0.0]])
    traj = plan_types.Trajectory(np.zeros(1), q, np.zeros_like(q), np.zeros_like(q))
    bare = joint_torques(robot, traj)[0]
    loaded = joint_torques(robot, traj, payload=2.0, payload_at=np.array([0, 0, 0.1]))[0]
    # the payload sits 0.5 + 0.1 m from J2's axis, horizontally: 2 kg * g * 0.6 m more at J2
    assert abs(loaded[1] - bare[1]) == pytest.approx(2.0 * 9.81 * 0.6, rel=1e-3)
