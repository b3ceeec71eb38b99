"""RAPID task variables and the statements on them, read into rmot's runtime logic (§12).

A `VAR` or `PERS` `num` or `bool` the module assigns (`:=`, `Incr`, `Decr`) is a task variable:
`var name: int|num|bool = value` at the top of the main routine (RAPID starts a num at 0 and a
bool at FALSE where no value is given: Technical reference manual – RAPID overview, "Data
declarations"). A num is an rmot `int` when its value and every value assigned to it are whole
(RAPID's num holds both). A `PERS` keeps its value from one run to the next, which a task
variable does not: W541 where the main routine does not set it first thing. rmot's procs do not see a task's variables, so only the main routine
reads them; elsewhere their statements stay native. `WaitDI`/`WaitUntil ... \\TimeFlag:=f`
followed by `IF f THEN ... ENDIF`, with `f` read nowhere else, is `wait until ... timeout T else
{ ... }` (RAPID Instructions, WaitDI: the flag is TRUE when the time ran out).
"""

from __future__ import annotations

import re
from itertools import islice
from collections.abc import Callable

from rmot.backends.readers.common import Tally
from rmot.backends.readers.logic import RAPID, fits, fold_first_values, translate, warn_persistent
from rmot.backends.readers.model import Assign, Cond, Conds, GroupIn, If, Stmt, VarDecl, Where
from rmot.backends.readers.rapid_text import Statement

__all__ = ["RapidVars", "assigned_names", "timeout_flags", "condition"]

_ASSIGNED = re.compile(r"(?i)^(?:(\w+)\s*:=|(?:Incr|Decr)\s+(\w+)\s*$)")


def assigned_names(stmts: list[Statement]) -> dict[str, list[str]]:
    """Upper-case name -> the expressions assigned to it (`Incr`/`Decr`: `x+1`)."""
    out: dict[str, list[str]] = {}
    for st in stmts:
        m = _ASSIGNED.match(st.text)
        if m:
            name = (m.group(1) or m.group(2)).upper()
            out.setdefault(name, []).append(st.text.split(":=", 1)[1] if m.group(1) else "1")
    return out


def timeout_flags(stmts: list[Statement]) -> set[str]:
    """Flags set by a wait's `\\TimeFlag` and read only by the `IF flag THEN` right after it."""
    flags = {m.upper() for st in stmts for m in re.findall(r"(?i)\\TimeFlag\s*:=\s*(\w+)", st.text)}
    where_used: dict[str, list[int]] = {}
    for i, st in enumerate(stmts):
        for word in {w.upper() for w in re.findall(r"\w+", st.text)} & flags:
            where_used.setdefault(word, []).append(i)
    out = set()
    for flag in flags:
        uses = where_used.get(flag, [])
        waits = [i for i in uses if re.search(r"(?i)\\TimeFlag", stmts[i].text)]
        ifs = [i for i in uses if re.fullmatch(rf"(?i)IF\s+{flag}\s+THEN", stmts[i].text)]
        decls = [i for i in uses if re.match(r"(?i)^(?:LOCAL\s+|TASK\s+)*VAR\s+bool\s+", stmts[i].text)]
        if len(decls) == 1 and len(waits) == len(ifs) and all(w + 1 == f for w, f in zip(waits, ifs)) \
                and len(uses) == 1 + len(waits) + len(ifs):
            out.add(flag)
    return out


def condition(text: str, names: dict[str, tuple[str, str]]) -> Conds | None:
    """A RAPID bool expression over the names and digital inputs (`DInput(s) = 1`, `s = 0`,
    `TestDI(s)`) and group inputs (`GInput(s) = 3`: function GInput, the unsigned integer of the
    GI signal s), None when it has no rmot form."""
    found = translate(text, RAPID, names, lambda tokens, i: _input(tokens, i, names))
    return found[0] if found is not None and found[1] == "bool" else None


