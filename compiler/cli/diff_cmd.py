"""`rmot diff A B [--cell CELL]`: what changed between two programs of one vendor (a pendant
touch-up), or between a vendor program and the .rmot it was compiled from.

Each side is one vendor file (with a KRL `.src` its `.dat` beside it is read too) or a .rmot
program, which is compiled for the other side's vendor in memory first (then the `B.rmot[...]`
places name lines of that generated program, whose `file.rmot:LINE` comments lead back to the
source). Prints one line per difference, located `file:line` on both sides: targets moved
(mm, deg), speeds, zones, times, tools, frames and I/O changed, instructions added or removed.
Exit 0 when the programs mean the same, 1 when they differ, 2 on input errors (as diff(1)).
"""

from __future__ import annotations

import os
import sys
import tempfile

import click

from rmot.compiler.cli import EXIT_FINDINGS, EXIT_INPUT, EXIT_OK
from rmot.lang.diagnostics import Diagnostic, Severity, render
from rmot.lang.atomic import write_text

__all__ = ["diff"]

def _fail(message: str, path: str, no_counterpart: bool = False) -> None:
    from rmot.backends.readers import codes, span_of  # late: loads numpy only when this runs
    from rmot.backends.readers.model import Where  # late: loads numpy only when this runs

    code = codes.DIFF_NO_COUNTERPART if no_counterpart else codes.DIFF_VENDORS_DIFFER
    click.echo(render(Diagnostic(code, Severity.ERROR, message, span_of(Where(path, 1)))), err=True)
    sys.exit(EXIT_INPUT)


def _compiled(source: str, vendor: str, cell: str | None, workdir: str,
              other: list[str]) -> tuple[list[str], dict[str, str], int]:
    """Compile `source` for `vendor` into `workdir`: (the files to read, temp path -> shown
    name, how many compiled files are left out). The files read are those named like the other
    side's (`handover_r1.mod` of a program of two tasks, a TP job's `MAIN.ls` without the
    programs it calls), so both sides hold the same programs."""
    from rmot.compiler.cli.compile_cmd import compile_program  # late: loads coal only when this runs

    outcome = compile_program(source, (vendor,), cell=cell, allow_findings=True)
    if not outcome.files:
        for d in outcome.diagnostics:
            if d.is_error:
                click.echo(render(d), err=True)
        sys.exit(EXIT_INPUT)
    stem = os.path.splitext(os.path.basename(source))[0].lower()
    named = [os.path.basename(path).lower() for path in other]
    program = [stem + os.path.splitext(name)[1] for name in named]  # a vendor file renamed: the program's own
    shown: dict[str, str] = {}
    by_name: dict[str, str] = {}
    for name, text in sorted(outcome.files.items()):
        path = os.path.join(workdir, name.replace("/", "_"))
        write_text(path, text)
        shown[path] = f"{source}[{name}]"
        by_name[os.path.basename(name).lower()] = path
    read = {k: by_name[n] for k, n in enumerate(named) if n in by_name} or \
        {k: by_name[n] for k, n in enumerate(program) if n in by_name}
    if not read:
        names = ", ".join(sorted(os.path.basename(n) for n in outcome.files))
        _fail(f"{source} compiles for {vendor} to {names}: none is named like {os.path.basename(other[0])} "
              "(give the vendor file of the same name)", other[0], no_counterpart=True)
    return [read[k] for k in sorted(read)], shown, len(outcome.files) - len(read)


@click.command(name="diff", help="The semantic difference of two programs of one vendor (or of one and its .rmot).")
@click.argument("a", type=click.Path(dir_okay=False, exists=True))
@click.argument("b", type=click.Path(dir_okay=False, exists=True))
@click.option("--cell", "cell", type=click.Path(dir_okay=False, exists=True), default=None,
              help="The cell of a .rmot side (else its own `use cell` or the default cell).")
def diff(a: str, b: str, cell: str | None) -> None:
    from rmot.backends.readers import ImportError_, companions, read_files, vendor_of  # late: loads numpy only when this runs
    from rmot.backends.readers.diff import diff_documents  # late: loads numpy only when this runs

    va, vb = vendor_of(a), vendor_of(b)
    if va is None and vb is None:
        _fail("at least one side must be a vendor program (got two .rmot files: compare them with `rmot check`)", b)
    if va is not None and vb is not None and va != vb:
        _fail(f"both programs must be of one vendor (got {va} and {vb})", b)
    vendor = va or vb
    assert vendor is not None
    with tempfile.TemporaryDirectory(prefix="rmot-diff-") as workdir:
        sides: list[list[str]] = [companions(a) if va else [], companions(b) if vb else []]
        shown: dict[str, str] = {}
        left_out = 0
        for k, path in ((0, a), (1, b)):
            if not sides[k]:
                sides[k], names, left_out = _compiled(path, vendor, cell, workdir, sides[1 - k])
                shown.update(names)
        try:
            left, right = read_files(sides[0]), read_files(sides[1])
        except ImportError_ as exc:
            click.echo(render(exc.diagnostic), err=True)
            sys.exit(EXIT_INPUT)
        lines = diff_documents(left, right)
    for line in lines:
        for temp, name in shown.items():
            line = line.replace(temp, name)
        click.echo(line)
    click.echo(f"{len(lines)} difference{'s' if len(lines) != 1 else ''}")
    if left_out:
        click.echo(f"note: the .rmot compiles to {left_out} more {vendor} file{'s' if left_out != 1 else ''} "
                   "(other tasks' programs, routines in files of their own), not compared: "
                   "diff each against the vendor file of its name", err=True)
    sys.exit(EXIT_FINDINGS if lines else EXIT_OK)
