"""Instructions a jump the reader kept native can skip or repeat are kept native too; those it
skips every time, where nothing else reaches them, are read into a proc nothing calls.

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

A line that leaves the routine (TP `END`, INFORM `RET`, RAPID `RETURN`/`RAISE`, KRL `RETURN`) is
such a jump, past the routine's last line; a KRL `EXIT` leaves its loop, so a block the reader
read around it is kept native. A jump inside a block the reader read (an if's arm,
a loop) whose label is in its own body keeps its span native there; one that leaves its body
keeps the whole block native (which of its lines run is then known only at run time), and then
spans what follows. An if whose arm ends in an unconditional jump forward to a label of its body
(or in an exit, where that body ends the routine) is read as the if/else it is: what the jump
skips is the other arm, where no line names a label among it.

What an unconditional forward jump (`GOTO FINAL`, `JMP LBL[9]`, `JUMP *END`) skips, where no
line of the routine names a label among it (by any jump, wait exit or SELECT arm) and no native
block line (`ENDIF`, `CASE`, `ELSE`, ..) among it says the jump sits in a block that ends
there, never runs: programs keep teach points there (a KUKA palletizing program's section of
inline forms after `GOTO FINAL`) or switch code off. It is read, not kept native: into a proc
no line calls (W552), so its moves and targets are rmot's while nothing plans, verifies or
compiles them, as the controller never runs them. Where it declares, assigns or tests a
variable or passes an argument (a proc sees no task variable), it stays native as above.
"""

from __future__ import annotations

import bisect
import os
import re
from dataclasses import replace
from collections.abc import Callable, Sequence
from typing import Protocol

from rmot.backends.readers import codes
from rmot.backends.readers.common import Tally, rmot_name
from rmot.backends.readers.rapid_text import native_line
from rmot.backends.readers.model import (
    Assign, Call, Cond, Conds, For, GroupIn, If, Native, Routine, Stmt, Sync, VarDecl, WaitIn, Where, While, walk,
)

__all__ = ["keep_jumped_spans", "goto_spans", "exit_spans"]

# a jump taken only as a value decides: on a condition, or an arm of a TP SELECT (`SELECT R[1]=1,JMP
# LBL[10]`, `=2,JMP LBL[20]`, `ELSE,JMP LBL[99]`)
_CONDITIONAL = re.compile(r"(?i)\bIF\b|^\s*(?:SELECT\b|ELSE\s*,|=)")
_GOTO = re.compile(r"(?i)\bGOTO\s+(\w+)")  # RAPID `GOTO l;` / `IF c GOTO l;`, KRL `GOTO l`
# every way a line names a label it may go to (group 1: the label as written; a name no label
# has, as `LBL[R[1]]`'s, is a jump rmot cannot follow: then nothing of the routine is unreached)
_REFERENCE = {
    "fanuc": re.compile(r"LBL\[([^\]:]*)"),  # JMP LBL[n], TIMEOUT,LBL[n], Skip,LBL[n], SELECT arms
    "inform": re.compile(r"(?i)\bJUMP\s+(?!JOB:)\*?(\S+)"),
    "krl": _GOTO,
    "rapid": _GOTO,
    "urscript": re.compile(r"(?!)"),  # URScript has no labels
}
# a native line that closes or divides a block, or starts a RAPID routine's handler (an error, a
# backward run or an undo runs it): the jump before it may sit inside that block, or reach it
_BLOCK_LINE = re.compile(r"(?i)^\s*(?:=|(?:END\w*|ELSE\w*|CASE|DEFAULT|UNTIL|ERROR|BACKWARD|UNDO)\b)")
# a native line that leaves the routine (a jump past its end; group 1: the word, a name no label has)
_EXITS = {
    "rapid": re.compile(r"(?i)^\s*(?:IF\b.*?\s)?(RETURN|RAISE|EXIT|EXITCYCLE)\b"),  # to the caller or the handler
    "krl": re.compile(r"(?i)^\s*(RETURN)\b"),  # (RETURN in the main routine is read as `stop`)
    "fanuc": re.compile(r"(?i)^\s*(END|ABORT)\s*;?\s*$"),  # (END returns to a caller, ends a program)
    "inform": re.compile(r"(?i)^\s*(RET|END)\b"),  # `RET IF IN#(1)=ON` too
    "urscript": re.compile(r"^\s*(return)\b"),  # (a function's; `halt` is read as `stop`)
}

