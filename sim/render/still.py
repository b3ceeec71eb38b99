"""Still pictures of a planned program: a frame at an instant, and a finding's worst instant."""

from __future__ import annotations

import numpy as np

from rmot.compiler.planned import Plan
from rmot.lang.diagnostics import Diagnostic
from rmot.sim.render.camera import Camera
from rmot.sim.render.caption import add_caption
from rmot.sim.render.files import write_png
from rmot.sim.render.overlay import sample_segments, stamp, visible
from rmot.sim.render.pipeline import Picture, downsample, draw, to_uint8
from rmot.sim.render.scene import PATH, RenderScene, body_poses, prepare, soup

__all__ = ["default_camera", "finding_caption", "frame", "render_finding", "render_still", "still_image"]


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
          highlight: tuple[str, ...] = (), paths: bool = True) -> np.ndarray:
    """One picture (H, W, 3) uint8 of the scene with bodies at poses (B, 4, 4)."""
    vertices, normals, colors = soup(rs, poses, highlight)
    picture = draw(vertices, normals, colors, camera, size, aa)
    if paths:
        _draw_paths(picture, rs, camera)
    return to_uint8(downsample(picture.color, aa))


def _check_size(size: tuple[int, int], aa: int) -> None:
    if len(size) != 2 or min(size) < 1:
        raise ValueError(f"size must be (width, height) in pixels, both >= 1 (got {size})")
    if aa < 1:
        raise ValueError(f"aa must be >= 1 (got {aa})")


def render_still(plan: Plan, *, time: float = 0.0, size: tuple[int, int] = (640, 480), aa: int = 2,
                 camera: Camera | None = None, highlight: tuple[str, ...] = (),
                 caption: str | None = None) -> np.ndarray:
    """The cell at `time` s of the program: (H, W, 3) uint8, `highlight` bodies in red."""
    return still_image(prepare(plan), time=time, size=size, aa=aa, camera=camera, highlight=highlight, caption=caption)


def still_image(rs: RenderScene, *, time: float = 0.0, size: tuple[int, int] = (640, 480), aa: int = 2,
                camera: Camera | None = None, highlight: tuple[str, ...] = (), caption: str | None = None) -> np.ndarray:
    """render_still on an already prepared scene."""
    _check_size(size, aa)
    camera = camera or default_camera(rs, size)
    image = frame(rs, body_poses(rs, np.array([time]))[0], camera, size, aa, highlight)
    return add_caption(image, caption) if caption else image


def finding_caption(diagnostic: Diagnostic) -> str:
    """'E301 line 12 t=3.21 s: message' (parts without data are left out)."""
    parts = [diagnostic.code.id]
    if diagnostic.span is not None:
        parts.append(f"line {diagnostic.span.start.line}")
    instant = worst_instant(diagnostic)
    if instant is not None:
        parts.append(f"t={instant:.2f} s")
    return " ".join(parts) + f": {diagnostic.message}"


def worst_instant(diagnostic: Diagnostic) -> float | None:
    """When the finding is worst: the deepest contact or closest approach where the checker
    recorded it (peak_time_s), else the start of its interval."""
    return diagnostic.peak_time_s if diagnostic.peak_time_s is not None else diagnostic.time_s


def render_finding(plan: Plan, diagnostic: Diagnostic, path: str, size: tuple[int, int] = (640, 480)) -> None:
    """A PNG of the finding's worst instant, its bodies in red, with a caption."""
    image = render_still(plan, time=worst_instant(diagnostic) or 0.0, size=size, highlight=tuple(diagnostic.bodies),
                         caption=finding_caption(diagnostic))
    write_png(path, image)
