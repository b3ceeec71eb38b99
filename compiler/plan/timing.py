"""Timing: ruckig for point-to-point joint moves, toppra for geometric paths, as `Piece`s.

A Piece is one stretch of a task's timeline: `duration` (s) and `sample(tl)` giving
(q, qd, qdd), each (N, dof), at local times tl (N,) in [0, duration].

* Joint moves from rest to rest: ruckig, jerk-limited, *phase*-synchronised (all joints start
  and stop together and the joint path stays the straight line). The jerk limit is derived from
  the acceleration limit, jmax = JERK_PER_ACCEL * amax (full acceleration is reached in 0.1 s);
  controllers publish no jerk limits, so this is a documented estimate.
  Only the offline `calculate` is used; never ruckig's intermediate positions (its free build
  sends those to a cloud server).
* Geometric paths (Cartesian moves, blended chains): toppra with joint velocity and
  acceleration constraints. toppra holds its limits only at its grid points, so the result is
  re-checked on a dense time grid (0.25 ms, plus toppra's own grid times): first the grid is
  refined where a limit was exceeded (`_REFINE_ROUNDS` times), then the offending limits are
  tightened (up to `_RETIME_ROUNDS` runs in all), and whatever excess remains is removed by a
  uniform time stretch (velocity scales by 1/k, acceleration by 1/k^2), so every sample ends
  within the limits. The TCP speed is a limit on the path speed itself (`rate`, linear
  between waypoints, which are all on toppra's grid), not a spline coordinate: a spline's
  slope rings where the TCP-per-joint ratio jumps, and the re-timing then slowed whole chains
  (issue 4: a weld seam at 7.9 of 12 mm/s). The parametrisation is toppra's
  constant-acceleration one, re-implemented here vectorised and invertible (`ConstAccelTiming`: the time at a path point, for records).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = [
    "ConstAccelTiming", "HoldPiece", "JERK_PER_ACCEL", "PathPiece", "Piece", "RuckigPiece", "TimingError",
    "joint_move_piece", "path_piece", "stretched",
]

JERK_PER_ACCEL = 10.0  # 1/s: jmax = 10 * amax
_RETIME_ROUNDS = 4
_REFINE_ROUNDS = 2
_GRID_PER_WAYPOINT, _GRID_MIN, _GRID_MAX = 1.0, 40, 400
_V_MARGIN = 1e-6  # relative headroom kept below the limits after re-checking
_A_MARGIN = 1e-4
_MIN_CELL = 0.05  # smallest grid cell, as a share of the uniform spacing
_NO_LIMIT = 1e9  # a bound that never binds (toppra needs finite limits)


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
class RuckigPiece(Piece):
    trajectory: object  # ruckig.Trajectory
    duration: float
    dof: int

    def sample(self, tl: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        out = np.empty((3, len(tl), self.dof))
        for i, t in enumerate(np.clip(tl, 0.0, self.duration)):
            p, v, a = self.trajectory.at_time(float(t))  # type: ignore[attr-defined]
            out[0, i], out[1, i], out[2, i] = p, v, a
        return out[0], out[1], out[2]


@dataclass(frozen=True, eq=False)
class ConstAccelTiming:
    """A path timed piecewise at constant path acceleration between grid points (what toppra's
    ParametrizeConstAccel does), evaluated vectorised and invertible (t at a given s).

    path: a toppra SplineInterpolator over s; ss (K,) grid; sd (K,) path speeds at the grid.
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


# --------------------------------------------------------------------------- ruckig


