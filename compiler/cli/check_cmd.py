"""`rmot check PROGRAM...`: load, plan and verify programs; report for people and for CI.

Exit codes: 0 clean (warnings allowed), 1 error findings from planning or verification,
2 input or usage errors (a front-end error, a missing file, a bad option).
Output is deterministic: programs are reported in the order given, whatever `--jobs` is.
"""

from __future__ import annotations

import os
import re
from typing import TYPE_CHECKING, Any

import click

from rmot.lang.atomic import write_atomic, write_text
from rmot.compiler.cli import EXIT_FINDINGS, EXIT_INPUT, EXIT_OK
from rmot.lang.record import record
from rmot.lang.diagnostics import Diagnostic, Severity
from rmot.compiler.cli.oserrors import output_is_input
from rmot.compiler.cli.shard import parse_shard, select_shard

if TYPE_CHECKING:  # the heavy stages load only when a check runs
    from rmot.lang.plan_types import Plan
    from rmot.sim.report import Report

__all__ = ["CheckOutcome", "check", "check_one", "parse_length"]

FORMATS = ("text", "json", "junit", "sarif")
_LENGTH = re.compile(r"^\s*([0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?)\s*(mm|cm|m)\s*$")
_UNIT = {"mm": 1e-3, "cm": 1e-2, "m": 1.0}


@record
class CheckOutcome:
    report: Report
    input_error: bool
    dynamics: str = ""  # --dynamics: per-joint torque lines (rmot.compiler.design.dynamics_text)


def parse_length(text: str) -> float:
    """'10mm' / '1.5 cm' / '0.01m' -> metres; raises ValueError otherwise."""
    match = _LENGTH.match(text)
    if not match:
        raise ValueError(f"must be a length with a unit, e.g. 10mm (got '{text}')")
    value = float(match.group(1)) * _UNIT[match.group(2)]
    if not value <= 10.0:  # also inf (`1e999mm`): a clearance beyond 10 m says nothing about a cell
        raise ValueError(f"must be a length of at most 10 m (got '{text}')")
    return value


def check_one(path: str, cell: str | None = None, project_root: str | None = None,
              clearance: float | None = None, images: str | None = None, use_cache: bool = True,
              dynamics: bool = False) -> CheckOutcome:
    """One program through front end -> planner -> verification (runs in a worker process)."""
    from rmot.compiler.cli import stages  # late: loads coal only when this runs
    from rmot.sim.report import Report  # late: loads numpy only when this runs

    # the front end reports a missing file (E501) and a file without a program (E119); a stage
    # failing unexpectedly is E550 in this program's report (compiler/cli/stages.py)
    try:
        front = stages.load(path, cell=cell, project_root=project_root, use_cache=use_cache)
    except stages.StageError as exc:
        return CheckOutcome(Report(path, {}, (exc.diagnostic,)), True)
    front_diags = tuple(front.diagnostics)
    if any(d.is_error for d in front_diags) or front.program is None:
        return CheckOutcome(Report(path, {}, front_diags), True)
    try:
        plan = stages.plan(front.program, use_cache=use_cache)
        report = stages.verify(plan, clearance=clearance)
    except stages.StageError as exc:
        return CheckOutcome(Report(path, {}, front_diags + (exc.diagnostic,)), True)
    report = Report(path, report.cycle_times, front_diags + report.diagnostics, report.tasks)
    if images:
        report = _render_images(plan, report, images)
    if dynamics:
        from rmot.compiler.design.dynamics_text import dynamics_json, dynamics_text  # late: loads coal only when this runs
        from rmot.compiler.design.metrics import program_metrics  # late: loads coal only when this runs

        metrics = program_metrics(plan)
        blocks = dynamics_json(metrics)  # the JSON report's per-task `dynamics` (schema: sim/report.py)
        tasks = None if report.tasks is None else tuple(
            {**t, "dynamics": blocks[t["task"]]} if t["task"] in blocks else t for t in report.tasks)
        report = Report(path, report.cycle_times, report.diagnostics, tasks)
        return CheckOutcome(report, False, dynamics_text(plan, metrics))
    return CheckOutcome(report, False)


def _render_images(plan: Plan, report: Report, directory: str) -> Report:
    """One PNG per error event (findings.events) with a time; written atomically (temp file + rename)."""
    from rmot.sim import codes  # late: tests replace it (monkeypatch): read at call time
    from rmot.sim.report import Report  # late: loads numpy only when this runs

    try:
        from rmot.sim.render import render_finding  # late: optional, tried where used
        from rmot.sim.render.findings import events  # late: optional, tried where used
    except ImportError as exc:
        note = Diagnostic(codes.RENDER_UNAVAILABLE, Severity.WARNING,
                          f"images were not rendered: the renderer is not available ({exc})", None)
        return Report(report.program_file, report.cycle_times, report.diagnostics + (note,), report.tasks)
    try:
        os.makedirs(directory, exist_ok=True)
    except OSError as exc:  # a folder that cannot be made is a finding about the option, not a traceback
        from rmot.lang import check_codes as check_codes  # late: optional, tried where used

        why = Diagnostic(check_codes.OUTPUT_FAILED, Severity.ERROR,
                         f"images folder '{directory}' must be a folder that can be made (got {exc.strerror or exc})", None)
        return Report(report.program_file, report.cycle_times, report.diagnostics + (why,), report.tasks)
    stem = os.path.splitext(os.path.basename(report.program_file))[0]
    extra = []
    for k, d in enumerate(events(report.errors), start=1):  # one picture per event, not per piece of it
        if d.time_s is None:
            continue
        final = os.path.join(directory, f"{stem}-{k:02d}-{d.code.id}.png")
        try:
            write_atomic(final, lambda tmp, d=d: render_finding(plan, d, tmp))  # type: ignore[misc]
        except OSError as exc:
            extra.append(Diagnostic(codes.RENDER_UNAVAILABLE, Severity.WARNING,
                                    f"image for {d.code.id} was not rendered: '{directory}' is not writable ({exc.strerror or exc})", d.span))
        except Exception as exc:  # a failed picture must not hide the finding itself
            extra.append(Diagnostic(codes.RENDER_UNAVAILABLE, Severity.WARNING,
                                    f"image for {d.code.id} at t={d.time_s:.3f} s was not rendered ({exc})", d.span))
    return Report(report.program_file, report.cycle_times, report.diagnostics + tuple(extra), report.tasks)


