"""Still pictures of a planned program: a frame at an instant, and a finding's worst instant."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from rmot.compiler.planned import Plan
from rmot.lang.diagnostics import Diagnostic
from rmot.sim.render.camera import Camera
from rmot.sim.render.caption import add_caption
from rmot.sim.render.files import write_png
from rmot.sim.render.findings import Marking, active, finding_caption, mark_picture, markings, worst_instant
from rmot.sim.render.overlay import sample_segments, stamp, visible
from rmot.sim.render.pipeline import Picture, downsample, draw, to_uint8
from rmot.sim.render.scene import PATH, RenderScene, body_poses, prepare, soup

__all__ = ["default_camera", "finding_caption", "frame", "render_finding", "render_still", "still_image", "worst_instant"]


def default_camera(rs: RenderScene, size: tuple[int, int]) -> Camera:
    """The three-quarter view framing every body over the whole program."""
    return Camera.framing(rs.bounds, aspect=size[0] / size[1], points=rs.extent)


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


def render_finding(plan: Plan, diagnostic: Diagnostic, path: str, size: tuple[int, int] = (640, 480),
                   camera: Camera | None = None) -> None:
    """A PNG of the finding's worst instant: its bodies marked (the contact region strongest), with a caption."""
    rs = prepare(plan)
    marks = markings(rs, [diagnostic])
    time = marks[0].worst if marks else (worst_instant(diagnostic) or 0.0)
    image = still_image(rs, time=time, size=size, camera=camera, marks=marks)
    if not marks:  # no time or no bodies of this scene: the caption alone says what happened
        image = add_caption(image, finding_caption(diagnostic))
    write_png(path, image)
