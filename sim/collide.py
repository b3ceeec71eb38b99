"""Collision and clearance over a sampled timeline, with a no-miss guarantee between samples.

Engine (chosen by measurement, tests/benchmarks/bench_verify.py): coal (FCL's successor,
shipped with pinocchio) on primitives and convex hulls, confirmed on mesh triangles, behind
a numpy broad phase that discards most (pair, sample) combinations without calling it.

THE GUARANTEE — no contact between two samples is missed:
  * Between samples each robot follows the linear interpolation of its joint samples; the
    true path strays from it by at most max|qdd|·dt²/8 per joint, added as padding.
  * While q goes from q_i to q_i+1, a point p of a body moves by at most
        D = Σ_j |Δq_j| · reach_j(body)      (reach_j >= |p - origin of joint j|, scene.py)
    and two bodies of one robot move relative to each other only through the joints
    between them (bounds.pair_reach). So if their distance at sample i is d_i, they cannot
    touch before the accumulated bound Σ D reaches d_i.
  * Stage 1 (numpy, all samples at once): per block of 16 samples one sphere per body that
    holds it over the block, against fixture boxes / other bodies' spheres; blocks whose
    bound clears the motion margin of every interval in it are done.
  * Stage 2 (numpy, remaining samples): sphere covers of the solids against fixture boxes
    or each other's spheres.
  * Stage 3 (coal, remaining samples): the exact distance d_i. It certifies every following
    interval until the accumulated motion bound reaches d_i (conservative advancement);
    an interval it cannot certify is bisected — all such intervals of a pair at once per
    level — until the motion bound of a piece is below CONTACT_TOL (10 µm).
    Inside a contact nothing needs proving: for convex pairs (a true signed distance, which
    changes by at most the motion bound) a depth p at sample i proves every later sample
    within motion p in contact, so those are skipped; a skipped sample is measured only if
    it could be deeper than its run's deepest exact value by more than DEPTH_TOL (10 µm).
Every bound is a lower bound on the true distance (tests/sim/test_sim_scene.py checks the
covers, the reach bound and the broad-phase bounds against coal), so a contact is found
unless it is shallower than CONTACT_TOL; with a clearance c the same test against d - c
finds every approach closer than c.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass
from typing import Any

import numpy as np

from rmot.lang.record import record
from rmot.sim.bounds import (
    BLOCK, LazyCentres, block_bound, block_spheres, joint_motion, lower_bound, model_q, pair_reach,
)
from rmot.sim.exact import ExactPair
from rmot.sim.scene import Body, Scene

__all__ = ["CONTACT_TOL", "PairHit", "Timeline", "candidate_pairs", "check_timeline"]

CONTACT_TOL = 1e-5  # m: bisection stops when no body can move more than this
STATIC_TOL = 1e-4  # m: bodies that never move may touch (a robot standing on its stand)
_MAX_DEPTH = 40


@dataclass(frozen=True, eq=False)
class Timeline:
    """Shared samples: t (M,); q[robot] (M, dof); accel[robot] (M, dof) bound on |qdd|."""

    t: np.ndarray
    q: dict[str, np.ndarray]
    accel: dict[str, np.ndarray]


@record
class PairHit:
    """One contiguous interval where two bodies touch ("collision") or come closer than the
    clearance ("clearance"), or a permanent overlap of two static bodies ("static")."""

    kind: str
    a: str
    b: str
    t0: float
    t1: float
    distance: float  # m: the smallest signed distance found (negative = penetration)
    t_worst: float | None = None  # s: when that smallest distance was found


# --------------------------------------------------------------------------- pairs


def candidate_pairs(scene: Scene, only_robot: str | None = None) -> list[tuple[Body, Body]]:
    """Every pair to check: moving bodies vs fixtures, self pairs that are not adjacent, and
    bodies of different robots; minus the cell's allowed contacts. With `only_robot`, only
    pairs that involve that robot's bodies."""
    allowed = {frozenset(p) for p in scene.cell.allowed_contacts}
    bodies = scene.bodies
    pairs = []
    for i, a in enumerate(bodies):
        for b in bodies[i + 1:]:
            if a.kind == "fixture" and b.kind == "fixture":
                continue
            if only_robot is not None and only_robot not in (a.robot, b.robot):
                continue
            if _allowed(a, b, allowed) or (a.robot == b.robot and _adjacent(scene, a, b)):
                continue
            if frozenset((a.name, b.name)) in scene.always_touching:
                continue
            pairs.append((a, b))
    return pairs


