"""A KRL loop's work copy of a target: `P_loop = P`, then `P_loop.X = P.X + expr` (a shift of P).

The copy (a data-list variable of the .dat) is read as P, shifted by the offsets the component
lines give, only while nothing else may change it: by the rules of readers/krl_flow.py (a label,
another assignment, a call that may write it, an interrupt routine), a block whose lines may
change it (other than by the copy's own lines, which derive it from P afresh on every pass)
before it is read, and any block that changes it after (a loop's last pass, a branch not taken).
"""

from __future__ import annotations

import re
from collections.abc import Mapping

from rmot.backends.readers.common import num_expr
from rmot.backends.readers.krl_flow import KnownPositions, block_end, is_block
from rmot.backends.readers.krl_text import Line

__all__ = ["WorkCopies"]

_COPY = re.compile(r"(\w+)\s*=\s*(\w+)")
_COMPONENT = re.compile(r"(?i)(\w+)\.([XYZ])\s*=\s*(\w+)\.([XYZ])\s*\+\s*(.+)")
_FOR = re.compile(r"(?i)\s*FOR\s+(\w+)\s*=")
_LOOPS = ("FOR", "WHILE", "LOOP", "REPEAT")
_ENDS = ("ENDFOR", "ENDIF", "ENDWHILE", "ENDLOOP", "UNTIL", "ENDSWITCH", "ENDSPLINE")


class WorkCopies:
    """The work copies known at the line being read: COPY -> (its target, axis -> offset in rmot)."""

    def __init__(self) -> None:
        self.copies: dict[str, tuple[str, dict[str, str]]] = {}
        self.made: set[str] = set()  # every copy the module makes (no target of its own)

    def __contains__(self, key: object) -> bool:
        """Whether a name is a work copy somewhere in the module."""
        return key in self.made

    def routine(self) -> None:
        """A routine starts: its copies are its own."""
        self.copies = {}

    def _parse(self, text: str, targets: Mapping[str, object], data: Mapping[str, object],
               names: set[str]) -> tuple[str, str, str, str] | None:
        """(copy, target, axis or "", offset or "") of a line that sets a work copy, else None."""
        m = _COPY.fullmatch(text)
        if m and m.group(2).upper() in targets and m.group(1).upper() in data:
            return m.group(1).upper(), m.group(2).upper(), "", ""
        c = _COMPONENT.fullmatch(text)
        key = c.group(1).upper() if c else ""
        if c is None or key not in self.copies or c.group(2).upper() != c.group(4).upper():
            return None
        expr = num_expr(c.group(5), names)
        if expr is None or self.copies[key][0] != c.group(3).upper():
            return None
        return key, self.copies[key][0], c.group(2).lower(), expr

    def read(self, lines: list[Line], i: int, flow: KnownPositions, targets: Mapping[str, object],
             data: Mapping[str, object], names: set[str], top: bool) -> bool:
        """Learn line `i` where it sets a work copy whose value the import can vouch for at every
        line that reads it (True; `top`: the line is at the routine's top level), or nothing."""
        found = self._parse(lines[i].text, targets, data, names)
        if found is None:
            return False
        key, base, axis, expr = found
        if not axis:
            if not top or not self._holds(lines, i, (key, base), flow, names):
                return False
            self.copies[key] = (base, {})
            self.made.add(key)
        else:
            self.copies[key][1][axis] = expr
        return True

    @staticmethod
    def _own(text: str, key: str, base: str, names: set[str]) -> str:
        """"copy" or "component" where a line is the copy's own (`key = base`, `key.c = base.c + ..`
        with an offset over `names` this reader reads), else ""."""
        m = _COPY.fullmatch(text)
        if m and m.group(1).upper() == key and m.group(2).upper() == base:
            return "copy"
        c = _COMPONENT.fullmatch(text)
        own = c and c.group(1).upper() == key and c.group(3).upper() == base and c.group(2).upper() == c.group(4).upper()
        return "component" if own and num_expr(c.group(5), names) is not None else ""

    def _holds(self, lines: list[Line], i: int, copy: tuple[str, str], flow: KnownPositions, names: set[str]) -> bool:
        """Whether copy `key` of `base`, set at top-level line `i`, holds base shifted by its own
        component lines wherever the routine reads it after: no other line of the routine may
        change it (krl_flow.py's rules), and each component line is at top level or directly in a
        top-level loop, no line of which reads the copy before it and no line after which does."""
        (key, base), depth, loop_at, k = copy, 0, -1, i + 1
        end = self._end(lines, i)
        # the offsets may use the counters of the routine's FOR loops (the reader knows each in its loop)
        known = names | {m.group(1).upper() for ln in lines[i:end] if (m := _FOR.match(ln.text))}
        reads = re.compile(rf"(?i)\b{key}\b")
        while k < len(lines) and not (depth == 0 and lines[k].word == "END"):
            ln, own = lines[k], self._own(lines[k].text, key, base, known)
            if (not own or (own == "copy" and depth > 0)) and flow.may_change(ln, key) is not None:
                return False
            if own == "component" and depth > 0:
                opener = lines[loop_at]
                if depth > 1 or opener.word not in _LOOPS or any(reads.search(x.text) for x in lines[loop_at + 1:k]):
                    return False
                if any(reads.search(x.text) for x in lines[block_end(lines, loop_at) + 1:end]):
                    return False
            if is_block(ln):
                depth, loop_at = depth + 1, k if depth == 0 else loop_at
            depth -= ln.word in _ENDS
            k += 1
        return True

    @staticmethod
    def _end(lines: list[Line], k: int) -> int:
        """The index of the routine's END from line k on."""
        return next((j for j in range(k, len(lines)) if lines[j].word == "END"), len(lines))
