"""Pass 7: sync barriers must pair up across the tasks of a multi-task program.

A sync name used by only one task would wait forever; two tasks passing the same barriers
in a different order would deadlock. Syncs are collected in source order, looking into
proc calls; a sync inside an `if` arm counts too (both arms are verified). A single-task
program's syncs are no-ops and are not checked.
"""

from __future__ import annotations

from rmot.compiler import codes, ir
from rmot.compiler.passes.state import FrontendState

__all__ = ["check_syncs"]


def _syncs(task: ir.Task) -> list[ir.Sync]:
    return [i for i in ir.walk(task.body) if isinstance(i, ir.Sync)]


def check_syncs(state: FrontendState) -> FrontendState:
    prog = state.program
    if prog is None or len(prog.tasks) < 2:
        return state
    rep = state.reporter
    per_task = {t.name: _syncs(t) for t in prog.tasks}
    users: dict[str, list[str]] = {}
    for name, syncs in per_task.items():
        for s in syncs:
            users.setdefault(s.name, [])
            if name not in users[s.name]:
                users[s.name].append(name)
    for name, syncs in per_task.items():
        for s in syncs:
            if len(users[s.name]) == 1:
                rep.error(codes.SYNC_UNMATCHED, f"sync '{s.name}' must appear in at least two tasks (got it only in task '{name}')", s.span)
    tasks = list(per_task)
    for i, a in enumerate(tasks):
        for b in tasks[i + 1:]:
            _compare_order(a, per_task[a], b, per_task[b], state)
    return state


def _compare_order(a: str, sa: list[ir.Sync], b: str, sb: list[ir.Sync], state: FrontendState) -> None:
    shared = {s.name for s in sa} & {s.name for s in sb}
    seq_a = [s for s in sa if s.name in shared]
    seq_b = [s for s in sb if s.name in shared]
    for x, y in zip(seq_a, seq_b):
        if x.name != y.name:
            state.reporter.error(codes.SYNC_ORDER, f"tasks '{a}' and '{b}' must pass their shared syncs in the same order "
                                 f"(got '{x.name}' in '{a}' where '{b}' has '{y.name}')", x.span,
                                 ((f"task '{b}' has '{y.name}' here", y.span),))
            return
    if len(seq_a) != len(seq_b):
        longer, name = (seq_a, a) if len(seq_a) > len(seq_b) else (seq_b, b)
        extra = longer[min(len(seq_a), len(seq_b))]
        other = b if name == a else a
        state.reporter.error(codes.SYNC_ORDER, f"sync '{extra.name}' must be passed as often in task '{other}' as in task '{name}' "
                             f"(got {sum(s.name == extra.name for s in longer)} and "
                             f"{sum(s.name == extra.name for s in (seq_b if name == a else seq_a))})", extra.span)