# a native line that leaves the loop it is in (KRL EXIT): out of any block the reader read
# around it, as a jump out of them; in a loop kept native it goes on after that loop's lines
_LOOP_EXITS = {"krl": re.compile(r"(?i)^\s*EXIT\b"), "urscript": re.compile(r"^\s*(break|continue)\b")}


class _Jump:
    """Where a native line goes: `jump` finds the label a line jumps to (group 1), or the vendor's
    exit (RETURN, END, RET) that leaves the routine, a jump past its last line."""

    def __init__(self, jump: re.Pattern[str], vendor: str) -> None:
        self.jump = jump
        self.exit = _EXITS.get(vendor, re.compile(r"(?!)"))
        self.loop_exit = _LOOP_EXITS.get(vendor, re.compile(r"(?!)"))

    def search(self, text: str) -> re.Match[str] | None:
        return self.jump.search(text) or self.exit.search(text)

    def match(self, text: str) -> re.Match[str] | None:
        return self.jump.match(text) or self.exit.match(text)

    def leaves(self, text: str) -> bool:
        """Whether the line leaves the routine (no label is its target)."""
        return self.jump.search(text) is None and self.exit.search(text) is not None


def keep_jumped_spans(body: tuple[Stmt, ...], tally: Tally, jump: re.Pattern[str], label_of: Callable[[str], str | None],
                      instructions: Sequence[tuple[str, Where]], native_text: Callable[[str], str]) -> tuple[Stmt, ...]:
    """The routine's `body` with what its native jumps can skip or repeat kept native (see the
    module docstring). `jump` finds the label a native line jumps to (group 1); `label_of(text)`
    the label a native line is (None: none; compared without case); `instructions` the routine's
    (text, place) in order; `native_text` the text a native line of an instruction carries."""
    jumps = _Jump(jump, tally.vendor)
    if _is_cycle(list(body), jumps, label_of):
        tally.warn(codes.LOOP_READ_ONCE, "a jump from the program's end back to its first line is read as one cycle "
                   "of the program (the controller repeats an rmot program)", body[-1].where)
    return _Routine(tally, jumps, label_of, instructions, native_text).spans(body, ends_routine=True)


