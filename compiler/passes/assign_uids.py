"""Pass 8: number every instruction, unique within the Program, in source order.

Numbering runs after unrolling and inlining, task by task, parent before children (the
order of ir.walk): an If or ProcCall gets its uid before the instructions it holds.
"""

from __future__ import annotations

from dataclasses import replace
from itertools import count
from typing import Iterator

from rmot.lang import ir
from rmot.lang.ir_tree import children, rebuilt
from rmot.compiler.passes.state import FrontendState

__all__ = ["assign_uids", "number"]


def number(body: tuple[ir.Instr, ...], counter: Iterator[int]) -> tuple[ir.Instr, ...]:
    out: list[ir.Instr] = []
    for instr in body:
        uid = next(counter)  # parent first, then every body in order (each Loop iteration too)
        bodies = tuple(number(sub, counter) for sub in children(instr))
        out.append(rebuilt(instr, bodies, uid=uid))
    return tuple(out)


def assign_uids(state: FrontendState) -> FrontendState:
    if state.program is None:
        return state
    counter = count(1)
    tasks = tuple(replace(t, body=number(t.body, counter)) for t in state.program.tasks)
    return replace(state, program=replace(state.program, tasks=tasks))
