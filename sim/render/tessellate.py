"""Solids -> triangle meshes with smooth normals, in the solid's own geometry frame.

Conventions follow ir.py (and coal/FCL): boxes, cylinders and capsules are centred on their
frame, cylinders and capsules run along local z. Curved surfaces get the analytic normal
at each vertex (smooth under Gouraud/Phong shading), flat faces the face normal, so box
and cylinder edges stay sharp. Meshes from files get face normals.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import njit

from rmot.lang import ir

__all__ = ["TriMesh", "box", "capsule", "cylinder", "from_indexed", "merge", "sphere", "tessellate"]

SEGMENTS = 24  # around a circle: a 1 m cylinder deviates 9 mm from the true surface


@dataclass(frozen=True, eq=False)
class TriMesh:
    """A triangle soup: vertices (T, 3, 3) m and per-vertex unit normals (T, 3, 3)."""

    vertices: np.ndarray
    normals: np.ndarray

    def __len__(self) -> int:
        return len(self.vertices)


def _unit(v: np.ndarray) -> np.ndarray:
    n = np.linalg.norm(v, axis=-1, keepdims=True)
    return v / np.where(n > 0.0, n, 1.0)


def from_indexed(points: np.ndarray, faces: np.ndarray, crease_deg: float = 35.0) -> TriMesh:
    """From points (V, 3) and faces (F, 3), with crease-aware smooth normals: each corner's
    normal averages (weighted by corner angle) the faces around its point that turn less than
    `crease_deg` from its own face, so meshed cylinders look round and CAD edges stay sharp."""
    points, faces = np.asarray(points, float), np.asarray(faces, np.int64)
    tris = points[faces]
    face_n = _unit(np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0]))
    e1 = _unit(np.roll(tris, -1, axis=1) - tris)
    e2 = _unit(np.roll(tris, 1, axis=1) - tris)
    angle = np.arccos(np.clip(np.einsum("ijk,ijk->ij", e1, e2), -1.0, 1.0)).ravel()
    order = np.argsort(faces.ravel(), kind="stable")  # corners grouped by the point they sit on
    starts = np.r_[0, np.flatnonzero(np.diff(faces.ravel()[order])) + 1, order.size]
    normals = _crease_normals(order, starts, face_n, angle, float(np.cos(np.radians(crease_deg))))
    return TriMesh(tris, normals.reshape(-1, 3, 3))


@njit(cache=True)
def _crease_normals(order: np.ndarray, starts: np.ndarray, face_n: np.ndarray, angle: np.ndarray,
                    cos_crease: float) -> np.ndarray:
    """(3F, 3) corner normals; corners of one point are order[starts[g]:starts[g + 1]]."""
    out = np.empty((order.size, 3))
    for g in range(starts.size - 1):
        group = order[starts[g]:starts[g + 1]]
        for a in group:
            fa = a // 3
            acc = np.zeros(3)
            for b in group:
                fb = b // 3
                if face_n[fa] @ face_n[fb] >= cos_crease:  # same smooth patch as corner a
                    acc += angle[b] * face_n[fb]
            length = np.sqrt(acc @ acc)
            out[a] = acc / length if length > 0.0 else face_n[fa]
    return out


def merge(meshes: list[TriMesh]) -> TriMesh:
    if not meshes:
        return TriMesh(np.zeros((0, 3, 3)), np.zeros((0, 3, 3)))
    return TriMesh(np.concatenate([m.vertices for m in meshes]), np.concatenate([m.normals for m in meshes]))


def _quads(grid: np.ndarray, normals: np.ndarray) -> TriMesh:
    """A (R, C, 3) grid of points (with normals) -> two triangles per cell, outward-facing."""
    a, b = grid[:-1, :-1], grid[:-1, 1:]
    c, d = grid[1:, 1:], grid[1:, :-1]
    na, nb, nc, nd = normals[:-1, :-1], normals[:-1, 1:], normals[1:, 1:], normals[1:, :-1]
    tris = np.concatenate([np.stack([a, b, c], 2).reshape(-1, 3, 3), np.stack([a, c, d], 2).reshape(-1, 3, 3)])
    norms = np.concatenate([np.stack([na, nb, nc], 2).reshape(-1, 3, 3), np.stack([na, nc, nd], 2).reshape(-1, 3, 3)])
    return TriMesh(tris, norms)


def box(size: tuple[float, float, float]) -> TriMesh:
    """12 triangles, face normals (sharp edges)."""
    half = np.asarray(size, float) / 2.0
    meshes = []
    for axis in range(3):
        u, v = (axis + 1) % 3, (axis + 2) % 3
        for sign in (1.0, -1.0):
            corners = np.zeros((2, 2, 3))
            for i, su in enumerate((-1.0, 1.0)):
                for j, sv in enumerate((-1.0, 1.0)):
                    corners[i, j, axis] = sign * half[axis]
                    corners[i, j, u] = su * half[u]
                    corners[i, j, v] = sv * half[v]
            if sign > 0:
                corners = corners[:, ::-1]  # keep counter-clockwise seen from outside
            normal = np.zeros(3)
            normal[axis] = sign
            meshes.append(_quads(corners, np.broadcast_to(normal, corners.shape)))
    return merge(meshes)


def _ring(radius: float, z: float, segments: int) -> np.ndarray:
    a = np.linspace(0.0, 2.0 * np.pi, segments + 1)
    return np.stack([radius * np.cos(a), radius * np.sin(a), np.full_like(a, z)], axis=1)


def _disc(radius: float, z: float, up: bool, segments: int) -> TriMesh:
    ring = _ring(radius, z, segments)
    centre = np.array([0.0, 0.0, z])
    first, second = (ring[:-1], ring[1:]) if up else (ring[1:], ring[:-1])
    tris = np.stack([np.broadcast_to(centre, first.shape), first, second], axis=1)
    normal = np.array([0.0, 0.0, 1.0 if up else -1.0])
    return TriMesh(tris, np.broadcast_to(normal, tris.shape).copy())


def cylinder(radius: float, height: float, segments: int = SEGMENTS) -> TriMesh:
    """Side with radial normals plus two flat caps."""
    rings = np.stack([_ring(radius, -height / 2, segments), _ring(radius, height / 2, segments)])
    normals = rings.copy()
    normals[..., 2] = 0.0
    side = _quads(rings, _unit(normals))
    return merge([side, _disc(radius, height / 2, True, segments), _disc(radius, -height / 2, False, segments)])


def _sphere_grid(radius: float, lat: np.ndarray, z_offset: float, segments: int) -> tuple[np.ndarray, np.ndarray]:
    """Points and unit normals of a latitude band (lat from -pi/2 .. pi/2, rows) around z."""
    lon = np.linspace(0.0, 2.0 * np.pi, segments + 1)
    n = np.stack([np.cos(lat)[:, None] * np.cos(lon), np.cos(lat)[:, None] * np.sin(lon),
                  np.broadcast_to(np.sin(lat)[:, None], (len(lat), len(lon)))], axis=2)
    p = radius * n
    p[..., 2] += z_offset
    return p, n


def sphere(radius: float, segments: int = SEGMENTS) -> TriMesh:
    lat = np.linspace(-np.pi / 2, np.pi / 2, segments // 2 + 1)
    return _quads(*_sphere_grid(radius, lat, 0.0, segments))


def capsule(radius: float, length: float, segments: int = SEGMENTS) -> TriMesh:
    """A cylinder of `length` between two hemispheres: one smooth latitude grid, split at the equator."""
    half = segments // 4
    south = np.linspace(-np.pi / 2, 0.0, half + 1)
    north = np.linspace(0.0, np.pi / 2, half + 1)
    p_s, n_s = _sphere_grid(radius, south, -length / 2, segments)
    p_n, n_n = _sphere_grid(radius, north, length / 2, segments)
    return _quads(np.concatenate([p_s, p_n]), np.concatenate([n_s, n_n]))


def tessellate(shape: object) -> TriMesh:
    """A solid (ir.Box/Cylinder/Sphere/Capsule, or anything with vertices (V, 3) and faces (F, 3))."""
    if isinstance(shape, ir.Box):
        return box(shape.size)
    if isinstance(shape, ir.Cylinder):
        return cylinder(shape.radius, shape.height)
    if isinstance(shape, ir.Sphere):
        return sphere(shape.radius)
    if isinstance(shape, ir.Capsule):
        return capsule(shape.radius, shape.length)
    vertices, faces = getattr(shape, "vertices", None), getattr(shape, "faces", None)
    if vertices is None or faces is None:
        raise TypeError(f"shape must be a primitive or have vertices and faces (got {type(shape).__name__})")
    return from_indexed(vertices, faces)
