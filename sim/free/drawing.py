"""A picture of each `move free`'s found path for the HTML report: the flange's path seen from
above (x-y) and from the side (x-z) in the cell frame, the via points the search inserted as
numbered dots, and the fixtures' bounding boxes. Plain SVG text, the same plan giving the same
bytes."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from rmot.lang import ir

SIZE = 260  # pixels per view
_VIEWS = (("from above (x, y)", 0, 1), ("from the side (x, z)", 0, 2))


def _corners(geometry: Any, pose: np.ndarray) -> np.ndarray | None:
    """The eight corners of a fixture's bounding box in the cell frame (None for a mesh)."""
    if isinstance(geometry, ir.Box):
        half = np.asarray(geometry.size) / 2
    elif isinstance(geometry, ir.Cylinder):
        half = np.array([geometry.radius, geometry.radius, geometry.height / 2])
    elif isinstance(geometry, ir.Capsule):
        half = np.array([geometry.radius, geometry.radius, geometry.length / 2 + geometry.radius])
    elif isinstance(geometry, ir.Sphere):
        half = np.full(3, geometry.radius)
    else:
        return None
    signs = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)], dtype=float)
    local = signs * half
    out: np.ndarray = local @ pose[:3, :3].T + pose[:3, 3]
    return out


def _view(title: str, a: int, b: int, path: np.ndarray, vias: np.ndarray,
          boxes: Sequence[tuple[str, np.ndarray]]) -> str:
    """One projection: fixtures as rectangles, the path as a line, the vias as numbered dots."""
    points = [path[:, [a, b]]] + [c[:, [a, b]] for _, c in boxes]
    lo = np.min([p.min(axis=0) for p in points], axis=0) - 0.05
    hi = np.max([p.max(axis=0) for p in points], axis=0) + 0.05
    scale = (SIZE - 20) / float(max(hi - lo))

    def xy(p: np.ndarray) -> tuple[float, float]:
        return 10 + (p[0] - lo[0]) * scale, SIZE - 10 - (p[1] - lo[1]) * scale

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{SIZE}" height="{SIZE + 16}">'
           f'<text x="4" y="{SIZE + 12}" font-size="11">{title}, metres = cell frame</text>']
    for name, c in boxes:
        (x0, y1), (x1, y0) = xy(c[:, [a, b]].min(axis=0)), xy(c[:, [a, b]].max(axis=0))
        out.append(f'<rect x="{x0:.1f}" y="{y0:.1f}" width="{x1 - x0:.1f}" height="{y1 - y0:.1f}" '
                   f'fill="#ccc" fill-opacity="0.5" stroke="#888"><title>{name}</title></rect>')
    line = " ".join("{:.1f},{:.1f}".format(*xy(p)) for p in path[:, [a, b]])
    out.append(f'<polyline points="{line}" fill="none" stroke="#1565c0" stroke-width="2"/>')
    for n, p in enumerate(vias[:, [a, b]] if len(vias) else (), start=1):
        x, y = xy(p)
        out.append(f'<circle cx="{x:.1f}" cy="{y:.1f}" r="4" fill="#e65100"/>'
                   f'<text x="{x + 5:.1f}" y="{y - 5:.1f}" font-size="11">{n}</text>')
    out.append("</svg>")
    return "".join(out)


def free_path_pictures(plan: Any) -> list[tuple[str, str]]:
    """(caption, SVG) per `move free` of a planned program, in program order."""
    from rmot.sim.robots import load_robot  # late: loads coal only when this runs

    cell = plan.program.cell
    boxes = [(f.name, c) for f in cell.fixtures if (c := _corners(f.geometry, f.pose.matrix())) is not None]
    pictures: list[tuple[str, str]] = []
    for tp in plan.tasks:
        moves = [i for i in tp.task.body if isinstance(i, ir.Move)]
        instance = cell.robot(tp.robot)
        robot, base = load_robot(instance.source.load_key), instance.base.matrix()
        for k, move in enumerate(moves):
            if move.free is None:
                continue
            vias = [m for m in moves[:k] if m.span == move.span and isinstance(m.target, ir.JointTarget)]
            before = moves[k - len(vias) - 1] if k - len(vias) >= 1 else None
            t0 = tp.record(before.uid).t_end if before is not None else 0.0
            window = (tp.trajectory.t >= t0) & (tp.trajectory.t <= tp.record(move.uid).t_end)
            path = np.array([(base @ np.asarray(robot.fk(q)))[:3, 3] for q in tp.trajectory.q[window]])
            if len(path) < 2:
                continue
            dots = np.array([(base @ np.asarray(robot.fk(np.asarray(v.target.values))))[:3, 3]
                             for v in vias if isinstance(v.target, ir.JointTarget)])
            where = f"{move.span.file.path}:{move.span.start.line}" if move.span is not None else tp.robot
            caption = f"{where}: 'move free' of {tp.robot}, flange path with {len(vias)} via points"
            pictures.append((caption, "".join(_view(t, a, b, path, dots, boxes) for t, a, b in _VIEWS)))
    return pictures
