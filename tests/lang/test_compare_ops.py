"""CompareOp.negated and .mirrored against Python's own comparisons (the operator module), on
every ordered pair of a few numbers, ties included."""

from __future__ import annotations

import itertools
import operator

import pytest

from rmot.lang.ir import CompareOp

PYTHON = {"==": operator.eq, "!=": operator.ne, "<": operator.lt, "<=": operator.le, ">": operator.gt, ">=": operator.ge}
VALUES = (-1.5, 0.0, 0.0, 2.0)


@pytest.mark.parametrize("op", list(CompareOp))
def test_negated_holds_exactly_when_the_comparison_does_not(op: CompareOp) -> None:
    for a, b in itertools.product(VALUES, repeat=2):
        assert PYTHON[op.negated().value](a, b) is (not PYTHON[op.value](a, b)), (op, a, b)


@pytest.mark.parametrize("op", list(CompareOp))
def test_mirrored_with_swapped_operands_means_the_same(op: CompareOp) -> None:
    for a, b in itertools.product(VALUES, repeat=2):
        assert PYTHON[op.mirrored().value](b, a) is PYTHON[op.value](a, b), (op, a, b)
