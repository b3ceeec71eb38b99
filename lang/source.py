"""Source files and spans: where every AST node, IR node and diagnostic came from.

Lines and columns are 1-based; `end` is exclusive on the same line (a span of one
character at column 5 has start col 5 and end col 6). Offsets are 0-based indexes into
`SourceFile.text`.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field

from rmot.lang.record import record

__all__ = ["Pos", "SourceFile", "Span"]


@record(slots=True)
class SourceFile:
    """One file's text, kept so a diagnostic can show the offending line."""

    path: str
    text: str = field(repr=False, compare=False, hash=False)

    def line_text(self, line: int) -> str:
        """The text of 1-based `line` without its newline ('' past the end).

        Lines end at LF only (a CRLF's CR is dropped), exactly as the lexer and `pos_at` count
        them: `str.splitlines` would also break at form feed, CR, U+2028 and five more, and
        then `file:line:col` and the quoted line would disagree."""
        starts = _line_starts(self.text)
        if not 1 <= line <= len(starts):
            return ""
        start = starts[line - 1]
        end = self.text.find("\n", start)
        text = self.text[start:] if end < 0 else self.text[start:end]
        return text[:-1] if text.endswith("\r") else text

    def pos_at(self, offset: int) -> Pos:
        """The 1-based line and column of a 0-based character offset."""
        offset = max(0, min(offset, len(self.text)))
        line = self.text.count("\n", 0, offset) + 1
        last_nl = self.text.rfind("\n", 0, offset)
        return Pos(line, offset - last_nl, offset)


@dataclass(frozen=True, slots=True, order=True)
class Pos:
    line: int
    col: int
    offset: int = 0


@record(slots=True)
class Span:
    """A range of source text. Never part of node equality (fields use compare=False)."""

    file: SourceFile
    start: Pos
    end: Pos
    # Where this text was expanded from: an instruction inlined from a proc keeps its own span
    # and points at the call site here (Cairo's Location.parent_location), so a diagnostic in
    # a proc body can say which call it came through.
    parent: Span | None = field(default=None, compare=False, hash=False, repr=False)

    def with_parent(self, parent: Span | None) -> Span:
        """This span expanded at `parent` (the innermost call site); chains keep the outer ones."""
        if parent is None:
            return self
        chained = parent if self.parent is None else self.parent.with_parent(parent)
        return Span(self.file, self.start, self.end, chained)

    def expansion_chain(self) -> tuple[Span, ...]:
        """The call sites this span was expanded through, innermost first."""
        chain: list[Span] = []
        site = self.parent
        while site is not None and len(chain) < 64:
            chain.append(site)
            site = site.parent
        return tuple(chain)

    @property
    def path(self) -> str:
        return self.file.path

    def __str__(self) -> str:
        return f"{self.file.path}:{self.start.line}:{self.start.col}"

    @staticmethod
    def whole(file: SourceFile) -> Span:
        """A span for a diagnostic about the whole file (points at its first character)."""
        return Span(file, Pos(1, 1, 0), Pos(1, 2, min(1, len(file.text))))

    @staticmethod
    def from_offsets(file: SourceFile, start: int, end: int) -> Span:
        return Span(file, file.pos_at(start), file.pos_at(max(start, end)))


@functools.lru_cache(maxsize=8)
def _line_starts(text: str) -> tuple[int, ...]:
    """The offset where each LF-ended line of `text` starts, computed once per text: a file
    with many diagnostics quotes many lines, and rescanning from the top for each made
    rendering them quadratic."""
    starts = [0]
    nl = text.find("\n")
    while nl >= 0:
        starts.append(nl + 1)
        nl = text.find("\n", nl + 1)
    return tuple(starts)
