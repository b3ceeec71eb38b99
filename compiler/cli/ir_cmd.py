"""`rmot ir FILE [--cell CELL] [--json] [--project-root DIR] [--planned]`: print the checked IR
(with --planned: the IR as planned, each `move free` written as joint moves through its via points).

Diagnostics go to stderr in compiler style; exit 2 when the input has errors, else 0.
A file that holds only a cell prints the cell.
"""

from __future__ import annotations

import sys

import click

from rmot.compiler.cli import EXIT_INPUT, EXIT_OK
from rmot.lang.diagnostics import render

__all__ = ["ir"]


@click.command(name="ir", help="Dump the checked IR of a program (or of a cell file).")
@click.argument("file", type=click.Path(dir_okay=False))
@click.option("--cell", "cell", type=click.Path(dir_okay=False), default=None, help="Use this cell file.")
@click.option("--json", "as_json", is_flag=True, help="Print JSON instead of the text dump.")
@click.option("--project-root", type=click.Path(file_okay=False), default=None,
              help="Directory every path in the sources must stay inside (default: FILE's directory).")
@click.option("--planned", is_flag=True,
              help="Print the IR the backends get: each `move free` as joint moves through its via points.")
def ir(file: str, cell: str | None, as_json: bool, project_root: str | None, planned: bool) -> None:
    from rmot.compiler.frontend import load_program  # late: tests replace it (monkeypatch): read at call time
    from rmot.compiler.ir_dump import dump_cell, dump_program, to_json  # late: loads numpy only when this runs

    result = load_program(file, cell=cell, project_root=project_root)
    for d in result.diagnostics:
        click.echo(render(d), err=True)
    if result.has_errors:
        sys.exit(EXIT_INPUT)
    if result.program is not None:
        program = result.program
        if planned:  # the plan's program: `move free` lowered at plan time (rmot.sim.free)
            from rmot.compiler.cli import stages  # late: loads coal only when this runs

            plan = stages.plan(program)
            for d in plan.diagnostics:
                click.echo(render(d), err=True)
            program = plan.program
        click.echo(to_json(program) if as_json else dump_program(program), nl=False)
    elif result.cell is not None:
        click.echo(to_json(result.cell) if as_json else dump_cell(result.cell) + "\n", nl=False)
    else:
        click.echo(f"rmot: {file} holds no program and no cell (a library: nothing to dump)", err=True)
    sys.exit(EXIT_OK)
