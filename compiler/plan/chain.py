"""Timing one chain: moves joined by zones, from rest to rest, turned into one Piece.

A single joint move is timed by ruckig (jerk-limited, synchronised); anything else (a Cartesian
move, or several moves blended together) is one joint path timed by toppra with:
* joint velocity limits: vmax * joint_speed along each joint move, the full vmax along
  Cartesian moves (their speed is the TCP's), the smaller share inside a blend; joint
  acceleration limits amax * joint_accel (the smallest in the chain: one constant set per
  chain, a documented simplification when a chain mixes accel settings);
* the TCP speed: an extra path coordinate c (TCP path length / programmed speed, see
  blend.ChainPath) limited to dc/dt <= 1, i.e. TCP speed <= the programmed speed of every
  Cartesian move, and d2c/dt2 <= min(tcp_accel / tcp_speed).
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
    if cartesian:
        wp = np.hstack([path.q, path.c[:, None]])
        acc_c = min(s.move.motion.tcp_accel * s.tcp_rate for s in cartesian)
        vlim, alim = np.append(vmax, 1.0), np.append(amax, acc_c)
    else:
        wp, vlim, alim = path.q, vmax.copy(), amax
    vscale = path.vscale[keep]
    if np.all(vscale == vscale[0]):  # one share for the whole chain: a plain constant limit
        vlim[:dof] *= vscale[0]
        vscale = None
    error = None
    try:
        piece = path_piece(wp[keep], ss[keep], vlim, alim, dof, vscale)
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


def _failed_path(path: ChainPath, segments, message: str) -> TimedChain:  # type: ignore[no-untyped-def]
    """toppra failed: keep the robot where the chain starts (the failure is reported)."""
    piece = HoldPiece(path.q[0].copy(), 0.0)
    zeros = tuple(0.0 for _ in segments)
    return TimedChain(piece, zeros, zeros, path.radii, path, message, False)