def _input(tokens: list[str], i: int, names: dict[str, tuple[str, str]]) -> tuple[Cond | GroupIn, int] | None:
    t = [x.upper() for x in tokens[i:i + 6]]
    if len(t) >= 4 and t[0] == "GINPUT" and t[1] == "(" and t[3] == ")":  # a GI signal's unsigned integer
        return GroupIn(tokens[i + 2]), 4
    if len(t) >= 6 and t[0] == "DINPUT" and t[1] == "(" and t[3] == ")" and t[4] == "=" and t[5] in ("0", "1"):
        return Cond(tokens[i + 2], t[5] == "1"), 6
    if len(t) >= 6 and t[0] == "DOUTPUT" and t[1] == "(" and t[3] == ")" and t[4] == "=" and t[5] in ("0", "1"):
        return Cond(tokens[i + 2], t[5] == "1", output=True), 6  # the DO signal's state (function DOutput)
    if len(t) >= 4 and t[0] == "TESTDI" and t[1] == "(" and t[3] == ")":
        return Cond(tokens[i + 2], True), 4
    if len(t) >= 3 and re.fullmatch(r"[A-Z_]\w*", t[0]) and t[0] not in names and t[0] not in ("TRUE", "FALSE", "NOT") \
            and t[1] == "=" and t[2] in ("0", "1") and (len(t) == 3 or t[3] not in ("+", "-", "*", "/")):
        return Cond(tokens[i], t[2] == "1"), 3
    return None


class RapidVars:
    """The task variables of one module: declared, typed, and the statements on them."""

    def __init__(self, stmts: list[Statement], tally: Tally) -> None:
        self.tally = tally
        self.persistent: set[str] = set()  # the PERS variables
        self.assigned = assigned_names(stmts)
        self.flags = timeout_flags(stmts)
        self.vars: dict[str, tuple[str, str]] = {}  # upper -> (name, rmot type)
        self.decls: list[VarDecl] = []
        self.visible: dict[str, tuple[str, str]] = {}  # the names the routine being read may use
        self.main: bool | None = None  # reading the main routine, another, or the module level
        self.stmts = stmts

    def enter(self, main: bool | None, consts: dict[str, float]) -> None:
        """Start (or, with None, end) reading a routine: the main one sees the task variables, every
        one the module's numeric constants."""
        self.main = main
        self.visible = {k.upper(): (k, "int" if v == int(v) else "num") for k, v in consts.items()}
        if main:
            self.visible = _Both(self.visible, self.vars)

    def flag_of(self, wait: Statement, start: int) -> bool:
        """Whether `wait` sets a timeout flag only the `IF flag THEN` block at `start` reads,
        a block with no ELSE."""
        m = re.search(r"(?i)\\TimeFlag\s*:=\s*(\w+)$", wait.text)
        if m is None or m.group(1).upper() not in self.flags or self.stmts[start].word != "IF":
            return False
        depth = 0
        for st in islice(self.stmts, start, None):
            opens = st.word == "IF" and re.search(r"(?i)\bTHEN\s*$", st.text) is not None
            depth += 1 if opens else -1 if st.word == "ENDIF" else 0
            if depth == 1 and st.word in ("ELSE", "ELSEIF"):
                return False
            if depth == 0:
                return True
        return False

    def declare(self, kind: str, type_: str, name: str, value: str | None, where: Where) -> bool:
        """Read `VAR|PERS num|bool name [:= value]` as a task variable where it is one."""
        key = name.upper()
        if kind.upper() == "CONST" or type_.lower() not in ("num", "bool") or key in self.vars:
            return False
        if key in self.flags and type_.lower() == "bool":
            return True  # written by the wait's `timeout ... else`
        if key not in self.assigned:
            return False
        text = value if value is not None else ("FALSE" if type_.lower() == "bool" else "0")
        found = translate(text, RAPID, {}, lambda tokens, i: None)
        if found is None or (found[1] == "bool") != (type_.lower() == "bool"):
            return False
        rtype = found[1] if found[1] == "bool" else self._num_type(key, found[1])
        self.vars[key] = (name, rtype)
        if kind.upper() == "PERS":
            self.persistent.add(name)
        self.decls.append(VarDecl(name, rtype, found[0], where))
        return True

    def _num_type(self, key: str, init: str) -> str:
        """int where the value and every assigned expression are whole numbers (no `/`, no
        decimal point, no name but variables assigned such expressions)."""
        seen: set[str] = set()

        def whole(k: str) -> bool:
            if k in seen:
                return True
            seen.add(k)
            for expr in self.assigned.get(k, []):
                if re.search(r"[./]|\d[eE]", expr):
                    return False
                names = [n.upper() for n in re.findall(r"[A-Za-z_]\w*", expr) if n.upper() not in ("DIV", "MOD")]
                if any(n not in self.assigned or not whole(n) for n in names):  # another name: its value unknown here
                    return False
            return True

        return "int" if init == "int" and whole(key) else "num"

    def fold_first_values(self, body: tuple[Stmt, ...]) -> tuple[list[VarDecl], tuple[Stmt, ...]]:
        """The declarations with the values the main routine starts by assigning (logic.py)."""
        decls, rest = fold_first_values(self.decls, body)
        warn_persistent(self.tally, self.decls, decls, self.persistent)
        return decls, rest

    def test(self, i: int, block: Callable[[int, tuple[str, ...]], tuple[list[Stmt], int]]
             ) -> tuple[list[Stmt], int] | None:
        """`TEST n` `CASE 1, 2:` .. `DEFAULT:` .. `ENDTEST` on a whole-number variable or constant,
        every CASE value a whole number → `if n == 1 or n == 2 { } else ..` (RAPID Instructions,
        TEST: the first CASE equal to n runs, else DEFAULT)."""
        m = re.fullmatch(r"(?i)TEST\s+(\w+)", self.stmts[i].text)
        found = self.visible[m.group(1).upper()] if m and m.group(1).upper() in self.visible else None
        cases = _cases(self.stmts, i) if found is not None and found[1] == "int" else None
        if cases is None:
            return None
        arms, j = [], i
        for k, values in cases:
            body, j = block(k + 1, ("CASE", "DEFAULT", "ENDTEST"))
            arms.append((values, body, self.stmts[k].where))
        orelse: tuple[Stmt, ...] = tuple(arms.pop()[1]) if not arms[-1][0] else ()
        for values, body, where in reversed(arms):
            test = Conds("logic", (), " or ".join(f"{found[0]} == {v}" for v in values))  # type: ignore[index]
            orelse = (If(test, tuple(body), orelse, where),)
        self.tally.imported += 1
        return list(orelse), j + 1

    def statement(self, st: Statement) -> Assign | None:
        """`x := e;`, `Incr x;`, `Decr x;` on a visible task variable."""
        m = _ASSIGNED.match(st.text)
        if m is None:
            return None
        key = (m.group(1) or m.group(2)).upper()
        if key not in self.visible:
            return None
        name, type_ = self.visible[key]
        if m.group(1):
            text = st.text.split(":=", 1)[1]
        else:
            text = f"{name} {'+' if st.word == 'INCR' else '-'} 1"
        found = translate(text, RAPID, self.visible, lambda tokens, i: _input(tokens, i, self.visible))
        if found is None or not fits(type_, found[1]):
            return None
        return Assign(name, found[0], st.where)


