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

import re
from collections.abc import Callable, Sequence
from typing import Protocol

from rmot.backends.readers import codes
from rmot.backends.readers.common import Tally
from rmot.backends.readers.model import Native, Stmt, Where, walk

__all__ = ["keep_jumped_spans", "goto_spans"]

_CONDITIONAL = re.compile(r"(?i)\bIF\b")
_GOTO = re.compile(r"(?i)\bGOTO\s+(\w+)")  # RAPID `GOTO l;` / `IF c GOTO l;`, KRL `GOTO l`


def keep_jumped_spans(body: tuple[Stmt, ...], tally: Tally, jump: re.Pattern[str], is_label: Callable[[str, str], bool],
                      instructions: Sequence[tuple[str, Where]], native_text: Callable[[str], str]) -> tuple[Stmt, ...]:
    """The routine's `body` with what its native jumps can skip or repeat kept native (see the
    module docstring). `jump` finds the label a native line jumps to (group 1); `is_label(text,
    name)` whether a native line is that label; `instructions` the routine's (text, place) in order;
    `native_text` the text a native line of an instruction carries."""
    out = list(body)
    if _is_cycle(out, jump, is_label):
        tally.warn(codes.LOOP_READ_ONCE, "a jump from the program's end back to its first line is read as one cycle "
                   "of the program (the controller repeats an rmot program)", out[-1].where)
    for _ in range(len(body)):  # each pass keeps one jump's span; bounded by the jumps there are
        span = _first_open_span(out, jump, is_label)
        if span is None:
            break
        lo, hi, first, last, why = span
        kept = {s.where.line: s for s in out[lo:hi] if isinstance(s, Native)}
        tally.imported -= sum(not isinstance(s, Native) for s in walk(tuple(out[lo:hi])))
        natives = [kept.get(w.line) or tally.keep(native_text(text), w, why)
                   for text, w in instructions if first < w.line < last]
        out[lo:hi] = natives
    return tuple(out)


def _first_open_span(body: list[Stmt], jump: re.Pattern[str], is_label: Callable[[str, str], bool],
                     ) -> tuple[int, int, int, float, str] | None:
    """(first and end index in `body`, the source lines strictly between which everything is
    kept, the reason) of the first native jump whose span still holds a read instruction."""
    for a, s in enumerate(body):
        m = jump.search(s.text) if isinstance(s, Native) else None
        if m is None or not isinstance(s, Native) or (a == len(body) - 1 and _is_cycle(body, jump, is_label)):
            continue
        b = next((k for k, t in enumerate(body) if isinstance(t, Native) and is_label(t.text, m.group(1))), None)
        lo, hi = (a + 1, len(body)) if b is None else (min(a, b) + 1, max(a, b))
        if all(isinstance(t, Native) for t in body[lo:hi]):
            continue
        first = s.where.line if b is None else body[min(a, b)].where.line
        last = float("inf") if b is None else body[max(a, b)].where.line
        text = s.text.rstrip(" ;")
        how = "over" if b is None or b > a else "back over"
        when = ("as a run-time value decides (it runs zero, once or many times)" if _CONDITIONAL.search(text)
                else "every time (it runs only where another jump lands in it, or again and again)")
        return lo, hi, first, last, f"`{text}` at line {s.where.line} jumps {how} this {when}"

    return None


def _is_cycle(body: list[Stmt], jump: re.Pattern[str], is_label: Callable[[str, str], bool]) -> bool:
    """Whether the body is one endless cycle: its first line a label, its last an unconditional
    jump back to it (TP `LBL[1]` .. `JMP LBL[1]`, INFORM `*L1` .. `JUMP *L1`)."""
    if len(body) < 2 or not isinstance(body[-1], Native) or not isinstance(body[0], Native):
        return False
    m = jump.search(body[-1].text)
    return m is not None and not _CONDITIONAL.search(body[-1].text) and is_label(body[0].text, m.group(1))


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
    return keep_jumped_spans(tuple(body), tally, _GOTO, _is_goto_label, [(ln.text, ln.where) for ln in lines if ln.text.strip()],
                             _rapid_native if tally.vendor == "rapid" else str.strip)


def _rapid_native(text: str) -> str:
    """A RAPID statement as its native line: with its `;` (the reader's statements carry none),
    except a block's own line (`IF .. THEN`, `ENDIF`, ..) and a label."""
    text = text.strip()
    block = re.match(r"(?i)^(IF\b.*\bTHEN|ELSEIF|ELSE|ENDIF|FOR|ENDFOR|WHILE|ENDWHILE|TEST|CASE|DEFAULT|ENDTEST)\b", text)
    return text if block or text.endswith(":") else text + ";"


def _is_goto_label(text: str, name: str) -> bool:
    """`name:` starting the line (RAPID joins a label with the statement after it), not `:=`."""
    return re.match(rf"(?i){re.escape(name)}\s*:(?!=)", text.strip()) is not None
