"""Animations of the whole program: GIF (Pillow) or MP4 (imageio + its ffmpeg plugin).

Frames are rendered one at a time and streamed to the writer, so memory does not grow with
the program's length (GIF frames are kept palettised, one byte per pixel, until saved).
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable, Iterator, Sequence

import numpy as np
from PIL import Image

from rmot.lang.plan_types import Plan
from rmot.sim.render.camera import Camera
from rmot.sim.render.files import write_atomic
from rmot.sim.render.findings import Marking, active
from rmot.sim.render.scene import RenderScene, body_poses, prepare
from rmot.sim.render.still import default_camera, frame

__all__ = ["AnimationError", "frame_times", "render_animation", "stderr_progress", "write_animation"]

Progress = Callable[[int, int], None]


class AnimationError(RuntimeError):
    """The animation cannot be written (unknown format, or no MP4 encoder installed)."""


def frame_times(duration: float, fps: float) -> np.ndarray:
    """Instants (N,) s from 0 to the end of the program inclusive, 1/fps apart (at least one)."""
    count = int(np.floor(max(duration, 0.0) * fps + 1e-9)) + 1
    times = np.arange(count) / fps
    if times[-1] < duration - 1e-9:
        times = np.append(times, duration)  # always show the final state
    return times


def stderr_progress(done: int, total: int) -> None:
    """A one-line text progress bar on stderr."""
    width = 30
    filled = int(width * done / max(total, 1))
    if done < total and filled == int(width * (done - 1) / max(total, 1)):
        return  # redraw only when the bar grows
    end = "\n" if done >= total else ""
    sys.stderr.write(f"\rrendering frames [{'#' * filled}{'.' * (width - filled)}] {done}/{total}{end}")
    sys.stderr.flush()


def _frames(rs: RenderScene, fps: float, size: tuple[int, int], aa: int, camera: Camera | None,
            progress: Progress | None, marks: Sequence[Marking] = ()) -> Iterator[np.ndarray]:
    plan = rs.plan
    camera = camera or default_camera(rs, size)
    times = frame_times(plan.cycle_time, fps)
    poses = body_poses(rs, times)
    for i in range(len(times)):
        yield frame(rs, poses[i], camera, size, aa, marks=active(marks, float(times[i])))
        if progress is not None:
            progress(i + 1, len(times))


def render_animation(plan: Plan, path: str, *, fps: int = 25, size: tuple[int, int] = (480, 360), aa: int = 1,
                     camera: Camera | None = None, progress: Progress | None | bool = None) -> None:
    """Write the animated program to `path` (.gif or .mp4) atomically.

    progress: a callback (done, total), False for none, None for a bar on stderr when the
    program lasts longer than 2 s and stderr is a terminal.
    """
    write_animation(prepare(plan), path, fps=fps, size=size, aa=aa, camera=camera, progress=progress)


def write_animation(rs: RenderScene, path: str, *, fps: int = 25, size: tuple[int, int] = (480, 360), aa: int = 1,
                    camera: Camera | None = None, progress: Progress | None | bool = None,
                    marks: Sequence[Marking] = ()) -> None:
    """render_animation on an already prepared scene; `marks` (findings.markings) are marked in
    the frames around their intervals."""
    plan = rs.plan
    ext = os.path.splitext(path)[1].lower()
    if ext not in (".gif", ".mp4"):
        raise AnimationError(f"animation file must end in .gif or .mp4 (got '{path}')")
    if progress is None:  # a bar redrawn with \r is for a terminal: in a CI log each redraw would be a line
        progress = stderr_progress if plan.cycle_time > 2.0 and sys.stderr.isatty() else False
    frames = _frames(rs, fps, size, aa, camera, progress if callable(progress) else None, marks)
    writer = _write_gif if ext == ".gif" else _write_mp4
    write_atomic(path, lambda temp: writer(temp, frames, fps))


def _write_gif(path: str, frames: Iterator[np.ndarray], fps: float) -> None:
    """All frames on one palette (made from the first frames), without dithering: the parts
    that do not move keep the same bytes from frame to frame, so the GIF writer stores only
    the changed rectangle of each frame and the file stays small."""
    head = next(frames, None)
    if head is None:
        raise AnimationError("an animation needs at least one frame")
    first = [head]
    palette = _palette(head)
    palettised = [_on_palette(f, palette) for f in first]
    palettised += [_on_palette(f, palette) for f in frames]
    duration = int(round(1000.0 / fps))  # ms per frame (GIF counts in 10 ms steps)
    palettised[0].save(path, format="GIF", save_all=True, append_images=palettised[1:], duration=duration,
                       loop=0, optimize=False)


_FINDING_COLORS = np.array([[219, 20, 15], [175, 60, 60], [24, 26, 30], [250, 250, 250]], np.uint8)  # red, tint, caption


def _palette(image: np.ndarray) -> Image.Image:
    """A 256-colour palette for the whole animation: the first frame's colours plus the
    colours that appear later (finding reds, the caption band and its text)."""
    extra = np.repeat(np.repeat(_FINDING_COLORS[None], 8, axis=0), 8, axis=1)  # small blocks of each
    board = np.concatenate([image.reshape(-1, 3), extra.reshape(-1, 3)])
    side = int(np.ceil(np.sqrt(len(board))))
    padded = np.concatenate([board, np.repeat(board[-1:], side * side - len(board), axis=0)]).reshape(side, side, 3)
    return Image.fromarray(padded).quantize(colors=255, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE)


def _on_palette(frame_rgb: np.ndarray, palette: Image.Image) -> Image.Image:
    return Image.fromarray(frame_rgb).quantize(palette=palette, dither=Image.Dither.NONE)


def _write_mp4(path: str, frames: Iterator[np.ndarray], fps: float) -> None:
    try:
        import imageio.v2 as imageio  # late: optional, tried where used
        import imageio_ffmpeg  # noqa: F401 - the encoder binary the writer needs  # late: optional, tried where used
    except ImportError:
        raise AnimationError("MP4 output needs the imageio-ffmpeg package (pip install imageio-ffmpeg)") from None
    writer = imageio.get_writer(path, format="FFMPEG", mode="I", fps=fps, codec="libx264", pixelformat="yuv420p",
                                macro_block_size=2, ffmpeg_log_level="error",
                                output_params=["-fflags", "+bitexact", "-flags:v", "+bitexact"])
    try:
        for f in frames:
            writer.append_data(f)
    finally:
        writer.close()
