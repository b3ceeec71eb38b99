"""Golden images: the pipeline's pictures stay as reviewed, within a tolerance for float rounding.

Regenerate after an intended change with RMOT_UPDATE_GOLDEN=1 and review the PNGs.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
from PIL import Image
from render_fixtures import arm3, plan

from rmot.sim.render.camera import Camera
from rmot.sim.render.pipeline import render_triangles
from rmot.sim.render.scene import prepare
from rmot.sim.render.shade import Shading
from rmot.sim.render.still import still_image
from rmot.sim.render.tessellate import box, capsule, cylinder, merge, sphere

GOLDEN = Path(__file__).parent / "golden"
SIZE = (160, 120)


def _compare(name: str, image: np.ndarray) -> None:
    path = GOLDEN / name
    if os.environ.get("RMOT_UPDATE_GOLDEN") == "1":
        Image.fromarray(image).save(path, format="PNG")
    golden = np.asarray(Image.open(path).convert("RGB")).astype(int)
    diff = np.abs(golden - image.astype(int)).max(axis=2)
    assert image.shape == golden.shape
    assert diff.mean() < 0.5, f"{name}: mean difference {diff.mean():.3f} levels"
    assert (diff > 8).mean() < 0.003, f"{name}: {(diff > 8).sum()} pixels differ by more than 8 levels"


def _primitives() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    parts = [(box((0.8, 0.6, 0.4)), (0.0, 0.0, 0.2), (0.55, 0.62, 0.70)),
             (sphere(0.3), (0.0, 0.0, 0.7), (0.9, 0.5, 0.1)),
             (cylinder(0.15, 0.8), (0.9, 0.3, 0.4), (0.2, 0.5, 0.9)),
             (capsule(0.1, 0.5), (-0.7, -0.4, 0.35), (0.3, 0.7, 0.3))]
    meshes = [m for m, _, _ in parts]
    merged = merge(meshes)
    offsets = np.concatenate([np.tile(o, (len(m), 1)) for m, o, _ in parts])
    colors = np.concatenate([np.tile(c, (len(m), 1)) for m, _, c in parts])
    return merged.vertices + offsets[:, None, :], merged.normals, colors


def test_primitives_gouraud() -> None:
    """Box, sphere, cylinder and capsule, Gouraud-shaded, 2x2 supersampled."""
    v, n, c = _primitives()
    cam = Camera(eye=(2.6, -2.2, 1.9), center=(0.0, 0.0, 0.35), fov_deg=40.0)
    _compare("primitives_gouraud.png", render_triangles(v, n, c, cam, SIZE, aa=2))


def test_primitives_phong() -> None:
    """The same scene with per-pixel (Phong) normal interpolation, no supersampling."""
    v, n, c = _primitives()
    cam = Camera(eye=(2.6, -2.2, 1.9), center=(0.0, 0.0, 0.35), fov_deg=40.0)
    _compare("primitives_phong.png", render_triangles(v, n, c, cam, SIZE, aa=1, shading=Shading.PHONG))


def test_cell_with_highlight_path_and_caption() -> None:
    """The demo cell at t = 1 s, a link and the post in red, the TCP path, a caption."""
    rs = prepare(plan(), robots={"r1": arm3()})
    image = still_image(rs, time=1.0, size=SIZE, aa=2, highlight=("r1/link3", "post"), caption="E300 t=1.00 s")
    _compare("cell_finding.png", image)
