"""Reach and singularity maps: which points of the cell the TCP reaches, and how well.

    m = reach_map(robot, base=B, tcp=T, orientation=R, grid=grid_for(robot, B, T, step))

For every grid point p (world, m) the TCP pose is (R, p) — R a fixed world orientation, or,
with orientation None, each of `ANY_ORIENTATIONS` in turn (the point counts as reached when
one of them is). The flange pose B⁻¹·(R, p)·T⁻¹ goes through the robot's own IK (every
branch, within the joint limits, each solution verified by FK); of the solutions found the
one farthest from a singularity is kept. Its quality is Yoshikawa's manipulability
sqrt(det(J Jᵀ)) with the angular rows of J scaled by the reach (so metres and radians
weigh alike), divided by the largest value on the map: 1 = the best-conditioned point of
this map, 0 = on a singularity. Collisions are NOT part of reach: a point may be reached
only through a fixture (the map draws the fixtures so one sees that).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

__all__ = ["ANY_ORIENTATIONS", "ReachMap", "grid_for", "reach_bound", "reach_map", "sampled_map", "slice_grid"]


def _rot(axis: int, angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    m = np.eye(3)
    m[i, i], m[i, j], m[j, i], m[j, j] = c, -s, s, c
    return m


def _any_orientations() -> np.ndarray:
    """26 tool orientations: the tool z axis along each of the 6 axis directions, the 12 edge
    diagonals and the 8 cube diagonals of a cube (every direction within 35° of one), each at
    one roll; a sampled stand-in for "any orientation", stated as such in every output."""
    dirs = [np.array(v, dtype=float) for v in np.ndindex(3, 3, 3) if v != (1, 1, 1)]
    out = []
    for d in dirs:
        z = (d - 1.0) / np.linalg.norm(d - 1.0)
        helper = np.array([1.0, 0.0, 0.0]) if abs(z[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
        x = np.cross(helper, z)
        x /= np.linalg.norm(x)
        out.append(np.column_stack([x, np.cross(z, x), z]))
    return np.array(out)


ANY_ORIENTATIONS = _any_orientations()


@dataclass(frozen=True, eq=False)
class ReachMap:
    """points (N,3) world m; reached (N,) bool; quality (N,) in [0,1] (NaN where not reached);
    q (N,dof) the kept joint solution (NaN rows where not reached); orientation (3,3) world
    or None (any of ANY_ORIENTATIONS); shape: the grid's (nx,ny,nz) when the points are a
    full grid (x fastest), else None."""

    robot: str
    points: np.ndarray
    reached: np.ndarray
    quality: np.ndarray
    q: np.ndarray
    orientation: np.ndarray | None
    base: np.ndarray
    tcp: np.ndarray
    bound: float
    manipulability_max: float

    def rescaled(self, top: float) -> ReachMap:
        """The same map with quality relative to `top` (to share one scale between maps)."""
        quality = np.where(self.reached, self._raw() / top if top > 0 else 0.0, np.nan)
        return replace(self, quality=quality, manipulability_max=top)

    def _raw(self) -> np.ndarray:
        return np.nan_to_num(self.quality) * self.manipulability_max

    @property
    def fraction(self) -> float:
        return float(self.reached.mean()) if self.reached.size else 0.0


def reach_bound(robot: Any, tcp: np.ndarray | None = None) -> float:
    """An upper bound (m) on the distance from the base origin to the TCP: the sum over the
    chain of every joint-to-joint offset length (a rigid link cannot stretch) plus the flange
    and TCP offsets. Read from the pinocchio model's joint placements, so any arm has one."""
    model = robot.model
    total = sum(float(np.linalg.norm(model.jointPlacements[j].translation)) for j in range(1, model.njoints))
    flange = np.linalg.inv(_last_joint_pose(robot, np.zeros(robot.dof))) @ robot.fk(np.clip(np.zeros(robot.dof), *robot.joint_limits.T))
    total += float(np.linalg.norm(flange[:3, 3]))
    prismatic = sum(float(max(abs(lo), abs(hi))) for (lo, hi), t in zip(robot.joint_limits, robot.joint_types) if t == "P")
    if tcp is not None:
        total += float(np.linalg.norm(np.asarray(tcp)[:3, 3]))
    return total + prismatic


