"""Exact distances between two bodies with coal (FCL's successor, shipped with pinocchio).

Convex shapes (the primitives, the convex hulls of meshes) go straight to coal's GJK/EPA,
which returns a signed distance (negative = penetration depth). A mesh is first measured
by its convex hull (a lower bound on the true distance); only when the hull is closer than
the caller needs is the distance confirmed on the triangles (BVH collision, then distance).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import coal
import numpy as np

from rmot.lang import ir
from rmot.sim.meshio import MeshData, is_flat

if TYPE_CHECKING:  # for annotations only: sim/scene imports this module
    from rmot.sim.scene import Body

__all__ = ["ExactPair", "coal_shapes", "exact_distance"]


def exact_distance(a: Body, b: Body, pose_a: np.ndarray, pose_b: np.ndarray) -> float:
    """Signed distance (m) between two bodies at the given world poses of their geometry."""
    return ExactPair(a, b).distance(pose_a, pose_b, 0.0)


class ExactPair:
    """coal distance between two bodies: convex shapes directly; meshes through their convex
    hull first and on the triangles only when the hull is closer than asked."""

    def __init__(self, a: Body, b: Body) -> None:
        self.a, self.b = coal_shapes(a.shape), coal_shapes(b.shape)
        self.req = coal.DistanceRequest()
        self.res = coal.DistanceResult()
        self._fixed: tuple[np.ndarray, coal.Transform3s] | None = None  # a fixture's pose, built once
        # reused: building a transform costs more than setting one
        self._scratch = (coal.Transform3s(), coal.Transform3s())

    def _tf(self, pose: np.ndarray, slot: int) -> coal.Transform3s:
        fixed = self._fixed
        if fixed is not None and fixed[0] is pose:
            return fixed[1]
        tf = self._scratch[slot]
        tf.setRotation(pose[:3, :3])
        tf.setTranslation(pose[:3, 3])
        return tf

    @property
    def convex(self) -> bool:
        """Both bodies convex: the distance is a true signed distance (GJK/EPA), which changes
        by at most how far any point of a body moves (1-Lipschitz), penetration included."""
        return self.a[1] is None and self.b[1] is None

    @property
    def fixed_pose(self) -> np.ndarray | None:
        return self._fixed[0] if self._fixed is not None else None

    def fix(self, pose: np.ndarray) -> None:
        """Remember a pose that recurs in every call (a fixture's)."""
        self._fixed = (pose, _transform(pose))

    def distance(self, pose_a: np.ndarray, pose_b: np.ndarray, need: float) -> float:
        ta, tb = self._tf(pose_a, 0), self._tf(pose_b, 1)
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
    if not is_flat(mesh.vertices):
        bvh.buildConvexHull(True, "Qt")
        return bvh.convex, bvh
    # A flat mesh (one triangle, a plane, fewer than 4 points) has no volume and coal's hull
    # raises on it (found by `make fuzz`): its hull is taken of the points and
    # copies of them 1 um along the plane's normal, a sheet one micrometre thick; a millionth
    # of its distance from the origin when that is more than a metre (qhull's precision is
    # relative to the coordinates: a 1 um sheet 170 m out crashed coal, make fuzz seed 3906).
    pts = np.asarray(mesh.vertices, dtype=np.float64)
    centred = pts - pts.mean(axis=0)
    _, _, vt = np.linalg.svd(centred if len(pts) >= 3 else np.vstack([centred, np.eye(3)]))
    normal, side = vt[-1], vt[-2]
    sheet = 1e-6 * max(1.0, float(np.max(np.abs(pts))))
    padded = np.vstack([pts, pts + sheet * normal, pts + sheet * side])
    hull = coal.BVHModelOBBRSS()
    hull.beginModel(0, len(padded))
    hull.addVertices(np.ascontiguousarray(padded))
    hull.endModel()
    hull.buildConvexHull(True, "Qt")
    return hull.convex, bvh


def _transform(pose: np.ndarray) -> coal.Transform3s:
    return coal.Transform3s(np.ascontiguousarray(pose[:3, :3]), np.ascontiguousarray(pose[:3, 3]))


