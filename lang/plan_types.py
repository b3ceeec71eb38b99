"""The Plan: what the robots will do, as data — the planner's hand-off to sim and backends.

Lives outside `compiler.plan` on purpose: the backends and the simulator import these
types, never the planner itself (nor pinocchio or scipy).

Shapes: `t (N,)`, `q, qd, qdd (N, dof)`; SI units (rad, rad/s, rad/s^2; m for prismatic).
Arrays are made read-only when a Trajectory is built.

Runtime `if`: a task's main timeline takes the `then` arm of every `if`; each other arm is
planned as well, as a `Variant` that starts at the `if`'s start state, so the simulator can
verify every branch and the backends can read the joint solutions of targets inside it.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from rmot.lang import ir, ir_tree, payload
from rmot.lang.diagnostics import Diagnostic
from rmot.lang.source import Span

__all__ = ["Branch", "InstructionRecord", "Plan", "TaskPlan", "Trajectory", "Variant"]

Branch = ir.Config  # with all three fields set: the branch a joint solution lies on


@dataclass(frozen=True, eq=False)
class Trajectory:
    """Samples at a fixed step (default 4 ms); t[0] is the task's start time on the timeline."""

    t: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    qdd: np.ndarray

    def __post_init__(self) -> None:
        n = self.t.shape[0]
        for name in ("q", "qd", "qdd"):
            a = getattr(self, name)
            if a.ndim != 2 or a.shape[0] != n:
                raise ValueError(f"Trajectory.{name} must have shape (N, dof) with N={n} (got {a.shape})")
        for a in (self.t, self.q, self.qd, self.qdd):
            a.setflags(write=False)

    @property
    def duration(self) -> float:
        return float(self.t[-1] - self.t[0]) if self.t.size else 0.0

    def at(self, time: float) -> np.ndarray:
        """Joint positions at `time`, linearly interpolated between samples, held at the ends."""
        return np.array([np.interp(time, self.t, self.q[:, j]) for j in range(self.q.shape[1])])


@dataclass(frozen=True, eq=False)
class InstructionRecord:
    """What the planner decided for one IR instruction (looked up by `uid`)."""

    uid: int
    span: Span | None
    t_start: float
    t_end: float
    q_target: np.ndarray | None = None  # joints at the move's target (dof,)
    branch: Branch | None = None  # the IK branch of q_target (6R arms)
    tcp_pose: ir.Pose | None = None  # TCP at the target, robot base frame
    flange_pose: ir.Pose | None = None  # flange at the target, robot base frame
    q_via: np.ndarray | None = None  # circular moves: joints at the via point
    # a coordinated move (ir.Move.coordinated): the external axes' values (K, n; ir.Move.ext order)
    # at times (K,) over [t_start, t_end], sampled from the move's one timing
    axes_path: tuple[np.ndarray, np.ndarray] | None = None
    ext_via: np.ndarray | None = None  # a coordinated circular move: the axes (ir.Move.ext order) as the TCP passes the via
    blend_radius: float = 0.0  # the blend actually used (m); 0 = exact stop
    # the share of the arm's joint acceleration limits the move was timed with: the smallest
    # `accel` of its blended chain (compiler/plan/move_chain.chain_accel_share); 1 = full
    accel_share: float = 1.0
    variant: int = 0  # 0 = main timeline; k = Plan variant k


@dataclass(frozen=True, eq=False)
class Variant:
    """An `if` arm not on the main timeline: planned from the `if`'s start state."""

    index: int
    if_uid: int
    arm: str  # "then" or "otherwise"
    trajectory: Trajectory


@dataclass(frozen=True, eq=False)
class TaskPlan:
    task: ir.Task
    robot: str
    trajectory: Trajectory
    records: tuple[InstructionRecord, ...]
    variants: tuple[Variant, ...] = ()
    # the load the flange carries (tool and held parts), decided by the planner before it times
    # the task and read by every consumer (lang/payload.of); None only in a plan built by hand
    load: payload.TaskLoad | None = None

    @property
    def cycle_time(self) -> float:
        return self.trajectory.duration

    def leading_axis_rates(self, rec: InstructionRecord) -> tuple[float, float] | None:
        """(peak speed, peak acceleration) of a joint move's leading axis (the joint that moves
        farthest) over [t_start, t_end] of the record's timeline, or None without a motion
        there. The planned joint move runs along its joint-space line, every axis in step, so
        the leading axis' speed and acceleration determine the move's timing (what URScript's
        movej `v` and `a` give the controller)."""
        traj = self.trajectory
        if rec.variant:
            traj = next((v.trajectory for v in self.variants if v.index == rec.variant), traj)
        if rec.q_target is None or traj.t.size == 0:
            return None
        inside = (traj.t >= rec.t_start - 1e-9) & (traj.t <= rec.t_end + 1e-9)
        if not np.any(inside):
            return None
        lead = int(np.argmax(np.abs(np.asarray(rec.q_target) - traj.at(rec.t_start))))
        speed = float(np.max(np.abs(traj.qd[inside, lead])))
        accel = float(np.max(np.abs(traj.qdd[inside, lead])))
        return (speed, accel) if speed > 0.0 and accel > 0.0 else None

    def next_move(self, rec: InstructionRecord) -> ir.Move | None:
        """The move that follows `rec` on its timeline (the one a blend at `rec` joins), or None."""
        moves = {i.uid: i for i in ir_tree.walk(self.task.body) if isinstance(i, ir.Move)}
        later = [r for r in self.records if r.variant == rec.variant and r.uid in moves
                 and r.uid != rec.uid and r.t_start >= rec.t_end - 1e-9]
        if not later:
            return None
        return moves[min(later, key=lambda r: (r.t_start, r.t_end)).uid]

    def record(self, uid: int) -> InstructionRecord | None:
        for r in self.records:
            if r.uid == uid and r.variant == 0:
                return r
        for r in self.records:
            if r.uid == uid:
                return r
        return None


@dataclass(frozen=True, eq=False)
class Plan:
    program: ir.Program
    tasks: tuple[TaskPlan, ...]
    step: float = 0.004  # s, the sampling step of every trajectory
    diagnostics: tuple[Diagnostic, ...] = field(default=())

    @property
    def cycle_time(self) -> float:
        return max((tp.trajectory.t[-1] for tp in self.tasks if tp.trajectory.t.size), default=0.0)

    def task(self, name: str) -> TaskPlan:
        for tp in self.tasks:
            if tp.task.name == name:
                return tp
        raise KeyError(name)


# ------------------------------------------------------------------ variant paths
# How a Variant's path is named in messages: Variant.arm -> words ({at}: " at line N", or "" when
# the instruction has no source position).
PATHS = {
    "otherwise": "the path through the 'otherwise' arm of the if{at}",
    "timeout": "the path where the wait{at} times out",
    "no iteration": "the path where the while{at} runs no iteration",
}


def path_words(arm: str, line: object | None) -> str:
    words = PATHS.get(arm, "the path through the '" + arm + "' arm of the if{at}")
    return words.format(at=f" at line {line}" if line is not None else "")
