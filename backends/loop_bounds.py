"""The IR's `Loop.last` read as the last value the loop runs (issue #15 adapter).

The front end (compiler/passes/lower_body.py) stores `for i in a .. b` with `last = b`, the end
excluded (`range(a, b)`), and `repeat n` with `last = n`; backends/loops.py reads `last` as
the last value run (inclusive). Until the two agree, the Fanuc, INFORM and VAL3 emitters hand
loops.analyse a copy whose `last` is the value of the loop's last iteration (every nested loop
too), which is right under either reading: the iterations are what the plan verified."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import fields, is_dataclass, replace
from typing import Any

from rmot.backends.loops import LoopTemplate, Unrolled
from rmot.compiler import ir

__all__ = ["analyse_peeled", "inclusive_last"]


def inclusive_last(loop: ir.Loop) -> ir.Loop:
    """`loop` (and every loop nested in it) with `last` = the value of its last iteration."""
    iterations = tuple(replace(it, body=tuple(_fix(n) for n in it.body)) for it in loop.iterations)
    last = iterations[-1].value if iterations else loop.last
    return replace(loop, last=last, iterations=iterations)


def _fix(v: Any) -> Any:
    if isinstance(v, ir.Loop):
        return inclusive_last(v)
    if isinstance(v, tuple):
        return tuple(_fix(x) for x in v)
    if (
        is_dataclass(v)
        and not isinstance(v, type)
        and any(isinstance(getattr(v, f.name), tuple) for f in fields(v))
    ):
        return replace(
            v,
            **{
                f.name: _fix(getattr(v, f.name))
                for f in fields(v)
                if f.init and isinstance(getattr(v, f.name), tuple)
            },
        )
    return v


def analyse_peeled(
    loop: ir.Loop, analyse_one: Callable[[ir.Loop], LoopTemplate | Unrolled]
) -> tuple[LoopTemplate | Unrolled, ir.LoopIteration | None, str]:
    """(template or reason, the last iteration written after the loop or None, the note).

    A loop's last iteration often differs from the others only where the task goes on after
    the loop (its last move blends into what follows instead of stopping where the next
    iteration waits). When the whole loop cannot be one vendor loop but all iterations but the
    last can, the loop is written for those and the last iteration after it, on its own; the
    note says why (loops.analyse's reason for the whole loop)."""
    whole = analyse_one(inclusive_last(loop))
    if isinstance(whole, LoopTemplate) or len(loop.iterations) < 3:
        return whole, None, ""
    head = analyse_one(inclusive_last(replace(loop, iterations=loop.iterations[:-1])))
    if isinstance(head, Unrolled):
        return whole, None, ""
    last = loop.iterations[-1]
    name = loop.var or "iteration"
    return (
        head,
        last,
        (
            f"{whole.message}; written as a loop to {name} = {loop.iterations[-2].value} "
            f"and the last iteration ({name} = {last.value}) after it"
        ),
    )
