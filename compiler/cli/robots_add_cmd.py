"""`rmot robots add TABLE`: a data sheet's DH table as a library-style arm definition.

Prints the definition (or writes it atomically with -o) after checking it by FK against the
table (sim/robots/add_robot.py). Errors are located diagnostics (E547-E549, exit 2);
warnings (W547, W548) go to stderr and the definition is still written.
"""

from __future__ import annotations

import sys

import click
from rmot.lang.atomic import write_text
from rmot.lang.diagnostics import render

__all__ = ["add_cmd"]


@click.command(name="add")
@click.argument("table", type=click.Path(dir_okay=False))
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="Write the definition to this file.")
@click.option("--name", help="URDF only: the library name of the arm.")
@click.option("--vendor", help="URDF only: the maker whose pendant values the URDF's joint values are.")
@click.option("--source", default="", help="URDF only: where the file comes from (cited in the definition).")
@click.option("--base", "base_link", help="URDF only: the link of the controller's base frame.")
@click.option("--tip", help="URDF only: the link of the controller's flange frame.")
def add_cmd(table: str, output: str | None, name: str | None, vendor: str | None, source: str,
            base_link: str | None, tip: str | None) -> None:
    """Turn a DH table (YAML/JSON) or a URDF (lang/REFERENCE.md) into a checked library definition."""
    from rmot.sim.robots.add_robot import add_from_urdf  # late: loads coal only when this runs

    if table.lower().endswith(".urdf"):
        if not name or not vendor:
            raise click.UsageError("a URDF needs --name and --vendor")
        _report(table, add_from_urdf(table, name, vendor.lower(), source, base_link, tip), output, write_text, render)
        return
    _report(table, _from_table(table), output, write_text, render)


def _from_table(table: str):  # type: ignore[no-untyped-def]
    from rmot.sim.robots.add_robot import add_from_dh  # late: loads coal only when this runs

    try:
        with open(table, encoding="utf-8") as f:
            text = f.read(1_000_001)
    except (OSError, UnicodeDecodeError) as exc:
        click.echo(f"{table}: error[E547]: cannot read the DH table ({exc.__class__.__name__})", err=True)
        sys.exit(2)
    if len(text) > 1_000_000:
        click.echo(f"{table}: error[E547]: the DH table is over 1 MB", err=True)
        sys.exit(2)
    return add_from_dh(table, text)


def _report(table: str, added, output: str | None, write_text, render) -> None:  # type: ignore[no-untyped-def]
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
