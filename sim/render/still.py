"""Still pictures of a planned program: a frame at an instant, and a finding's worst instant."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from rmot.lang.plan_types import Plan
from rmot.lang.diagnostics import Diagnostic
from rmot.sim.render.camera import Camera
from rmot.sim.render.caption import add_caption
from rmot.sim.render.files import write_png
from rmot.sim.render.findings import Marking, active, finding_caption, mark_picture, markings, worst_instant
from rmot.sim.render.overlay import sample_segments, stamp, visible
from rmot.sim.render.pipeline import Picture, depth_frame, downsample, draw, to_uint8
from rmot.sim.render.scene import PATH, RenderScene, body_poses, prepare, soup

__all__ = ["default_camera", "finding_caption", "frame", "render_finding", "render_still", "still_image", "worst_instant"]


# Candidate views (azimuth offset from the direction the robots face, elevation), in order
# of preference: three-quarter views from the working side first, then the sides, the back,
# and higher views. The first one that shows the most of the robots and their TCP paths wins.
CANDIDATES = ((-40.0, 28.0), (40.0, 28.0), (0.0, 22.0), (-80.0, 28.0), (80.0, 28.0), (-130.0, 28.0), (130.0, 28.0),
              (180.0, 28.0), (-40.0, 55.0), (40.0, 55.0), (0.0, 75.0))
PRESETS = {"front": (0.0, 12.0), "side": (90.0, 12.0), "top": (0.0, 89.0), "iso": (-45.0, 35.26)}
_PROBE = (64, 48)  # px: the size at which candidate views are compared


def facing_deg(rs: RenderScene) -> float:
    """Azimuth (deg, from +x about +z) of the side the robots work on: from their bases towards
    their TCP paths (the bases' x axes when there is no path)."""
    bases = np.array([np.asarray(e.base)[:3, 3] for e in rs.scene.robots.values()]).reshape(-1, 3)
    paths = [p for p in rs.paths if len(p)]
    direction = np.zeros(2)
    if len(bases) and paths:
        direction = np.concatenate(paths)[:, :2].mean(axis=0) - bases[:, :2].mean(axis=0)
    if np.linalg.norm(direction) < 0.05:
        direction = sum((np.asarray(e.base)[:2, 0] for e in rs.scene.robots.values()), np.zeros(2))
    if np.linalg.norm(direction) < 0.05 and len(bases) >= 2:  # robots facing each other: look across
        line = bases[1, :2] - bases[0, :2]
        direction = np.array([-line[1], line[0]])
    if np.linalg.norm(direction) < 1e-9:
        return -50.0  # nothing to go by: the classic three-quarter view
    return float(np.degrees(np.arctan2(direction[1], direction[0])))


def preset_camera(rs: RenderScene, name: str, size: tuple[int, int]) -> Camera:
    """A named view (front, side, top, iso) relative to the side the robots work on."""
    azimuth, elevation = PRESETS[name]
    return Camera.framing(rs.bounds, aspect=size[0] / size[1], azimuth_deg=facing_deg(rs) + azimuth,
                          elevation_deg=elevation, points=rs.extent)


def _visibility(rs: RenderScene, camera: Camera, poses: np.ndarray, work: np.ndarray) -> float:
    """How much of the robots (share of their pixels not hidden by fixtures) and of their TCP
    paths (share of samples in view and unhidden) a camera shows, 0..2."""
    vertices, _, _ = soup(rs, poses)
    owner = np.concatenate([np.full(len(rs.floor), -1)] + [np.full(len(m), i) for i, m in enumerate(rs.meshes)])
    mine = np.isin(owner, work)
    frame_all, source = depth_frame(vertices, camera.fitted(vertices), _PROBE)
    seen = np.isin(owner[source][np.maximum(frame_all.tri, 0)], work) & (frame_all.tri >= 0)
    alone, _ = depth_frame(vertices[mine], camera.fitted(vertices), _PROBE)
    robots = seen.sum() / max(int((alone.tri >= 0).sum()), 1)
    path_score = 0.0
    paths = [p for p in rs.paths if len(p) > 1]
    if paths:
        fitted = camera.fitted(vertices)
        a = np.concatenate([p[:-1] for p in paths])
        b = np.concatenate([p[1:] for p in paths])
        samples = sample_segments(a, b, fitted, _PROBE, step=2.0)
        total = sum(len(p) - 1 for p in paths)
        path_score = float(visible(frame_all, samples, fitted).sum()) / max(len(samples.depth), 1) if total else 0.0
    return float(robots) + path_score


def default_camera(rs: RenderScene, size: tuple[int, int]) -> Camera:
    """A view that frames every body over the whole program and shows the work: of the
    CANDIDATES views around the side the robots face, the first that shows the most of the
    robots and their TCP paths unhidden by fixtures (compared on small pictures at 20, 50 and
    80 % of the program; a later candidate must be clearly better to win)."""
    aspect = size[0] / size[1]
    facing = facing_deg(rs)
    work = np.array([i for i, b in enumerate(rs.scene.bodies) if getattr(b, "kind", "") != "fixture"], int)
    instants = body_poses(rs, np.array([0.2, 0.5, 0.8]) * float(rs.plan.cycle_time))
    best: tuple[float, Camera] | None = None
    for d_az, elevation in CANDIDATES:
        camera = Camera.framing(rs.bounds, aspect=aspect, azimuth_deg=facing + d_az, elevation_deg=elevation,
                                points=rs.extent)
        if len(work) == 0:
            return camera
        score = sum(_visibility(rs, camera, poses, work) for poses in instants) / len(instants)
        if best is None or score > best[0] + 0.05:  # a clearly better view, else keep the preferred one
            best = (score, camera)
    assert best is not None
    return best[1]


def _draw_paths(picture: Picture, rs: RenderScene, camera: Camera) -> None:
    """The TCP paths over the picture: solid where seen, faint where a body hides them."""
    height, width = picture.frame.depth.shape
    camera = picture.camera or camera  # the near/far planes the z-buffer was drawn with
    for path in rs.paths:
        samples = sample_segments(path[:-1], path[1:], camera, (width, height))
        seen = visible(picture.frame, samples, camera)
        radius = max(picture.scale // 2, 0)
        stamp(picture.color, samples.xy[~seen], PATH, radius, alpha=0.25)
        stamp(picture.color, samples.xy[seen], PATH, radius)


def frame(rs: RenderScene, poses: np.ndarray, camera: Camera, size: tuple[int, int], aa: int,
          highlight: tuple[str, ...] = (), paths: bool = True, marks: Sequence[Marking] = ()) -> np.ndarray:
    """One picture (H, W, 3) uint8 of the scene with bodies at poses (B, 4, 4); `marks` are the
    findings to mark in it (bodies in red, the contact region strongest, captions below)."""
    vertices, normals, colors = soup(rs, poses, highlight)
    picture = draw(vertices, normals, colors, camera, size, aa)
    mark_picture(picture, rs, marks)
    if paths:
        _draw_paths(picture, rs, camera)
    image = to_uint8(downsample(picture.color, aa))
    if marks:
        image = add_caption(image, "\n".join(m.caption for m in marks), max_lines=2 * len(marks) + 1)
    return image


def _check_size(size: tuple[int, int], aa: int) -> None:
    if len(size) != 2 or min(size) < 1:
        raise ValueError(f"size must be (width, height) in pixels, both >= 1 (got {size})")
    if aa < 1:
        raise ValueError(f"aa must be >= 1 (got {aa})")


def render_still(plan: Plan, *, time: float = 0.0, size: tuple[int, int] = (640, 480), aa: int = 2,
                 camera: Camera | None = None, highlight: tuple[str, ...] = (),
                 caption: str | None = None, findings: Sequence[Diagnostic] = ()) -> np.ndarray:
    """The cell at `time` s of the program: (H, W, 3) uint8, `highlight` bodies in red, the
    `findings` active at that instant marked (see still_image)."""
    rs = prepare(plan)
    return still_image(rs, time=time, size=size, aa=aa, camera=camera, highlight=highlight, caption=caption,
                       marks=markings(rs, findings))


def still_image(rs: RenderScene, *, time: float = 0.0, size: tuple[int, int] = (640, 480), aa: int = 2,
                camera: Camera | None = None, highlight: tuple[str, ...] = (), caption: str | None = None,
                marks: Sequence[Marking] = ()) -> np.ndarray:
    """render_still on an already prepared scene; `marks` (findings.markings) whose interval
    (widened by findings.WINDOW) holds `time` are marked and captioned."""
    _check_size(size, aa)
    camera = camera or default_camera(rs, size)
    image = frame(rs, body_poses(rs, np.array([time]))[0], camera, size, aa, highlight, marks=active(marks, time))
    return add_caption(image, caption) if caption else image


def finding_camera(rs: RenderScene, mark: Marking, size: tuple[int, int]) -> Camera:
    """The default view's direction, closer: framing the finding's bodies at its worst instant
    and 0.3 m around the contact point, so the contact fills the picture."""
    base = default_camera(rs, size)
    poses = body_poses(rs, np.array([mark.worst]))[0]
    points = []
    for name in mark.bodies:
        i = rs.names.index(name)
        if len(rs.meshes[i]):
            pts = rs.meshes[i].vertices.reshape(-1, 3) @ poses[i, :3, :3].T + poses[i, :3, 3]
            points.append(np.stack([pts.min(axis=0), pts.max(axis=0)]))
    if mark.contact is not None:
        points.append(np.stack([mark.contact - 0.3, mark.contact + 0.3]))
    if not points:
        return base
    box = np.concatenate(points)
    lo, hi = box.min(axis=0), box.max(axis=0)
    if mark.contact is not None:  # a large fixture: keep to 1 m around the contact
        lo, hi = np.maximum(lo, mark.contact - 1.0), np.minimum(hi, mark.contact + 1.0)
    corners = np.array([[(lo, hi)[a][0], (lo, hi)[b][1], (lo, hi)[c][2]] for a in (0, 1) for b in (0, 1) for c in (0, 1)])
    d = np.subtract(base.eye, base.center)
    d /= np.linalg.norm(d)
    azimuth, elevation = np.degrees(np.arctan2(d[1], d[0])), np.degrees(np.arcsin(np.clip(d[2], -1.0, 1.0)))
    return Camera.framing(np.stack([lo, hi]), aspect=size[0] / size[1], fov_deg=base.fov_deg, azimuth_deg=float(azimuth),
                          elevation_deg=float(elevation), points=corners, fill=0.8)


def render_finding(plan: Plan, diagnostic: Diagnostic, path: str, size: tuple[int, int] = (640, 480),
                   camera: Camera | None = None) -> None:
    """A PNG of the finding's worst instant: its bodies marked (the contact region strongest),
    with a caption, seen from the default direction framing the finding (finding_camera)."""
    rs = prepare(plan)
    marks = markings(rs, [diagnostic])
    time = marks[0].worst if marks else (worst_instant(diagnostic) or 0.0)
    if camera is None and marks:
        camera = finding_camera(rs, marks[0], size)
    image = still_image(rs, time=time, size=size, camera=camera, marks=marks)
    if not marks:  # no time or no bodies of this scene: the caption alone says what happened
        image = add_caption(image, finding_caption(diagnostic))
    write_png(path, image)
