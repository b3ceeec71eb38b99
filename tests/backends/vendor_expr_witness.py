"""A tiny evaluator of RAPID and KRL expressions for the import tests, written from the vendors'
operator priorities (RAPID kernel manual, "priority between operators"; KSS 8.x, "priority of
operators"), independent of backends/readers/logic.py: numbers, TRUE/FALSE, NOT, parentheses,
binary operators by priority (left-associative), and the vendor's own reads by `leaf`."""

from __future__ import annotations

import re
from collections.abc import Callable

__all__ = ["evaluate", "RAPID_PRIORITY", "KRL_PRIORITY"]

RAPID_PRIORITY = {"OR": 1, "AND": 2, "=": 3, "<>": 3, "<": 3, "<=": 3, ">": 3, ">=": 3, "+": 4, "-": 4, "*": 5, "/": 5}
KRL_PRIORITY = {"==": 1, "<>": 1, "<": 1, "<=": 1, ">": 1, ">=": 1, "OR": 2, "AND": 4, "+": 5, "-": 5, "*": 6, "/": 6}
_APPLY: dict[str, Callable[[object, object], object]] = {
    "OR": lambda a, b: a or b, "AND": lambda a, b: a and b, "=": lambda a, b: a == b, "==": lambda a, b: a == b,
    "<>": lambda a, b: a != b, "<": lambda a, b: a < b, "<=": lambda a, b: a <= b,  # type: ignore[operator]
    ">": lambda a, b: a > b, ">=": lambda a, b: a >= b, "+": lambda a, b: a + b,  # type: ignore[operator]
    "-": lambda a, b: a - b, "*": lambda a, b: a * b, "/": lambda a, b: a / b}  # type: ignore[operator]


def evaluate(text: str, priority: dict[str, int], leaf: Callable[[list[str], int], tuple[object, int]],
             *, int_division: bool = False) -> object:
    """The value of `text`; `leaf(tokens, i)`: a name or read's value and how many tokens it takes.
    `int_division`: a number without a point is an INT and INT / INT drops the fraction (KRL:
    KSS 8.x Programming for System Integrators, "Arithmetic operators": both operands INT, the
    result is INT, its decimal places cut off)."""
    tokens = re.findall(r"\$IN\[\d+\]|\d+\.?\d*|\w+|<>|<=|>=|==|[-+*/()<>=]", text)
    pos = [0]

    def atom() -> object:
        t = tokens[pos[0]]
        if t == "(":
            pos[0] += 1
            v = expr(0)
            pos[0] += 1
            return v
        if t.upper() == "NOT":
            pos[0] += 1
            return not atom()
        if t.upper() in ("TRUE", "FALSE"):
            pos[0] += 1
            return t.upper() == "TRUE"
        if re.fullmatch(r"[\d.]+", t):
            pos[0] += 1
            return int(t) if int_division and "." not in t else float(t)
        value, used = leaf(tokens, pos[0])
        pos[0] += used
        return value

    def expr(floor: int) -> object:
        left = atom()
        while pos[0] < len(tokens) and priority.get(tokens[pos[0]].upper(), 0) > floor:
            op = tokens[pos[0]].upper()
            pos[0] += 1
            right = expr(priority[op])
            whole = int_division and op == "/" and isinstance(left, int) and isinstance(right, int)
            left = int(left / right) if whole else _APPLY[op](left, right)  # type: ignore[operator]
        return left

    return expr(0)
