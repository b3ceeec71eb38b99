"""`rmot compare PROGRAM --robot A --robot B ...`: the same program on several arms.

Without --robot: the cell's own robot (its metrics and dynamics alone). Each arm stands in the
place of the program's robot (same base pose; `--place` with
`--region` places each one first, as `rmot place` does) and goes through the planner and
verifier of `rmot check`. Per arm: verifies or not (with the first findings), cycle time (null
for an arm that does not verify), worst joint-limit margin, worst manipulability, peak torque
against the rated torque.

Exit codes: 0 at least one arm verifies; 1 none does; 2 bad input (E80x diagnostics of
compiler/design/codes.py). An arm that does not load is that arm's finding (E320), not an input error.
"""

from __future__ import annotations

import json
import math
import sys
from typing import Any

import click

from rmot.compiler.cli import EXIT_FINDINGS, EXIT_INPUT, EXIT_OK
from rmot.compiler.cli.design_errors import fail, fail_code
from rmot.lang.diagnostics import render_all, Diagnostic, Severity, render
from rmot.compiler.design import codes
from dataclasses import replace

__all__ = ["compare", "format_json", "format_text"]


def _margin(m: Any) -> dict[str, Any] | None:
    if m is None or not math.isfinite(m.margin):
        return None
    if m.margin_prismatic:
        return {"joint": m.margin_joint, "value": round(m.margin * 1000, 3), "unit": "mm"}
    return {"joint": m.margin_joint, "value": round(math.degrees(m.margin), 3), "unit": "deg"}


def _finding(d: Any) -> dict[str, Any]:
    span = d.span
    return {"code": d.code.id, "message": d.message, "file": span.path if span else None,
            "line": span.start.line if span else None, "col": span.start.col if span else None}


def arm_dict(r: Any) -> dict[str, Any]:
    m = r.metrics
    dyn = None
    if m is not None and m.dynamics is not None:
        dyn = [{"joint": j.joint, "peak_torque": round(j.peak_torque, 4), "rms_torque": round(j.rms_torque, 4),
                "peak_power_w": round(j.peak_power, 4), "rated_torque": j.rated_torque,
                "utilisation": None if j.utilisation is None else round(j.utilisation, 4)} for j in m.dynamics]
    return {
        "robot": r.key, "model": r.model, "verified": r.verified,
        "first_findings": [_finding(d) for d in r.first_findings()],
        # only a verified arm has a cycle time: one that cannot reach or collides has none to rank by
        "cycle_time_s": None if not r.verified or r.report.cycle_time is None else round(r.report.cycle_time, 6),
        "joint_margin": _margin(m),
        "manipulability": None if m is None or not math.isfinite(m.manipulability) else round(m.manipulability, 6),
        "dynamics": dyn,
        "note": "; ".join(filter(None, (m.dynamics_note if m is not None else "", r.note))),
    }


def format_json(path: str, slot: str, results: list[Any]) -> str:
    doc = {"version": 1, "program": path, "robot": slot, "arms": [arm_dict(r) for r in results]}
    return json.dumps(doc, indent=2, sort_keys=True) + "\n"


def format_text(path: str, slot: str, results: list[Any]) -> str:
    rows = [("arm", "model", "verifies", "cycle", "worst joint margin", "worst manip.", "peak torque / rated")]
    for r in results:
        d = arm_dict(r)
        margin = d["joint_margin"]
        dyn = d["dynamics"]
        if dyn is None:
            torque = "no inertia data"
        else:
            used = [j for j in dyn if j["utilisation"] is not None]
            worst = max(used, key=lambda j: j["utilisation"]) if used else max(dyn, key=lambda j: j["peak_torque"])
            torque = (f"J{worst['joint']} {worst['utilisation'] * 100:.0f}%" if used
                      else f"J{worst['joint']} {worst['peak_torque']:.1f} N·m (rating unknown)")
        rows.append((r.key, r.model, "yes" if r.verified else "NO",
                     "-" if d["cycle_time_s"] is None else f"{d['cycle_time_s']:.3f} s",
                     "-" if margin is None else f"J{margin['joint']} {margin['value']:.1f} {margin['unit']}",
                     "-" if d["manipulability"] is None else f"{d['manipulability']:.4f}", torque))
    widths = [max(len(row[i]) for row in rows) for i in range(len(rows[0]))]
    lines = [f"{path}: robot '{slot}' replaced by each arm"]
    lines += ["  ".join(cell.ljust(w) for cell, w in zip(row, widths)).rstrip() for row in rows]
    for r in results:
        d = arm_dict(r)
        if d["dynamics"]:
            per = ", ".join(f"J{j['joint']} {j['peak_torque']:.1f}/{j['rms_torque']:.1f} N·m {j['peak_power_w']:.0f} W"
                            + (f" ({j['utilisation'] * 100:.0f}%)" if j["utilisation"] is not None else "")
                            for j in d["dynamics"])
            lines.append(f"{r.key} torque peak/RMS, peak power: {per}")
        if d["note"]:
            lines.append(f"{r.key}: {d['note']}")
        for f in d["first_findings"]:
            where = f"{f['file']}:{f['line']}:{f['col']}: " if f["file"] else ""
            lines.append(f"{r.key}: {where}error[{f['code']}]: {f['message']}")
    lines.append("worst manip.: Yoshikawa's measure of the Jacobian with its linear rows divided by the reach "
                 "(0 = singular); torque: peak over the program against the model's rated torque")
    return "\n".join(lines) + "\n"


