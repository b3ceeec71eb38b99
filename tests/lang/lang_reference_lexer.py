"""The reference the fused parse loop (lang/_lalr.py) is tested against: lark's own LALR loop
(`Lark.parse`) with a lark Lexer and a lark post-lexer doing what the fused loop does inline.

Only the tests use these. The lexer takes its token rules from lang/lexer.py (TOKEN, BLANKS,
CONTINUES, TokenKinds), so a new token needs no second copy here; what is tested is the loop:
lark's generator stages, its contextual token typing through `parser_state`, its shift/reduce
and its errors, against the fused one.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Iterator
from typing import Any

from lark import Lark, Token
from lark.exceptions import UnexpectedCharacters
from lark.lexer import Lexer
from rmot.lang import _build
from rmot.lang._tables import GRAMMAR
from rmot.lang.lexer import (AXIS_CONTINUES, BLANKS, CONTINUES, INDEXED, MOUNT_CONTINUES, TOKEN, TokenKinds,
                             in_statement_of)
from rmot.lang.units import COMPOUND_CUT

__all__ = ["PostLexer", "RmotLexer", "reference_parser"]


class RmotLexer(Lexer):
    """lang/lexer.py's rules as a lark Lexer (lark's loop calls it with its parser state)."""

    __future_interface__ = 2

    def __init__(self, lexer_conf: Any) -> None:
        kinds = TokenKinds(lexer_conf.terminals)
        self.punct, self._word_type = kinds.punct, kinds.word_type
        self._axis_starts = frozenset(kinds.keywords[w] for w in ("track", "positioner"))
        self._mount_starts = frozenset(kinds.keywords[w] for w in ("robot", "fixture", "tool"))

    def lex(self, lexer_state: Any, parser_state: Any) -> Iterator[Token]:
        text = getattr(lexer_state.text, "text", lexer_state.text)
        states = parser_state.parse_conf.states
        pos, line, line_start, n = 0, 1, 0, len(text)
        while pos < n:
            m = TOKEN.match(text, pos)
            if m is None:
                pos = BLANKS.match(text, pos).end()  # type: ignore[union-attr]
                if pos >= n:
                    return
                accepts = states[parser_state.position]
                raise UnexpectedCharacters(text, pos, line, pos - line_start + 1, allowed=set(accepts),
                                           state=parser_state)
            kind, end = m.lastgroup, m.end()
            assert kind is not None
            value = m.group(kind)
            start = end - len(value)
            col = start - line_start + 1
            if kind == "nl":
                newlines = value.count("\n")
                end_line = line + newlines
                end_col = (end - (value.rfind("\n") + start)) if newlines else col + len(value)
                skip = CONTINUES.match(text, end) is not None or (value[0] != ";" and (
                    AXIS_CONTINUES.match(text, end) is not None
                    and in_statement_of(parser_state.value_stack, self._axis_starts)
                    or MOUNT_CONTINUES.match(text, end) is not None
                    and in_statement_of(parser_state.value_stack, self._mount_starts)))
                tok = None if skip else Token("_NL", value, start, line, col, end_line, end_col, end)
                if newlines:
                    line, line_start = end_line, start + value.rfind("\n") + 1
                pos = end
                if tok is not None:
                    yield tok
                continue
            accepts = states[parser_state.position]
            if kind == "word":
                ttype = self._word_type(value, accepts, INDEXED.match(text, end) is not None)
            elif kind == "number":
                ttype = "NUMBER"
            elif kind == "string":
                ttype = "STRING"
            elif kind == "unit":
                if "UNIT" in accepts:
                    ttype = "UNIT"
                else:  # `m/s` where no unit fits: just the word `m`, then `/` and `s`
                    value = value[: COMPOUND_CUT.search(value).start()]  # type: ignore[union-attr]
                    end = start + len(value)
                    ttype = self._word_type(value, accepts)
            else:
                ttype = self.punct[value]
            yield Token(ttype, value, start, line, col, line, col + (end - start), end)
            pos = end


class PostLexer:
    """Drops newlines inside ( ) and [ ]; tracks the open braces and the last tokens
    (lark's post-lexer interface)."""

    always_accept = ("_NL",)

    def __init__(self) -> None:
        self.braces: list[Token] = []
        self.unmatched_close: Token | None = None
        self.history: deque[Token] = deque(maxlen=3)

    def process(self, stream: Iterator[Token]) -> Iterator[Token]:
        self.braces = []
        self.unmatched_close = None
        self.history.clear()
        depth = 0
        for tok in stream:
            kind = tok.type
            if kind == "_NL" and depth > 0:
                continue
            if kind in ("LPAR", "LSQB"):
                depth += 1
            elif kind in ("RPAR", "RSQB"):
                depth = max(0, depth - 1)
            elif kind == "LBRACE":
                depth = 0  # a '{' ends any unclosed '(' before it: report there, not at EOF
                self.braces.append(tok)
            elif kind == "RBRACE":
                if self.braces:
                    self.braces.pop()
                elif self.unmatched_close is None:
                    self.unmatched_close = tok
            self.history.append(tok)
            yield tok


def reference_parser() -> tuple[Lark, _build.AstBuilder, PostLexer]:
    """A Lark of rmot.lark with RmotLexer, PostLexer and an AstBuilder embedded, built by lark
    from the grammar text (no cached tables)."""
    builder, post = _build.AstBuilder(), PostLexer()
    parser = Lark(GRAMMAR.read_text(encoding="utf-8"), parser="lalr", lexer=RmotLexer, maybe_placeholders=True,
                  postlex=post, transformer=builder, cache=False)
    return parser, builder, post
