"""KRL task variables and the statements on them, read into rmot's runtime logic (§12).

A scalar `INT`, `REAL` or `BOOL` (KSS 8.x, "Data types": INT whole, REAL floating point, BOOL
TRUE/FALSE) declared in the main DEF (`DECL INT n`, `INT n, m`) or in its .dat (`DECL INT
n=0`) that the main DEF assigns (`n = e`) is a task variable: `var n: int|num|bool = v` at the
top of the task's body, with the .dat's value (W541 where the DEF does not set it first thing:
a .dat keeps the value the last run left), else 0 / off (a KRL variable read before it is
given a value stops the program; a `n = value` the DEF starts with becomes the declared value).
Assignments `n = e` where the value's type fits (a REAL into an INT would be rounded by KRL:
native), `IF`/`WHILE`/`WAIT FOR` on expressions over them and the digital inputs (`$IN[n]`, a
SIGNAL's name of one input), and `SWITCH n` on an INT variable with whole CASE values. Only the
main DEF reads them (rmot's procs do not see a task's variables); `$config.dat` globals, which
other programs may set, are not variables here.

A whole number the program tests but neither declares nor assigns (`SWITCH PGNO`, `IF
(nStation == 2)`) is a global the PLC or another task sets: a group input `gin[k]` of that name
(W534 at its first use), where no `$config.dat` is found or the one found declares it as a
SIGNAL of a group of inputs or an INT (krl_names.group_globals); `SWITCH` on it is an if chain.
Likewise a `$FLAG[n]` or a BOOL global of the `$config.dat` found that the program tests and never
sets is another program's (the submit interpreter, the PLC, an interrupt): the input of that name
(W549 at its first read). One it only resets is a handshake and stays native (krl_vars.raised_why).
"""

from __future__ import annotations

import re
from collections.abc import Callable

from rmot.backends.readers import codes
from rmot.backends.readers.common import Tally, rmot_name
from rmot.backends.readers.krl_names import declared_names
from rmot.backends.readers.krl_text import Line, declarations, lines
from rmot.backends.readers.krl_vars import Global, flag_names, outside_setup, global_note, global_vars, raised_elsewhere, raised_why
from rmot.backends.readers.logic import KRL, fits, fold_first_values, translate, warn_persistent
from rmot.backends.readers.model import (
    Assign, Cond, Conds, GroupIn, Stmt, Stop, VarDecl, WaitIn, Where, While, group_reads, leaves,
)

__all__ = ["KrlVars"]

_TYPES = {"INT": "int", "REAL": "num", "BOOL": "bool"}
_LOCAL = re.compile(r"(?i)^(?:DECL\s+)?(INT|REAL|BOOL)\s+([A-Za-z_]\w*(?:\s*,\s*[A-Za-z_]\w*)*)$")
_ASSIGN = re.compile(r"(?i)^([A-Za-z_]\w*)\s*=(?!=)\s*(.+)$")
# KRL's words an expression may hold that are never a name (KSS 8.x operators and literals)
_KEYWORDS = frozenset({"TRUE", "FALSE", "NOT", "AND", "OR", "EXOR", "B_AND", "B_OR", "B_NOT", "B_EXOR"})


def _loop_end(found: list[Line], i: int) -> int | None:
    """The index of the ENDLOOP/UNTIL closing the loop at `i`, None where an EXIT leaves it
    (an EXIT leaves the innermost LOOP, FOR, WHILE or REPEAT)."""
    depth = 0
    for j in range(i, len(found)):
        word = found[j].word if found[j].fold is None else ""
        depth += (word in ("LOOP", "FOR", "WHILE", "REPEAT")) - (word in ("ENDLOOP", "ENDFOR", "ENDWHILE", "UNTIL"))
        if word == "EXIT" and depth == 1:
            return None
        if depth == 0:
            return j
    return None


def _exits(found: list[Line], i: int) -> list[int]:
    """The EXIT lines that leave the LOOP at `i`, then its ENDLOOP (none where it has no end)."""
    depth, out = 0, []
    for j in range(i, len(found)):
        word = found[j].word if found[j].fold is None else ""
        depth += (word in ("LOOP", "FOR", "WHILE", "REPEAT")) - (word in ("ENDLOOP", "ENDFOR", "ENDWHILE", "UNTIL"))
        if word == "EXIT" and depth == 1:
            out.append(j)
        if depth == 0:
            return out + [j]
    return []


