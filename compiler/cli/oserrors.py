"""Operating-system errors as diagnostics: a missing output folder, a full disk,
a name longer than NAME_MAX, a folder that cannot be made become `rmot: error[E520]: ...`
naming the path, never a traceback."""

from __future__ import annotations
from rmot.lang.diagnostics import Diagnostic, Severity, render
import os
from rmot.compiler.cli.output_tree import MARKER, ForeignOutputDir

__all__ = ["foreign_output_dir", "output_failed", "output_is_input"]


def output_failed(what: str, path: str, exc: OSError) -> str:
    """The rendered E520 diagnostic for an output `path` that could not be written."""
    from rmot.lang import check_codes as codes  # late: tests replace it (monkeypatch): read at call time

    reason = exc.strerror or exc.__class__.__name__
    where = exc.filename if isinstance(exc.filename, str) else path
    msg = f"{what} '{path}' must be writable (got {reason}: {where!r})"
    return render(Diagnostic(codes.OUTPUT_FAILED, Severity.ERROR, msg, None))


def output_is_input(what: str, output: str, inputs: tuple[str | None, ...]) -> str | None:
    """The rendered E564 diagnostic when `output` is one of `inputs` (same resolved path, or
    the same file through a hard link), else None: checked before any work, nothing written."""

    from rmot.lang import check_codes as codes  # late: tests replace it (monkeypatch): read at call time

    target = os.path.realpath(output)
    for source in inputs:
        if source is None:
            continue
        same = os.path.realpath(source) == target
        if not same and os.path.exists(output) and os.path.exists(source):
            try:
                same = os.path.samefile(source, output)
            except OSError:
                same = False
        if same:
            msg = f"{what} '{output}' must not be an input of the command (it is '{source}'); nothing was written"
            return render(Diagnostic(codes.OUTPUT_IS_INPUT, Severity.ERROR, msg, None))
    return None


def foreign_output_dir(exc: OSError) -> str | None:
    """The rendered E565 diagnostic when `exc` is the writer's refusal to replace a vendor
    folder rmot did not create (compiler/cli/output_tree.py), else None."""
    from rmot.lang import check_codes as codes  # late: tests replace it (monkeypatch): read at call time

    if not isinstance(exc, ForeignOutputDir):
        return None
    msg = (f"output folder '{exc.filename}' must be empty or one rmot wrote (listed in {MARKER} beside it); "
           "it holds other files, so nothing was written: move it or choose another -o")
    return render(Diagnostic(codes.FOREIGN_OUTPUT_DIR, Severity.ERROR, msg, None))
