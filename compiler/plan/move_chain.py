"""Timing one chain: moves joined by zones, from rest to rest, turned into one Piece.

A single joint move is the joint-space line timed exactly (timing.joint_move_piece); anything
else (a Cartesian move, or several moves blended together) is one joint path timed
time-optimally (timing.path_piece) under physical limits only:
* joint velocity limits: vmax * joint_speed along each joint move, the full vmax along
  Cartesian moves (their speed is the TCP's), the smaller share inside a blend; joint
  acceleration limits amax * joint_accel (the smallest in the chain: one constant set per
  chain, a documented simplification when a chain mixes accel settings);
* on Cartesian moves and in every blend touching one: TCP path speed <= the programmed
  speed and TCP path acceleration <= the programmed (or default) accel; in a blend between
  a joint move and a Cartesian move the Cartesian move's limits apply from the blend's start.
If a chain cannot be timed as a whole, each of its moves is timed on its own with an exact
stop at every corner (W225 names the corner's move and time): nothing is dropped.
Joint torque limits (compiler/plan/torque.py, where the robot has ratings): a chain timed as
above whose torques exceed a rating is timed again with the torque rows (a joint move then
as the joint-space line through path_piece): the motion slows where the motors need it to.
`times` gives each segment's start and end on the piece's local clock (end = zone entry).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from rmot.lang import ir
from rmot.compiler.plan.blend import ChainPath, blend_chain
from rmot.compiler.plan.segments import Segment
from rmot.compiler.plan.timing import (HoldPiece, PathPiece, Piece, TimingError, joint_move_piece,
                                       path_piece, stretched)
from rmot.compiler.plan.torque import TorqueLimits, exceeds
from rmot.compiler.plan.robot_model import RobotModel

__all__ = ["TimedChain", "chain_accel_share", "time_chain"]



@dataclass(frozen=True, eq=False)
class TimedChain:
    piece: Piece
    starts: tuple[float, ...]  # s, local time each segment starts
    ends: tuple[float, ...]  # s, local time each segment ends (zone entry when blended)
    radii: tuple[float, ...]
    path: ChainPath | None
    error: str | None = None  # a timing problem (time too short, no timing found), user-facing
    error_is_time: bool = False
    stops: tuple[int, ...] = ()  # corners (segment indexes) turned into exact stops because the chain could not be timed
    error_at: int | None = None  # the segment the error belongs to (None: the chain's last)
    stop_reason: str = ""  # why the chain could not be timed as a whole (with `stops`)


def chain_accel_share(segments: list[Segment]) -> float:
    """The share of the joint acceleration limits a chain is timed with: the smallest
    joint_accel of its moves (one constant set of limits per chain), recorded on every move's
    InstructionRecord for the backends to print."""
    return min(s.move.motion.joint_accel for s in segments)


def _limits(robot: RobotModel, segments: list[Segment]) -> tuple[np.ndarray, np.ndarray]:
    """Joint velocity limits (full; joint_speed applies per point, see ChainPath.vscale) and
    joint acceleration limits (amax times the smallest joint_accel of the chain)."""
    return robot.velocity_limits.copy(), robot.accel_limits * chain_accel_share(segments)


def time_chain(robot: RobotModel, segments: list[Segment],
               torque: TorqueLimits | None = None) -> TimedChain:
    """Time segments (len >= 1) joined by their zones; segments[-1] ends at rest. `torque`: the
    task's joint torque limits (compiler/plan/torque.py), None where the robot has no ratings."""
    vmax, amax = _limits(robot, segments)
    duration = segments[0].move.motion.duration if len(segments) == 1 else None
    floor = segments[0].move.motion.min_duration if len(segments) == 1 else None  # external axes moving with the arm
    if len(segments) == 1 and segments[0].move.kind is ir.MotionKind.JOINT:
        timed = _joint_chain(segments[0], vmax * segments[0].speed_factor, amax, duration, torque)
        if floor is not None and timed.piece.duration < floor:
            timed = _joint_chain(segments[0], vmax * segments[0].speed_factor, amax, floor, torque)
            if duration is not None and timed.error is None:  # the programmed time cannot hold: say so
                error = (f"time must be at least the {floor:.3f} s the external axes need for their move "
                         f"(got {duration:.3f} s)")
                timed = replace(timed, error=error, error_is_time=True)
        return timed
    path = blend_chain(robot, segments)
    return _path_chain(path, segments, vmax, amax, duration, torque)


