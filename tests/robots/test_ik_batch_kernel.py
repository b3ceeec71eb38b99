"""ik_batch's compiled pass (sim/robots/fastbatch.py, used for many poses per call) gives
the same joint values as its numpy path (`_nearest_in_limits` + `_verify_batch`) from the same
closed-form rows, NaN rows included, with and without seeds, on reachable, unreachable and
out-of-limits poses."""

from __future__ import annotations

import numpy as np
import pytest

from rmot.sim.robots import ik, load_robot


@pytest.mark.parametrize("name", ["abb_irb1600", "ur5e", "kuka_kr6_r900", "fanuc_m20ia"])
def test_compiled_pass_equals_the_numpy_path(name: str) -> None:
    robot = load_robot(name)
    rng = np.random.default_rng(7)
    lo, hi = robot.joint_limits[:, 0], robot.joint_limits[:, 1]
    q = rng.uniform(np.maximum(lo, -4.0), np.minimum(hi, 4.0), (300, robot.dof))
    poses = robot.fk_batch(q)
    poses[::17, :3, 3] += 5.0  # out of reach
    n = len(poses)
    assert n >= ik._BATCH_KERNEL_POSES
    raw = robot.ik_closed_form(poses)
    for seed in (None, q[0] + 0.3, q + rng.normal(0, 2.0, q.shape)):
        seeds = np.zeros_like(raw) if seed is None else np.broadcast_to(
            seed.reshape(-1, 1, robot.dof) if seed.ndim == 2 else seed, raw.shape)
        numpy_path = ik._verify_batch(robot, poses, ik._nearest_in_limits(robot, raw, seeds))
        seed_q = np.zeros(robot.dof) if seed is None else seed
        compiled = ik._nearest_verified_compiled(robot, poses, raw, seed_q)  # on the same raw
        np.testing.assert_allclose(robot.ik_batch(poses, seed=seed), compiled, rtol=0, atol=1e-12)
        assert np.array_equal(compiled, numpy_path, equal_nan=True)
        assert np.isfinite(compiled).any() and np.isnan(compiled[::17]).all()


@pytest.mark.parametrize("name", ["ur5e", "kuka_kr6_r900"])
def test_a_row_that_misses_its_pose_is_caught_in_any_block(name: str) -> None:
    """Rows of many poses share one FK block: a row moved off its pose (by 1e-6 rad, beyond the
    tolerance; or by 1e-3, beyond polishing) must be caught for its own pose and branch, as the
    numpy path catches it (polished back, or NaN), wherever it falls in a block."""
    robot = load_robot(name)
    rng = np.random.default_rng(11)
    lo, hi = robot.joint_limits[:, 0], robot.joint_limits[:, 1]
    q = rng.uniform(np.maximum(lo, -3.0), np.minimum(hi, 3.0), (200, robot.dof))
    poses = robot.fk_batch(q)
    raw = robot.ik_closed_form(poses)
    hit = [(i, b) for i in range(0, 200, 7) for b in range(8) if np.isfinite(raw[i, b]).all()][::3]
    assert len(hit) > 10
    for k, (i, b) in enumerate(hit):
        raw[i, b, k % robot.dof] += 1e-6 if k % 2 else 1e-3
    seeds = np.broadcast_to(q[0], raw.shape)
    numpy_path = ik._verify_batch(robot, poses, ik._nearest_in_limits(robot, raw, seeds))
    compiled = ik._nearest_verified_compiled(robot, poses, raw, q[0])
    assert np.array_equal(compiled, numpy_path, equal_nan=True)
    for k, (i, b) in enumerate(hit):
        row = compiled[i, b]
        if k % 2 == 0:
            assert np.isnan(row).all()  # 1e-3 off: beyond polishing, dropped
        elif np.isfinite(row).all():  # polished: it reaches the pose (pinocchio's FK)
            dp, dr = ik.pose_error(robot.fk(row), poses[i])
            assert dp <= ik.POS_TOL and dr <= ik.ROT_TOL
