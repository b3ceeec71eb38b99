"""A wire-frame vector drawing with hidden lines removed, as a pen plotter would draw it.

Which edges: the feature edges of the tessellation — open boundaries, creases (faces
meeting at more than `crease_deg`) and silhouettes (one face towards the eye, the other
away) — not the diagonals that split flat faces. Which parts: each edge is sampled every
half pixel and a sample is kept when the z-buffer of the same scene has nothing nearer
at its pixel (overlay.visible); consecutive kept samples become one straight stroke.
"""

from __future__ import annotations

from collections.abc import Sequence
from xml.sax.saxutils import escape, quoteattr

import numpy as np

from rmot.sim.render.camera import Camera
from rmot.sim.render.findings import Marking, active
from rmot.sim.render.overlay import sample_segments, visible
from rmot.sim.render.pipeline import depth_frame, face_normals
from rmot.sim.render.scene import RenderScene, body_poses
from rmot.sim.render.transform import to_clip, to_screen, transform_points

__all__ = ["feature_edges", "render_svg", "wireframe_svg"]

_SCALE = 2  # the z-buffer is sampled at twice the drawing's resolution


def feature_edges(vertices: np.ndarray, eye: np.ndarray, crease_deg: float = 30.0) -> tuple[np.ndarray, np.ndarray]:
    """Feature edges of triangles (T, 3, 3) seen from `eye`: segments (E, 2, 3) and a triangle of each (E,)."""
    normals = face_normals(vertices)
    solid = np.linalg.norm(normals, axis=1) > 0.5  # degenerate triangles have no normal and no edges
    tri_index = np.flatnonzero(solid)
    vertices, normals = vertices[solid], normals[solid]
    keys = np.round(vertices.reshape(-1, 3) * 1e6).astype(np.int64)  # weld points closer than 1 um
    _, point_id = np.unique(keys, axis=0, return_inverse=True)
    point_id = point_id.reshape(-1, 3)
    pairs = np.concatenate([point_id[:, [0, 1]], point_id[:, [1, 2]], point_id[:, [2, 0]]])
    corner = np.concatenate([np.stack([vertices[:, 0], vertices[:, 1]], 1), np.stack([vertices[:, 1], vertices[:, 2]], 1),
                             np.stack([vertices[:, 2], vertices[:, 0]], 1)])
    face = np.tile(np.arange(len(vertices)), 3)
    pairs.sort(axis=1)
    real = pairs[:, 0] != pairs[:, 1]
    pairs, corner, face = pairs[real], corner[real], face[real]
    _, edge, count = np.unique(pairs, axis=0, return_inverse=True, return_counts=True)
    edge = edge.ravel()
    order = np.argsort(edge, kind="stable")
    first = order[np.r_[0, np.flatnonzero(np.diff(edge[order])) + 1]]  # one half-edge per edge
    faces_of = np.full((len(count), 2), -1)
    starts = np.r_[0, np.cumsum(count)[:-1]]
    faces_of[:, 0] = face[order[starts]]
    two = count == 2
    faces_of[two, 1] = face[order[starts[two] + 1]]
    front = np.einsum("ij,ij->i", normals, eye - vertices.mean(axis=1)) > 0.0
    fa, fb = faces_of[:, 0], faces_of[:, 1]
    crease = np.einsum("ij,ij->i", normals[fa[two]], normals[fb[two]]) < np.cos(np.radians(crease_deg))
    silhouette = front[fa[two]] != front[fb[two]]
    keep = ~two
    keep[two] = crease | silhouette
    return corner[first[keep]], tri_index[faces_of[keep, 0]]


MIN_STROKE = 1.5  # px: shorter runs are the tolerance's stubs where a hidden edge leaves a visible corner


def _strokes(xy: np.ndarray, segment: np.ndarray, seen: np.ndarray, scale: float) -> list[str]:
    """Runs of consecutive visible samples of one segment -> 'M x y L x y' strokes (specks dropped)."""
    if not seen.any():
        return []
    breaks = np.flatnonzero((np.diff(seen.astype(np.int8)) != 0) | (np.diff(segment) != 0)) + 1
    bounds = np.r_[0, breaks, len(seen)]
    strokes = []
    for lo, hi in zip(bounds[:-1], bounds[1:]):
        if seen[lo] and hi - lo >= 2:
            (x0, y0), (x1, y1) = xy[lo] / scale, xy[hi - 1] / scale
            if np.hypot(x1 - x0, y1 - y0) < MIN_STROKE:
                continue
            strokes.append(f"M{x0:.2f} {y0:.2f}L{x1:.2f} {y1:.2f}")
    return strokes


