"""IR -> IR lowerings shared by the backends."""

from __future__ import annotations

from backend_fixtures import span_at

from rmot.backends.lowering import (
    count_instructions, routine_names, split_body,
)
from rmot.lang import ir


def _wait(uid: int) -> ir.WaitTime:
    return ir.WaitTime(uid=uid, duration=0.1 * uid, span=span_at(uid))


def _call(uid: int, proc: str, body: tuple[ir.Instr, ...]) -> ir.ProcCall:
    return ir.ProcCall(uid=uid, proc=proc, args=(), body=body, span=span_at(uid))


class TestSplit:
    def test_short_body_unchanged(self) -> None:
        """A body within the limit is returned as is."""
        body = tuple(_wait(i) for i in range(1, 4))
        assert split_body(body, 3, "main") is body

    def test_long_body_split_in_order(self) -> None:
        """Parts hold at most the limit, keep the order, and are named stem_partK."""
        body = tuple(_wait(i) for i in range(1, 8))
        parts = split_body(body, 3, "main")
        assert [p.proc for p in parts] == ["main_part1", "main_part2", "main_part3"]
        assert [[n.uid for n in p.body] for p in parts] == [[1, 2, 3], [4, 5, 6], [7]]
        assert all(p.uid < 0 for p in parts) and parts[1].span == span_at(4)

    def test_if_counts_with_its_arms(self) -> None:
        """An If is never cut; it counts as itself plus its arms."""
        cond = ir.InputCondition(port=1, value=True)
        big_if = ir.If(uid=10, condition=cond, then=(_wait(11), _wait(12)), span=span_at(10))
        assert count_instructions((big_if,)) == 3
        parts = split_body((_wait(1), big_if, _wait(2)), 3, "m")
        assert [[n.uid for n in p.body] for p in parts] == [[1], [10], [2]]


class TestRoutineNames:
    def test_single_and_repeated_calls(self) -> None:
        """A proc called once keeps its name; repeated calls are numbered in source order."""
        body = (_call(1, "pick", ()), _call(2, "place", ()), _call(3, "pick", (_call(4, "grip", ()),)))
        assert routine_names(body) == {1: "pick_1", 2: "place", 3: "pick_2", 4: "grip"}
