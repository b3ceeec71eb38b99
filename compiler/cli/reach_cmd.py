"""`rmot reach [CELL] --robot NAME -o map.png|.svg|.html`: the reachable workspace.

    rmot reach examples/cells/demo.rmot --robot r1 --tool gripper --orientation rx=180deg -o reach.png
    rmot reach --robot abb_irb120 -o irb120.html

PNG / SVG: two slices, a top view at height --z (default: the base's height) and a side
view through the base (y = the base's y). HTML: the 3-D point cloud, interactive.
Every point is coloured by manipulability relative to the best on the map (0 = singular).
Exit codes: 0 written; 2 bad input (cell errors, unknown robot or tool, bad option: E80x
diagnostics of compiler/design/codes.py; an unwritable -o file: E520).
"""

from __future__ import annotations

import os
import sys
from typing import Any

import click

from rmot.compiler.cli import EXIT_INPUT
from rmot.lang.diagnostics import render_all
from rmot.compiler.cli.design_errors import fail, fail_code, fail_output, require_output_dir
from rmot.compiler.design import codes

__all__ = ["reach"]

FORMATS = (".png", ".svg", ".html")
SLICE_SAMPLES = 1_000_000  # joint vectors drawn for an any-orientation slice
CLOUD_SAMPLES = 200_000  # ... for the 3-D cloud


def load_cell(path: str, project_root: str | None) -> Any:
    """The cell of a cell file or a program file; front-end errors end the command (exit 2)."""
    from rmot.compiler.frontend import load_program  # late: tests replace it (monkeypatch): read at call time

    loaded = load_program(path, project_root=project_root)
    if loaded.diagnostics:
        click.echo(render_all(loaded.diagnostics), err=True)
    if loaded.has_errors or loaded.cell is None:
        sys.exit(EXIT_INPUT)
    return loaded.cell


def _map(study: Any, points: Any, step: float, rot: Any, label: str, sweep: Any = None) -> Any:
    """IK at every point for a fixed orientation; forward sampling for any orientation; for a
    robot on a track, both over the track's travel (compiler/design/reach_track.py)."""
    import numpy as np  # late: loads numpy only when this runs

    from rmot.compiler.design.reach import reach_map, sampled_map  # late: loads numpy only when this runs
    from rmot.compiler.design.reach_track import swept_map  # late: loads numpy only when this runs

    if sweep is not None:
        planar = bool(np.ptp(points, axis=0).min() < step / 2)
        return swept_map(study, sweep, points, step, rot, label, SLICE_SAMPLES if planar else CLOUD_SAMPLES)

    if rot is None:
        planar = bool(np.ptp(points, axis=0).min() < step / 2)  # a slice catches ~1/40 of the samples: draw more
        return sampled_map(study.robot, points, step, base=study.base, tcp=study.tcp, name=label,
                           samples=SLICE_SAMPLES if planar else CLOUD_SAMPLES)
    return reach_map(study.robot, points, base=study.base, tcp=study.tcp, orientation=rot, name=label)


@click.command(name="reach")
@click.argument("cell", required=False, type=click.Path(dir_okay=False))
@click.option("--robot", "robot_name", default=None, help="The cell's robot (default: its only one), or a library robot / URDF without CELL.")
@click.option("-o", "--output", required=True, help="Output file: .png or .svg (slices), .html (interactive 3-D).")
@click.option("--tool", default=None, help="A tool of the cell: map its TCP instead of the flange.")
@click.option("--orientation", default="any", show_default=True,
              help="TCP orientation in world, e.g. 'rx=180deg' (R = Rz·Ry·Rx), or 'any' (sampled joint space).")
@click.option("--z", "z_text", default=None, help="Height of the top-view slice, e.g. 750mm [the base's height].")
@click.option("--step", "step_text", default=None, help="Grid step, e.g. 20mm [reach/40 for slices, reach/12 in 3-D].")
@click.option("--project-root", type=click.Path(file_okay=False), default=None, help="Directory that file paths may not leave.")
def reach(cell: str | None, robot_name: str | None, output: str, tool: str | None, orientation: str,
          z_text: str | None, step_text: str | None, project_root: str | None) -> None:
    """Draw the reachable workspace of a robot, coloured by distance to singularity."""
    import numpy as np  # late: loads numpy only when this runs

    from rmot.compiler.design.reach import reach_bound  # late: loads numpy only when this runs
    from rmot.compiler.design.reach_track import track_sweep  # late: loads numpy only when this runs
    from rmot.compiler.design.study import OptionError, fixture_meshes, parse_angles, rotation_rpy, study_for  # late: loads PIL only when this runs

    ext = os.path.splitext(output)[1].lower()
    if ext not in FORMATS:
        fail_code(codes.OUTPUT_FORMAT, f"-o must end in one of {', '.join(FORMATS)} (got '{output}')")
    require_output_dir("map file", output)
    try:
        rot = None if orientation.strip() == "any" else rotation_rpy(*parse_angles(orientation))
        z = _length("--z", z_text)
        step = _length("--step", step_text)
        if step is not None and not step > 0:
            raise OptionError(codes.OPTION_RANGE, f"--step must be positive (got '{step_text}')")
        study = study_for(load_cell(cell, project_root) if cell else None, robot_name, tool)
        bound = reach_bound(study.robot, study.tcp)
        sweep = track_sweep(study.cell, study.instance.name) if study.instance is not None else None
        if step is not None:
            _check_work(ext, step, bound + (0.0 if sweep is None else 0.5 * float(np.linalg.norm(sweep.travel))), step_text or "")
    except OptionError as exc:
        fail(exc.diagnostic())
    fixtures, diags = fixture_meshes(study.cell)
    if diags:

        click.echo(render_all(diags), err=True)
    label = study.instance.name if study.instance else study.robot.name
    what = ("any orientation (sampled joint vectors: a cell without a sample may still be reachable)"
            if rot is None else f"orientation {orientation.strip()}")
    caption = [f"{label} ({study.robot.model_name}): TCP {'of ' + tool if tool else '= flange'}, {what}; "
               f"colour = manipulability / best on this map (0 = singular)",
               "reach only: joint limits and IK, not collisions; dashed circle = upper bound on reach from the link lengths"]
    caption += _axes_notes(study.cell, sweep)
    try:
        _draw(study, ext, output, step, bound, rot, z, label, caption, fixtures, sweep)
    except OSError as exc:
        fail_output("map file", output, exc)
    click.echo(f"wrote {output}")


