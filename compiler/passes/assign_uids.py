"""Pass 8: number every instruction, unique within the Program, in source order.

Numbering runs after unrolling and inlining, task by task, parent before children (the
order of ir.walk): an If or ProcCall gets its uid before the instructions it holds.
"""

from __future__ import annotations

from dataclasses import replace
from itertools import count
from typing import Iterator

from rmot.compiler import ir
from rmot.compiler.passes.state import FrontendState

__all__ = ["assign_uids", "number"]


def number(body: tuple[ir.Instr, ...], counter: Iterator[int]) -> tuple[ir.Instr, ...]:
    out: list[ir.Instr] = []
    for instr in body:
        uid = next(counter)
        if isinstance(instr, ir.If):
            then = number(instr.then, counter)
            otherwise = number(instr.otherwise, counter)
            out.append(replace(instr, uid=uid, then=then, otherwise=otherwise))
        elif isinstance(instr, ir.ProcCall):
            out.append(replace(instr, uid=uid, body=number(instr.body, counter)))
        else:
            out.append(replace(instr, uid=uid))
    return tuple(out)


def assign_uids(state: FrontendState) -> FrontendState:
    if state.program is None:
        return state
    counter = count(1)
    tasks = tuple(replace(t, body=number(t.body, counter)) for t in state.program.tasks)
    return replace(state, program=replace(state.program, tasks=tasks))
