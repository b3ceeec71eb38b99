"""The front end's Reporter drops exact repeats only (a mutation of its warning
de-duplication survived every test)."""

from __future__ import annotations

import pytest

from rmot.lang import check_codes as codes
from rmot.compiler.passes.context import Reporter
from rmot.lang.diagnostics import Severity
from rmot.lang.source import SourceFile, Span

_FILE = SourceFile("/virtual/r.rmot", "wait 1 s\nwait 2 s\n")


def _span(start: int, end: int) -> Span:
    return Span.from_offsets(_FILE, start, end)


@pytest.mark.parametrize("kind", ["error", "warning"])
def test_exact_repeats_are_reported_once(kind: str) -> None:
    """The same code, message and place three times (a loop body unrolled) is one diagnostic,
    of the right severity."""
    rep = Reporter()
    for _ in range(3):
        getattr(rep, kind)(codes.UNKNOWN_NAME, "unknown name 'x'", _span(0, 4))
    (d,) = rep.sink.items
    assert d.severity is (Severity.ERROR if kind == "error" else Severity.WARNING)
    assert rep.has_errors is (kind == "error")


@pytest.mark.parametrize("kind", ["error", "warning"])
def test_anything_different_is_reported_again(kind: str) -> None:
    """Another message, another place or another code is another diagnostic."""
    rep = Reporter()
    report = getattr(rep, kind)
    report(codes.UNKNOWN_NAME, "unknown name 'x'", _span(0, 4))
    report(codes.UNKNOWN_NAME, "unknown name 'y'", _span(0, 4))
    report(codes.UNKNOWN_NAME, "unknown name 'x'", _span(9, 13))
    report(codes.UNKNOWN_NAME, "unknown name 'x'", _span(0, 5))
    report(codes.WRONG_TYPE, "unknown name 'x'", _span(0, 4))
    report(codes.UNKNOWN_NAME, "unknown name 'x'", None)
    report(codes.UNKNOWN_NAME, "unknown name 'x'", None)
    assert len(rep.sink.items) == 6
