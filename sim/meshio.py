"""Mesh files -> triangle arrays in metres, or a Diagnostic at the span that names the file.

Formats: STL, OBJ, PLY, OFF through trimesh; STEP (.step/.stp) through OpenCASCADE
(sim/step.py: tessellated within 0.05 mm, grown by it); every other suffix is read as the classic
"points then polygons" text format (LANGUAGE.md §3):

    <point count> <polygon count>          (on one line or on two)
    x y z                                  (one line per point)
    k i1 i2 ... ik                         (one line per polygon, fan-triangulated)

Polygon indices are 0-based; a file whose indices run 1..point count (and never use 0) is
read as 1-based, as several old tools wrote it. `#` starts a comment.

A missing, unreadable, truncated or empty file is an error; a surface that is not a closed
manifold is a warning (W560) carried in `MeshData.warnings`: collision checks work on the
triangles, but a body wholly inside an open surface is not detected as a contact.
"""

from __future__ import annotations

import errno
import functools
import logging
import os
from dataclasses import dataclass
from stat import S_ISREG

import numpy as np

from rmot.lang import ir
from rmot.lang.diagnostics import Code, Diagnostic, Severity
from rmot.sim import codes
from rmot.sim.step import STEP_SUFFIXES, StepError, read_step

__all__ = ["MeshData", "centroid", "load_mesh", "parse_classic"]

_TRIMESH_SUFFIXES = {".stl", ".obj", ".ply", ".off"}


@dataclass(frozen=True, eq=False)
class MeshData:
    """vertices: (V, 3) float64 in metres (scale applied); faces: (F, 3) int64 vertex indexes."""

    vertices: np.ndarray
    faces: np.ndarray
    warnings: tuple[Diagnostic, ...] = ()

    def __post_init__(self) -> None:
        self.vertices.setflags(write=False)
        self.faces.setflags(write=False)


class _MeshError(Exception):
    def __init__(self, code: Code, message: str) -> None:
        super().__init__(message)
        self.code = code
        self.message = message


def load_mesh(mesh: ir.Mesh) -> MeshData | Diagnostic:
    """Load `mesh.path`, scaled to metres; a Diagnostic (at `mesh.span`) if it is unusable."""
    path = mesh.path
    try:
        stat = os.stat(path)
    except OSError:
        return _error(mesh, codes.MESH_MISSING, f"mesh file must exist (got '{path}')")
    try:
        if not S_ISREG(stat.st_mode):  # a FIFO would block the read forever, a device never end
            raise OSError(errno.EINVAL, "not a regular file (a FIFO, device or folder)")
        with open(path, "rb"):  # an unreadable file is said to be unreadable, not "not a valid STL"
            pass
    except OSError as exc:
        from rmot.lang import check_codes as check_codes  # late: optional, tried where used

        return _error(mesh, check_codes.UNREADABLE, f"mesh file must be readable (got {exc.strerror or exc} for '{path}')")
    try:
        vertices, faces, watertight = _read_cached(path, stat.st_mtime_ns, stat.st_size)
    except _MeshError as exc:
        return _error(mesh, exc.code, exc.message)
    extent = float(np.max(np.abs(vertices))) * float(mesh.scale) if vertices.size else 0.0
    if not extent <= _MAX_EXTENT_M:  # also NaN: a scaled mesh of 1e300 m crashed the collision library
        from rmot.lang import check_codes as check_codes  # late: tests replace it (monkeypatch): read at call time

        return _error(mesh, check_codes.PHYSICAL_RANGE, f"mesh must lie within {_MAX_EXTENT_M:g} m of its origin once scaled "
                      f"(got a vertex {extent:.3g} m away; check its unit or scale)")
    warnings: tuple[Diagnostic, ...] = ()
    if not watertight:
        warnings = (
            Diagnostic(
                codes.MESH_NOT_WATERTIGHT, Severity.WARNING,
                f"mesh '{os.path.basename(path)}' should be a closed manifold surface (it has open "
                "or non-manifold edges); a body wholly inside it is not detected", mesh.span,
            ),
        )
    return MeshData(vertices * float(mesh.scale), faces.copy(), warnings)


_MAX_EXTENT_M = 1000.0  # policy, as compiler/passes/limits.MAX_SIZE_M: solids up to a kilometre


