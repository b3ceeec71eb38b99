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

__all__ = ["CONTACT_TOL", "PairHit", "Timeline", "check_timeline", "candidate_pairs"]

CONTACT_TOL = 1e-5  # m: bisection stops when no body can move more than this
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
    disp = {name: _displacement(scene, scene.body(name), timeline) for name in poses}
    hits: list[PairHit] = []
    for a, b in pairs:
        if not a.moves and not b.moves:
            hits += _static_pair(a, b, poses)
            continue
        hits += _moving_pair(scene, timeline, a, b, poses, disp, clearance)
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


def _displacement(scene: Scene, body: Body, timeline: Timeline) -> np.ndarray:
    """(M-1,) bound on how far any point of the body moves over each interval (m)."""
    m = timeline.t.shape[0]
    if not body.moves:
        return np.zeros(max(m - 1, 0))
    q = timeline.q[body.robot]  # type: ignore[index]
    dt = np.diff(timeline.t)
    acc = timeline.accel[body.robot]  # type: ignore[index]
    acc_bound = np.maximum(acc[:-1], acc[1:])
    deviation = acc_bound * (dt[:, None] ** 2) / 8.0  # true path vs linear interpolation
    return (np.abs(np.diff(q, axis=0)) + deviation) @ body.reach + 0.0


def _lower_bound(a: Body, b: Body, pa: np.ndarray, pb: np.ndarray) -> np.ndarray:
    """(M,) a lower bound on the distance between a and b at every sample (m)."""
    if b.kind == "fixture":
        a, b, pa, pb = b, a, pb, pa
    centres_b = _world_spheres(b, pb)
    if a.kind == "fixture":
        box = a.local.copy()
        box[:3, 3] += box[:3, :3] @ a.obb_centre
        inv = np.linalg.inv(box)
        local = centres_b @ inv[:3, :3].T + inv[:3, 3]
        gap = np.abs(local) - a.obb_half
        dist = np.linalg.norm(np.maximum(gap, 0.0), axis=-1)
        return np.min(dist - b.spheres[:, 3], axis=-1)
    centres_a = _world_spheres(a, pa)
    diff = centres_a[:, :, None, :] - centres_b[:, None, :, :]
    dist = np.linalg.norm(diff, axis=-1) - a.spheres[None, :, None, 3] - b.spheres[None, None, :, 3]
    return np.min(dist, axis=(1, 2))


def _world_spheres(body: Body, poses: np.ndarray) -> np.ndarray:
    """(M, K, 3) sphere centres in world."""
    return np.einsum("mij,kj->mki", poses[:, :3, :3], body.spheres[:, :3]) + poses[:, None, :3, 3]


def _moving_pair(scene: Scene, timeline: Timeline, a: Body, b: Body, poses: dict[str, np.ndarray],
                 disp: dict[str, np.ndarray], clearance: float) -> list[PairHit]:
    pa, pb = poses[a.name], poses[b.name]
    m = timeline.t.shape[0]
    bound = np.broadcast_to(_lower_bound(a, b, pa, pb), (m,))
    motion = _motion(a, disp, m) + _motion(b, disp, m)
    need = np.append(motion, 0.0) + clearance  # the last sample needs no motion margin
    flagged = np.nonzero(bound < need)[0]
    if flagged.size == 0:
        return []
    exact = _ExactPair(a, b)
    times: list[float] = []
    dists: list[float] = []
    for i in flagged:
        d = exact.distance(_at(pa, i), _at(pb, i), float(need[i]))
        times.append(float(timeline.t[i]))
        dists.append(d)
        if i + 1 < m and d < need[i]:
            sub = _bisect(scene, timeline, exact, a, b, i, d, clearance)
            times += sub[0]
            dists += sub[1]
    # samples not evaluated exactly are free (their lower bound already clears the margin)
    free_t = timeline.t[np.setdiff1d(np.arange(m), flagged)]
    return _runs(a, b, np.array(times), np.array(dists), free_t, clearance)