def _cases(stmts: list[Statement], i: int) -> list[tuple[int, list[str]]] | None:
    """The CASE/DEFAULT statements of the TEST at `i` (index, whole values; DEFAULT: none, last),
    None where a value is not a whole number or a statement comes before the first CASE."""
    cases: list[tuple[int, list[str]]] = []
    depth, j = 0, i + 1
    while j < len(stmts) and (depth or stmts[j].word != "ENDTEST"):
        st = stmts[j]
        depth += (st.word == "TEST") - (st.word == "ENDTEST")
        if depth == 0 and st.word in ("CASE", "DEFAULT"):
            values = re.fullmatch(r"(?i)CASE\s+(-?\d+(?:\s*,\s*-?\d+)*)\s*:", st.text)
            if (st.word == "CASE" and values is None) or (cases and not cases[-1][1]):
                return None
            cases.append((j, [str(int(v)) for v in re.split(r"\s*,\s*", values.group(1))] if values else []))
        elif depth == 0 and not cases:
            return None
        j += 1
    return cases if j < len(stmts) and cases else None


class _Both(dict[str, tuple[str, str]]):
    """The constants, and the task variables as they are declared (a view, read at each lookup)."""

    def __init__(self, consts: dict[str, tuple[str, str]], variables: dict[str, tuple[str, str]]) -> None:
        super().__init__(consts)
        self.variables = variables

    def __contains__(self, key: object) -> bool:
        return key in self.variables or super().__contains__(key)

    def __getitem__(self, key: str) -> tuple[str, str]:
        return self.variables[key] if key in self.variables else super().__getitem__(key)
