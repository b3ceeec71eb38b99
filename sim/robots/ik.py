"""Inverse kinematics: candidates (closed form or numeric), verified, expanded, sorted.

Every returned solution is within the joint limits and reproduces the pose by FK to 1e-9 m
and 1e-9 rad. A joint whose range spans more than 360° contributes every equivalent angle
(q ± 2πk) inside its limits; all are returned, nearest to the seed first (Euclidean distance
in joint space; seed None = all zeros). At the wrist singularity (J5 = 0) the seed's J4 is kept.
Only the distinct solutions are checked by FK: their 2π-equivalents reproduce the same pose
exactly (a revolute joint's transform is 2π-periodic), so they are verified by that invariance
and share their solution's branch (every branch quantity is 2π-periodic too).

Statuses: OK; SINGULAR = solutions returned and verified, but the pose lies on a singularity
(smallest reach-scaled singular value of J < 1e-6 at the first solution: treat it as OK with
a warning, or refuse a linear move through it); UNREACHABLE = no solution (distance from the
workspace in m; also used when `config` excludes every existing branch);
OUT_OF_LIMITS = solutions exist but every one violates a limit (joint index, excess).
"""

from __future__ import annotations

import itertools
import math
from typing import Any

import numpy as np

from rmot.lang import ir
from rmot.sim.robots.ik_result import (
    POS_TOL, ROT_TOL, SINGULAR_SIGMA, IkResult, IkStatus, result,
)
from rmot.sim.robots.ik_result import is_singular as _is_singular
from rmot.sim.robots.ik_rows import BranchRows, JointRows
from rmot.sim.robots.numeric import dls, dls_fast, restart_seeds

__all__ = [
    "IkResult", "IkStatus", "solve", "solve_batch", "POS_TOL", "ROT_TOL", "SINGULAR_SIGMA", "result",
]

TWO_PI = 2 * math.pi
NUMERIC_RESTARTS = 24


_EYE3 = np.eye(3)


def _check_pose(pose: np.ndarray) -> np.ndarray:
    t = np.asarray(pose, dtype=float)
    if t.shape != (4, 4) or not np.isfinite(t).all():
        raise ValueError(f"pose must be a finite (4,4) matrix (got shape {t.shape})")
    r = t[:3, :3]
    if np.abs(r @ r.T - _EYE3).max() > 1e-6:
        raise ValueError("pose rotation must be orthonormal")
    return t


def pose_error(a: np.ndarray, b: np.ndarray) -> tuple[float, float]:
    """(position error m, rotation error rad) between two (4,4) poses."""
    dp = float(np.linalg.norm(a[:3, 3] - b[:3, 3]))
    cos = (np.trace(a[:3, :3].T @ b[:3, :3]) - 1) / 2
    skew = a[:3, :3].T @ b[:3, :3]
    sin = 0.5 * math.sqrt((skew[2, 1] - skew[1, 2]) ** 2 + (skew[0, 2] - skew[2, 0]) ** 2 + (skew[1, 0] - skew[0, 1]) ** 2)
    return dp, math.atan2(sin, cos)


def _verified(robot, target: np.ndarray, q: np.ndarray) -> np.ndarray | None:  # type: ignore[no-untyped-def]
    """q if FK(q) matches target within tolerance, after up to a few Newton polish steps."""
    dp, dr = pose_error(robot.fk(q), target)
    if dp <= POS_TOL and dr <= ROT_TOL:
        return q
    if dp > 1e-4 or dr > 1e-4:
        return None
    q2, _ = dls(robot, target, q, max_iter=4)
    dp, dr = pose_error(robot.fk(q2), target)
    return q2 if dp <= POS_TOL and dr <= ROT_TOL else None


