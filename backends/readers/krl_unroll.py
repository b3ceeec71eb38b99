"""A KRL FOR loop whose moves go to the array elements its variable selects, read iteration by iteration.

`FOR i = 1 TO 4` .. `LIN xInsideWall[i] C_DIS` .. `ENDFOR` (KSS 8.x Operating and Programming
Instructions for System Integrators, FOR: the counter takes first, first + 1, .., last, the bounds
included, STEP 1) moves to xInsideWall[1] .. [4] in turn. An rmot `for` binds its variable for
each iteration, but a target cannot be chosen by it (REFERENCE §12: targets are names, not arrays),
so where every element the loop reaches is a known position and the variable is used nowhere else,
the loop is written out once per iteration (W538), bounded: beyond MAX_ITERATIONS iterations or
MAX_LINES lines written out it stays the loop it is (W537), its moves native; a loop with a loop
inside stays a loop (written-out loops never nest).
"""

from __future__ import annotations

import re
from dataclasses import replace
from typing import Protocol

from rmot.backends.readers import codes
from rmot.backends.readers.common import Tally
from rmot.backends.readers.krl_flow import block_end
from rmot.backends.readers.krl_inline import MOTIONS
from rmot.backends.readers.krl_text import Line
from rmot.backends.readers.model import Stmt, Target, Where

__all__ = ["unrolled_for", "MAX_ITERATIONS", "MAX_LINES"]

MAX_ITERATIONS = 64  # a pallet layer or a path of points; more is a run-time computation, not a list
MAX_LINES = 2000  # body lines times iterations written out at most


class _Reader(Protocol):
    lines: list[Line]
    tally: Tally

    def _block(self, i: int, ends: tuple[str, ...]) -> tuple[list[Stmt], int]: ...

    def _target(self, text: str, at: Where | None = None) -> tuple[str, str | None, Target | None] | None: ...


def unrolled_for(reader: _Reader, i: int, var: str, first: int, last: int) -> tuple[list[Stmt], int] | None:
    """The FOR at line `i` (`var` = first TO last) written out per iteration, with the index after
    its ENDFOR; None where it is read as a loop (see the module's docstring)."""
    lines = reader.lines
    end = block_end(lines, i)
    body = lines[i + 1:end]
    index = re.compile(rf"(?i)(\w+)\s*\[\s*{re.escape(var)}\s*\]")
    uses = [ln for ln in body if re.search(rf"(?i)\b{re.escape(var)}\b", ln.text + (ln.fold or ""))]
    # a loop inside stays a loop: written-out loops never nest, so what is written out stays bounded
    if not uses or any(ln.word in ("FOR", "WHILE", "LOOP", "REPEAT") for ln in body) or any(ln.word not in MOTIONS or ln.fold is not None or
                       re.search(rf"(?i)\b{re.escape(var)}\b", index.sub("", ln.text)) for ln in uses):
        return None
    count = last - first + 1
    where = lines[i].where
    if count <= 0:
        return None
    if count > MAX_ITERATIONS or count * len(body) > MAX_LINES:
        reader.tally.warn(codes.LOOP_NOT_UNROLLED, f"this FOR moves to array elements its counter selects over "
                          f"{count} iterations ({count * len(body)} lines written out): beyond {MAX_ITERATIONS} "
                          f"iterations or {MAX_LINES} lines it stays a loop, its moves native", where)
        return None
    names = {name for ln in uses for name in index.findall(ln.text)}
    if any(reader._target(f"{name}[{k}]", where) is None for name in sorted(names) for k in range(first, last + 1)):
        return None
    out: list[Stmt] = []
    try:
        for k in range(first, last + 1):
            reader.lines = lines[:i + 1] + [replace(ln, text=index.sub(rf"\g<1>[{k}]", ln.text))
                                           for ln in body] + lines[end:]
            stmts, _ = reader._block(i + 1, ("ENDFOR",))
            out += stmts
    finally:
        reader.lines = lines
    reader.tally.imported += 1
    reader.tally.warn(codes.LOOP_UNROLLED, f"this FOR moves to {', '.join(sorted(names))}[{first}..{last}], which an "
                      f"rmot target cannot select by the counter: written out as its {count} iterations", where)
    return out, end + 1
