"""STEP (ISO 10303-21) fixtures: `mesh("fixture.step")` / `.stp`, tessellated by OpenCASCADE.

cascadio (PyPI; the `cad` extra `make demo`/`make test` install) reads the file with
OpenCASCADE's STEP reader and tessellates it; trimesh reads the resulting glTF (metres).
OpenCASCADE works in millimetres whatever the file's unit, and its linear deflection
`TOLERANCE_MM` bounds how far a triangle strays from the CAD surface (tests/sim/test_step.py
measures it on a cylinder: the chord's sagitta stays below it). The triangles of a convex
curved face lie inside the true surface by up to that much, so the mesh is grown outward by
TOLERANCE_MM (each vertex along its normal, far enough that every face plane moves out by
it): a collision or clearance check against a STEP body is conservative by exactly that
tolerance, as if it were added to the clearance around the body.

The conversion runs in a child Python process (argv, no shell) with a time limit, so a
hostile or damaged file costs at most STEP_TIMEOUT_S and cannot take rmot down with it.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
from typing import Any

import numpy as np

__all__ = ["STEP_SUFFIXES", "TOLERANCE_MM", "StepError", "read_step"]

STEP_SUFFIXES = frozenset({".step", ".stp"})
TOLERANCE_MM = 0.05  # OpenCASCADE linear deflection (mm): the largest distance of a triangle from the surface
ANGULAR_TOLERANCE_RAD = 0.5  # OpenCASCADE angular deflection: the linear one decides on fixture-sized parts
STEP_TIMEOUT_S = 120.0
MAX_STEP_BYTES = 256 * 1024 * 1024
_MAX_GROWTH = 10.0  # a vertex moves at most 10 x the tolerance (needle-sharp corners)
_CONVERT = ("import sys, cascadio; sys.exit(0 if cascadio.step_to_glb(sys.argv[1], sys.argv[2], "
            "tol_linear=float(sys.argv[3]), tol_angular=float(sys.argv[4]), use_parallel=False) == 0 else 3)")


class StepError(Exception):
    """Why a STEP file cannot be used (the message is for the user)."""


def read_step(path: str) -> tuple[np.ndarray, np.ndarray]:
    """(vertices (V,3) m, faces (F,3)) of the STEP file's solids, grown by TOLERANCE_MM."""
    import trimesh  # late: trimesh is heavy or optional, loaded only where used

    size = os.path.getsize(path)
    if size > MAX_STEP_BYTES:
        raise StepError(f"STEP file must be at most {MAX_STEP_BYTES // (1024 * 1024)} MiB (got {size // (1024 * 1024)} MiB)")
    with open(path, "rb") as f:
        head = f.read(64).lstrip(b"\xef\xbb\xbf \t\r\n")
    if not head.startswith(b"ISO-10303-21;"):
        raise StepError("STEP file must start with ISO-10303-21; (it is not a STEP part 21 file)")
    with tempfile.TemporaryDirectory(prefix="rmot-step-") as tmp:
        glb = os.path.join(tmp, "part.glb")
        try:
            done = subprocess.run([sys.executable, "-c", _CONVERT, path, glb, repr(TOLERANCE_MM), repr(ANGULAR_TOLERANCE_RAD)],
                                  capture_output=True, timeout=STEP_TIMEOUT_S, check=False)
        except subprocess.TimeoutExpired:
            raise StepError(f"STEP file must tessellate within {STEP_TIMEOUT_S:g} s (OpenCASCADE did not finish)") from None
        if done.returncode != 0 or not os.path.isfile(glb):
            if b"No module named 'cascadio'" in done.stderr:
                raise StepError("STEP files need the cad extra: pip install 'rmot[cad]' (cascadio)")
            raise StepError("STEP file must hold solids OpenCASCADE can read and tessellate (it found none it could mesh)")
        try:
            loaded: Any = trimesh.load(glb, force="mesh", process=False)  # force="mesh": a Trimesh
        except Exception:  # an empty scene has no geometry to concatenate
            raise StepError("STEP file must hold at least one solid or surface (it holds no geometry)") from None
    loaded.merge_vertices()
    vertices = np.asarray(loaded.vertices, dtype=np.float64).reshape(-1, 3)
    faces = np.asarray(loaded.faces, dtype=np.int64).reshape(-1, 3)
    if len(faces) == 0 or not np.all(np.isfinite(vertices)):
        raise StepError("STEP file must hold at least one solid with finite coordinates")
    return grown(vertices, faces, TOLERANCE_MM / 1000.0), faces


def grown(vertices: np.ndarray, faces: np.ndarray, distance: float) -> np.ndarray:
    """Vertices moved outward so that every face plane moves out by at least `distance` (m):
    along the angle-weighted vertex normal n_v, by distance / min over the vertex's faces of
    n_v·n_f. At a corner sharper than that allows (n_v·n_f < 1/_MAX_GROWTH) the move is capped
    at _MAX_GROWTH × distance."""
    a, b, c = vertices[faces[:, 0]], vertices[faces[:, 1]], vertices[faces[:, 2]]
    cross = np.cross(b - a, c - a)
    area2 = np.linalg.norm(cross, axis=1)
    keep = area2 > 0
    unit = np.zeros_like(cross)
    unit[keep] = cross[keep] / area2[keep, None]
    normals = np.zeros_like(vertices)
    for k in range(3):  # angle-weighted: a box corner's normal is the diagonal, whatever its faces' sizes
        e1 = vertices[faces[:, (k + 1) % 3]] - vertices[faces[:, k]]
        e2 = vertices[faces[:, (k + 2) % 3]] - vertices[faces[:, k]]
        cosine = np.einsum("ij,ij->i", e1, e2) / np.maximum(np.linalg.norm(e1, axis=1) * np.linalg.norm(e2, axis=1), 1e-300)
        np.add.at(normals, faces[:, k], unit * np.arccos(np.clip(cosine, -1.0, 1.0))[:, None])
    length = np.linalg.norm(normals, axis=1)
    safe = length > 0
    normals[safe] /= length[safe, None]
    worst = np.ones(len(vertices))
    for k in range(3):
        np.minimum.at(worst, faces[keep, k], np.einsum("ij,ij->i", normals[faces[keep, k]], unit[keep]))
    factor = np.where(worst > 1.0 / _MAX_GROWTH, 1.0 / np.maximum(worst, 1e-12), _MAX_GROWTH)
    return vertices + normals * (distance * factor)[:, None]
