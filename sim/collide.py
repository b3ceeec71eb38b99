"""Collision and clearance over a sampled timeline, with a no-miss guarantee between samples.

Engine (measured, see tests/benchmarks/bench_verify.py): coal (FCL's successor, shipped
with pinocchio) called pair by pair on primitives and convex hulls, behind a numpy broad
phase; python-fcl is only the benchmark's reference.

The guarantee — no contact between two samples is missed:
  * Between samples the robots follow the linear interpolation of their joint samples; the
    true path deviates from it by at most max|qdd|·dt²/8 per joint, added as padding.
  * A point p of a body carried by joints j moves by at most
        D = Σ_j |Δq_j| · reach_j(body)
    while q goes from q_i to q_i+1 (reach_j: a bound on |p - origin of joint j|, from the
    chain offsets, see scene.py; 1 for a prismatic joint). Two bodies can therefore not
    touch during the interval if their distance at its start, d_i, is at least D_a + D_b.
  * Level 1 bounds d_i from below for every pair and every sample at once (numpy): sphere
    covers of the moving solids against oriented boxes of the fixtures or each other's
    spheres. Intervals where the bound is not enough go to level 2: the exact distance with
    coal (convex hulls of meshes first, confirmed on the triangles when close). If even
    that is not enough, the interval is bisected until D < CONTACT_TOL (10 µm).
So a contact is found unless it is shallower than CONTACT_TOL; the same bound with the
clearance added finds every approach closer than the clearance.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

import coal
import numpy as np

from rmot.compiler import ir
from rmot.sim.meshio import MeshData
from rmot.sim.scene import Body, Scene

__all__ = ["CONTACT_TOL", "exact_distance", "PairHit", "Timeline", "check_timeline", "candidate_pairs"]

CONTACT_TOL = 1e-5  # m: bisection stops when no body can move more than this
STATIC_TOL = 1e-4  # m: bodies that never move may touch (a robot standing on its stand)
_MAX_DEPTH = 40


@dataclass(frozen=True, eq=False)
class Timeline:
    """Shared samples: t (M,); q[robot] (M, dof); accel[robot] (M, dof) bound on |qdd|."""

    t: np.ndarray
    q: dict[str, np.ndarray]
    accel: dict[str, np.ndarray]


@dataclass(frozen=True)
class PairHit:
    """One contiguous interval where two bodies touch ("collision") or come closer than the
    clearance ("clearance"), or a permanent overlap of two static bodies ("static")."""

    kind: str
    a: str
    b: str
    t0: float
    t1: float
    distance: float  # m: the smallest signed distance found (negative = penetration)


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
    motion = {r: _joint_motion(scene, r, timeline) for r in timeline.q}
    centres = _LazyCentres(scene, poses)
    blocks = {b.name: _block_spheres(b, poses[b.name]) for b in scene.bodies if b.kind != "fixture"}
    hits: list[PairHit] = []
    for a, b in pairs:
        if not a.moves and not b.moves:
            hits += _static_pair(a, b, poses)
            continue
        # the clearance is about other things in the cell: a robot's own solids sit close by design
        own = a.robot is not None and a.robot == b.robot
        hits += _moving_pair(scene, timeline, a, b, poses, (centres, blocks), motion, 0.0 if own else clearance)
    return hits


def _sample_poses(scene: Scene, timeline: Timeline) -> dict[str, np.ndarray]:
    """name -> (M, 4, 4) world poses of every robot body; fixtures -> (1, 4, 4)."""
    poses: dict[str, np.ndarray] = {}
    for robot, q in timeline.q.items():
        poses.update(scene.poses(robot, q))
    for body in scene.bodies:
        if body.kind == "fixture":
            poses[body.name] = body.local[None]
    return poses


def _joint_motion(scene: Scene, robot: str, timeline: Timeline) -> tuple[np.ndarray, np.ndarray]:
    """(|Δq| (M-1, dof), pad (M-1, dof)) per interval in model joint space; pad bounds how far
    the true path strays from the linear interpolation of the samples: max|qdd|·dt²/8."""
    q = _model_q(scene, robot, timeline.q[robot])
    dt = np.diff(timeline.t)
    acc = timeline.accel[robot]
    pad = _model_abs(scene, robot, np.maximum(acc[:-1], acc[1:]) * (dt[:, None] ** 2) / 8.0)
    return np.abs(np.diff(q, axis=0)), pad


def _pair_reach(scene: Scene, a: Body, b: Body) -> dict[str, np.ndarray]:
    """robot -> (dof,) weights w with: relative motion of a and b <= Σ_j |Δq_j| w_j.

    Bodies of one robot only move relative to each other through the joints between them
    (the joints before both carry them together), so for a pair of one serial robot only
    the joints in (lower joint, upper joint] count, with the upper body's reach."""
    out: dict[str, np.ndarray] = {}
    if a.robot is not None and a.robot == b.robot:
        low, high = (a, b) if a.joint <= b.joint else (b, a)
        mask = np.zeros(scene.robots[a.robot].robot.dof)
        mask[low.joint:high.joint] = 1.0  # joints low.joint+1 .. high.joint (1-based)
        out[a.robot] = high.reach * mask  # type: ignore[operator]
        return out
    for body in (a, b):
        if body.moves:
            out[body.robot] = out.get(body.robot, 0.0) + body.reach  # type: ignore[index, operator]
    return out