def _joint_chain(seg: Segment, vmax: np.ndarray, amax: np.ndarray, duration: float | None,
                 limits: TorqueLimits | None) -> TimedChain:
    error = None
    try:
        piece = joint_move_piece(seg.q[0], seg.q[-1], vmax, amax, duration)
    except TimingError as exc:
        error = str(exc)
        piece = joint_move_piece(seg.q[0], seg.q[-1], vmax, amax, None)
    if limits is not None and exceeds(limits, piece):
        slower = _line_piece(seg.q[0], seg.q[-1], vmax, amax, limits)
        if slower is not None:
            piece, error = slower, None
            if duration is not None:
                if duration < piece.duration * (1 - 1e-9):
                    error = (f"time must be at least the fastest feasible {piece.duration:.3f} s "
                             f"(got {duration:.3f} s)")
                else:
                    piece = stretched(piece, duration)
    return TimedChain(piece, (0.0,), (piece.duration,), (0.0,), None, error, error is not None)


def _line_piece(q0: np.ndarray, q1: np.ndarray, vmax: np.ndarray, amax: np.ndarray,
                limits: TorqueLimits) -> PathPiece | None:
    """The straight joint-space line q0 -> q1 timed with the torque rows (None: no such timing,
    e.g. the payload's weight alone exceeds a rating; the verification then reports the torque)."""
    length = float(np.linalg.norm(q1 - q0))
    if length < 1e-9:
        return None
    ss = np.linspace(0.0, length, max(2, int(np.ceil(length / 0.05)) + 1))
    waypoints = q0 + (ss / length)[:, None] * (q1 - q0)
    try:
        return path_piece(waypoints, ss, vmax, amax, len(q0), torque=limits)
    except TimingError:
        return None


def _torque_limited(piece: PathPiece, args: tuple[Any, ...], kwargs: dict[str, Any],
                    limits: TorqueLimits | None) -> PathPiece:
    """`piece` (path_piece(*args, **kwargs)), or the same path timed again with the task's torque
    `limits` where its torques exceed them (unchanged if that timing fails)."""
    if limits is None or not exceeds(limits, piece):
        return piece
    try:
        return path_piece(*args, **kwargs, torque=limits)
    except TimingError:
        return piece


def _path_chain(path: ChainPath, segments, vmax, amax, duration, torque) -> TimedChain:  # type: ignore[no-untyped-def]
    dof = path.q.shape[1]
    ss = path.ss
    if ss[-1] < 1e-9:
        hold = HoldPiece(path.q[-1].copy(), duration or 0.0)
        zeros = tuple(0.0 for _ in segments)
        return TimedChain(hold, zeros, tuple(hold.duration for _ in segments), path.radii, path)
    keep = np.concatenate([[True], np.diff(ss) > 1e-10])
    tcp_kw: dict[str, Any] = {}
    if any(s.tcp_rate > 0 for s in segments) and path.tcp_speed is not None \
            and path.tcp_accel is not None:
        tcp_kw = dict(tcp=path.tcp[keep], tcp_speed=path.tcp_speed[keep], tcp_accel=path.tcp_accel[keep])
    vscale = path.vscale[keep]
    vlim = vmax.copy()
    if np.all(vscale == vscale[0]):  # one share for the whole chain: a plain constant limit
        vlim *= vscale[0]
        vscale = None
    error = None
    try:
        args = (path.q[keep], ss[keep], vlim, amax, dof, vscale)
        piece = _torque_limited(path_piece(*args, **tcp_kw), args, tcp_kw, torque)
    except TimingError as exc:
        return _stopped_chain(segments, vmax, amax, str(exc), torque)
    if duration is not None:
        if duration < piece.duration * (1 - 1e-9):
            error = f"time must be at least the fastest feasible {piece.duration:.3f} s (got {duration:.3f} s)"
        else:
            piece = stretched(piece, duration)
    starts = tuple(piece.time_at(float(ss[i])) for i in path.starts)
    ends = tuple(piece.time_at(float(ss[i])) for i in path.ends)
    ends = ends[:-1] + (piece.duration,)
    return TimedChain(piece, starts, ends, path.radii, path, error, error is not None)


