"""Instructions a jump the reader kept native can skip or repeat are kept native too.

INFORM and Fanuc TP branch and loop with jumps to labels (`JUMP *L IF ..`, `IF R[1]<>1,JMP
LBL[2]`). The readers turn the jump forms they understand into rmot `if`/`for`/`while`; a jump
they cannot read (on a variable, a register, a flag) stays a `native` line. The instructions
between such a jump and its label then run on the controller zero, once or many times, as a
run-time value decides: read as straight-line rmot code, they would be planned and verified as
if they ran exactly once, without a word. So every instruction from the jump to its label (or,
for a backward jump, from the label to the jump) is kept native with the reason, and where the
label is not in the same block, everything after the jump in that block is. A program that is
one endless cycle (its first line a label, its last an unconditional jump back to it) is read as
one cycle, W518, as the other readers read an outermost `LOOP` / `while True:`.
"""

from __future__ import annotations

import bisect
import re
from collections.abc import Callable, Sequence
from typing import Protocol

from rmot.backends.readers import codes
from rmot.backends.readers.common import Tally
from rmot.backends.readers.model import Native, Stmt, Where, walk

__all__ = ["keep_jumped_spans", "goto_spans"]

_CONDITIONAL = re.compile(r"(?i)\bIF\b")
_GOTO = re.compile(r"(?i)\bGOTO\s+(\w+)")  # RAPID `GOTO l;` / `IF c GOTO l;`, KRL `GOTO l`


def keep_jumped_spans(body: tuple[Stmt, ...], tally: Tally, jump: re.Pattern[str], label_of: Callable[[str], str | None],
                      instructions: Sequence[tuple[str, Where]], native_text: Callable[[str], str]) -> tuple[Stmt, ...]:
    """The routine's `body` with what its native jumps can skip or repeat kept native (see the
    module docstring). `jump` finds the label a native line jumps to (group 1); `label_of(text)`
    the label a native line is (None: none; compared without case); `instructions` the routine's
    (text, place) in order; `native_text` the text a native line of an instruction carries."""
    out = list(body)
    if _is_cycle(out, jump, label_of):
        tally.warn(codes.LOOP_READ_ONCE, "a jump from the program's end back to its first line is read as one cycle "
                   "of the program (the controller repeats an rmot program)", out[-1].where)
    lines = [w.line for _, w in instructions]  # in source order
    for _ in range(len(body) + 1):  # each pass keeps every disjoint open span; bounded by the jumps there are
        spans = _open_spans(out, jump, label_of)
        if not spans:
            break
        shift = 0  # how far the spans kept before this one moved the places after them
        for lo, hi, first, last, why in spans:
            lo, hi = lo + shift, hi + shift
            kept = {s.where.line: s for s in out[lo:hi] if isinstance(s, Native)}
            tally.imported -= sum(not isinstance(s, Native) for s in walk(tuple(out[lo:hi])))
            inside = instructions[bisect.bisect_right(lines, first):bisect.bisect_left(lines, last)]
            out[lo:hi] = [kept.get(w.line) or tally.keep(native_text(text), w, why) for text, w in inside]
            shift += len(inside) - (hi - lo)
    return tuple(out)


def _open_spans(body: list[Stmt], jump: re.Pattern[str], label_of: Callable[[str], str | None],
                ) -> list[tuple[int, int, int, float, str]]:
    """(first and end index in `body`, the source lines strictly between which everything is
    kept, the reason) of the native jumps whose spans still hold a read instruction: the first
    one, then those after it that overlap none before and whose label is in the body (one with
    none reaches the end: it waits for the next pass, where keeping other spans may bring its
    label out of a block). Processed together they give what one at a time would."""
    labels: dict[str, int] = {}  # each label's first place in the body, found in one scan
    reads = [0]  # how many statements before each place are read (not native)
    for k, t in enumerate(body):
        name = label_of(t.text) if isinstance(t, Native) else None
        if name is not None:
            labels.setdefault(name.upper(), k)
        reads.append(reads[-1] + (not isinstance(t, Native)))
    spans: list[tuple[int, int, int, float, str]] = []
    reached = -1  # the last place a chosen span covers
    for a, s in enumerate(body):
        m = jump.search(s.text) if isinstance(s, Native) else None
        if m is None or not isinstance(s, Native) or (a == len(body) - 1 and _is_cycle(body, jump, label_of)):
            continue
        b = labels.get(m.group(1).upper())
        lo, hi = (a + 1, len(body)) if b is None else (min(a, b) + 1, max(a, b))
        if reads[hi] == reads[lo] or min(a, b if b is not None else a) <= reached:
            continue
        if b is None and spans:
            break
        first = s.where.line if b is None else body[min(a, b)].where.line
        last = float("inf") if b is None else body[max(a, b)].where.line
        spans.append((lo, hi, first, last, _why(s, b is None or b > a)))
        reached = len(body) if b is None else max(a, b)
    return spans


def _why(s: Native, forward: bool) -> str:
    text = s.text.rstrip(" ;")
    when = ("as a run-time value decides (it runs zero, once or many times)" if _CONDITIONAL.search(text)
            else "every time (it runs only where another jump lands in it, or again and again)")
    return f"`{text}` at line {s.where.line} jumps {'over' if forward else 'back over'} this {when}"


def _is_cycle(body: list[Stmt], jump: re.Pattern[str], label_of: Callable[[str], str | None]) -> bool:
    """Whether the body is one endless cycle: its first line a label, its last an unconditional
    jump back to it (TP `LBL[1]` .. `JMP LBL[1]`, INFORM `*L1` .. `JUMP *L1`)."""
    if len(body) < 2 or not isinstance(body[-1], Native) or not isinstance(body[0], Native):
        return False
    m = jump.search(body[-1].text)
    first = label_of(body[0].text)
    return (m is not None and not _CONDITIONAL.search(body[-1].text) and first is not None
            and first.upper() == m.group(1).upper())


class _Line(Protocol):
    """A reader's statement: RAPID's `Statement`, KRL's `Line`."""

    @property
    def text(self) -> str: ...

    @property
    def where(self) -> Where: ...


def goto_spans(body: Sequence[Stmt], tally: Tally, lines: Sequence[_Line]) -> tuple[Stmt, ...]:
    """RAPID and KRL: what a `GOTO label` the reader kept native can skip or repeat, kept native
    (as `keep_jumped_spans`); `lines`: the routine's statements (text, place), its header and end
    excluded."""
    return keep_jumped_spans(tuple(body), tally, _GOTO, _goto_label, [(ln.text, ln.where) for ln in lines if ln.text.strip()],
                             _rapid_native if tally.vendor == "rapid" else str.strip)


def _rapid_native(text: str) -> str:
    """A RAPID statement as its native line: with its `;` (the reader's statements carry none),
    except a block's own line (`IF .. THEN`, `ENDIF`, ..) and a label."""
    text = text.strip()
    block = re.match(r"(?i)^(IF\b.*\bTHEN|ELSEIF|ELSE|ENDIF|FOR|ENDFOR|WHILE|ENDWHILE|TEST|CASE|DEFAULT|ENDTEST)\b", text)
    return text if block or text.endswith(":") else text + ";"


def _goto_label(text: str) -> str | None:
    """The label `name:` starting a RAPID or KRL line (not `:=`)."""
    m = re.match(r"(\w+)\s*:(?!=)", text.strip())
    return m.group(1) if m else None
