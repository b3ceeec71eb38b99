"""`rmot place PROGRAM... --robot NAME --region "x=a..b, y=c..d[, z=..][, rz=..]" -o CELL`.

Finds a base pose for the cell's robot NAME in the region with which every program verifies
(reach, branches, joint limits, collisions, payload), the best by --objective; writes a copy
of the cell with that `at` pose, prints the pose, the objective and the runners-up. When no
pose works it says what fails where. See rmot.compiler.design.place for the search. A robot on a
track has the track placed instead (its `at` rewritten; compiler/design/place_track.py).

Exit codes: 0 a pose was found and written; 1 no pose in the region verifies; 2 bad input
(E80x diagnostics of compiler/design/codes.py; an unwritable -o file: E520).
"""

from __future__ import annotations

import sys
from typing import Any

import click

from rmot.compiler.cli import EXIT_FINDINGS, EXIT_INPUT
import math
from rmot.compiler.cli.design_errors import fail, fail_code, fail_output, require_output_dir
from rmot.lang.diagnostics import render_all
from rmot.compiler.design import codes
from rmot.compiler.cli.oserrors import output_is_input

__all__ = ["place"]


def _line(c, objective: str) -> str:  # type: ignore[no-untyped-def]

    margin = f"{math.degrees(c.margin):.1f} deg" if math.isfinite(c.margin) else "-"
    return f"{c.describe()}: cycle {c.cycle_time:.3f} s, worst joint margin {margin}, worst manipulability {c.manipulability:.4f}"


def _placed_declaration(loaded: list[Any], name: str) -> tuple[Any, Any]:
    """(the declaration whose `at` is rewritten, the place.Mover or None for the robot's own base):
    a robot on a track has its track placed, the arm riding on the carriage."""
    from rmot.compiler.design.place_track import TrackMover, track_of  # late: loads coal only when this runs
    from rmot.sim.robots import load_robot  # late: loads coal only when this runs

    instance = loaded[0].cell.robot(name)
    track = track_of(loaded[0].cell, name)
    if track is not None:
        click.echo(f"robot '{name}' rides on track '{track.name}': placing the track (its `at`), the arm on its carriage")
    span = instance.span if track is None else track.span
    if span is None:  # lower_cell gives every robot and mechanism its declaration's span
        raise RuntimeError(f"internal: '{name}' has no source span to rewrite")
    return span, None if track is None else TrackMover(loaded, name, load_robot(instance.source.load_key))


@click.command(name="place")
@click.argument("programs", nargs=-1, required=True, type=click.Path(dir_okay=False))
@click.option("--robot", "slot", default=None, help="The cell's robot to place [the first program's robot].")
@click.option("--region", required=True, help='e.g. "x=0m..1m, y=-500mm..500mm, rz=-180deg..180deg" (world).')
@click.option("-o", "--output", required=True, type=click.Path(dir_okay=False), help="The cell copy to write.")
@click.option("--objective", type=click.Choice(("cycle", "margin")), default="cycle", show_default=True)
@click.option("--cell", type=click.Path(dir_okay=False), default=None, help="Cell file (overrides `use cell`).")
@click.option("--samples", type=click.IntRange(8, 100_000), default=256, show_default=True, help="Poses screened by IK.")
@click.option("--project-root", type=click.Path(file_okay=False), default=None, help="Directory that file paths may not leave.")
def place(programs: tuple[str, ...], slot: str | None, region: str, output: str, objective: str, cell: str | None,
          samples: int, project_root: str | None) -> None:
    """Find the best base pose for a robot in a region; write the cell with it."""
    from rmot.compiler.frontend import load_program  # late: tests replace it (monkeypatch): read at call time
    from rmot.compiler.design.cell_edit import with_robot_at  # late: loads numpy only when this runs
    from rmot.compiler.design.place import place as search  # late: loads coal only when this runs
    from rmot.compiler.design.study import OptionError, parse_region  # late: loads PIL only when this runs
    from rmot.sim.render.files import write_text  # late: loads PIL only when this runs

    try:
        bounds = parse_region(region)
    except OptionError as exc:
        fail(exc.diagnostic())
    require_output_dir("cell file", output)
    loaded = []
    for path in programs:
        result = load_program(path, cell=cell, project_root=project_root, require_program=True)
        if result.has_errors or result.program is None:
            click.echo(render_all(result.diagnostics), err=True)
            sys.exit(EXIT_INPUT)
        loaded.append(result.program)

        clash = output_is_input("cell file", output, (path, cell, *result.sources))
        if clash:
            click.echo(clash, err=True)
            sys.exit(EXIT_INPUT)
    name = slot or loaded[0].tasks[0].robot
    spans = set()
    for p in loaded:
        try:
            spans.add(p.cell.robot(name).span)
        except KeyError:
            names = ", ".join(r.name for r in p.cell.robots)
            fail_code(codes.ROBOT_UNKNOWN, f"--robot must name a robot of cell '{p.cell.name}' ({names}) (got '{name}')")
    span, mover = _placed_declaration(loaded, name)
    found = search(loaded, name, bounds, objective=objective, screen_n=samples, mover=mover)
    click.echo(f"screened {found.screened} poses by IK ({found.screen_feasible} reach every target), "
               f"planned and verified {found.verified_count} in full, {found.passing} of them clean (only those are ranked)")
    if found.best is None:
        click.echo(f"no pose of robot '{name}' in the region verifies:")
        for line in found.failures:
            click.echo(f"  {line}")
        sys.exit(EXIT_FINDINGS)
    best = found.best
    click.echo(f"best ({objective}): {_line(best, objective)}")
    for k, c in enumerate(found.runners_up, 2):
        click.echo(f"  #{k}: {_line(c, objective)}")
    with open(span.path, encoding="utf-8") as f:
        text = f.read()
    try:
        write_text(output, with_robot_at(text, span.start.offset, span.end.offset, best.base))
    except OSError as exc:
        fail_output("cell file", output, exc)
    click.echo(f"wrote {output}")
