"""Sync barriers and sampling: tasks planned independently, aligned, then sampled.

A barrier is a `sync NAME` (its k-th occurrence in a task pairs with the k-th occurrence of
the same name in every other task that names it). Barriers are processed in an order every
task agrees with; at each, every participating task's arrival time is computed and the tasks
that arrive early hold still (a hold piece is inserted) so that all leave together. Records,
later barriers and variants after the barrier move by the hold. Tasks whose barrier orders
contradict each other (a deadlock on the real controllers) get an error (E229).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from rmot.compiler.plan import codes
from rmot.compiler.plan.timeline import TaskDraft
from rmot.compiler.plan.timing import HoldPiece, Piece
from rmot.lang.plan_types import Trajectory
from rmot.lang.diagnostics import Diagnostic, Severity

__all__ = ["align", "hold_variants", "sample"]


def _keys(draft: TaskDraft) -> list[tuple[str, int]]:
    seen: dict[str, int] = {}
    out = []
    for sync, _, _ in draft.syncs:
        seen[sync.name] = seen.get(sync.name, 0) + 1
        out.append((sync.name, seen[sync.name]))
    return out


def _arrival(draft: TaskDraft, k: int) -> float:
    return float(sum(p.duration for p in draft.pieces[: draft.syncs[k][1]]))


def _hold(draft: TaskDraft, k: int, hold: float) -> None:
    """Insert a hold of `hold` s at draft's k-th sync and shift what follows."""
    sync, pos, rec = draft.syncs[k]
    q = draft.pieces[pos - 1].end_q() if pos > 0 else _first_q(draft)
    draft.pieces.insert(pos, HoldPiece(q, hold))
    draft.syncs[k + 1:] = [(s, p + 1, r) for s, p, r in draft.syncs[k + 1:]]
    draft.records[rec] = replace(draft.records[rec], t_end=draft.records[rec].t_end + hold)
    for i in range(rec + 1, len(draft.records)):
        r = draft.records[i]
        draft.records[i] = replace(r, t_start=r.t_start + hold, t_end=r.t_end + hold)
    for v in draft.variants:
        if v.order > rec:
            v.t0 += hold


def _first_q(draft: TaskDraft) -> np.ndarray:
    assert draft.q is not None
    return draft.pieces[0].sample(np.array([0.0]))[0][0] if draft.pieces else draft.q


def align(drafts: dict[str, TaskDraft]) -> list[Diagnostic]:
    """Align the drafts (in place) at their barriers; returns E229 errors for deadlocks."""
    keys = {name: _keys(d) for name, d in drafts.items()}
    pointer = {name: 0 for name in drafts}
    while True:
        heads = {name: keys[name][pointer[name]] for name in drafts if pointer[name] < len(keys[name])}
        if not heads:
            return []
        ready = next((key for key in heads.values()
                      if all(heads.get(n) == key for n in drafts if key in keys[n])), None)
        if ready is None:
            name, key = next(iter(heads.items()))
            sync = drafts[name].syncs[pointer[name]][0]
            msg = (f"sync '{key[0]}' must be reached in the same order by every task "
                   "(the tasks would wait for each other forever)")
            return [Diagnostic(codes.SYNC_MISMATCH, Severity.ERROR, msg, sync.span, task=name)]
        members = [n for n in drafts if heads.get(n) == ready]
        arrive = {n: _arrival(drafts[n], pointer[n]) for n in members}
        leave = max(arrive.values())
        for n in members:
            if leave - arrive[n] > 0:
                _hold(drafts[n], pointer[n], leave - arrive[n])
            pointer[n] += 1


def hold_variants(draft: TaskDraft) -> None:
    """Hold each variant at the syncs of its continuation until the main timeline leaves them
    (in place; after `align`). A variant that arrives later than the main timeline leaves when
    it arrives: the other tasks are not re-aligned to it (documented limitation)."""
    for v in draft.variants:
        for i, (pos, rec) in enumerate(v.syncs):
            k = v.sync_base + i
            if k >= len(draft.syncs):
                continue
            leave = draft.records[draft.syncs[k][2]].t_end
            arrive = v.t0 + float(sum(p.duration for p in v.pieces[:pos]))
            hold = leave - arrive
            if hold <= 1e-12:
                continue
            q = v.pieces[pos - 1].end_q() if pos > 0 else v.q0
            assert q is not None
            v.pieces.insert(pos, HoldPiece(q, hold))
            v.syncs[i + 1:] = [(p + 1, r) for p, r in v.syncs[i + 1:]]
            draft.records[rec] = replace(draft.records[rec], t_end=draft.records[rec].t_end + hold)
            for j in range(rec + 1, len(draft.records)):
                r = draft.records[j]
                if r.variant == v.index:
                    draft.records[j] = replace(r, t_start=r.t_start + hold, t_end=r.t_end + hold)


def sample(pieces: list[Piece], step: float, t0: float, dof: int, q_rest: np.ndarray) -> Trajectory:
    """Samples every `step` s from t0 to the end of the pieces (the last sample at or after the
    end, holding the final state)."""
    total = float(sum(p.duration for p in pieces))
    n = int(math.ceil(total / step - 1e-9)) + 1
    tl = np.arange(n) * step
    q = np.tile(q_rest, (n, 1)).astype(float)
    qd, qdd = np.zeros((n, dof)), np.zeros((n, dof))
    start = 0.0
    for piece in pieces:  # each piece's samples by bisection: linear in pieces + samples (a
        end = start + piece.duration  # full-length mask per piece made 10,000 waits quadratic)
        if piece.duration > 0:
            lo, hi = int(np.searchsorted(tl, start, "left")), int(np.searchsorted(tl, end, "left"))
            if hi > lo:
                q[lo:hi], qd[lo:hi], qdd[lo:hi] = piece.sample(tl[lo:hi] - start)
        start = end
    if pieces:
        last = tl >= start
        q[last] = pieces[-1].end_q()
    return Trajectory(t0 + tl, q, qd, qdd)
