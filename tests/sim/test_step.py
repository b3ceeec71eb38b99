"""STEP fixtures (sim/step.py): tessellation within the stated tolerance, grown by it, and
collisions where the geometry is.

Witnesses: the dimensions typed into the STEP files (tests/sim/step_files.py writes them
entity by entity, no rmot code), the chord's sagitta r(1 - cos(gap/2)) of the tessellated
circle, and the verifier's E300 against a robot moved into / above the part.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from rmot.compiler.cli.compile_cmd import compile_program
from rmot.compiler.frontend import load_program
from rmot.sim.step import TOLERANCE_MM, read_step
from step_files import step_box, step_cylinder

TOL = TOLERANCE_MM / 1000.0


def test_box_is_its_dimensions_grown_by_the_tolerance(tmp_path: Path) -> None:
    (tmp_path / "box.step").write_text(step_box(200.0, 100.0, 50.0))
    vertices, faces = read_step(str(tmp_path / "box.step"))
    assert len(faces) == 12
    assert np.allclose(vertices.min(axis=0), [-TOL] * 3, atol=1e-12)
    assert np.allclose(vertices.max(axis=0), [0.2 + TOL, 0.1 + TOL, 0.05 + TOL], atol=1e-12)


def test_cylinder_tessellation_within_tolerance_and_grown_mesh_contains_it(tmp_path: Path) -> None:
    import cascadio
    import trimesh

    (tmp_path / "c.step").write_text(step_cylinder(50.0, 100.0))
    cascadio.step_to_glb(str(tmp_path / "c.step"), str(tmp_path / "c.glb"), tol_linear=TOLERANCE_MM, tol_angular=0.5)
    raw = trimesh.load(str(tmp_path / "c.glb"), force="mesh")
    rim = raw.vertices[(np.abs(raw.vertices[:, 2]) < 1e-9) & (np.hypot(raw.vertices[:, 0], raw.vertices[:, 1]) > 0.049)]
    angles = np.sort(np.unique(np.round(np.arctan2(rim[:, 1], rim[:, 0]), 9)))
    gap = float(np.max(np.diff(np.append(angles, angles[0] + 2 * math.pi))))
    assert 0.05 * (1 - math.cos(gap / 2)) <= TOL  # the chord's sagitta: the stated tolerance holds
    vertices, faces = read_step(str(tmp_path / "c.step"))
    side = np.abs(np.einsum("ij,ij->i", np.cross(vertices[faces[:, 1]] - vertices[faces[:, 0]],
                                                  vertices[faces[:, 2]] - vertices[faces[:, 0]]), [[0, 0, 1]])) < 1e-12
    mids = (vertices[faces[side]].sum(axis=1)) / 3.0  # centroids of the lateral triangles
    assert np.all(np.hypot(mids[:, 0], mids[:, 1]) >= 0.05)  # grown: the true surface is inside
    assert np.all(np.hypot(vertices[:, 0], vertices[:, 1]) <= 0.05 + 10 * TOL)


PROGRAM = """cell c {{
  robot r1 = abb_irb120
  fixture block = {mesh} at pose(x=350mm, y=-100mm)
}}
program p on r1 {{
  move joint joints(0, 0, 0, 0, 30, 0) deg
  move joint pose(x=450mm, y=-50mm, z={z}mm, ry=180deg)
}}
"""


@pytest.mark.parametrize("z, collides", [(30, True), (160, False)])
def test_step_fixture_collides_where_its_geometry_is(tmp_path: Path, z: int, collides: bool) -> None:
    """The box spans x 350..550, y -100..0, z 0..50 mm: the flange at z = 30 mm is inside."""
    (tmp_path / "box.step").write_text(step_box(200.0, 100.0, 50.0))
    (tmp_path / "p.rmot").write_text(PROGRAM.format(mesh='mesh("box.step")', z=z))
    outcome = compile_program(str(tmp_path / "p.rmot"), ("json",), use_cache=False)
    hits = [d for d in outcome.diagnostics if d.code.id == "E300"]
    assert bool(hits) == collides, [d.message for d in outcome.diagnostics]
    if collides:
        assert "'block'" in hits[0].message


@pytest.mark.parametrize("text, words", [
    ("solid not a step file\n", "ISO-10303-21"),
    ("ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\n#1=GARBAGE(((;\nENDSEC;\nEND-ISO-10303-21;\n", "OpenCASCADE"),
    ("ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\nENDSEC;\nEND-ISO-10303-21;\n", "OpenCASCADE"),
])
def test_bad_step_file_is_a_located_error(tmp_path: Path, text: str, words: str) -> None:
    (tmp_path / "bad.step").write_text(text)
    (tmp_path / "p.rmot").write_text(PROGRAM.format(mesh='mesh("bad.step")', z=160))
    outcome = compile_program(str(tmp_path / "p.rmot"), ("json",), use_cache=False)
    found = [d for d in outcome.diagnostics if d.is_error]
    assert found and found[0].code.id == "E561" and words in found[0].message, [d.message for d in found]
    assert found[0].span is not None and found[0].span.start.line == 3


def test_step_takes_no_unit(tmp_path: Path) -> None:
    (tmp_path / "box.step").write_text(step_box(10.0, 10.0, 10.0))
    (tmp_path / "p.rmot").write_text(PROGRAM.format(mesh='mesh("box.step", unit=mm)', z=160))
    front = load_program(str(tmp_path / "p.rmot"))
    assert [d.code.id for d in front.diagnostics if d.is_error][:1] == ["E543"]
