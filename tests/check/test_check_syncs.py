"""Sync barriers: every barrier in every task, same count and order; never inside an `if` arm."""

from __future__ import annotations

from pathlib import Path

from rmot.compiler.frontend import load_text
from rmot.lang.parse import parse_text

BAD = Path(__file__).resolve().parents[1] / "data" / "bad"


def _load(body: str):  # type: ignore[no-untyped-def]
    text = f'use cell "support/three_robots.rmot"\nprogram p {{\n{body}}}\n'
    return load_text(text, str(BAD / "probe.rmot"))


def test_barrier_missing_in_third_task_names_it_with_a_note_at_a_user() -> None:
    """Two of three tasks meeting at a barrier would deadlock: error at the third, note at a user."""
    result = _load("  task r1 { sync meet }\n  task r2 { sync meet }\n  task r3 { wait 1 s }\n")
    (err,) = [d for d in result.diagnostics if d.is_error]
    assert err.code.id == "E113" and "task 'r3'" in err.message
    assert err.span.start.line == 5
    (note,) = err.notes
    assert "task 'r1'" in note[0] and note[1].start.line == 3


def test_three_tasks_with_the_same_barriers_are_accepted() -> None:
    """Every task passing the same barriers in the same order is a valid program."""
    body = "".join(f"  task {r} {{ sync a; wait 1 s; sync b }}\n" for r in ("r1", "r2", "r3"))
    result = _load(body)
    assert not result.has_errors, [d.message for d in result.diagnostics]
    assert len(result.program.tasks) == 3


def test_order_is_compared_against_every_task() -> None:
    """A third task with a swapped order is E114 even when the first two agree."""
    result = _load("  task r1 { sync a; sync b }\n  task r2 { sync a; sync b }\n  task r3 { sync b; sync a }\n")
    assert [d.code.id for d in result.diagnostics if d.is_error] == ["E114"]


def test_sync_inside_if_arm_is_an_error_at_the_sync() -> None:
    """A conditional barrier cannot be aligned: E115 at the sync, no follow-on E113/E114."""
    body = "  task r1 { if in[1] == on { sync a } }\n  task r2 { sync a }\n  task r3 { sync a }\n"
    errors = [d for d in _load(body).diagnostics if d.is_error]
    assert [d.code.id for d in errors] == ["E115"]
    assert "'if' arm" in errors[0].message and errors[0].span.start.col == 30


def test_return_is_reserved_with_a_clear_message() -> None:
    """`return` says it is reserved, not 'did you mean return'."""
    (d,) = parse_text("proc f() {\n  return\n}\n").diagnostics
    assert d.code.id == "E008"
    assert "'return' is reserved for future use: procs end at their closing brace" in d.message
    assert "did you mean" not in d.message


def test_return_call_is_the_reserved_error_alone() -> None:
    """`return()` parses as a call: one E008, no follow-on 'unknown proc'."""
    result = load_text("program p {\n  return()\n}\n", str(BAD / "probe.rmot"))
    assert [d.code.id for d in result.diagnostics] == ["E008"]
