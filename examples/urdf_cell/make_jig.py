"""Regenerate meshes/jig.stl, the STL fixture of the URDF example (run once; the STL is committed).

A welding/assembly jig: a 300 x 200 x 20 mm base plate with two 40 mm wide jaws, 60 mm
tall, at its ends, leaving a 220 mm wide pocket for the part. Millimetres, origin at the
centre of the base plate's underside, z up. Built as one closed surface: the U-shaped
profile in the x-z plane extruded 200 mm along y (a closed, manifold mesh: the verifier can
then also tell when a body is wholly inside it).

    .venv/bin/python examples/urdf_cell/make_jig.py
"""

from pathlib import Path

import numpy as np
import trimesh

# The U profile (x, z), counter-clockwise, and a triangulation of it that uses only its corners.
PROFILE = [(-150, 0), (150, 0), (150, 80), (110, 80), (110, 20), (-110, 20), (-110, 80), (-150, 80)]
CAP = [(0, 1, 4), (0, 4, 5), (1, 2, 3), (1, 3, 4), (0, 5, 6), (0, 6, 7)]
HALF_DEPTH = 100.0

n = len(PROFILE)
vertices = np.array([(x, y, z) for y in (-HALF_DEPTH, HALF_DEPTH) for x, z in PROFILE], dtype=float)
faces = [tri for tri in CAP] + [(a + n, c + n, b + n) for a, b, c in CAP]  # the two end caps
for i in range(n):  # the side walls: one quad per profile edge, wound so normals point out
    j = (i + 1) % n
    faces += [(i, j + n, j), (i, i + n, j + n)]
jig = trimesh.Trimesh(vertices, np.array(faces), process=True)
assert jig.is_watertight and jig.is_volume, "the jig must be a closed, consistently oriented surface"
out = Path(__file__).with_name("meshes") / "jig.stl"
out.write_text(trimesh.exchange.stl.export_stl_ascii(jig), encoding="ascii")
print(f"wrote {out}: {len(jig.faces)} triangles, volume {jig.volume / 1e3:.0f} cm^3")
