"""`rmot render`: a picture, an animation, a hidden-line drawing or an interactive view.

    rmot render PROGRAM [--cell CELL] -o out.png|out.gif|out.mp4|out.svg|out.html
                [--at SECONDS] [--size WxH] [--aa K] [--camera "eye=x,y,z;center=x,y,z;fov=40"]
                [--fps N] [--project-root DIR]

Bad input (the program, the cell, the options) is reported as diagnostics, exit code 2.
Planning errors are reported too (exit 1, as in `rmot check`), but the planned motion is still drawn: seeing
where a move goes wrong is the point of the picture. Rendering only draws: the exit code
never depends on verification findings.
"""

from __future__ import annotations

import os
import sys
from typing import Any, NoReturn

import click

from rmot.compiler.cli import EXIT_FINDINGS, EXIT_INPUT
from rmot.lang.diagnostics import render_all, Diagnostic, Severity

__all__ = ["render"]

FORMATS = (".png", ".gif", ".mp4", ".svg", ".html")


def _parse_size(ctx: click.Context, param: click.Parameter, value: str | None) -> tuple[int, int] | None:
    if value is None:
        return None
    width, sep, height = value.lower().partition("x")
    try:
        size = (int(width), int(height))
    except ValueError:
        size = (0, 0)
    if not sep or not (16 <= size[0] <= 8192 and 16 <= size[1] <= 8192):
        raise click.BadParameter(f"must be WIDTHxHEIGHT in pixels, each 16..8192 (got {value!r})")
    return size


def _check_camera(ctx: click.Context, param: click.Parameter, value: str | None) -> str | None:
    """Syntax now; the values merge with the default framing once the scene is known."""
    if value is None or value.strip().lower() in ("front", "side", "top", "iso"):
        return value
    from rmot.sim.render.camera import CameraSpecError, camera_fields  # late: loads PIL only when this runs

    try:
        camera_fields(value)
    except CameraSpecError as exc:
        raise click.BadParameter(str(exc)) from None
    return value


def _camera(text: str | None, scene: Any, size: tuple[int, int]) -> Any:
    """The --camera settings over the default three-quarter view of the scene."""
    if text is None:
        return None
    from rmot.sim.render.camera import CameraSpecError, parse_camera  # late: loads PIL only when this runs
    from rmot.sim.render.still import PRESETS, default_camera, preset_camera  # late: loads PIL only when this runs

    if text.strip().lower() in PRESETS:  # a named view: front, side, top, iso
        return preset_camera(scene, text.strip().lower(), size)

    try:
        return parse_camera(text, default=default_camera(scene, size))
    except CameraSpecError as exc:
        raise click.BadParameter(str(exc), param_hint="'--camera'") from None


def _output_format(ctx: click.Context, param: click.Parameter, value: str) -> str:
    if os.path.splitext(value)[1].lower() not in FORMATS:
        raise click.BadParameter(f"must end in one of {', '.join(FORMATS)} (got {value!r})")
    return value


@click.command(name="render")
@click.argument("program", type=click.Path(dir_okay=False))
@click.option("--cell", "cell", type=click.Path(dir_okay=False), default=None, help="The cell file, if not in PROGRAM.")
@click.option("-o", "--output", required=True, callback=_output_format,
              help="Output file: .png (still), .gif/.mp4 (animation), .svg (hidden-line), .html (3D viewer).")
@click.option("--at", "at", type=float, default=0.0, show_default=True, help="Instant of a still picture, s.")
@click.option("--size", callback=_parse_size, default=None, help="WIDTHxHEIGHT in pixels [640x480; 480x360 for animations].")
@click.option("--aa", type=click.IntRange(1, 8), default=None, help="Supersampling factor K (K x K samples per pixel).")
@click.option("--camera", callback=_check_camera, default=None,
              help='front|side|top|iso, or e.g. "eye=3,-3,2;center=0.5,0,0.5;fov=40" (m, deg); keys left out keep the default view.')
@click.option("--fps", type=click.IntRange(1, 60), default=None, help="Frames per second of animations [GIF 10, MP4 and HTML 25].")
@click.option("--project-root", type=click.Path(file_okay=False), default=None, help="Directory that file paths may not leave.")
@click.option("--no-cache", is_flag=True, help="Plan from scratch; neither read nor write the plan cache.")
def render(program: str, cell: str | None, output: str, at: float, size: tuple[int, int] | None, aa: int | None,
           camera: str | None, fps: int | None, project_root: str | None, no_cache: bool) -> None:
    """Render a program to PNG, GIF, MP4, SVG or HTML."""
    plan = load_plan(program, cell, project_root, use_cache=not no_cache)
    ext = os.path.splitext(output)[1].lower()
    fps = fps or (10 if ext == ".gif" else 25)  # GIF: fewer frames keep the file small
    try:
        _write(plan, output, ext, at, size, aa, camera, fps)
        click.echo(f"wrote {output}")  # a success says so, as compile and place do
        if any(d.is_error for d in plan.diagnostics):
            sys.exit(EXIT_FINDINGS)  # drawn anyway (a picture helps to see what failed), but not a success
    except _InputError as exc:
        _fail(exc.diagnostic)
    except OSError as exc:
        from rmot.lang.diagnostics import Diagnostic, Severity  # late: optional, tried where used
        from rmot.sim.render import codes  # late: optional, tried where used

        _fail(Diagnostic(codes.OUTPUT_FAILED, Severity.ERROR,
                         f"output file must be writable (got '{output}': {exc.strerror or exc})", None))