def _allowed(a: Body, b: Body, allowed: set[frozenset[str]]) -> bool:
    names_a = {a.name} | ({a.robot} if a.robot else set())
    names_b = {b.name} | ({b.robot} if b.robot else set())
    return any(frozenset((x, y)) in allowed or (x == y and frozenset((x,)) in allowed)
               for x in names_a for y in names_b)


def _adjacent(scene: Scene, a: Body, b: Body) -> bool:
    """Same-robot pairs never checked: listed adjacent solids, both static, the tool with the
    solids of the last joint, two tools on one flange."""
    if not a.moves and not b.moves:
        return True
    robot = scene.robots[a.robot].robot  # type: ignore[index]
    if a.kind == "link" and b.kind == "link":
        pair = (a.solid_index, b.solid_index)
        return pair in robot.adjacent_pairs or pair[::-1] in robot.adjacent_pairs
    if a.kind == "tool" and b.kind == "tool":
        return True
    link = a if a.kind == "link" else b
    return link.joint == robot.dof


# --------------------------------------------------------------------------- the check


def check_timeline(scene: Scene, timeline: Timeline, pairs: Iterable[tuple[Body, Body]],
                   clearance: float = 0.0) -> list[PairHit]:
    """Every collision (and approach closer than `clearance`, m) between the pairs."""
    poses = _sample_poses(scene, timeline)
    motion = {r: joint_motion(scene, r, timeline) for r in timeline.q}
    centres = LazyCentres(scene, poses)
    blocks = {b.name: block_spheres(b, poses[b.name]) for b in scene.bodies if b.kind != "fixture"}
    margins = _Margins(scene, timeline, motion)
    hits: list[PairHit] = []
    for a, b in pairs:
        if not a.moves and not b.moves:
            hits += _static_pair(a, b, poses)
            continue
        # the clearance is about other things in the cell: a robot's own solids sit close by design
        own = a.robot is not None and a.robot == b.robot
        hits += _moving_pair(scene, timeline, a, b, poses, (centres, blocks, margins), motion, 0.0 if own else clearance)
    return hits