class _Routine:
    """One routine's native jumps, and what each skips or repeats: kept native, read as the
    if/else it is, or read into a proc nothing calls."""

    def __init__(self, tally: Tally, jump: _Jump, label_of: Callable[[str], str | None],
                 instructions: Sequence[tuple[str, Where]], native_text: Callable[[str], str]) -> None:
        self.tally = tally
        self.jump = jump
        self.label_of = label_of
        self.instructions = instructions
        self.native_text = native_text
        self.named = _named_labels(instructions, label_of, _REFERENCE[tally.vendor])
        self.lines = [w.line for _, w in instructions]  # in source order
        self.gone: set[int] = set()  # the lines read into procs nothing calls, at any depth

    def _between(self, first: float, last: float) -> list[tuple[str, Where]]:
        """The instructions strictly between lines `first` and `last`, but those read as unreached."""
        inside = self.instructions[bisect.bisect_right(self.lines, first):bisect.bisect_left(self.lines, last)]
        return [(text, w) for text, w in inside if w.line not in self.gone]

    def spans(self, body: tuple[Stmt, ...], ends_routine: bool) -> tuple[Stmt, ...]:
        """`body` (the routine's, or a block's inside it; `ends_routine`: whether its end is the
        routine's) with its jumps' spans kept native, read as if/else or as unreached, its
        blocks' first."""
        inner: set[int] = set()  # the lines of jumps a block held
        out = self.blocks_with_jumps(self.early_exits(body, ends_routine), inner, ends_routine)
        self.read_unreached(out, inner)
        for _ in range(len(body) + 1):  # each pass keeps every disjoint open span; bounded by the jumps there are
            spans = _open_spans(out, self.jump, self.label_of, inner)
            if not spans:
                break
            shift = 0  # how far the spans kept before this one moved the places after them
            for lo, hi, first, last, why in spans:
                lo, hi = lo + shift, hi + shift
                kept = {s.where.line: s for s in out[lo:hi] if isinstance(s, Native)}
                self.tally.imported -= sum(not isinstance(s, Native) for s in walk(tuple(out[lo:hi])))
                inside = self._between(first, last)
                out[lo:hi] = [kept.get(w.line) or self.tally.keep(self.native_text(text), w, why) for text, w in inside]
                shift += len(inside) - (hi - lo)
        return tuple(out)

    def early_exits(self, body: tuple[Stmt, ...], ends_routine: bool) -> tuple[Stmt, ...]:
        """`body` with each if whose arm ends in an unconditional jump forward to a label of
        `body`, or in a routine exit where `body` ends the routine (`IF stop THEN .. RETURN ENDIF`,
        lines, the end), read as the if/else it is: the lines up to the label (the end) become the
        other arm's last (they run exactly when that arm does not), where no line names a label
        among them. The last such if first: an earlier one's lines then hold it, read."""
        out = list(body)
        for k in range(len(out) - 1, -1, -1) if self.named is not None else ():
            s = out[k]
            if not isinstance(s, If):
                continue
            for arm, other in (("then", "orelse"), ("orelse", "then")):
                end = self._exit_end(out, k, getattr(s, arm), ends_routine)
                if end is None or any(isinstance(t, Native) and (self.label_of(t.text) or "").upper() in (self.named or ())
                                      for t in walk(tuple(out[k + 1:end]))):
                    continue
                rest = tuple(out[k + 1:end])
                kept, grown = getattr(s, arm)[:-1], (*getattr(s, other), *rest)
                out[k:end] = [replace(s, **{arm: kept, other: grown}) if kept or arm == "orelse"
                              else replace(s, cond=Conds("not", (s.cond,)), then=grown, orelse=())]
                self.tally.unkeep(getattr(s, arm)[-1].where)  # the jump is the if's own structure
                break
        return tuple(out)

    def _exit_end(self, out: list[Stmt], k: int, arm: tuple[Stmt, ...], ends_routine: bool) -> int | None:
        """Where the lines an arm's last line skips end in `out` (the if at place `k`): the place
        of the label it jumps to, or the end where it leaves the routine and `out` ends it."""
        last = arm[-1] if arm else None
        if not isinstance(last, Native) or _CONDITIONAL.search(last.text):
            return None
        m = self.jump.match(last.text.strip())
        if m is None:
            return None
        if self.jump.leaves(last.text):
            return len(out) if ends_routine else None
        return _label_after(out, k, m.group(1), self.label_of)

    def blocks_with_jumps(self, body: tuple[Stmt, ...], inner: set[int], ends_routine: bool) -> list[Stmt]:
        """`body` with each read block (an if, a loop, a wait's timeout branch) that holds a
        native jump: where every such jump lands in its own body (a routine exit in a body that
        ends the routine: an if's arm, where the if ends a body that does), that body's spans
        kept as a routine's are; where one leaves its body, the whole block kept native, for
        which of its lines run is known only at run time; the jump, a native line of the body
        itself from there on, spans what follows as any other, as a jump a value decides (its
        line goes into `inner`)."""
        out: list[Stmt] = []
        for k, s in enumerate(body):
            last = ends_routine and k == len(body) - 1 and isinstance(s, If)  # its arms end the routine
            leaving = _jump_leaving(s, self.jump, self.label_of, last)
            if leaving is None:
                out.append(self._with_spans_inside(s, last))
                continue
            end = body[k + 1].where.line if k + 1 < len(body) else float("inf")
            kept = {t.where.line: t for t in walk((s,)) if isinstance(t, Native)}
            self.tally.imported -= sum(not isinstance(t, Native) for t in walk((s,)))
            inner.update(t.where.line for t in kept.values() if self.jump.search(t.text))
            why = (f"`{leaving.text.rstrip(' ;')}` at line {leaving.where.line} inside this block "
                   f"{'leaves the routine' if self.jump.leaves(leaving.text) else 'jumps out of it'}: which of its "
                   "lines run is known only at run time")
            out += [kept.get(w.line) or self.tally.keep(self.native_text(text), w, why)
                    for text, w in self._between(s.where.line - 1, end)]
        return out

    def _with_spans_inside(self, s: Stmt, ends_routine: bool) -> Stmt:
        """Block `s` with the spans of the jumps in its bodies kept (each lands in its own body;
        `ends_routine`: an if whose arms end the routine)."""
        if isinstance(s, If):
            return replace(s, then=self.spans(s.then, ends_routine), orelse=self.spans(s.orelse, ends_routine))
        if isinstance(s, (While, For)):
            return replace(s, body=self.spans(s.body, False))
        if isinstance(s, WaitIn):
            return replace(s, orelse=self.spans(s.orelse, False))
        return s

    def read_unreached(self, out: list[Stmt], inner: set[int]) -> None:
        """Take out of `out` what its unconditional forward jumps (not on the `inner` lines,
        which a block held) skip where it never runs (see the module docstring), each into a
        proc nothing calls (`tally.unreached`), W552 at the jump; their lines go into `gone`."""
        if self.named is None:
            return  # a jump to a computed label may land anywhere
        for a, s in enumerate(out):
            m = (self.jump.match(s.text.strip()) if isinstance(s, Native) and not _CONDITIONAL.search(s.text)
                 and s.where.line not in inner else None)
            b = _label_after(out, a, m.group(1), self.label_of) if m is not None else None
            if b is None or not isinstance(s, Native):
                continue
            span, inside = out[a + 1:b], self._between(s.where.line, out[b].where.line)
            if any(not isinstance(t, Native) for t in span) and _unreached(span, inside, self.label_of, self.named):
                out[a + 1:b] = []  # after place a: the loop goes on at the label
                _as_proc(self.tally, span, s)
                self.gone.update(w.line for _, w in inside)


