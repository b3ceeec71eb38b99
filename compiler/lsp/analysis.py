"""One document through the front end (compiler/pipeline.py), kept for the editor features.

`analyze` runs the same passes as `rmot check`'s front end on the editor's text (not the
file on disk), with the same project root (the document's folder) and the same robot
loader, so its diagnostics are the ones `rmot check --format json` prints for the saved
file. Unlike `frontend.load_text` it keeps the parsed modules of every file read, for the
symbol index (index.py). It never raises for bad input: a half-typed program is a syntax
diagnostic and the features work on what the files that do parse declare.
"""

from __future__ import annotations

import os
from functools import cached_property
from typing import Any

from lsprotocol import types as lsp

from rmot.lang import ir
from rmot.compiler.lsp.index import SymbolIndex, build_index
from rmot.lang import ast
from rmot.lang.diagnostics import Diagnostic, Severity
from rmot.lang.record import record
from rmot.lang.source import Span

__all__ = ["Analysis", "analyze", "to_lsp", "lsp_range", "uri_of", "path_of"]

SOURCE = "rmot"
_SEVERITY = {Severity.ERROR: lsp.DiagnosticSeverity.Error, Severity.WARNING: lsp.DiagnosticSeverity.Warning,
             Severity.NOTE: lsp.DiagnosticSeverity.Information}


@record
class Analysis:
    path: str  # absolute
    version: int | None
    text: str
    diagnostics: tuple[Diagnostic, ...]
    modules: dict[str, ast.Module]  # absolute path -> parsed module (this document first)
    program: ir.Program | None  # None when the front end found errors or there is no program
    cell: ir.Cell | None

    @cached_property
    def index(self) -> SymbolIndex:
        """The names of every file read, built on the first request that needs them (not on
        the way to the diagnostics of a keystroke)."""
        return build_index(list(self.modules.values()))

    @property
    def has_errors(self) -> bool:
        return any(d.is_error for d in self.diagnostics)

    @property
    def module(self) -> ast.Module | None:
        return self.modules.get(self.path)

    @cached_property
    def entries(self) -> dict[str, Span]:
        """The file each `import` / `use cell` of this document names -> that statement."""
        module = self.module
        if module is None:
            return {}
        folder = os.path.dirname(self.path)
        return {os.path.normpath(os.path.join(folder, s.path.value)): s.span for s in module.body
                if isinstance(s, (ast.Import, ast.UseCell))}

    def to_lsp(self, diagnostic: Diagnostic) -> lsp.Diagnostic:
        return to_lsp(diagnostic, self.path, self.entries)


def analyze(path: str, text: str, version: int | None = None) -> Analysis:
    """The front end's result for `text` as the content of `path` (see the module docstring)."""
    from rmot.compiler.frontend import run_passes  # late: loads coal only when this runs

    path = os.path.abspath(path)
    state = run_passes(path, text)
    diagnostics = state.reporter.sink.items
    loaded = [state.main, *state.modules.values(), state.cell_module]
    modules = {os.path.abspath(m.path): m.module for m in loaded if m is not None}
    program = None if any(d.is_error for d in diagnostics) else state.program
    return Analysis(path, version, text, diagnostics, modules, program, state.cell)


def uri_of(path: str) -> str:
    from pygls.uris import from_fs_path  # late: pygls is heavy or optional, loaded only where used

    return from_fs_path(os.path.abspath(path)) or path


def path_of(uri: str) -> str:
    from pygls.uris import to_fs_path  # late: pygls is heavy or optional, loaded only where used

    return os.path.abspath(to_fs_path(uri) or uri)


def lsp_range(span: Span) -> lsp.Range:
    """1-based lines and columns (end exclusive) -> the LSP's 0-based positions."""
    return lsp.Range(lsp.Position(span.start.line - 1, span.start.col - 1),
                     lsp.Position(span.end.line - 1, max(span.end.col - 1, span.start.col - 1)))


def to_lsp(diagnostic: Diagnostic, path: str, entries: dict[str, Span] | None = None) -> lsp.Diagnostic:
    """An rmot Diagnostic as the LSP's, placed in the document `path`.

    A diagnostic from another file (an import, the cell) or from a proc body inlined at a
    call is shown at the call, or at the `import` / `use cell` (`entries`: file -> that
    statement), in this document that brought it in; its own place and the chain of calls
    are related locations, as are its notes ("first defined here")."""
    related: list[lsp.DiagnosticRelatedInformation] = []
    span = diagnostic.span
    where = lsp.Range(lsp.Position(0, 0), lsp.Position(0, 1))
    if span is not None:
        chain = (span, *span.expansion_chain())
        here = next((s for s in chain if os.path.abspath(s.path) == path), None)
        if here is not None:
            where = lsp_range(here)
        elif entries and os.path.abspath(span.path) in entries:
            where = lsp_range(entries[os.path.abspath(span.path)])
        if here is not span:
            related.append(_related(span, "reported here"))
        related += [_related(site, "through this call") for site in span.expansion_chain() if site is not here]
    related += [_related(s, text) for text, s in diagnostic.notes if s is not None]
    message = diagnostic.message
    if diagnostic.time_s is not None:
        message += f" (at t = {diagnostic.time_s:.3f} s" + (f", task {diagnostic.task})" if diagnostic.task else ")")
    return lsp.Diagnostic(where, message, severity=_SEVERITY[diagnostic.severity], code=diagnostic.code.id,
                          source=SOURCE, related_information=related or None,
                          code_description=None, data=_data(diagnostic))


def _related(span: Span, message: str) -> lsp.DiagnosticRelatedInformation:
    return lsp.DiagnosticRelatedInformation(lsp.Location(uri_of(span.path), lsp_range(span)), message)


def _data(diagnostic: Diagnostic) -> Any:
    """The finding's time and bodies, for clients that show them (not the LSP's own fields)."""
    if diagnostic.time_s is None and not diagnostic.bodies:
        return None
    return {"time_s": diagnostic.time_s, "end_time_s": diagnostic.end_time_s, "bodies": list(diagnostic.bodies),
            "task": diagnostic.task}
