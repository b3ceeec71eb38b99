"""`rmot plan FILE [--cell CELL] [--csv OUT] [--step 4ms] [--project-root DIR]`: plan a program.

Prints every diagnostic (compiler style) and one line per task with its cycle time; with
--csv, writes the sampled trajectories (atomically). Exit codes as in `rmot check`: 2 for
input errors (front end: a missing file is E501, a file without a program E119), 1 for
planning errors (the CSV is still written), 0 otherwise.
"""

from __future__ import annotations

import io
import re

import click

from rmot.lang.atomic import write_text
from rmot.compiler.cli import EXIT_FINDINGS, EXIT_INPUT, EXIT_OK
from rmot.lang.diagnostics import render
from rmot.compiler.cli.oserrors import output_is_input

__all__ = ["plan", "parse_step", "trajectory_csv"]

_STEP = re.compile(r"^\s*([0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?)\s*(ms|s)?\s*$")


def parse_step(text: str) -> float:
    """'4ms', '0.004 s' or '0.004' (seconds) -> seconds; raises click.BadParameter."""
    m = _STEP.match(text)
    if not m:
        raise click.BadParameter(f"step must be a time such as 4ms or 0.004s (got {text!r})")
    value = float(m.group(1)) * (1e-3 if m.group(2) == "ms" else 1.0)
    if not 1e-4 <= value <= 1.0:
        raise click.BadParameter(f"step must be between 0.1 ms and 1 s (got {text!r})")
    return value


def trajectory_csv(plan: object) -> str:
    """One row per sample: task, t (s), q1..qn (rad or m), qd1..qdn, qdd1..qddn."""
    out = io.StringIO()
    width = max((tp.trajectory.q.shape[1] for tp in plan.tasks), default=0)  # type: ignore[attr-defined]
    cols = ["task", "t"] + [f"{k}{j + 1}" for k in ("q", "qd", "qdd") for j in range(width)]
    out.write(",".join(cols) + "\n")
    for tp in plan.tasks:  # type: ignore[attr-defined]
        tr = tp.trajectory
        for i in range(tr.t.shape[0]):
            values = [f"{tr.t[i]:.6f}"] + [f"{v:.9g}" for a in (tr.q, tr.qd, tr.qdd) for v in a[i]]
            out.write(",".join([tp.task.name] + values) + "\n")
    return out.getvalue()


def _load(file: str, cell: str | None, project_root: str | None):  # type: ignore[no-untyped-def]
    """(program or None, diagnostics) from the front end."""
    from rmot.compiler.cli import stages  # late: loads coal only when this runs

    result = stages.load(file, cell=cell, project_root=project_root)
    return result.program, tuple(result.diagnostics)


@click.command(name="plan")
@click.argument("file", type=click.Path(dir_okay=False))
@click.option("--cell", type=click.Path(dir_okay=False), default=None, help="The cell file, if not in FILE.")
@click.option("--csv", "csv_out", type=click.Path(dir_okay=False), default=None, help="Write the sampled trajectory here.")
@click.option("--step", default="4ms", show_default=True, help="Sampling step of the trajectory.")
@click.option("--project-root", type=click.Path(file_okay=False), default=None, help="Paths may not leave this directory.")
@click.option("--no-cache", is_flag=True, help="Plan from scratch; neither read nor write the plan cache.")
def plan(file: str, cell: str | None, csv_out: str | None, step: str, project_root: str | None, no_cache: bool) -> None:
    """Plan FILE: joint trajectories, cycle time per task, planning diagnostics."""

    if csv_out:

        clash = output_is_input("trajectory file", csv_out, (file, cell))
        if clash:
            click.echo(clash, err=True)
            raise SystemExit(EXIT_INPUT)
    step_s = parse_step(step)
    program, diagnostics = _load(file, cell, project_root)
    for d in diagnostics:
        click.echo(render(d), err=True)
    if program is None or any(d.is_error for d in diagnostics):
        raise SystemExit(EXIT_INPUT)
    from rmot.compiler.cli import stages  # late: loads coal only when this runs

    result = stages.plan(program, step=step_s, use_cache=not no_cache)
    for d in result.diagnostics:
        click.echo(render(d), err=True)
    for tp in result.tasks:
        click.echo(f"task {tp.task.name} ({tp.robot}): cycle time {tp.cycle_time:.3f} s")
    if csv_out:
        try:
            write_text(csv_out, trajectory_csv(result))
        except OSError as exc:
            from rmot.compiler.cli.oserrors import output_failed  # late: optional, tried where used

            click.echo(output_failed("trajectory file", csv_out, exc), err=True)
            raise SystemExit(EXIT_INPUT) from None
    raise SystemExit(EXIT_FINDINGS if any(d.is_error for d in result.diagnostics) else EXIT_OK)
