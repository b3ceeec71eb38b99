"""One rule for every table keyed by ir.MotionKind: it has a handler for each kind.

The planner (compiler/plan/segments.py: how a kind's joint path is built) and every backend
(backends/base.py `Backend.MOVES`: which method prints a kind) declare a table kind -> handler
and check it here when they are imported. A kind added to ir.MotionKind without a handler in
one of them is an import-time error naming the table, never a silent default (such as
printing every move that is neither joint nor linear as a circle).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from enum import Enum

from rmot.lang import ir

__all__ = ["MissingMotionHandler", "require_handlers"]


class MissingMotionHandler(TypeError):
    """A table keyed by motion kind lacks a kind (or names one that does not exist)."""


def require_handlers(owner: str, table: Mapping[ir.MotionKind, object],
                     kinds: Iterable[Enum] = ir.MotionKind) -> None:
    """Raise MissingMotionHandler unless `table` has exactly one entry per member of `kinds`
    (compared by name, so a test can pass an Enum with an extra member)."""
    wanted = {k.name for k in kinds}
    have = {k.name for k in table}
    missing, unknown = sorted(wanted - have), sorted(have - wanted)
    if missing or unknown:
        parts = ([f"no handler for motion kind {', '.join(missing)}"] if missing else []) + (
            [f"a handler for unknown kind {', '.join(unknown)}"] if unknown else [])
        raise MissingMotionHandler(f"{owner}: {'; '.join(parts)} (every ir.MotionKind needs one)")