def is_flat(vertices: np.ndarray) -> bool:
    """Fewer than 4 points, or all within 1e-9 of the size of the mesh of one plane."""
    if len(vertices) < 4:
        return True
    centred = vertices - vertices.mean(axis=0)
    sv = np.linalg.svd(centred, compute_uv=False)
    return bool(not np.all(np.isfinite(sv)) or sv[2] <= 1e-9 * max(sv[0], 1e-300))


def centroid(data: MeshData) -> tuple[float, float, float]:
    """The centre of mass (m, the mesh's frame) of the solid a mesh bounds, at uniform density:
    the volume-weighted mean of the signed tetrahedra from the origin to each triangle
    (divergence theorem). A surface that bounds no volume (open, non-manifold or flat: its
    signed volume would depend on where the origin is) gives the area-weighted mean of its
    triangles' centres instead."""
    tri = data.vertices[data.faces]  # (F, 3 corners, 3)
    a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]
    volumes = np.einsum("ij,ij->i", a, np.cross(b, c)) / 6.0
    centres = (a + b + c) / 4.0  # of each tetrahedron (origin, a, b, c)
    total = float(volumes.sum())
    size = float(np.ptp(data.vertices, axis=0).max()) if data.vertices.size else 0.0
    if data.faces.size and _is_watertight(data.faces) and abs(total) > 1e-9 * size ** 3:
        x, y, z = (float(v) for v in volumes @ centres / total)
        return x, y, z
    areas = np.linalg.norm(np.cross(b - a, c - a), axis=1)
    if not data.faces.size or float(areas.sum()) <= 0.0:
        return 0.0, 0.0, 0.0
    x, y, z = (float(v) for v in areas @ ((a + b + c) / 3.0) / float(areas.sum()))
    return x, y, z


def _error(mesh: ir.Mesh, code: Code, message: str) -> Diagnostic:
    return Diagnostic(code, Severity.ERROR, message, mesh.span)


@functools.lru_cache(maxsize=64)
def _read_cached(path: str, mtime_ns: int, size: int) -> tuple[np.ndarray, np.ndarray, bool]:
    """Parse once per file version (mtime and size are part of the key)."""
    del mtime_ns, size
    suffix = os.path.splitext(path)[1].lower()
    if suffix in _TRIMESH_SUFFIXES:
        vertices, faces = _read_trimesh(path)
    elif suffix in STEP_SUFFIXES:  # tessellated by OpenCASCADE, grown by its tolerance (sim/step.py)
        try:
            vertices, faces = read_step(path)
        except StepError as exc:
            raise _MeshError(codes.MESH_UNREADABLE, str(exc)) from None
    else:
        try:
            with open(path, encoding="utf-8") as f:
                text = f.read()
        except (OSError, UnicodeDecodeError) as exc:
            raise _MeshError(codes.MESH_UNREADABLE, f"mesh file must be readable text (got {exc.__class__.__name__})") from None
        vertices, faces = parse_classic(text)
    _check_nonempty(path, vertices, faces)
    watertight = _is_watertight(faces)  # of the file's own triangles: dropping slivers does not open a surface
    faces = _without_zero_area(path, vertices, faces)
    vertices.setflags(write=False)
    faces.setflags(write=False)
    return vertices, faces, watertight


