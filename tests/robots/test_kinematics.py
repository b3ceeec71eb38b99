"""FK, Jacobian, batch paths, singularity measures and branch stability of the library."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rmot.lang import ir
from rmot.sim.robots import list_robots, load_robot
from rmot.sim.robots.library import SPECS
from rmot.sim.robots.opw import opw_shoulder_elbow


def random_q(robot, n: int, seed: int = 0) -> np.ndarray:
    return np.random.default_rng(seed).uniform(robot.joint_limits[:, 0], robot.joint_limits[:, 1], (n, robot.dof))


def rotation_vector(r: np.ndarray) -> np.ndarray:
    angle = math.acos(max(-1.0, min(1.0, (np.trace(r) - 1) / 2)))
    v = np.array([r[2, 1] - r[1, 2], r[0, 2] - r[2, 0], r[1, 0] - r[0, 1]]) / 2
    return v if angle < 1e-12 else v * angle / math.sin(angle)


def sigma_min(robot, q: np.ndarray) -> float:
    j = robot.jacobian(q).copy()
    j[3:] *= robot.reach
    return float(np.linalg.svd(j, compute_uv=False)[-1])


@pytest.mark.parametrize("name", list_robots())
def test_jacobian_matches_central_differences(name):
    """Each Jacobian column equals the central difference of the flange pose (1e-7)."""
    r = load_robot(name)
    h = 1e-6
    for q in random_q(r, 5, seed=4):
        jac = r.jacobian(q)
        for i in range(r.dof):
            dq = np.zeros(r.dof)
            dq[i] = h
            plus, minus = r.fk(q + dq), r.fk(q - dq)
            linear = (plus[:3, 3] - minus[:3, 3]) / (2 * h)
            angular = rotation_vector(plus[:3, :3] @ minus[:3, :3].T) / (2 * h)
            np.testing.assert_allclose(jac[:3, i], linear, atol=1e-7)
            np.testing.assert_allclose(jac[3:, i], angular, atol=1e-7)


@pytest.mark.parametrize("name", list_robots())
def test_batch_paths_equal_single_calls(name):
    """fk_batch and solid_poses_batch equal fk and solid_poses per configuration."""
    r = load_robot(name)
    qs = random_q(r, 20, seed=5)
    np.testing.assert_allclose(r.fk_batch(qs), np.array([r.fk(q) for q in qs]), atol=1e-13)
    np.testing.assert_allclose(r.solid_poses_batch(qs), np.array([r.solid_poses(q) for q in qs]), atol=1e-13)
    np.testing.assert_allclose(r._chain.joint_frames(r.to_model(qs)), r._chain.joint_frames_numpy(r.to_model(qs)), atol=1e-13)


def test_fk_rejects_a_wrong_joint_count():
    """fk with 5 values for a 6-axis arm is a ValueError naming the expected shape."""
    with pytest.raises(ValueError, match=r"shape \(6,\)"):
        load_robot("abb_irb120").fk(np.zeros(5))


def test_manipulability_and_condition_flag_singularities():
    """At J5 = 0 manipulability vanishes and the condition number explodes; not elsewhere."""
    r = load_robot("abb_irb1600")
    singular, regular = np.radians([0, 10, 20, 0, 0, 0]), np.radians([0, 10, 20, 0, 40, 0])
    assert r.manipulability(singular) < 1e-12 < 1e-3 < r.manipulability(regular)
    assert r.condition(singular) > 1e12 and r.condition(regular) < 100


def flips_along(robot, q0: np.ndarray, joint: int, steps: int = 721) -> list[tuple[np.ndarray, np.ndarray]]:
    """Consecutive sweep samples (a, b) of one joint whose branch names differ."""
    lo, hi = robot.joint_limits[joint]
    samples = np.repeat(q0[None], steps, axis=0)
    samples[:, joint] = np.linspace(lo, hi, steps)
    names = [robot.branch(q) for q in samples]
    return [(samples[i], samples[i + 1]) for i in range(steps - 1) if names[i] != names[i + 1]]


def crossing(robot, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Bisect to the point where the branch name changes."""
    name_a = robot.branch(a)
    for _ in range(50):
        mid = (a + b) / 2
        a, b = (mid, b) if robot.branch(mid) == name_a else (a, mid)
    return (a + b) / 2


@pytest.mark.parametrize("name", list_robots())
def test_branch_names_change_only_at_singularities(name):
    """Sweeping each joint over its whole range, the branch name changes only where the arm is
    singular (smallest reach-scaled singular value < 1e-6): no flicker anywhere else."""
    r = load_robot(name)
    for q0 in random_q(r, 2, seed=9):
        for joint in range(r.dof):
            for a, b in flips_along(r, q0, joint):
                assert sigma_min(r, crossing(r, a, b)) < 1e-6, (joint, np.degrees(a))


@pytest.mark.parametrize("name", [n for n in list_robots() if SPECS[n].opw is not None])
def test_opw_branch_names_follow_the_documented_quantities(name):
    """shoulder = sign of the wrist centre ahead of J1, elbow = sign of sin(θ3+ψ3), wrist = sign of sin J5."""
    r = load_robot(name)
    params, jmap = SPECS[name].opw
    qs = random_q(r, 300, seed=10)
    front, up = opw_shoulder_elbow(params, jmap.to_theta(qs))
    for q, f, u in zip(qs, front, up):
        b = r.branch(q)
        assert (b.shoulder is ir.Shoulder.FRONT) == (f >= 0)
        assert (b.elbow is ir.Elbow.UP) == (u >= 0)
        assert (b.wrist is ir.Wrist.FLIP) == (math.sin(q[4]) < 0)


def test_vendor_home_poses_are_front_up():
    """ABB zero, KUKA HOME, Fanuc zero and UR (0,-90,90,-90,-90,0) are shoulder front, elbow up."""
    cases = [("abb_irb120", (0, 0, 0, 0, 30, 0)), ("kuka_kr6_r900", (0, -90, 90, 0, 30, 0)),
             ("fanuc_lrmate200id", (0, 0, 0, 0, -30, 0)), ("ur5e", (0, -90, 90, -90, -90, 0))]
    for name, q in cases:
        b = load_robot(name).branch(np.radians(q))
        assert (b.shoulder, b.elbow) == (ir.Shoulder.FRONT, ir.Elbow.UP), name