def joint_move_piece(
    q0: np.ndarray, q1: np.ndarray, vmax: np.ndarray, amax: np.ndarray, duration: float | None = None
) -> Piece:
    """Rest-to-rest, phase-synchronised, jerk-limited joint motion q0 -> q1 (dof,).

    duration: a fixed duration (s) from a `time` modifier; raises TimingError if shorter than
    the fastest feasible motion.
    """
    from ruckig import InputParameter, Result, Synchronization, Trajectory

    dof = q0.shape[0]
    if float(np.max(np.abs(q1 - q0))) < 1e-12:
        return HoldPiece(q0.copy(), duration or 0.0)
    inp = InputParameter(dof)
    inp.current_position, inp.target_position = q0.tolist(), q1.tolist()
    inp.current_velocity = inp.current_acceleration = [0.0] * dof
    inp.target_velocity = inp.target_acceleration = [0.0] * dof
    inp.max_velocity, inp.max_acceleration = vmax.tolist(), amax.tolist()
    inp.max_jerk = (JERK_PER_ACCEL * amax).tolist()
    inp.synchronization = Synchronization.Phase
    traj = Trajectory(dof)
    _ruckig_ok(_calculate(inp, traj, dof), Result)
    if duration is not None:
        if duration < traj.duration * (1 - 1e-9):
            raise TimingError(
                f"time must be at least the fastest feasible {traj.duration:.3f} s (got {duration:.3f} s)"
            )
        inp.minimum_duration = duration
        traj = Trajectory(dof)
        _ruckig_ok(_calculate(inp, traj, dof), Result)
    return RuckigPiece(traj, float(traj.duration), dof)


def _calculate(inp: object, traj: object, dof: int) -> object:
    """Ruckig's calculate; on ruckig's "error in step 1/2" exception (seen at knife-edge
    distances where the profile just reaches full acceleration, e.g. 12 deg at 150 deg/s,
    600 deg/s^2, jerk 10x: issue #20) once more with the jerk limit 1e-9 lower, which moves
    the input off the edge and changes the duration by about 1e-10 s; then a TimingError."""
    from ruckig import Ruckig, RuckigError

    try:
        return Ruckig(dof).calculate(inp, traj)
    except RuckigError:
        inp.max_jerk = [j * (1 - 1e-9) for j in inp.max_jerk]  # type: ignore[attr-defined]
    try:
        return Ruckig(dof).calculate(inp, traj)
    except RuckigError as exc:
        raise TimingError(f"ruckig could not compute this joint move ({str(exc).strip().splitlines()[0]})") from None


def _ruckig_ok(result: object, Result: type) -> None:  # noqa: N803 - ruckig's enum
    """Map every ruckig Result to success or a TimingError with a readable reason."""
    reasons = {
        Result.Error: "ruckig reported an unspecified error",  # type: ignore[attr-defined]
        Result.ErrorInvalidInput: "ruckig rejected the input (limits must be positive and finite)",  # type: ignore[attr-defined]
        Result.ErrorExecutionTimeCalculation: "ruckig could not compute the motion's duration",  # type: ignore[attr-defined]
        Result.ErrorPositionalLimits: "ruckig's motion would leave the position limits",  # type: ignore[attr-defined]
        Result.ErrorSynchronizationCalculation: "ruckig could not synchronise the joints",  # type: ignore[attr-defined]
    }
    if result in (Result.Working, Result.Finished):  # type: ignore[attr-defined]
        return
    raise TimingError(reasons.get(result, f"ruckig returned {result}"))


# --------------------------------------------------------------------------- toppra


