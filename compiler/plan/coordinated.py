"""Coordinated motion: a linear or circular move while external axes move: its frame rides on
a positioner that moves, or stays put in world while the track carrying the robot moves.

The move (ir.Move with `coordinated`, lang/ir_axes.Coordinated) has one path parameter u in
[0, 1] for everything that moves:
* the TCP follows the line or arc *in the moving frame* (the part's): from where the TCP is at
  the start, seen in the frame at the start axis values, to the target `in_frame`; orientation
  by SLERP (compiler/plan/cartesian.py, the same geometry as a plain move);
* the axes of the frame's mechanism go from their start to their end values linearly in u;
* so the TCP in the robot's base frame at u is F(e(u)) * P(u), with F the frame in the base
  frame at the axis values e(u) (Coordinated.part_in_base): B(e)^-1 W(e), the frame's world
  pose W (its positioner's flange, or constant for a fixed frame) seen from the arm's base B
  (on the track's carriage at the track's value, or fixed). A move on a fixed frame while the
  track moves is the same geometry with W constant: the TCP on the line in world, the arm's
  IK at the carriage's pose along the path (ABB TRACK unit, KUKA ROBROOT kinematic, Fanuc
  integrated rail: backends/ext_axes.py cites each).
This is how the controllers describe it: ABB, a movable work object (wobjdata ufprog FALSE,
ufmec the unit) "the robot ... coordinated with the movement of the mechanical unit", the
speed "relative to the work object" ("Technical reference manual - RAPID Instructions,
Functions and Data types", wobjdata; "Application manual - Motion coordination and
supervision", Coordinated work objects); KUKA, a base on an external kinematic ($BASE=EK(...))
whose LIN/CIRC path and $VEL.CP are relative to that moving base (KSS 8.x "Configuration of
Kinematic Systems", mathematical coupling); Fanuc, a COORD motion "executed relative to a
leader motion group" with "constant relative speed" (FANUC Coordinated Motion Function,
Setup and Operations Manual, "Overview" and "COORD motion option").

Dense IK at each u (compiler/plan/dense.follow_path, on a path whose poses are F(e(u)) P(u)),
then one time-optimal timing of the joined path (arm joints + axes) under every arm joint's
and every axis' speed and acceleration and the programmed TCP speed and acceleration *in the
moving frame* (the TCP spline is the part-frame positions). The axes' values over time are
sampled from that same timing onto the move's InstructionRecord (`axes_path`), the one place
the verifier, renderer and backends read them from (lang/axis_motion.axis_samples).
Joint torque limits are not applied to a coordinated move (its timing ignores them; a known
simplification, documented in lang/REFERENCE.md).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from rmot.lang import codes_axes, ir
from rmot.lang.diagnostics import Severity
from rmot.compiler.plan import codes
from rmot.compiler.plan.cartesian import CartesianPath, DegenerateArc, arc_path, line_path
from rmot.compiler.plan.dense import PathFailure, follow_path
from rmot.compiler.plan.move_chain import TimedChain
from rmot.compiler.plan.robot_model import RobotModel
from rmot.compiler.plan.segments import Segment, end_turns
from rmot.compiler.plan.targets import Finding, solve_target
from rmot.compiler.plan.timing import HoldPiece, PathPiece, TimingError, path_piece, stretched

__all__ = ["CoordinatedChain", "CoordinatedSegment", "coordinated_axes", "coordinated_segment", "time_coordinated"]

_CURVE_POINTS = 2000  # samples of the TCP's curve in the base frame, for its length and distances to it
_LOCAL_POINTS = 9  # samples of the curve within one interval of the dense path (MovingFramePath.deviation)
_JOINT_WEIGHT = 0.01  # m per rad (or m) of joint/axis motion in the path parameter (see _parameter)
_AXES_STEP = 0.002  # s between the samples of the axes' values recorded on the plan
_SLOWDOWN_WARN = 1.05  # W606 when a joint or axis forces the TCP below 1/1.05 of its programmed speed


@dataclass(frozen=True, eq=False)
class MovingFramePath(CartesianPath):
    """The TCP path in the robot's base frame of a coordinated move: `part` (the line or arc in
    the moving frame) carried by `frames` (u (N,) -> (N, 4, 4) the frame in the base frame)."""

    part: CartesianPath | None = None
    frames: Callable[[np.ndarray], np.ndarray] | None = None
    curve: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))

    @staticmethod
    def of(part: CartesianPath, frames: Callable[[np.ndarray], np.ndarray]) -> MovingFramePath:
        u = np.linspace(0.0, 1.0, _CURVE_POINTS)
        poses = frames(u) @ part.poses(u)
        curve = poses[:, :3, 3]
        length = float(np.sum(np.linalg.norm(np.diff(curve, axis=0), axis=1)))
        rel = np.einsum("nji,njk->nik", poses[:-1, :3, :3], poses[1:, :3, :3])
        angle = float(np.sum(np.arccos(np.clip((np.trace(rel, axis1=1, axis2=2) - 1.0) / 2.0, -1.0, 1.0))))
        # the initial sampling (dense.follow_path) follows the longer of the two: the TCP may stand
        # still in the base frame while it runs along the whole seam in the part's
        return MovingFramePath(part.kind, curve[0], curve[-1], part.q0, part.q1, max(length, part.length),
                               max(angle, part.angle), part=part, frames=frames, curve=curve)

    def poses(self, u: np.ndarray) -> np.ndarray:
        assert self.part is not None and self.frames is not None  # built by `of`
        u = np.asarray(u, dtype=float)
        out: np.ndarray = self.frames(u) @ self.part.poses(u)
        return out

    def positions(self, u: np.ndarray) -> np.ndarray:
        out: np.ndarray = self.poses(u)[:, :3, 3]
        return out

    def deviation(self, u0: np.ndarray, u1: np.ndarray, points: np.ndarray) -> np.ndarray:
        """Distance (m) of points (N, 3) from the TCP's curve between u0 and u1 (N,) (a polyline
        of _LOCAL_POINTS samples there): a curve that passes one place twice, or stands still in
        the base frame while the part turns, is not matched far from where the point belongs."""
        fractions = np.linspace(0.0, 1.0, _LOCAL_POINTS)
        us = u0[:, None] + (u1 - u0)[:, None] * fractions
        curve = self.positions(us.ravel()).reshape(len(u0), _LOCAL_POINTS, 3)
        a, d = curve[:, :-1], np.diff(curve, axis=1)
        rel = points[:, None, :] - a
        t = np.clip(np.einsum("nki,nki->nk", rel, d) / np.maximum(np.einsum("nki,nki->nk", d, d), 1e-30), 0.0, 1.0)
        out: np.ndarray = np.min(np.linalg.norm(rel - t[..., None] * d, axis=2), axis=1)
        return out

    def distance(self, points: np.ndarray) -> np.ndarray:
        """Distance (m) of points (N, 3) from the TCP's curve in the base frame (the polyline of
        _CURVE_POINTS samples; its chords stay within microns of the curve at cell sizes)."""
        a, b = self.curve[:-1], self.curve[1:]
        d = b - a
        n2 = np.maximum(np.einsum("ij,ij->i", d, d), 1e-30)
        out = np.empty(len(points))
        for k, p in enumerate(points):
            t = np.clip(np.einsum("ij,ij->i", p - a, d) / n2, 0.0, 1.0)
            out[k] = float(np.min(np.linalg.norm(a + t[:, None] * d - p, axis=1)))
        return out


@dataclass(frozen=True, eq=False)
class CoordinatedSegment(Segment):
    """A coordinated move's Segment: `tcp` is the TCP in the moving frame (its speed is the
    programmed one), `ext` (M, n) the program's axes at each of the M points."""

    ext: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))

    def via_axes(self) -> np.ndarray | None:
        """A circular move's axes (ir.Move.ext order) where the TCP passes its via point: at the
        via's exact progress u on the arc in the moving frame (not the nearest dense sample), so
        a controller that takes the via with its own axis values (INFORM's SMOVC) sees the axes
        go linearly in u through it."""
        if self.move.via is None or self.path is None or self.path.kind != "arc":
            return None
        _, e0, e1 = _axis_values(self.move)
        u = self.path.u_at_via(np.asarray(self.move.via.in_frame.position))
        values: np.ndarray = e0 + u * (e1 - e0)
        return values


