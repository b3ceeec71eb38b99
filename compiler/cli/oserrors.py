"""Operating-system errors as diagnostics: a missing output folder, a full disk,
a name longer than NAME_MAX, a folder that cannot be made become `rmot: error[E520]: ...`
naming the path, never a traceback."""

from __future__ import annotations

__all__ = ["output_failed"]


def output_failed(what: str, path: str, exc: OSError) -> str:
    """The rendered E520 diagnostic for an output `path` that could not be written."""
    from rmot.compiler import codes
    from rmot.lang.diagnostics import Diagnostic, Severity, render

    reason = exc.strerror or exc.__class__.__name__
    where = exc.filename if isinstance(exc.filename, str) else path
    msg = f"{what} '{path}' must be writable (got {reason}: {where!r})"
    return render(Diagnostic(codes.OUTPUT_FAILED, Severity.ERROR, msg, None))