def path_piece(
    waypoints: np.ndarray, ss: np.ndarray, vlim: np.ndarray, alim: np.ndarray, dof: int,
    vscale: np.ndarray | None = None, check_dt: float = 0.00025, rate: np.ndarray | None = None,
) -> PathPiece:
    """Time-optimal rest-to-rest timing of the path through waypoints (M, n) at ss (M,).

    vlim, alim: (n,) symmetric limits of every coordinate (joints first, then extra
    coordinates such as the TCP-time coordinate); vscale (M,) optional factors on the joint
    velocity limits per waypoint (a joint move's joint_speed within a chain). rate (M,)
    optional: a limit on the path speed itself, ds/dt <= 1 / rate(s), rate given at the
    waypoints and linear between them (the TCP speed: rate = TCP time per unit of s, s/m
    over the programmed speed; 0 = no limit). Raises TimingError if toppra fails.
    The result respects the joint limits, the path-speed limit and the extra coordinates'
    velocity limits at every point of a `check_dt` grid (see module doc). The path-speed limit
    is evaluated from `rate` itself, not from a spline coordinate (whose slope rings where the
    TCP-per-joint ratio changes abruptly, e.g. where an arc starts to turn the tool), and
    toppra's grid holds every waypoint (see _initial_grid). The extra coordinates'
    acceleration limits are passed to toppra but not re-checked: the TCP coordinate has a kink
    where a joint move meets a Cartesian one, which the spline rounds off into acceleration
    spikes that are not physical; re-timing for them would slow the whole chain for nothing.
    """
    if rate is not None:  # the path parameter itself as a last coordinate (slope 1), limited by rate
        waypoints = np.hstack([waypoints, ss[:, None]])
        vlim, alim = np.append(vlim, 1.0), np.append(alim, _NO_LIMIT)
    base_v, base_a = vlim.astype(float).copy(), alim.astype(float).copy()
    # toppra meets its limits exactly at the grid points: ask for a hair less than allowed
    vlim, alim = base_v * (1 - 2 * _V_MARGIN), base_a * (1 - 2 * _A_MARGIN)
    grid_scale, exact_scale = _speed_limits(ss, vscale, rate, len(vlim), dof)
    path = _spline(ss, waypoints)
    grid = _initial_grid(ss)
    for attempt in range(_RETIME_ROUNDS + 1):
        traj = _toppra(path, grid, vlim, alim, grid_scale(grid) if grid_scale else None)
        rv, ra, bad_s = _ratios(traj, base_v, base_a, check_dt, dof, exact_scale)
        if not bad_s.size or attempt == _RETIME_ROUNDS:
            break
        if attempt < _REFINE_ROUNDS:  # first refine the grid where the limits were exceeded
            grid = _refined(grid, bad_s)
        else:  # then tighten the limits of the offending coordinates
            vlim = vlim / np.maximum(1.0, rv * (1 + 10 * _V_MARGIN))
            alim = alim / np.maximum(1.0, ra * (1 + 10 * _A_MARGIN))
    scale = max(1.0, float(np.max(rv)) * (1 + _V_MARGIN), math.sqrt(float(np.max(ra)) * (1 + _A_MARGIN)))
    return PathPiece(traj, float(traj.duration), scale, dof)


def _spline(ss: np.ndarray, waypoints: np.ndarray) -> object:
    import toppra

    return toppra.SplineInterpolator(ss, waypoints)


def _initial_grid(ss: np.ndarray) -> np.ndarray:
    """toppra's grid: the waypoints (every k-th one beyond _GRID_MAX of them) and as many
    uniform points (_GRID_MIN to _GRID_MAX). Waypoints are where a limit may change slope or
    jump (the path-speed limit is linear between them) and are dense where the path is
    detailed; the uniform points keep the grid fine where waypoints are sparse (a straight
    line needs few), so that toppra's piecewise-constant acceleration stays near optimal."""
    k = max(1, int(math.ceil(len(ss) / (_GRID_PER_WAYPOINT * _GRID_MAX))))
    n = int(np.clip(_GRID_PER_WAYPOINT * len(ss), _GRID_MIN, _GRID_MAX))
    grid = np.union1d(np.union1d(ss[::k], ss[-1:]), np.linspace(ss[0], ss[-1], n))
    # no sliver cells: toppra's constant acceleration across a near-zero interval is unbounded
    # (a limit jump inside a merged cell is still seen, see _grid_factors and _grid_rate)
    grid = grid[np.concatenate([[True], np.diff(grid) >= _MIN_CELL * (ss[-1] - ss[0]) / n])]
    grid[-1] = ss[-1]
    return grid


