"""What every vendor reader shares: located diagnostics, the imported/native tally, reading
a file as text, splitting argument lists at top level, and numeric expressions.

Inputs are data: nothing here evaluates vendor text; numbers are parsed with float() and
refused when not finite.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from typing import TypeVar

from rmot.backends.readers import codes
from rmot.backends.readers.model import (
    Call, Cond, FileCount, Native, Pulse, Routine, SetOut, Stmt, Wait, WaitIn, Where,
)
from rmot.lang import ir
from rmot.lang.diagnostics import Code, Diagnostic, Severity
from rmot.lang.source import Pos, SourceFile, Span

__all__ = ["SIMPLE_FORMS", "label_arms", "label_loop", "reaches",
           "match_simple", "Tally", "ImportError_", "read_text", "split_top", "number", "NUMBER_RE", "MAX_BYTES",
           "num_expr", "rmot_name", "RMOT_RESERVED", "same_pose"]

T = TypeVar("T")
MAX_BYTES = 4 * 1024 * 1024  # the largest vendor file read (a pendant job is far smaller)
NUMBER_RE = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")

# rmot's reserved words (lang/REFERENCE.md section 2): a vendor name equal to one is renamed
RMOT_RESERVED = frozenset(
    "move joint linear circular via to speed accel zone fine tool frame target set wait until timeout "
    "pulse for in repeat if else proc return const use import cell program task sync native on off "
    "config at robot fixture io joint_speed joints time var while stop and or not true false none tcp "
    "mass flange base world pose inv shift int num bool".split())


class ImportError_(Exception):
    """A file that cannot be read as the vendor language: carries the located E510."""

    def __init__(self, diagnostic: Diagnostic) -> None:
        super().__init__(diagnostic.message)
        self.diagnostic = diagnostic


class Tally:
    """Collects one file's diagnostics and its imported / native instruction count."""

    def __init__(self, path: str, text: str, vendor: str) -> None:
        self.path = path
        self.vendor = vendor
        self.source = SourceFile(path, text)
        self.diagnostics: list[Diagnostic] = []
        self.imported = 0
        self.native = 0
        self.comments: list[Native] = []  # declarations and routines kept as a comment block
        self.unreached: list[Routine] = []  # what a jump skips every time, as procs nothing calls (jump_spans.py)
        self.depth = 0  # blocks open while reading (bounded: a hostile file cannot exhaust the stack)

    def span(self, where: Where) -> Span:
        pos = Pos(where.line, where.col)
        return Span(self.source, pos, pos)

    def warn(self, code: Code, message: str, where: Where) -> None:
        self.diagnostics.append(Diagnostic(code, Severity.WARNING, message, self.span(where)))

    def fail(self, message: str, where: Where) -> ImportError_:
        return ImportError_(Diagnostic(codes.NOT_VENDOR_LANGUAGE, Severity.ERROR, message, self.span(where)))

    def keep(self, text: str, where: Where, why: str) -> Native:
        """A line rmot cannot express: a native statement at its place, and W510 there."""
        self.native += 1
        self.warn(codes.KEPT_NATIVE, f"{why}; kept as `native {self.vendor}`: {text.strip()[:60]}", where)
        return Native(self.vendor, text.strip(), where)

    def unkeep(self, where: Where) -> None:
        """The native line at `where` is read after all (a jump that is an if's structure): its
        count and its W510 are taken back."""
        self.native -= 1
        self.imported += 1
        self.diagnostics = [d for d in self.diagnostics if not (
            d.code is codes.KEPT_NATIVE and d.span is not None and (d.span.start.line, d.span.start.col)
            == (where.line, where.col))]

    MAX_NESTING = 64

    def enter(self, where: Where) -> None:
        """A block opens; more than MAX_NESTING open blocks is E510 (no controller nests so deep)."""
        self.depth += 1
        if self.depth > self.MAX_NESTING:
            raise self.fail(f"blocks must nest at most {self.MAX_NESTING} deep", where)

    def leave(self) -> None:
        self.depth -= 1

    def nested(self, where: Where, read: Callable[[], T]) -> T:
        """`read()` one block deeper (enter/leave around it)."""
        self.enter(where)
        try:
            return read()
        finally:
            self.leave()

    def comment(self, text: str, where: Where) -> None:
        """A line with no rmot form outside any routine: kept in the comment block (counted native)."""
        self.native += 1
        self.comments.append(Native(self.vendor, text.strip(), where))

    def count(self) -> FileCount:
        return FileCount(self.path, self.imported, self.native)


