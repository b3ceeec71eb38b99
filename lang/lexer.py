"""The .rmot lexer: one master regex, words typed by what the LALR parser accepts next.

A faster stand-in for lark's contextual lexer (which tries one regex per terminal and
parser state). It keeps the same contract:
  * a word is a keyword where the parser accepts that keyword, else a unit where a unit is
    accepted (`150 mm`), else a move kind / I/O kind where one is accepted, else a NAME —
    so `on`, `in`, `m`, `s` stay usable as names where no keyword fits; `in`, `out`, `ain`,
    `aout`, `gin` are an I/O kind only right before `[` (`ain[1] * 2`) where a name fits
    too, so a target, var, proc or const with one of those names stays usable in an
    expression (`move joint out`, `x = gin + 1`): no name is ever indexed;
  * a word the parser cannot take at all keeps its keyword type (better error messages);
  * `_NL` is a run of newlines, `;`, blank lines and comments; a newline before `to` or
    `else` is whitespace, so a circular move and an if/else may span lines; inside a `track`
    or `positioner` declaration a newline before an axis option (`speed`, `accel`, `inform`,
    `solid`, `mass`) or `on` is whitespace too, so a track spans lines as a positioner does,
    and so is one before `on` in a `robot`, `fixture` or `tool` declaration.
Errors: a character that starts no token raises lark's UnexpectedCharacters.

`TOKEN` + `TokenKinds` are what lang/_lalr.py fuses into its parse loop (one match per
token, blanks and comments included); tests/lang/reference_lexer.py wraps the same rules in
a lark Lexer for lark's own loop, the reference the fused loop is tested against.
"""

from __future__ import annotations

import re
from typing import Any

from rmot.lang.units import BASE_UNITS, COMPOUND_UNIT

__all__ = ["AXIS_CONTINUES", "BLANKS", "CONTINUES", "INDEXED", "IO_WORDS", "MOUNT_CONTINUES", "TOKEN", "TokenKinds",
           "in_statement_of"]

_SIMPLE_UNITS = frozenset(BASE_UNITS)
# The parse loop (lang/_lalr.py) takes the blanks and a comment before a token in the same
# match (possessive, so a failed match never gives back part of a comment as a token).
TOKEN = re.compile(r"""
    [ \t\f\r]*+(?:\#[^\n]*+)?+
    (?: (?P<nl>(?:;|\r?\n)(?:\s|;|\#[^\n]*)*)
      | (?P<number>[0-9]+(?:\.[0-9]+)?(?:[eE][+-]?[0-9]+)?)
      | (?P<unit>""" + COMPOUND_UNIT + r""")
      | (?P<word>[A-Za-z_][A-Za-z0-9_]*)
      | (?P<string>"(?:[^"\\\n]|\\.)*")
      | (?P<punct>\.\.|==|!=|<=|>=|[-+*/%().,:=\[\]{}<>])
    )
""", re.X)
BLANKS = re.compile(r"[ \t\f\r]*+(?:\#[^\n]*+)?+")
CONTINUES = re.compile(r"\s*(?:to|else|at)(?![A-Za-z0-9_])")
# The words that continue a track or positioner declaration on the next line (only there: a
# line starting with `speed` elsewhere is a speed setting).
AXIS_CONTINUES = re.compile(r"\s*(?:speed|accel|inform|solid|mass|on)(?![A-Za-z0-9_])")
# `on NAME` continues a robot, fixture or tool declaration on the next line (no statement starts with it).
MOUNT_CONTINUES = re.compile(r"\s*on(?![A-Za-z0-9_])")
_STATEMENT_BOUNDS = frozenset({"_NL", "LBRACE", "RBRACE"})
_MOVE_WORDS = frozenset({"joint", "linear"})
IO_WORDS = frozenset({"in", "out", "ain", "aout", "gin"})
# An I/O word right before `[` (blanks between allowed, as in `in [1]`) is a port read.
INDEXED = re.compile(r"[ \t\f\r]*\[")


class TokenKinds:
    """Token type names from the grammar's terminals: keywords, punctuation, and word typing."""

    def __init__(self, terminals: Any) -> None:
        self.keywords: dict[str, str] = {}
        self.punct: dict[str, str] = {"==": "COMPARE", "!=": "COMPARE", "%": "UNIT", "<": "COMPARE",
                                      "<=": "COMPARE", ">": "COMPARE", ">=": "COMPARE"}
        for t in terminals:
            if t.pattern.type != "str":
                continue
            target = self.keywords if t.pattern.value.isidentifier() else self.punct
            target.setdefault(t.pattern.value, t.name)

    def word_type(self, word: str, accepts: Any, indexed: bool = False) -> str:
        """`accepts`: the terminal names the parser's current state takes (a set or a dict);
        `indexed`: the word's next non-blank character is `[` (only I/O words ask)."""
        kw = self.keywords.get(word)
        if kw is not None and kw in accepts:
            return kw
        if word in _SIMPLE_UNITS and "UNIT" in accepts:
            return "UNIT"
        if word in _MOVE_WORDS and "MOVE_KIND" in accepts:
            return "MOVE_KIND"
        if word in IO_WORDS and "IO_KIND" in accepts and (indexed or "NAME" not in accepts):
            return "IO_KIND"
        if "NAME" in accepts or kw is None:
            return "NAME"
        return kw


def in_statement_of(values: Any, starts: frozenset[str]) -> bool:
    """Whether the parser's value stack is inside a statement that began with one of the token
    types `starts` (e.g. the `track` and `positioner` keywords): the statement's tokens stay on the
    stack until it ends, and the newline or brace before it bounds the search."""
    for value in reversed(values):
        kind = getattr(value, "type", None) if isinstance(value, str) else None
        if kind in starts:
            return True
        if kind in _STATEMENT_BOUNDS:
            return False
    return False