def _main_lines(found: list[Line], name: str) -> list[Line]:
    """The lines of the DEF called `name` (the module's main routine)."""
    out: list[Line] = []
    inside = False
    for ln in found:
        if re.match(rf"(?i)^(?:GLOBAL\s+)?DEF\s+{re.escape(name)}\s*\(", ln.text):
            inside = True
        elif inside and ln.word == "END":
            return out
        elif inside:
            out.append(ln)
    return out


class KrlVars:
    """The task variables of one KRL program and the statements on them."""

    def __init__(self, found: list[Line], name: str, dat: tuple[str, str] | None, taken: set[str],
                 signal: Callable[[str], int | None], tally: Tally | None = None,
                 group: Callable[[str], bool] = lambda name: False, config: tuple[str, str] | None = None,
                 output: Callable[[str], int | None] = lambda name: None) -> None:
        self.tally, self.dat, self.group = tally, dat, group
        self.groups_warned: set[str] = set()  # group inputs warned at their first use (W534)
        self.persistent: set[str] = set()  # the .dat's variables
        whole = _main_lines(found, name)
        body = outside_setup(whole)  # what the set-up folds assign is not read
        assigned = {m.group(1).upper() for ln in body for m in [_ASSIGN.match(ln.text)] if m and ln.fold is None}
        self.set_up_only: set[str] = {m.group(1).upper() for ln in whole for m in [_ASSIGN.match(ln.text)] if m} - assigned
        taken = taken | {m.group(1).upper() for ln in found for m in [re.match(r"(?i)FOR\s+(\w+)", ln.text)] if m}
        self.vars: dict[str, tuple[str, str]] = {}  # upper -> (rmot name, type)
        self.decls: list[VarDecl] = []
        self.signal, self.output = signal, output
        self.visible: dict[str, tuple[str, str]] = {}
        self.main = False  # reading the main DEF
        self.exiting: Where | None = None  # the EXIT of the loop being read that becomes its condition
        self.end_label: str | None = None
        self.skipped: set[Where | None] = set()  # the increments of stepped FOR loops, read into their count
        found_decls = [(d.type, d.name, d.value, d.where) for d in declarations(lines(*dat))] if dat else []
        self.persistent = {rmot_name(d[1]) for d in found_decls}
        for ln in body:
            m = _LOCAL.match(ln.text)
            for n in re.split(r"\s*,\s*", m.group(2)) if m else []:
                found_decls.append((m.group(1).upper(), n, None, ln.where))  # type: ignore[union-attr]
        inside = {id(ln) for ln in body}
        known = {d[1].upper() for d in found_decls} | taken | declared_names("\n".join(ln.text for ln in found))
        self.globals: dict[str, Global] = {rmot_name(g.name): g for g in global_vars(body, [ln for ln in found if id(ln) not in inside],
                                                                  known, config)}
        found_decls += [(g.type, g.name, g.value, g.where) for g in self.globals.values()]
        assigned |= {g.name.upper() for g in self.globals.values()}
        for type_, var, value, where in found_decls:
            key = var.upper()
            if type_ not in _TYPES or key not in assigned or key in self.vars or key in taken or "[" in var:
                continue
            init = translate(value or ("FALSE" if type_ == "BOOL" else "0"), KRL, {}, lambda t, i: None)
            if init is None or not fits(_TYPES[type_], init[1]):
                continue
            self.vars[key] = (rmot_name(var), _TYPES[type_])
            self.decls.append(VarDecl(rmot_name(var), _TYPES[type_], init[0], where))
        self.raised = raised_elsewhere(found, known | set(self.vars), config)  # handshake flags another program raises
        statements = [ln for ln in body if ln.text and ln.fold is None and not ln.endfold]
        last = re.fullmatch(r"([A-Za-z_]\w*)\s*:", statements[-1].text) if statements else None
        self.end_label = last.group(1).upper() if last else None  # a label right before the main DEF's END

    def timed_else(self, found: list[Line], i: int, cond_of: Callable[[str], Cond | Conds | None]) -> bool:
        """Whether the lines at `i` are the backend's timed wait with a branch: timer reset, `WAIT FOR
        (c) OR ($TIMER[k]>=ms)`, `IF NOT (c) THEN` B `ENDIF` (`wait until c timeout T else { B }`)."""
        head = self._timed_head(found, i)
        return head is not None and cond_of(head[0]) is not None

    def _timed_head(self, found: list[Line], i: int) -> tuple[str, float] | None:
        texts = [ln.text.replace(" ", "").upper() for ln in found[i:i + 6]]
        m = re.fullmatch(r"\$TIMER_STOP\[(\d+)\]=TRUE", texts[0]) if len(texts) == 6 else None
        k = m.group(1) if m else ""
        w = re.fullmatch(rf"WAITFOR\((.*)\)OR\(\$TIMER\[{k}\]>=(\d+)\)", texts[3]) if m else None
        ok = (w is not None and texts[1] == f"$TIMER[{k}]=0" and texts[2] == f"$TIMER_STOP[{k}]=FALSE"
              and texts[4] == f"$TIMER_STOP[{k}]=TRUE" and texts[5] == f"IFNOT({w.group(1)})THEN")
        if not ok or w is None:
            return None
        head = re.fullmatch(r"(?i)WAIT\s+FOR\s+\((.*)\)\s+OR\s+\(\s*\$TIMER\[\d+\]\s*>=\s*\d+\s*\)", found[i + 3].text)
        return (head.group(1), int(w.group(2)) / 1000.0) if head else None

    def with_else(self, timed: WaitIn | None, found: list[Line], i: int,
                  block: Callable[[int, tuple[str, ...]], tuple[list[Stmt], int]],
                  cond_of: Callable[[str], Cond | Conds | None]) -> tuple[list[Stmt], int]:
        """The timed wait at `i` (`timed`: the one that HALTs, read already) and where reading goes on."""
        if timed is not None:
            return [timed], i + 8
        text, seconds = self._timed_head(found, i)  # type: ignore[misc]
        cond = cond_of(text)
        orelse, j = block(i + 6, ("ENDIF",))
        return [WaitIn(cond, seconds, found[i + 3].where, tuple(orelse))], j + 1  # type: ignore[arg-type]

    def routine(self, main: bool, read: Callable[[], tuple[list[Stmt], int]]) -> tuple[list[Stmt], int]:
        """A DEF's body as `read` gives it: the main one sees the task variables and gets their
        declarations at its top."""
        self.visible, self.main = (self.vars if main else {}), main
        body, end = read()
        return (list(self.hoisted(tuple(body))) if main else body), end

    def hoisted(self, body: tuple[Stmt, ...]) -> tuple[Stmt, ...]:
        """The main DEF's body with the declarations at its top."""
        decls, rest = fold_first_values(self.decls, body)
        if self.tally is not None:
            warn_persistent(self.tally, self.decls, decls, self.persistent, dict([self.dat] if self.dat else []))
            for before, after in zip(self.decls, decls):
                found = self.globals.get(before.name)
                if found is not None:
                    self.tally.warn(codes.GLOBAL_READ_AS_VARIABLE, global_note(found, before.init.text,
                                                                               after.init is not before.init), found.where)
        return (*decls, *rest)

    def _input(self, tokens: list[str], i: int) -> tuple[Cond | GroupIn, int] | None:
        t = [x.upper() for x in tokens[i:i + 4]]
        if len(t) == 4 and t[0] == "$IN" and t[1] == "[" and t[2].isdigit() and t[3] == "]":
            return Cond(int(t[2]), True), 4
        if len(t) == 4 and t[0] == "$OUT" and t[1] == "[" and t[2].isdigit() and t[3] == "]":  # the output's state
            return Cond(int(t[2]), True, output=True), 4
        if len(t) == 4 and t[0] == "$FLAG" and t[1] == "[" and t[2].isdigit() and t[3] == "]" \
                and self.raised.get(f"FLAG_{int(t[2])}") == "":  # a flag another program raises: an input
            return Cond(f"$FLAG[{int(t[2])}]", True), 4
        if t and (len(t) < 2 or t[1] not in ("[", "(", ".")) and self.raised.get(t[0]) == "" and t[0] not in self.visible:
            flag = re.fullmatch(r"FLAG_(\d+)", t[0])  # (`$FLAG[n]` spelled as a task variable's name)
            return Cond(f"$FLAG[{flag.group(1)}]" if flag else tokens[i], True), 1  # or a BOOL global never set
        port = self.signal(t[0]) if t and t[0] not in self.visible else None
        alone = len(t) < 2 or t[1] not in ("[", "(", ".")
        out = self.output(t[0]) if t and port is None and t[0] not in self.visible else None
        if out is not None and alone:  # an output's SIGNAL reads the output's state, as $OUT[n] does
            return Cond(out, True, output=True), 1
        if port is None and t and alone and self._group_name(t[0]):
            return GroupIn(tokens[i]), 1
        return (Cond(port, True), 1) if port is not None and alone else None

    def _group_name(self, key: str) -> bool:
        return (re.fullmatch(r"[A-Z_]\w*", key) is not None and key not in _KEYWORDS and key not in self.visible
                and self.group(key))

    def condition(self, text: str, where: Where | None = None) -> Conds | None:
        """A KRL bool expression over the visible variables and inputs; None without an rmot form."""
        found = translate(self._spelled(text), KRL, self.visible, self._input, int_division=True)
        cond = found[0] if found is not None and found[1] == "bool" else None
        if cond is not None and where is not None:
            self.warn_external(cond, where)
        return cond

    def warn_external(self, value: Cond | Conds | GroupIn, where: Where) -> None:
        """W534 at the first read of each group input `value` reads; W549 at the first read of
        each flag or BOOL global another program raises, read as an input."""
        for c in leaves(value):
            key = flag_names(str(c.signal)).upper()
            if self.raised.get(key) == "" and key not in self.groups_warned and self.tally is not None:
                self.groups_warned.add(key)
                self.tally.warn(codes.BIT_READ_AS_INPUT, f"`{c.signal}` is a global flag the program tests but never "
                                "sets (another program, the submit interpreter, the PLC or an interrupt raises it): "
                                "read as the input of that name, so each arm is planned and verified; compiled "
                                "back, it is that input, not the flag: give --cell to wire it", where)
        for g in group_reads(value):
            if str(g.signal).upper() in self.groups_warned or self.tally is None:
                continue
            self.groups_warned.add(str(g.signal).upper())
            self.tally.warn(codes.NAME_READ_AS_GROUP_INPUT, f"`{g.signal}` is a whole number the program neither "
                            "declares nor assigns: read as the group input of that name (a SIGNAL group or INT "
                            "global of $config.dat the PLC or another task sets); give --cell to check it", where)

    def statement(self, ln: Line) -> Assign | Stop | None:
        """`n = e` on a visible task variable; `RETURN` from the main DEF (it ends the program,
        KSS 8.x "RETURN": back to the caller, and the main DEF has none), and `GOTO L` there where
        the label `L:` is its last statement (KSS 8.x "GOTO": the jump reaches END, as RETURN)."""
        if self.main and re.fullmatch(r"(?i)RETURN", ln.text):
            return Stop(ln.where)
        jump = re.fullmatch(r"(?i)GOTO\s+(\w+)", ln.text)
        if self.main and jump and jump.group(1).upper() == self.end_label:
            return Stop(ln.where)  # a jump to the main DEF's END is its RETURN
        if ln.where == self.exiting:
            return Stop(ln.where)  # the loop's own EXIT, read into the loop's condition (loop())
        m = _ASSIGN.match(self._spelled(ln.text))
        if m is None or m.group(1).upper() not in self.visible:
            return None
        name, type_ = self.visible[m.group(1).upper()]
        found = translate(m.group(2), KRL, self.visible, self._input, int_division=True)
        if found is None or not fits(type_, found[1]):
            return None
        self.warn_external(found[0], ln.where)
        return Assign(name, found[0], ln.where)

    def why(self, text: str) -> str | None:
        """Why a line on a flag another program raises (or a cyclic flag), or a condition on a
        name only the set-up fold assigns, stays native, if it does."""
        found = raised_why(text, self.raised)
        test = re.match(r"(?i)(IF|WHILE|UNTIL|WAIT\s+FOR)\b(.*)", text)
        for name in re.findall(r"(?<![\w$])[A-Za-z_]\w*", test.group(2)) if test and found is None else []:
            if name.upper() in self.set_up_only:
                return (f"it tests `{name}`, which only the set-up fold (INI, USER INI) assigns: the import keeps "
                        "that fold as a comment")
        return found

    def _spelled(self, text: str) -> str:
        """`text` with the `$FLAG[n]` read as task variables written as their names (`FLAG_n`)."""
        return flag_names(text) if any(g.flag for g in self.globals.values()) and "$" in text else text

    def switchable(self, params: dict[str, tuple[str, str]], text: str = "") -> dict[str, tuple[str, str]]:
        """The names a SWITCH may test: the routine's number parameters, the main DEF's INT variables,
        and the group input the SWITCH `text` tests (written `{0}`: the condition's part)."""
        group = self.switch_group(text, params) if text else None
        groups = {str(group.signal).upper(): ("{0}", "number")} if group is not None else {}
        return {**params, **{k: (n, "number") for k, (n, t) in self.visible.items() if t == "int"}, **groups}

    def loop(self, found: list[Line], i: int, block: Callable[[int, tuple[str, ...]], tuple[list[Stmt], int]],
             cond_of: Callable[[str], Cond | Conds | None]) -> tuple[list[Stmt], int] | None:
        """`LOOP` B `ENDLOOP` with no EXIT of its own → `while on { B }` (it never ends, KSS 8.x
        "LOOP"); `REPEAT` B `UNTIL c` → B then `while not c { B }` (B runs once, then until c
        holds, KSS 8.x "REPEAT"). None where an EXIT leaves it or c has no rmot form."""
        word = found[i].word
        end = _loop_end(found, i)
        if end is None:
            return self._exit_at_edge(found, i, block, cond_of) if word == "LOOP" else None
        until = re.fullmatch(r"(?i)UNTIL\s+(.+)", found[end].text) if word == "REPEAT" else None
        cond = cond_of(until.group(1)) if until else None
        if word == "REPEAT" and cond is None:
            return None
        body, j = block(i + 1, ("ENDLOOP",) if word == "LOOP" else ("UNTIL",))
        if word == "LOOP":
            return [While(Conds("logic", (), "on"), tuple(body), found[i].where)], j + 1
        again = Conds("logic", (cond,), "not ({0})") if isinstance(cond, Conds) else cond.negated()  # type: ignore[union-attr]
        return [*body, While(again, tuple(body), found[j].where)], j + 1

    def _exit_at_edge(self, found: list[Line], i: int, block: Callable[[int, tuple[str, ...]], tuple[list[Stmt], int]],
                      cond_of: Callable[[str], Cond | Conds | None]) -> tuple[list[Stmt], int] | None:
        """`LOOP` `IF c THEN EXIT ENDIF` B `ENDLOOP` → `while not c { B }`; `LOOP` B `IF c THEN
        EXIT ENDIF` `ENDLOOP` → B then `while not c { B }` (the loop's only EXIT)."""
        exits = _exits(found, i)
        if len(exits) != 2:
            return None
        k = exits[0]
        near = [j for j in range(i + 1, exits[1] + 1) if found[j].text or found[j].fold is not None]
        at = near.index(k) if k in near else -1
        head = re.fullmatch(r"(?i)IF\s+(.*?)\s+THEN", found[near[at - 1]].text) if at > 0 else None
        if head is None or at + 1 >= len(near) or found[near[at + 1]].word != "ENDIF":
            return None
        first, last = near[at - 1] == near[0], at + 2 < len(near) and found[near[at + 2]].word == "ENDLOOP"
        cond = cond_of(head.group(1))
        if cond is None or not (first or last):
            return None
        self.exiting = found[k].where
        body, j = block(i + 1, ("ENDLOOP",))
        self.exiting = None
        rest = tuple(body[1:] if first else body[:-1])
        again = Conds("logic", (cond,), "not ({0})") if isinstance(cond, Conds) else cond.negated()
        return [*(() if first else rest), While(again, rest, found[i].where)], j + 1

    def switch_var(self, text: str) -> str | None:
        """The rmot name of the INT variable `SWITCH n` tests, where it is one."""
        m = re.fullmatch(r"(?i)SWITCH\s+(\w+)", text)
        found = self.visible.get(m.group(1).upper()) if m else None
        return found[0] if found is not None and found[1] == "int" else None

    def switch_head(self, ln: Line, params: dict[str, tuple[str, str]]) -> tuple[str, str, tuple[GroupIn, ...]]:
        """What the tests of `SWITCH k` at `ln` compare: (k's rmot name, the Conds op, its parts): a
        parameter ("expr": the compiler decides), a task variable or a group input ("logic"; the
        group is part {0}, warned W534 at its first use)."""
        group = self.switch_group(ln.text, params)
        if group is not None:
            self.warn_external(group, ln.where)
            return "{0}", "logic", (group,)
        name = self.switchable(params)[ln.text.split()[1].upper()][0]
        return name, "logic" if self.switch_var(ln.text) else "expr", ()

    def switch_group(self, text: str, params: dict[str, tuple[str, str]]) -> GroupIn | None:
        """The group input `SWITCH name` tests, where the name is one (not a parameter or variable)."""
        m = re.fullmatch(r"(?i)SWITCH\s+(\w+)", text)
        key = m.group(1).upper() if m else ""
        return GroupIn(m.group(1)) if m and key not in params and self._group_name(key) else None
