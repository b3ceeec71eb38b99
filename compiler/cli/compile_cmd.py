"""`rmot compile PROGRAM --target VENDOR [--target ...] -o OUTDIR`: verify, then emit vendor files.

Pipeline: front end (rmot.compiler.frontend.load_program) -> planner (rmot.compiler.plan.
plan_program) -> verification (rmot.sim.verify) -> one backend per --target
(rmot.backends.BACKENDS). Files go to OUTDIR/<vendor>/<file>.

Exit codes:
  0  files written (warnings allowed);
  1  verification reported errors: no file is written, unless --allow-findings lets them
     through (every file then starts with a warning header); or a backend refused the
     program: that vendor's directory is not written (its old output stays), the other
     vendors are written, and the refusal is reported;
  2  input or usage errors (missing file, front-end errors, unknown target, an output
     directory that cannot be written: E520).
Writing is per vendor and atomic (compiler/cli/output_tree.py): every text is built in
memory, written into a staging directory beside OUTDIR/<vendor>, and the staging directory
takes the vendor directory's place in one rename, so OUTDIR/<vendor> is always wholly the
old or wholly the new output, also when the run is killed (SIGKILL) midway; a failed compile
leaves the previous output untouched.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import click

from rmot.lang.vendors import targets as registered_targets
from rmot.compiler.cli import EXIT_FINDINGS, EXIT_INPUT, EXIT_OK
from rmot.lang.record import record
from rmot.lang.diagnostics import Diagnostic, Severity, render
from rmot.compiler.cli.output_tree import write_vendor_dirs

if TYPE_CHECKING:
    from rmot.lang import ir
    from rmot.lang.diagnostics import Diagnostic

__all__ = ["CompileOutcome", "compile_", "compile_program", "write_all"]


class _Targets(click.Choice):  # type: ignore[type-arg]
    """click.Choice over the target registry (lang/vendors.py) as it is when the
    option is read, so a backend registered after import is a valid --target."""

    def __init__(self) -> None:
        super().__init__(registered_targets())

    def convert(self, value: object, param: click.Parameter | None,
                ctx: click.Context | None) -> object:
        self.choices = registered_targets()
        return super().convert(value, param, ctx)


@record
class CompileOutcome:
    """What a compile produced: files (relative path -> text), diagnostics, and the exit code."""

    files: dict[str, str]
    diagnostics: tuple[Diagnostic, ...]
    exit_code: int
    refused: tuple[str, ...] = ()  # targets whose backend reported errors: not written


def compile_program(path: str, targets: tuple[str, ...], *, cell: str | None = None,
                    project_root: str | None = None, allow_findings: bool = False,
                    source_map: bool = True, write_frames: bool = False, use_cache: bool = True,
                    unroll: bool = False) -> CompileOutcome:
    """Run the pipeline in memory (compiler/cli/stages.py); nothing is written here."""
    from rmot.compiler.cli import stages  # late: loads coal only when this runs

    # the front end reports a missing file (E501) and a file without a program (E119)
    try:
        front = stages.load(path, cell=cell, project_root=project_root, use_cache=use_cache)
    except stages.StageError as exc:
        return CompileOutcome({}, (exc.diagnostic,), EXIT_INPUT)
    diagnostics = tuple(front.diagnostics)
    if front.program is None or any(d.is_error for d in diagnostics):
        return CompileOutcome({}, diagnostics, EXIT_INPUT)
    try:
        plan = stages.plan(front.program, use_cache=use_cache)
        report = stages.verify(plan, targets=targets)
    except stages.StageError as exc:
        return CompileOutcome({}, diagnostics + (exc.diagnostic,), EXIT_INPUT)
    diagnostics += tuple(report.diagnostics)
    findings = any(d.is_error for d in report.diagnostics)
    if findings and not allow_findings:
        return CompileOutcome({}, diagnostics, EXIT_FINDINGS)
    files: dict[str, str] = {}
    refused: list[str] = []
    for target in dict.fromkeys(targets):  # each target once, in the order given
        undeclared = controller_refusals(target, plan.program.cell)
        if undeclared:  # the vendor cannot vouch for these robots' joint values: nothing emitted
            diagnostics += undeclared
            refused.append(target)
            continue
        try:
            result = stages.emit(target, plan, source_map=source_map,
                                 allow_findings_header=findings, write_frames=write_frames, unroll=unroll)
        except stages.StageError as exc:  # a backend bug refuses that vendor only
            diagnostics += (exc.diagnostic,)
            refused.append(target)
            continue
        diagnostics += result.diagnostics
        if result.has_errors:  # this vendor refuses the program: its old output stays, the others are written
            refused.append(target)
            continue
        clash = _case_clash(result.files)
        if clash:
            from rmot.lang import check_codes as codes  # late: tests replace it (monkeypatch): read at call time

            msg = (f"{target}: output files must have names that differ also without regard to case (got "
                   f"{' and '.join(repr(n) for n in clash)}, one file on Windows and macOS); rename a task")
            diagnostics += (Diagnostic(codes.OUTPUT_NAME_CLASH, Severity.ERROR, msg, plan.program.span),)
            refused.append(target)
            continue
        files.update({f"{target}/{name}": text for name, text in result.files.items()})
    return CompileOutcome(files, diagnostics, EXIT_FINDINGS if refused else EXIT_OK, tuple(refused))


def controller_refusals(target: str, cell: ir.Cell) -> tuple[Diagnostic, ...]:
    """E480/E481 at each robot of the cell whose joint values a `target` controller cannot take
    as they are: a cell model or URDF arm that declares no controller, or declares another
    maker's (sim/robots/controller.py). Library arms carry their vendor's conventions
    (another brand's arm is W415, backends/base.py); data formats (csv, json) need none."""
    from rmot.backends import codes as backend_codes  # late: tests replace it (monkeypatch): read at call time
    from rmot.backends.controller_data import TARGET_BRANDS  # late: loads numpy only when this runs
    from rmot.lang import ir  # late: tests replace it (monkeypatch): read at call time

    brand = TARGET_BRANDS.get(target)
    own_models = [r for r in cell.robots if r.source.kind is not ir.RobotSourceKind.LIBRARY]
    if brand is None or not own_models:
        return ()
    # the robot package loads pinocchio: only for a cell that has its own arms
    from rmot.sim.robots import RobotError, load_robot  # late: loads coal only when this runs
    from rmot.sim.robots.controller import ANY, MAKERS  # late: loads coal only when this runs
    out = []
    for robot in own_models:
        try:
            declared = load_robot(robot.source.ref).controller
        except RobotError:  # reported by the front end
            continue
        how = ("a `controller` line in the model (e.g. `controller " + target_word(brand[0]) + "`, with "
               "pendant(sign=, zero=, coupled_to=) on joints that differ)"
               if robot.source.kind is ir.RobotSourceKind.MODEL
               else f'urdf(..., controller="{target_word(brand[0])}")')
        if declared is None:
            out.append(Diagnostic(backend_codes.CONTROLLER_UNDECLARED, Severity.ERROR,
                                  f"{target}: robot '{robot.name}' must declare its controller's conventions (joint "
                                  f"signs and zeros, couplings, base and flange frames) before a {brand[0]} program "
                                  f"can carry its joint values; add {how}, or `controller any` to vouch for them "
                                  "as they are", robot.span))
        elif declared != ANY and MAKERS.get(declared) != brand[0]:
            out.append(Diagnostic(backend_codes.CONTROLLER_MISMATCH, Severity.ERROR,
                                  f"{target}: robot '{robot.name}' declares {MAKERS.get(declared, declared)} pendant "
                                  f"values; a {target} program runs on {brand[0]} controllers (compile for "
                                  f"{_target_of(MAKERS.get(declared, ''))} instead)", robot.span))
    return tuple(out)


def target_word(brand: str) -> str:
    """The cell's word for a maker (the inverse of controller.MAKERS)."""
    from rmot.sim.robots.controller import MAKERS  # late: loads coal only when this runs

    return next(word for word, name in MAKERS.items() if name == brand)


def _target_of(brand: str) -> str:
    from rmot.backends.controller_data import TARGET_BRANDS  # late: loads numpy only when this runs

    return next((t for t, (b, _) in TARGET_BRANDS.items() if b == brand), "its own controller")


def _case_clash(files: dict[str, str]) -> tuple[str, str] | None:
    seen: dict[str, str] = {}
    for name in files:
        folded = name.casefold()
        if folded in seen:
            return seen[folded], name
        seen[folded] = name
    return None


def write_all(outdir: str, files: dict[str, str]) -> list[str]:
    """Write every file, grouped by vendor (the first path component); each vendor directory
    is replaced whole and atomically (compiler/cli/output_tree.py). Returns the final paths."""

    vendors: dict[str, dict[str, str]] = {}
    for rel, text in files.items():
        vendor, _, name = rel.partition("/")
        vendors.setdefault(vendor, {})[name] = text
    return write_vendor_dirs(outdir, vendors)


@click.command("compile")
@click.argument("program", type=click.Path(dir_okay=False))
@click.option("--cell", type=click.Path(dir_okay=False), default=None, help="Cell file (overrides `use cell`).")
@click.option("--target", "targets", multiple=True, required=True, type=_Targets(),
              help="Vendor to emit (repeatable).")
@click.option("-o", "--output", "outdir", required=True, type=click.Path(file_okay=False),
              help="Output directory; files go to OUTDIR/<vendor>/.")
@click.option("--allow-findings", is_flag=True, help="Write files even when verification reports errors.")
@click.option("--no-source-map", is_flag=True, help="Leave out the `file:line` comments.")
@click.option("--project-root", type=click.Path(file_okay=False), default=None, help="Paths may not leave this directory.")
@click.option("--write-frames", is_flag=True,
              help="Also write numbered tools and frames into the controller's stored data (Fanuc, KRL).")
@click.option("--no-cache", is_flag=True, help="Plan from scratch; neither read nor write the plan cache.")
@click.option("--unroll", is_flag=True,
              help="Write every `for` loop iteration by iteration (default: vendor loops where they fit).")
def compile_(program: str, cell: str | None, targets: tuple[str, ...], outdir: str, allow_findings: bool,
             no_source_map: bool, project_root: str | None, write_frames: bool, no_cache: bool,
             unroll: bool = False) -> None:
    """Verify PROGRAM, then write it for each --target controller."""

    outcome = compile_program(program, targets, cell=cell, project_root=project_root,
                              allow_findings=allow_findings, source_map=not no_source_map,
                              write_frames=write_frames, use_cache=not no_cache, unroll=unroll)
    for d in outcome.diagnostics:
        click.echo(render(d), err=True)
    ctx = click.get_current_context()
    if not outcome.files:
        click.echo(f"rmot: no files written ({_count(outcome.diagnostics)})", err=True)
        ctx.exit(outcome.exit_code if outcome.exit_code != EXIT_OK else EXIT_FINDINGS)
    try:
        written = write_all(outdir, outcome.files)
    except OSError as exc:
        from rmot.compiler.cli.oserrors import foreign_output_dir, output_failed  # late: optional, tried where used

        click.echo(foreign_output_dir(exc) or output_failed("output directory", outdir, exc), err=True)
        ctx.exit(EXIT_INPUT)
    for path in written:
        click.echo(f"wrote {path}")
    if outcome.refused:
        click.echo(f"rmot: not written for {', '.join(outcome.refused)} ({_count(outcome.diagnostics)}); "
                   "their earlier output, if any, is unchanged", err=True)
    ctx.exit(outcome.exit_code)


def _count(diagnostics: tuple[Diagnostic, ...]) -> str:
    errors = sum(1 for d in diagnostics if d.is_error)
    return f"{errors} error{'s' if errors != 1 else ''}"