@dataclass(frozen=True, eq=False)
class SequencePiece(Piece):
    """Pieces one after the other (a chain whose corners became exact stops)."""

    pieces: tuple[Piece, ...]
    dof: int

    @property
    def duration(self) -> float:  # type: ignore[override]
        return float(sum(p.duration for p in self.pieces))

    def sample(self, tl: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        bounds = np.concatenate([[0.0], np.cumsum([p.duration for p in self.pieces])])
        which = np.clip(np.searchsorted(bounds, tl, side="right") - 1, 0, len(self.pieces) - 1)
        out = [np.empty((len(tl), self.dof)) for _ in range(3)]
        for k in np.unique(which):
            sel = which == k
            for o, v in zip(out, self.pieces[k].sample(np.asarray(tl)[sel] - bounds[k])):
                o[sel] = v
        return out[0], out[1], out[2]


def _stopped_chain(segments, vmax, amax, message: str, torque) -> TimedChain:  # type: ignore[no-untyped-def]
    """The chain could not be timed as a whole: every move on its own, exact stops at the
    corners (reported by the caller at each stop's move and time). A move that cannot be
    timed even on its own keeps its error (E228) at its move; the robot then holds there."""
    pieces, starts, ends, error, error_at = [], [], [], None, None
    t = 0.0
    for k, seg in enumerate(segments):
        single = time_chain_single(seg, vmax, amax, torque)
        if single.error is not None and error is None:
            error, error_at = single.error, k
        pieces.append(single.piece)
        starts.append(t)
        t += single.piece.duration
        ends.append(t)
    dof = segments[0].q.shape[1]
    return TimedChain(SequencePiece(tuple(pieces), dof), tuple(starts), tuple(ends),
                      tuple(0.0 for _ in segments), None, error, False, tuple(range(len(segments) - 1)),
                      error_at, message)


def time_chain_single(seg: Segment, vmax: np.ndarray, amax: np.ndarray,
                      torque: TorqueLimits | None = None) -> TimedChain:
    """One move from rest to rest (no zone), never raising: a move that cannot be timed holds
    at its start with the reason in `error`."""
    if seg.move.kind is ir.MotionKind.JOINT:
        return _joint_chain(seg, vmax * seg.speed_factor, amax, None, torque)
    path = blend_chain(None, [seg])  # one move: no corner, no robot needed
    try:
        return _path_chain_strict(path, [seg], vmax, amax, torque)
    except TimingError as exc:
        return TimedChain(HoldPiece(seg.q[0].copy(), 0.0), (0.0,), (0.0,), (0.0,), None, str(exc), False)


def _path_chain_strict(path: ChainPath, segments, vmax, amax, torque) -> TimedChain:  # type: ignore[no-untyped-def]
    dof = path.q.shape[1]
    ss = path.ss
    if ss[-1] < 1e-9:
        hold = HoldPiece(path.q[-1].copy(), 0.0)
        return TimedChain(hold, (0.0,), (0.0,), (0.0,), path)
    keep = np.concatenate([[True], np.diff(ss) > 1e-10])
    tcp_kw: dict[str, Any] = {}
    if path.tcp_speed is not None and path.tcp_accel is not None \
            and np.any(np.isfinite(path.tcp_speed)):
        tcp_kw = dict(tcp=path.tcp[keep], tcp_speed=path.tcp_speed[keep], tcp_accel=path.tcp_accel[keep])
    args = (path.q[keep], ss[keep], vmax * segments[0].speed_factor, amax, dof, None)
    piece = _torque_limited(path_piece(*args, **tcp_kw), args, tcp_kw, torque)
    return TimedChain(piece, (0.0,), (piece.duration,), (0.0,), path)
