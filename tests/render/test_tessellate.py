"""Solids become closed, outward-facing triangle meshes of the right size."""

from __future__ import annotations

import numpy as np
import pytest

from rmot.lang import ir
from rmot.sim.render.tessellate import tessellate


def _area_volume(v: np.ndarray) -> tuple[float, float]:
    cross = np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0])
    area = 0.5 * np.linalg.norm(cross, axis=1).sum()
    volume = np.einsum("ij,ij->i", v[:, 0], np.cross(v[:, 1], v[:, 2])).sum() / 6.0  # divergence theorem
    return float(area), float(volume)


CASES = [
    (ir.Box((0.3, 0.5, 0.7)), 2 * (0.15 + 0.35 + 0.21), 0.105, 1e-12),
    (ir.Cylinder(0.2, 0.6), 2 * np.pi * 0.2 * 0.6 + 2 * np.pi * 0.04, np.pi * 0.04 * 0.6, 0.03),
    (ir.Sphere(0.5), 4 * np.pi * 0.25, 4 / 3 * np.pi * 0.125, 0.03),
    (ir.Capsule(0.1, 0.4), 2 * np.pi * 0.1 * 0.4 + 4 * np.pi * 0.01, np.pi * 0.01 * 0.4 + 4 / 3 * np.pi * 0.001, 0.03),
]


@pytest.mark.parametrize(("shape", "area", "volume", "rel"), CASES, ids=lambda c: type(c).__name__ if hasattr(c, "__dataclass_fields__") else "")
def test_area_and_volume_match_the_solid(shape: object, area: float, volume: float, rel: float) -> None:
    """Surface area and enclosed volume (positive: faces wind outward) are those of the solid within the facet error."""
    mesh = tessellate(shape)
    got_area, got_volume = _area_volume(mesh.vertices)
    assert got_area == pytest.approx(area, rel=rel)
    assert got_volume == pytest.approx(volume, rel=rel)


@pytest.mark.parametrize("shape", [c[0] for c in CASES], ids=lambda s: type(s).__name__)
def test_vertex_normals_are_unit_and_agree_with_the_winding(shape: object) -> None:
    """Every vertex normal has length 1 and points to the same side as its face's winding normal."""
    mesh = tessellate(shape)
    np.testing.assert_allclose(np.linalg.norm(mesh.normals, axis=2), 1.0, atol=1e-12)
    v = mesh.vertices
    face = np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0])
    real = np.linalg.norm(face, axis=1) > 1e-12
    assert np.all(np.einsum("ij,ikj->ik", face[real], mesh.normals[real]) > 0)


def test_mesh_data_is_turned_into_a_soup_with_face_normals() -> None:
    """Anything with vertices (V, 3) and faces (F, 3) becomes triangles (F, 3, 3)."""
    class Data:
        vertices = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
        faces = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])

    mesh = tessellate(Data())
    assert mesh.vertices.shape == (4, 3, 3)
    assert _area_volume(mesh.vertices)[1] == pytest.approx(1 / 6)
    np.testing.assert_allclose(mesh.normals[0], np.tile([0.0, 0.0, -1.0], (3, 1)))


def test_meshed_cylinder_gets_smooth_sides_and_sharp_cap_edges() -> None:
    """An indexed cylinder mesh: side normals are radial (smooth), cap normals stay +-z (crease kept)."""
    import trimesh

    cyl = trimesh.creation.cylinder(radius=0.1, height=0.4, sections=48)
    mesh = tessellate(type("Data", (), {"vertices": cyl.vertices, "faces": cyl.faces})())
    p, n = mesh.vertices.reshape(-1, 3), mesh.normals.reshape(-1, 3)
    face = np.repeat(np.cross(mesh.vertices[:, 1] - mesh.vertices[:, 0], mesh.vertices[:, 2] - mesh.vertices[:, 0]), 3, axis=0)
    side = np.abs(face[:, 2]) < 1e-9 * np.linalg.norm(face, axis=1).max()
    radial = p[side] * [1.0, 1.0, 0.0]
    radial /= np.linalg.norm(radial, axis=1, keepdims=True)
    np.testing.assert_allclose(n[side], radial, atol=1e-9)
    np.testing.assert_allclose(np.abs(n[~side, 2]), 1.0, atol=1e-9)
