"""Timing: one motion model for every motion, as `Piece`s.

A Piece is one stretch of a task's timeline: `duration` (s) and `sample(tl)` giving
(q, qd, qdd), each (N, dof), at local times tl (N,) in [0, duration].

The motion model (lang/REFERENCE.md section 6) is acceleration-limited, with no jerk limit,
for every motion alike: the fastest timing of the joint path under the joint velocity and
acceleration limits and, on linear and circular moves, the TCP path speed and TCP path
acceleration limits. (Controllers publish no jerk limits; the joint acceleration limits are
effective values, see sim/robots/library.py.)

* Joint moves from rest to rest (`joint_move_piece`): a straight line in joint space, all
  joints starting and stopping together; the fastest timing of a straight line is the
  trapezoidal (or triangular) speed profile, computed exactly.
* Geometric paths (Cartesian moves, blended chains, `path_piece`): the time-optimal
  parametrisation on a dense grid (compiler/plan/topp.py), every waypoint on the grid and
  every waypoint interval split (`_GRID_STEP`); cost linear in the path's length. The
  limits are re-checked at the end and the middle of every grid cell; where one is exceeded
  only that spot's limits are tightened and the passes re-run (`_REPAIR_ROUNDS`); a remaining
  excess (never seen in practice, kept as a guarantee) is removed by a uniform time stretch.
The parametrisation is piecewise constant path acceleration (`ConstAccelTiming`: evaluated
vectorised, invertible for the time at a path point).
"""

from __future__ import annotations

from typing import Any
import math
from dataclasses import dataclass

import numpy as np

from rmot.compiler.plan.cubic import CubicSpline

__all__ = [
    "ConstAccelTiming", "HoldPiece", "PathPiece", "Piece", "TimingError",
    "joint_move_piece", "path_piece", "stretched",
]

_REPAIR_ROUNDS = 12
# the refinement may grow a path's grid to this many times its first size or this many points,
# whichever is more; past that it repairs in place (a limit violated nearly everywhere, e.g. a
# torque limit under an absurd payload, would otherwise quadruple the grid every round: 4^5)
_MAX_GROWTH = 16
_MAX_REFINED_POINTS = 100_000
_REFINE_ROUNDS = 5  # first split the cells where a limit is exceeded, this many times
_GRID_STEP = 0.004  # largest grid cell in path units (rad of joint arc, or scaled TCP length)
_GRID_SUB_MAX = 64  # at most this many cells per waypoint interval
_V_MARGIN = 1e-4  # relative headroom asked below the limits (the check allows the full limit)
_A_MARGIN = 2e-3
_CHECK_TOL = 1e-6  # relative excess the check accepts
_CHECK_AT = (0.25, 0.5, 0.75)  # where inside every grid cell the limits are re-checked (and at its end)


class TimingError(ValueError):
    """Timing found no solution; the message is user-facing."""