def _equivalents(robot, q: np.ndarray) -> np.ndarray:  # type: ignore[no-untyped-def]
    """(k,dof): every q + 2πk (per revolute joint) inside the limits (k may be 0), in
    itertools.product order over the joints (last joint fastest)."""
    flat, counts, multiple = [], [], False
    for v, lo, hi, revolute in zip(q.tolist(), robot._lo, robot._hi, robot._revolute_list):
        first = v + math.ceil((lo - 1e-12 - v) / TWO_PI) * TWO_PI if revolute else v
        if not lo - 1e-12 <= first <= hi + 1e-12:
            return np.empty((0, len(q)))
        value = min(max(first, lo), hi)
        flat.append(value)
        n = 1
        while revolute and value + TWO_PI <= hi + 1e-12:
            value = min(value + TWO_PI, hi)
            flat.append(value)
            n += 1
            multiple = True
        counts.append(n)
    if not multiple:
        return np.array([flat])
    return np.array(flat)[_product_index(tuple(counts))]


_PRODUCT_INDEX: dict[tuple[int, ...], np.ndarray] = {}


def _product_index(counts: tuple[int, ...]) -> np.ndarray:
    """(prod(counts), len(counts)) indices into the joints' concatenated options, rows in
    itertools.product order; cached per count pattern (a handful per robot)."""
    index = _PRODUCT_INDEX.get(counts)
    if index is None:
        starts = np.concatenate([[0], np.cumsum(counts)[:-1]])
        index = np.array(list(itertools.product(*(range(n) for n in counts))), dtype=np.intp) + starts
        _PRODUCT_INDEX[counts] = index
    return index


def _excess(robot, q: np.ndarray) -> tuple[int, float]:  # type: ignore[no-untyped-def]
    """(joint, amount) of the worst limit violation of the best equivalent of q."""
    worst, amount = 0, 0.0
    for j, (v, (lo, hi)) in enumerate(zip(q, robot.joint_limits)):
        values = [v] if robot.joint_types[j] == "P" else [v + k * TWO_PI for k in range(-3, 4)]
        e = min(max(lo - x, x - hi, 0.0) for x in values)
        if e > amount:
            worst, amount = j, e
    return worst, amount


def _candidates(robot, target: np.ndarray, seed: np.ndarray) -> list[np.ndarray]:  # type: ignore[no-untyped-def]
    if robot.has_closed_form:
        raw = robot.ik_closed_form(target[None])[0]
        return [row for row in raw if np.all(np.isfinite(row))]
    found = []
    q, err = dls_fast(robot, target, seed)
    if err < 1e-9:
        found.append(q)
        if _has_equivalent(robot, q):
            return found
    if robot._restarts is None:  # deterministic, drawn once per robot
        robot._restarts = restart_seeds(robot.joint_limits, NUMERIC_RESTARTS)
    for start in robot._restarts:
        q, err = dls_fast(robot, target, start)
        if err < 1e-9:
            found.append(q)
            if _has_equivalent(robot, q):
                break
    return found


def _has_equivalent(robot, q: np.ndarray) -> bool:  # type: ignore[no-untyped-def]
    """Whether some q + 2πk lies inside the limits (the cheap test of `_equivalents`)."""
    for v, lo, hi, revolute in zip(q.tolist(), robot._lo, robot._hi, robot._revolute_list):
        first = v + math.ceil((lo - 1e-12 - v) / TWO_PI) * TWO_PI if revolute else v
        if not lo - 1e-12 <= first <= hi + 1e-12:
            return False
    return True


def solve(robot, pose: np.ndarray, seed: np.ndarray | None = None, config: ir.Config | None = None) -> IkResult:  # type: ignore[no-untyped-def]
    fast = robot._fast
    if fast is None:
        fast = robot._fast = _fast_solver(robot)
    if fast and (fast.compiled is not None or fast.kernel.prefer_compiled(1)):
        res: IkResult | None = fast.solve(robot, pose, seed, config)
        if res is not None:
            return res
    return solve_exact(robot, pose, seed, config)


