"""The one pipeline the commands run: front end -> planner -> verification ->
backends, each stage called through `run`, so that a stage failing unexpectedly (a bug, not
the input) becomes the same diagnostic in every command:

    rmot: error[E550]: internal error in the planner (KeyError: 'q'); please report it

exit code 2, never a Python traceback. `check` and `report` put it in the failing program's
report and go on with the other programs; `compile` refuses only the failing vendor; every
other command stops with it. An exception no stage caught (in a command's own code) gets the
same diagnostic from the command group (compiler/cli/__init__.py `LazyGroup.invoke`).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, TypeVar
from rmot.compiler.cli import codes
from rmot.lang.diagnostics import Diagnostic, Severity
from rmot.backends import BACKENDS

if TYPE_CHECKING:
    from rmot.compiler.frontend import FrontendResult
    from rmot.lang.plan_types import Plan
    from rmot.lang.diagnostics import Diagnostic
    from rmot.sim.report import Report

__all__ = ["StageError", "emit", "internal_error", "load", "plan", "run", "verify"]

T = TypeVar("T")


class StageError(Exception):
    """A stage failed unexpectedly; `diagnostic` is the E550 that says so."""

    def __init__(self, diagnostic: Diagnostic) -> None:
        super().__init__(diagnostic.message)
        self.diagnostic = diagnostic


def internal_error(stage: str, exc: BaseException) -> Diagnostic:
    """E550 for `exc` raised inside `stage` ("the planner", "backend rapid", "rmot plot")."""

    message = f"internal error in {stage} ({type(exc).__name__}: {exc}); please report it"
    return Diagnostic(codes.INTERNAL_ERROR, Severity.ERROR, message, None)


def run(stage: str, fn: Callable[..., T], *args: Any, **kwargs: Any) -> T:
    """fn(*args, **kwargs); an Exception escaping it becomes StageError(E550)."""
    try:
        return fn(*args, **kwargs)
    except Exception as exc:  # a bug in a stage: one diagnostic, never a traceback
        raise StageError(internal_error(stage, exc)) from exc


def load(path: str, *, cell: str | None = None, project_root: str | None = None,
         require_program: bool = True, use_cache: bool = False) -> FrontendResult:
    """The front end (input errors are diagnostics in the result, not exceptions); with
    `use_cache`, a program already planned is taken from the caches when no file it read has
    changed (compiler/cli/load_cache.py)."""
    if use_cache:
        from rmot.compiler.cli import load_cache  # late: loads coal only when this runs

        return run("the front end", load_cache.load, path, cell=cell, project_root=project_root,
                   require_program=require_program)
    from rmot.compiler import frontend  # late: tests replace it (monkeypatch): read at call time

    return run("the front end", frontend.load_program, path, cell=cell, project_root=project_root,
               require_program=require_program)


def plan(program: Any, *, use_cache: bool = True, step: float | None = None) -> Plan:
    """The planner, through the plan cache."""
    from rmot.compiler.cli import load_cache  # late: loads coal only when this runs

    if use_cache and step is None:
        known = load_cache.planned(program)
        if known is not None:
            return known
    kwargs: dict[str, Any] = {"use_cache": use_cache}
    if step is not None:
        kwargs["step"] = step
    planned = run("the planner", _plan_free_moves, program, kwargs)
    if use_cache and step is None:
        load_cache.record(program, planned)
    return planned


def _plan_free_moves(program: Any, kwargs: dict[str, Any]) -> Plan:
    """The plan; a program with `move free` is planned with its via points found first
    (rmot.sim.free: the search needs the verifier's collision model, so the CLI joins them),
    and the searches' findings and notes join the plan's diagnostics."""

    from rmot.compiler import plan_cache  # late: tests replace it (monkeypatch): read at call time
    from rmot.sim.free.lower import has_free_moves, lower_free_moves  # late: loads coal only when this runs

    if not has_free_moves(program):
        return plan_cache.cached_plan(program, **kwargs)
    from rmot.compiler.cli.free_cache import FreePathCache  # late: loads numpy only when this runs

    store = FreePathCache() if kwargs["use_cache"] else None
    lowered = lower_free_moves(program, lambda p: plan_cache.cached_plan(p, **kwargs), store)
    planned = plan_cache.cached_plan(lowered.program, **kwargs)
    found = planned.diagnostics + lowered.diagnostics

    def order(k: int) -> tuple[str, int]:  # the planner's order: by source position, stable
        span = found[k].span
        return (span.path, span.start.offset) if span is not None else ("", -1)

    return dataclasses.replace(planned, diagnostics=tuple(found[k] for k in sorted(range(len(found)), key=order)))


def verify(planned: Plan, *, clearance: float | None = None, use_cache: bool = True,
           targets: tuple[str, ...] = ()) -> Report:
    """The verification (collisions, limits) of a plan, through the verification cache
    (compiler/cli/verify_cache.py: used only for a plan that came through the plan cache).
    A corner finding that concerns only some controllers (W341) is kept when `targets` names
    one of them (sim/corners.py: `rmot check` has no target and reports the zone sphere)."""
    from rmot.compiler.cli.verify_cache import cached_verify  # late: loads coal only when this runs
    from rmot.sim.corner_vendors import for_targets  # late: loads numpy only when this runs

    report: Report = run("the verification", cached_verify, planned, clearance=clearance,
                         use_cache=use_cache)
    return dataclasses.replace(report, diagnostics=for_targets(report.diagnostics, targets))


def emit(target: str, planned: Plan, *, source_map: bool = True, **options: Any) -> Any:
    """One backend's EmitResult (its module is imported on first use)."""

    return run(f"backend {target}",
               lambda: BACKENDS[target](**options).emit(planned, source_map=source_map))