def read_text(data: bytes) -> str:
    """Vendor files are ASCII, UTF-8 or Latin-1 (older controllers); a NUL byte means binary."""
    if b"\x00" in data:
        raise ValueError("binary data (NUL bytes)")
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError:
        text = data.decode("latin-1")
    return text.replace("\r\n", "\n").replace("\r", "\n")


def split_top(text: str, seps: str = ",") -> list[str]:
    """Split at separators outside brackets, parentheses, braces and strings."""
    parts: list[str] = []
    depth, start, quote = 0, 0, False
    for i, ch in enumerate(text):
        if ch == '"':
            quote = not quote
        elif quote:
            continue
        elif ch in "([{":
            depth += 1
        elif ch in ")]}":
            depth -= 1
        elif ch in seps and depth == 0:
            parts.append(text[start:i])
            start = i + 1
    parts.append(text[start:])
    return [p.strip() for p in parts]


def number(text: str) -> float | None:
    """A finite decimal number, or None (names, expressions, 9E+09 placeholders are numbers)."""
    text = text.strip()
    if not NUMBER_RE.fullmatch(text):
        return None
    value = float(text)
    return value if math.isfinite(value) else None


_EXPR_TOKEN = re.compile(r"\s*(?:(\d+\.?\d*(?:[eE][+-]?\d+)?)|([A-Za-z_]\w*)|([-+*/()]))")


def num_expr(text: str, names: frozenset[str] | set[str]) -> str | None:
    """A vendor arithmetic expression over numbers and known names (loop counters,
    parameters, constants) as rmot text, or None when it holds anything else."""
    out: list[str] = []
    pos = 0
    text = text.strip()
    if number(text) is not None:
        return text
    while pos < len(text):
        m = _EXPR_TOKEN.match(text, pos)
        if m is None or m.end() == pos:
            return None
        num, name, op = m.groups()
        if name is not None and name not in names:
            return None
        out.append(num or name or op)
        pos = m.end()
    return " ".join(out) if out else None


def rmot_name(name: str, taken: set[str] | None = None) -> str:
    """A vendor identifier as a legal rmot name (keywords get a trailing `_`; idempotent, so that
    rmot's own output reads back under the names it was written with)."""
    clean = re.sub(r"\W", "_", name)
    if not clean or clean[0].isdigit():
        clean = "n_" + clean
    if clean in RMOT_RESERVED:
        clean += "_"
    return clean


def same_pose(a: ir.Pose, b: ir.Pose) -> bool:
    """Equal to what the vendors print: 1 um and 1e-6 in each quaternion component (up to sign)."""
    near = all(abs(x - y) < 1e-6 for x, y in zip(a.position, b.position))
    dot = abs(sum(x * y for x, y in zip(a.quaternion, b.quaternion)))
    return near and dot > 1 - 1e-9


# The I/O, wait and call statements every vendor writes in one line, built from a match whose
# groups are (signal or name, value): a vendor reader lists its own patterns for these kinds.
SIMPLE_FORMS: dict[str, Callable[[re.Match[str], Where], Stmt]] = {
    "out": lambda m, w: SetOut(int(m.group(1)), 1.0 if m.group(2) == "ON" else 0.0, w),
    "pulse": lambda m, w: Pulse(int(m.group(1)), float(m.group(2)), w),
    "aout": lambda m, w: SetOut(int(m.group(1)), float(m.group(2)), w, analog=True),
    "wait": lambda m, w: Wait(float(m.group(1)), w),
    "wait_in": lambda m, w: WaitIn(Cond(int(m.group(1)), m.group(2) == "ON"), None, w),
    "wait_out": lambda m, w: WaitIn(Cond(int(m.group(1)), m.group(2) == "ON", output=True), None, w),
    "wait_true": lambda m, w: WaitIn(Cond(int(m.group("sig")), not m.group("neg")), None, w),  # WAIT (!DI[n])
    "call": lambda m, w: Call(m.group(1), (), w),  # the routine keeps the name it has in its file
    "call_renamed": lambda m, w: Call(rmot_name(m.group(1)), (), w),  # a routine named as rmot names it
}


