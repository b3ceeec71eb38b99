"""rmot.lang: the .rmot language front end — text to AST, with compiler-grade diagnostics.

    from rmot.lang import parse_text
    result = parse_text(source, "cell.rmot")   # ParseResult(module: ast.Module | None, diagnostics)

The grammar is lang/grammar/rmot.lark (lark LALR); `ast` holds the frozen node types;
`codes` the E0xx diagnostic codes; `diagnostics` and `source` the shared Span/Diagnostic types.
"""

from rmot.lang import ast, codes
from rmot.lang.diagnostics import Code, Diagnostic, DiagnosticSink, Severity, render, render_all
from rmot.lang.parse import KEYWORDS, UNITS, ParseResult, parse_source, parse_text, wrap_syntax_error
from rmot.lang.source import Pos, SourceFile, Span

__all__ = [
    "KEYWORDS", "UNITS", "Code", "Diagnostic", "DiagnosticSink", "ParseResult", "Pos", "Severity",
    "SourceFile", "Span", "ast", "codes", "parse_source", "parse_text", "render", "render_all",
    "wrap_syntax_error",
]