def _fast_solver(robot) -> Any:  # type: ignore[no-untyped-def]
    """fastsolve's compiled pass for closed-form 6R arms (False for every other robot)."""
    from rmot.sim.robots.closed_form import ClosedForm  # late: loads subprocess only when this runs

    closed_form = robot._closed_form
    if not isinstance(closed_form, ClosedForm) or not closed_form.branch:
        return False
    from rmot.sim.robots.fast_solver import FastSolver  # numba-compiled: loaded on first use  # late: loads subprocess only when this runs

    solver = FastSolver(robot, closed_form)
    return solver if solver.usable else False


def solve_exact(robot, pose: np.ndarray, seed: np.ndarray | None = None, config: ir.Config | None = None) -> IkResult:  # type: ignore[no-untyped-def]
    """`solve` step by step in numpy and pinocchio: the reference of fastsolve's compiled pass,
    and the path of every pose that pass hands back."""
    target = _check_pose(pose)
    seed_q = np.zeros(robot.dof) if seed is None else np.asarray(seed, dtype=float).reshape(robot.dof)
    raw = _candidates(robot, target, seed_q)
    verified = _distinct([_wrist_from_seed(robot, target, q, seed_q) for q in _verify_all(robot, target, raw)])
    if not verified:
        return _unreachable(robot, target)
    # Equivalent angles share their branch (every branch quantity is 2π-periodic).
    groups = [(robot.branch(q), _equivalents(robot, q)) for q in verified]
    groups = [(b, e) for b, e in groups if len(e)]
    if not groups:
        return _out_of_limits(robot, verified)
    kept = [(b, e) for b, e in groups if _matches(b, config)]
    if not kept:
        found = ", ".join(sorted({str(b) for b, _ in groups}))
        return IkResult(IkStatus.UNREACHABLE, message=f"no IK solution with {config} (solutions exist with: {found})",
)
    qs = kept[0][1] if len(kept) == 1 else np.concatenate([e for _, e in kept])
    delta = qs - seed_q
    order = np.argsort(np.sqrt(np.add.reduce(delta * delta, axis=1)), kind="stable")  # = norm(delta, axis=1)
    qs = qs[order]
    qs.setflags(write=False)
    sols = JointRows(qs)
    if len(kept) == 1:
        brs = BranchRows((kept[0][0],) * len(sols))
    else:
        names = [b for b, e in kept for _ in range(len(e))]
        brs = BranchRows(tuple(names[i] for i in order.tolist()))
    if _is_singular(robot, sols[0]):
        return IkResult(IkStatus.SINGULAR, sols, brs, "the pose lies on a kinematic singularity")
    return IkResult(IkStatus.OK, sols, brs)


def _verify_all(robot, target: np.ndarray, raw: list[np.ndarray]) -> list[np.ndarray]:  # type: ignore[no-untyped-def]
    """The candidates whose FK matches the target (polishing the near misses)."""
    if not raw:
        return []
    fk = robot.fk(raw[0])[None] if len(raw) == 1 else robot.fk_batch(np.array(raw))
    # np.add.reduce is what np.sum calls, minus its Python wrapper.
    dp = np.sqrt(np.add.reduce((fk[:, :3, 3] - target[:3, 3]) ** 2, axis=1))
    dr = np.sqrt(np.add.reduce((fk[:, :3, :3] - target[:3, :3]) ** 2, axis=(1, 2)) / 2)  # ≈ angle when small
    out = []
    for q, p_err, r_err in zip(raw, dp.tolist(), dr.tolist()):
        if p_err <= POS_TOL and r_err <= ROT_TOL:
            out.append(q)
        elif p_err < 1e-4 and r_err < 1e-4:
            fixed = _verified(robot, target, q)
            if fixed is not None:
                out.append(fixed)
    return out


