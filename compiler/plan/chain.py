"""Timing one chain: moves joined by zones, from rest to rest, turned into one Piece.

A single joint move is timed by ruckig (jerk-limited, synchronised); anything else (a Cartesian
move, or several moves blended together) is one joint path timed by toppra with:
* joint velocity limits: vmax * joint_speed along each joint move, the full vmax along
  Cartesian moves (their speed is the TCP's), the smaller share inside a blend; joint
  acceleration limits amax * joint_accel (the smallest in the chain: one constant set per
  chain, a documented simplification when a chain mixes accel settings);
* the TCP speed: with c the TCP time (TCP path length / programmed speed, see
  blend.ChainPath), dc/dt <= 1, i.e. TCP speed <= the programmed speed of every Cartesian
  move, as a limit on the path speed ds/dt <= 1 / (dc/ds) with dc/ds exact per waypoint
  interval (timing.path_piece's `rate`); c is also an extra spline coordinate with
  d2c/dt2 <= min(tcp_accel / tcp_speed), to shape the TCP acceleration.
`times` gives each segment's start and end on the piece's local clock (end = zone entry).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rmot.compiler import ir
from rmot.compiler.plan.blend import ChainPath, blend_chain
from rmot.compiler.plan.segments import Segment
from rmot.compiler.plan.timing import HoldPiece, Piece, TimingError, joint_move_piece, path_piece, stretched

__all__ = ["TimedChain", "time_chain"]

_UNLIMITED = 1e9  # the TCP-time coordinate's velocity bound: its limit is `rate` (see _path_chain)


@dataclass(frozen=True, eq=False)
class TimedChain:
    piece: Piece
    starts: tuple[float, ...]  # s, local time each segment starts
    ends: tuple[float, ...]  # s, local time each segment ends (zone entry when blended)
    radii: tuple[float, ...]
    path: ChainPath | None
    error: str | None = None  # a timing problem (time too short, toppra failure), user-facing
    error_is_time: bool = False


def _limits(robot: object, segments: list[Segment]) -> tuple[np.ndarray, np.ndarray]:
    """Joint velocity limits (full; joint_speed applies per point, see ChainPath.vscale) and
    joint acceleration limits (amax times the smallest joint_accel of the chain)."""
    fa = min(s.move.motion.joint_accel for s in segments)
    return robot.velocity_limits.copy(), robot.accel_limits * fa  # type: ignore[attr-defined]


def time_chain(robot: object, segments: list[Segment]) -> TimedChain:
    """Time segments (len >= 1) joined by their zones; segments[-1] ends at rest."""
    vmax, amax = _limits(robot, segments)
    duration = segments[0].move.motion.duration if len(segments) == 1 else None
    if len(segments) == 1 and segments[0].move.kind is ir.MotionKind.JOINT:
        return _joint_chain(segments[0], vmax * segments[0].speed_factor, amax, duration)
    path = blend_chain(robot, segments)
    return _path_chain(path, segments, vmax, amax, duration)


def _joint_chain(seg: Segment, vmax: np.ndarray, amax: np.ndarray, duration: float | None) -> TimedChain:
    error = None
    try:
        piece = joint_move_piece(seg.q[0], seg.q[-1], vmax, amax, duration)
    except TimingError as exc:
        error = str(exc)
        piece = joint_move_piece(seg.q[0], seg.q[-1], vmax, amax, None)
    return TimedChain(piece, (0.0,), (piece.duration,), (0.0,), None, error, error is not None)


def _path_chain(path: ChainPath, segments, vmax, amax, duration) -> TimedChain:  # type: ignore[no-untyped-def]
    dof = path.q.shape[1]
    ss = path.ss
    if ss[-1] < 1e-9:
        piece = HoldPiece(path.q[-1].copy(), duration or 0.0)
        zeros = tuple(0.0 for _ in segments)
        return TimedChain(piece, zeros, tuple(piece.duration for _ in segments), path.radii, path)
    cartesian = [s for s in segments if s.tcp_rate > 0]
    keep = np.concatenate([[True], np.diff(ss) > 1e-10])
    rate = None
    if cartesian:
        # The TCP speed limit is a limit on the path speed, ds/dt <= 1 / (dc/ds), with dc/ds
        # exact per waypoint interval. c itself stays a coordinate only to shape the TCP
        # acceleration: as a spline its slope rings where dc/ds jumps (an arc starting to turn
        # the tool), which as a speed limit slowed whole chains down (issue 4).
        wp = np.hstack([path.q, path.c[:, None]])
        acc_c = min(s.move.motion.tcp_accel * s.tcp_rate for s in cartesian)
        vlim, alim = np.append(vmax, _UNLIMITED), np.append(amax, acc_c)
        rate = _tcp_rate(path.c[keep], ss[keep])
    else:
        wp, vlim, alim = path.q, vmax.copy(), amax
    vscale = path.vscale[keep]
    if np.all(vscale == vscale[0]):  # one share for the whole chain: a plain constant limit
        vlim[:dof] *= vscale[0]
        vscale = None
    error = None
    try:
        piece = path_piece(wp[keep], ss[keep], vlim, alim, dof, vscale, rate=rate)
    except TimingError as exc:
        return _failed_path(path, segments, str(exc))
    if duration is not None:
        if duration < piece.duration * (1 - 1e-9):
            error = f"time must be at least the fastest feasible {piece.duration:.3f} s (got {duration:.3f} s)"
        else:
            piece = stretched(piece, duration)
    starts = tuple(piece.time_at(float(ss[i])) for i in path.starts)
    ends = tuple(piece.time_at(float(ss[i])) for i in path.ends)
    ends = ends[:-1] + (piece.duration,)
    return TimedChain(piece, starts, ends, path.radii, path, error, error is not None)


def _tcp_rate(c: np.ndarray, ss: np.ndarray) -> np.ndarray:
    """(M,) dc/ds at the waypoints: the three-point (parabola) estimate inside, the end
    intervals' slope at the ends. The secant slopes of neighbouring intervals differ by a few
    percent where the TCP-per-joint ratio changes along an arc; a limit taking the larger of
    the two at every waypoint made the TCP that much slower than programmed."""
    h = np.diff(ss)
    slope = np.diff(c) / h
    if len(slope) == 1:
        return np.repeat(slope, 2)
    inner = (slope[:-1] * h[1:] + slope[1:] * h[:-1]) / (h[:-1] + h[1:])
    return np.concatenate([slope[:1], inner, slope[-1:]])


def _failed_path(path: ChainPath, segments, message: str) -> TimedChain:  # type: ignore[no-untyped-def]
    """toppra failed: keep the robot where the chain starts (the failure is reported)."""
    piece = HoldPiece(path.q[0].copy(), 0.0)
    zeros = tuple(0.0 for _ in segments)
    return TimedChain(piece, zeros, zeros, path.radii, path, message, False)

