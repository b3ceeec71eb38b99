"""Pass 7: sync barriers must line up across the tasks of a multi-task program.

A barrier waits for every task: RAPID's WaitSyncTask names all tasks, and the I/O
handshake of the other backends counts barriers per task. So in a multi-task program every
`sync NAME` must appear in every task, as often, and all tasks must pass their barriers in
the same order; otherwise a controller waits forever. Syncs are collected in source order,
looking into proc calls. A sync inside an `if` arm cannot be aligned (only one arm runs,
and the controllers would wait inside the IF), so it is an error in any program. A
single-task program's syncs are no-ops and are otherwise not checked.
"""

from __future__ import annotations

from rmot.lang import check_codes as codes, ir, ir_tree
from rmot.compiler.passes.state import FrontendState
from rmot.lang.source import Span

__all__ = ["check_syncs"]


def _syncs(body: tuple[ir.Instr, ...], conditional: list[ir.Sync]) -> list[ir.Sync]:
    """The syncs of `body` that always run, in source order (into proc calls and every loop
    iteration); syncs in bodies that may not run (if arms, whiles, timeout branches) go to
    `conditional`."""
    out: list[ir.Sync] = []
    for instr in body:
        if isinstance(instr, ir.Sync):
            out.append(instr)
            continue
        runs, bodies = ir_tree.flow(instr)
        if runs.sure:
            for sub in bodies:
                out.extend(_syncs(sub, conditional))
        else:
            conditional.extend(i for i in ir_tree.walk_bodies(bodies) if isinstance(i, ir.Sync))
    return out


def check_syncs(state: FrontendState) -> FrontendState:
    prog = state.program
    if prog is None:
        return state
    rep = state.reporter
    conditional: dict[str, list[ir.Sync]] = {t.name: [] for t in prog.tasks}
    per_task = {t.name: _syncs(t.body, conditional[t.name]) for t in prog.tasks}
    for s in (s for syncs in conditional.values() for s in syncs):
        rep.error(codes.MISPLACED, f"sync '{s.name}' must not be inside an 'if' arm (got it in an arm: only one arm runs, "
                  "so the other tasks could not meet it; move it before or after the 'if')", s.span)
    if len(prog.tasks) < 2:
        return state
    tasks = {t.name: t for t in prog.tasks}
    first_use: dict[str, tuple[str, ir.Sync]] = {}
    for name, syncs in per_task.items():
        for s in syncs:
            first_use.setdefault(s.name, (name, s))
    everywhere = set(first_use) - {s.name for syncs in conditional.values() for s in syncs}
    for barrier, (owner, use) in first_use.items():
        for name, syncs in per_task.items():
            if all(s.name != barrier for s in syncs + conditional[name]):  # an `if` sync has its own error
                everywhere.discard(barrier)
                rep.error(codes.SYNC_UNMATCHED, f"sync '{barrier}' must appear in every task (got none in task '{name}')",
                          _header(tasks[name]) or use.span, ((f"task '{owner}' has sync '{barrier}' here", use.span),))
    names = list(per_task)
    for other in names[1:]:
        _compare_order(names[0], per_task[names[0]], other, per_task[other], everywhere, state)
    return state


def _header(task: ir.Task) -> Span | None:
    """The task's first line (a whole task block would be a long underline)."""
    span = task.span
    if span is None:
        return None
    line_end = span.file.text.find("\n", span.start.offset)
    end = span.end.offset if line_end < 0 else min(span.end.offset, line_end)
    return Span.from_offsets(span.file, span.start.offset, end)


def _compare_order(a: str, sa: list[ir.Sync], b: str, sb: list[ir.Sync], shared: set[str], state: FrontendState) -> None:
    seq_a = [s for s in sa if s.name in shared]
    seq_b = [s for s in sb if s.name in shared]
    for x, y in zip(seq_a, seq_b):
        if x.name != y.name:
            state.reporter.error(codes.SYNC_ORDER, f"tasks '{a}' and '{b}' must pass their syncs in the same order "
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
