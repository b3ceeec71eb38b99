"""Mesh loading: the classic text format, STL through trimesh, and every broken file a diagnostic."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

from rmot.lang import ir
from rmot.lang.diagnostics import Diagnostic, Severity
from rmot.lang.source import Pos, SourceFile, Span
from rmot.sim import codes, load_mesh
from rmot.sim.meshio import MeshData

CUBE_CLASSIC = """8 6
0 0 0
1 0 0
1 1 0
0 1 0
0 0 1
1 0 1
1 1 1
0 1 1
4 0 3 2 1
4 4 5 6 7
4 0 1 5 4
4 1 2 6 5
4 2 3 7 6
4 3 0 4 7
"""

SPAN = Span(SourceFile("cell.rmot", 'fixture f = mesh("m")\n'), Pos(1, 13, 12), Pos(1, 22, 21))


def _mesh(path, scale: float = 1.0) -> ir.Mesh:
    return ir.Mesh(str(path), scale, span=SPAN)


def _area_volume(m: MeshData) -> tuple[float, float]:
    tm = trimesh.Trimesh(m.vertices, m.faces, process=False)
    return float(tm.area), float(abs(tm.volume))


class TestClassicFormat:
    def test_cube_is_triangulated(self, tmp_path) -> None:
        """8 points and 6 quads give 12 triangles of a closed unit cube, scaled to metres."""
        path = tmp_path / "cube.dat"
        path.write_text(CUBE_CLASSIC)
        m = load_mesh(_mesh(path, 0.001))
        assert isinstance(m, MeshData) and m.warnings == ()
        assert m.faces.shape == (12, 3) and m.vertices.shape == (8, 3)
        area, volume = _area_volume(m)
        assert area == pytest.approx(6e-6) and volume == pytest.approx(1e-9)

    def test_one_based_indices(self, tmp_path) -> None:
        """A file indexing points 1..n is read as 1-based (same cube)."""
        lines = CUBE_CLASSIC.splitlines()
        polys = [" ".join([p.split()[0]] + [str(int(i) + 1) for i in p.split()[1:]]) for p in lines[9:]]
        path = tmp_path / "cube1.txt"
        path.write_text("\n".join(lines[:9] + polys) + "\n")
        m = load_mesh(_mesh(path))
        assert isinstance(m, MeshData)
        assert _area_volume(m) == pytest.approx((6.0, 1.0))

    @pytest.mark.parametrize(("text", "code"), [
        ("8 6\n0 0 0\n1 0 0\n", codes.MESH_TRUNCATED),
        (CUBE_CLASSIC.rsplit("\n", 3)[0], codes.MESH_TRUNCATED),
        ("eight six\n", codes.MESH_UNREADABLE),
        ("3 1\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n", codes.MESH_UNREADABLE),
        ("   \n# nothing\n", codes.MESH_EMPTY),
        ("0 0\n", codes.MESH_EMPTY),
    ])
    def test_broken_files_are_diagnostics(self, tmp_path, text: str, code) -> None:
        """Truncated, unparsable, out-of-range and empty files give an error at the mesh's span."""
        path = tmp_path / "bad.dat"
        path.write_text(text)
        d = load_mesh(_mesh(path))
        assert isinstance(d, Diagnostic)
        assert d.code is code and d.severity is Severity.ERROR and d.span == SPAN

    def test_open_surface_is_a_warning(self, tmp_path) -> None:
        """A single triangle loads, with a W560 not-watertight warning."""
        path = tmp_path / "tri.dat"
        path.write_text("3 1\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
        m = load_mesh(_mesh(path))
        assert isinstance(m, MeshData) and m.faces.tolist() == [[0, 1, 2]]
        assert [w.code for w in m.warnings] == [codes.MESH_NOT_WATERTIGHT]


class TestTrimeshFormats:
    def test_stl_in_mm(self, tmp_path) -> None:
        """A binary STL box of 100 x 200 x 300 mm loads as 0.1 x 0.2 x 0.3 m."""
        path = tmp_path / "box.stl"
        trimesh.creation.box((100, 200, 300)).export(path)
        m = load_mesh(_mesh(path, 0.001))
        assert isinstance(m, MeshData) and m.warnings == ()
        np.testing.assert_allclose(m.vertices.max(axis=0) - m.vertices.min(axis=0), [0.1, 0.2, 0.3])

    def test_truncated_stl(self, tmp_path) -> None:
        """A binary STL cut short of its declared triangle count is E563."""
        path = tmp_path / "cut.stl"
        trimesh.creation.box((1, 1, 1)).export(path)
        data = path.read_bytes()
        path.write_bytes(data[: len(data) - 120])
        d = load_mesh(_mesh(path))
        assert isinstance(d, Diagnostic) and d.code is codes.MESH_TRUNCATED

    def test_empty_and_missing(self, tmp_path) -> None:
        """An empty STL is E562; a path that does not exist is E560."""
        empty = tmp_path / "empty.stl"
        empty.write_bytes(b"")
        assert load_mesh(_mesh(empty)).code is codes.MESH_EMPTY
        missing = load_mesh(_mesh(tmp_path / "nope.obj"))
        assert isinstance(missing, Diagnostic) and missing.code is codes.MESH_MISSING
        assert "nope.obj" in missing.message

    def test_garbage_obj(self, tmp_path) -> None:
        """An OBJ with no faces is a diagnostic, not an exception."""
        path = tmp_path / "junk.obj"
        path.write_text("this is not a mesh\n")
        d = load_mesh(_mesh(path))
        assert isinstance(d, Diagnostic) and d.code in (codes.MESH_EMPTY, codes.MESH_UNREADABLE)