def _read_trimesh(path: str) -> tuple[np.ndarray, np.ndarray]:
    import trimesh  # late: trimesh is heavy or optional, loaded only where used

    if os.path.getsize(path) == 0:
        raise _MeshError(codes.MESH_EMPTY, f"mesh file must contain triangles (got an empty file '{os.path.basename(path)}')")
    if _looks_truncated_stl(path):
        raise _MeshError(codes.MESH_TRUNCATED, "binary STL file must hold as many triangles as its header declares (the file is truncated)")
    short = _off_shortfall(path)
    if short == "polygons":
        raise _MeshError(codes.MESH_TRUNCATED, "OFF file faces must each list 3 or more corners and as many vertex indices "
                         "(got a face line that is no polygon)")
    if short:
        raise _MeshError(codes.MESH_TRUNCATED, f"OFF file must hold as many {short} as its header declares (the file is truncated)")
    log = logging.getLogger("trimesh")  # its modules log a traceback of what they tried and gave up
    level = log.level  # on (a text STL's bad normal line): what a file lacks is ours to say, located
    log.setLevel(logging.CRITICAL)
    try:
        loaded = trimesh.load(path, force="mesh", process=False)
    except Exception as exc:  # trimesh raises many types for bad files; all mean "unreadable"
        raise _MeshError(codes.MESH_UNREADABLE, f"mesh file must be a valid {os.path.splitext(path)[1][1:].upper()} file ({_short(exc)})") from None
    finally:
        log.setLevel(level)
    if hasattr(loaded, "merge_vertices"):  # STL repeats each corner per triangle
        loaded.merge_vertices()
    vertices = np.asarray(getattr(loaded, "vertices", np.empty((0, 3))), dtype=np.float64).reshape(-1, 3)
    faces = np.asarray(getattr(loaded, "faces", np.empty((0, 3))), dtype=np.int64).reshape(-1, 3)
    if not np.all(np.isfinite(vertices)):
        raise _MeshError(codes.MESH_UNREADABLE, "mesh vertices must be finite numbers (got NaN or infinity)")
    return vertices, faces


def _looks_truncated_stl(path: str) -> bool:
    """A binary STL declares its triangle count at byte 80; check the file is that long."""
    if not path.lower().endswith(".stl"):
        return False
    with open(path, "rb") as f:
        head = f.read(84)
    if len(head) < 84 or head[:5].lower() == b"solid":
        return False
    declared = int.from_bytes(head[80:84], "little")
    return os.path.getsize(path) < 84 + 50 * declared


def _off_shortfall(path: str) -> str:
    """'vertices' or 'faces' when a text OFF file holds fewer lines of them than its header
    declares (trimesh reads what is there without a word), 'polygons' for a face line that is
    no polygon (fewer than 3 corners, or fewer indices than it declares: trimesh drops it), else
    ''. The header is `OFF` (or COFF, NOFF, ...), then the vertex, face and edge counts, on
    its line or the next."""
    if not path.lower().endswith(".off"):
        return ""
    with open(path, "rb") as f:
        raw = f.read()
    try:
        text = raw.decode("ascii")
    except UnicodeDecodeError:  # binary OFF: trimesh checks its lengths
        return ""
    lines = [line.split("#", 1)[0].split() for line in text.splitlines()]
    lines = [line for line in lines if line]
    if not lines or not lines[0][0].upper().endswith("OFF") or "BINARY" in (t.upper() for t in lines[0]):
        return ""
    counts, rest = (lines[0][1:], lines[1:]) if len(lines[0]) > 1 else ((lines[1] if len(lines) > 1 else []), lines[2:])
    if len(counts) < 2 or not all(t.isdigit() for t in counts[:2]):
        return ""  # not a header trimesh reads either: it reports the file as unreadable
    n_vertices, n_faces = int(counts[0]), int(counts[1])
    if len(rest) < n_vertices:
        return "vertices"
    if len(rest) < n_vertices + n_faces:
        return "faces"
    polygons = rest[n_vertices:n_vertices + n_faces]
    if any(not p[0].isdigit() or int(p[0]) < 3 or len(p) < 1 + int(p[0]) for p in polygons):
        return "polygons"
    return ""


def _short(exc: Exception) -> str:
    text = str(exc).strip().splitlines()
    return text[0][:120] if text else exc.__class__.__name__


def parse_classic(text: str) -> tuple[np.ndarray, np.ndarray]:
    """The classic text format -> (vertices (V, 3), faces (F, 3)); raises _MeshError."""
    tokens_by_line = [line.split("#", 1)[0].split() for line in text.splitlines()]
    tokens = [tok for line in tokens_by_line for tok in line]
    if not tokens:
        raise _MeshError(codes.MESH_EMPTY, "mesh file must contain points and polygons (got an empty file)")
    stream = _Tokens(tokens)
    n_points = stream.count("point count")
    n_polys = stream.count("polygon count")
    vertices = np.array([[stream.number(f"coordinate of point {i + 1}") for _ in range(3)] for i in range(n_points)], dtype=np.float64).reshape(-1, 3)
    polygons: list[list[int]] = []
    for p in range(n_polys):
        k = stream.count(f"vertex count of polygon {p + 1}")
        if k < 3:
            raise _MeshError(codes.MESH_UNREADABLE, f"polygon {p + 1} must have at least 3 vertices (got {k})")
        polygons.append([stream.count(f"index in polygon {p + 1}") for _ in range(k)])
    if stream.remaining:
        raise _MeshError(codes.MESH_UNREADABLE, f"mesh file must end after {n_polys} polygons (got {stream.remaining} extra values)")
    return vertices, _triangulate(polygons, n_points)


