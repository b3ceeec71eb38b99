"""Positions a KRL routine computes in straight-line code, known at compile time.

KRL (KUKA KSS 8.x Operating and Programming Instructions for System Integrators, structure
variables and aggregates): `P = Q` copies the whole value of a structure (E6POS/POS/FRAME/E6AXIS);
`P.Z = P.Z + 400` changes one component and keeps the others; an aggregate `P = {X 10, Z 5}`
assigns the named components and keeps the unnamed ones (the Status and Turn too). A position
assigned from a known position (a data-list value the program never assigns, `$NULLFRAME`, an
aggregate with every component, or another known position) and then changed by components with
constant values has a value known when the compiler reads it; that knowledge ends at anything that
could change it: an assignment with a value known only at run time, a call (it may write a global or
an OUT parameter), a label (a jump lands there), and a block (a loop's back edge, a branch not
taken): the names a block assigns are forgotten on entering it and again after it. Where the module
declares an interrupt, only the routine's own variables (DECL in the routine, which no interrupt
routine sees) are known. Lines are only observed here: each keeps its own reading.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Mapping

from rmot.backends.readers.krl_data import Data, position
from rmot.backends.readers.krl_text import Line, aggregate
from rmot.backends.readers.model import Target, Where
from rmot.backends.readers.rapid import num_text, pose_expr

__all__ = ["block_end", "is_block", "is_label", "Known", "KnownPositions", "evaluate", "shift_terms", "data_value", "known_target", "literal"]

Known = tuple[str, str | None, dict[str, object], dict[str, object]]
"""(the declared type, the data-list position it was copied from (None: computed), that position's
value, the current value), values as aggregates (upper-case keys)."""

Resolve = Callable[[str], "Known | None"]

_BLOCKS = {"FOR": "ENDFOR", "IF": "ENDIF", "WHILE": "ENDWHILE", "LOOP": "ENDLOOP", "REPEAT": "UNTIL",
           "SWITCH": "ENDSWITCH", "SPLINE": "ENDSPLINE"}
_TOKEN = re.compile(r"\s*(?:(\d+\.?\d*(?:[eE][-+]?\d+)?|\.\d+(?:[eE][-+]?\d+)?)|(\w+(?:\[\s*\d+\s*\])?)\.(\w+)|([-+*/()]))")
_NULLFRAME: dict[str, object] = {k: 0.0 for k in ("X", "Y", "Z", "A", "B", "C")}
_LABEL = re.compile(r"\w+\s*:")  # a label: a GOTO lands here from anywhere
_ASSIGNS = re.compile(r"(\w+)\s*(\[[^\]]*\])?\s*(\.\w+)?\s*=(?!=)")
_CALL = re.compile(r"(?i)(\w+)\s*\((.*)\)")


def _key(text: str) -> str:
    return re.sub(r"\s+", "", text).upper()


def evaluate(text: str, component: Callable[[str, str], float | None]) -> float | None:
    """A constant arithmetic expression (numbers, `+ - * /`, parentheses, `P.X` components a callback
    knows) as a finite number; None where a term is anything else (a variable, a function)."""
    tokens: list[tuple[str, object]] = []
    pos, text = 0, text.strip()
    if text.count("(") > 32:  # nesting bounded: a hostile line cannot exhaust the stack
        return None
    while pos < len(text):
        m = _TOKEN.match(text, pos)
        if m is None or m.end() == pos:
            return None
        pos = m.end()
        if m.group(1):
            tokens.append(("n", float(m.group(1))))
        elif m.group(2):
            value = component(_key(m.group(2)), m.group(3).upper())
            if value is None:
                return None
            tokens.append(("n", value))
        else:
            tokens.append((m.group(4), None))
    value, rest = _sum(tokens, 0)
    return value if value is not None and rest == len(tokens) and math.isfinite(value) else None


def _sum(tokens: list[tuple[str, object]], i: int) -> tuple[float | None, int]:
    left, i = _product(tokens, i)
    while left is not None and i < len(tokens) and tokens[i][0] in "+-":
        op = tokens[i][0]
        right, i = _product(tokens, i + 1)
        left = None if right is None else left + right if op == "+" else left - right
    return left, i


def _product(tokens: list[tuple[str, object]], i: int) -> tuple[float | None, int]:
    left, i = _factor(tokens, i)
    while left is not None and i < len(tokens) and tokens[i][0] in "*/":
        op = tokens[i][0]
        right, i = _factor(tokens, i + 1)
        left = None if right is None or (op == "/" and right == 0.0) else left * right if op == "*" else left / right
    return left, i


def _factor(tokens: list[tuple[str, object]], i: int, depth: int = 0) -> tuple[float | None, int]:
    if i >= len(tokens) or depth > 32:
        return None, i
    kind, value = tokens[i]
    if kind in "+-":
        inner, j = _factor(tokens, i + 1, depth + 1)
        return (None if inner is None else -inner if kind == "-" else inner), j
    if kind == "n":
        return value, i + 1  # type: ignore[return-value]
    if kind == "(":
        inner, j = _sum(tokens, i + 1)
        return (inner, j + 1) if j < len(tokens) and tokens[j][0] == ")" else (None, j)
    return None, i


def is_label(ln: Line) -> bool:
    """Whether a line is a label (`name:`), where a GOTO lands from anywhere."""
    return _LABEL.fullmatch(ln.text) is not None


def is_block(ln: Line) -> bool:
    """Whether a line opens a block (FOR, IF, WHILE, LOOP, REPEAT, SWITCH, SPLINE)."""
    return ln.word in _BLOCKS


def _opener(lines: list[Line], i: int) -> int:
    """The index of the line that opens the block line `i` (an ELSE, a CASE) is a branch of."""
    depth = 0
    for j in range(i - 1, -1, -1):
        depth += lines[j].word in _BLOCKS.values()
        if lines[j].word in _BLOCKS:
            if depth == 0:
                return j
            depth -= 1
    return 0


def block_end(lines: list[Line], i: int) -> int:
    """The index of the line that ends the block opened at `i` (nested ones included)."""
    start, end = lines[i].word, _BLOCKS[lines[i].word]
    depth = 0
    for j in range(i, len(lines)):
        depth += lines[j].word == start
        depth -= lines[j].word == end
        if depth <= 0:
            return j
    return len(lines) - 1


class KnownPositions:
    """The positions known at the line being read of one routine (see the module's docstring)."""

    def __init__(self, interrupts: bool) -> None:
        self.interrupts = interrupts  # the module declares an interrupt: only the routine's own variables
        self.values: dict[str, Known] = {}
        self.locals: set[str] = set()
        self.lost: dict[str, str] = {}  # NAME -> why its value is not known here (the line that made it so)

    def routine(self, lines: list[Line], i: int) -> None:
        """A routine starts at `i`: nothing is known; its own variables are the DECLs up to its END."""
        self.values = {}
        self.locals = set()
        self.lost = {}
        for ln in lines[i + 1:]:
            if ln.word == "END":
                break
            m = re.match(r"(?i)\s*(?:DECL\s+)?(?:E6POS|POS|FRAME|E6AXIS|AXIS)\s+(.*)", ln.text)
            if m is not None:
                self.locals |= {re.sub(r"\[.*", "", n).strip().upper() for n in re.split(r",(?![^\[]*\])", m.group(1))}

    def get(self, text: str) -> Known | None:
        return self.values.get(_key(text))

    def observe(self, lines: list[Line], i: int, resolve: Resolve) -> None:
        """Line `i` is about to be read: learn what it assigns, or forget what it may change."""
        ln = lines[i]
        if i > 0 and lines[i - 1].word in ("ELSE", "CASE", "DEFAULT"):  # a branch: the ones before it did not run
            opener = _opener(lines, i - 1)
            self.disturb(lines[opener + 1:i - 1], lines[opener])
        if ln.word in _BLOCKS:
            self.disturb(lines[i:block_end(lines, i) + 1], ln)
        elif not self._assign(ln.text, resolve):
            self.disturb([ln])

    def disturb(self, lines: list[Line], block: Line | None = None) -> None:
        """Forget what these lines may change (a block's, opened by `block`, before and after it is read)."""
        for ln in lines:
            text = ln.text
            if is_label(ln):
                self._forget(list(self.values), f"unknown after the label at line {ln.where.line}, where a jump may "
                             "land: its value is known only at run time")
            m = _ASSIGNS.match(text)
            if m is not None:
                name = m.group(1).upper()
                why = (f"assigned inside the block at line {block.where.line} (a loop repeats it, a branch may not run): "
                       "its value is known only at run time" if block is not None else
                       f"assigned at line {ln.where.line} (`{text[:40]}`) a value known only at run time")
                if block is not None or m.group(3) is None or name not in self.lost:
                    self.lost[name] = why
                self._forget([k for k in self.values if k.split("[")[0] == name], why)
            call = _CALL.fullmatch(text)
            if call is not None and call.group(1).upper() != "BAS":
                self._forget([k for k in self.values if self._call_writes(call, k.split("[")[0])],
                             f"known before `{call.group(1)}(..)` at line {ln.where.line}, which may change it: its value is known "
                             "only at run time")

    def _call_writes(self, call: re.Match[str], name: str) -> bool:
        """Whether a call may write variable `name`: a global one (not the routine's own), or one
        passed to it (an OUT parameter)."""
        return name not in self.locals or name in {w.upper() for w in re.findall(r"\w+", call.group(2))}

    def may_change(self, ln: Line, name: str) -> str | None:
        """Why line `ln` may change variable `name` (upper case) by the rules above (a label, an
        assignment to it, a call that may write it, an interrupt routine where the module declares
        one and it is not the routine's own), as its value's reason to be known only at run time;
        None where it cannot."""
        text = ln.text
        if self.interrupts and name not in self.locals:
            return "a global variable an interrupt routine may change at any time: its value is known only at run time"
        if _LABEL.fullmatch(text):
            return f"unknown after the label at line {ln.where.line}, where a jump may land"
        m = _ASSIGNS.match(text)
        if m is not None and m.group(1).upper() == name:
            return f"assigned at line {ln.where.line} (`{text[:40]}`) a value known only at run time"
        call = _CALL.fullmatch(text)
        if call is not None and call.group(1).upper() != "BAS" and self._call_writes(call, name):
            return f"known before `{call.group(1)}(..)` at line {ln.where.line}, which may change it"
        return None

    def _forget(self, keys: list[str], why: str) -> None:
        for key in keys:
            del self.values[key]
            self.lost[key.split("[")[0]] = why

    def _assign(self, text: str, resolve: Resolve) -> bool:
        """`P = Q`, `P = {..}` or `P.C = expr` with a value known here: learnt (True)."""
        m = re.fullmatch(r"(\w+(?:\s*\[\s*\d+\s*\])?)\s*(?:\.(\w+))?\s*=\s*(.+)", text)
        if m is None:
            return False
        name = _key(m.group(1))
        if self.interrupts and name.split("[")[0] not in self.locals:
            return False
        current = self.values.get(name)
        if m.group(2) is not None:
            part = m.group(2).upper()
            value = evaluate(m.group(3), lambda p, c: self._component(p, c, resolve))
            if current is None or value is None or not isinstance(current[3].get(part), float):
                return False
            self.values[name] = (current[0], current[1], current[2], {**current[3], part: value})
            self.lost.pop(name.split("[")[0], None)
            return True
        source = m.group(3).strip()
        found = self.values.get(_key(source)) or resolve(_key(source))
        if _key(source) == "$NULLFRAME":
            found = ("FRAME", None, _NULLFRAME, dict(_NULLFRAME))
        if found is None and not self._aggregate(name, current, source):
            return False
        self.values[name] = found or self.values[name]
        self.lost.pop(name.split("[")[0], None)
        return True

    def _aggregate(self, name: str, current: Known | None, source: str) -> bool:
        agg = aggregate(source)
        if agg is None or not agg or not all(isinstance(v, float) for v in agg.values()):
            return False
        if current is not None and set(agg) <= set(current[3]):
            self.values[name] = (current[0], current[1], current[2], {**current[3], **agg})
            return True
        if {"X", "Y", "Z", "A", "B", "C"} <= set(agg):
            self.values[name] = ("POS", None, dict(agg), dict(agg))
            return True
        return False

    def _component(self, name: str, part: str, resolve: Resolve) -> float | None:
        found = self.values.get(name) or resolve(name)
        value = found[3].get(part) if found is not None else None
        return value if isinstance(value, float) else None


def shift_terms(known: Known) -> Mapping[str, float] | None:
    """The X/Y/Z offsets (mm) from the data-list position a known value was copied from, when it
    differs from it by these only; None where it was computed otherwise."""
    _, origin, before, now = known
    if origin is None or set(before) != set(now):
        return None
    if any(now[k] != before[k] for k in now if k not in ("X", "Y", "Z")):
        return None
    return {k.lower(): float(now[k]) - float(before[k]) for k in ("X", "Y", "Z")  # type: ignore[arg-type]
            if k in now and now[k] != before[k]}


def literal(target: Target) -> str:
    """A position's value as an rmot expression: a pose, or the axes in degrees."""
    return pose_expr(target.pose) if target.pose is not None else \
        f"joints({', '.join(num_text(j) for j in target.joints or ())}) deg"


def data_value(key: str, data_lists: tuple[Mapping[str, Data], ...], assigned: set[str]) -> Known | None:
    """A data-list position the program never assigns (`key`), as a value a computation starts from."""
    found = next((d[key] for d in data_lists if key in d), None)
    if key.split("[")[0] in assigned or found is None or not isinstance(found[2], dict) or position(*found) is None:
        return None
    return (found[0], key, found[2], dict(found[2]))


def known_target(known: Known, at: Where, target_of: Callable[[str, Where], tuple[str, str | None, Target | None] | None]
                 ) -> tuple[str, str | None, Target | None] | None:
    """A position computed in straight-line code as a move's target: a shift of the data-list position
    it was copied from where only X, Y, Z changed (the offsets in that position's own base, as
    `P.X = P.X + d` adds them), else the literal value."""
    decl = position(known[0], "", known[3], at)
    terms = shift_terms(known)
    origin = target_of(known[1], at) if decl is not None and known[1] is not None and terms is not None else None
    if decl is None or origin is None or terms is None:
        return (literal(decl), None, decl) if decl is not None else None
    text = ", ".join(f"{axis}={num_text(value)}mm" for axis, value in sorted(terms.items()) if num_text(value) != "0")
    return (f"shift({origin[0]}, {text})" if text else origin[0], origin[1], decl)