# Work bound of one map: grid points IK is solved at (or sampled cells of a slice). A 3-D map at
# the default step has ~7,000 points, a slice ~6,400; 2,000,000 is ~300 times that (minutes).
MAX_GRID_POINTS = 2_000_000


def _length(option: str, text: str | None) -> float | None:
    """A length option ('750mm') in metres, or None when not given; raises OptionError (E802)."""
    from rmot.compiler.cli.check_cmd import parse_length  # late: loads coal only when this runs
    from rmot.compiler.design.study import OptionError  # late: loads PIL only when this runs

    if text is None:
        return None
    try:
        return parse_length(text)
    except ValueError as exc:
        raise OptionError(codes.OPTION_NUMBER, f"{option} {exc}") from None


def _check_work(ext: str, step: float, bound: float, step_text: str) -> None:
    """A --step so small that the grid exceeds MAX_GRID_POINTS is refused (E808) before any work."""
    from rmot.compiler.design.study import OptionError  # late: loads PIL only when this runs

    per_axis = 2 * bound / step + 1
    points = per_axis ** 3 if ext == ".html" else 2 * per_axis ** 2
    if points > MAX_GRID_POINTS:
        least = 2 * bound / ((MAX_GRID_POINTS if ext == ".html" else MAX_GRID_POINTS / 2) ** (1 / (3 if ext == ".html" else 2)) - 1)
        raise OptionError(codes.OPTION_RANGE, f"--step must be at least {least * 1000:.1f} mm for this map "
                          f"(got '{step_text}': {points:.3g} grid points, at most {MAX_GRID_POINTS:,})")


def _axes_notes(cell: Any, sweep: Any) -> list[str]:
    """Caption lines for a cell with external axes: the track swept; fixtures on a positioner at home."""
    notes = [] if sweep is None else [sweep.caption()]
    external = getattr(cell, "external", None)
    riding = sorted({m.mechanism for m in external.mounts if m.kind == "fixture"}) if external is not None else []
    if riding:
        notes.append(f"fixtures on {', '.join(riding)} drawn with the axes at home")
    return notes


def _draw(study: Any, ext: str, output: str, step: float | None, bound: float, rot: Any, z: float | None,
          label: str, caption: list[str], fixtures: list[Any], sweep: Any = None) -> None:
    from rmot.compiler.design.reach import grid_for, slice_grid  # late: loads numpy only when this runs
    from rmot.compiler.design.reach_track import swept_grid, swept_slice  # late: loads numpy only when this runs

    if ext == ".html":
        grid_step = step or bound / (12 if study.robot.has_closed_form or rot is None else 8)
        grid = grid_for(study.base, bound, grid_step) if sweep is None else swept_grid(sweep, bound, grid_step)
        m = _map(study, grid, grid_step, rot, label, sweep)
        from rmot.compiler.design.reach_draw import reach_html  # late: loads numpy only when this runs
        from rmot.sim.render.files import write_text  # late: loads PIL only when this runs

        caption.append(f"grid step {grid_step * 1000:.0f} mm; {int(m.reached.sum())} of {len(m.points)} points reached")
        write_text(output, reach_html(m, fixtures, f"rmot reach: {label}", caption))
    else:
        from rmot.compiler.design.figure import to_png, to_svg  # late: loads numpy only when this runs
        from rmot.compiler.design.reach_draw import Panel, panels_figure  # late: loads numpy only when this runs
        from rmot.sim.render.files import write_png, write_text  # late: loads PIL only when this runs

        grid_step = step or bound / (40 if study.robot.has_closed_form or rot is None else 20)
        level_z = float(study.base[2, 3]) if z is None else z
        level_y = float(study.base[1, 3])
        def plane(kind: str, level: float) -> Any:
            grid = slice_grid(study.base, bound, grid_step, kind, level) if sweep is None else swept_slice(sweep, bound, grid_step, kind, level)
            return _map(study, grid, grid_step, rot, label, sweep)

        top, side = plane("xy", level_z), plane("xz", level_y)
        best = max(top.manipulability_max, side.manipulability_max)
        top, side = top.rescaled(best), side.rescaled(best)
        panels = [Panel(f"top view, z = {level_z:.3f} m", "xy", level_z, grid_step, top),
                  Panel(f"side view, y = {level_y:.3f} m", "xz", level_y, grid_step, side)]
        caption.append(f"grid step {grid_step * 1000:.0f} mm")
        fig = panels_figure(panels, fixtures, caption)
        if ext == ".png":
            write_png(output, to_png(fig))
        else:
            write_text(output, to_svg(fig))
