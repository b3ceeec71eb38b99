"""Routine keys: a hashable picture of IR instructions as a backend prints them, so proc
calls whose routines would print the same text share one routine (Backend.routine_key).
"""

from __future__ import annotations

from collections.abc import Callable, Hashable
from dataclasses import fields, is_dataclass
from enum import Enum
from typing import Any

import numpy as np

from rmot.backends.task_context import TaskContext, source_ref
from rmot.lang import ir
from rmot.lang.source import Span

__all__ = ["fingerprint", "key_value"]

_NESTED = ("body", "then", "otherwise")  # IR fields holding instructions
_RECORD_FIELDS = ("q_target", "branch", "tcp_pose", "flange_pose", "q_via", "blend_radius")


def fingerprint(nodes: tuple[ir.Instr, ...], ctx: TaskContext,
                 context_key: Callable[[ir.Instr, TaskContext], Hashable]) -> tuple[Hashable, ...]:
    """A hashable picture of `nodes` as a backend prints them (see Backend.routine_key)."""
    out: list[Hashable] = []
    for node in nodes:
        own = tuple(fingerprint(getattr(node, f.name), ctx, context_key) if f.name in _NESTED
                    else key_value(getattr(node, f.name))
                    for f in fields(node) if f.name not in ("uid", "span"))
        rec = ctx.record(node)
        recorded = None if rec is None else tuple(key_value(getattr(rec, name)) for name in _RECORD_FIELDS)
        out.append((type(node).__name__, own, source_ref(getattr(node, "span", None)),
                    recorded, context_key(node, ctx)))
    return tuple(out)


def key_value(v: Any) -> Hashable:
    """`v` as a hashable value: floats rounded to 1e-9, arrays and dataclasses as tuples,
    spans left out (they never print beyond `file:line`)."""
    if v is None or isinstance(v, (str, bool, int, Enum)):
        return v
    if isinstance(v, float):
        return round(v, 9)
    if isinstance(v, Span):
        return None
    if isinstance(v, np.ndarray):
        return ("array", v.shape, tuple(round(float(x), 9) for x in v.ravel()))
    if is_dataclass(v):
        return (type(v).__name__, tuple(key_value(getattr(v, f.name)) for f in fields(v)))
    if isinstance(v, (tuple, list, frozenset, set)):
        items = tuple(key_value(x) for x in v)
        return tuple(sorted(items, key=repr)) if isinstance(v, (set, frozenset)) else items
    if isinstance(v, dict):
        return tuple(sorted(((key_value(k), key_value(x)) for k, x in v.items()), key=repr))
    if isinstance(v, (np.floating, np.integer)):
        return key_value(v.item())
    return repr(v)
