"""The "expected ..." list of a syntax error: at most six alternatives, then "..." (a
mutation of the cut-off would otherwise survive every test)."""

from __future__ import annotations

import pytest

from rmot.lang.parse import expected_in_words

# terminal names the grammar does not have: each reads as its name in lower case
_NAMES = ["ALPHA", "BRAVO", "CHARLIE", "DELTA", "ECHO", "FOXTROT", "GOLF", "HOTEL"]


def _items(text: str) -> list[str]:
    """The alternatives of 'a, b, c or d' (written out independently of the code)."""
    head, _, last = text.rpartition(" or ")
    return [*head.split(", "), last] if head else [last]


@pytest.mark.parametrize("n", range(1, len(_NAMES) + 1))
def test_at_most_six_alternatives_then_an_ellipsis(n: int) -> None:
    """1..6 alternatives are all listed in order; from 7 on, the first six and '...'."""
    words = [name.lower() for name in _NAMES[:n]]
    expected = words if n <= 6 else [*words[:6], "..."]
    assert _items(expected_in_words(set(_NAMES[:n]))) == expected


def test_one_alternative_is_the_word_alone() -> None:
    assert expected_in_words({"ALPHA"}) == "alpha"