def _interval_factors(ss: np.ndarray, vscale: np.ndarray | None, n: int, dof: int) -> np.ndarray:
    """(M-1, n) factors on the velocity limits inside each waypoint interval: the smaller
    vscale of its two waypoints on the joints, 1 elsewhere."""
    out = np.ones((len(ss) - 1, n))
    if vscale is not None:
        out[:, :dof] = np.minimum(vscale[:-1], vscale[1:])[:, None]
    return out


def _speed_limits(ss: np.ndarray, vscale: np.ndarray | None, rate: np.ndarray | None, n: int, dof: int):  # type: ignore[no-untyped-def]
    """(for toppra: grid (K,) -> s -> (n,) factors, exact: s (N,) -> (N, n) factors) on the
    velocity limits, or (None, None) when every factor is 1. The joints' factors are constant
    per waypoint interval; the path-speed limit (last coordinate, when rate is given) is
    1 / rate with rate linear between waypoints."""
    if (vscale is None or np.all(vscale == 1.0)) and rate is None:
        return None, None
    factors = _interval_factors(ss, vscale, n, dof)
    last = len(factors) - 1

    def exact(s: np.ndarray) -> np.ndarray:
        out = factors[np.clip(np.searchsorted(ss, s, side="right") - 1, 0, last)]
        if rate is not None:
            out = out.copy()
            out[:, -1] = 1.0 / np.maximum(np.interp(s, ss, rate), 1.0 / _NO_LIMIT)
        return out

    def for_grid(grid: np.ndarray):  # type: ignore[no-untyped-def]
        per_point = _grid_factors(ss, factors, grid)
        if rate is not None:
            per_point[:, -1] = 1.0 / np.maximum(_grid_rate(ss, rate, grid), 1.0 / _NO_LIMIT)
        tol = 1e-12 * max(1.0, abs(float(grid[-1])))

        def at(s: np.ndarray) -> np.ndarray:
            return per_point[np.clip(np.searchsorted(grid, s - tol), 0, len(grid) - 1)]

        return at

    return for_grid, exact


def _grid_factors(ss: np.ndarray, factors: np.ndarray, grid: np.ndarray) -> np.ndarray:
    """(K, n) factors for toppra at the grid points (K,): the smallest over every waypoint
    interval that meets [previous grid point, next grid point]. Between two grid points
    toppra's path speed squared is linear in s, so its speed stays below the larger end value,
    and both end values are then below every limit inside the interval: the limits hold
    everywhere, not only at the grid points, even where a limit jumps between grid points."""
    last = len(factors) - 1
    lo = np.clip(np.searchsorted(ss, grid[:-1], side="right") - 1, 0, last)  # interval holding each cell's start
    hi = np.clip(np.searchsorted(ss, grid[1:], side="left") - 1, lo, last)  # ... and its end
    # reduceat takes the min over [lo[i], lo[i+1]) (just lo[i] where they are equal); hi[i] is
    # lo[i+1] or the one before it
    cell = np.minimum(np.minimum.reduceat(factors, lo, axis=0), factors[hi])
    return np.vstack([cell[:1], np.minimum(cell[:-1], cell[1:]), cell[-1:]])


def _grid_rate(ss: np.ndarray, rate: np.ndarray, grid: np.ndarray) -> np.ndarray:
    """(K,) the path-speed rate toppra must respect at each grid point: its value there, or
    the largest at a waypoint strictly between the neighbouring grid points (where the grid
    skips waypoints, a peak of the rate between grid points must not be missed)."""
    at = np.interp(grid, ss, rate)
    inner = np.full(len(grid) - 1, -np.inf)  # per cell, the largest rate at a waypoint inside
    lo = np.searchsorted(ss, grid[:-1], side="right")
    hi = np.searchsorted(ss, grid[1:], side="left")
    has = hi > lo
    if np.any(has):  # only where the grid skips waypoints (long paths): a few hundred cells at most
        inner[has] = [rate[a:b].max() for a, b in zip(lo[has], hi[has])]
    return np.maximum(at, np.maximum(np.append(-np.inf, inner), np.append(inner, -np.inf)))


