"""A 50,000-triangle robot cell as plain triangle arrays, shared by the render benchmarks."""

from __future__ import annotations

import numpy as np

from rmot.sim.render.camera import Camera
from rmot.sim.render.tessellate import TriMesh, box, capsule, cylinder, sphere


LIGHT_DIRECTION = (0.35, -0.55, 0.76)  # towards the one directional light of the benchmark


def _place(mesh: TriMesh, pose: np.ndarray) -> TriMesh:
    return TriMesh(mesh.vertices @ pose[:3, :3].T + pose[:3, 3], mesh.normals @ pose[:3, :3].T)


def _pose(x: float, y: float, z: float, ry: float = 0.0, rz: float = 0.0) -> np.ndarray:
    cy, sy, cz, sz = np.cos(ry), np.sin(ry), np.cos(rz), np.sin(rz)
    rot = np.array([[cz, -sz, 0], [sz, cz, 0], [0, 0, 1]]) @ np.array([[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]])
    m = np.eye(4)
    m[:3, :3], m[:3, 3] = rot, (x, y, z)
    return m


def _arm(base: tuple[float, float], segments: int) -> list[TriMesh]:
    """A six-link arm of cylinders and capsules, finely tessellated like CAD link meshes."""
    x, y = base
    return [
        _place(cylinder(0.16, 0.3, segments), _pose(x, y, 0.15)),
        _place(capsule(0.12, 0.3, segments), _pose(x, y, 0.45)),
        _place(capsule(0.09, 0.7, segments), _pose(x + 0.25, y, 0.85, ry=0.9)),
        _place(sphere(0.11, segments), _pose(x + 0.5, y, 1.1)),
        _place(capsule(0.07, 0.6, segments), _pose(x + 0.8, y, 1.0, ry=1.9)),
        _place(cylinder(0.06, 0.15, segments), _pose(x + 1.1, y, 0.85)),
    ]


def cell(target: int = 50_000) -> tuple[np.ndarray, np.ndarray, np.ndarray, Camera]:
    """(vertices (T, 3, 3), normals (T, 3, 3), colours (T, 3), the default camera) with T close to `target`."""
    segments = 96
    while True:
        parts: list[tuple[TriMesh, tuple[float, float, float]]] = []
        for k, base in enumerate(((0.0, 0.0), (0.0, 1.6))):
            parts += [(m, ((0.96, 0.45, 0.05), (0.93, 0.93, 0.91))[k]) for m in _arm(base, segments)]
        parts += [(_place(box((0.8, 0.6, 0.75)), _pose(1.3, 0.3, 0.375)), (0.55, 0.62, 0.70)),
                  (_place(box((1.2, 0.8, 0.7)), _pose(1.4, 1.5, 0.35)), (0.55, 0.62, 0.70)),
                  (_place(box((4.0, 0.05, 1.5)), _pose(0.8, 2.4, 0.75)), (0.40, 0.45, 0.5))]
        for i in range(6):  # parts on the table
            parts.append((_place(sphere(0.05, segments // 2), _pose(1.1 + 0.1 * i, 0.3, 0.8)), (0.2, 0.5, 0.9)))
        tiles = [(_place(box((0.5, 0.5, 0.01)), _pose(-1.0 + 0.5 * i, -0.75 + 0.5 * j, -0.005)),
                  ((0.8, 0.81, 0.83), (0.72, 0.73, 0.76))[(i + j) % 2]) for i in range(8) for j in range(7)]
        parts += tiles
        total = sum(len(m) for m, _ in parts)
        if total <= target:
            break
        segments -= 2
    verts = np.concatenate([m.vertices for m, _ in parts])
    normals = np.concatenate([m.normals for m, _ in parts])
    colors = np.concatenate([np.tile(c, (len(m), 1)) for m, c in parts]).astype(np.float32)
    lo, hi = verts.reshape(-1, 3).min(axis=0), verts.reshape(-1, 3).max(axis=0)
    camera = Camera.framing(np.stack([lo, hi]), aspect=4 / 3)
    return verts, normals, colors, camera