class _InputError(Exception):
    def __init__(self, diagnostic: Any) -> None:
        super().__init__(diagnostic.message)
        self.diagnostic = diagnostic


def _fail(*diagnostics: Any) -> NoReturn:

    click.echo(render_all(list(diagnostics)), err=True)
    sys.exit(EXIT_INPUT)


def _report(diagnostics: Any, stop_on_error: bool = True) -> None:
    """Print the diagnostics; exit 2 if any is an error (unless told to go on)."""

    diagnostics = tuple(diagnostics or ())
    if diagnostics:
        click.echo(render_all(diagnostics), err=True)
    if stop_on_error and any(d.is_error for d in diagnostics):
        sys.exit(EXIT_INPUT)


def load_plan(program: str, cell: str | None, project_root: str | None, use_cache: bool = True,
              purpose: str = "render") -> Any:
    """Front end then planner (shared by render and plot). Front-end errors end the command
    (exit 2; a missing file is E501, a file without a program E119); planning errors are
    printed and the plan is still returned, so the caller draws it and exits 1."""
    from rmot.compiler.cli import stages  # late: loads coal only when this runs
    from rmot.sim.render import codes  # late: loads PIL only when this runs

    loaded = stages.load(program, cell=cell, project_root=project_root, use_cache=use_cache)
    _report(loaded.diagnostics)
    if loaded.program is None:
        _fail(Diagnostic(codes.NOTHING_TO_RENDER, Severity.ERROR,
                         f"'{program}' must contain a program to {purpose} (got only a cell)", None))
    planned = stages.plan(loaded.program, use_cache=use_cache)
    _report(planned.diagnostics, stop_on_error=False)
    return planned


def _write(plan: Any, output: str, ext: str, at: float, size: tuple[int, int] | None, aa: int | None,
           camera_text: str | None, fps: int) -> None:
    from rmot.sim.render import codes  # late: loads PIL only when this runs
    from rmot.sim.render.files import write_png, write_text  # late: loads PIL only when this runs
    from rmot.sim.render.scene import prepare  # late: loads PIL only when this runs

    duration = float(plan.cycle_time)
    if ext in (".png", ".svg") and not 0.0 <= at <= duration + 1e-9:
        raise _InputError(Diagnostic(codes.TIME_OUTSIDE, Severity.ERROR,
                                     f"--at must be within 0..{duration:.3f} s, the program's duration (got {at:g} s)", None))
    scene = prepare(plan)
    _report(scene.diagnostics)  # meshes that do not load: errors stop here, warnings are shown
    size = size or ((480, 360) if ext in (".gif", ".mp4") else (640, 480))
    camera = _camera(camera_text, scene, size)
    marks = _markings(plan, scene)  # findings are marked in every kind of picture
    if ext == ".png":
        from rmot.sim.render.still import still_image  # late: loads PIL only when this runs

        write_png(output, still_image(scene, time=at, size=size, aa=aa or 2, camera=camera, marks=marks))
    elif ext in (".gif", ".mp4"):
        from rmot.sim.render.animate import AnimationError, write_animation  # late: loads PIL only when this runs

        try:
            write_animation(scene, output, fps=fps, size=size, aa=aa or 1, camera=camera, marks=marks)
        except AnimationError as exc:
            raise _InputError(Diagnostic(codes.FORMAT_UNAVAILABLE, Severity.ERROR, str(exc), None)) from None
    elif ext == ".svg":
        from rmot.sim.render.svg import render_svg  # late: loads PIL only when this runs

        write_text(output, render_svg(scene, time=at, size=size, camera=camera, marks=marks))
    else:
        from rmot.sim.render.html import render_html  # late: loads PIL only when this runs

        write_text(output, render_html(scene, fps=fps, camera=camera, marks=marks))


def _markings(plan: Any, scene: Any) -> Any:
    """The scene's markings of the plan's findings, verified through the one pipeline (and its
    cache: compiler/cli/verify_cache.py). A verification that cannot run leaves the pictures
    unmarked, as sim.render.findings.verified_markings does: `rmot check` reports it."""
    from rmot.compiler.cli import stages  # late: loads coal only when this runs
    from rmot.sim.render.findings import markings  # late: loads PIL only when this runs

    try:
        found = stages.verify(plan).diagnostics
    except stages.StageError:
        return ()
    return markings(scene, found)