class _Margins(dict[tuple[tuple[str, bytes], ...], tuple[np.ndarray, np.ndarray]]):
    """reach key -> (motion bound per interval (M-1,), its maximum per block (nB,)); every
    fixture pair of one body shares them, so they are computed once per body."""

    def __init__(self, scene: Scene, timeline: Timeline, motion: dict[str, tuple[np.ndarray, np.ndarray]]) -> None:
        super().__init__()
        self._scene, self._timeline, self._motion = scene, timeline, motion

    def of(self, a: Body, b: Body) -> tuple[np.ndarray, np.ndarray]:
        reach = pair_reach(self._scene, a, b)
        key = tuple(sorted((r, w.tobytes()) for r, w in reach.items()))
        if key not in self:
            m = self._timeline.t.shape[0]
            move = sum(((dq + pad) @ reach[r] for r, (dq, pad) in self._motion.items() if r in reach), np.zeros(m - 1))
            n_blocks = -(-m // BLOCK)
            padded = np.concatenate([move, np.zeros(n_blocks * BLOCK - m + 1)])  # the last sample needs no margin
            self[key] = (move, padded.reshape(n_blocks, BLOCK).max(axis=1))
        return self[key]


def _sample_poses(scene: Scene, timeline: Timeline) -> dict[str, np.ndarray]:
    """name -> (M, 4, 4) world poses of every robot body; fixtures -> (1, 4, 4)."""
    poses: dict[str, np.ndarray] = {}
    for robot, q in timeline.q.items():
        poses.update(scene.poses(robot, q))
    for body in scene.bodies:
        if body.kind == "fixture":
            poses[body.name] = body.local[None]
    return poses


def _moving_pair(scene: Scene, timeline: Timeline, a: Body, b: Body, poses: dict[str, np.ndarray],
                 bounds: tuple[dict[str, np.ndarray], dict[str, Any], _Margins], motion: dict[str, tuple[np.ndarray, np.ndarray]],
                 clearance: float) -> list[PairHit]:
    pa, pb = poses[a.name], poses[b.name]
    centres, blocks, margins = bounds
    m = timeline.t.shape[0]
    reach = pair_reach(scene, a, b)
    move, block_move = margins.of(a, b)
    # coarse: whole blocks of samples whose block bound clears every margin in the block
    near_blocks = np.nonzero(block_bound(a, b, blocks) < block_move + clearance)[0]
    if near_blocks.size == 0:
        return []
    idx = (near_blocks[:, None] * BLOCK + np.arange(BLOCK)).ravel()
    idx = idx[idx < m]
    need = np.append(move, 0.0) + clearance  # the last sample needs no motion margin
    # fine: per-sample sphere bounds in those blocks
    flagged = idx[lower_bound(a, b, pa, pb, centres, idx) < need[idx]]
    if flagged.size == 0:
        return []
    exact = ExactPair(a, b)
    pose_a, pose_b = _per_sample(pa, exact), _per_sample(pb, exact)
    evaluated, dists_at, split = _advance(flagged, need, move, clearance,
                                          lambda i: exact.distance(pose_a(i), pose_b(i), float(need[i])),
                                          lipschitz=exact.convex)
    times, dists = [timeline.t[evaluated]], [dists_at]
    if split.size:
        sub_t, sub_d = _bisect(scene, timeline, exact, a, b, reach, split, dists_at[np.searchsorted(evaluated, split)],
                               clearance, {r: motion[r][1] for r in reach}, {a.name: pa, b.name: pb})
        times.append(sub_t)
        dists.append(sub_d)
    # samples not evaluated exactly are free (their lower bound already clears the margin)
    free = np.ones(m, dtype=bool)
    free[evaluated] = False
    free_t = timeline.t[free]
    return _runs(a, b, np.concatenate(times), np.concatenate(dists), free_t, clearance)


def _advance(flagged: np.ndarray, need: np.ndarray, move: np.ndarray, clearance: float,
             distance_at: Callable[[int], float], lipschitz: bool = False
             ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Conservative advancement over the flagged samples: an exact distance d at sample i
    certifies every following interval up to where the accumulated motion bound reaches
    d - clearance, so those samples need no evaluation of their own.

    With `lipschitz` (a true signed distance, which moves by at most the motion bound), a
    contact of depth p at sample i also proves every following sample within motion p to be
    in contact: those are skipped too (the interval is already a finding), carrying the upper
    bound d_i + motion as their distance, and only where the pair could be deeper than the
    deepest exact value of its run by more than DEPTH_TOL are they evaluated (_refine_depth).
    Returns (evaluated samples, their distances, intervals that still need splitting)."""
    cum = np.concatenate([[0.0], np.cumsum(move)])  # cum[k]: motion bound from sample 0 to k
    evaluated: list[int] = []
    dists: list[float] = []
    split: list[int] = []
    skipped: list[tuple[int, int]] = []  # (i, e): samples i+1..e proved in contact by sample i
    k = 0
    m = need.shape[0]
    while k < flagged.size:
        i = int(flagged[k])
        d = distance_at(i)
        evaluated.append(i)
        dists.append(d)
        if lipschitz and d < 0.0:
            # samples j with cum[j] - cum[i] < -d are in contact: d_j <= d + (cum[j] - cum[i]) < 0
            e = min(int(np.searchsorted(cum, cum[i] - d, side="left")) - 1, m - 1)
            if e > i:
                skipped.append((i, e))
            # max(e, i): a contact shallower than cum's rounding (d = -1e-12, two faces touching)
            # gives e = i - 1, which must not stall the walk on sample i
            k = int(np.searchsorted(flagged, max(e, i) + 1, side="left"))
            continue
        # intervals i..J are safe while cum[J+1] <= cum[i] + d - clearance
        last_safe = int(np.searchsorted(cum, cum[i] + d - clearance, side="right")) - 2
        if last_safe < i and d > 0.0 and i + 1 < m:
            split.append(i)  # not certified by its own start: look inside (a contact needs no look)
        k = int(np.searchsorted(flagged, max(last_safe + 1, i + 1), side="left"))
    ev, dv = np.array(evaluated, dtype=int), np.array(dists)
    if skipped:
        ev, dv = _refine_depth(ev, dv, skipped, cum, m, distance_at)
    return ev, dv, np.array(split, dtype=int)


DEPTH_TOL = 1e-5  # m: a run's reported depth is within this of its deepest sample


def _refine_depth(ev: np.ndarray, dv: np.ndarray, skipped: list[tuple[int, int]], cum: np.ndarray, m: int,
                  distance_at: Callable[[int], float]) -> tuple[np.ndarray, np.ndarray]:
    """Add the skipped contact samples (upper-bound distances) and evaluate exactly those that
    could be deeper than their run's deepest exact value by more than DEPTH_TOL. One pass is
    enough: evaluating only lowers that deepest value, so the rest stay within tolerance."""
    exact = np.full(m, np.nan)
    exact[ev] = dv
    starts = np.array([i for i, _ in skipped])
    counts = np.array([e - i for i, e in skipped])
    owner = np.repeat(starts, counts)  # the sample whose contact proved each skipped one
    j = owner + (np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts)) + 1
    d_owner = exact[owner]
    upper = d_owner + (cum[j] - cum[owner])
    lower = d_owner - (cum[j] - cum[owner])
    nxt = np.repeat(np.array([e for _, e in skipped]) + 1, counts)  # the sample after the gap
    d_next = np.where(nxt < m, exact[np.minimum(nxt, m - 1)], np.nan)
    has_next = ~np.isnan(d_next)
    jn, kn = j[has_next], nxt[has_next]
    lower[has_next] = np.maximum(lower[has_next], d_next[has_next] - (cum[kn] - cum[jn]))
    # runs of contact over all samples: exact contacts and skipped ones
    dist = np.where(np.isnan(exact), np.inf, exact)
    dist[j] = upper
    contact = dist <= 0.0
    run = np.cumsum(np.concatenate([[contact[0]], contact[1:] & ~contact[:-1]]))
    best = np.full(run[-1] + 1, np.inf)
    exact_contact = ~np.isnan(exact) & contact
    np.minimum.at(best, run[exact_contact], exact[exact_contact])
    check = j[lower < best[run[j]] - DEPTH_TOL]
    for s in check:
        dist[s] = distance_at(int(s))
    keep = np.zeros(m, dtype=bool)
    keep[ev] = True
    keep[j] = True
    idx = np.flatnonzero(keep)
    return idx, dist[idx]


def _at(poses: np.ndarray, i: int) -> np.ndarray:
    return poses[i] if poses.shape[0] > 1 else poses[0]


def _per_sample(poses: np.ndarray, exact: ExactPair):  # type: ignore[no-untyped-def]
    """i -> pose; a pose that never changes is one object, registered with `exact` once."""
    if poses.shape[0] > 1:
        return poses.__getitem__
    single = poses[0]
    exact.fix(single)
    return lambda i: single


def _bisect(scene: Scene, timeline: Timeline, exact: ExactPair, a: Body, b: Body, reach: dict[str, np.ndarray],
            intervals: np.ndarray, d0: np.ndarray, clearance: float, pads: dict[str, np.ndarray],
            poses: dict[str, np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """Split the given intervals (index i = [t_i, t_i+1], start distance d0) in halves, all
    of them at once per level, until the motion bound clears every start distance."""
    robots = sorted(reach)
    t = timeline.t
    i = intervals
    ta, tb = t[i], t[i + 1]
    qa = {r: timeline.q[r][i] for r in robots}
    qb = {r: timeline.q[r][i + 1] for r in robots}
    pad = {r: pads[r][i] for r in robots}
    frac = np.ones(len(i))
    da = np.asarray(d0, dtype=float)
    fixed = {body.name: exact.fixed_pose for body in (a, b) if poses[body.name].shape[0] == 1}
    out_t: list[np.ndarray] = []
    out_d: list[np.ndarray] = []
    for _ in range(_MAX_DEPTH):
        move = sum((np.abs(model_q(scene, r, qb[r]) - model_q(scene, r, qa[r])) + pad[r] * (frac**2)[:, None]) @ reach[r]
                   for r in robots)
        # split unless: safe, already a contact, or closer than the clearance with no contact possible
        done = (da >= move + clearance) | (da <= 0.0) | ((move <= da) & (da < clearance)) | (move < CONTACT_TOL)
        keep = ~done
        if not keep.any():
            break
        ta, tb, da, frac = ta[keep], tb[keep], da[keep], frac[keep] / 2
        qa = {r: qa[r][keep] for r in robots}
        qb = {r: qb[r][keep] for r in robots}
        pad = {r: pad[r][keep] for r in robots}
        move = move[keep]
        tm = (ta + tb) / 2
        qm = {r: (qa[r] + qb[r]) / 2 for r in robots}
        pm = {r: scene.poses(r, qm[r]) for r in robots}
        # a body of a robot without a task stands still: its first pose (KeyError, found by make fuzz)
        def pose(body: Body, k: int, pm: dict[str, dict[str, np.ndarray]] = pm) -> np.ndarray:
            if body.name in fixed:
                return fixed[body.name]  # type: ignore[return-value]  # set for a body of one pose
            if body.robot is not None and body.robot in pm:
                return pm[body.robot][body.name][k]
            return poses[body.name][0]

        dm = np.array([exact.distance(pose(a, k), pose(b, k), float(move[k] / 2 + clearance)) for k in range(len(tm))])
        out_t.append(tm)
        out_d.append(dm)
        # the two halves: [ta, tm] starting at da, [tm, tb] starting at dm
        ta, tb, da = np.concatenate([ta, tm]), np.concatenate([tm, tb]), np.concatenate([da, dm])
        qa, qb = ({r: np.concatenate([qa[r], qm[r]]) for r in robots}, {r: np.concatenate([qm[r], qb[r]]) for r in robots})
        pad = {r: np.concatenate([pad[r], pad[r]]) for r in robots}
        frac = np.concatenate([frac, frac])
    empty = np.zeros(0)
    return (np.concatenate(out_t) if out_t else empty), (np.concatenate(out_d) if out_d else empty)


def _static_pair(a: Body, b: Body, poses: dict[str, np.ndarray]) -> list[PairHit]:
    d = ExactPair(a, b).distance(_at(poses[a.name], 0), _at(poses[b.name], 0), 0.0)
    return [PairHit("static", a.name, b.name, 0.0, 0.0, d)] if d < -STATIC_TOL else []


def _runs(a: Body, b: Body, times: np.ndarray, dists: np.ndarray, free_t: np.ndarray,
          clearance: float) -> list[PairHit]:
    """Merge evaluated instants into contiguous intervals: one hit per run of instants below
    the threshold with no free instant between them."""
    order = np.argsort(times, kind="stable")
    t_all = np.concatenate([times[order], free_t])
    d_all = np.concatenate([dists[order], np.full(free_t.shape, np.inf)])
    order = np.argsort(t_all, kind="stable")
    t_all, d_all = t_all[order], d_all[order]
    hits = _runs_below(a, b, t_all, d_all, 0.0, "collision")
    if clearance > 0:
        near = _runs_below(a, b, t_all, d_all, clearance, "clearance")
        hits += [h for h in near if h.distance > 0.0 and not any(c.t0 <= h.t1 and h.t0 <= c.t1 for c in hits)]
    return hits


def _runs_below(a: Body, b: Body, t: np.ndarray, d: np.ndarray, threshold: float, kind: str) -> list[PairHit]:
    below = d <= threshold if kind == "collision" else d < threshold
    edges = np.flatnonzero(np.diff(np.concatenate([[0], below.astype(np.int8), [0]])))
    hits = []
    for start, stop in zip(edges[::2], edges[1::2], strict=True):
        worst = start + int(np.argmin(d[start:stop]))
        hits.append(PairHit(kind, a.name, b.name, float(t[start]), float(t[stop - 1]), float(d[worst]), float(t[worst])))
    return hits
