"""Text -> AST: the LALR parser (built on first use) and the one place lark errors become words.

`parse_source(file)` never raises for bad input: it returns the Module (or None) and the
diagnostics. lark's LALR tables for rmot.lark (lang/_tables.py: computed by lark once, then
read as JSON data from the user's cache) and lark's rule callbacks with the Transformer in
`lang/_build.py` embedded make each rule one AST node with its span as it is reduced: no
parse tree is built. lang/_lalr.py runs those tables and callbacks over the tokens of
lang/lexer.py with the post-lexer fused in (newlines inside brackets dropped, braces
tracked); tests/lang/test_lang_driver.py checks it against lark's own loop.

Parsing is serialised by a lock: the embedded transformer keeps the state of the current
parse (the file). The post-lexer state the error messages read is made per parse and passed
along, never kept between parses. The garbage collector is left alone here (the command line
pauses it around its front end: compiler/cli).

lark's internals read here and in _lalr.py / _tables.py are pinned by the lark versions in
pyproject.toml; tests/lang/test_lang_lark_version.py fails on any other version.
"""

from __future__ import annotations

import dataclasses
import difflib
import functools
import re
import threading
from typing import cast

from lark import Token
from lark.exceptions import UnexpectedCharacters, UnexpectedEOF, UnexpectedInput, UnexpectedToken

from rmot.lang import ast
from rmot.lang import codes
from rmot.lang._build import AstBuilder
from rmot.lang._build_nodes import KEYWORDS, RESERVED, reserved_statement, token_span
from rmot.lang._lalr import LalrDriver, PostLexState
from rmot.lang._tables import GRAMMAR as _GRAMMAR
from rmot.lang._tables import load_tables
from rmot.lang.diagnostics import Code, Diagnostic, Severity
from rmot.lang.record import record
from rmot.lang.source import Pos, SourceFile, Span
from rmot.lang.units import unknown_unit
from lark import Tree
from lark.parse_tree_builder import ParseTreeBuilder

__all__ = ["ParseResult", "parse_source", "parse_text", "wrap_syntax_error", "KEYWORDS", "RESERVED"]


_MAX_EXPECTED = 6


@record(slots=True)
class ParseResult:
    module: ast.Module | None
    diagnostics: tuple[Diagnostic, ...]


class _Parser:
    """The tables, the embedded builder and the loop that runs them; one per process."""

    def __init__(self) -> None:

        tables = load_tables(_GRAMMAR.read_text(encoding="utf-8"))
        self.builder = AstBuilder()
        # as lark's Lark._prepare_callbacks for parser="lalr", maybe_placeholders=True
        rules = list(tables.rules)
        builder = ParseTreeBuilder(rules, Tree, False, False, True)  # type: ignore[no-untyped-call]
        callbacks = builder.create_callback(self.builder)  # type: ignore[no-untyped-call]
        self.driver = LalrDriver(tables, callbacks)
        self.patterns = {t.name: t.pattern for t in tables.terminals}
        self.lock = threading.Lock()

    def parse(self, file: SourceFile, post: PostLexState
              ) -> tuple[ast.Module, tuple[Diagnostic, ...]]:
        """The Module and the builder's diagnostics; lark's exceptions on bad input."""
        with self.lock:
            self.builder.begin(file)
            module: ast.Module = self.driver.parse(file.text, post)
            return module, tuple(self.builder.diagnostics)


@functools.cache
def _parser() -> _Parser:
    return _Parser()


def parse_text(text: str, path: str = "<input>") -> ParseResult:
    return parse_source(SourceFile(path, text))


def parse_source(file: SourceFile) -> ParseResult:
    """Parse one file; syntax errors become diagnostics (LALR stops at the first one; the
    lines of later ones are found by parsing again without the failing line, _later_errors)."""
    binary = _binary_problem(file) or _line_break_problem(file)
    if binary is not None:
        return ParseResult(None, (binary,))
    if not file.text.strip():
        msg = "file must contain a cell, a program or declarations (got an empty file)"
        return ParseResult(None, (_error(codes.EMPTY_FILE, msg, Span.whole(file)),))
    post = PostLexState()
    try:
        module, problems = _parser().parse(file, post)
    except UnexpectedInput as exc:
        first = wrap_syntax_error(exc, file, post)
        return ParseResult(None, (first, *_later_errors(file, first)))
    except Exception as exc:  # a builder bug must still not reach the user as a traceback
        span = Span.whole(file)
        return ParseResult(None, (_error(codes.SYNTAX, f"internal parser error: {exc!r}", span),))
    if not module.body:
        msg = "file must contain a cell, a program or declarations (got only comments)"
        problems += (_error(codes.EMPTY_FILE, msg, Span.whole(file)),)
    return ParseResult(module, problems)


