"""Joint torque limits feed the timing: a heavy payload slows the motion rather than
exceeding the motors.

Witnesses, none of them rmot's timing code:
* the torques are recomputed here by pinocchio's RNEA along the sampled trajectory, the payload
  put on the model here, at the flange found from the robot's link solids
  (sim.scene.flange_in_last_joint, not the planner's torque module);
* toppra (not used by rmot) with its JointTorqueConstraint times the same joint-space line
  under the same joint velocity, acceleration and torque limits; rmot's duration must be
  within 2 % of it (toppra's collocation on its grid is itself approximate);
* the UR5e's rated joint torques are Universal Robots' "max joint torques" as published in
  ros-industrial universal_robot ur5e/joint_limits.yaml (max_effort 150, 150, 150, 28, 28, 28
  N·m), cited in sim/robots/library.py and checked here against those numbers.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest
from plan_helpers import Prog, pose, program
from rmot.lang import ir
from rmot.compiler.plan import plan_program, topp
from rmot.compiler.plan import torque as torque_mod
from rmot.sim.robots import load_robot
from rmot.sim.scene import flange_in_last_joint

ARM = "ur5e"
UR5E_MAX_EFFORT = (150.0, 150.0, 150.0, 28.0, 28.0, 28.0)  # ros-industrial ur5e joint_limits.yaml
START = [
    0.0,
    -160.0,
    0.0,
    -90.0,
    -90.0,
    0.0,
]  # deg: the arm stretched out, swung up through horizontal
END = [0.0, -20.0, 0.0, -90.0, -90.0, 0.0]
TCP_Z = 100.0  # mm
HEAVY = 8.0  # kg (UR5e rated 5 kg): gravity alone stays within the ratings, the swing does not


def _program(mass: float) -> ir.Program:
    p = Prog(tool=ir.ToolRef("t", pose(z=TCP_Z), mass))
    p.joint(START)
    p.joint(END, zone=0)
    return program(p.task(), robots={"r1": ARM})


def _payload_model(robot, mass: float):  # type: ignore[no-untyped-def]
    """The robot's model with `mass` at half the TCP (ir.payload_cog's convention, written out
    here) in the last joint's frame, by the solids-based flange of sim.scene."""
    model = pin.Model(robot.model)
    at = flange_in_last_joint(robot) @ np.array([0.0, 0.0, TCP_Z / 2e3, 1.0])
    model.inertias[robot.dof] = model.inertias[robot.dof] + pin.Inertia(
        mass, at[:3], np.zeros((3, 3))
    )
    return model


def _peak(robot, traj, mass: float) -> np.ndarray:  # type: ignore[no-untyped-def]
    model = _payload_model(robot, mass)
    data = model.createData()
    tau = np.array([pin.rnea(model, data, q, v, a) for q, v, a in zip(traj.q, traj.qd, traj.qdd)])
    return np.abs(tau).max(axis=0)


def _toppra_duration(robot, mass: float) -> float:  # type: ignore[no-untyped-def]
    import toppra
    import toppra.algorithm as algo
    from toppra import constraint

    toppra.setup_logging("CRITICAL")
    q0, q1 = np.radians(START), np.radians(END)
    length = float(np.linalg.norm(q1 - q0))
    ss = np.linspace(0.0, length, 5)
    path = toppra.SplineInterpolator(ss, q0 + (ss / length)[:, None] * (q1 - q0))
    model = _payload_model(robot, mass)
    data = model.createData()

    def inv_dyn(q: np.ndarray, v: np.ndarray, a: np.ndarray) -> np.ndarray:
        return np.asarray(pin.rnea(model, data, q, v, a))

    effort = np.array(UR5E_MAX_EFFORT)
    vlim, alim = robot.velocity_limits, robot.accel_limits
    cons = [
        constraint.JointVelocityConstraint(np.stack([-vlim, vlim], axis=1)),
        constraint.JointAccelerationConstraint(np.stack([-alim, alim], axis=1)),
        constraint.JointTorqueConstraint(inv_dyn, np.stack([-effort, effort], axis=1), np.zeros(6)),
    ]
    traj = algo.TOPPRA(cons, path, gridpoints=np.linspace(0.0, length, 1500)).compute_trajectory(
        0.0, 0.0
    )
    assert traj is not None
    return float(traj.duration)


def test_ur5e_ratings_are_the_cited_ones() -> None:
    robot = load_robot(ARM)
    assert np.allclose(np.asarray(robot.model.effortLimit)[:6], UR5E_MAX_EFFORT)


