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

# the file of a compiled program that runs (the others are its routines, read with it)
_MAIN_EXT = {"rapid": ".mod", "krl": ".src", "urscript": ".script", "fanuc": ".ls"}


def _fail(message: str, path: str) -> None:
    from rmot.backends.readers import codes, span_of  # late: loads numpy only when this runs
    from rmot.backends.readers.model import Where  # late: loads numpy only when this runs

    click.echo(render(Diagnostic(codes.DIFF_VENDORS_DIFFER, Severity.ERROR, message, span_of(Where(path, 1)))), err=True)
    sys.exit(EXIT_INPUT)


def _compiled(source: str, vendor: str, cell: str | None, workdir: str) -> tuple[list[str], dict[str, str]]:
    """Compile `source` for `vendor` into `workdir`: (files to read, temp path -> shown name)."""
    from rmot.compiler.cli.compile_cmd import compile_program  # late: loads coal only when this runs

    outcome = compile_program(source, (vendor,), cell=cell, allow_findings=True)
    if not outcome.files:
        for d in outcome.diagnostics:
            if d.is_error:
                click.echo(render(d), err=True)
        sys.exit(EXIT_INPUT)
    shown: dict[str, str] = {}
    read: list[tuple[bool, str]] = []
    stem = os.path.splitext(os.path.basename(source))[0].lower()
    for name, text in sorted(outcome.files.items()):
        path = os.path.join(workdir, name.replace("/", "_"))
        write_text(path, text)
        shown[path] = f"{source}[{name}]"
        own = os.path.splitext(name.split("/", 1)[-1])[0].lower()
        if name.endswith(_MAIN_EXT[vendor]) and (vendor == "fanuc" or own == stem):
            read.append((own != stem, path))  # the program's own file first: its main runs
    return [path for _, path in sorted(read)], shown


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
        sides, shown = [], {}
        for path, v in ((a, va), (b, vb)):
            if v is None:
                files, names = _compiled(path, vendor, cell, workdir)
                sides.append(files)
                shown.update(names)
            else:
                sides.append(companions(path))
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
    sys.exit(EXIT_FINDINGS if lines else EXIT_OK)
