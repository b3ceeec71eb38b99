"""`rmot import FILE... -o OUT.rmot [--robot NAME] [--cell CELL]`: vendor programs to .rmot.

The readers (backends/readers) turn RAPID files into a neutral document; this command picks
the cell (the one given, or a stub it writes beside OUT with the tools, work objects and I/O
names the files declare), prints the program, and says per file how many instructions were
imported and how many kept native. A file that is not its vendor's language is a located
error (exit 2); a line kept native is a located warning.
"""

from __future__ import annotations

import math
import os
import sys
from collections.abc import Sequence
from typing import TYPE_CHECKING

import click

from rmot.compiler.cli import EXIT_INPUT, EXIT_OK
from rmot.lang.diagnostics import render_all, render
from rmot.lang.atomic import write_text

if TYPE_CHECKING:
    import numpy as np

    from rmot.backends.readers.model import Document
    from rmot.lang import ir
    from rmot.lang.ir import Pose

__all__ = ["import_", "DEFAULT_MODELS"]

# the stub cell's robot when --robot is not given: a library arm of the vendor's maker
DEFAULT_MODELS = {"rapid": "abb_irb1600", "krl": "kuka_kr6_r900", "urscript": "ur5e",
                  "fanuc": "fanuc_m20ia", "inform": "yaskawa_gp8", "val3": "staubli_tx2_60"}


def _joint_limits(model: str | None) -> tuple[tuple[float, ...], tuple[float, ...]] | None:
    """(speed rad/s, acceleration rad/s^2) of each joint of the arm `model` (the cell's robot or
    --robot), None where it does not load: a reader then keeps the joint shares it cannot derive."""
    if not model:
        return None
    from rmot.sim.robots.errors import RobotError  # late: loads coal only when this runs
    from rmot.sim.robots.loader import load_robot  # late: loads coal only when this runs

    try:
        robot = load_robot(model)
    except RobotError:
        return None
    return tuple(map(float, robot.velocity_limits)), tuple(map(float, robot.accel_limits))


def _inform_configs(doc: Document, model: str | None, tcp_of: dict[str, Pose]) -> Document:
    """INFORM joint moves configured from their RCONF with the arm's IK (readers/inform_conf.py);
    `doc` as it is for other vendors or where the arm does not load."""
    if doc.vendor != "inform" or not model:
        return doc
    from rmot.backends.readers.inform_conf import resolve_rconf  # late: loads numpy only when this runs
    from rmot.sim.robots.errors import RobotError  # late: loads coal only when this runs
    from rmot.sim.robots.loader import load_robot  # late: loads coal only when this runs

    try:
        robot = load_robot(model)
    except RobotError:
        return doc
    wide = tuple(j for j, (lo, hi) in enumerate(robot.joint_limits.tolist()) if hi - lo > 2 * math.pi + 1e-9)

    def ik(flange: np.ndarray) -> tuple[Sequence[np.ndarray], Sequence[ir.Config]]:
        result = robot.ik(flange)
        return result.solutions, result.branches

    return resolve_rconf(doc, ik, tcp_of, wide)


def _cell_signals(cell_path: str, robot: str | None) -> tuple[object, str, object] | str:
    """(SignalMap, robot name, ir.Cell) of a cell file, or the error text."""
    from rmot.backends.readers.writer import SignalMap  # late: loads numpy only when this runs
    from rmot.lang import ir  # late: tests replace it (monkeypatch): read at call time
    from rmot.compiler.frontend import load_program  # late: tests replace it (monkeypatch): read at call time

    result = load_program(cell_path)
    if result.cell is None or any(d.is_error for d in result.diagnostics):
        return render_all([d for d in result.diagnostics if d.is_error]) or f"rmot: {cell_path}: not a cell"
    names = [r.name for r in result.cell.robots]
    chosen = robot or names[0]
    if chosen not in names:
        return f"rmot: --robot must name a robot of the cell ({', '.join(names)}; got {chosen})"
    kinds = {ir.IoDirection.DIGITAL_OUT: 0, ir.IoDirection.DIGITAL_IN: 1, ir.IoDirection.ANALOG_OUT: 2,
             ir.IoDirection.GROUP_IN: 3}
    tables: list[list[tuple[str, int]]] = [[], [], [], []]
    for s in result.cell.io:
        if s.direction in kinds and s.robot in (None, chosen):
            tables[kinds[s.direction]].append((s.name.upper(), s.port))
    return SignalMap(*(tuple(t) for t in tables)), chosen, result.cell


