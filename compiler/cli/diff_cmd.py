"""`rmot diff A B`: what changed between two vendor programs of one vendor (a pendant touch-up).

Each side is one vendor file (with a KRL `.src` its `.dat` beside it is read too). Prints one
line per difference, located `file:line` on both sides: targets moved (mm, deg), speeds,
zones, times, tools, frames and I/O changed, instructions added or removed. Exit 0 when the
programs mean the same, 1 when they differ, 2 on input errors (as diff(1)).
"""

from __future__ import annotations

import sys

import click

from rmot.compiler.cli import EXIT_FINDINGS, EXIT_INPUT, EXIT_OK

__all__ = ["diff"]


@click.command(name="diff", help="The semantic difference of two vendor programs of one vendor.")
@click.argument("a", type=click.Path(dir_okay=False, exists=True))
@click.argument("b", type=click.Path(dir_okay=False, exists=True))
def diff(a: str, b: str) -> None:
    from rmot.backends.readers import ImportError_, companions, read_files, vendor_of
    from rmot.backends.readers import codes
    from rmot.backends.readers.diff import diff_documents
    from rmot.lang.diagnostics import Diagnostic, Severity, render

    if vendor_of(a) is not None and vendor_of(a) != vendor_of(b):
        from rmot.backends.readers import span_of
        from rmot.backends.readers.model import Where

        click.echo(render(Diagnostic(codes.DIFF_VENDORS_DIFFER, Severity.ERROR,
                                     f"both programs must be of one vendor (got {vendor_of(a)} and {vendor_of(b)})",
                                     span_of(Where(b, 1)))), err=True)
        sys.exit(EXIT_INPUT)
    try:
        left, right = read_files(companions(a)), read_files(companions(b))
    except ImportError_ as exc:
        click.echo(render(exc.diagnostic), err=True)
        sys.exit(EXIT_INPUT)
    lines = diff_documents(left, right)
    for line in lines:
        click.echo(line)
    click.echo(f"{len(lines)} difference{'s' if len(lines) != 1 else ''}")
    sys.exit(EXIT_FINDINGS if lines else EXIT_OK)
