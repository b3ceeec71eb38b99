"""`rmot import --task r1=A.mod --task r2=B.mod -o OUT.rmot --cell CELL`: several robots'
programs into one .rmot program with a task per robot.

Each `--task ROBOT=FILE` gives a file of ROBOT's program (repeat one robot for its several
files: a KRL .src and .dat, TP programs, RAPID modules of one task; its main file first). The
robots keep the order of their first `--task`: the k-th is RAPID task T_ROBk, unless
`--task ROBOT:NAME=FILE` names its task (the names a controller's WaitSyncTask lists use). Each task's files
are read as `rmot import --cell CELL --robot ROBOT` reads them; backends/readers/tasks.py then
reads the barriers back as `sync`. Bad arguments are located errors (E523, exit 2): a robot
that is not the cell's, a file given twice, --task without --cell or with FILE arguments.
"""

from __future__ import annotations

import os
import re
import sys
from dataclasses import replace

import click

from rmot.compiler.cli import EXIT_INPUT, EXIT_OK
from rmot.compiler.cli.import_read import (
    cell_signals, print_summary, read_on_robot, refuse_output_input, robot_signals, write_output,
)
from rmot.lang.diagnostics import Diagnostic, Severity, render
from rmot.lang.source import SourceFile

__all__ = ["import_tasks"]


def _fail(message: str, path: str | None) -> None:
    """Print E523 (at line 1 of `path` where given) and exit 2."""
    from rmot.backends.readers import codes, span_of  # late: loads numpy only when this runs
    from rmot.backends.readers.model import Where  # late: loads numpy only when this runs

    span = None
    if path is not None:
        span = span_of(Where(path, 1))
        if not span.file.text:  # not read yet: its first line, to show under the message
            span = replace(span, file=SourceFile(path, _first_line(path)))
    click.echo(render(Diagnostic(codes.TASK_SPEC_INVALID, Severity.ERROR, message, span)), err=True)
    sys.exit(EXIT_INPUT)


def _first_line(path: str) -> str:
    """The file's first line as text ('' where it does not read): for showing, not for parsing."""
    try:
        with open(path, "rb") as f:
            return f.readline(200).decode("utf-8", errors="replace").rstrip("\r\n")
    except OSError:
        return ""


def _task_files(specs: tuple[str, ...], robots: list[str]) -> dict[str, tuple[str, list[str]]]:
    """robot -> (its RAPID task's name or "", its files), robots in the order of their first
    --task; E523 on a bad spec."""
    out: dict[str, tuple[str, list[str]]] = {}
    seen: dict[str, str] = {}
    for spec in specs:
        head, eq, path = spec.partition("=")
        robot, _, task = (x.strip() for x in head.partition(":"))
        path = path.strip()
        if not eq or not robot or not path or not re.fullmatch(r"\w*", task):
            _fail(f"--task must be ROBOT=FILE or ROBOT:RAPIDTASK=FILE (got `{spec}`)", None)
        if not os.path.isfile(path):
            _fail(f"--task {robot}=FILE must name an existing file (got `{path}`)", None)
        if robot not in robots:
            _fail(f"--task {robot}: the task's robot must be a robot of the cell ({', '.join(robots)}; "
                  f"got `{robot}`)", path)
        key = os.path.realpath(path)
        if key in seen:
            _fail(f"a file must be given once (`{path}` is given for {seen[key]} already)", path)
        seen[key] = robot
        named, files = out.setdefault(robot, (task, []))
        if task and named and task.upper() != named.upper():
            _fail(f"--task {robot}: a robot runs one RAPID task (got {named} and {task})", path)
        out[robot] = (named or task, files + [path])
    return out


def import_tasks(files: tuple[str, ...], output: str, robot: str | None, cell: str | None,
                 specs: tuple[str, ...]) -> None:
    """Read every task's files, their barriers as `sync`, write OUT; exits (0, or 2 on bad input)."""
    from rmot.backends.readers import ImportError_, span_of  # late: loads numpy only when this runs
    from rmot.backends.readers.tasks import TaskDoc, read_barriers, tasks_program_text  # late: loads numpy
    from rmot.backends.readers.position_records import with_position_records  # late: loads numpy only when this runs
    from rmot.backends.readers.writer import SignalMap, rename_warnings  # late: loads numpy only when this runs
    from rmot.backends.handshake import handshake_ports  # late: loads numpy only when this runs
    from rmot.lang import ir  # late: tests replace it (monkeypatch): read at call time

    if files or robot is not None or cell is None:
        _fail("--task ROBOT=FILE reads several robots' programs into one: give --cell CELL, and no FILE "
              "arguments or --robot (each --task names its robot)", None)
    assert cell is not None
    first = cell_signals(cell, None)
    if isinstance(first, str):
        click.echo(first, err=True)
        sys.exit(EXIT_INPUT)
    cell_ir = first[2]
    assert isinstance(cell_ir, ir.Cell)
    given = _task_files(specs, [r.name for r in cell_ir.robots])
    refuse_output_input(output, tuple(f for _, paths in given.values() for f in paths))
    tasks = []
    try:
        for name, (task, paths) in given.items():
            found = robot_signals(cell_ir, name)
            assert isinstance(found[0], SignalMap)
            doc = read_on_robot(paths, cell, found, None)
            tasks.append(TaskDoc(name, doc, found[0], handshake_ports(cell_ir, name), task))
        tasks, warnings = read_barriers(tasks, span_of)
        tasks = [replace(t, doc=with_position_records(t.doc)) for t in tasks]  # the data natives name, barriers read
    except ImportError_ as exc:
        click.echo(render(exc.diagnostic), err=True)
        sys.exit(EXIT_INPUT)
    for t in tasks:
        for d in t.doc.diagnostics + rename_warnings(t.doc, span_of):
            click.echo(render(d), err=True)
    for d in warnings:
        click.echo(render(d), err=True)
    use = os.path.relpath(os.path.abspath(cell), os.path.dirname(os.path.abspath(output)))
    write_output("program", output, tasks_program_text(tasks, use), tuple(f for _, paths in given.values() for f in paths))
    for t in tasks:
        print_summary(t.doc)
    click.echo(f"wrote {output}")
    sys.exit(EXIT_OK)