@dataclass(frozen=True, eq=False)
class CoordinatedChain(TimedChain):
    """A coordinated move timed: `axes_t` (K,) local times and `axes` (K, n) the axes there."""

    axes_t: np.ndarray = field(default_factory=lambda: np.zeros(0))
    axes: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))


def _axis_values(move: ir.Move) -> tuple[tuple[str, ...], np.ndarray, np.ndarray]:
    coord = move.coordinated
    assert coord is not None  # only coordinated moves come here
    names = tuple(n for n, _ in move.ext)
    start = dict(coord.start)
    return names, np.array([start[n] for n in names]), np.array([v for _, v in move.ext])


def coordinated_segment(robot: RobotModel, move: ir.Move, q_now: np.ndarray) -> tuple[Segment | None, list[Finding]]:
    """The dense joint path of a coordinated move from q_now (dof,), or None and the errors."""
    coord = move.coordinated
    assert coord is not None  # only coordinated moves come here
    q_target, findings = solve_target(robot, move, q_now)
    if q_target is None:
        return None, findings
    names, e0, e1 = _axis_values(move)

    def frames(u: np.ndarray) -> np.ndarray:
        return coord.part_in_base(names, e0 + np.asarray(u, dtype=float)[:, None] * (e1 - e0))

    tool = move.tool.tcp.matrix()
    at_start, at_end = np.linalg.inv(frames(np.array([0.0, 1.0])))
    start = at_start @ robot.fk(q_now) @ tool
    end = at_end @ (move.target.pose.matrix() if isinstance(move.target, ir.CartesianTarget) else robot.fk(q_target) @ tool)
    try:
        if move.kind is ir.MotionKind.CIRCULAR:
            assert move.via is not None  # a circular move has its via point
            part = arc_path(start, np.asarray(move.via.in_frame.position), end)
        else:
            part = line_path(start, end)
    except DegenerateArc as exc:
        return None, findings + [Finding(codes.ARC_DEGENERATE, Severity.ERROR, str(exc))]
    dense = follow_path(robot, MovingFramePath.of(part, frames), np.linalg.inv(tool), q_now)
    if isinstance(dense, PathFailure):
        code = {"singular": codes.PATH_SINGULAR, "limit": codes.JOINT_LIMIT_PATH}.get(dense.kind, codes.TARGET_UNREACHABLE)
        moving = "the frame moves with the axes" if coord.relative() else "the track carries the arm along the path"
        return None, findings + [Finding(code, Severity.ERROR, f"{dense.message} (coordinated: {moving})")]
    via_index = None
    if part.kind == "arc":
        assert move.via is not None
        via_index = int(np.argmin(np.abs(dense.u - part.u_at_via(np.asarray(move.via.in_frame.position)))))
    ext = e0 + dense.u[:, None] * (e1 - e0)
    seg = CoordinatedSegment(move, dense.q, part.positions(dense.u), 1.0 / move.motion.tcp_speed, via_index, part, ext=ext)
    off = end_turns(seg, move)
    return (None, findings + [off]) if off is not None else (seg, findings + _slowdown(robot, seg))