# Syntax errors reported after the first, and the largest file searched for them (each one is
# a parse of the whole file again).
MAX_LATER_ERRORS = 10
MAX_RECOVERY_BYTES = 64 * 1024


def _later_errors(file: SourceFile, first: Diagnostic) -> tuple[Diagnostic, ...]:
    """The syntax errors after `first` (an unknown word does not hide the next one): the line
    of each error is blanked (spaces, so every later position stays) and the file parsed
    again. Only a line without braces is blanked, so a block's structure never changes and
    no error is one the blanking made; the search stops at a line with a brace."""
    found: list[Diagnostic] = []
    text, error = file.text, first
    while len(found) < MAX_LATER_ERRORS and len(text) <= MAX_RECOVERY_BYTES and error.span is not None:
        start = text.rfind("\n", 0, error.span.start.offset) + 1
        end = text.find("\n", error.span.start.offset)
        end = len(text) if end < 0 else end
        if "{" in text[start:end] or "}" in text[start:end] or not text[start:end].strip():
            break
        text = text[:start] + " " * (end - start) + text[end:]
        post = PostLexState()
        try:
            _parser().parse(SourceFile(file.path, text), post)
            break
        except UnexpectedInput as exc:
            error = wrap_syntax_error(exc, SourceFile(file.path, text), post)
        except Exception:  # a builder bug while recovering: the errors found so far stand
            break
        if error.span is None or error.span.start.offset < end:
            break
        found.append(_in_file(error, file))
    return tuple(found)


def _in_file(error: Diagnostic, file: SourceFile) -> Diagnostic:
    """`error`, found in a copy of `file` with lines blanked, with its spans in `file` itself."""
    def moved(span: Span | None) -> Span | None:
        return None if span is None else Span.from_offsets(file, span.start.offset, span.end.offset)

    return dataclasses.replace(error, span=moved(error.span), notes=tuple((text, moved(s)) for text, s in error.notes))


def _error(code: Code, message: str, span: Span | None,
           notes: tuple[tuple[str, Span | None], ...] = ()) -> Diagnostic:
    return Diagnostic(code, Severity.ERROR, message, span, notes)


def _binary_problem(file: SourceFile) -> Diagnostic | None:
    """NUL and other C0 control characters (besides tab, newline, CR, FF) mean a binary file."""
    found = _CONTROL.search(file.text)  # the whole file: a NUL after 64 KiB is binary too
    if found is not None:
        i, ch = found.start(), found.group()
        span = Span.from_offsets(file, i, i + 1)
        return _error(codes.BINARY_INPUT, f"file must be text (got control character {ch!r})", span)
    return None


_CONTROL = re.compile(r"[\x00-\x08\x0b\x0e-\x1f]")
# Line breaks the lexer does not take as one but other text layers do (Python's splitlines,
# editors): refused, so that every tool counts the same lines as `file:line:col`.
_ODD_BREAK = re.compile("\r(?!\n)|[\x85\u2028\u2029]")


def _line_break_problem(file: SourceFile) -> Diagnostic | None:
    found = _ODD_BREAK.search(file.text)
    if found is None:
        return None
    span = Span.from_offsets(file, found.start(), found.start() + 1)
    if found.group() == "\r":
        return _error(codes.LONE_CR, "lines must end with LF or CRLF (got a carriage return alone: "
                      "old Mac line endings; convert the file to LF)", span)
    name = {"\x85": "U+0085 NEXT LINE", "\u2028": "U+2028 LINE SEPARATOR", "\u2029": "U+2029 PARAGRAPH SEPARATOR"}[found.group()]
    return _error(codes.UNICODE_LINE_BREAK, f"lines must end with LF or CRLF (got {name}, which some editors "
                  "show as a line break and the compiler does not)", span)


# --------------------------------------------------------------------------- errors in words

_WORDS = {
    "NAME": "a name", "NUMBER": "a number", "STRING": "a string", "UNIT": "a unit such as mm or deg",
    "_NL": "a new line or ';'", "$END": "the end of the file", "MOVE_KIND": "'joint', 'linear' or 'circular'",
    "IO_KIND": "an I/O port such as in[1] or out[2]", "COMPARE": "a comparison (== != < <= > >=)",
}
_EXPR_START = {"NAME", "NUMBER", "STRING", "LPAR", "MINUS", "PLUS", "JOINTS", "IO_KIND"}  # in[1]: a read
_STMT_START = {"MOVE", "SET", "WAIT", "PULSE", "FOR", "REPEAT", "IF", "SYNC", "NATIVE", "SPEED",
               "ACCEL", "ZONE", "TOOL", "FRAME", "TARGET", "CONST", "PROC", "JOINT_SPEED",
               "VAR", "WHILE", "STOP"}
