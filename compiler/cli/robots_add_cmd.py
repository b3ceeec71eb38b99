"""`rmot robots add TABLE`: a data sheet's DH table as a library-style arm definition.

Prints the definition (or writes it atomically with -o) after checking it by FK against the
table (compiler/robots/add_robot.py). Errors are located diagnostics (E547-E549, exit 2);
warnings (W547, W548) go to stderr and the definition is still written.
"""

from __future__ import annotations

import sys

import click

__all__ = ["add_cmd"]


@click.command(name="add")
@click.argument("table", type=click.Path(dir_okay=False))
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="Write the definition to this file.")
def add_cmd(table: str, output: str | None) -> None:
    """Turn a DH table (YAML/JSON, lang/REFERENCE.md) into a checked library definition."""
    from rmot.compiler.atomic import write_text
    from rmot.compiler.robots.add_robot import add_from_dh
    from rmot.lang.diagnostics import render

    try:
        with open(table, encoding="utf-8") as f:
            text = f.read(1_000_001)
    except (OSError, UnicodeDecodeError) as exc:
        click.echo(f"{table}: error[E547]: cannot read the DH table ({exc.__class__.__name__})", err=True)
        sys.exit(2)
    if len(text) > 1_000_000:
        click.echo(f"{table}: error[E547]: the DH table is over 1 MB", err=True)
        sys.exit(2)
    added = add_from_dh(table, text)
    for d in added.diagnostics:
        click.echo(render(d), err=True)
    if any(d.is_error for d in added.diagnostics):
        sys.exit(2)
    if output:
        write_text(output, added.text)
    else:
        click.echo(added.text, nl=False)
    click.echo(f"checked: FK of the definition = FK of the table within {added.max_mm:.2e} mm and "
               f"{added.max_rad:.2e} rad at 64 random joint values in the ranges", err=True)
    if added.max_mm > 0.01 or added.max_rad > 1e-6:
        click.echo(f"{table}: error[E549]: the definition does not reproduce the table's FK", err=True)
        sys.exit(2)