def _last_joint_pose(robot: Any, q: np.ndarray) -> np.ndarray:
    import pinocchio as pin  # late: pinocchio is heavy or optional, loaded only where used

    data = robot.model.createData()
    q = np.clip(q, robot.joint_limits[:, 0], robot.joint_limits[:, 1])
    pin.forwardKinematics(robot.model, data, robot.to_model(q))
    return data.oMi[robot.model.njoints - 1].homogeneous


def grid_for(base: np.ndarray, bound: float, step: float) -> np.ndarray:
    """(N,3) world points of a cubic grid of `step` m around the base origin, inside the
    sphere of radius `bound` (nothing outside it can be reached), x fastest."""
    n = int(math.floor(bound / step))
    axis = np.arange(-n, n + 1) * step
    z, y, x = np.meshgrid(axis, axis, axis, indexing="ij")
    local = np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1)
    local = local[np.linalg.norm(local, axis=1) <= bound + 1e-12]
    return local + np.asarray(base)[:3, 3]


def slice_grid(base: np.ndarray, bound: float, step: float, plane: str, level: float) -> np.ndarray:
    """(N,3) world points of a square grid in one plane: 'xy' at z=level, 'xz' at y=level
    (world m), covering the base's reach disc."""
    c = np.asarray(base)[:3, 3]
    n = int(math.ceil(bound / step))
    axis = np.arange(-n, n + 1) * step
    u, v = np.meshgrid(axis, axis, indexing="xy")
    u, v = u.ravel(), v.ravel()
    if plane == "xy":
        pts = np.stack([c[0] + u, c[1] + v, np.full(u.shape, level)], axis=1)
    elif plane == "xz":
        pts = np.stack([c[0] + u, np.full(u.shape, level), c[2] + v], axis=1)
    else:
        raise ValueError(f"plane must be 'xy' or 'xz' (got {plane!r})")
    return pts


def _quality_batch(robot: Any, qs: np.ndarray) -> np.ndarray:
    """(N,dof) -> (N,) Yoshikawa's sqrt(det(J Jᵀ)), the product of J's singular values, with
    the angular rows of J scaled by the reach (so metres and radians weigh alike)."""
    if len(qs) == 0:
        return np.zeros(0)
    jac = np.array([robot.jacobian(q) for q in qs])
    jac[:, 3:] *= max(robot.reach, 1e-3)
    return np.prod(np.linalg.svd(jac, compute_uv=False), axis=1)


def reach_map(robot: Any, points: np.ndarray, *, base: np.ndarray | None = None, tcp: np.ndarray | None = None,
              orientation: np.ndarray | None = None, name: str | None = None) -> ReachMap:
    """The map at `points` (N,3) world (see the module docstring)."""
    base = np.eye(4) if base is None else np.asarray(base, dtype=float)
    tcp = np.eye(4) if tcp is None else np.asarray(tcp, dtype=float)
    points = np.asarray(points, dtype=float).reshape(-1, 3)
    bound = reach_bound(robot, tcp)
    rots = ANY_ORIENTATIONS if orientation is None else np.asarray(orientation, dtype=float).reshape(1, 3, 3)
    inside = np.linalg.norm(points - base[:3, 3], axis=1) <= bound + 1e-9
    n, dof = len(points), robot.dof
    best_q = np.full((n, dof), np.nan)
    best_m = np.full(n, -1.0)
    base_inv, tcp_inv = np.linalg.inv(base), np.linalg.inv(tcp)
    idx = np.flatnonzero(inside)
    for rot in rots:
        world = np.repeat(np.eye(4)[None], len(idx), axis=0)
        world[:, :3, :3] = rot
        world[:, :3, 3] = points[idx]
        sols = robot.ik_batch(base_inv @ world @ tcp_inv)  # (k, 8, dof), NaN rows: no solution within limits
        ok = np.all(np.isfinite(sols), axis=2)
        rows, branches = np.nonzero(ok)
        if rows.size == 0:
            continue
        cand = sols[rows, branches]
        m = _quality_batch(robot, cand)
        order = np.lexsort((-m, rows))  # per point, the best candidate first
        first = np.ones(order.size, dtype=bool)
        first[1:] = rows[order][1:] != rows[order][:-1]
        pick = order[first]
        target = idx[rows[pick]]
        better = m[pick] > best_m[target]
        best_m[target[better]] = m[pick][better]
        best_q[target[better]] = cand[pick][better]
    reached = best_m >= 0
    top = float(best_m[reached].max()) if reached.any() else 0.0
    quality = np.where(reached, best_m / top if top > 0 else 0.0, np.nan)
    return ReachMap(name or robot.name, points, reached, quality, best_q, None if orientation is None else rots[0],
                    base, tcp, bound, top)