def _motion(body: Body, disp: dict[str, np.ndarray], m: int) -> np.ndarray:
    return disp[body.name] if body.name in disp else np.zeros(m - 1)


def _at(poses: np.ndarray, i: int) -> np.ndarray:
    return poses[i] if poses.shape[0] > 1 else poses[0]


def _bisect(scene: Scene, timeline: Timeline, exact: _ExactPair, a: Body, b: Body, i: int,
            d0: float, clearance: float) -> tuple[list[float], list[float]]:
    """Evaluate inside interval i until the motion bound clears the distances (see module doc)."""
    robots = sorted({body.robot for body in (a, b) if body.moves})  # type: ignore[type-var]
    t = timeline.t
    qa = {r: timeline.q[r][i] for r in robots}
    qb = {r: timeline.q[r][i + 1] for r in robots}
    pad = {r: np.maximum(timeline.accel[r][i], timeline.accel[r][i + 1]) * (t[i + 1] - t[i]) ** 2 / 8 for r in robots}
    fixed = {body.name: body.local for body in (a, b) if body.kind == "fixture"}
    out_t: list[float] = []
    out_d: list[float] = []
    stack = [(float(t[i]), qa, d0, float(t[i + 1]), qb, 1.0)]
    while stack:
        t0, q0, d, t1, q1, frac = stack.pop()
        motion = sum(_body_motion(body, q0, q1, pad, frac) for body in (a, b) if body.moves)
        # safe, already a contact, or already closer than the clearance with no contact possible
        if d >= motion + clearance or d <= 0.0 or (motion <= d < clearance):
            continue
        if motion < CONTACT_TOL or frac < 2.0 ** -_MAX_DEPTH:
            continue
        tm = (t0 + t1) / 2
        qm = {r: (q0[r] + q1[r]) / 2 for r in robots}
        pm = {r: scene.poses(r, qm[r][None]) for r in robots}
        pose = lambda body: fixed[body.name] if body.name in fixed else pm[body.robot][body.name][0]  # noqa: E731
        dm = exact.distance(pose(a), pose(b), motion / 2 + clearance)
        out_t.append(tm)
        out_d.append(dm)
        stack.append((tm, qm, dm, t1, q1, frac / 2))
        stack.append((t0, q0, d, tm, qm, frac / 2))
    return out_t, out_d


def _body_motion(body: Body, q0: dict, q1: dict, pad: dict, frac: float) -> float:
    r = body.robot
    return float((np.abs(q1[r] - q0[r]) + pad[r] * frac * frac) @ body.reach)


def _static_pair(a: Body, b: Body, poses: dict[str, np.ndarray]) -> list[PairHit]:
    d = _ExactPair(a, b).distance(_at(poses[a.name], 0), _at(poses[b.name], 0), 0.0)
    return [PairHit("static", a.name, b.name, 0.0, 0.0, d)] if d <= 0.0 else []


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
        hits += [h for h in near if h.distance > 0.0]
    return hits


def _runs_below(a: Body, b: Body, t: np.ndarray, d: np.ndarray, threshold: float, kind: str) -> list[PairHit]:
    below = d <= threshold if kind == "collision" else d < threshold
    hits = []
    start = None
    for k in range(len(t) + 1):
        inside = k < len(t) and below[k]
        if inside and start is None:
            start = k
        elif not inside and start is not None:
            seg = slice(start, k)
            hits.append(PairHit(kind, a.name, b.name, float(t[start]), float(t[k - 1]), float(np.min(d[seg]))))
            start = None
    return hits


# --------------------------------------------------------------------------- exact distances


class _ExactPair:
    """coal distance between two bodies: convex shapes directly; meshes through their convex
    hull first and on the triangles only when the hull is closer than asked."""

    def __init__(self, a: Body, b: Body) -> None:
        self.a, self.b = coal_shapes(a.shape), coal_shapes(b.shape)
        self.req = coal.DistanceRequest()
        self.res = coal.DistanceResult()

    def distance(self, pose_a: np.ndarray, pose_b: np.ndarray, need: float) -> float:
        ta, tb = _transform(pose_a), _transform(pose_b)
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

