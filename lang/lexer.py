"""The .rmot lexer: one master regex, words typed by what the LALR parser accepts next.

A faster stand-in for lark's contextual lexer (which tries one regex per terminal and
parser state). It keeps the same contract:
  * a word is a keyword where the parser accepts that keyword, else a unit where a unit is
    accepted (`150 mm`), else a move kind / I/O kind where one is accepted, else a NAME —
    so `on`, `in`, `m`, `s` stay usable as names where no keyword fits;
  * a word the parser cannot take at all keeps its keyword type (better error messages);
  * `_NL` is a run of newlines, `;`, blank lines and comments; a newline before `to` or
    `else` is whitespace, so a circular move and an if/else may span lines.
Errors: a character that starts no token raises lark's UnexpectedCharacters.

Two forms of the same lexer: `RmotLexer`, a lark Lexer (lark's own loop runs it; the tests
keep it as the reference), and `TOKEN` + `TokenKinds`, which lang/_lalr.py fuses into its
parse loop (one match per token, blanks and comments included).
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from typing import Any

from lark import Token
from lark.exceptions import UnexpectedCharacters
from lark.lexer import Lexer

from rmot.lang.units import BASE_UNITS, COMPOUND_UNIT

__all__ = ["BLANKS", "CONTINUES", "TOKEN", "RmotLexer", "TokenKinds"]

_SIMPLE_UNITS = frozenset(BASE_UNITS)
_MASTER = re.compile(r"""
    (?P<ws>[ \t\f\r]+)
  | (?P<comment>\#[^\n]*)
  | (?P<nl>(?:;|\r?\n)(?:\s|;|\#[^\n]*)*)
  | (?P<number>[0-9]+(?:\.[0-9]+)?(?:[eE][+-]?[0-9]+)?)
  | (?P<unit>""" + COMPOUND_UNIT + r""")
  | (?P<word>[A-Za-z_][A-Za-z0-9_]*)
  | (?P<string>"(?:[^"\\\n]|\\.)*")
  | (?P<punct>\.\.|==|!=|[-+*/%().,:=\[\]{}])
""", re.X)
# The parse loop (lang/_lalr.py) takes the blanks and a comment before a token in the same
# match (possessive, so a failed match never gives back part of a comment as a token).
TOKEN = re.compile(r"""
    [ \t\f\r]*+(?:\#[^\n]*+)?+
    (?: (?P<nl>(?:;|\r?\n)(?:\s|;|\#[^\n]*)*)
      | (?P<number>[0-9]+(?:\.[0-9]+)?(?:[eE][+-]?[0-9]+)?)
      | (?P<unit>""" + COMPOUND_UNIT + r""")
      | (?P<word>[A-Za-z_][A-Za-z0-9_]*)
      | (?P<string>"(?:[^"\\\n]|\\.)*")
      | (?P<punct>\.\.|==|!=|[-+*/%().,:=\[\]{}])
    )
""", re.X)
BLANKS = re.compile(r"[ \t\f\r]*+(?:\#[^\n]*+)?+")
CONTINUES = re.compile(r"\s*(?:to|else)(?![A-Za-z0-9_])")
_WORD_KINDS = (("MOVE_KIND", frozenset({"joint", "linear"})), ("IO_KIND", frozenset({"in", "out", "ain", "aout"})))


class TokenKinds:
    """Token type names from the grammar's terminals: keywords, punctuation, and word typing."""

    def __init__(self, terminals: Any) -> None:
        self.keywords: dict[str, str] = {}
        self.punct: dict[str, str] = {"==": "COMPARE", "!=": "COMPARE", "%": "UNIT"}
        for t in terminals:
            if t.pattern.type != "str":
                continue
            target = self.keywords if t.pattern.value.isidentifier() else self.punct
            target.setdefault(t.pattern.value, t.name)

    def word_type(self, word: str, accepts: Any) -> str:
        """`accepts`: the terminal names the parser's current state takes (a set or a dict)."""
        kw = self.keywords.get(word)
        if kw is not None and kw in accepts:
            return kw
        if word in _SIMPLE_UNITS and "UNIT" in accepts:
            return "UNIT"
        for kind, words in _WORD_KINDS:
            if word in words and kind in accepts:
                return kind
        if "NAME" in accepts or kw is None:
            return "NAME"
        return kw


class RmotLexer(Lexer):
    """The same lexer as a lark Lexer (lang/_lalr.py fuses it into its parse loop instead)."""

    __future_interface__ = 2

    def __init__(self, lexer_conf: Any) -> None:
        kinds = TokenKinds(lexer_conf.terminals)
        self.keywords, self.punct, self._word_type = kinds.keywords, kinds.punct, kinds.word_type

    def lex(self, lexer_state: Any, parser_state: Any) -> Iterator[Token]:
        text = getattr(lexer_state.text, "text", lexer_state.text)
        states = parser_state.parse_conf.states
        pos, line, line_start, n = 0, 1, 0, len(text)
        match = _MASTER.match
        while pos < n:
            m = match(text, pos)
            if m is None:
                accepts = states[parser_state.position]
                raise UnexpectedCharacters(  # type: ignore[no-untyped-call]  # lark's are untyped
                    text, pos, line, pos - line_start + 1, allowed=set(accepts), state=parser_state)
            kind, end, value = m.lastgroup, m.end(), m.group()
            if kind == "ws" or kind == "comment":
                pos = end
                continue
            col = pos - line_start + 1
            if kind == "nl":
                newlines = value.count("\n")
                end_line, end_col = line + newlines, (end - (value.rfind("\n") + pos)) if newlines else col + len(value)
                skip = CONTINUES.match(text, end) is not None
                tok = None if skip else Token("_NL", value, pos, line, col, end_line, end_col, end)
                if newlines:
                    line, line_start = end_line, pos + value.rfind("\n") + 1
                pos = end
                if tok is not None:
                    yield tok
                continue
            accepts = states[parser_state.position]
            if kind == "word":
                ttype = self._word_type(value, accepts)
            elif kind == "number":
                ttype = "NUMBER"
            elif kind == "string":
                ttype = "STRING"
            elif kind == "unit":
                if "UNIT" in accepts:
                    ttype = "UNIT"
                else:  # `m/s` where no unit fits: just the word `m`, then `/` and `s`
                    value = value[: value.index("/")]
                    end = pos + len(value)
                    ttype = self._word_type(value, accepts)
            else:
                ttype = self.punct[value]
            yield Token(ttype, value, pos, line, col, line, col + (end - pos), end)
            pos = end
