"""A mixin for backends whose routines repeat source lines (unrolled loops, one routine per
proc call): the same diagnostic at the same span is reported once."""

from __future__ import annotations

from rmot.backends.base import Backend, EmitResult
from rmot.compiler import planned

__all__ = ["UniqueDiagnostics"]


class UniqueDiagnostics(Backend):
    """Backend.emit with repeated (code, severity, message, span) diagnostics dropped, order kept."""

    def emit(self, plan: planned.Plan, *, source_map: bool = True) -> EmitResult:
        result = super().emit(plan, source_map=source_map)
        return EmitResult(result.files, tuple(dict.fromkeys(result.diagnostics)))