def _format(fmt: str, reports: list[Report]) -> str:
    from rmot.sim import report as fmt_mod  # late: loads numpy only when this runs

    return {"text": fmt_mod.format_text, "json": fmt_mod.format_json,
            "junit": fmt_mod.format_junit, "sarif": fmt_mod.format_sarif}[fmt](reports)


@click.command("check")
@click.argument("programs", nargs=-1, required=True, type=click.Path(dir_okay=False))
@click.option("--cell", type=click.Path(dir_okay=False), default=None, help="Cell file (overrides `use cell`).")
@click.option("--format", "fmt", type=click.Choice(FORMATS), default="text", show_default=True, help="Report format.")
@click.option("-o", "--output", type=click.Path(dir_okay=False), default=None, help="Write the report to FILE.")
@click.option("--clearance", default=None, metavar="LENGTH", help="Also warn about approaches closer than this, e.g. 10mm.")
@click.option("--jobs", type=click.IntRange(min=1), default=1, show_default=True, help="Programs checked in parallel.")
@click.option("--images", type=click.Path(file_okay=False), default=None, help="Render a PNG per error finding into DIR.")
@click.option("--project-root", type=click.Path(file_okay=False), default=None, help="Paths may not leave this directory.")
@click.option("--shard", default=None, metavar="K/N",
              help="Check only shard K of N: a deterministic, size-balanced share of PROGRAMs (CI matrices).")
@click.option("--no-cache", is_flag=True, help="Plan from scratch; neither read nor write the plan cache.")
@click.option("--dynamics", is_flag=True, help="Also report per-joint peak/RMS torque and peak power "
              "(text lines; a per-task `dynamics` block in --format json).")
def check(programs: tuple[str, ...], cell: str | None, fmt: str, output: str | None, clearance: str | None,
          jobs: int, images: str | None, project_root: str | None, shard: str | None, no_cache: bool,
          dynamics: bool = False) -> None:
    """Parse, plan and verify PROGRAMs; report collisions, limit excesses and cycle times."""
    if output:

        clash = output_is_input("report file", output, (*programs, cell))
        if clash:
            click.echo(clash, err=True)
            click.get_current_context().exit(EXIT_INPUT)
    if shard is not None:

        try:
            programs = tuple(select_shard(programs, parse_shard(shard)))
        except ValueError as exc:
            raise click.BadParameter(str(exc), param_hint="--shard") from None
    clearance_m = None
    if clearance is not None:
        try:
            clearance_m = parse_length(clearance)
        except ValueError as exc:
            raise click.BadParameter(str(exc), param_hint="--clearance") from None
    # options other than the first five are passed only when asked for (tests stand in a
    # five-argument check_one)
    options = {**({"use_cache": False} if no_cache else {}), **({"dynamics": True} if dynamics else {})}
    args = [((p, cell, project_root, clearance_m, images), options) for p in programs]
    if jobs > 1 and len(programs) > 1:
        # imported here: multiprocessing costs ~20 ms of every check, and only --jobs uses it
        from concurrent.futures import ProcessPoolExecutor  # late: loads subprocess only when this runs

        with ProcessPoolExecutor(max_workers=min(jobs, len(programs))) as pool:
            outcomes = list(pool.map(_check_args, args))
    else:
        outcomes = [_check_args(a) for a in args]
    reports = [o.report for o in outcomes]
    text = _format(fmt, reports)
    if dynamics and fmt == "text":
        text += "".join(o.dynamics for o in outcomes)
    if output:
        try:
            write_text(output, text)
        except OSError as exc:
            from rmot.compiler.cli.oserrors import output_failed  # late: optional, tried where used

            click.echo(output_failed("report file", output, exc), err=True)
            click.get_current_context().exit(EXIT_INPUT)
    else:
        click.echo(text, nl=False)
    ctx = click.get_current_context()
    if any(o.input_error for o in outcomes):
        ctx.exit(EXIT_INPUT)
    ctx.exit(EXIT_FINDINGS if any(r.has_errors for r in reports) else EXIT_OK)


def _check_args(call: tuple[tuple[Any, ...], dict[str, Any]]) -> CheckOutcome:
    args, options = call
    return check_one(*args, **options)
