"""One self-contained HTML file with an interactive 3D view of the animated program.

Our own small WebGL page (viewer.html + viewer.js in this package), inlined: no CDN, no
external files, works offline. The file embeds each body's triangles once, in its own
frame, and per frame only the body poses (3 x 4 floats each), base64 float32.
"""

from __future__ import annotations

import base64
import html as html_text
import json
from collections.abc import Sequence
from importlib import resources

import numpy as np

from rmot.sim.render.animate import frame_times
from rmot.sim.render.camera import Camera
from rmot.sim.render.findings import WINDOW, Marking
from rmot.sim.render.scene import FLOOR, HIGHLIGHT, PATH, RenderScene, body_poses
from rmot.sim.render.still import default_camera

__all__ = ["render_html"]


def _b64(array: np.ndarray) -> str:
    """Little-endian float32 bytes of an array, base64 text."""
    return base64.b64encode(np.ascontiguousarray(array, dtype="<f4").tobytes()).decode("ascii")


def _color(c: object) -> list[float]:
    return [round(float(v), 4) for v in np.asarray(c).ravel()[:3]]


def _finding(m: Marking, names: tuple[str, ...]) -> dict[str, object]:
    d = m.diagnostic
    return {"code": d.code.id, "severity": d.severity.name.lower(), "line": d.span.start.line if d.span else None,
            "message": d.message, "caption": m.caption, "t0": round(m.t0, 4), "t1": round(m.t1, 4),
            "worst": round(m.worst, 4), "bodies": [names.index(b) for b in m.bodies],
            "contact": None if m.contact is None else [round(float(v), 5) for v in m.contact],
            "radius": round(m.radius, 4)}


def scene_data(rs: RenderScene, fps: float = 25.0, camera: Camera | None = None,
               marks: Sequence[Marking] = ()) -> dict[str, object]:
    """What the viewer needs, as JSON-ready values."""
    times = frame_times(rs.plan.cycle_time, min(fps, 30.0))
    poses = body_poses(rs, times)[:, :, :3, :].reshape(len(times), len(rs.names), 12)
    camera = camera or default_camera(rs, (4, 3))
    floor = []
    for color in FLOOR:
        mine = np.all(np.isclose(rs.floor_colors, color, atol=1e-3), axis=1) if len(rs.floor_colors) else np.zeros(0, bool)
        if mine.any():
            floor.append({"vertices": _b64(rs.floor.vertices[mine]), "normals": _b64(rs.floor.normals[mine]), "color": _color(color)})
    return {
        "bodies": [{"name": name, "vertices": _b64(mesh.vertices), "normals": _b64(mesh.normals), "color": _color(color),
                    "kind": str(getattr(body, "kind", ""))}
                   for name, mesh, color, body in zip(rs.names, rs.meshes, rs.colors, rs.scene.bodies)],
        "floor": floor,
        "paths": [_b64(p) for p in rs.paths],
        "pathColor": _color(PATH),
        "times": [round(float(t), 4) for t in times],
        "poses": _b64(poses),
        "camera": {"eye": list(camera.eye), "center": list(camera.center), "fov": camera.fov_deg},
        "findings": [_finding(m, rs.names) for m in marks],
        "highlight": _color(HIGHLIGHT),
        "window": WINDOW,
    }


def render_html(rs: RenderScene, *, fps: float = 25.0, camera: Camera | None = None, marks: Sequence[Marking] = (),
                start: float | None = None) -> str:
    """The viewer page as text (the same scene gives the same bytes). `marks` are listed in a
    panel (click: jump to the worst instant) and drawn red around their intervals; `start`
    opens the page paused at that instant (a URL fragment #t=SECONDS does the same)."""
    package = resources.files("rmot.sim.render")
    page = (package / "viewer.html").read_text(encoding="utf-8")
    script = (package / "viewer.js").read_text(encoding="utf-8")
    content = scene_data(rs, fps, camera, marks)
    content["start"] = None if start is None else round(float(start), 4)
    data = json.dumps(content, sort_keys=True, separators=(",", ":"))
    data = data.replace("</", "<\\/")  # never close the <script> element early
    title = html_text.escape(rs.plan.program.name)
    return page.replace("__TITLE__", title).replace("__SCRIPT__", script).replace("__DATA__", data)
