"""`rmot report PROGRAM... -o report.html`: one self-contained, offline HTML page.

For each program: verdict, cycle times, model assumptions, every finding with its source
line, a picture and a link into the embedded 3D viewer at its worst instant, the plots, the
cycle-time breakdown, and the robot and cell data used (rmot.sim.report_html).

Exit codes as `rmot check`: 0 every program verifies, 1 findings of severity error, 2 input
errors (the page is still written, with the programs that could be read).
"""

from __future__ import annotations

import os
import sys

import click

from rmot.compiler.cli import EXIT_FINDINGS, EXIT_INPUT
from rmot.lang.diagnostics import Diagnostic, render_all

__all__ = ["report"]


def _output(ctx: click.Context, param: click.Parameter, value: str) -> str:
    if os.path.splitext(value)[1].lower() not in (".html", ".htm"):
        raise click.BadParameter(f"must end in .html (got {value!r})")
    return value


@click.command(name="report")
@click.argument("programs", nargs=-1, required=True, type=click.Path(dir_okay=False))
@click.option("-o", "--output", required=True, callback=_output, help="The HTML page to write.")
@click.option("--cell", type=click.Path(dir_okay=False), default=None, help="Cell file (overrides `use cell`).")
@click.option("--project-root", type=click.Path(file_okay=False), default=None, help="Paths may not leave this directory.")
@click.option("--no-cache", is_flag=True, help="Plan from scratch; neither read nor write the plan cache.")
def report(programs: tuple[str, ...], output: str, cell: str | None, project_root: str | None, no_cache: bool) -> None:
    """Verify PROGRAMs and write one HTML page: findings with pictures, plots, 3D view, data."""
    from rmot.compiler.cli.plot_cmd import write_or_fail  # late: loads PIL only when this runs
    from rmot.compiler.cli import stages  # late: loads coal only when this runs
    from rmot.sim.report_html import ProgramResult, render_report  # late: loads PIL only when this runs

    results, input_error = [], False
    for path in programs:
        front: tuple[Diagnostic, ...] = ()
        try:  # a stage failing unexpectedly is E550 for this program (compiler/cli/stages.py)
            loaded = stages.load(path, cell=cell, project_root=project_root, use_cache=not no_cache)
            front = tuple(loaded.diagnostics)
            if any(d.is_error for d in front) or loaded.program is None:
                input_error = True
                results.append(ProgramResult(path, None, front))
                continue
            plan = stages.plan(loaded.program, use_cache=not no_cache)
            checked = stages.verify(plan)
        except stages.StageError as exc:
            input_error = True
            results.append(ProgramResult(path, None, front + (exc.diagnostic,)))
            continue
        from rmot.compiler.design.machine_data import checklists  # late: loads numpy only when this runs

        results.append(ProgramResult(path, plan, front + tuple(checked.diagnostics), dict(checked.cycle_times),
                                     machine_data=checklists(plan)))
    page, problems = render_report(results)
    write_or_fail(output, page.encode("utf-8"))
    click.echo(f"wrote {output}")  # a success says so, as compile, render and place do
    shown = [d for r in results for d in r.diagnostics] + list(problems)
    if shown:
        click.echo(render_all(shown), err=True)
    if input_error:
        sys.exit(EXIT_INPUT)
    if any(d.is_error for r in results for d in r.diagnostics):
        sys.exit(EXIT_FINDINGS)
