"""The limits of a lowered body (instructions, nesting, free-motion
options) and the counts TaskLowering checks them with."""

from __future__ import annotations

from rmot.lang import ir
from rmot.lang.ir_tree import children, rebuilt
from rmot.lang.source import Span


__all__ = ["MAX_INSTRUCTIONS", "MAX_NESTING", "MAX_FREE_SAMPLES", "MAX_FREE_CLEARANCE_M"]


MAX_INSTRUCTIONS = 200_000


# Policy: blocks nest at most 64 levels. The planner, the verifier and every backend recurse
# once or more per level; under the command line they fail near 125 levels, so 64 keeps every
# stage at half its real limit (tests/robust: a program at the limit compiles to every target).
MAX_NESTING = 64


_KINDS = {"joint": ir.MotionKind.JOINT, "linear": ir.MotionKind.LINEAR, "circular": ir.MotionKind.CIRCULAR,
          "free": ir.MotionKind.JOINT}  # `move free`: a joint move whose path is searched (ir.FreeMotion)


_FREE_OPTIONS = ("clearance", "samples", "budget")


MAX_FREE_SAMPLES = 1_000_000  # policy: a search drawing more would run for hours (about 1 ms a draw)


MAX_FREE_CLEARANCE_M = 1.0  # policy: a larger gap leaves no room in any cell rmot models


_CONFIG = {"shoulder": ir.Shoulder, "elbow": ir.Elbow, "wrist": ir.Wrist}


_CALL_STEPS = 4  # measured: a proc call costs about five statements of lowering


def _node_count(body: tuple[ir.Instr, ...]) -> int:
    n = 0
    for instr in body:
        n += 1
        for sub in children(instr):
            n += _node_count(sub)
    return n


def _expanded_at(instr: ir.Instr, call_site: Span | None) -> ir.Instr:
    """`instr` inlined at `call_site`: its span (and its children's) records the call, so a
    finding in a proc body can say which call it came through (Span.parent)."""
    if call_site is None:
        return instr
    changes: dict[str, object] = {}
    if instr.span is not None:
        changes["span"] = instr.span.with_parent(call_site)
    bodies = tuple(tuple(_expanded_at(i, call_site) for i in sub) for sub in children(instr))
    return rebuilt(instr, bodies, **changes)