def _bodies(s: Stmt) -> tuple[tuple[Stmt, ...], ...]:
    """The bodies of a block statement (none for any other)."""
    if isinstance(s, If):
        return s.then, s.orelse
    if isinstance(s, (While, For)):
        return (s.body,)
    return (s.orelse,) if isinstance(s, WaitIn) else ()


def _jump_leaving(s: Stmt, jump: _Jump, label_of: Callable[[str], str | None], ends_routine: bool) -> Native | None:
    """A native jump inside block `s` (at any depth) whose label is not in its own body, or a
    routine exit in a body that does not end the routine (`ends_routine`: `s` is an if whose arms
    do), if any."""
    for block_body in _bodies(s):
        labels = {(label_of(t.text) or "").upper() for t in block_body if isinstance(t, Native)}
        for k, t in enumerate(block_body):
            m = jump.search(t.text) if isinstance(t, Native) else None
            if isinstance(t, Native) and (jump.loop_exit.match(t.text) or m is not None and m.group(
                    1).upper() not in labels and not (ends_routine and jump.leaves(t.text))):
                return t
            last = ends_routine and k == len(block_body) - 1 and isinstance(t, If)
            found = _jump_leaving(t, jump, label_of, last)
            if found is not None:
                return found
    return None


def _open_spans(body: list[Stmt], jump: _Jump, label_of: Callable[[str], str | None],
                inner: set[int]) -> list[tuple[int, int, int, float, str]]:
    """(first and end index in `body`, the source lines strictly between which everything is
    kept, the reason) of the native jumps whose spans still hold a read instruction: the first
    one, then those after it that overlap none before and whose label is in the body (one with
    none reaches the end: it waits for the next pass, where keeping other spans may bring its
    label out of a block). Processed together they give what one at a time would. A jump on an
    `inner` line (a block held it) is one a value decides."""
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
        spans.append((lo, hi, first, last, _why(s, b is None or b > a, s.where.line in inner, jump.leaves(s.text))))
        reached = len(body) if b is None else max(a, b)
    return spans