_OPERATORS = {"PLUS", "MINUS", "STAR", "SLASH", "DOT"}


def _word(name: str) -> str:
    if name in _WORDS:
        return _WORDS[name]
    pattern = _parser().patterns.get(name)
    if pattern is not None and pattern.type == "str":
        return f"'{pattern.value}'"
    return name.lower()


def _keyword_values(expected: set[str]) -> list[str]:
    words = []
    patterns = _parser().patterns
    for name in expected:
        pattern = patterns.get(name)
        if pattern is not None and pattern.type == "str" and pattern.value.isidentifier():
            words.append(pattern.value)
    if "MOVE_KIND" in expected:
        words += ["joint", "linear"]
    return words


def expected_in_words(expected: set[str]) -> str:
    """Group terminal names into what a user reads: 'an expression', 'a statement', ..."""
    items: list[str] = []
    rest = set(expected)
    if len(rest & _STMT_START) >= 5:
        items.append("a statement")
        rest -= _STMT_START | {"NAME"}
    if {"NAME", "NUMBER"} <= rest:
        items.append("an expression")
        rest -= _EXPR_START
    if "UNIT" in rest:
        items.append(_WORDS["UNIT"])
        rest.discard("UNIT")
    if len(rest & _OPERATORS) >= 3:
        items.append("an operator")
        rest -= _OPERATORS
    items += sorted(_word(n) for n in rest)
    if len(items) > _MAX_EXPECTED:
        items = items[:_MAX_EXPECTED] + ["..."]
    if len(items) == 1:
        return items[0]
    return ", ".join(items[:-1]) + " or " + items[-1]


def _shown(tok: Token) -> str:
    if tok.type == "$END":
        return "the end of the file"
    if tok.type == "_NL":
        return "the end of the line" if not str(tok).startswith(";") else "';'"
    return f"'{tok}'"


def wrap_syntax_error(exc: UnexpectedInput, file: SourceFile,
                      post: PostLexState | None = None) -> Diagnostic:
    """The single conversion of a lark error into a Diagnostic with words, not token names.

    `post`: the post-lexer state of the parse that failed (open braces, last tokens), which
    sharpens the message; without it the message names only the token and what was expected."""
    post = PostLexState() if post is None else post
    if isinstance(exc, UnexpectedCharacters):
        return _bad_character(exc, file)
    if isinstance(exc, UnexpectedToken):
        return _bad_token(exc.token, set(exc.expected), file, post)
    if isinstance(exc, UnexpectedEOF):
        return _bad_token(Token("$END", "", len(file.text)), set(exc.expected), file, post)
    return _error(codes.SYNTAX, str(exc).splitlines()[0], Span.whole(file))


def _bad_character(exc: UnexpectedCharacters, file: SourceFile) -> Diagnostic:
    # lark types a position as int | None; an UnexpectedCharacters always has one
    offset, line, column = cast(int, exc.pos_in_stream), exc.line, exc.column
    ch = file.text[offset] if offset < len(file.text) else ""
    span = Span(file, Pos(line, column, offset), Pos(line, column + 1, offset + 1))
    if ch == '"':
        end = file.text.find("\n", offset)
        end = len(file.text) if end < 0 else end
        span = Span(file, span.start, Pos(line, column + (end - offset), end))
        return _error(codes.UNTERMINATED_STRING, "string must end with '\"' on the same line (got the end of the line)", span)
    msg = f"unexpected character {ch!r}: outside strings and comments only names, numbers, units, operators and brackets may appear"
    return _error(codes.UNEXPECTED_CHARACTER, msg, span)


def _eof_span(file: SourceFile) -> Span:
    n = len(file.text)
    start = file.pos_at(max(0, n - 1))
    return Span(file, start, Pos(start.line, start.col + 1, n))


def _bad_token(tok: Token, expected: set[str], file: SourceFile, post: PostLexState) -> Diagnostic:
    at_end = tok.type == "$END"
    span = _eof_span(file) if at_end or tok.line is None else token_span(file, tok)
    if tok.type == "RBRACE" and post.unmatched_close is not None:
        span = token_span(file, post.unmatched_close)
        return _error(codes.UNBALANCED_BRACE, "'}' must close an open '{' (got none open)", span)
    if at_end and post.braces:
        opening = token_span(file, post.braces[-1])
        msg = "'{' must be closed by '}' (got the end of the file)"
        return _error(codes.UNBALANCED_BRACE, msg, opening, (("the file ends here", span),))
    history = _history_before(tok, post)
    if tok.type == "_NL" and history:
        span = _after(file, history[-1])  # point just past the last word, not past a comment
    misspelt = _misspelt(tok, expected, file, history, _inside_cell(post, file))
    if misspelt is not None:
        return misspelt
    code = codes.UNEXPECTED_END if at_end else codes.SYNTAX
    return _error(code, f"expected {expected_in_words(expected)} (got {_shown(tok)})", span)


