"""`rmot plot PROGRAM -o FILE.png|.svg [--what KIND]`: the planned motion as a chart.

    joints    joint positions against their limits      speeds  joint speeds against theirs
    accels    joint accelerations against theirs        torque  joint torques (inverse dynamics)
    tcp       TCP speed against the programmed speed, W221 slowdowns shaded
    timeline  each task's instructions side by side: moves, waits, syncs, I/O

Exit codes as `rmot render`: 2 bad input (missing file E501, no program E119), 1 planning
errors (the motion is still plotted), else 0. Plotting never depends on verification.
"""

from __future__ import annotations

import os
import sys
from typing import Any

import click

from rmot.compiler.cli import EXIT_FINDINGS, EXIT_INPUT
from rmot.lang.diagnostics import render_all, Diagnostic, Severity
from rmot.lang.atomic import write_bytes

__all__ = ["plot", "write_or_fail"]

KINDS = ("joints", "speeds", "accels", "torque", "tcp", "timeline")


def _output(ctx: click.Context, param: click.Parameter, value: str) -> str:
    if os.path.splitext(value)[1].lower() not in (".png", ".svg"):
        raise click.BadParameter(f"must end in .png or .svg (got {value!r})")
    return value


def fail(*diagnostics: Any) -> None:

    click.echo(render_all(list(diagnostics)), err=True)
    sys.exit(EXIT_INPUT)


def write_or_fail(path: str, data: bytes) -> None:
    from rmot.sim.render import codes as picture_codes  # late: loads PIL only when this runs

    try:
        write_bytes(path, data)
    except OSError as exc:
        fail(Diagnostic(picture_codes.VIEW_OUTPUT_FAILED, Severity.ERROR,
                        f"output file must be writable (got '{path}': {exc.strerror or exc})", None))


@click.command(name="plot")
@click.argument("program", type=click.Path(dir_okay=False))
@click.option("-o", "--output", required=True, callback=_output, help="Output file: .png or .svg.")
@click.option("--what", type=click.Choice(KINDS), default="joints", show_default=True, help="What to plot.")
@click.option("--cell", type=click.Path(dir_okay=False), default=None, help="The cell file, if not in PROGRAM.")
@click.option("--project-root", type=click.Path(file_okay=False), default=None, help="Directory that file paths may not leave.")
@click.option("--no-cache", is_flag=True, help="Plan from scratch; neither read nor write the plan cache.")
def plot(program: str, output: str, what: str, cell: str | None, project_root: str | None, no_cache: bool) -> None:
    """Plot a program's joints, speeds, torques, TCP speed or timeline to PNG or SVG."""
    from rmot.compiler.cli.render_cmd import load_plan  # late: loads PIL only when this runs

    plan = load_plan(program, cell, project_root, use_cache=not no_cache, purpose="plot")
    from rmot.sim.plots import figure_bytes, plot_data  # late: tests replace it (monkeypatch): read at call time

    fmt = os.path.splitext(output)[1].lower().lstrip(".")
    write_or_fail(output, figure_bytes(plot_data(plan), what, fmt))
    click.echo(f"wrote {output}")  # a success says so, as compile, render and place do
    if any(d.is_error for d in plan.diagnostics):
        sys.exit(EXIT_FINDINGS)
