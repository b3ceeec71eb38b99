"""Diagnostics render like a compiler: location, code, message, source line and carets."""

from __future__ import annotations

from rmot.lang.diagnostics import Amount, Code, Diagnostic, Severity, render
from rmot.lang.source import Pos, SourceFile, Span

TEST_CODE = Code("E999", "test-only", "a code used by the diagnostics tests")


def _span(text: str, line: int, col: int, end_col: int) -> Span:
    src = SourceFile("cell.rmot", text)
    return Span(src, Pos(line, col), Pos(line, end_col))


def test_render_shows_location_code_line_and_carets() -> None:
    """The first line is file:line:col: severity[CODE]: message; then the line and ^~~."""
    text = "program p on r1 {\n  move joint hme\n}\n"
    d = Diagnostic(TEST_CODE, Severity.ERROR, "unknown name 'hme'", _span(text, 2, 14, 17))
    assert render(d).splitlines() == [
        "cell.rmot:2:14: error[E999]: unknown name 'hme'",
        " 2 |   move joint hme",
        "   |              ^~~",
    ]


def test_render_notes_point_at_their_own_site() -> None:
    """A note with a span renders its own location and caret (e.g. 'first defined here')."""
    text = "target a = joints(0,0,0,0,0,0) deg\ntarget a = joints(0,0,0,0,0,0) deg\n"
    first = _span(text, 1, 8, 9)
    d = Diagnostic(TEST_CODE, Severity.ERROR, "duplicate", _span(text, 2, 8, 9), notes=(("first defined here", first),))
    lines = render(d).splitlines()
    assert lines[3] == "cell.rmot:1:8: note: first defined here"
    assert lines[5] == "   |        ^"


def test_render_includes_time_interval_of_findings() -> None:
    """Verification findings say when: the interval in seconds follows the message."""
    d = Diagnostic(
        TEST_CODE, Severity.WARNING, "close", _span("move\n", 1, 1, 5),
        time_s=1.25, end_time_s=1.5, amount=Amount(3.0, "mm"),
    )
    assert render(d).splitlines()[0] == "cell.rmot:1:1: warning[E999]: close (at t=1.250..1.500 s)"


def test_registering_a_code_twice_with_another_name_fails() -> None:
    """Codes are unique: one id, one meaning."""
    try:
        Code("E999", "other-name", "clash")
    except ValueError as exc:
        assert "E999" in str(exc)
    else:
        raise AssertionError("duplicate code id accepted")


def test_a_span_inside_an_inlined_proc_names_its_call_sites() -> None:
    """A diagnostic in a proc body shows each call it was expanded through, innermost first."""
    lib = SourceFile("lib.rmot", "proc pick(p: pose) {\n  move linear p\n}\n")
    main = SourceFile("main.rmot", "pick(a)\npick(b)\n")
    body = Span(lib, Pos(2, 3), Pos(2, 16))
    outer = Span(main, Pos(2, 1), Pos(2, 8))
    inner = Span(main, Pos(1, 1), Pos(1, 8)).with_parent(outer)
    expanded = body.with_parent(inner)
    assert expanded == body  # the parent never changes equality
    assert [str(s) for s in expanded.expansion_chain()] == ["main.rmot:1:1", "main.rmot:2:1"]
    lines = render(Diagnostic(TEST_CODE, Severity.ERROR, "unreachable", expanded)).splitlines()
    assert lines[0] == "lib.rmot:2:3: error[E999]: unreachable"
    assert lines[3] == "main.rmot:1:1: note: in the proc call here"
    assert lines[4] == " 1 | pick(a)"
    assert lines[6] == "main.rmot:2:1: note: in the proc call here"