def _slowdown(robot: RobotModel, seg: CoordinatedSegment) -> list[Finding]:
    """W606 where an arm joint or an axis cannot keep the programmed TCP speed relative to the
    move's frame (the part's, or a fixed frame while the track moves): the rate each needs at
    that speed (its step over the TCP's step in the frame) over its speed limit, names the worst."""
    coord = seg.move.coordinated
    assert coord is not None
    by_name = {a.name: a for m in coord.external.mechanisms for a in m.axes}
    axes = [by_name[n] for n, _ in seg.move.ext]
    dl = np.linalg.norm(np.diff(seg.tcp, axis=0), axis=1)
    ok = dl > 1e-7
    speed = seg.move.motion.tcp_speed
    limits = np.concatenate([robot.velocity_limits, [a.speed for a in axes]])
    need = np.abs(np.diff(np.hstack([seg.q, seg.ext]), axis=0))[ok] / dl[ok, None] * speed
    if not np.any(ok) or float(np.max(need / limits)) <= _SLOWDOWN_WARN:
        return []
    i, j = np.unravel_index(int(np.argmax(need / limits)), need.shape)
    dof = seg.q.shape[1]
    if j < dof:
        name, unit, scale = f"joint {j + 1}", "deg/s", float(np.degrees(1.0))
    else:
        axis = axes[j - dof]
        name, unit, scale = f"axis '{axis.name}'", "mm/s" if axis.linear else "deg/s", 1000.0 if axis.linear else float(np.degrees(1.0))
    worst = float(need[i, j] / limits[j])
    where = "relative to the part" if coord.relative() else f"in frame '{coord.frame}'"
    msg = (f"the TCP speed {where} must drop to {speed / worst * 1e3:.1f} mm/s (programmed "
           f"{speed * 1e3:.0f} mm/s): {name} would need {need[i, j] * scale:.0f} {unit} (max {limits[j] * scale:.0f} {unit})")
    return [Finding(codes_axes.EXT_SLOWDOWN, Severity.WARNING, msg)]


