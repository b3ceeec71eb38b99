"""rmot.lang: the .rmot language and the vocabulary every stage shares; the bottom layer, which
imports no other rmot folder (pyproject's layer contract, `lint-imports`).

    from rmot.lang import parse_text
    result = parse_text(source, "cell.rmot")   # ParseResult(module: ast.Module | None, diagnostics)

The language: the grammar is lang/grammar/rmot.lark (lark LALR: _lalr.py, _tables.py, lexer,
parse, _build); `ast` holds the frozen node types; `codes` the E0xx diagnostic codes;
`diagnostics` and `source` the shared Span/Diagnostic types; units, record (@record values).
The vocabulary the later stages read: ir (the checked program, SI units), ir_tree (which
instruction holds which bodies: the one IR walker), plan_types (the Plan: the planner's
hand-off), payload (the load on a flange: one model for planner, verification and backends),
check_codes / cache_codes (the check stage's and the caches' diagnostic codes),
motion_kinds (tables keyed by motion kind are complete), model_spec (a cell's `model` robot as
data), vendors (the one registry of --target names), atomic (the one file writer), jit (numba
kernels that also run as plain Python), cache_seal (the cache directory and its seal).
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from rmot.lang import ast, codes
    from rmot.lang.diagnostics import Code, Diagnostic, DiagnosticSink, Severity, render, render_all
    from rmot.lang.parse import KEYWORDS, ParseResult, parse_source, parse_text, wrap_syntax_error
    from rmot.lang.source import Pos, SourceFile, Span
    from rmot.lang.units import UNIT_NAMES

# Names load on first use (PEP 562): importing rmot.lang.source or .diagnostics (as the IR, the
# robot library and every report do) must not build the parser, which only parsing needs.
_LAZY = {
    "Code": "diagnostics", "Diagnostic": "diagnostics", "DiagnosticSink": "diagnostics",
    "Severity": "diagnostics", "render": "diagnostics", "render_all": "diagnostics",
    "KEYWORDS": "parse", "UNIT_NAMES": "units", "ParseResult": "parse", "parse_source": "parse",
    "parse_text": "parse", "wrap_syntax_error": "parse",
    "Pos": "source", "SourceFile": "source", "Span": "source",
}


def __getattr__(name: str) -> Any:
    if name in ("ast", "codes"):
        return importlib.import_module(f"rmot.lang.{name}")
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'rmot.lang' has no attribute {name!r}")
    value = getattr(importlib.import_module(f"rmot.lang.{module}"), name)
    globals()[name] = value
    return value


__all__ = [
    "KEYWORDS", "UNIT_NAMES", "Code", "Diagnostic", "DiagnosticSink", "ParseResult", "Pos", "Severity",
    "SourceFile", "Span", "ast", "codes", "parse_source", "parse_text", "render", "render_all",
    "wrap_syntax_error",
]
