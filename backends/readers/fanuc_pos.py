"""The position records a TP program's native lines move to, kept with them.

A line kept native that moves to a position of its program (`L P[2] 100mm/sec FINE Offset,
PR[4]`) needs that position's data, which lives in the program's /POS section, not in the
line. Each such position is kept as a native statement holding its record at the top of the
routine the program became, its whitespace collapsed and the arm group's `UF : n, UT : m`
turned into the names of the frame and tool those numbers have in the import (`UF : base,
UT : gripper`; a number the program names no frame or tool by stays a number, which the
backend refuses): the Fanuc backend writes it into the compiled program's /POS and points the
line at it (backends/fanuc_records.py). A routine holding a native line read from another
program (one inlined at its call) gets none: one program's records serve all its lines, and
the inlined line's numbers are the other program's.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import replace

from rmot.backends.readers.fanuc_text import position_blocks
from rmot.backends.readers.model import Document, FrameData, Native, Routine, Stmt, ToolData, VarDecl, Where, walk

__all__ = ["native_positions", "position_records", "with_position_records"]

_POSITION = re.compile(r"\bP\[(\d+)")
_SELECTION = re.compile(r"\bUF\s*:\s*(\d+)\s*,\s*UT\s*:\s*(\d+)")


def position_records(path: str, text: str, tools: Mapping[int, ToolData], frames: Mapping[int, FrameData]) -> tuple[Native, ...]:
    """Every position of the program as a record a native line may need, `P[n]{..}`, its frame
    and tool named as the program's moves name them."""
    def named(m: re.Match[str]) -> str:
        uf, ut = int(m.group(1)), int(m.group(2))
        frame = "base" if uf == 0 else frames[uf].name if uf in frames else str(uf)
        return f"UF : {frame}, UT : {tools[ut].name if ut in tools else ut}"

    return tuple(Native("fanuc", f"P[{n}" + (f':"{label}"' if label else "") + "]{ "
                        + _SELECTION.sub(named, " ".join(whole.split()), count=1) + " }", Where(path, line))
                 for n, label, whole, line in position_blocks(text))


def _named(natives: list[Native]) -> list[int]:
    return list(dict.fromkeys(int(m.group(1)) for s in natives for line in s.text.split("\n")
                              if not line.lstrip().startswith("!") for m in _POSITION.finditer(line)))


def native_positions(body: tuple[Stmt, ...], path: str) -> list[int]:
    """The positions the native lines of `body` read from `path` move to, in order."""
    return _named([s for s in walk(body) if isinstance(s, Native) and s.where.path == path])


def _with_records(routine: Routine, records: Mapping[tuple[str, int], Native]) -> Routine:
    natives = [s for s in walk(routine.body) if isinstance(s, Native)]
    if any(s.where.path != routine.where.path for s in natives if _named([s])):
        return routine
    kept = [records[routine.where.path, n] for n in _named(natives) if (routine.where.path, n) in records]
    if not kept:
        return routine
    top = next((k for k, s in enumerate(routine.body) if not isinstance(s, VarDecl)), len(routine.body))
    return replace(routine, body=(*routine.body[:top], *kept, *routine.body[top:]))


def with_position_records(doc: Document) -> Document:
    """`doc` with the records of the positions each routine's native lines move to at its top
    (after its variables), once each."""
    if doc.vendor != "fanuc" or not doc.records:
        return doc
    records = {(r.where.path, int(m.group(1))): r for r in doc.records if (m := _POSITION.match(r.text))}
    return replace(doc, routines=tuple(_with_records(r, records) for r in doc.routines))
