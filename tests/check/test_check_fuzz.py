"""Property tests: no input makes the front end raise, and every diagnostic points inside its file."""

from __future__ import annotations

import re
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from rmot.compiler.frontend import FrontendResult, load_text
from rmot.lang.diagnostics import render

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = sorted((ROOT / "examples").glob("*.rmot")) + sorted((ROOT / "examples").glob("*/*.rmot"))
_TOKEN = re.compile(r'"(?:[^"\\\n]|\\.)*"|[A-Za-z_][A-Za-z0-9_]*|\d+(?:\.\d+)?|\.\.|==|!=|\s+|.', re.S)
_FUZZ = settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def _check(result: FrontendResult) -> None:
    for d in result.diagnostics:
        render(d)
        for span in [d.span, *(s for _, s in d.notes)]:
            if span is None:
                continue
            text = span.file.text
            assert 0 <= span.start.offset <= span.end.offset <= len(text), (d.message, span)
            pos = span.file.pos_at(span.start.offset)
            assert (pos.line, pos.col) == (span.start.line, span.start.col), (d.message, span)
    if result.program is not None:
        assert not result.has_errors


@_FUZZ
@given(st.text(max_size=300))
def test_random_text_never_raises(text: str) -> None:
    """Arbitrary unicode text gives diagnostics, never an exception."""
    _check(load_text(text, str(ROOT / "examples" / "fuzz.rmot")))


@_FUZZ
@given(st.lists(st.sampled_from(list("{}()[];\n =.,\"#+-*/%^") + ["move", "joint", "linear", "pose", "x", "mm", "10",
                                                                    "program", "p", "on", "r1", "to", "else", " "]),
                max_size=60).map("".join))
def test_random_token_soup_never_raises(text: str) -> None:
    """Grammar-shaped noise reaches deeper parser states without raising."""
    _check(load_text(text, str(ROOT / "examples" / "fuzz.rmot")))


@st.composite
def mutated_example(draw: st.DrawFn) -> tuple[Path, str]:
    path = draw(st.sampled_from(EXAMPLES))
    tokens = _TOKEN.findall(path.read_text(encoding="utf-8"))
    for _ in range(draw(st.integers(1, 3))):
        i = draw(st.integers(0, len(tokens) - 1))
        op = draw(st.sampled_from(["delete", "duplicate", "swap", "replace"]))
        if op == "delete":
            del tokens[i]
        elif op == "duplicate":
            tokens.insert(i, tokens[i])
        elif op == "swap" and i + 1 < len(tokens):
            tokens[i], tokens[i + 1] = tokens[i + 1], tokens[i]
        elif op == "replace":
            tokens[i] = draw(st.sampled_from(tokens))
    return path, "".join(tokens)


@_FUZZ
@given(mutated_example())
def test_token_mutations_of_every_example_never_raise(case: tuple[Path, str]) -> None:
    """Delete / duplicate / swap / replace tokens of a shipped example: diagnostics only, all inside the file."""
    path, text = case
    _check(load_text(text, str(path)))


def test_every_example_is_clean() -> None:
    """The shipped examples lower without a diagnostic (the mutations start from valid text)."""
    for path in EXAMPLES:
        result = load_text(path.read_text(encoding="utf-8"), str(path))
        assert result.diagnostics == (), (path, [render(d) for d in result.diagnostics])