def wireframe_svg(vertices: np.ndarray, camera: Camera, size: tuple[int, int] = (640, 480), *,
                  groups: np.ndarray | None = None, names: tuple[str, ...] = ("scene",),
                  colors: tuple[str, ...] = ("#000",), lines: tuple[tuple[np.ndarray, np.ndarray, str], ...] = (),
                  occluders: np.ndarray | None = None) -> str:
    """SVG text of triangles (T, 3, 3) drawn as hidden-line wire-frame at size (W, H).

    groups (T,) names the body of each triangle (index into `names`/`colors`); `lines` are
    extra world segments (a (S, 3), b (S, 3), colour) drawn with the same hiding;
    `occluders` (T2, 3, 3) hide lines without drawing their own edges (e.g. a floor).
    """
    vertices = np.asarray(vertices, float).reshape(-1, 3, 3)
    groups = np.zeros(len(vertices), int) if groups is None else np.asarray(groups)
    hidden_by = vertices if occluders is None else np.concatenate([vertices, occluders])
    big = (size[0] * _SCALE, size[1] * _SCALE)
    camera = camera.fitted(np.concatenate([hidden_by.reshape(-1, 3)] + [np.concatenate([a, b]).reshape(-1, 3)
                                                                         for a, b, _ in lines]))
    frame, _ = depth_frame(hidden_by, camera, big)  # the same planes for the surfaces and the lines
    edges, tri = feature_edges(vertices, np.asarray(camera.eye, float))
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{size[0]}" height="{size[1]}" '
           f'viewBox="0 0 {size[0]} {size[1]}">',
           f'<rect width="{size[0]}" height="{size[1]}" fill="#fff"/>']
    layers = [(a, b, color, "lines" if k == 0 else f"lines-{k}") for k, (a, b, color) in enumerate(lines)]
    for g, name in enumerate(names):
        mine = groups[tri] == g
        layers.append((edges[mine, 0], edges[mine, 1], colors[g % len(colors)], name))
    for a, b, color, name in layers:
        if len(a) == 0:
            continue
        samples = sample_segments(a, b, camera, big)
        seen = visible(frame, samples, camera, neighbourhood=1)
        strokes = _strokes(samples.xy, samples.segment, seen, _SCALE)
        if strokes:
            out.append(f'<path id={quoteattr(name)} fill="none" stroke="{color}" stroke-width="1" '
                       f'stroke-linecap="round" d="{"".join(strokes)}"/>')
    out.append("</svg>")
    return "\n".join(out) + "\n"


def _floor_grid(rs: RenderScene, spacing: float = 0.5) -> tuple[np.ndarray, np.ndarray]:
    pts = rs.floor.vertices.reshape(-1, 3)
    if len(pts) == 0:
        return np.zeros((0, 3)), np.zeros((0, 3))
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    xs = np.arange(np.ceil(lo[0] / spacing), np.floor(hi[0] / spacing) + 1) * spacing
    ys = np.arange(np.ceil(lo[1] / spacing), np.floor(hi[1] / spacing) + 1) * spacing
    a = np.concatenate([np.stack([xs, np.full_like(xs, lo[1]), 0 * xs], 1), np.stack([np.full_like(ys, lo[0]), ys, 0 * ys], 1)])
    b = np.concatenate([np.stack([xs, np.full_like(xs, hi[1]), 0 * xs], 1), np.stack([np.full_like(ys, hi[0]), ys, 0 * ys], 1)])
    return a, b


def render_svg(rs: RenderScene, *, time: float = 0.0, size: tuple[int, int] = (640, 480), camera: Camera | None = None,
               marks: Sequence[Marking] = ()) -> str:
    """The hidden-line drawing of the cell at `time` s (bodies as <path id=name>, floor grid in
    grey, the TCP paths in blue); findings of `marks` active at `time` draw their bodies in red,
    circle the contact point and add a caption (<text class="finding">)."""
    from rmot.sim.render.still import default_camera  # late: loads pinocchio only when this runs

    camera = camera or default_camera(rs, size)
    poses = body_poses(rs, np.array([time]))[0]
    tris = [transform_points(poses[i], m.vertices) for i, m in enumerate(rs.meshes)]
    groups = np.concatenate([np.full(len(m), i) for i, m in enumerate(rs.meshes)]) if tris else np.zeros(0, int)
    vertices = np.concatenate(tris) if tris else np.zeros((0, 3, 3))
    a, b = _floor_grid(rs)
    shown = active(marks, time)
    marked = {name for m in shown for name in m.bodies}
    colors = tuple(_RED if name in marked else "#111" for name in rs.names)
    lines = [(a, b, "#aaa")] + [(p[:-1], p[1:], _PATH) for p in rs.paths if len(p) > 1]
    svg = wireframe_svg(vertices, camera, size, groups=groups, names=rs.names, colors=colors or ("#111",),
                        lines=tuple(lines), occluders=rs.floor.vertices)
    return svg.replace("</svg>\n", "".join(_finding_marks(shown, camera, size)) + "</svg>\n")


_RED, _PATH = "#d32f2f", "#0d6efd"


def _finding_marks(marks: Sequence[Marking], camera: Camera, size: tuple[int, int]) -> list[str]:
    """A red circle at each contact point and the captions along the bottom."""
    out = []
    for m in marks:
        if m.contact is None:
            continue
        clip = to_clip(camera.matrix(size[0] / size[1]), np.asarray(m.contact, float)[None])
        if clip[0, 3] <= 0:
            continue
        (x, y, _), = to_screen(clip, size[0], size[1])[0]
        out.append(f'<circle class="contact" cx="{x:.1f}" cy="{y:.1f}" r="14" fill="none" stroke="{_RED}" stroke-width="2"/>\n')
    for k, m in enumerate(reversed(marks)):
        y = size[1] - 8 - 16 * k
        out.append(f'<text class="finding" x="8" y="{y}" font-family="sans-serif" font-size="12" fill="{_RED}">'
                   f'{escape(m.caption)}</text>\n')
    return out
