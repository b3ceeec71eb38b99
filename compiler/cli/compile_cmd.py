"""`rmot compile PROGRAM --target VENDOR [--target ...] -o OUTDIR`: verify, then emit vendor files.

Pipeline: front end (rmot.compiler.frontend.load_program) -> planner (rmot.compiler.plan.
plan_program) -> verification (rmot.sim.verify) -> one backend per --target
(rmot.backends.BACKENDS). Files go to OUTDIR/<vendor>/<file>.

Exit codes:
  0  files written (warnings allowed);
  1  verification or a backend reported errors: no file is written, unless --allow-findings
     lets verification errors through (every file then starts with a warning header;
     backend errors always block: their output would not be faithful);
  2  input or usage errors (missing file, front-end errors, unknown target).
Writing is all-or-nothing: every text is built in memory, written to a temporary file in its
final directory, and only when all of them are written are they renamed into place
(os.replace), so a failed compile leaves the previous output untouched.
"""

from __future__ import annotations

import os
import tempfile
from dataclasses import dataclass

import click

from rmot.compiler.cli import EXIT_FINDINGS, EXIT_INPUT, EXIT_OK

__all__ = ["CompileOutcome", "compile_", "compile_program", "write_all"]

TARGETS = ("rapid", "krl", "fanuc", "urscript", "inform", "val3", "csv", "json")


@dataclass(frozen=True)
class CompileOutcome:
    """What a compile produced: files (relative path -> text), diagnostics, and the exit code."""

    files: dict[str, str]
    diagnostics: tuple
    exit_code: int


def compile_program(path: str, targets: tuple[str, ...], *, cell: str | None = None,
                    project_root: str | None = None, allow_findings: bool = False,
                    source_map: bool = True, write_frames: bool = False, use_cache: bool = True) -> CompileOutcome:
    """Run the pipeline in memory; nothing is written here."""
    from rmot.backends import BACKENDS

    from rmot.compiler.frontend import load_program
    from rmot.compiler.plan_cache import cached_plan
    from rmot.sim import verify

    # the front end reports a missing file (E501) and a file without a program (E119)
    front = load_program(path, cell=cell, project_root=project_root, require_program=True)
    diagnostics = tuple(front.diagnostics)
    if front.program is None or any(d.is_error for d in diagnostics):
        return CompileOutcome({}, diagnostics, EXIT_INPUT)
    plan = cached_plan(front.program, use_cache=use_cache)
    report = verify(plan)
    diagnostics += tuple(report.diagnostics)
    findings = any(d.is_error for d in report.diagnostics)
    if findings and not allow_findings:
        return CompileOutcome({}, diagnostics, EXIT_FINDINGS)
    files: dict[str, str] = {}
    backend_errors = False
    for target in dict.fromkeys(targets):  # each target once, in the order given
        result = BACKENDS[target](allow_findings_header=findings, write_frames=write_frames).emit(
            plan, source_map=source_map)
        diagnostics += result.diagnostics
        backend_errors |= result.has_errors
        files.update({f"{target}/{name}": text for name, text in result.files.items()})
    if backend_errors:
        return CompileOutcome({}, diagnostics, EXIT_FINDINGS)
    return CompileOutcome(files, diagnostics, EXIT_OK)


def write_all(outdir: str, files: dict[str, str]) -> list[str]:
    """Write every file atomically and all-or-nothing; returns the final paths in order."""
    staged: list[tuple[str, str]] = []
    try:
        for rel, text in files.items():
            final = os.path.join(outdir, *rel.split("/"))
            os.makedirs(os.path.dirname(final), exist_ok=True)
            fd, tmp = tempfile.mkstemp(prefix=".rmot-", dir=os.path.dirname(final))
            staged.append((tmp, final))
            with os.fdopen(fd, "w", encoding="utf-8", newline="\n") as f:
                f.write(text)
        for tmp, final in staged:
            os.replace(tmp, final)
    finally:
        for tmp, _ in staged:
            if os.path.exists(tmp):
                os.unlink(tmp)
    return [final for _, final in staged]


@click.command("compile")
@click.argument("program", type=click.Path(dir_okay=False))
@click.option("--cell", type=click.Path(dir_okay=False), default=None, help="Cell file (overrides `use cell`).")
@click.option("--target", "targets", multiple=True, required=True, type=click.Choice(TARGETS),
              help="Vendor to emit (repeatable).")
@click.option("-o", "--output", "outdir", required=True, type=click.Path(file_okay=False),
              help="Output directory; files go to OUTDIR/<vendor>/.")
@click.option("--allow-findings", is_flag=True, help="Write files even when verification reports errors.")
@click.option("--no-source-map", is_flag=True, help="Leave out the `file:line` comments.")
@click.option("--project-root", type=click.Path(file_okay=False), default=None, help="Paths may not leave this directory.")
@click.option("--write-frames", is_flag=True,
              help="Also write numbered tools and frames into the controller's stored data (Fanuc, KRL).")
@click.option("--no-cache", is_flag=True, help="Plan from scratch; neither read nor write the plan cache.")
def compile_(program: str, cell: str | None, targets: tuple[str, ...], outdir: str, allow_findings: bool,
             no_source_map: bool, project_root: str | None, write_frames: bool, no_cache: bool) -> None:
    """Verify PROGRAM, then write it for each --target controller."""
    from rmot.lang.diagnostics import render

    outcome = compile_program(program, targets, cell=cell, project_root=project_root,
                              allow_findings=allow_findings, source_map=not no_source_map,
                              write_frames=write_frames, use_cache=not no_cache)
    for d in outcome.diagnostics:
        click.echo(render(d), err=True)
    ctx = click.get_current_context()
    if outcome.exit_code != EXIT_OK:
        click.echo(f"rmot: no files written ({_count(outcome.diagnostics)})", err=True)
        ctx.exit(outcome.exit_code)
    try:
        written = write_all(outdir, outcome.files)
    except OSError as exc:
        click.echo(f"rmot: error: output directory must be writable ({exc})", err=True)
        ctx.exit(EXIT_INPUT)
    for path in written:
        click.echo(f"wrote {path}")
    ctx.exit(EXIT_OK)


def _count(diagnostics: tuple) -> str:
    errors = sum(1 for d in diagnostics if d.is_error)
    return f"{errors} error{'s' if errors != 1 else ''}"