@click.command(name="import", help="Read RAPID, KRL, URScript, Fanuc TP, INFORM or VAL3 programs back into .rmot.")
@click.argument("files", nargs=-1, required=True, type=click.Path(dir_okay=False, exists=True))
@click.option("-o", "--output", "output", required=True, type=click.Path(dir_okay=False), help="The .rmot file to write.")
@click.option("--robot", default=None, help="With --cell: the cell's robot; without: the library arm of the stub cell.")
@click.option("--cell", "cell", type=click.Path(dir_okay=False, exists=True), default=None,
              help="Run the imported program in this cell (else a stub cell is written beside OUT).")
def import_(files: tuple[str, ...], output: str, robot: str | None, cell: str | None) -> None:
    from rmot.backends.readers import ImportError_, read_files, span_of  # late: loads numpy only when this runs
    from rmot.backends.readers.counts import motion_io_counts  # late: loads numpy only when this runs
    from rmot.backends.readers.payload import cell_parts, match_payloads  # late: loads numpy only when this runs
    from rmot.backends.readers.writer import (  # late: loads numpy only when this runs
        SignalMap, cell_stub, match_tools, program_text, rename_warnings, resolve_signals, stub_signals,
    )
    from rmot.lang import ir  # late: tests replace it (monkeypatch): read at call time

    found = _cell_signals(cell, robot) if cell is not None else None
    if isinstance(found, str):
        click.echo(found, err=True)
        sys.exit(EXIT_INPUT)
    model = robot
    if found is not None:
        cell_ir = found[2]
        assert isinstance(cell_ir, ir.Cell)
        model = cell_ir.robot(found[1]).source.ref
    try:
        doc = read_files(list(files), model=model, limits=_joint_limits(model))
    except ImportError_ as exc:
        click.echo(render(exc.diagnostic), err=True)
        sys.exit(EXIT_INPUT)
    out_dir = os.path.dirname(os.path.abspath(output))
    if cell is not None and found is not None:
        signals, robot_name, cell_ir = found
        assert isinstance(signals, SignalMap) and isinstance(cell_ir, ir.Cell)
        doc = resolve_signals(doc, signals, span_of)
        doc = match_tools(doc, tuple((t.name, t.tcp) for t in cell_ir.tools if t.robot == robot_name))
        doc = match_payloads(doc, cell_parts(cell_ir),
                             tuple((t.tcp, t.mass) for t in cell_ir.tools if t.robot == robot_name), span_of)
        doc = _inform_configs(doc, model, {t.name: t.tcp for t in cell_ir.tools if t.robot == robot_name})
        use = os.path.relpath(os.path.abspath(cell), out_dir)
    else:
        signals, robot_name = stub_signals(doc), "r1"
        robot = robot or DEFAULT_MODELS[doc.vendor]
        stem = os.path.splitext(os.path.basename(output))[0]
        use = f"{stem}_cell.rmot"
        write_text(os.path.join(out_dir, use), cell_stub(doc, signals, robot))
    for d in doc.diagnostics + rename_warnings(doc, span_of):
        click.echo(render(d), err=True)
    write_text(output, program_text(doc, signals, robot_name, use))
    motion_io = motion_io_counts(doc)
    for c in doc.counts:
        total = c.imported + c.native
        share = 100.0 * c.imported / total if total else 100.0
        moved, kept = motion_io.get(c.path, (0, 0))
        io_share = 100.0 * moved / (moved + kept) if moved + kept else 100.0
        click.echo(f"{c.path}: {c.imported} imported, {c.native} kept native ({share:.1f} % imported); "
                   f"motion and I/O: {moved} imported, {kept} kept native ({io_share:.1f} %)")
    click.echo(f"wrote {output}")
    sys.exit(EXIT_OK)