def _after(file: SourceFile, tok: Token) -> Span:
    line, col, pos = cast(int, tok.end_line), cast(int, tok.end_column), cast(int, tok.end_pos)
    return Span(file, Pos(line, col, pos), Pos(line, col + 1, pos + 1))


def _history_before(tok: Token, post: PostLexState) -> list[Token]:
    """The tokens the parser took before `tok` (the post-lexer may or may not have seen tok)."""
    history = list(post.history)
    if history and history[-1] is tok:
        history.pop()
    return history


def _misspelt(tok: Token, expected: set[str], file: SourceFile, history: list[Token], in_cell: bool = False) -> Diagnostic | None:
    """A name near a keyword the parser wanted, or a word after a number that is no unit."""
    prev = history[-1] if history else None
    if tok.type == "NAME" and "UNIT" in expected and prev is not None and prev.type == "NUMBER":
        return unknown_unit(str(tok), token_span(file, tok))
    if tok.type == "NAME":
        near = difflib.get_close_matches(str(tok), _keyword_values(expected), n=1, cutoff=0.7)
        if near:
            return _error(codes.MISSPELT_KEYWORD, f"unknown keyword '{tok}'; did you mean '{near[0]}'?", token_span(file, tok))
    # `mvoe joint home`: the parser took `mvoe` for a call and stumbles on the next token.
    before = history[-2] if len(history) >= 2 else None
    starts_statement = before is None or before.type in ("_NL", "LBRACE")
    if prev is not None and prev.type == "NAME" and starts_statement and str(prev) in RESERVED:
        return reserved_statement(str(prev), token_span(file, prev))
    if prev is not None and prev.type == "NAME" and starts_statement and "LPAR" in expected:
        word = str(prev)
        if word in _OTHER_LANGUAGES:
            msg = f"unknown statement '{word}'; rmot writes this as {_OTHER_LANGUAGES[word]}"
            return _error(codes.MISSPELT_KEYWORD, msg, token_span(file, prev))
        starts = CELL_DECLARATION_STARTS if in_cell else STATEMENT_STARTS
        near = difflib.get_close_matches(word, starts, n=1, cutoff=0.6)
        if near:
            kind = "declaration" if in_cell else "statement"
            return _error(codes.MISSPELT_KEYWORD, f"unknown {kind} '{prev}'; did you mean '{near[0]}'?", token_span(file, prev))
        words = ", ".join(starts)
        msg = (f"unknown statement '{prev}': a statement starts with {words}, "
               "or is a proc call NAME(...) or an assignment NAME = EXPR")
        if in_cell:
            msg = f"unknown declaration '{prev}' in a cell: a cell declaration starts with {words}"
        return _error(codes.MISSPELT_KEYWORD, msg, token_span(file, prev))
    return None


def _inside_cell(post: PostLexState, file: SourceFile) -> bool:
    """The innermost open block is the body of `cell NAME {`."""
    if not post.braces:
        return False
    return re.search(r"\bcell\s+[A-Za-z_]\w*\s*\Z", file.text[:post.braces[-1].start_pos]) is not None


# the words a declaration in a cell starts with (compiler/passes/lower_cell.py lowers these)
CELL_DECLARATION_STARTS = ["robot", "fixture", "tool", "frame", "io", "const", "model", "part", "track", "positioner"]

# the words a statement may start with (an unknown statement word lists them, and a
# near miss is matched against these only, so `let` is not taken for `at` nor `var` for `via`)
STATEMENT_STARTS = [
    "move",
    "set",
    "pulse",
    "wait",
    "if",
    "for",
    "repeat",
    "while",
    "var",
    "stop",
    "sync",
    "native",
    "attach",
    "detach",
    "speed",
    "joint_speed",
    "accel",
    "zone",
    "tool",
    "frame",
    "target",
    "const",
    "proc",
    "part",
    "feeder",
]
# words of other robot languages for what rmot spells differently
_OTHER_LANGUAGES = {
    "let": "'var NAME: int|num|bool = EXPR'",
    "dim": "'var NAME: int|num|bool = EXPR'",
    "int": "'var NAME: int = EXPR'",
    "num": "'var NAME: num = EXPR'",
    "bool": "'var NAME: bool = EXPR'",
    "decl": "'var NAME: int|num|bool = EXPR'",
    "loop": "'while COND { ... }' or 'repeat N { ... }'",
    "halt": "'stop'",
    "exit": "'stop'",
    "end": "'stop'",
    "goto": "a loop or an if (rmot has no jumps)",
}
