"""Diagnostics behaviour that mutation testing (`make mutation`) found untested:
the code registry, carets on empty and multi-line spans, time ranges, span-less text, and
the sink. Expected texts are written out by hand."""

from __future__ import annotations

import pytest

from rmot.lang import codes
from rmot.lang.diagnostics import (
    Code, Diagnostic, DiagnosticSink, Severity, all_codes, render, render_all,
)
from rmot.lang.source import Pos, SourceFile, Span


class TestRegistry:
    def test_registering_an_equal_code_again_is_allowed_and_keeps_it(self) -> None:
        again = Code(codes.SYNTAX.id, codes.SYNTAX.name, codes.SYNTAX.summary)
        assert again == codes.SYNTAX
        listed = all_codes()
        assert codes.SYNTAX in listed and all(isinstance(c, Code) for c in listed)
        assert [c.id for c in listed] == sorted(c.id for c in listed)
        assert next(c for c in listed if c.id == codes.SYNTAX.id) is codes.SYNTAX  # the first stays

    def test_an_id_taken_by_another_name_is_refused(self) -> None:
        with pytest.raises(ValueError, match=f"{codes.SYNTAX.id} registered twice"):
            Code(codes.SYNTAX.id, "something-else", "another meaning")
        assert codes.SYNTAX in all_codes()
        assert str(codes.SYNTAX) == codes.SYNTAX.id


def _d(span: Span | None, message: str = "msg", **extra: object) -> Diagnostic:
    return Diagnostic(codes.SYNTAX, Severity.ERROR, message, span, **extra)  # type: ignore[arg-type]


class TestCarets:
    def test_a_span_running_onto_the_next_line_is_underlined_to_its_line_end(self) -> None:
        src = SourceFile("f.rmot", "abc def\nxyz\n")
        text = render(_d(Span(src, Pos(1, 5, 4), Pos(2, 2, 9))))
        assert text.splitlines()[1:] == [" 1 | abc def", "   |     ^~~"]  # d, e, f

    def test_an_empty_line_of_a_file_still_shows_its_gutter_and_caret(self) -> None:
        src = SourceFile("f.rmot", "a\n\nb\n")
        text = render(_d(Span(src, Pos(2, 1, 2), Pos(2, 1, 2))))
        assert text.splitlines()[1:] == [" 2 | ", "   | ^"]

    def test_an_empty_file_shows_line_1_but_nothing_past_it(self) -> None:
        empty = SourceFile("e.rmot", "")
        assert render(_d(Span(empty, Pos(1, 1, 0), Pos(1, 1, 0)))).splitlines()[1:] == [" 1 | ", "   | ^"]
        assert render(_d(Span(empty, Pos(2, 1, 0), Pos(2, 1, 0)))).splitlines() == [
            "e.rmot:2:1: error[E001]: msg"]


class TestTextWithoutSpans:
    def test_a_diagnostic_without_a_span_names_rmot(self) -> None:
        assert render(_d(None)) == "rmot: error[E001]: msg"

    def test_a_note_without_a_span_is_indented(self) -> None:
        assert render(_d(None, notes=(("see the manual", None),))).splitlines() == [
            "rmot: error[E001]: msg", "  note: see the manual"]


class TestTimes:
    @pytest.mark.parametrize(("t0", "t1", "shown"), [
        (1.0, None, " (at t=1.000 s)"),
        (1.0, 1.0, " (at t=1.000 s)"),  # an instant, not a range
        (1.0, 2.5, " (at t=1.000..2.500 s)"),
        (2.0, 1.0, " (at t=2.000 s)"),
    ])
    def test_time_or_time_range(self, t0: float, t1: float | None, shown: str) -> None:
        assert render(_d(None, time_s=t0, end_time_s=t1)) == f"rmot: error[E001]: msg{shown}"


class TestSink:
    def test_sink_keeps_every_item_in_order_with_its_severity(self) -> None:
        sink = DiagnosticSink()
        sink.warning(codes.SYNTAX, "w", None)
        assert not sink.has_errors and len(sink) == 1
        sink.error(codes.SYNTAX, "e", None, time_s=1.0)
        sink.add(_d(None, "a"))
        sink.extend([_d(None, "b")])
        assert [(d.severity, d.message) for d in sink.items] == [
            (Severity.WARNING, "w"), (Severity.ERROR, "e"), (Severity.ERROR, "a"), (Severity.ERROR, "b")]
        assert sink.items[1].time_s == 1.0
        assert sink.has_errors and len(sink) == 4
        assert sink.errors_since(0) and sink.errors_since(1) and not sink.errors_since(4)
        sink2 = DiagnosticSink()
        sink2.warning(codes.SYNTAX, "w", None)
        sink2.error(codes.SYNTAX, "e", None)
        assert sink2.errors_since(1) and not DiagnosticSink().errors_since(0)
        warn_only = DiagnosticSink()
        warn_only.warning(codes.SYNTAX, "w1", None)
        warn_only.warning(codes.SYNTAX, "w2", None)
        assert not warn_only.errors_since(0)

    def test_sink_keeps_code_span_and_extra_fields(self) -> None:
        src = SourceFile("f.rmot", "abc\n")
        span = Span(src, Pos(1, 1, 0), Pos(1, 2, 1))
        sink = DiagnosticSink()
        sink.error(codes.SYNTAX, "e", span, time_s=1.0)
        sink.warning(codes.UNKNOWN_UNIT, "w", span, time_s=2.0, bodies=("a",))
        e, w = sink.items
        assert (e.code, e.span, e.time_s) == (codes.SYNTAX, span, 1.0)
        assert (w.code, w.span, w.time_s, w.bodies) == (codes.UNKNOWN_UNIT, span, 2.0, ("a",))


def test_render_all_is_one_diagnostic_after_the_other() -> None:
    a, b = _d(None, "first"), _d(None, "second")
    assert render_all([a, b]) == "rmot: error[E001]: first\nrmot: error[E001]: second"
    assert render_all(()) == ""
