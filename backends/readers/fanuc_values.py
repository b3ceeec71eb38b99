"""The register values one Fanuc TP motion line reads: a speed `R[k]mm/sec`, an offset
`Offset,PR[k]` / `Tool_Offset,PR[k]`, a target `PR[k]`.

A value is known where the program itself sets it in straight-line code before the line (no
label, jump, block or call between: nothing else can run there), where a counting loop builds
the offset (fanuc.py reads its counter), or, for a register no program given writes, where a
backup's .VA file saved it (fanuc_va.py, W543). Everywhere else the line stays native and
`unread` says why. B-83284EN (R-30iB Operator's Manual): `PR[k]=LPOS-LPOS` is a Cartesian zero,
`PR[k,i]=v` sets element i of X Y Z W P R, `R[k]=v` a numeric register.
"""

from __future__ import annotations

import bisect
import re

from rmot.backends.readers.common import Tally, number
from rmot.backends.readers.fanuc_va import Controller, Saved
from rmot.backends.readers.model import Where

__all__ = ["RegisterValues", "built_offset"]

# what ends straight-line code: a label or jump (another path), a block's line, a call (the
# callee may write the register), an indirect write (any register may change)
_NOT_STRAIGHT = re.compile(r"^(LBL\[|JMP\b|IF\b|ELSE\b|ENDIF\b|FOR\b|ENDFOR\b|SELECT\b|CALL\b|RUN\b)|\b(PR|R)\[\s*A?R\[")
_CLEAR = re.compile(r"LPOS\s*-\s*LPOS")
_COUNTER = re.compile(r"R\[\d+(?::[^\]]*)?\]\*-?[\d.]+")


def built_offset(writes: list[tuple[int, re.Match[str]]], since: int, use: int, counted: bool) -> dict[str, float] | str | None:
    """What PR[k] holds at instruction `use` where the program builds it, from `writes` (each
    line writing PR[k]: its index, its match) and `since` (the last line before `use` that ends
    straight-line code): the elements set since `PR[k]=LPOS-LPOS`, or all six set with numbers,
    after `since` (the last write of each wins); {} where `counted` (a counting loop's
    `PR[k,i]=R[v]*d` builds it) and nothing else here writes PR[k]; None where no line writes
    PR[k] (the controller's); else why not followed."""
    values: dict[str, float] = {}
    for _, m in reversed([w for w in writes if since < w[0] < use]):
        value = number(m.group(2).strip().strip("()")) if m.group(1) else None
        if m.group(1) is None and _CLEAR.fullmatch(m.group(2).strip()):
            return values
        if value is None or not 1 <= int(m.group(1)) <= 6:
            break
        values.setdefault("xyzwpr"[int(m.group(1)) - 1], value)
        if len(values) == 6:
            return values
    if counted and all((m.group(1) is None and _CLEAR.fullmatch(m.group(2).strip())) or _COUNTER.fullmatch(m.group(2))
                       for _, m in writes):
        return {}  # (in a program the loop's caller inlines, too: it writes none)
    if not writes:
        return None
    k = re.match(r"PR\[(\d+)", writes[0][1].group(0))
    return f"the program sets PR[{k.group(1) if k else ''}] where the import does not follow its value (after a label, a block or a call)"


class RegisterValues:
    """The register values of one program's motion lines, read one line at a time (`start`);
    each register's writes and the lines that end straight-line code are found once."""

    def __init__(self, controller: Controller, texts: list[str]) -> None:
        self.controller = controller
        self.texts = texts  # the program's instructions, in order
        self.breaks = [j for j, t in enumerate(texts) if _NOT_STRAIGHT.search(t)]
        self.writes: dict[tuple[str, int], list[tuple[int, re.Match[str]]]] = {}
        self.at = 0  # the instruction being read
        self.unread: str | None = None  # why its value is not known
        self.used: list[tuple[str, int]] = []  # the saved registers it reads

    def _writes(self, kind: str, k: int) -> list[tuple[int, re.Match[str]]]:
        """The lines writing R[k] (a FOR counter too) or PR[k]: (index, match of the value)."""
        if (kind, k) not in self.writes:
            write = re.compile(rf"(?:FOR\s+)?{kind}\[{k}(?:,\s*(\d))?(?::[^\]]*)?\]\s*=\s*(.+)")
            self.writes[(kind, k)] = [(j, m) for j, t in enumerate(self.texts) if (m := write.fullmatch(t))]
        return self.writes[(kind, k)]

    def _since(self) -> int:
        """The last line before the one being read that ends straight-line code (-1: none)."""
        k = bisect.bisect_left(self.breaks, self.at)
        return self.breaks[k - 1] if k else -1

    def start(self, at: int) -> None:
        self.at, self.unread, self.used = at, None, []

    def note(self, tally: Tally, where: Where) -> None:
        """W543 for the saved values the line, now read, uses."""
        for kind, n in self.used:
            self.controller.note(tally, where, kind, n)

    def speed(self, speed: str) -> str:
        """A speed `R[k]mm/sec` (`R[k]%`, ..) with R[k]'s value in place where it is known."""
        m = re.match(r"R\[(\d+)(?::[^\]]*)?\]\s*(.*)", speed.strip())
        if m is None:
            return speed
        n = int(m.group(1))
        last = [(j, w) for j, w in self._writes("R", n) if self._since() < j < self.at][-1:]
        value: float | str | None = number(last[0][1].group(2).strip().strip("()")) if last and \
            not last[0][1].group(0).startswith("FOR") else None
        if value is None:
            value = self.controller.register(n)
            self.used += [] if isinstance(value, str) else [("R", n)]
        if isinstance(value, str):
            self.unread = f"its speed {value}"
            return speed
        return f"{value:g}{m.group(2)}"

    def offset(self, n: int, counted: dict[str, str] | None) -> dict[str, str] | None:
        """The shift terms (mm per axis) of an offset by PR[n], the counting loop's `counted` terms
        merged; None (with why) where its value is not known or it turns."""
        built = built_offset(self._writes("PR", n), self._since(), self.at, bool(counted))
        if built is None:
            saved = self.position(n)
            if saved is not None and (saved.xyzwpr is None or any(abs(a) > 1e-9 for a in saved.xyzwpr[3:])):
                self.unread, saved = f"the offset PR[{n}] holds a saved {'rotation' if saved.xyzwpr else 'joint position'}", None
            built = None if saved is None or saved.xyzwpr is None else dict(zip("xyz", saved.xyzwpr[:3]))
            if built is None:
                return None
        if isinstance(built, str) or any(built.get(a) for a in "wpr") or set(built) & set(counted or {}):
            self.unread = built if isinstance(built, str) else f"the offset PR[{n}] turns, or a loop and a number set one element"
            return None
        return {**{a: f"{v:g}" for a, v in built.items() if v}, **(counted or {})}

    def position(self, n: int) -> Saved | None:
        """PR[n]'s saved position (a target or an offset), where the backup holds it."""
        found = self.controller.position(n)
        self.unread = found if isinstance(found, str) else self.unread
        self.used += [] if isinstance(found, str) else [("PR", n)]
        return None if isinstance(found, str) else found