def _triangulate(polygons: list[list[int]], n_points: int) -> np.ndarray:
    flat = [i for poly in polygons for i in poly]
    one_based = bool(flat) and min(flat) >= 1 and max(flat) == n_points
    triangles: list[tuple[int, int, int]] = []
    for p, poly in enumerate(polygons):
        idx = [i - 1 for i in poly] if one_based else poly
        bad = [i for i in idx if not 0 <= i < n_points]
        if bad:
            raise _MeshError(codes.MESH_UNREADABLE, f"polygon {p + 1} must index points 0..{n_points - 1} (got {bad[0]})")
        triangles += [(idx[0], idx[j], idx[j + 1]) for j in range(1, len(idx) - 1)]
    return np.array(triangles, dtype=np.int64).reshape(-1, 3)


class _Tokens:
    def __init__(self, tokens: list[str]) -> None:
        self._tokens = tokens
        self._pos = 0

    @property
    def remaining(self) -> int:
        return len(self._tokens) - self._pos

    def _next(self, what: str) -> str:
        if self._pos >= len(self._tokens):
            raise _MeshError(codes.MESH_TRUNCATED, f"mesh file ends early: expected the {what}")
        tok = self._tokens[self._pos]
        self._pos += 1
        return tok

    def count(self, what: str) -> int:
        tok = self._next(what)
        try:
            value = int(tok)
        except ValueError:
            raise _MeshError(codes.MESH_UNREADABLE, f"the {what} must be a whole number (got '{tok[:20]}')") from None
        if value < 0:
            raise _MeshError(codes.MESH_UNREADABLE, f"the {what} must not be negative (got {value})")
        return value

    def number(self, what: str) -> float:
        tok = self._next(what)
        try:
            value = float(tok)
        except ValueError:
            raise _MeshError(codes.MESH_UNREADABLE, f"the {what} must be a number (got '{tok[:20]}')") from None
        if not np.isfinite(value):
            raise _MeshError(codes.MESH_UNREADABLE, f"the {what} must be finite (got '{tok}')")
        return value


def _check_nonempty(path: str, vertices: np.ndarray, faces: np.ndarray) -> None:
    if len(faces) == 0 or len(vertices) == 0:
        raise _MeshError(codes.MESH_EMPTY, f"mesh file must contain triangles (got none in '{os.path.basename(path)}')")
    if faces.min() < 0 or faces.max() >= len(vertices):
        raise _MeshError(codes.MESH_UNREADABLE, "mesh faces must index its vertices")


def _without_zero_area(path: str, vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """The faces with a non-zero area. A triangle whose corners coincide or lie on one line
    bounds nothing, and the collision library crashes on a mesh made only of them; such
    triangles are dropped, and a mesh left with none is refused (E562)."""
    corners = vertices[faces]
    twice_area = np.linalg.norm(np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]), axis=1)
    size = float(np.ptp(vertices, axis=0).max()) if len(vertices) else 0.0
    kept: np.ndarray = faces[twice_area > _ZERO_AREA * size * size]
    if len(kept) == 0:
        raise _MeshError(codes.MESH_EMPTY, f"mesh file must contain a triangle of non-zero area (all {len(faces)} in "
                         f"'{os.path.basename(path)}' have zero area)")
    return kept


_ZERO_AREA = 1e-12  # relative to the mesh's size squared: far below any modelling tolerance, above rounding


def _is_watertight(faces: np.ndarray) -> bool:
    """Closed 2-manifold test: every undirected edge is shared by exactly two triangles."""
    edges = np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1)
    _, counts = np.unique(edges, axis=0, return_counts=True)
    return bool(np.all(counts == 2))