def _toppra(path: object, grid: np.ndarray, vlim: np.ndarray, alim: np.ndarray, scale_at=None) -> ConstAccelTiming:  # type: ignore[no-untyped-def]
    import toppra
    import toppra.algorithm as algo
    import toppra.constraint as constraint

    toppra.setup_logging("CRITICAL")
    if scale_at is None:
        velocity = constraint.JointVelocityConstraint(np.stack([-vlim, vlim], axis=1))
    else:
        def varying(s: float) -> np.ndarray:
            v = vlim * scale_at(np.array([s]))[0]
            return np.stack([-v, v], axis=1)

        velocity = constraint.JointVelocityConstraintVarying(varying)
    cons = [
        velocity,
        constraint.JointAccelerationConstraint(np.stack([-alim, alim], axis=1)),
    ]
    instance = algo.TOPPRA(cons, path, gridpoints=grid)
    result = instance.compute_parameterization(0.0, 0.0)
    sd_vec = result[1] if result is not None else None
    if sd_vec is None or not np.all(np.isfinite(sd_vec)):
        raise TimingError("toppra found no feasible timing for the path (the path may be non-smooth)")
    sd = np.sqrt(np.maximum(np.asarray(sd_vec, dtype=float) ** 2, 0.0))
    sd[0] = sd[-1] = 0.0
    return ConstAccelTiming(path, grid, sd)


_MAX_CHECK_POINTS = 200_000  # policy: long (slow) moves are checked on a coarser grid than 0.25 ms


def _ratios(
    traj: ConstAccelTiming, vlim: np.ndarray, alim: np.ndarray, dt: float, dof: int, scale_at=None  # type: ignore[no-untyped-def]
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """On a dense time grid, per coordinate: max |velocity| / vlim and max |acceleration| /
    alim (joints only: extra coordinates' accelerations are shaping limits), and the path
    parameters s where a limit (less its margin) is exceeded."""
    duration = traj.duration
    # at most _MAX_CHECK_POINTS: a 10-minute move at 0.25 ms would be 2.4 million (1.3 GB, issue #20)
    dense = np.linspace(0.0, duration, max(3, min(int(math.ceil(duration / dt)) + 1, _MAX_CHECK_POINTS)))
    ts = np.union1d(dense, traj.ts)  # type: ignore[attr-defined] - and toppra's own grid times
    _, xd, xdd = _eval(traj, ts)
    rel_v = np.abs(xd) / (vlim if scale_at is None else vlim * scale_at(traj.params(ts)[0]))
    rel_a = np.abs(xdd[:, :dof]) / alim[:dof]
    over = np.any(rel_v > 1 - _V_MARGIN, axis=1) | np.any(rel_a > 1 - _A_MARGIN, axis=1)
    ra = np.zeros(len(vlim))
    ra[:dof] = np.max(rel_a, axis=0)
    return np.max(rel_v, axis=0), ra, traj.params(ts[over])[0]


def _refined(grid: np.ndarray, bad_s: np.ndarray) -> np.ndarray:
    """The grid with each interval containing a bad s (and its two neighbours) split in four."""
    idx = np.unique(np.clip(np.searchsorted(grid, bad_s) - 1, 0, len(grid) - 2))
    idx = np.unique(np.clip(np.concatenate([idx - 1, idx, idx + 1]), 0, len(grid) - 2))
    lo, hi = grid[idx], grid[idx + 1]
    extra = (lo[:, None] + (hi - lo)[:, None] * np.array([0.25, 0.5, 0.75])).ravel()
    return np.union1d(grid, extra)