_BLOCK = 16  # samples per block of the coarse (block) broad phase


def _block_spheres(body: Body, poses: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per block of _BLOCK samples, one sphere holding the body at every sample of the block:
    (nB, 3) centres, (nB,) radii (built on the body's single bounding sphere)."""
    centre = body.spheres[:, :3].mean(axis=0)
    radius = float(np.max(np.linalg.norm(body.spheres[:, :3] - centre, axis=1) + body.spheres[:, 3]))
    track = poses[:, :3, :3] @ centre + poses[:, :3, 3]  # (M, 3)
    m = track.shape[0]
    n_blocks = -(-m // _BLOCK)
    padded = np.concatenate([track, np.repeat(track[-1:], n_blocks * _BLOCK - m, axis=0)])
    blocks = padded.reshape(n_blocks, _BLOCK, 3)
    mid = (blocks.max(axis=1) + blocks.min(axis=1)) / 2
    spread = np.sqrt(np.max(np.sum((blocks - mid[:, None]) ** 2, axis=-1), axis=1))
    return mid, spread + radius


def _block_bound(a: Body, b: Body, blocks: dict[str, tuple[np.ndarray, np.ndarray]]) -> np.ndarray:
    """(nB,) a lower bound on the pair's distance over each block of samples."""
    if b.kind == "fixture":
        a, b = b, a
    cb, rb = blocks[b.name]
    if a.kind == "fixture":
        return _point_box_distance(a, cb) - rb
    ca, ra = blocks[a.name]
    return np.linalg.norm(ca - cb, axis=-1) - ra - rb


def _point_box_distance(fixture: Body, points: np.ndarray) -> np.ndarray:
    """Distance from world points (..., 3) to the fixture's bounding box (0 inside)."""
    box = fixture.local.copy()
    box[:3, 3] += box[:3, :3] @ fixture.obb_centre
    local = (points - box[:3, 3]) @ box[:3, :3]
    return np.linalg.norm(np.maximum(np.abs(local) - fixture.obb_half, 0.0), axis=-1)


def _lower_bound(a: Body, b: Body, pa: np.ndarray, pb: np.ndarray,
                 centres: dict[str, np.ndarray] | None = None, idx: np.ndarray | None = None) -> np.ndarray:
    """(M,) a lower bound on the distance between a and b at every sample (m) — or at the
    samples `idx` only. `centres`: world sphere centres already computed, by body name."""
    if b.kind == "fixture":
        a, b, pa, pb = b, a, pb, pa
    centres = centres or {}
    centres_b = centres[b.name] if b.name in centres else _world_spheres(b, pb)
    if idx is not None:
        centres_b = centres_b[idx]
    if a.kind == "fixture":
        return np.min(_point_box_distance(a, centres_b) - b.spheres[:, 3], axis=-1)
    centres_a = centres[a.name] if a.name in centres else _world_spheres(a, pa)
    if idx is not None:
        centres_a = centres_a[idx]
    diff = centres_a[:, :, None, :] - centres_b[:, None, :, :]
    dist = np.linalg.norm(diff, axis=-1) - a.spheres[None, :, None, 3] - b.spheres[None, None, :, 3]
    return np.min(dist, axis=(1, 2))


class _LazyCentres(dict):
    """name -> (M, K, 3) world sphere centres, computed for a body when first asked for."""

    def __init__(self, scene: Scene, poses: dict[str, np.ndarray]) -> None:
        super().__init__()
        self._scene, self._poses = scene, poses

    def __contains__(self, name: object) -> bool:
        return name in self._poses and self._poses[name].shape[0] > 1  # type: ignore[index]

    def __missing__(self, name: str) -> np.ndarray:
        value = _world_spheres(self._scene.body(name), self._poses[name])
        self[name] = value
        return value


def _world_spheres(body: Body, poses: np.ndarray) -> np.ndarray:
    """(M, K, 3) sphere centres in world."""
    return np.matmul(body.spheres[None, :, :3], poses[:, :3, :3].transpose(0, 2, 1)) + poses[:, None, :3, 3]


def _moving_pair(scene: Scene, timeline: Timeline, a: Body, b: Body, poses: dict[str, np.ndarray],
                 bounds: tuple[dict, dict], motion: dict[str, tuple[np.ndarray, np.ndarray]],
                 clearance: float) -> list[PairHit]:
    pa, pb = poses[a.name], poses[b.name]
    centres, blocks = bounds
    m = timeline.t.shape[0]
    reach = _pair_reach(scene, a, b)
    move = sum(((dq + pad) @ reach[r] for r, (dq, pad) in motion.items() if r in reach), np.zeros(m - 1))
    need = np.append(move, 0.0) + clearance  # the last sample needs no motion margin
    # coarse: whole blocks of samples whose block bound clears every margin in the block
    n_blocks = -(-m // _BLOCK)
    block_need = np.concatenate([need, np.full(n_blocks * _BLOCK - m, -np.inf)]).reshape(n_blocks, _BLOCK).max(axis=1)
    near_blocks = np.nonzero(_block_bound(a, b, blocks) < block_need)[0]
    if near_blocks.size == 0:
        return []
    idx = (near_blocks[:, None] * _BLOCK + np.arange(_BLOCK)).ravel()
    idx = idx[idx < m]
    # fine: per-sample sphere bounds in those blocks
    flagged = idx[_lower_bound(a, b, pa, pb, centres, idx) < need[idx]]
    if flagged.size == 0:
        return []
    exact = _ExactPair(a, b)
    pose_a, pose_b = _per_sample(pa, exact), _per_sample(pb, exact)
    evaluated, dists_at, split = _advance(flagged, need, move, clearance,
                                          lambda i: exact.distance(pose_a(i), pose_b(i), float(need[i])))
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
             distance_at) -> tuple[np.ndarray, np.ndarray, np.ndarray]:  # type: ignore[no-untyped-def]
    """Conservative advancement over the flagged samples: an exact distance d at sample i
    certifies every following interval up to where the accumulated motion bound reaches
    d - clearance, so those samples need no evaluation of their own.
    Returns (evaluated samples, their distances, intervals that still need splitting)."""
    cum = np.concatenate([[0.0], np.cumsum(move)])  # cum[k]: motion bound from sample 0 to k
    evaluated: list[int] = []
    dists: list[float] = []
    split: list[int] = []
    k = 0
    m = need.shape[0]
    while k < flagged.size:
        i = int(flagged[k])
        d = distance_at(i)
        evaluated.append(i)
        dists.append(d)
        # intervals i..J are safe while cum[J+1] <= cum[i] + d - clearance
        last_safe = int(np.searchsorted(cum, cum[i] + d - clearance, side="right")) - 2
        if last_safe < i and d > 0.0 and i + 1 < m:
            split.append(i)  # not certified by its own start: look inside (a contact needs no look)
        k = int(np.searchsorted(flagged, max(last_safe + 1, i + 1), side="left"))
    return np.array(evaluated, dtype=int), np.array(dists), np.array(split, dtype=int)


def _at(poses: np.ndarray, i: int) -> np.ndarray:
    return poses[i] if poses.shape[0] > 1 else poses[0]


def _per_sample(poses: np.ndarray, exact: _ExactPair):  # type: ignore[no-untyped-def]
    """i -> pose; a pose that never changes is one object, registered with `exact` once."""
    if poses.shape[0] > 1:
        return poses.__getitem__
    single = poses[0]
    exact.fix(single)
    return lambda i: single


def _bisect(scene: Scene, timeline: Timeline, exact: _ExactPair, a: Body, b: Body, reach: dict[str, np.ndarray],
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
        move = sum((np.abs(_model_q(scene, r, qb[r]) - _model_q(scene, r, qa[r])) + pad[r] * (frac**2)[:, None]) @ reach[r]
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
        pose = lambda body, k: fixed[body.name] if body.name in fixed else pm[body.robot][body.name][k]  # noqa: E731
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


def _model_q(scene: Scene, robot: str, q: np.ndarray) -> np.ndarray:
    """Controller joint values -> the kinematic model's (a linear map: Fanuc's J2/J3 coupling);
    the reach bounds are per model joint."""
    to_model = getattr(scene.robots[robot].robot, "to_model", None)
    return np.asarray(to_model(q)) if to_model is not None else q


def _model_abs(scene: Scene, robot: str | None, v: np.ndarray) -> np.ndarray:
    """Bound on |model-space vector| from |controller-space vector| v (..., dof): |C| v."""
    entry = scene.robots[robot]  # type: ignore[index]
    coupling = np.abs(_model_q(scene, entry.name, np.eye(entry.robot.dof)))  # row k = C e_k
    return v @ coupling


def _static_pair(a: Body, b: Body, poses: dict[str, np.ndarray]) -> list[PairHit]:
    d = _ExactPair(a, b).distance(_at(poses[a.name], 0), _at(poses[b.name], 0), 0.0)
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
    return [PairHit(kind, a.name, b.name, float(t[start]), float(t[stop - 1]), float(np.min(d[start:stop])))
            for start, stop in zip(edges[::2], edges[1::2], strict=True)]


# --------------------------------------------------------------------------- exact distances


def exact_distance(a: Body, b: Body, pose_a: np.ndarray, pose_b: np.ndarray) -> float:
    """Signed distance (m) between two bodies at the given world poses of their geometry."""
    return _ExactPair(a, b).distance(pose_a, pose_b, 0.0)


class _ExactPair:
    """coal distance between two bodies: convex shapes directly; meshes through their convex
    hull first and on the triangles only when the hull is closer than asked."""

    def __init__(self, a: Body, b: Body) -> None:
        self.a, self.b = coal_shapes(a.shape), coal_shapes(b.shape)
        self.req = coal.DistanceRequest()
        self.res = coal.DistanceResult()
        self._fixed: tuple[np.ndarray, coal.Transform3s] | None = None  # a fixture's pose, built once

    def _tf(self, pose: np.ndarray) -> coal.Transform3s:
        fixed = self._fixed
        if fixed is not None and fixed[0] is pose:
            return fixed[1]
        return _transform(pose)

    @property
    def fixed_pose(self) -> np.ndarray | None:
        return self._fixed[0] if self._fixed is not None else None

    def fix(self, pose: np.ndarray) -> None:
        """Remember a pose that recurs in every call (a fixture's)."""
        self._fixed = (pose, _transform(pose))

    def distance(self, pose_a: np.ndarray, pose_b: np.ndarray, need: float) -> float:
        ta, tb = self._tf(pose_a), self._tf(pose_b)
        (hull_a, mesh_a), (hull_b, mesh_b) = self.a, self.b
        self.res.clear()
        d = coal.distance(hull_a, ta, hull_b, tb, self.req, self.res)
        if d >= need or (mesh_a is None and mesh_b is None):
            return float(d)
        return _mesh_distance(mesh_a or hull_a, ta, mesh_b or hull_b, tb)


def _mesh_distance(a: object, ta: coal.Transform3s, b: object, tb: coal.Transform3s) -> float:
    """Signed distance with at least one triangle mesh: penetration depth if they collide."""
    creq = coal.CollisionRequest()
    creq.enable_contact = True
    cres = coal.CollisionResult()
    if coal.collide(a, ta, b, tb, creq, cres):
        depth = max((c.penetration_depth for c in cres.getContacts()), key=abs, default=0.0)
        return -abs(float(depth))
    res = coal.DistanceResult()
    return float(coal.distance(a, ta, b, tb, coal.DistanceRequest(), res))


_SHAPE_CACHE: dict[int, tuple[object, object | None, object]] = {}  # id -> (hull, bvh, shape kept alive)


def coal_shapes(shape: object) -> tuple[object, object | None]:
    """(convex coal shape, triangle BVH or None) for an ir primitive or a MeshData."""
    key = id(shape)
    cached = _SHAPE_CACHE.get(key)
    if cached is not None and cached[2] is shape:
        return cached[0], cached[1]
    if isinstance(shape, ir.Box):
        out: tuple[object, object | None] = (coal.Box(*shape.size), None)
    elif isinstance(shape, ir.Sphere):
        out = (coal.Sphere(shape.radius), None)
    elif isinstance(shape, ir.Cylinder):
        out = (coal.Cylinder(shape.radius, shape.height), None)
    elif isinstance(shape, ir.Capsule):
        out = (coal.Capsule(shape.radius, shape.length), None)
    elif isinstance(shape, MeshData):
        out = _mesh_shapes(shape)
    else:
        raise TypeError(f"no collision shape for {type(shape).__name__}")
    _SHAPE_CACHE[key] = (out[0], out[1], shape)
    return out


def _mesh_shapes(mesh: MeshData) -> tuple[object, object]:
    bvh = coal.BVHModelOBBRSS()
    bvh.beginModel(len(mesh.faces), len(mesh.vertices))
    bvh.addVertices(np.ascontiguousarray(mesh.vertices, dtype=np.float64))
    bvh.addTriangles(np.ascontiguousarray(mesh.faces, dtype=np.int64))
    bvh.endModel()
    bvh.buildConvexHull(True, "Qt")
    return bvh.convex, bvh


def _transform(pose: np.ndarray) -> coal.Transform3s:
    return coal.Transform3s(np.ascontiguousarray(pose[:3, :3]), np.ascontiguousarray(pose[:3, 3]))

