"""RAPID `MoveExtJ` read back as `move axes`: the mechanical units alone, the arm holding its
joints (ABB RAPID reference, MoveExtJ "Move one or several mechanical units without TCP":
ToJointPos, Speed [\\T], Zone).

The backend writes `move axes M to V` as `MoveExtJ jext, vmax\\T:=t, fine;` to a jointtarget
whose arm joints are 9E+09 (the arm holds) and whose extax holds every driven axis at its new
value, t the planned duration (backends/rapid.py). The RAPID reader keeps that jointtarget as a
comment (it is no joint values) and the line native; with the cell, `absorb_move_ext_j` reads the
pair back as an axes-only move (readers/axes.py maps its slots like any target's), and
`one_mechanism` names the one mechanism whose values it changes against the move before it in
the same block. `t` within the 0.5 ms RAPID's three decimals round off of the axes' own shortest
time (lang/ir_axes.axis_time, the planner's floor) is that time, no `time`; a longer one is
`time t`. A MoveExtJ at another speed or zone, moving no mechanism or several, or with no move
before it in its block, stays native (W510 from the reader, W523 here).
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from dataclasses import replace

from rmot.backends.readers import codes
from rmot.backends.readers.axes_slots import RAPID_UNUSED_FROM
from rmot.backends.readers.model import Document, Move, Native, Stmt, Where
from rmot.lang.diagnostics import Diagnostic, Severity
from rmot.lang.ir_axes import Mechanism, axis_time
from rmot.lang.source import Span

__all__ = ["absorb_move_ext_j", "one_mechanism"]

ROUNDED_S = 0.0006  # RAPID writes \T with three decimals: 0.5 ms, and a margin
_DECL = re.compile(r"(?i)(?:CONST|PERS|VAR)\s+jointtarget\s+(\w+)\s*:=\s*\[\s*\[([^\]]*)\]\s*,\s*\[([^\]]*)\]\s*\]\s*;")
_LINE = re.compile(r"(?i)MoveExtJ\s+(\w+)\s*,\s*vmax\s*(?:\\T\s*:=\s*([0-9.]+))?\s*,\s*fine\s*;")


def _held_targets(doc: Document) -> dict[str, tuple[tuple[float | None, ...], Where]]:
    """The kept jointtargets whose arm joints are all 9E+09: name (upper case) -> (extax slots,
    where the declaration is)."""
    out: dict[str, tuple[tuple[float | None, ...], Where]] = {}
    for kept in doc.kept:
        m = _DECL.fullmatch(kept.text.strip())
        try:
            robax, extax = ([float(v) for v in part.split(",")] for part in m.group(2, 3)) if m else ([], [])
        except ValueError:
            continue
        if m and len(robax) == len(extax) == 6 and all(v >= RAPID_UNUSED_FROM for v in robax) \
                and all(math.isfinite(v) for v in extax):
            out[m.group(1).upper()] = (tuple(None if v >= RAPID_UNUSED_FROM else v for v in extax), kept.where)
    return out


def absorb_move_ext_j(doc: Document, bodies: Callable[..., tuple[Stmt, ...]]) -> Document:
    """`doc` with each native `MoveExtJ NAME, vmax[\\T:=t], fine;` to a held jointtarget as an
    axes-only Move of its slots; the line's W510 and the declaration's W511 dropped, both
    counted imported (the declaration stays in the comment block: a MoveExtJ resolve_axes keeps
    native still shows the values it names)."""
    held = _held_targets(doc) if doc.vendor == "rapid" else {}
    taken: list[Where] = []
    declared: set[Where] = set()

    def absorb(body: tuple[Stmt, ...]) -> tuple[Stmt, ...]:
        out: list[Stmt] = []
        for s in body:
            m = _LINE.fullmatch(s.text.strip()) if isinstance(s, Native) else None
            if m is not None and m.group(1).upper() in held:
                slots, where = held[m.group(1).upper()]
                taken.append(s.where)
                declared.add(where)
                s = Move("joint", "", None, s.where, time=float(m.group(2)) if m.group(2) else None,
                         slots=slots, axes_only=True, source=m.string)
            out.append(s)
        return tuple(out)

    if not held:
        return doc
    routines = tuple(replace(r, body=bodies(r.body, absorb)) for r in doc.routines)
    places = {(w.path, w.line) for w in (*taken, *declared)}
    diags = tuple(d for d in doc.diagnostics if not (d.code in (codes.KEPT_NATIVE, codes.DECLARATION_KEPT)
                                                     and d.span is not None
                                                     and (d.span.file.path, d.span.start.line) in places))
    moved = [w.path for w in (*taken, *declared)]
    counts = tuple(replace(c, imported=c.imported + moved.count(c.path), native=c.native - moved.count(c.path))
                   for c in doc.counts)
    return replace(doc, routines=routines, diagnostics=diags, counts=counts)


def one_mechanism(body: tuple[Stmt, ...], chosen: tuple[Mechanism, ...],
                  values_of: Callable[[Move], tuple[float | None, ...]], span_of: Callable[[Where], Span],
                  diags: list[Diagnostic]) -> tuple[Stmt, ...]:
    """`body` with each axes-only move (its `ext` every chosen mechanism's values) as `move axes`
    of the one mechanism it changes against the move before it in `body`; else native (W523)."""
    out: list[Stmt] = []
    before: tuple[float | None, ...] | None = None
    for s in body:
        if isinstance(s, Move):
            now = values_of(s)
            if s.axes_only and s.ext:
                s = _axes_move(s, now, before, chosen, span_of, diags)
            before = now if now and None not in now else None
        out.append(s)
    return tuple(out)


def _axes_move(move: Move, new: tuple[float | None, ...], old: tuple[float | None, ...] | None,
               chosen: tuple[Mechanism, ...], span_of: Callable[[Where], Span], diags: list[Diagnostic]) -> Move | Native:
    changed, k = [], 0
    for mech in chosen:
        if old is None or new[k:k + len(mech.axes)] != old[k:k + len(mech.axes)]:
            changed.append((mech, k))
        k += len(mech.axes)
    if old is None or len(changed) != 1:
        why = "no move with axis values before it in its block" if old is None else f"it moves {len(changed)} mechanisms"
        diags.append(Diagnostic(codes.AXES_KEPT, Severity.WARNING, "MoveExtJ must move one mechanism after a move "
                                f"of the arm (`move axes`): {why}; kept native", span_of(move.where)))
        return Native("rapid", move.source, move.where)
    mech, first = changed[0]
    shortest = max(axis_time(si_value(a.linear, v) - si_value(a.linear, w), a.speed, a.accel)
                   for a, v, w in zip(mech.axes, new[first:], old[first:]))
    time = None if move.time is None or abs(move.time - shortest) <= ROUNDED_S else move.time
    return replace(move, ext=tuple(e for e in move.ext if e[0] == mech.name), time=time)


def si_value(linear: bool, value: float | None) -> float:
    """An axis value as the vendor files write it (mm, deg; None: not set, 0) in SI units (m, rad)."""
    return (value or 0.0) / 1000.0 if linear else math.radians(value or 0.0)
