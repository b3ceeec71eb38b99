"""IR -> IR transforms shared by the vendor backends (sqlglot's transforms.py).

Each function takes a task body and returns a new one, keeping every node's uid and span
(records and diagnostics keep pointing at the source). Nodes a lowering creates that have no
source instruction get negative uids (never looked up in the plan's records).

`sync` for vendors without a multi-robot barrier is lowered by backends/handshake.py (its
convention — the cell's "sync" signals and the level-toggling handshake — is documented there);
it needs the cell and the robot (Backend.lowered_body).
"""

from __future__ import annotations

from collections.abc import Callable, Hashable, Iterator

from rmot.lang import ir, ir_tree

__all__ = [
    "count_instructions", "iter_proc_calls", "routine_names", "split_body",
]


def count_instructions(body: tuple[ir.Instr, ...]) -> int:
    """Instructions in `body`, counting into If arms but not into ProcCall bodies (own routines)."""
    n = 0
    for node in body:
        n += 1
        runs, bodies = ir_tree.flow(node)
        if runs is ir_tree.Runs.ONE_OF:
            n += sum(count_instructions(sub) for sub in bodies)
    return n


def split_body(body: tuple[ir.Instr, ...], max_instructions: int, stem: str) -> tuple[ir.Instr, ...]:
    """Split a long body into ProcCall parts `stem_part1`, `stem_part2`, ... of at most
    `max_instructions` top-level instructions each (an If counts with its arms).

    Returns `body` unchanged when it fits. The parts carry the span of their first
    instruction and negative uids.
    """
    if count_instructions(body) <= max_instructions:
        return body
    parts: list[list[ir.Instr]] = [[]]
    size = 0
    for node in body:
        n = count_instructions((node,))
        if parts[-1] and size + n > max_instructions:
            parts.append([])
            size = 0
        parts[-1].append(node)
        size += n
    return tuple(
        ir.ProcCall(uid=-(k + 1) * 1_000_000, proc=f"{stem}_part{k + 1}", args=(), body=tuple(p),
                    span=getattr(p[0], "span", None))
        for k, p in enumerate(parts)
    )


def iter_proc_calls(body: tuple[ir.Instr, ...]) -> Iterator[ir.ProcCall]:
    """Every ProcCall in source order, outer before inner, including those inside If arms."""
    for node in ir_tree.walk(body):
        if isinstance(node, ir.ProcCall):
            yield node


def routine_names(body: tuple[ir.Instr, ...],
                  key: Callable[[ir.ProcCall], Hashable] | None = None) -> dict[int, str]:
    """A routine name per ProcCall uid. Calls of one proc with equal `key` (the text their
    routine would print: see Backend.routine_key) share one routine; without `key` every call
    is its own. A proc whose calls all share one routine keeps the proc's name; otherwise its
    routines are `name_1`, `name_2`, ... in the source order of their first call."""
    calls = list(iter_proc_calls(body))
    variant: dict[int, tuple[str, int]] = {}  # uid -> (proc, variant number from 1)
    seen: dict[str, dict[Hashable, int]] = {}
    for call in calls:
        keys = seen.setdefault(call.proc, {})
        k = key(call) if key is not None else call.uid
        variant[call.uid] = (call.proc, keys.setdefault(k, len(keys) + 1))
    return {uid: proc if len(seen[proc]) == 1 else f"{proc}_{n}" for uid, (proc, n) in variant.items()}
