"""Figures of merit of a planned, verified program, per task: what `rmot compare` and
`rmot place` rank by.

- joint-limit margin: the smallest distance of any joint from either end of its range over
  the whole trajectory (rad or m), and which joint;
- manipulability: the smallest Yoshikawa measure sqrt(det(J Jᵀ)) over the trajectory, of the
  Jacobian with its linear rows divided by the robot's reach (dimensionless, so arms of
  different size compare; 0 = singular);
- dynamics (where the model has inertias): per joint peak and RMS torque by inverse dynamics
  (pinocchio's RNEA, the payload as in verification) and peak mechanical power |τ·q̇|,
  against the model's rated torque (effortLimit) where it has one.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from rmot.lang import ir, plan_types
from rmot.lang.record import record
from rmot.sim.report import Report
from dataclasses import replace

__all__ = ["JointDynamics", "TaskMetrics", "dynamics", "task_metrics", "program_metrics", "substitute_robot"]

SUFFICE_SLACK = 1e-3  # the verification's torque slack (sim/limits._SLACK["torque"])
MAX_SAMPLES = 1500  # manipulability is evaluated on at most this many samples per trajectory (evenly spaced)


@record
class JointDynamics:
    joint: int  # 1-based
    peak_torque: float  # N·m (N for prismatic)
    rms_torque: float
    peak_power: float  # W
    rated_torque: float | None  # the model's effort limit, None when unknown
    prismatic: bool = False  # then the "torques" are forces (N) and power is force x speed

    @property
    def utilisation(self) -> float | None:
        return self.peak_torque / self.rated_torque if self.rated_torque else None

    @property
    def rms_utilisation(self) -> float | None:
        return self.rms_torque / self.rated_torque if self.rated_torque else None

    @property
    def suffices(self) -> bool | None:
        """Whether the motor's rating covers the joint's peak torque, and so its RMS (within
        the torque check's 0.1 % slack, sim/limits.py); None when the joint has no rating."""
        if not self.rated_torque:
            return None
        return self.peak_torque <= self.rated_torque * (1 + SUFFICE_SLACK)


@record
class TaskMetrics:
    task: str
    robot: str  # the cell's robot name
    model: str  # the robot's library name / model
    cycle_time: float
    margin: float  # rad (revolute) or m (prismatic): the worst joint-limit margin
    margin_joint: int  # 1-based
    margin_prismatic: bool
    manipulability: float  # the worst over the trajectory (dimensionless)
    dynamics: tuple[JointDynamics, ...] | None  # None: the model has no inertia data
    dynamics_note: str = ""


def _trajectories(tp: plan_types.TaskPlan) -> list[plan_types.Trajectory]:
    return [tp.trajectory] + [v.trajectory for v in tp.variants]


def _margin(robot: Any, trajs: list[plan_types.Trajectory]) -> tuple[float, int]:
    lo, hi = robot.joint_limits[:, 0], robot.joint_limits[:, 1]
    best, joint = np.inf, 1
    for tr in trajs:
        if tr.q.size == 0:
            continue
        m = np.minimum(tr.q - lo, hi - tr.q).min(axis=0)
        j = int(np.argmin(m))
        if m[j] < best:
            best, joint = float(m[j]), j + 1
    return best, joint


def _manipulability(robot: Any, trajs: list[plan_types.Trajectory]) -> float:
    worst = np.inf
    scale = max(float(robot.reach), 1e-3)
    for tr in trajs:
        if tr.q.size == 0:
            continue
        idx = np.unique(np.linspace(0, len(tr.q) - 1, min(len(tr.q), MAX_SAMPLES)).astype(int))
        jac = np.array([robot.jacobian(q) for q in tr.q[idx]])
        jac[:, :3] /= scale
        s = np.linalg.svd(jac, compute_uv=False)
        worst = min(worst, float(np.prod(s, axis=1).min()))
    return worst


def dynamics(robot: Any, tp: plan_types.TaskPlan, payload: float, payload_at: np.ndarray | None
             ) -> tuple[tuple[JointDynamics, ...] | None, str]:
    """Per joint peak / RMS torque and peak power over every trajectory of the task."""
    if not getattr(robot, "has_inertia", False):
        return None, "no inertia data for this robot model: torques not computed"
    from rmot.sim.limits import joint_torques  # late: loads subprocess only when this runs

    effort = np.asarray(robot.model.effortLimit, dtype=float)[: robot.dof]
    peak = np.zeros(robot.dof)
    power = np.zeros(robot.dof)
    sq, n = np.zeros(robot.dof), 0
    for tr in _trajectories(tp):
        if tr.q.size == 0:
            continue
        tau = joint_torques(robot, tr, payload, payload_at)
        qd = np.asarray(robot.to_model(tr.qd)) if hasattr(robot, "to_model") else tr.qd
        peak = np.maximum(peak, np.abs(tau).max(axis=0))
        power = np.maximum(power, np.abs(tau * qd).max(axis=0))
        sq += (tau ** 2).sum(axis=0)
        n += len(tau)
    rms = np.sqrt(sq / max(n, 1))
    rated = [float(e) if np.isfinite(e) and e > 0 else None for e in effort]
    joints = tuple(JointDynamics(j + 1, float(peak[j]), float(rms[j]), float(power[j]), rated[j], robot.joint_types[j] == "P")
                   for j in range(robot.dof))
    note = "" if all(r is not None for r in rated) else "rated torque unknown for some joints"
    return joints, note


def task_metrics(robot: Any, tp: plan_types.TaskPlan, payload: float = 0.0, payload_at: np.ndarray | None = None) -> TaskMetrics:
    trajs = _trajectories(tp)
    margin, joint = _margin(robot, trajs)
    dyn, note = dynamics(robot, tp, payload, payload_at)
    return TaskMetrics(tp.task.name, tp.robot, getattr(robot, "name", "?"), float(tp.cycle_time), margin, joint,
                       robot.joint_types[joint - 1] == "P", _manipulability(robot, trajs), dyn, note)


def program_metrics(plan: plan_types.Plan, robots: dict[str, Any] | None = None) -> dict[str, TaskMetrics]:
    """task name -> TaskMetrics, the payload taken as verification takes it."""
    from rmot.sim.scene import build_scene  # late: loads coal only when this runs
    from rmot.sim.verification import _payload, _tools_used  # late: loads coal only when this runs

    scene = build_scene(plan.program.cell, _tools_used(plan.program), robots)
    out = {}
    for tp in plan.tasks:
        if tp.robot not in scene.robots:
            continue
        payload, at = _payload(scene, tp)
        out[tp.task.name] = task_metrics(scene.robots[tp.robot].robot, tp, payload, at)
    return out


def substitute_robot(program: ir.Program, slot: str, key: str, dof: int) -> ir.Program:
    """The program with the cell's robot `slot` replaced by the robot `key` (library name or
    absolute URDF path) at the same base pose; targets stay where they are in the base frame."""

    kind = ir.RobotSourceKind.URDF if key.lower().endswith(".urdf") else ir.RobotSourceKind.LIBRARY
    robots = tuple(replace(r, source=ir.RobotSource(kind, key), dof=dof) if r.name == slot else r
                   for r in program.cell.robots)
    return replace(program, cell=replace(program.cell, robots=robots))


def verified(report: Report) -> bool:
    return not report.has_errors