def _wrist_from_seed(robot, target: np.ndarray, q: np.ndarray, seed: np.ndarray) -> np.ndarray:  # type: ignore[no-untyped-def]
    """At the wrist singularity (J4 and J6 aligned) only J4 ± J6 is fixed: keep the seed's J4."""
    if robot.dof != 6 or abs(math.sin(q[4])) > 1e-7 or not robot.has_closed_form:
        return q
    shift = q[3] - seed[3]
    for k in (1.0, -1.0):
        moved = q.copy()
        moved[3], moved[5] = seed[3], q[5] + k * shift
        dp, dr = pose_error(robot.fk(moved), target)
        if dp <= POS_TOL and dr <= ROT_TOL:
            return moved
    return q


def _matches(branch: ir.Config, want: ir.Config | None) -> bool:
    if want is None:
        return True
    return all(w is None or w == b for w, b in ((want.shoulder, branch.shoulder), (want.elbow, branch.elbow), (want.wrist, branch.wrist)))


def _distinct(qs: list[np.ndarray]) -> list[np.ndarray]:
    """Drop candidates equal to an earlier one modulo 2π within 1e-9 (branches that meet at
    a singularity); their equivalent angles would be the same set."""
    if len(qs) < 2:
        return qs
    wrapped = np.remainder(np.array(qs), TWO_PI)
    gap = np.abs(wrapped[:, None] - wrapped[None])
    diff = np.minimum(gap, TWO_PI - gap).max(axis=2)
    same_as_earlier = np.any(np.tril(diff <= 1e-9, k=-1), axis=1)
    return [q for q, dup in zip(qs, same_as_earlier) if not dup]


def _unreachable(robot, target: np.ndarray) -> IkResult:  # type: ignore[no-untyped-def]
    if robot._workspace_distance is not None:
        dist = float(robot._workspace_distance(target))
    else:
        dist = float("nan")
    where = f"{dist * 1000:.1f} mm outside the workspace" if math.isfinite(dist) else "outside the workspace"
    return IkResult(IkStatus.UNREACHABLE, message=f"the pose is {where} of {robot.name}",
                    distance=dist)


def _out_of_limits(robot, verified: list[np.ndarray]) -> IkResult:  # type: ignore[no-untyped-def]
    joint, amount = min((_excess(robot, q) for q in verified), key=lambda e: e[1])
    unit, shown = ("mm", amount * 1000) if robot.joint_types[joint] == "P" else ("deg", math.degrees(amount))
    msg = f"joint {joint + 1} exceeds its limit by {shown:.1f} {unit} in the best of {len(verified)} IK solutions"
    return IkResult(IkStatus.OUT_OF_LIMITS, message=msg, joint=joint, excess=amount)


def solve_batch(robot, poses: np.ndarray, seed: np.ndarray | None = None) -> np.ndarray:  # type: ignore[no-untyped-def]
    poses = np.asarray(poses, dtype=float).reshape(-1, 4, 4)
    n = len(poses)
    seed_q = np.zeros(robot.dof) if seed is None else np.asarray(seed, dtype=float)
    if not robot.has_closed_form:
        out = np.full((n, 8, robot.dof), np.nan)
        for i, t in enumerate(poses):
            res = solve(robot, t, seed_q if seed_q.ndim == 1 else seed_q[i])
            if res.solutions:
                out[i, 0] = res.solutions[0]
        return out
    raw = robot.ik_closed_form(poses)
    if n >= _BATCH_KERNEL_POSES:
        return _nearest_verified_compiled(robot, poses, raw, seed_q)
    seeds = np.broadcast_to(seed_q.reshape(-1, 1, robot.dof) if seed_q.ndim == 2 else seed_q, raw.shape)
    q = _nearest_in_limits(robot, raw, seeds)
    return _verify_batch(robot, poses, q)


# poses per ik_batch call from which the compiled loop (fastbatch) runs instead of numpy
_BATCH_KERNEL_POSES = 64


