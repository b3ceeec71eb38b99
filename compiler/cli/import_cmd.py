"""`rmot import FILE... -o OUT.rmot [--robot NAME] [--cell CELL]`: vendor programs to .rmot.

The readers (backends/readers) turn RAPID files into a neutral document; this command picks
the cell (the one given, or a stub it writes beside OUT with the tools, work objects and I/O
names the files declare), prints the program, and says per file how many instructions were
imported and how many kept native. A file that is not its vendor's language is a located
error (exit 2); a line kept native is a located warning.
"""

from __future__ import annotations

import os
import sys

import click

from rmot.compiler.cli import EXIT_INPUT, EXIT_OK
from rmot.compiler.cli.import_read import cell_signals, print_summary, read_on_robot, refuse_output_input, write_output
from rmot.lang.diagnostics import Diagnostic, Severity, render

__all__ = ["import_", "DEFAULT_MODELS"]

# the stub cell's robot when --robot is not given: a library arm of the vendor's maker
DEFAULT_MODELS = {"rapid": "abb_irb1600", "krl": "kuka_kr6_r900", "urscript": "ur5e",
                  "fanuc": "fanuc_m20ia", "inform": "yaskawa_gp8", "val3": "staubli_tx2_60"}


@click.command(name="import", help="Read RAPID, KRL, URScript, Fanuc TP (with a backup's NUMREG.VA, POSREG.VA, SYSFRAME.VA), "
               "INFORM or VAL3 programs back into .rmot. "
               "Several robots' programs: one --task ROBOT=FILE per file (with --cell), read into one program "
               "with a task per robot, RAPID WaitSyncTask and the other vendors' sync handshakes as `sync`.")
@click.argument("files", nargs=-1, required=False, type=click.Path(dir_okay=False, exists=True))
@click.option("-o", "--output", "output", required=True, type=click.Path(dir_okay=False), help="The .rmot file to write.")
@click.option("--robot", default=None, help="With --cell: the cell's robot; without: the library arm of the stub cell.")
@click.option("--cell", "cell", type=click.Path(dir_okay=False, exists=True), default=None,
              help="Run the imported program in this cell (else a stub cell is written beside OUT).")
@click.option("--task", "tasks", multiple=True, metavar="ROBOT[:RAPIDTASK]=FILE",
              help="A file of ROBOT's program (repeat: one task per robot, several files of one task in order; "
                   "the k-th robot is RAPID task T_ROBk unless :RAPIDTASK names it). Needs --cell, no FILES.")
@click.option("--pulses-per-degree", "pulses", default=None, metavar="S,L,U,R,B,T",
              help="INFORM: the arm's encoder pulses per degree, axis by axis (the controller's parameters): "
                   "pulse positions are read as joint targets, else their moves stay native.")
def import_(files: tuple[str, ...], output: str, robot: str | None, cell: str | None, tasks: tuple[str, ...],
            pulses: str | None) -> None:
    from rmot.backends.readers import ImportError_, span_of  # late: loads numpy only when this runs
    from rmot.backends.readers.position_records import with_position_records  # late: loads numpy only when this runs
    from rmot.backends.readers.writer import (  # late: loads numpy only when this runs
        SignalMap, cell_stub, program_text, rename_warnings, stub_signals, stub_warnings,
    )

    if tasks and pulses is not None:  # one arm's scales: which of the tasks' arms is theirs is not said
        _pulse_scales(pulses, "--pulses-per-degree is one arm's scales and cannot be given with --task")
    if tasks:
        from rmot.compiler.cli.import_tasks import import_tasks  # late: loads numpy only when this runs

        import_tasks(files, output, robot, cell, tasks)
    if not files:
        click.echo("rmot: import needs FILE... (one robot's program) or --task ROBOT=FILE (several robots)", err=True)
        sys.exit(EXIT_INPUT)
    refuse_output_input(output, files)
    scales = _pulse_scales(pulses) if pulses is not None else None
    found = cell_signals(cell, robot) if cell is not None else None
    if isinstance(found, str):
        click.echo(found, err=True)
        sys.exit(EXIT_INPUT)
    try:
        doc = with_position_records(read_on_robot(list(files), cell, found, robot, scales))  # the data natives name
    except ImportError_ as exc:
        click.echo(render(exc.diagnostic), err=True)
        sys.exit(EXIT_INPUT)
    out_dir = os.path.dirname(os.path.abspath(output))
    stubbed: tuple[Diagnostic, ...] = ()
    if cell is not None and found is not None:
        signals, robot_name = found[0], found[1]
        assert isinstance(signals, SignalMap)
        use = os.path.relpath(os.path.abspath(cell), out_dir)
    else:
        signals, robot_name = stub_signals(doc), "r1"
        robot = robot or DEFAULT_MODELS[doc.vendor]
        stem = os.path.splitext(os.path.basename(output))[0]
        use = f"{stem}_cell.rmot"
        write_output("cell stub", os.path.join(out_dir, use), cell_stub(doc, signals, robot), files)
        stubbed = stub_warnings(doc, span_of)
    for d in doc.diagnostics + rename_warnings(doc, span_of) + stubbed:
        click.echo(render(d), err=True)
    write_output("program", output, program_text(doc, signals, robot_name, use), files)
    print_summary(doc)
    click.echo(f"wrote {output}")
    sys.exit(EXIT_OK)


def _pulse_scales(text: str, refused: str = "") -> tuple[float, ...]:
    """--pulses-per-degree read; E525 and exit 2 where it is not valid or `refused` says why not."""
    from rmot.backends.readers import codes  # late: loads numpy only when this runs
    from rmot.backends.readers.inform import pulse_scales  # late: loads numpy only when this runs

    scales = refused or pulse_scales(text)
    if isinstance(scales, str):
        click.echo(render(Diagnostic(codes.PULSE_SCALES_INVALID, Severity.ERROR, scales, None)), err=True)
        sys.exit(EXIT_INPUT)
    return scales