def test_heavy_payload_slows_the_move_and_stays_within_the_ratings(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    robot = load_robot(ARM)
    effort = np.array(UR5E_MAX_EFFORT)
    light, heavy = plan_program(_program(0.0)), plan_program(_program(HEAVY))
    assert not light.diagnostics and not heavy.diagnostics
    t_light, t_heavy = light.tasks[0].cycle_time, heavy.tasks[0].cycle_time
    # without the payload the motors are far from their ratings: the plain timing stands
    assert np.all(_peak(robot, light.tasks[0].trajectory, 0.0) < 0.6 * effort)
    # with it, the plain timing would need more than J2's rating...
    monkeypatch.setattr(torque_mod, "torque_limits", lambda *a, **k: None)
    unlimited = plan_program(_program(HEAVY)).tasks[0]
    monkeypatch.undo()
    assert unlimited.cycle_time == pytest.approx(t_light, abs=1e-9)
    assert _peak(robot, unlimited.trajectory, HEAVY)[1] > 1.1 * effort[1]
    # ...so the timing slows the move until the motors suffice
    assert t_heavy > 1.2 * t_light
    peak = _peak(robot, heavy.tasks[0].trajectory, HEAVY)
    assert np.all(peak <= effort * (1 + 1e-3)), peak / effort
    assert peak[1] > 0.99 * effort[1]  # and not slower than it needs: J2 runs at its rating


def test_toppra_torque_constraint_agrees() -> None:
    robot = load_robot(ARM)
    plan = plan_program(_program(HEAVY))
    ours = plan.tasks[0].cycle_time
    ref = _toppra_duration(robot, HEAVY)
    assert abs(ours - ref) <= 0.02 * ref, (ours, ref)


def test_without_binding_torque_the_plan_is_unchanged(monkeypatch: pytest.MonkeyPatch) -> None:
    """A payload the motors manage: the plan is the same, to the bit, as with no torque limits."""
    with_limits = plan_program(_program(2.0)).tasks[0].trajectory
    monkeypatch.setattr(torque_mod, "torque_limits", lambda *a, **k: None)
    without = plan_program(_program(2.0)).tasks[0].trajectory
    assert np.array_equal(with_limits.q, without.q) and np.array_equal(with_limits.t, without.t)


def test_symmetric_rows_given_one_sided_solve_identically() -> None:
    """lo = -c, hi = c as one-sided rows gives the symmetric rows' solution bit for bit."""
    rng = np.random.default_rng(3)
    k, m = 400, 5
    a, b = rng.normal(size=(k, m)), rng.normal(size=(k, m))
    c = rng.uniform(0.5, 2.0, size=(k, m))
    ss = np.cumsum(rng.uniform(0.001, 0.01, size=k))
    xmax = rng.uniform(1.0, 5.0, size=k)
    sym = topp.solve(ss, xmax, topp.Rows(a, b, c))
    one = topp.solve(ss, xmax, topp.Rows(a, b, c, -c))
    assert np.array_equal(sym, one)


@pytest.mark.parametrize(
    "arm", ["ur5e", "abb_irb1600", "fanuc_m20ia", "kuka_kr210", "staubli_tx2_60"]
)
def test_vectorised_rnea_equals_pinocchio(arm: str) -> None:
    """compiler/plan/rnea.py against pinocchio.rnea, one call per sample, with a payload."""
    from rmot.compiler.plan.rnea import Dynamics

    robot = load_robot(arm)
    model = _payload_model(robot, 5.0)
    rng = np.random.default_rng(7)
    q, qd, qdd = (rng.uniform(-2.0, 2.0, (200, robot.dof)) for _ in range(3))
    dyn = Dynamics(model)
    assert dyn.supported
    data = model.createData()
    ref = np.array([pin.rnea(model, data, *x) for x in zip(q, qd, qdd)])
    np.testing.assert_allclose(dyn.rnea(q, qd, qdd), ref, rtol=1e-10, atol=1e-9)


def test_vectorised_rnea_prismatic_and_unaligned_joints() -> None:
    """A prismatic joint and joints about unaligned axes (built here in pinocchio directly)."""
    from rmot.compiler.plan.rnea import Dynamics

    model = pin.Model()
    parent = 0
    joints = [
        pin.JointModelRZ(),
        pin.JointModelPX(),
        pin.JointModelRevoluteUnaligned(np.array([0.48, 0.6, 0.64])),
        pin.JointModelPrismaticUnaligned(np.array([0.0, 0.6, 0.8])),
        pin.JointModelRY(),
    ]
    rng = np.random.default_rng(2)
    for k, joint in enumerate(joints):
        place = pin.SE3(pin.exp3(rng.normal(size=3)), rng.normal(size=3) * 0.3)
        parent = model.addJoint(parent, joint, place, f"j{k}")
        model.appendBodyToJoint(parent, pin.Inertia.Random(), pin.SE3.Identity())
    dyn = Dynamics(model)
    assert dyn.supported
    q, qd, qdd = (rng.uniform(-1.0, 1.0, (50, 5)) for _ in range(3))
    data = model.createData()
    ref = np.array([pin.rnea(model, data, *x) for x in zip(q, qd, qdd)])
    np.testing.assert_allclose(dyn.rnea(q, qd, qdd), ref, rtol=1e-10, atol=1e-9)
    # an axis that is not a unit vector, or a joint type it does not follow: left to pinocchio
    odd = pin.Model()
    j = odd.addJoint(
        0, pin.JointModelRevoluteUnaligned(np.array([0.3, 0.5, 0.8])), pin.SE3.Identity(), "j"
    )
    odd.appendBodyToJoint(j, pin.Inertia.Random(), pin.SE3.Identity())
    fallback = Dynamics(odd)
    assert not fallback.supported
    d2 = odd.createData()
    np.testing.assert_allclose(
        fallback.rnea(q[:, :1], qd[:, :1], qdd[:, :1]),
        np.array([pin.rnea(odd, d2, *x) for x in zip(q[:, :1], qd[:, :1], qdd[:, :1])]),
    )