class Piece:
    duration: float
    dof: int

    def sample(self, tl: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        raise NotImplementedError

    def end_q(self) -> np.ndarray:
        return self.sample(np.array([self.duration]))[0][0]


@dataclass(frozen=True, eq=False)
class HoldPiece(Piece):
    """Standing still at q (dof,) for `duration` s."""

    q: np.ndarray
    duration: float

    @property
    def dof(self) -> int:  # type: ignore[override]
        return self.q.shape[0]

    def sample(self, tl: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        n = len(tl)
        z = np.zeros((n, self.dof))
        return np.tile(self.q, (n, 1)), z, z.copy()


@dataclass(frozen=True, eq=False)
class ConstAccelTiming:
    """A path timed piecewise at constant path acceleration between grid points (what toppra's
    ParametrizeConstAccel does), evaluated vectorised and invertible (t at a given s).

    path: a cubic spline q(s) (_PathSpline); ss (K,) grid; sd (K,) path speeds at the grid.
    """

    path: object
    ss: np.ndarray
    sd: np.ndarray

    def __post_init__(self) -> None:
        ds = np.diff(self.ss)
        sdd = (self.sd[1:] ** 2 - self.sd[:-1] ** 2) / (2 * ds)
        dt = 2 * ds / np.maximum(self.sd[1:] + self.sd[:-1], 1e-300)
        object.__setattr__(self, "sdd", sdd)
        object.__setattr__(self, "ts", np.concatenate([[0.0], np.cumsum(dt)]))

    @property
    def duration(self) -> float:
        return float(self.ts[-1])  # type: ignore[attr-defined]

    def params(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """s, ds/dt, d2s/dt2 at times t (N,)."""
        ts, sdd = self.ts, self.sdd  # type: ignore[attr-defined]
        i = np.clip(np.searchsorted(ts, t, side="right") - 1, 0, len(sdd) - 1)
        dt = t - ts[i]
        s = np.minimum(self.ss[i] + self.sd[i] * dt + 0.5 * sdd[i] * dt * dt, self.ss[-1])
        return s, np.maximum(self.sd[i] + sdd[i] * dt, 0.0), sdd[i]

    def __call__(self, t: np.ndarray, order: int = 0) -> np.ndarray:
        s, v, a = self.params(np.asarray(t, dtype=float))
        path = self.path
        if order == 0:
            return path(s)  # type: ignore[operator]
        if order == 1:
            return path(s, 1) * v[:, None]  # type: ignore[operator]
        return path(s, 2) * (v * v)[:, None] + path(s, 1) * a[:, None]  # type: ignore[operator]

    def evaluate(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Position, velocity and acceleration (N, n) at times t (N,), in one pass."""
        s, v, a = self.params(np.asarray(t, dtype=float))
        path = self.path
        d1, d2 = path(s, 1), path(s, 2)  # type: ignore[operator]
        return path(s), d1 * v[:, None], d2 * (v * v)[:, None] + d1 * a[:, None]  # type: ignore[operator]

    def time_at(self, s: float) -> float:
        """The time (s) at which the path parameter reaches s."""
        ts, sdd = self.ts, self.sdd  # type: ignore[attr-defined]
        i = int(np.clip(np.searchsorted(self.ss, s, side="right") - 1, 0, len(sdd) - 1))
        ds, v0, a = s - self.ss[i], self.sd[i], sdd[i]
        if ds <= 0:
            return float(ts[i])
        if abs(a) < 1e-12:
            return float(ts[i] + ds / max(v0, 1e-300))
        disc = max(v0 * v0 + 2 * a * ds, 0.0)
        return float(min(ts[i] + (np.sqrt(disc) - v0) / a, ts[i + 1]))


@dataclass(frozen=True, eq=False)
class PathPiece(Piece):
    """A timed path, stretched by `scale` >= 1; only the first `dof` coordinates are joints
    (extra coordinates, such as the TCP-speed coordinate, are dropped)."""

    trajectory: ConstAccelTiming
    native_duration: float
    scale: float
    dof: int

    @property
    def duration(self) -> float:  # type: ignore[override]
        return self.native_duration * self.scale

    def sample(self, tl: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        x, xd, xdd = _eval(self.trajectory, np.clip(tl / self.scale, 0.0, self.native_duration))
        k = self.scale
        return x[:, : self.dof], xd[:, : self.dof] / k, xdd[:, : self.dof] / (k * k)

    def time_at(self, s: float) -> float:
        """Local time (s) at which the path parameter reaches s."""
        return self.trajectory.time_at(s) * self.scale


def stretched(piece: PathPiece, duration: float) -> PathPiece:
    """The same path timed to last exactly `duration` (>= piece.duration)."""
    return PathPiece(piece.trajectory, piece.native_duration, duration / piece.native_duration, piece.dof)


def _eval(traj: ConstAccelTiming, ts: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    return traj.evaluate(ts)


# --------------------------------------------------------------------------- joint moves


@dataclass(frozen=True, eq=False)
class _Line:
    """The straight joint-space path q0 + s * unit, s in [0, length] (a path for ConstAccelTiming)."""

    q0: np.ndarray
    unit: np.ndarray

    def __call__(self, s: np.ndarray, order: int = 0) -> np.ndarray:
        s = np.asarray(s, dtype=float)
        if order == 0:
            return self.q0 + s[:, None] * self.unit
        if order == 1:
            return np.tile(self.unit, (len(s), 1))
        return np.zeros((len(s), len(self.unit)))


def joint_move_piece(
    q0: np.ndarray, q1: np.ndarray, vmax: np.ndarray, amax: np.ndarray, duration: float | None = None
) -> Piece:
    """Rest-to-rest, synchronised joint motion q0 -> q1 (dof,) on the joint-space line: the
    exact time-optimal trapezoid (triangle when the top speed is not reached).

    duration: a fixed duration (s) from a `time` modifier; raises TimingError if shorter than
    the fastest feasible motion (the motion is then stretched uniformly).
    """
    dof = q0.shape[0]
    delta = q1 - q0
    length = float(np.linalg.norm(delta))
    if float(np.max(np.abs(delta))) < 1e-12:
        return HoldPiece(q0.copy(), duration or 0.0)
    unit = delta / length
    moving = np.abs(unit) > 1e-15
    if not (np.all(vmax[moving] > 0) and np.all(amax[moving] > 0)):
        raise TimingError("joint speed and acceleration limits must be positive")
    v = float(np.min(vmax[moving] / np.abs(unit[moving])))  # path speed limit
    a = float(np.min(amax[moving] / np.abs(unit[moving])))  # path acceleration limit
    if v * v / a >= length:  # triangle: the top speed is never reached
        peak = math.sqrt(a * length)
        ss, sd = np.array([0.0, 0.5 * length, length]), np.array([0.0, peak, 0.0])
    else:
        ramp = 0.5 * v * v / a
        ss, sd = np.array([0.0, ramp, length - ramp, length]), np.array([0.0, v, v, 0.0])
    traj = ConstAccelTiming(_Line(q0.astype(float).copy(), unit), ss, sd)
    piece = PathPiece(traj, traj.duration, 1.0, dof)
    if duration is not None:
        if duration < piece.duration * (1 - 1e-9):
            raise TimingError(
                f"time must be at least the fastest feasible {piece.duration:.3f} s (got {duration:.3f} s)"
            )
        piece = stretched(piece, duration)
    return piece


# --------------------------------------------------------------------------- paths


def path_piece(
    waypoints: np.ndarray, ss: np.ndarray, vlim: np.ndarray, alim: np.ndarray, dof: int | None = None,
    vscale: np.ndarray | None = None, *, tcp: np.ndarray | None = None, tcp_speed: np.ndarray | None = None,
    tcp_accel: np.ndarray | None = None, torque: object | None = None,
) -> PathPiece:
    """Time-optimal rest-to-rest timing of the joint path through waypoints (M, dof) at ss (M,).

    vlim, alim (dof,): joint velocity and acceleration limits; vscale (M,) optional factors on
    the velocity limits per waypoint (a joint move's joint_speed within a chain; inside a
    waypoint interval the smaller of its two ends applies). TCP limits, optional: tcp (M, 3)
    the TCP positions at the waypoints, tcp_speed (M,) the programmed TCP speed (m/s, inf =
    none) and tcp_accel (M,) the TCP path acceleration limit (m/s^2, inf = none); inside an
    interval the smaller of its ends. The TCP path is the cubic spline through `tcp` over
    ss (the waypoints are the dense IK points, within 0.05 mm of the path).
    torque: optional joint torque limits (compiler/plan/torque.TorqueLimits): |tau_j| <=
    tau_max_j by inverse dynamics along the path, rows of the parametrisation like the joint
    accelerations and re-checked and repaired the same way.
    Every limit holds at both ends and the middle of every grid cell (see module doc).
    """

    waypoints = np.asarray(waypoints, dtype=float)
    dof = waypoints.shape[1] if dof is None else dof
    waypoints = waypoints[:, :dof]
    vlim, alim = np.asarray(vlim[:dof], dtype=float), np.asarray(alim[:dof], dtype=float)
    path = _PathSpline(ss, waypoints)
    spline = None
    if tcp is not None and tcp_speed is not None:
        spline = CubicSpline(ss, tcp)
    n_int = len(ss) - 1
    f_int = np.ones(n_int) if vscale is None else np.minimum(vscale[:-1], vscale[1:])
    tcp_int = None
    if spline is not None:
        assert tcp_speed is not None  # a TCP spline comes with its speed limits
        acc_int = np.minimum(tcp_accel[:-1], tcp_accel[1:]) if tcp_accel is not None else np.full(n_int, np.inf)
        tcp_int = (np.minimum(tcp_speed[:-1], tcp_speed[1:]), acc_int)
    grid, _ = _grid(ss)
    arrays = _Arrays(_Limits(path, spline, ss, vlim, alim, f_int, tcp_int, torque), grid)
    bound = max(_MAX_GROWTH * len(arrays.grid), _MAX_REFINED_POINTS)
    for attempt in range(_REFINE_ROUNDS + 1):
        rounds = 0 if attempt < _REFINE_ROUNDS else _REPAIR_ROUNDS
        x, r_acc, r_vel, bad, w_tau = arrays.solve(arrays.xmax.copy(), rounds)
        if not np.any(bad) or attempt == _REFINE_ROUNDS:
            break
        if len(arrays.grid) + 9 * np.count_nonzero(bad) > bound:
            # splitting would grow the grid past its bound (a limit violated nearly everywhere,
            # e.g. a torque limit under an absurd payload: each round would quadruple the grid):
            # repair the cells in place instead, with the same local ceilings as the last round
            x, r_acc, r_vel, bad, w_tau = arrays.solve(arrays.xmax.copy(), _REPAIR_ROUNDS)
            break
        arrays = arrays.refined(np.flatnonzero(bad))  # first split the offending cells (consumes the old)
    worst_a = float(np.max(r_acc, initial=0.0))
    worst_v = float(np.max(r_vel, initial=0.0))
    sd = np.sqrt(np.maximum(x, 0.0))
    if not np.all(np.isfinite(sd)) or np.any((sd[1:] + sd[:-1]) <= 0):
        raise TimingError("no feasible timing was found for the path (a speed limit is zero)")
    traj = ConstAccelTiming(path, arrays.grid, sd)
    scale = max(1.0, worst_v * (1 + _CHECK_TOL), math.sqrt(worst_a * (1 + _CHECK_TOL)))
    if w_tau is not None:  # a torque excess left after the repairs: x (~ 1 / scale^2) shrinks
        scale = max(scale, math.sqrt(float(np.max(w_tau, initial=0.0)) * (1 + _CHECK_TOL)))
    return PathPiece(traj, float(traj.duration), scale, dof)


def _arc_rates(spline, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:  # type: ignore[no-untyped-def]
    """TCP arc length's first and second derivative in s: |p'| and p'.p'' / |p'|."""
    p1, p2 = spline(s, 1), spline(s, 2)
    l1 = np.linalg.norm(p1, axis=1)
    l2 = np.einsum("ij,ij->i", p1, p2) / np.maximum(l1, 1e-15)
    return l1, l2


class _PathSpline:
    """q(s) and its first two derivatives: the not-a-knot cubic spline through the waypoints,
    the same interpolation as toppra's SplineInterpolator default (scipy's CubicSpline), built
    on numpy (compiler/plan/cubic.py) so that timing imports neither toppra (whose package
    imports matplotlib) nor scipy.interpolate: ~1.4 s of start-up together."""

    def __init__(self, ss: np.ndarray, waypoints: np.ndarray) -> None:
        self._constant = waypoints[0] if len(ss) == 1 else None
        if self._constant is None:
            spline = CubicSpline(ss, waypoints)
            self._orders = (spline, spline.derivative(), spline.derivative(2))

    def __call__(self, s: np.ndarray, order: int = 0) -> np.ndarray:
        if order not in (0, 1, 2):
            raise ValueError(f"derivative order must be 0, 1 or 2 (got {order})")
        if self._constant is not None:
            value = self._constant if order == 0 else np.zeros_like(self._constant)
            return np.broadcast_to(value, (*np.shape(s), len(value))).copy()
        return self._orders[order](s)


def _grid(ss: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The grid: every waypoint, and each waypoint interval split into equal cells of at most
    _GRID_STEP (at least 2, at most _GRID_SUB_MAX per interval): its size grows linearly with
    the path. Returns the grid (K,) and, per cell (K-1,), the waypoint interval holding it."""
    h = np.diff(ss)
    n = np.clip(np.ceil(h / _GRID_STEP), 2, _GRID_SUB_MAX).astype(int)
    cell_of = np.repeat(np.arange(len(h)), n)
    first = np.repeat(np.cumsum(n) - n, n)
    frac = (np.arange(len(cell_of)) - first) / np.repeat(n, n)
    grid = np.append(ss[cell_of] + frac * h[cell_of], ss[-1])
    return grid, cell_of


@dataclass(frozen=True, eq=False)
class _Limits:
    """What the limits are made of: the joint path, the TCP spline, per waypoint interval the
    joint speed share and the TCP speed and acceleration limits."""

    path: object
    spline: object
    ss: np.ndarray
    vlim: np.ndarray
    alim: np.ndarray
    f_int: np.ndarray
    tcp_int: tuple[np.ndarray, np.ndarray] | None
    torque: object | None = None  # compiler/plan/torque.TorqueLimits, or None

    def points(self, s: np.ndarray, left: np.ndarray, right: np.ndarray):  # type: ignore[no-untyped-def]
        """At grid points s with the waypoint intervals on their left and right: the joints'
        d1, d2, the acceleration rows (a, b, c asked) and the speed ratios per sqrt(x)."""
        d1, d2 = self.path(s, 1), self.path(s, 2)  # type: ignore[operator]
        f = np.minimum(self.f_int[left], self.f_int[right])
        a, b = [d1], [d2]
        c = [np.tile(self.alim, (len(s), 1))]
        vel = np.max(np.abs(d1) / (self.vlim * f[:, None]), axis=1)
        if self.spline is not None:
            assert self.tcp_int is not None
            sp = np.minimum(self.tcp_int[0][left], self.tcp_int[0][right])
            ac = np.minimum(self.tcp_int[1][left], self.tcp_int[1][right])
            l1, l2 = _arc_rates(self.spline, s)
            on = np.isfinite(ac)
            # the TCP path acceleration is held at the grid points only: between them it is not
            # re-checked, since where the TCP-per-joint ratio l' changes within a cell (a blend's
            # edge) the constant path acceleration of a cell cannot follow it, and tightening the
            # spot only slows it without end (the joints' limits, the physical ones, are checked)
            a.append(np.where(on, l1, 0.0)[:, None])
            b.append(np.where(on, l2, 0.0)[:, None])
            c.append(np.where(on, ac, np.inf)[:, None])
            vel = np.maximum(vel, l1 / sp)
        trows = None
        if self.torque is not None:  # lo <= a u + b x <= hi with lo, hi = -+tau_max - g
            q = self.path(s)  # type: ignore[operator]
            ta, tb, tc = self.torque.rows(q, d1, d2)  # type: ignore[attr-defined]
            lim = self.torque.limit * (1 - _A_MARGIN)  # type: ignore[attr-defined]
            trows = (ta, tb, lim - tc, -lim - tc)
        return d1, d2, np.hstack(a), np.hstack(b), np.hstack(c) * (1 - _A_MARGIN), vel, trows

    def cells(self, lo: np.ndarray, h: np.ndarray, interval: np.ndarray):  # type: ignore[no-untyped-def]
        """Inside cells [lo, lo + h] of the given waypoint intervals, at _CHECK_AT: the joints'
        derivatives m1, m2 (T, N, dof) and the speed ratios per sqrt(x) (T, N); with torque
        limits also the torque rows a, b, c (T + 1, N, dof) at _CHECK_AT and the cell's end."""
        m1, m2, vel = [], [], []
        f = self.f_int[interval]
        for th in _CHECK_AT:
            s = lo + th * h
            d1 = self.path(s, 1)  # type: ignore[operator]
            m1.append(d1)
            m2.append(self.path(s, 2))  # type: ignore[operator]
            v = np.max(np.abs(d1) / (self.vlim * f[:, None]), axis=1)
            if self.spline is not None:
                assert self.tcp_int is not None
                v = np.maximum(v, _arc_rates(self.spline, s)[0] / self.tcp_int[0][interval])
            vel.append(v)
        if self.torque is None:
            return np.stack(m1), np.stack(m2), np.stack(vel)
        path, torque = self.path, self.torque
        rows = [torque.rows(path(s), path(s, 1), path(s, 2))  # type: ignore[attr-defined, operator]
                for s in (lo + th * h for th in (*_CHECK_AT, 1.0))]
        ta, tb, tc = (np.stack([r[k] for r in rows]) for k in range(3))
        return np.stack(m1), np.stack(m2), np.stack(vel), ta, tb, tc


class _Arrays:
    """The limits on one grid: acceleration rows and speed ceilings at its points, and the
    joints' derivatives and speed ratios inside its cells for the re-check. `refined` splits
    cells and evaluates only the new points and cells (cost linear in what was added)."""

    def __init__(self, limits: _Limits, grid: np.ndarray, parts=None) -> None:  # type: ignore[no-untyped-def]
        self.limits, self.grid = limits, grid
        self.h = np.diff(grid)
        if parts is None:
            last = len(limits.ss) - 2
            interval = np.clip(np.searchsorted(limits.ss, 0.5 * (grid[:-1] + grid[1:]), side="right") - 1, 0, last)
            left = np.concatenate([interval[:1], interval])
            right = np.concatenate([interval, interval[-1:]])
            pts = _normalised(limits.points(grid, left, right))
            parts = (interval, pts, limits.cells(grid[:-1], self.h, interval))
        self.interval, self.pts = parts[0], parts[1]
        self.m1, self.m2, self.v_in = parts[2][:3]
        self.tau = parts[2][3:] or None  # torque rows inside the cells, with torque limits only
        d1, d2, beta, lo, hi, ceiling, vel = self.pts
        self.d1, self.d2 = d1, d2
        self.rows = (beta, lo, hi, ceiling)
        with np.errstate(divide="ignore"):
            xmax = 1.0 / vel ** 2 * (1 - _V_MARGIN) ** 2
        xmax[~np.isfinite(xmax)] = 1e18
        self.xmax = xmax

    def refined(self, bad: np.ndarray) -> _Arrays:
        """Each listed cell and its two neighbours split in four. Consumes this grid: its large
        arrays are released as they are merged (the caller keeps only the refined grid), so
        that the old and the new grid are never both held whole (peak memory)."""
        cells = np.unique(np.clip(np.concatenate([bad - 1, bad, bad + 1]), 0, len(self.h) - 1))
        lo, h, interval = self.grid[cells], self.h[cells], self.interval[cells]
        frac = np.array([0.25, 0.5, 0.75])
        extra = (lo[:, None] + h[:, None] * frac).ravel()
        extra_int = np.repeat(interval, 3)
        new_pts = _normalised(self.limits.points(extra, extra_int, extra_int))
        sub_lo = (lo[:, None] + h[:, None] * np.array([0.0, 0.25, 0.5, 0.75])).ravel()
        sub_h = np.repeat(h * 0.25, 4)
        sub_int = np.repeat(interval, 4)
        new_cells = self.limits.cells(sub_lo, sub_h, sub_int)
        # merge points (old ones keep their values) and cells (split ones replaced), each array
        # written once into its place (no concatenated copy on the way: these are the planner's
        # largest arrays)
        grid = np.concatenate([self.grid, extra])
        order = np.argsort(grid, kind="stable")
        place = _places(order, len(self.grid))
        old_pts = list(self.pts)
        self.pts = self.d1 = self.d2 = self.rows = self.xmax = None  # type: ignore[assignment]
        pts = []
        for i, new in enumerate(new_pts):
            pts.append(_merged(old_pts[i], new, place, axis=0))
            old_pts[i] = None
        keep = np.ones(len(self.h), bool)
        keep[cells] = False
        cell_lo = np.concatenate([self.grid[:-1][keep], sub_lo])
        cplace = _places(np.argsort(cell_lo, kind="stable"), int(np.count_nonzero(keep)))
        interval_all = _merged(self.interval, sub_int, cplace, axis=0, keep=keep)
        m1 = _merged(self.m1, new_cells[0], cplace, axis=1, keep=keep)
        self.m1 = None
        m2 = _merged(self.m2, new_cells[1], cplace, axis=1, keep=keep)
        self.m2 = None
        v_in = _merged(self.v_in, new_cells[2], cplace, axis=1, keep=keep)
        self.v_in = None
        tau = tuple(_merged(old, new, cplace, axis=1, keep=keep)
                    for old, new in zip(self.tau or (), new_cells[3:]))
        self.tau = None
        return _Arrays(self.limits, grid[order], (interval_all, tuple(pts), (m1, m2, v_in, *tau)))

    def solve(self, xmax: np.ndarray, rounds: int):  # type: ignore[no-untyped-def]
        """Time-optimal x on this grid, with up to `rounds` local repairs; (x, r_acc, r_vel, bad,
        w_tau) with per cell the largest acceleration and speed ratio found by the re-check (at
        the cell's end, with the cell's u and the next point's derivatives, and inside it) and,
        with torque limits, the factor x must shrink by for the torques to hold (else None)."""
        from rmot.compiler.plan import topp  # late: loads coal only when this runs

        for _ in range(rounds + 1):
            x = topp.solve(self.grid, xmax, self.rows)
            r_acc, r_vel = topp.check(x, self.h, self.d1, self.d2, self.m1, self.m2, self.v_in,
                                      _CHECK_AT, self.limits.alim)
            bad = (r_acc > 1 + _CHECK_TOL) | (r_vel > 1 + _CHECK_TOL)
            w_tau = None
            if self.tau is not None:
                ta, tb, tc = self.tau
                w_tau = topp.check_torque(x, self.h, ta, tb, tc, (*_CHECK_AT, 1.0),
                                          self.limits.torque.limit)  # type: ignore[attr-defined]
                bad |= w_tau > 1 + _CHECK_TOL
            if not np.any(bad):
                break
            # local repair: lower the speed ceiling at the offending cells' two ends only (as a
            # time stretch by k would, locally: speed / k, acceleration about / k^2)
            worst = np.maximum(r_acc, r_vel ** 2)  # per cell, in units of x
            if w_tau is not None:
                worst = np.maximum(worst, w_tau)
            cells = np.flatnonzero(bad)
            factor = 1.0 / (worst[cells] * (1 + _A_MARGIN))
            for end in (cells, cells + 1):
                np.minimum.at(xmax, end, x[end] * factor)
        return x, r_acc, r_vel, bad, w_tau


def _normalised(pts: tuple[Any, ...]) -> tuple[Any, ...]:
    """A point's (d1, d2, a, b, c, vel, torque rows) as (d1, d2, beta, lo, hi, ceiling, vel): the
    rows in the solver's form (topp.Rows.normalised, row by row), kept instead of a, b, c; the
    torque rows (a, b, hi, lo) or None, one-sided, appended after the symmetric ones."""
    from rmot.compiler.plan import topp  # late: loads coal only when this runs

    d1, d2, a, b, c, vel, trows = pts
    if trows is None:
        return (d1, d2, *topp.Rows(a, b, c).normalised(), vel)
    parts = zip(topp.Rows(a, b, c).parts(), topp.Rows(*trows).parts())
    beta, lo, hi, pure = (np.hstack(p) for p in parts)
    ceiling = np.minimum(topp.static_ceiling(beta, lo, hi), np.min(pure, axis=1, initial=np.inf))
    return d1, d2, beta, lo, hi, ceiling, vel


def _places(order: np.ndarray, n_old: int) -> tuple[np.ndarray, np.ndarray]:
    """Where the old (first n_old) and the new entries of a concatenation go once sorted by
    `order` (the inverse permutation, split)."""
    place = np.empty_like(order)
    place[order] = np.arange(len(order))
    return place[:n_old], place[n_old:]


def _merged(old: np.ndarray, new: np.ndarray, place: tuple[np.ndarray, np.ndarray], axis: int,
            keep: np.ndarray | None = None) -> np.ndarray:
    """concatenate([old (only its `keep` entries along axis, if given), new], axis)[order along
    axis], written in place (C-contiguous); axis 1: one leading row at a time (smaller temporaries)."""
    n_old = len(place[0])
    shape = list(old.shape)
    shape[axis] = n_old + new.shape[axis]
    out = np.empty(shape, dtype=np.result_type(old, new))
    kept = None if keep is None else np.flatnonzero(keep)  # take is ~4x faster than a mask
    rows = old.ndim == axis + 2  # rows of m values moved as one m-value record each (~2x faster)
    wrap = _records if rows else (lambda a: a)
    dst = wrap(out)
    if axis == 0:
        dst[place[0]] = wrap(old if kept is None else old.take(kept, axis=0))
        dst[place[1]] = wrap(new)
    else:
        for t in range(old.shape[0]):
            dst[t, place[0]] = wrap(old[t] if kept is None else old[t].take(kept, axis=0))
            dst[t, place[1]] = wrap(new[t])
    return out


def _records(a: np.ndarray) -> np.ndarray:
    """(..., n, m) floats viewed as (..., n) records of m floats (the same memory)."""
    a = np.ascontiguousarray(a)
    return a.view(np.dtype((np.void, a.dtype.itemsize * a.shape[-1])))[..., 0]