def match_simple(text: str, patterns: tuple[tuple[str, re.Pattern[str]], ...], where: Where) -> Stmt | None:
    """The statement of the first (kind, pattern) in `patterns` that matches all of `text`."""
    for kind, pattern in patterns:
        m = pattern.fullmatch(text)
        if m:
            return SIMPLE_FORMS[kind](m, where)
    return None


def label_arms(text_at: Callable[[int], str], i: int, end: int, label_a: str, jump: re.Pattern[str],
               label: Callable[[str], str]) -> tuple[int, int | None] | None:
    """The lines of an if written with labels (TP, INFORM): the conditional jump at line `i`
    goes to `label_a` (the else arm, or the end); a jump to another label just before it
    (`jump`, the label's name in group 1, its line `label(name)`) ends the then-arm and marks an
    else-arm up to that label. (line of label_a, line of the end label or None), or None."""
    ja = next((k for k in range(i + 1, end) if text_at(k) == label_a), None)
    if ja is None:
        return None
    jmp = jump.fullmatch(text_at(ja - 1))
    jb = next((k for k in range(ja + 1, end) if jmp and text_at(k) == label(jmp.group(1))), None)
    return ja, jb


def label_loop(text_at: Callable[[int], str], i: int, end: int, start: str, label: str,
               close: Callable[[str, str], str], step: Callable[[str], str]) -> tuple[str, int, int, int] | None:
    """A counted loop written with a label (TP, INFORM): line `i` sets the counter (`start`:
    groups counter, first value), the next is the label (`label`: group its name), the body,
    the step line (`step(counter)`) and the conditional jump back (`close(counter, label)`:
    group the last value). (counter, first, last, line of the jump back) or None."""
    m = re.fullmatch(start, text_at(i))
    lbl = re.fullmatch(label, text_at(i + 1)) if m else None
    if m is None or lbl is None:
        return None
    back = close(m.group(1), lbl.group(1))
    j = next((k for k in range(i + 2, end) if re.fullmatch(back, text_at(k))), None)
    if j is None or not re.fullmatch(step(m.group(1)), text_at(j - 1)):
        return None
    return m.group(1), int(m.group(2)), int(re.fullmatch(back, text_at(j)).group(1)), j  # type: ignore[union-attr]


def native_line(vendor: str, raw: str) -> str:
    """A source line as the text of its native statement: TP's without its line number and with
    its `;` as the reader writes it (`IF R[2]<>3,JMP LBL[1] ;`), the others stripped."""
    if vendor != "fanuc":
        return raw.strip()
    m = re.fullmatch(r"\s*\d*:\s*(.*?)\s*;?\s*", raw)
    return f"{m.group(1)} ;" if m and m.group(1) else raw.strip()


def counter_alone(text_at: Callable[[int], str], lines: int, i: int, j: int, counter: str,
                  inside: tuple[str, ...], outside: tuple[str, ...], own: tuple[int, ...] = ()) -> bool:
    """Whether a counted loop (lines `i` to `j`; its own lines that set, step and test the counter
    `own`, else those of label_loop: i, j - 1 and j) is all the program does with its
    counter (the pattern `counter`): inside the body it appears only in the forms `inside` (the
    offsets it builds), elsewhere only in those and `outside` (setting it, counting another loop
    with it and building that loop's offsets).
    A write in the body would skip iterations the rmot `for` runs; a read after the loop would see
    the value the loop left, which the `for` has not."""
    for k in range(lines):
        text = text_at(k)
        if k in (own or (i, j - 1, j)) or not re.search(counter, text):
            continue
        if not any(re.fullmatch(form, text) for form in (inside if i < k < j else inside + outside)):
            return False
    return True


def reaches(sources: dict[str, tuple[str, str]], name: str, uses: Callable[[str], bool], call: str,
            depth: int = 0) -> bool:
    """Whether program `name` (its (path, text) in `sources`, by upper-case name), or one it
    calls (`call`: a pattern whose group 1 names the callee), 8 levels down, has text for which
    `uses` holds (a TP offset register or an INFORM shift a caller's loop sets)."""
    source = sources.get(name.upper())
    if source is None or depth > 8:
        return False
    return uses(source[1]) or any(reaches(sources, callee, uses, call, depth + 1)
                                  for callee in re.findall(call, source[1]))
