"""Segments: the joint-space geometry of one move, before blending and timing.

A Segment is the dense joint path of a move: q (M, dof) from the start joints to the target
joints, with the TCP positions (M, 3) along it. Joint moves are the straight line in joint
space (what a synchronised joint move does), sampled every `_JOINT_STEP` rad so that blends
and splines can follow it. Linear and circular moves are the dense IK of the TCP path
(compiler.plan.dense), checked for unreachable points, singularities and joint limits.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from rmot.lang import ir
from rmot.lang.motion_kinds import require_handlers
from rmot.compiler.plan import codes
from rmot.compiler.plan.cartesian import CartesianPath, DegenerateArc, arc_path, line_path
from rmot.compiler.plan.dense import DensePath, PathFailure, follow_path
from rmot.compiler.plan.targets import Finding, off_turns, solve_target
from rmot.lang.diagnostics import Severity
from rmot.compiler.plan.robot_model import RobotModel

__all__ = ["Segment", "build_segment", "end_turns"]

_JOINT_STEP = 0.02  # rad between samples of a joint move
_SLOWDOWN_WARN = 1.05  # warn when joints force the TCP below 1/1.05 of the programmed speed


@dataclass(frozen=True, eq=False)
class Segment:
    """One move's joint path. `tcp_rate` is 1 / programmed TCP speed (s/m) for Cartesian moves,
    0 for joint moves (no TCP speed limit). `via_index`: circular moves, the sample at the via."""

    move: ir.Move
    q: np.ndarray
    tcp: np.ndarray
    tcp_rate: float
    via_index: int | None = None
    path: CartesianPath | None = None

    @property
    def q_end(self) -> np.ndarray:
        return self.q[-1]

    @property
    def speed_factor(self) -> float:
        """The share of the joint velocity limits this move may use (joint_speed for joint moves)."""
        return self.move.motion.joint_speed if self.move.kind is ir.MotionKind.JOINT else 1.0

    @property
    def tcp_length(self) -> float:
        return float(np.sum(np.linalg.norm(np.diff(self.tcp, axis=0), axis=1)))

    @property
    def joint_length(self) -> float:
        return float(np.max(np.abs(self.q[-1] - self.q[0]))) if len(self.q) > 1 else 0.0


def _tcp_positions(robot: RobotModel, q: np.ndarray, tool: np.ndarray) -> np.ndarray:
    return (robot.fk_batch(q) @ tool)[:, :3, 3]


def build_segment(
    robot: RobotModel, move: ir.Move, q_now: np.ndarray
) -> tuple[Segment | None, list[Finding]]:
    """The move's Segment from the current joints q_now (dof,), or None and the errors."""
    q_target, findings = solve_target(robot, move, q_now)
    if q_target is None:
        return None, findings
    tool = move.tool.tcp.matrix()
    if _TCP_PATHS[move.kind] is None:  # the straight line in joint space
        n = int(np.ceil(np.max(np.abs(q_target - q_now)) / _JOINT_STEP)) + 1
        q = q_now + np.linspace(0.0, 1.0, max(n, 2))[:, None] * (q_target - q_now)
        return Segment(move, q, _tcp_positions(robot, q, tool), 0.0), findings
    seg, more = _cartesian_segment(robot, move, q_now, q_target, tool)
    off = end_turns(seg, move) if seg is not None else None
    if off is not None:
        return None, findings + more + [off]
    return seg, findings + more


def end_turns(seg: Segment, move: ir.Move) -> Finding | None:
    """E-finding when a Cartesian path ends with a joint on another turn than `config` fixes:
    the path decides the end's turns, so they must be the ones fixed."""
    off = off_turns(seg.q_end, move.config.turns)
    if not off:
        return None
    j, n, got = off[0]
    msg = (f"a {move.kind.name.lower()} move must end with joint {j + 1} on turn {n} "
           f"(config(j{j + 1}={n})); its path from the current joints ends at "
           f"{np.degrees(seg.q_end[j]):.1f} deg, turn {got}: "
           f"insert a joint move with config(j{j + 1}={n}) before it")
    return Finding(codes.TURN_NOT_REACHED, Severity.ERROR, msg)