@click.command(name="compare")
@click.argument("program", type=click.Path(dir_okay=False))
@click.option("--robot", "robots", multiple=True, help="An arm to try: a library robot or a URDF file (repeat) [the cell's own].")
@click.option("--cell", type=click.Path(dir_okay=False), default=None, help="Cell file (overrides `use cell`).")
@click.option("--as", "slot", default=None, help="The cell robot the arms replace [the program's first task's robot].")
@click.option("--format", "fmt", type=click.Choice(("text", "json")), default="text", show_default=True)
@click.option("--place", "do_place", is_flag=True, help="Place each arm in --region first (as `rmot place`).")
@click.option("--region", default=None, help="With --place: e.g. \"x=-0.5m..0.5m, y=-0.5m..0.5m, rz=-180deg..180deg\".")
@click.option("--project-root", type=click.Path(file_okay=False), default=None, help="Directory that file paths may not leave.")
def compare(program: str, robots: tuple[str, ...], cell: str | None, slot: str | None, fmt: str, do_place: bool,
            region: str | None, project_root: str | None) -> None:
    """Run one program on several arms and compare them."""
    from rmot.compiler.frontend import load_program  # late: tests replace it (monkeypatch): read at call time
    from rmot.compiler.design.compare import run_arm, slot_of  # late: loads coal only when this runs
    from rmot.compiler.design.study import OptionError, parse_region  # late: loads PIL only when this runs

    loaded = load_program(program, cell=cell, project_root=project_root, require_program=True)
    if loaded.has_errors or loaded.program is None:
        click.echo(render_all(loaded.diagnostics), err=True)
        sys.exit(EXIT_INPUT)
    try:
        name = slot_of(loaded.program, slot)
    except KeyError:
        names = ", ".join(r.name for r in loaded.program.cell.robots)
        fail_code(codes.ROBOT_UNKNOWN, f"--as must name a robot of cell '{loaded.program.cell.name}' ({names}) (got '{slot}')")
    if do_place and region is None:
        fail_code(codes.OPTION_MISSING, "--place needs --region")

    if region is not None:
        try:
            parse_region(region)  # checked before any arm is planned
        except OptionError as exc:
            fail(exc.diagnostic())
        if not do_place:

            click.echo(render(Diagnostic(codes.OPTION_IGNORED, Severity.WARNING,
                                         "--region is ignored without --place (the arms stand at the cell's pose)", None)), err=True)
    _known_arms(robots)
    results = []
    for key in robots or (None,):
        prog = loaded.program
        note = ""
        if do_place:
            prog, note = _placed(prog, key or prog.cell.robot(name).source.load_key, name, region or "", program)
        results.append(run_arm(prog, key, name, program))
        if note:

            results[-1] = replace(results[-1], note=note)
    text = (format_json if fmt == "json" else format_text)(program, name, results)
    click.echo(text, nl=False)
    sys.exit(EXIT_OK if any(r.verified for r in results) else EXIT_FINDINGS)


def _known_arms(keys: tuple[str, ...]) -> None:
    """Before any arm is planned: a --robot that names no library robot and no URDF file ends the
    command with E804 (as `rmot reach` and `rmot place` do); a file that does not load stays a
    per-arm finding (E320) in the table."""
    from rmot.sim.robots import RobotError, load_robot  # late: loads coal only when this runs
    from rmot.sim.robots.codes import UNKNOWN_ROBOT  # late: loads coal only when this runs

    for key in keys:
        try:
            load_robot(key)
        except RobotError as exc:
            if exc.code is None or exc.code == UNKNOWN_ROBOT:
                fail_code(codes.ROBOT_UNKNOWN,
                          f"--robot must name a library robot or a URDF file ({exc.message})")


def _placed(program: Any, key: str, slot: str, region: str, path: str) -> tuple[Any, str]:
    """The program with arm `key` placed by `rmot place`'s search (unchanged if none verifies)."""
    from rmot.sim.robots import RobotError, load_robot  # late: loads coal only when this runs
    from rmot.compiler.design.compare import stand_in  # late: loads coal only when this runs
    from rmot.compiler.design.place import place, rebase  # late: loads coal only when this runs
    from rmot.compiler.design.study import parse_region  # late: loads PIL only when this runs

    bounds = parse_region(region)  # parsed once already in compare()
    try:
        robot = load_robot(key)
    except RobotError:
        return program, ""
    from rmot.compiler.design.place_track import TrackMover, track_of  # late: loads coal only when this runs

    prog = stand_in(program, slot, key, robot)
    track = track_of(prog.cell, slot)  # a robot on a track: its track is placed, the arm rides it
    mover = None if track is None else TrackMover([prog], slot, robot)
    result = place([prog], slot, bounds, robot=robot, mover=mover)
    if result.best is None:
        return prog, "no verified placement in the region: compared at the cell's pose"
    placed = rebase(prog, slot, result.best.base) if mover is None else mover.rebase(prog, result.best.base)
    what = "placed" if track is None else f"track '{track.name}' placed"
    return placed, f"{what} at {result.best.describe()}"
