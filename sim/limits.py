"""Joint limits along a trajectory: position, velocity, acceleration, and torque by inverse
dynamics (pinocchio's RNEA) where the robot model has inertias.

One LimitHit per joint, quantity and contiguous run of samples over the limit, carrying the
worst value of the run.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from rmot.lang import plan_types
from rmot.lang.record import record

__all__ = ["LimitHit", "check_limits", "joint_torques"]

# Relative slack before a value counts as over its limit: planners hit limits exactly, and
# accelerations come from finite differences.
_SLACK = {"position": 1e-6, "velocity": 1e-4, "acceleration": 1e-3, "torque": 1e-3}


@record
class LimitHit:
    quantity: str  # "position" | "velocity" | "acceleration" | "torque"
    joint: int  # 1-based, as on the pendant
    t0: float
    t1: float
    value: float  # the worst value of the run (signed), SI
    limit: float  # the bound it exceeds (signed for position: the violated end), SI
    prismatic: bool


def check_limits(robot: Any, traj: plan_types.Trajectory, payload: float = 0.0,
                 payload_at: np.ndarray | None = None) -> list[LimitHit]:
    """Every run of samples over a limit. payload: kg at `payload_at` (3,) in the last joint's frame."""
    hits: list[LimitHit] = []
    prismatic = np.array([t == "P" for t in robot.joint_types], dtype=bool)
    lo, hi = robot.joint_limits[:, 0], robot.joint_limits[:, 1]
    span = np.maximum(hi - lo, 1e-9)
    over_hi = traj.q - hi > _SLACK["position"] * span
    over_lo = lo - traj.q > _SLACK["position"] * span
    hits += _runs("position", traj, traj.q, over_hi, np.broadcast_to(hi, traj.q.shape), prismatic)
    hits += _runs("position", traj, traj.q, over_lo, np.broadcast_to(lo, traj.q.shape), prismatic)
    for quantity, values, bound in (
        ("velocity", traj.qd, robot.velocity_limits),
        ("acceleration", traj.qdd, robot.accel_limits),
    ):
        over = np.abs(values) > bound * (1 + _SLACK[quantity])
        hits += _runs(quantity, traj, values, over, np.broadcast_to(bound, values.shape), prismatic)
    if getattr(robot, "has_inertia", False):
        effort = np.asarray(robot.model.effortLimit, dtype=float)[: robot.dof]
        if np.all(np.isfinite(effort)) and np.all(effort > 0):
            tau = joint_torques(robot, traj, payload, payload_at)
            over = np.abs(tau) > effort * (1 + _SLACK["torque"])
            hits += _runs("torque", traj, tau, over, np.broadcast_to(effort, tau.shape), prismatic)
    return sorted(hits, key=lambda h: (h.t0, h.joint, h.quantity))


def joint_torques(robot: Any, traj: plan_types.Trajectory, payload: float = 0.0,
                  payload_at: np.ndarray | None = None) -> np.ndarray:
    """(N, dof) N·m (N for prismatic) by RNEA; the payload is a point mass on the last joint.
    Controller joint values go through robot.to_model (a linear map, Fanuc's J2/J3 coupling)
    when the robot has one; the torques are those of the model's joints."""
    import pinocchio as pin  # late: pinocchio is heavy or optional, loaded only where used

    model = pin.Model(robot.model)  # a copy: the payload must not leak into the shared model
    if payload > 0:
        at = np.zeros(3) if payload_at is None else np.asarray(payload_at, dtype=float)
        model.inertias[robot.dof] = model.inertias[robot.dof] + pin.Inertia(payload, at, np.zeros((3, 3)))
    data = model.createData()
    to_model = getattr(robot, "to_model", lambda v: v)
    q, qd, qdd = (np.asarray(to_model(np.asarray(v)), dtype=float) for v in (traj.q, traj.qd, traj.qdd))
    out = np.empty_like(q)
    for k in range(q.shape[0]):
        out[k] = pin.rnea(model, data, q[k], qd[k], qdd[k])[: robot.dof]
    return out


def _runs(quantity: str, traj: plan_types.Trajectory, values: np.ndarray, over: np.ndarray,
          bounds: np.ndarray, prismatic: np.ndarray) -> list[LimitHit]:
    hits = []
    for j in np.nonzero(over.any(axis=0))[0]:
        flags = np.concatenate([[False], over[:, j], [False]])
        edges = np.flatnonzero(np.diff(flags.astype(np.int8)))
        for start, stop in zip(edges[::2], edges[1::2], strict=True):
            seg = slice(start, stop)
            excess = np.abs(values[seg, j]) - np.abs(bounds[seg, j]) if quantity != "position" else np.abs(values[seg, j] - bounds[seg, j])
            worst = start + int(np.argmax(excess))
            hits.append(LimitHit(quantity, int(j) + 1, float(traj.t[start]), float(traj.t[stop - 1]),
                                 float(values[worst, j]), float(bounds[worst, j]), bool(prismatic[j])))
    return hits