def _cartesian_segment(robot: RobotModel, move: ir.Move, q_now: np.ndarray, q_target: np.ndarray,
                       tool: np.ndarray) -> tuple[Segment | None, list[Finding]]:
    start = robot.fk(q_now) @ tool
    if isinstance(move.target, ir.JointTarget):
        end = robot.fk(q_target) @ tool
    else:
        end = move.target.pose.matrix()
    try:
        path = _TCP_PATHS[move.kind](start, move.via, end)  # type: ignore[misc]
    except DegenerateArc as exc:
        return None, [Finding(codes.ARC_DEGENERATE, Severity.ERROR, str(exc))]
    tool_inv = np.linalg.inv(tool)
    dense = follow_path(robot, path, tool_inv, q_now)
    if isinstance(dense, PathFailure):
        code = {"singular": codes.PATH_SINGULAR, "limit": codes.JOINT_LIMIT_PATH}.get(dense.kind, codes.TARGET_UNREACHABLE)
        return None, [Finding(code, Severity.ERROR, dense.message)]
    if isinstance(move.target, ir.JointTarget) and float(np.max(np.abs(dense.q[-1] - q_target))) > 1e-6:
        msg = (f"a {move.kind.name.lower()} move to joint values must reach them on the current branch "
               "(the path ends on other joint values); use a joint move instead")
        return None, [Finding(codes.BRANCH_CHANGE, Severity.ERROR, msg)]
    via_index = None
    if path.kind == "arc":
        assert move.via is not None  # a circular move has its via point
        via_index = int(np.argmin(np.abs(dense.u - path.u_at_via(np.asarray(move.via.pose.position)))))
    rate = 1.0 / move.motion.tcp_speed
    seg = Segment(move, dense.q, dense.tcp, rate, via_index, path)
    return seg, _slowdown(robot, seg, dense)


def _line(start: np.ndarray, via: ir.CartesianTarget | None, end: np.ndarray) -> CartesianPath:
    return line_path(start, end)


def _arc(start: np.ndarray, via: ir.CartesianTarget | None, end: np.ndarray) -> CartesianPath:
    if via is None:
        raise DegenerateArc("circular move must have a via point (got none)")
    return arc_path(start, np.asarray(via.pose.position), end)


# Per motion kind, the TCP path (start, via, end) a move follows by dense IK, or None for the
# straight line in joint space (a synchronised joint move). A kind without an entry fails at
# import, never a silent default.
_TCP_PATHS: dict[ir.MotionKind, Callable[[np.ndarray, ir.CartesianTarget | None, np.ndarray],
                                         CartesianPath] | None] = {
    ir.MotionKind.JOINT: None,
    ir.MotionKind.LINEAR: _line,
    ir.MotionKind.CIRCULAR: _arc,
}
require_handlers("planner (compiler/plan/segments.py _TCP_PATHS)", _TCP_PATHS)


def _slowdown(robot: RobotModel, seg: Segment, dense: DensePath) -> list[Finding]:
    """A warning where joint speed limits force the TCP below its programmed speed."""
    dl = np.linalg.norm(np.diff(dense.tcp, axis=0), axis=1)
    ok = dl > 1e-7
    if not np.any(ok):
        return []
    speed = seg.move.motion.tcp_speed
    qd = np.abs(np.diff(dense.q, axis=0)[ok]) / dl[ok, None] * speed  # joint speed at programmed TCP speed
    ratio = qd / robot.velocity_limits
    worst = float(np.max(ratio))
    if worst <= _SLOWDOWN_WARN:
        return []
    i, j = np.unravel_index(int(np.argmax(ratio)), ratio.shape)
    k = int(np.flatnonzero(ok)[i])
    where = "(" + ", ".join(f"{v * 1e3:.1f}" for v in dense.tcp[k]) + ") mm in the robot base frame"
    cond = float(robot.condition(dense.q[k]))
    manip = float(robot.manipulability(dense.q[k]))
    msg = (f"TCP speed must drop to {speed / worst * 1e3:.0f} mm/s (programmed {speed * 1e3:.0f} mm/s) "
           f"near {where}: joint {j + 1} would need {np.degrees(qd[i, j]):.0f} deg/s "
           f"(max {np.degrees(robot.velocity_limits[j]):.0f} deg/s); "
           f"Jacobian condition number {cond:.0f}, manipulability {manip:.2g}")
    return [Finding(codes.SLOWDOWN_SINGULAR, Severity.WARNING, msg)]