def _parameter(seg: CoordinatedSegment) -> np.ndarray:
    """The path parameter: TCP length in the moving frame, with a joint/axis step term so that
    a stretch where the TCP stands still in the frame while the frame turns still advances."""
    dl = np.linalg.norm(np.diff(seg.tcp, axis=0), axis=1)
    dq = np.max(np.abs(np.diff(np.hstack([seg.q, seg.ext]), axis=0)), axis=1)
    return np.concatenate([[0.0], np.cumsum(np.hypot(dl, _JOINT_WEIGHT * dq))])


def time_coordinated(robot: RobotModel, seg: Segment) -> TimedChain:
    """The time-optimal rest-to-rest timing of a coordinated move: arm joints and axes as one
    path under their speed and acceleration limits (the cell's, lang/ir_axes.ExtAxis) and the
    programmed TCP speed and acceleration in the moving frame. Never raises: a move that
    cannot be timed holds with the reason."""
    assert isinstance(seg, CoordinatedSegment) and seg.move.coordinated is not None
    by_name = {a.name: a for m in seg.move.coordinated.external.mechanisms for a in m.axes}
    axes_of = [by_name[n] for n, _ in seg.move.ext]
    dof = seg.q.shape[1]
    ss = _parameter(seg)
    keep = np.concatenate([[True], np.diff(ss) > 1e-10])
    if ss[-1] < 1e-9 or np.count_nonzero(keep) < 2:
        return TimedChain(HoldPiece(seg.q[-1].copy(), 0.0), (0.0,), (0.0,), (0.0,), None)
    joined = np.hstack([seg.q, seg.ext])[keep]
    vlim = np.concatenate([robot.velocity_limits, [a.speed for a in axes_of]])
    alim = np.concatenate([robot.accel_limits * seg.move.motion.joint_accel, [a.accel for a in axes_of]])
    n = int(np.count_nonzero(keep))
    motion = seg.move.motion
    try:
        piece = path_piece(joined, ss[keep], vlim, alim, joined.shape[1], None, tcp=seg.tcp[keep],
                           tcp_speed=np.full(n, motion.tcp_speed), tcp_accel=np.full(n, motion.tcp_accel))
    except TimingError as exc:
        return TimedChain(HoldPiece(seg.q[0].copy(), 0.0), (0.0,), (0.0,), (0.0,), None, str(exc), False)
    error = None
    if motion.duration is not None:
        if motion.duration < piece.duration * (1 - 1e-9):
            error = f"time must be at least the fastest feasible {piece.duration:.3f} s (got {motion.duration:.3f} s)"
        else:
            piece = stretched(piece, motion.duration)
    ts = np.linspace(0.0, piece.duration, max(2, int(np.ceil(piece.duration / _AXES_STEP)) + 1))
    axes = piece.sample(ts)[0][:, dof:]
    arm = PathPiece(piece.trajectory, piece.native_duration, piece.scale, dof)
    return CoordinatedChain(arm, (0.0,), (arm.duration,), (0.0,), None, error, error is not None, axes_t=ts, axes=axes)


def coordinated_axes(timed: TimedChain, t0: float) -> tuple[np.ndarray, np.ndarray] | None:
    """The axes' (times on the task's timeline, values) of a timed coordinated move, else None."""
    if not isinstance(timed, CoordinatedChain):
        return None
    return t0 + timed.axes_t, timed.axes
