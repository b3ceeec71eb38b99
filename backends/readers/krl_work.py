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
from rmot.backends.readers.krl_flow import KnownPositions, is_block, is_label
from rmot.backends.readers.krl_text import Line

__all__ = ["WorkCopies"]

_COPY = re.compile(r"(\w+)\s*=\s*(\w+)")
_COMPONENT = re.compile(r"(?i)(\w+)\.([XYZ])\s*=\s*(\w+)\.([XYZ])\s*\+\s*(.+)")
_DEF = re.compile(r"(?i)\s*(?:GLOBAL\s+)?DEF\b")  # a routine's first line
_FOR = re.compile(r"(?i)\s*FOR\s+(\w+)\s*=")
_LOOPS = ("FOR", "WHILE", "LOOP", "REPEAT")
_BRANCHES = ("ELSE", "CASE", "DEFAULT")  # a branch's end: the next one does not run after it
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
             data: Mapping[str, object], names: set[str]) -> bool:
        """Learn line `i` where it sets a work copy whose value the import can vouch for at every
        line that reads it (True), or nothing."""
        found = self._parse(lines[i].text, targets, data, names)
        if found is None:
            return False
        key, base, axis, expr = found
        if not axis:
            if not self._holds(lines, i, (key, base), flow, names):
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
        if c is None or c.group(1).upper() != key or c.group(3).upper() != base or c.group(2).upper() != c.group(4).upper():
            return ""
        return "component" if num_expr(c.group(5), names) is not None else ""

    def _holds(self, lines: list[Line], i: int, copy: tuple[str, str], flow: KnownPositions, names: set[str]) -> bool:
        """Whether copy `key` of `base`, set at line `i`, holds base shifted by its own component
        lines at every line that reads it: the routine has no label; up to the copy's next `key =
        base` at its level, or the end of its block or branch, no line that may change it
        (krl_flow.py's rules) comes before a read, and a component line is at its level or directly
        in a loop there that reads it only after it and after which its level reads it no more;
        after that, the copy's next line is a fresh `key = base`; in each loop around line `i`,
        the first line that names the copy is such a copy too (the next pass starts afresh)."""
        key, base = copy
        first = next((j for j in range(i, -1, -1) if _DEF.match(lines[j].text)), 0)
        end = next((j for j in range(i, len(lines)) if lines[j].word == "END"), len(lines))
        reads = re.compile(rf"(?i)\b{key}\b")
        # the offsets may use the counters of the routine's FOR loops (the reader knows each in its loop)
        known = names | {m.group(1).upper() for ln in lines[first:end] if (m := _FOR.match(ln.text))}
        if any(is_label(ln) for ln in lines[first:end]) or not self._fresh_in_loops(lines, first, i, key, base, reads):
            return False
        rel, changed, loop_at, shifted, k = 0, False, -1, False, i + 1
        while k < end and not (rel == 0 and (lines[k].word in _ENDS or lines[k].word in _BRANCHES)):
            ln, own = lines[k], self._own(lines[k].text, key, base, known)
            if rel == 0 and own == "copy":
                return True
            if reads.search(ln.text) and not own and (changed or (shifted and rel == 0)):
                return False
            changed |= (not own or rel > 0 and own == "copy") and flow.may_change(ln, key) is not None
            if own == "component" and rel > 0:
                if rel > 1 or lines[loop_at].word not in _LOOPS or any(reads.search(x.text) for x in lines[loop_at + 1:k]):
                    return False
                shifted = True
            loop_at = k if rel == 0 and is_block(ln) else loop_at
            rel += is_block(ln)
            rel -= ln.word in _ENDS
            k += 1
        return next((self._own(ln.text, key, base, known) == "copy" for ln in lines[k:end] if reads.search(ln.text)), True)

    def _fresh_in_loops(self, lines: list[Line], first: int, i: int, key: str, base: str, reads: re.Pattern[str]) -> bool:
        """Whether, in each loop open at line `i`, the first line that names the copy is a `key = base`."""
        opened: list[int] = []
        for j in range(first, i):
            if is_block(lines[j]):
                opened.append(j)
            elif lines[j].word in _ENDS and opened:
                opened.pop()
        for o in opened:
            named = next((ln for ln in lines[o + 1:i + 1] if reads.search(ln.text)), None)
            if lines[o].word in _LOOPS and (named is None or self._own(named.text, key, base, set()) != "copy"):
                return False
        return True