def _nearest_verified_compiled(  # type: ignore[no-untyped-def]
        robot, poses: np.ndarray, raw: np.ndarray, seed_q: np.ndarray) -> np.ndarray:
    """`_nearest_in_limits` + `_verify_batch` in one compiled pass (robots/fastbatch.py)."""
    from rmot.sim.robots.fastbatch import NEAREST_VERIFIED  # late: loads subprocess only when this runs

    n, b, dof = raw.shape
    rows_of_seeds = n if seed_q.ndim == 2 else 1  # one row for all poses: not copied n times
    seeds = np.ascontiguousarray(np.broadcast_to(seed_q, (rows_of_seeds, dof)), dtype=float)
    chain = robot._chain
    coupled = robot._coupling is not None
    coupling = np.ascontiguousarray(robot._coupling, dtype=float) if coupled else np.eye(dof)
    limits = np.ascontiguousarray(robot.joint_limits.T)
    out = np.empty_like(raw)
    bad = np.zeros((n, b), dtype=np.bool_)
    NEAREST_VERIFIED.jit()(
        np.ascontiguousarray(raw), seeds, limits[0], limits[1],
        np.array(robot._revolute, dtype=np.bool_), chain.placements, chain.axes, chain.prismatic,
        np.array(robot._flange_in_joint), coupling, coupled, np.ascontiguousarray(poses),
        POS_TOL / 2, ROT_TOL / 2, out, bad)
    # Rows the kernel's FK put within half a tolerance of failing (a few per thousand) get the
    # numpy path's own check, so that its rounding, not the kernel's, decides which to polish.
    if bad.any():
        rows = np.argwhere(bad)
        n_i, b_i = rows[:, 0], rows[:, 1]
        out[n_i, b_i] = _verify_batch(robot, poses[n_i], out[n_i, b_i][:, None])[:, 0]
    return out


def _nearest_in_limits(robot, raw: np.ndarray, seeds: np.ndarray) -> np.ndarray:  # type: ignore[no-untyped-def]
    lo, hi = robot.joint_limits[:, 0], robot.joint_limits[:, 1]
    revolute = np.array([t == "R" for t in robot.joint_types])
    k0 = np.where(revolute, np.round((seeds - raw) / TWO_PI), 0.0)
    best = np.full(raw.shape, np.nan)
    best_d = np.full(raw.shape, np.inf)
    for dk in (0.0, -1.0, 1.0, -2.0, 2.0):
        cand = raw + np.where(revolute, (k0 + dk) * TWO_PI, 0.0)
        ok = (cand >= lo - 1e-12) & (cand <= hi + 1e-12)
        d = np.abs(cand - seeds)
        better = ok & (d < best_d)
        best = np.where(better, np.clip(cand, lo, hi), best)
        best_d = np.where(better, d, best_d)
    return np.where(np.all(np.isfinite(best), axis=-1, keepdims=True), best, np.nan)


def _verify_batch(robot, poses: np.ndarray, q: np.ndarray) -> np.ndarray:  # type: ignore[no-untyped-def]
    n, b, dof = q.shape
    flat = q.reshape(-1, dof)
    good = np.all(np.isfinite(flat), axis=1)
    fk = robot.fk_batch(np.where(good[:, None], flat, 0.0))
    target = np.repeat(poses, b, axis=0)
    dp = np.linalg.norm(fk[:, :3, 3] - target[:, :3, 3], axis=1)
    dr = np.linalg.norm(fk[:, :3, :3] - target[:, :3, :3], axis=(1, 2)) / math.sqrt(2)
    bad = good & ((dp > POS_TOL) | (dr > ROT_TOL))
    for i in np.flatnonzero(bad):  # rare: near a singularity the closed form loses digits
        fixed = _verified(robot, target[i], flat[i])
        flat[i] = fixed if fixed is not None and not np.any(np.isnan(fixed)) else np.nan
    return flat.reshape(n, b, dof)
