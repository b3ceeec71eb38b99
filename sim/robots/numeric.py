"""Numeric IK: damped least squares on pinocchio, with seeded restarts.

Newton steps on the flange error log6(T(q)⁻¹·T*) in the flange frame, damped by λ² (small:
far from singularities it is plain Newton, quadratic near the solution), steps capped at
0.5 rad so a step near a singularity cannot throw q far away. Deterministic: restart seeds
come from a fixed-seed generator.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

__all__ = ["dls", "dls_fast", "restart_seeds"]

_DAMPING2 = 1e-12
_MAX_STEP = 0.5


def dls(robot, target: np.ndarray, q0: np.ndarray, tol: float = 1e-11, max_iter: int = 50) -> tuple[np.ndarray, float]:  # type: ignore[no-untyped-def]
    """One DLS run from q0 (controller values) -> (q, final error norm)."""
    model, data, fid = robot.model, robot._data, robot._fid
    joint, placement = robot._flange_joint, robot.model.frames[fid].placement
    coupling = robot._coupling
    goal = pin.SE3(target[:3, :3].copy(), target[:3, 3].copy())
    q = np.array(q0, dtype=float)
    eye = np.eye(6) * _DAMPING2
    err_norm = np.inf
    for _ in range(max_iter):
        qm = q if coupling is None else coupling @ q
        pin.computeJointJacobians(model, data, qm)  # FK too (computeFrameJacobian leaves oMi stale)
        jac = pin.getFrameJacobian(model, data, fid, pin.LOCAL)
        err = pin.log6((data.oMi[joint] * placement).actInv(goal)).vector
        err_norm = float(np.sqrt(err @ err))
        if err_norm < tol:
            break
        if coupling is not None:
            jac = jac @ coupling
        step = jac.T @ np.linalg.solve(jac @ jac.T + eye, err)
        size = float(np.max(np.abs(step)))
        q += step if size <= _MAX_STEP else step * (_MAX_STEP / size)
    return q, err_norm


def dls_fast(robot, target: np.ndarray, q0: np.ndarray, tol: float = 1e-11, max_iter: int = 60) -> tuple[np.ndarray, float]:  # type: ignore[no-untyped-def]
    """The same iteration compiled over the chain arrays (see `fastdls`)."""
    from rmot.sim.robots.fastdls import DLS_CHAIN  # late: loads subprocess only when this runs

    args = robot._dls_args
    if args is None:
        chain = robot._chain
        coupling = np.eye(robot.dof) if robot._coupling is None else np.array(robot._coupling)
        args = (chain.placements, chain.axes, chain.prismatic, np.array(robot._flange_in_joint), coupling)
        robot._dls_args = args
    q, err = DLS_CHAIN(max_iter, *args, np.asarray(target, dtype=float), np.array(q0, dtype=float),
                       tol, max_iter, _DAMPING2, _MAX_STEP)
    return q, float(err)


def restart_seeds(limits: np.ndarray, count: int, seed: int = 0) -> np.ndarray:
    """count deterministic seeds uniform within the limits (clipped to ±π for long ranges)."""
    lo, hi = np.maximum(limits[:, 0], -np.pi), np.minimum(limits[:, 1], np.pi)
    return np.random.default_rng(seed).uniform(lo, hi, size=(count, len(lo)))