def _named_labels(instructions: Sequence[tuple[str, Where]], label_of: Callable[[str], str | None],
                  reference: re.Pattern[str]) -> set[str] | None:
    """The labels (upper case) some line of the routine names, or None where a line names one
    the routine lacks (a jump to a computed label: any line may be its target)."""
    labels = {name.upper() for text, _ in instructions if (name := label_of(text)) is not None}
    named = {m.group(1).upper() for text, _ in instructions if label_of(text) is None
             for m in reference.finditer(text)}
    return named if named <= labels else None


def _unreached(span: list[Stmt], inside: Sequence[tuple[str, Where]], label_of: Callable[[str], str | None],
               named: set[str]) -> bool:
    """Whether what an unconditional forward jump skips (`span`, its statements; `inside`, its
    instruction lines at any depth) never runs and can stand in a proc no line calls."""
    if any((name := label_of(text)) is not None and name.upper() in named for text, _ in inside):
        return False  # a jump lands among it
    if any(isinstance(s, Native) and _BLOCK_LINE.match(s.text) for s in span):
        return False  # the jump sits in a native block that ends or divides here
    for s in walk(tuple(span)):
        if isinstance(s, (VarDecl, Assign, Sync)) or (isinstance(s, Call) and s.args):
            return False  # a proc sees no task variable, and a sync in a proc counts as run
        cond = getattr(s, "cond", None)
        if cond is not None and _tests_variable(cond):
            return False
    return True


def _tests_variable(cond: Cond | Conds | GroupIn) -> bool:
    """Whether a condition holds a variable's test (an expression), not only signals."""
    return isinstance(cond, Conds) and (cond.op in ("logic", "expr") or any(_tests_variable(p) for p in cond.parts))


def _label_after(out: list[Stmt], a: int, name: str, label_of: Callable[[str], str | None]) -> int | None:
    """The place of the first native label line `name` after place `a` in `out`."""
    return next((k for k in range(a + 1, len(out)) if isinstance(t := out[k], Native)
                 and (label_of(t.text) or "").upper() == name.upper()), None)


def _as_proc(tally: Tally, span: list[Stmt], jump: Native) -> None:
    """`span` (what `jump` skips) as a proc no line calls, W552 at the jump."""
    first, last = span[0].where.line, max(s.where.line for s in walk(tuple(span)))
    name = rmot_name(f"{os.path.splitext(os.path.basename(tally.path))[0]}_unreached_{first}")
    tally.unreached.append(Routine(name, (), tuple(span), span[0].where))
    lines, them = (f"line {first} never runs", "it") if first == last else (f"lines {first}-{last} never run", "them")
    tally.warn(codes.UNREACHED_READ_AS_PROC, f"{lines}: `{jump.text.rstrip(' ;')}` jumps over {them} every time and "
               f"no line names a label among {them} (teach points kept there, or code switched off); read into "
               f"`proc {name}`, which nothing calls: the moves and targets are kept, "
               "not planned, verified or compiled", jump.where)


def _why(s: Native, forward: bool, in_block: bool, leaves: bool) -> str:
    text = s.text.rstrip(" ;")
    when = ("as a run-time value decides (it runs zero, once or many times)" if in_block or _CONDITIONAL.search(text)
            else "every time (it runs only where another jump lands in it, or again and again)")
    goes = "leaves the routine before" if leaves else "jumps over" if forward else "jumps back over"
    return f"`{text}` at line {s.where.line} {goes} this {when}"


def _is_cycle(body: list[Stmt], jump: _Jump, label_of: Callable[[str], str | None]) -> bool:
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
                             native_line if tally.vendor == "rapid" else str.strip)


def exit_spans(body: tuple[Stmt, ...], tally: Tally, lines: Sequence[_Line]) -> tuple[Stmt, ...]:
    """URScript: a function's body with what a native `return` (or a `break`, `continue` in a
    loop read around it) can skip kept native, or read as the if/else it is (as
    `keep_jumped_spans`); `lines`: the function's lines between its `def` and its `end`."""
    return keep_jumped_spans(body, tally, re.compile(r"(?!)"), lambda text: None,
                             [(ln.text, ln.where) for ln in lines], str.strip)


def _goto_label(text: str) -> str | None:
    """The label `name:` starting a RAPID or KRL line (not `:=`)."""
    m = re.match(r"(\w+)\s*:(?!=)", text.strip())
    return m.group(1) if m else None