def sampled_map(robot: Any, points: np.ndarray, step: float, *, base: np.ndarray | None = None,
                tcp: np.ndarray | None = None, samples: int = 200_000, seed: int = 0, name: str | None = None,
                sweep: np.ndarray | None = None) -> ReachMap:
    """Reach in any orientation, by forward sampling: `samples` joint vectors drawn uniformly
    within the limits (fixed seed: the same map every run), the TCP of each by FK, binned to
    the lattice of `points` (spacing `step`; a full grid or one plane of it). A lattice cell
    holding a sample is reached (by that sample's q, the best-conditioned one kept); a cell
    without one may still be reachable (sampling is sufficient, not exhaustive). Every
    orientation counts, so this is the total workspace (IK per point would need a finite
    set of orientations, and is far slower for arms without a closed form). `sweep` (3,) world m:
    the base also slides by a uniform share of this vector per sample (a robot on a track, `base`
    at the track's low end), so the map is of the joined chain track + arm."""
    base = np.eye(4) if base is None else np.asarray(base, dtype=float)
    tcp = np.eye(4) if tcp is None else np.asarray(tcp, dtype=float)
    points = np.asarray(points, dtype=float).reshape(-1, 3)
    lo, hi = robot.joint_limits[:, 0], robot.joint_limits[:, 1]
    lo, hi = np.maximum(lo, -2 * math.pi), np.minimum(hi, 2 * math.pi)  # unbounded joints: one turn each way
    rng = np.random.default_rng(seed)
    n, dof = len(points), robot.dof
    best_q = np.full((n, dof), np.nan)
    best_m = np.full(n, -1.0)
    ref = points[0] if n else np.zeros(3)
    keys = np.round((points - ref) / step).astype(np.int64)
    shift = int(np.abs(keys).max()) + 2 if n else 2
    def code(k: np.ndarray) -> np.ndarray:
        return ((k[:, 0] + shift) * (2 * shift + 1) + (k[:, 1] + shift)) * (2 * shift + 1) + (k[:, 2] + shift)
    lattice = code(keys)
    order = np.argsort(lattice)
    sorted_codes = lattice[order]
    chunk = 20_000
    for start in range(0, samples, chunk):
        qs = lo + (hi - lo) * rng.random((min(chunk, samples - start), dof))
        tcp_world = (base @ robot.fk_batch(qs) @ tcp)[:, :3, 3]
        if sweep is not None:
            tcp_world = tcp_world + rng.random((len(qs), 1)) * np.asarray(sweep, dtype=float)
        k = np.round((tcp_world - ref) / step).astype(np.int64)
        inside = np.all(np.abs(k) < shift - 1, axis=1)
        c = code(np.where(inside[:, None], k, 0))
        pos = np.clip(np.searchsorted(sorted_codes, c), 0, max(len(sorted_codes) - 1, 0))
        hit = inside & (sorted_codes[pos] == c) if n else np.zeros(len(c), bool)
        if not hit.any():
            continue
        cell = order[pos[hit]]
        m = _quality_batch(robot, qs[hit])
        for i, value, q in zip(cell, m, qs[hit]):
            if value > best_m[i]:
                best_m[i], best_q[i] = value, q
    reached = best_m >= 0
    top = float(best_m[reached].max()) if reached.any() else 0.0
    quality = np.where(reached, best_m / top if top > 0 else 0.0, np.nan)
    return ReachMap(name or robot.name, points, reached, quality, best_q, None, base, tcp, reach_bound(robot, tcp), top)
