"""Read ABB RAPID modules (`.mod`, `.modx`, `.prg`) back into a neutral Document.

Conventions are the RAPID backend's, read in reverse (ABB Technical reference manual –
RAPID Instructions, Functions and Data types, 3HAC050917-001): robtarget
`[[x,y,z],[q1..q4],[cf1,cf4,cf6,cfx],[eax]]` in mm and a w-first quaternion relative to the
move's work object; confdata cfx = 4·(shoulder back) + 2·(elbow down) + (wrist flip) (inverted
through `backends.rapid.cfx_of`); speeddata v_tcp mm/s (v5..v7000 predefined); zonedata
pzone_tcp mm (z0..z200 predefined, `fine` a stop point); `Offs(p, dx, dy, dz)` a displacement
in the work object (= rmot `shift`); `RelTool(p, dx, dy, dz \\Rx \\Ry \\Rz)` in the tool frame,
rotations about x, then y, then z (= `p * pose(..)`).
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import replace

from rmot.backends.rapid_text import SPEEDS_MM_S, ZONES_MM
from rmot.backends.readers import axes_slots, codes, jump_spans
from rmot.backends.readers.common import Tally, num_expr, number, rmot_name, split_top
from rmot.backends.readers.model import (
    Call, Cond, FrameData, If, Move, Pulse, SetOut, Stmt, Stop, Target, ToolData, Wait, WaitIn, Where, While,
    For, Routine,
)
from rmot.backends.readers.rapid_data import (
    ACCSET, LATE_CALL, VELSET, DataFlow, assigned_at, branch_of, changed_data, frame_of, in_document, joints_of, pose_of, tool_of,
)
from rmot.backends.readers.rapid_logic import RapidVars, condition
from rmot.backends.readers.rapid_text import Statement, literal, native_line, statements
from rmot.lang import ir

__all__ = ["read_rapid", "pose_expr", "num_text", "mm"]

PULSE_DEFAULT_S = 0.2  # PulseDO without \PLength: 0.2 s (RAPID Instructions, PulseDO)
_PARAM_TYPES = {"robtarget": "pose", "jointtarget": "joints", "num": "number", "bool": "bool"}
_DECL = re.compile(r"(?i)^(?:(?:LOCAL|TASK)\s+)*(CONST|PERS|VAR)\s+(\w+)\s+(\w+)\s*(\{[^}]*\})?\s*(?::=\s*(.*))?$")
_MOVES = {"MOVEJ": "joint", "MOVEL": "linear", "MOVEC": "circular", "MOVEABSJ": "joint"}


def mm(expr: str) -> str:
    """An rmot length from a vendor number or expression in mm."""
    return f"{expr} mm" if number(expr) is not None else f"({expr}) * 1 mm"


class _Module:
    """One RAPID module being read: its data, routines and tally."""

    def __init__(self, path: str, text: str) -> None:
        self.tally = Tally(path, text, "rapid")
        self.stmts = statements(path, text)
        self.targets: dict[str, Target] = {}
        self.tools: dict[str, ToolData] = {}
        self.frames: dict[str, FrameData] = {}
        self.speeds: dict[str, float] = {f"V{s}": float(s) for s in SPEEDS_MM_S}
        self.zones: dict[str, float | None] = {"FINE": None, **{f"Z{z}": float(z) for z in ZONES_MM[1:]}, "Z0": 0.3}
        self.data = {d.group(3).upper() for st in self.stmts if (d := _DECL.match(st.text))}  # never a signal
        self.consts: dict[str, float] = {}
        self.routines: list[Routine] = []
        self.proc_names: dict[str, str] = {}  # upper -> as written
        self.names: set[str] = set()  # numeric names an expression may use
        self.pose_params: set[str] = set()  # the current PROC's target parameters
        self.name = "imported"
        self.logic = RapidVars(self.stmts, self.tally)  # task variables (rapid_logic.py)
        self.changed = changed_data(self.stmts)  # data some statement assigns: not constant (rapid_data.py)
        declared = {d.group(3).upper(): (d.group(2).lower(), d.group(3), literal(d.group(5)))
                    for st in self.stmts if (d := _DECL.match(st.text)) and d.group(5) and not d.group(4)}
        self.flow = DataFlow(self.stmts, declared, self.data)

    # ---------------------------------------------------------------- module level

    def read(self) -> None:
        header = re.match(r"(?i)MODULE\s+(\w+)", self.stmts[0].text) if self.stmts else None
        if header is None:
            raise self.tally.fail("a RAPID module must start with `MODULE name` (after an optional %%% header)",
                                  self.stmts[0].where if self.stmts else Where(self.tally.path, 1))
        self.name = header.group(1)
        self.predeclare(local=True)  # data declared below the PROCs that use them
        for st in self.stmts:
            m = re.match(r"(?i)^(?:LOCAL\s+)?PROC\s+(\w+)", st.text)
            if m:
                self.proc_names[m.group(1).upper()] = m.group(1)
        i = 1
        while i < len(self.stmts):
            st = self.stmts[i]
            if st.word == "ENDMODULE":
                self._hoist_vars()
                return
            if re.match(r"(?i)^(?:LOCAL\s+)?PROC\b", st.text):
                i = self._proc(i)
            elif re.match(r"(?i)^(?:LOCAL\s+)?(FUNC|TRAP)\b", st.text):
                i = self._skip_routine(i)
            else:
                self._declaration(st)
                i += 1
        raise self.tally.fail("the module has no ENDMODULE", self.stmts[-1].where)

    def module_data(self) -> list[tuple[str, Where]]:
        """The module-level data declarations, as written (text, where)."""
        return [(st.text, st.where) for st, depth in zip(self.stmts[1:], self._depths()) if depth == 0 and _DECL.match(st.text)]

    def _depths(self) -> list[int]:
        """Each statement's routine nesting (0: module level; a routine's own line counts inside)."""
        depth, out = 0, []
        for st in self.stmts[1:]:
            opens = re.match(r"(?i)^(?:LOCAL\s+)?(PROC|FUNC|TRAP)\b", st.text)
            depth += 1 if opens else 0
            out.append(depth)
            depth -= 1 if st.word in ("ENDPROC", "ENDFUNC", "ENDTRAP") else 0
        return out

    def predeclare(self, local: bool) -> None:
        """Every module-level data declaration, read ahead without counting (the module's own,
        `local`, so a PROC may use data declared after it; another module's, without its LOCAL
        data: the task's other modules see its global data, RAPID Overview, "Scope of data")."""
        for st, depth in zip(self.stmts[1:], self._depths()):
            m = _DECL.match(st.text) if depth == 0 else None
            if m is None or (not local and re.match(r"(?i)^LOCAL\b", st.text)):
                continue
            _, type_, name, dims, value = m.groups()
            if value and not dims and name.upper() not in self.logic.assigned and name.upper() not in self.changed:
                self._data(type_.lower(), name, literal(value), st.where)

    def share(self, other: _Module) -> None:
        """The global data of another module of the task, where this one declares no such name
        (`other` has read none that a module of the task assigns: read_rapid)."""
        self.targets = {**other.targets, **self.targets}
        self.tools = {**other.tools, **self.tools}
        self.frames = {**other.frames, **self.frames}
        self.speeds = {**other.speeds, **self.speeds}
        self.zones = {**other.zones, **self.zones}
        self.names |= other.names  # its numbers may be used here (declared by its own module)

    def _declaration(self, st: Statement) -> None:
        m = _DECL.match(st.text)
        if m is None:
            self.tally.warn(codes.DECLARATION_KEPT, f"not a RAPID data declaration rmot reads: {st.text[:60]}",
                            st.where)
            self.tally.comment(st.text + ";", st.where)
            return
        kind, type_, name, dims, value = m.groups()
        if not dims and self.logic.main is not False and self.logic.declare(kind, type_, name, value, st.where):
            self.tally.imported += 1
            return
        lit = literal(value) if value and not dims else None
        first = self.changed.get(name.upper())
        if first is not None:
            self.tally.warn(codes.DECLARATION_KEPT, f"{assigned_at(name, first, self.tally.path)}: its declared value "
                            "is not its value where a move reads it; kept as a comment", st.where)
            self.tally.comment(st.text + ";", st.where)
        elif not self._data(type_.lower(), name, lit, st.where):
            self.tally.warn(codes.DECLARATION_KEPT, f"{type_} {name} has no rmot form here: kept as a comment",
                            st.where)
            self.tally.comment(st.text + ";", st.where)
        else:
            self.tally.imported += 1

    def _data(self, type_: str, name: str, lit: object, where: Where) -> bool:
        if type_ == "robtarget":
            pose = pose_of(lit) if axes_slots.rapid_slots(lit, 3) is not None else None
            if pose is None:
                return False
            self.targets[name.upper()] = Target(name, pose, None, branch_of(lit), where, slots=axes_slots.rapid_slots(lit, 3) or ())
        elif type_ == "jointtarget":
            if not (isinstance(lit, list) and lit and isinstance(lit[0], list)
                    and all(isinstance(v, float) for v in lit[0]) and axes_slots.robax_read(lit)):
                return False
            self.targets[name.upper()] = Target(name, None, tuple(map(float, lit[0])), None, where, slots=axes_slots.rapid_slots(lit, 1) or ())
        elif type_ == "tooldata":
            return self._tool(name, lit, where)
        elif type_ == "wobjdata":
            return self._wobj(name, lit, where)
        elif type_ == "speeddata" and isinstance(lit, list) and lit and isinstance(lit[0], float):
            self.speeds[name.upper()] = lit[0]
        elif type_ == "zonedata" and isinstance(lit, list) and len(lit) > 1 and isinstance(lit[1], float):
            self.zones[name.upper()] = None if lit[0] == "TRUE" else lit[1]
        elif type_ == "num" and isinstance(lit, float):
            self.consts[name] = lit
            self.names.add(name)
        else:
            return False
        return True

    def _tool(self, name: str, lit: object, where: Where) -> bool:
        tool = tool_of(name, lit, where)
        if tool is not None:
            self.tools[name.upper()] = tool
        return tool is not None

    def _wobj(self, name: str, lit: object, where: Where) -> bool:
        frame = frame_of(name, lit, where)
        if frame is not None:
            self.frames[name.upper()] = frame
        return frame is not None

    def _skip_routine(self, i: int) -> int:
        """FUNC and TRAP routines: kept as comments (rmot has neither functions nor interrupts)."""
        start, start_i = self.stmts[i], i
        end = "END" + start.text.split()[0 if start.word != "LOCAL" else 1].upper()
        self.tally.warn(codes.DECLARATION_KEPT, f"{start.text[:40]} has no rmot form (a function, an "
                        "interrupt routine or a parameter rmot has no type for): kept as a comment", start.where)
        while i < len(self.stmts) and self.stmts[i].word != end:
            st = self.stmts[i]
            self.tally.comment(st.text if i == start_i else native_line(st.text), st.where)
            i += 1
        if i < len(self.stmts):
            self.tally.comment(self.stmts[i].text, self.stmts[i].where)
        return i + 1

    # ---------------------------------------------------------------- routines

    def _proc(self, start: int) -> int:
        i, st = start, self.stmts[start]
        m = re.match(r"(?i)^(?:LOCAL\s+)?PROC\s+(\w+)\s*\((.*)\)\s*$", st.text)
        if m is None:
            raise self.tally.fail(f"a PROC header must be `PROC name(params)` (got `{st.text[:40]}`)", st.where)
        params = self._params(m.group(2))
        if params is None:
            del self.proc_names[m.group(1).upper()]
            return self._skip_routine(i)
        saved = set(self.names)
        self.names |= {p for p, t in params if t == "number"}
        self.pose_params = {p for p, t in params if t in ("pose", "joints")}
        self.logic.enter(m.group(1) == self._main_name(), self.consts)
        self.flow.enter_routine(m.group(1), m.group(1) == self._main_name())
        body, i = self._block(i + 1, ("ENDPROC",), routine=True)
        self.names, self.pose_params = saved, set()
        self.logic.enter(None, self.consts)
        self.routines.append(Routine(m.group(1), tuple(params), jump_spans.goto_spans(body, self.tally, self.stmts[start + 1:i]), st.where))
        return i + 1

    @staticmethod
    def _params(text: str) -> list[tuple[str, str]] | None:
        """(name, rmot type) of each parameter; None when one has no rmot type (num, bool,
        robtarget, jointtarget are read; optional, INOUT and other types are not)."""
        out = []
        for p in split_top(text.replace("|", ","), ",") if text.strip() else []:
            words = p.split()
            if len(words) != 2 or words[0].lower() not in _PARAM_TYPES:
                return None
            out.append((words[1], _PARAM_TYPES[words[0].lower()]))
        return out

    def _block(self, i: int, ends: tuple[str, ...], routine: bool = False) -> tuple[list[Stmt], int]:
        """The statements from `i` to the block's end (nesting bounded by Tally.nested); the data
        it assigns are not known on entry (a routine's body runs once from its start) nor after
        it (rapid_data.DataFlow)."""
        before = self.flow.enter(i, forget=not routine)
        found = self.tally.nested(self.stmts[min(i, len(self.stmts) - 1)].where, lambda: self._block_body(i, ends))
        self.flow.leave(before, i, found[1])
        return found

    def _block_body(self, i: int, ends: tuple[str, ...]) -> tuple[list[Stmt], int]:
        body: list[Stmt] = []
        while i < len(self.stmts):
            st = self.stmts[i]
            if st.word in ends:
                return body, i
            if st.word in ("ERROR", "UNDO", "BACKWARD") and "ENDPROC" in ends:
                j = i
                while j < len(self.stmts) and self.stmts[j].word != "ENDPROC":
                    body.append(self.tally.keep(native_line(self.stmts[j].text), self.stmts[j].where, "an error handler"))
                    j += 1
                return body, j
            stmt, i = self._statement(i)
            body.extend(stmt)
        raise self.tally.fail(f"missing {' or '.join(ends)}", self.stmts[-1].where)

    def _statement(self, i: int) -> tuple[list[Stmt], int]:
        st = self.stmts[i]
        word = st.word
        if word in ("IF", "WHILE", "FOR") and re.search(r"(?i)\b(THEN|DO)\s*$", st.text):
            return self._compound(i)
        if word == "TEST":
            return self.logic.test(i, self._block) or self._keep_block(i, "ENDTEST", "TEST/CASE has no rmot form")
        if re.match(r"(?i)^(LOCAL\s+|TASK\s+)*(CONST|PERS|VAR)\s", st.text):
            self._declaration(st)
            return [], i + 1
        if word in ("WAITDI", "WAITUNTIL") and i + 1 < len(self.stmts) and self.logic.flag_of(st, i + 1):
            return self._timed_wait(i)
        if word in self.proc_names:
            self.flow.called(word)  # the routine may set data (rapid_data.DataFlow)
        elif re.match(rf"(?i)^(\w+\s*:$|{LATE_CALL})", st.text):
            self.flow.restart()  # a jump may arrive here; a call by name may run any routine
        if self.flow.assign(st):
            self.tally.imported += 1
            return [], i + 1
        assign = self.logic.statement(st)
        if assign is not None:
            self.tally.imported += 1
            return [assign], i + 1
        converted = self._simple(st)
        if converted is None:
            return [self.tally.keep(st.text + ("" if st.text.endswith(":") else ";"), st.where, self._why_kept(st))], i + 1
        self.tally.imported += 1
        return [converted], i + 1

    def _why_kept(self, st: Statement) -> str:
        """Why a statement stays native: for a move, the data it names that the files given do
        not declare (a task's modules share their data: the module declaring them is needed)."""
        if st.word not in _MOVES:
            return axes_slots.why_native(st.text) or "no rmot form"
        args = split_top(st.text[len(st.word):].strip())
        known = {*self.targets, *self.speeds, *self.zones, *self.tools, *self.frames, "VMAX", "TOOL0", "WOBJ0"}
        parts = [split_top(a, "\\") for a in args]  # a datum, then its optional arguments (`\WObj:=w`, `\Conc`)
        names = [m.group(1) for p in parts for b in p[:1] + [x for x in p[1:] if re.match(r"(?i)WObj\b", x.strip())]
                 for m in [re.fullmatch(r"(?i)(?:WObj\s*:=\s*)?(\w+)", b.strip())] if m]
        switch = next((x.split(":=")[0].strip() for p in parts for x in p[1:] if not re.match(r"(?i)(WObj|T|V|Z)\b", x.strip())), None)
        unknown = sorted({n for n in names if n.upper() not in known and not re.fullmatch(r"[\d.]+", n)},
                         key=names.index)
        displaced = self.flow.displaced()
        if displaced is not None and st.word != "MOVEABSJ":
            return (f"a program displacement may be on here (`{self.stmts[displaced].text[:40]}` at line "
                    f"{self.stmts[displaced].where.line}): the controller moves the position by a frame the import does not read")
        velset = self.flow.velset_at()
        if velset is not None and self.flow.value(VELSET) is None and not unknown:
            return (f"its speed follows `VelSet` (line {self.stmts[velset].where.line}: `{self.stmts[velset].text[:40]}`), "
                    "whose values here are known only at run time (set in a block, by a call or from a variable)")
        accset = self.flow.where.get(ACCSET, [(None, ())])[0][0]
        if accset is not None and not self.flow.accel()[0] and not unknown:
            return (f"its acceleration follows `AccSet` (line {self.stmts[accset].where.line}: `{self.stmts[accset].text[:40]}`), "
                    "whose values here are known only at run time or have no rmot form (a Ramp other than 100, "
                    "an Acc outside 20..100 %)")
        changed = [n for n in unknown if n.upper() in self.changed and self.flow.value(n) is None]
        if changed:
            first = self.changed[changed[0].upper()]
            return f"{assigned_at(changed[0], first, self.tally.path)}: its value here is known only at run time"
        if not unknown:
            return f"its optional argument `\\{switch}` has no rmot form" + (
                " (the statements after the move run while the robot moves)" if switch.upper() == "CONC" else "") \
                if switch else "no rmot form"
        return (f"{', '.join(unknown)} {'is' if len(unknown) == 1 else 'are'} not declared in the files given "
                "(another module of the task? give it too) or not constant data")

    def _keep_block(self, i: int, end: str, why: str) -> tuple[list[Stmt], int]:
        out: list[Stmt] = []
        self.flow.skip(i)
        depth = 0
        while i < len(self.stmts):
            st = self.stmts[i]
            depth += st.word == end[3:]
            depth -= st.word == end
            out.append(self.tally.keep(native_line(st.text), st.where, why))
            i += 1
            if depth <= 0:
                break
        return out, i

    def _compound(self, i: int) -> tuple[list[Stmt], int]:
        st = self.stmts[i]
        word = st.word
        end = {"IF": "ENDIF", "WHILE": "ENDWHILE", "FOR": "ENDFOR"}[word]
        head = self._head(st)
        if head is None:
            return self._keep_block(i, end, f"this {word} has no rmot form")
        if word == "FOR":
            var, first, stop = head  # type: ignore[misc]
            saved = set(self.names)
            self.names.add(var)
            body, j = self._block(i + 1, (end,))
            self.names = saved
            self.tally.imported += 1
            return [For(var, first, stop, tuple(body), st.where)], j + 1
        then, j = self._block(i + 1, (end, "ELSE", "ELSEIF"))
        self.tally.imported += 1
        if word == "WHILE":
            return [While(head, tuple(then), st.where)], j + 1  # type: ignore[arg-type]
        orelse: list[Stmt] = []
        if self.stmts[j].word == "ELSEIF":
            nested = Statement("IF" + self.stmts[j].text[6:], self.stmts[j].where)
            self.stmts[j] = nested
            orelse, j = self._compound(j)
            return [If(head, tuple(then), tuple(orelse), st.where)], j  # type: ignore[arg-type]
        if self.stmts[j].word == "ELSE":
            orelse, j = self._block(j + 1, (end,))
        return [If(head, tuple(then), tuple(orelse), st.where)], j + 1  # type: ignore[arg-type]

    def _main_name(self) -> str:
        """The routine that runs (as `rmot import` chooses it): `main`, else the first PROC."""
        return next((n for n in self.proc_names.values() if n.lower() == "main"), next(iter(self.proc_names.values()), ""))

    def _hoist_vars(self) -> None:
        """The task variables, declared at the top of the main routine (rmot declares them in the task's body)."""
        for k, r in enumerate(self.routines):
            if r.name == self._main_name():
                decls, body = self.logic.fold_first_values(r.body)
                self.routines[k] = Routine(r.name, r.params, (*decls, *body), r.where)

    def _timed_wait(self, i: int) -> tuple[list[Stmt], int]:
        """`WaitDI ...\\MaxTime:=T\\TimeFlag:=f; IF f THEN B ENDIF` as `wait until ... timeout T else { B }`."""
        st = self.stmts[i]
        wait = self._simple(Statement(re.sub(r"(?i)\s*\\TimeFlag\s*:=\s*\w+", "", st.text), st.where))
        if not isinstance(wait, WaitIn) or wait.timeout is None:
            return [self.tally.keep(st.text + ";", st.where, "no rmot form")], i + 1
        orelse, j = self._block(i + 2, ("ENDIF", "ELSE", "ELSEIF"))
        if self.stmts[j].word != "ENDIF":
            return [self.tally.keep(st.text + ";", st.where, "no rmot form")], i + 1
        self.tally.imported += 2
        return [WaitIn(wait.cond, wait.timeout, st.where, tuple(orelse))], j + 1

    def _head(self, st: Statement) -> Cond | tuple[str, int, int] | None:
        if st.word == "FOR":
            m = re.match(r"(?i)^FOR\s+(\w+)\s+FROM\s+(-?\d+)\s+TO\s+(-?\d+)\s+(?:STEP\s+1\s+)?DO$", st.text)
            if m is None:
                return None
            return (m.group(1), int(m.group(2)), int(m.group(3)) + 1)
        m = re.match(r"(?i)^(?:IF|WHILE)\s+(.*?)\s+(?:THEN|DO)$", st.text)
        return (_cond(m.group(1), self.data) or condition(m.group(1), self.logic.visible)) if m else None  # type: ignore[return-value]

    def _simple(self, st: Statement) -> Stmt | None:
        word = st.word
        args_text = st.text[len(word):].strip() if st.text[:len(word)].upper() == word else ""
        args: list[str] = []
        for a in split_top(args_text) if args_text else []:  # `tool1, \WObj:=w` (as RoboDK writes) is `tool1\WObj:=w`
            args += [args.pop() + a.strip()] if a.strip().startswith("\\") and args else [a]
        args_text = ", ".join(a.strip() for a in args)  # `WaitDI di1, 1, \MaxTime:=2` too
        if word in _MOVES:
            move = self._move(word, args, st.where)
            return replace(move, source=st.text + ";") if move is not None else None
        if word == "SETDO" and len(args) == 2 and args[1] in ("0", "1"):
            return SetOut(args[0], float(args[1]), st.where)
        if word in ("SET", "RESET") and len(args) == 1:
            return SetOut(args[0], 1.0 if word == "SET" else 0.0, st.where)
        if word == "SETAO" and len(args) == 2 and number(args[1]) is not None:
            return SetOut(args[0], number(args[1]), st.where, analog=True)  # type: ignore[arg-type]
        if word == "PULSEDO":
            m = re.match(r"(?i)^\\PLength\s*:=\s*([0-9.]+)\s*,\s*(\w+)$", args_text)
            if m:
                return Pulse(m.group(2), float(m.group(1)), st.where)
            if re.fullmatch(r"\w+", args_text):
                return Pulse(args_text, PULSE_DEFAULT_S, st.where)
            return None
        if word == "WAITTIME" and len(args) == 1 and number(args[0].replace("\\InPos", "")) is not None:
            return Wait(number(args[0].replace("\\InPos", "")), st.where)  # type: ignore[arg-type]
        if word == "WAITDI":
            m = re.match(r"(?i)^(\w+)\s*,\s*([01])\s*(?:\\MaxTime\s*:=\s*([0-9.]+))?$", args_text)
            if m:
                return WaitIn(Cond(m.group(1), m.group(2) == "1"),
                              float(m.group(3)) if m.group(3) else None, st.where)
            return None
        if word == "WAITUNTIL":
            m = re.match(r"(?i)^(.*?)\s*(?:\\MaxTime\s*:=\s*([0-9.]+))?$", args_text)
            cond = (_cond(m.group(1), self.data) or condition(m.group(1), self.logic.visible)) if m else None
            return WaitIn(cond, float(m.group(2)) if m and m.group(2) else None, st.where) if cond else None
        if word == "EXIT" and not args:
            return Stop(st.where)
        if word in self.proc_names:
            return self._call(word, args_text, st.where)
        return None

    def _call(self, word: str, args_text: str, where: Where) -> Stmt | None:
        args = []
        for a in split_top(args_text) if args_text else []:
            expr = self._target(a) if not re.fullmatch(r"-?[\d.]+", a) else a
            if expr is None:
                return None
            args.append(expr[0] if isinstance(expr, tuple) else expr)
        return Call(self.proc_names[word], tuple(args), where)

    def _move(self, word: str, args: list[str], where: Where) -> Move | None:
        kind = _MOVES[word]
        if len(args) != (5 if kind == "circular" else 4):
            return None
        parts = [split_top(a, "\\") for a in args]
        via = None
        if kind == "circular":
            via_t = self._target(parts[0][0])
            if via_t is None:
                return None
            via = via_t[0]
            parts = parts[1:]
        to, speed, zone, tool = parts
        target = self._target(to[0])
        if target is None or len(to) > 1 and to[1:] != ["NoEOffs"]:
            return None
        expr, name, decl = target
        if (word == "MOVEABSJ") != (decl is not None and decl.joints is not None):
            return None
        if word != "MOVEABSJ" and self.flow.displaced() is not None:
            return None  # a program displacement moves the robtarget (a jointtarget it does not)
        timing = self.flow.speed(kind, speed, self.speeds)
        zone_mm = self.flow.zone_of(zone, self.zones)
        frame = self._wobj_of(tool[1:], where)
        held = self.tools.get(tool[0].upper()) or self.flow.tool(tool[0], where)
        if timing is None or zone_mm == "bad" or (held is None and tool[0].upper() != "TOOL0") or frame is None \
                or not self.flow.accel()[0]:
            return None
        if kind == "joint" and timing[1] is None and (speed[0].upper() != "VMAX" or timing[2] != 100):
            self.tally.warn(codes.JOINT_SPEED_READ, f"{word} at {speed[0]}: rmot times a joint move by its joint share; "
                            f"read as {timing[2]:g} %" + (" (the VelSet override)" if timing[2] != 100 else ""), where)
        tool_name = in_document(held, self.tools).name if held is not None else "flange"
        config = decl.config if kind == "joint" and decl is not None and decl.pose is not None else None
        return Move(kind, expr, name, where, via=via, speed=timing[0] if kind != "joint" else None,
                    joint_pct=timing[2] if kind == "joint" and timing[1] is None else None, zone=zone_mm,  # type: ignore[arg-type]
                    time=timing[1], tool=tool_name, frame=frame, config=config,
                    pose=decl.pose if decl and expr in (decl.name, pose_expr(decl.pose) if decl.pose else None) else None,
                    joints=decl.joints if decl else None, joint_accel=self.flow.accel()[1], slots=decl.slots if decl else ())

    def _wobj_of(self, switches: list[str], where: Where) -> str | None:
        frame = "base"
        for s in switches:
            m = re.fullmatch(r"(?i)WObj\s*:=\s*(\w+)", s)
            if m is None:
                return None
            if m.group(1).upper() != "WOBJ0":
                found = self.frames.get(m.group(1).upper()) or self.flow.frame(m.group(1), where)
                if found is None:
                    return None
                frame = in_document(found, self.frames).name
        return frame

    def _target(self, text: str, depth: int = 0) -> tuple[str, str | None, Target | None] | None:
        """(rmot expression, declared name, declaration) of a RAPID target expression (offsets
        nested at most 8 deep)."""
        text = text.strip()
        if depth > 8:
            return None
        decl = self.targets.get(text.upper())
        if decl is not None:
            return (rmot_name(decl.name), decl.name, decl)
        if re.fullmatch(r"\w+", text):
            return (text, None, None) if text in self.pose_params else None
        m = re.fullmatch(r"(?i)(Offs|RelTool)\s*\((.*)\)", text)
        if m:
            args: list[str] = []
            for arg in split_top(m.group(2)):
                bits = split_top(arg, "\\")
                args += [bits[0]] + ["\\" + b for b in bits[1:]]
            return self._offset(m.group(1).upper(), args, depth)
        lit = literal(text)
        pose = pose_of(lit) if axes_slots.rapid_slots(lit, 3) is not None else None
        if pose is not None:
            return (pose_expr(pose), None, Target("", pose, None, branch_of(lit), Where("", 0), slots=axes_slots.rapid_slots(lit, 3) or ()))
        joints = joints_of(lit)
        if joints is not None:
            return (f"joints({', '.join(num_text(j) for j in joints)}) deg", None,
                    Target("", None, joints, None, Where("", 0), slots=axes_slots.rapid_slots(lit, 1) or ()))
        return None

    def _offset(self, func: str, args: list[str], depth: int) -> tuple[str, str | None, Target | None] | None:
        base = self._target(args[0], depth + 1) if args else None
        if base is None or len(args) < 4:
            return None
        offs = [num_expr(a, self.names) for a in args[1:4]]
        if any(o is None for o in offs):
            return None
        terms = ", ".join(f"{axis}={mm(o)}" for axis, o in zip("xyz", offs) if o not in ("0",))  # type: ignore[arg-type]
        if func == "OFFS" and len(args) == 4:
            return (f"shift({base[0]}, {terms})" if terms else base[0], base[1], base[2])
        turns = []
        for switch in args[4:] if func == "RELTOOL" else ["bad"]:
            m = re.fullmatch(r"(?i)\\R([xyz])\s*:=\s*(.+)", switch)
            angle = num_expr(m.group(2), self.names) if m else None
            if m is None or angle is None:
                return None
            turns.append(f" * pose(r{m.group(1).lower()}={angle if number(angle) is not None else f'({angle}) * 1'} deg)")
        shifted = f"{base[0]} * pose({terms})" if terms else base[0]
        return (shifted + "".join(turns), base[1], base[2])


def pose_expr(pose: ir.Pose) -> str:
    """An rmot pose literal: mm and the exact quaternion."""
    x, y, z = (num_text(v * 1000, 6) for v in pose.position)
    q = ", ".join(num_text(v, 10) for v in pose.quaternion)
    return f"pose(x={x}mm, y={y}mm, z={z}mm, q=({q}))"


def num_text(value: float, decimals: int = 9) -> str:
    """A number rounded to `decimals` places, shortest form, never `-0` (deterministic text)."""
    return f"{round(value, decimals) + 0.0:.15g}"


def _cond(text: str, data: set[str]) -> Cond | None:
    """`DInput(s) = 1`, `s = 1`, `[NOT] TestDI(s)` as a digital condition; declared data (`data`) is no signal."""
    text = text.strip()
    m = re.fullmatch(r"(?i)(?:DInput\s*\(\s*(\w+)\s*\)|(\w+))\s*=\s*([01]|high|low)", text)
    if m and not (m.group(2) and m.group(2).upper() in data):
        return Cond(m.group(1) or m.group(2), m.group(3).lower() in ("1", "high"))
    m = re.fullmatch(r"(?i)(NOT\s+)?TestDI\s*\(\s*(\w+)\s*\)", text)
    if m:
        return Cond(m.group(2), not m.group(1))
    return None


def read_rapid(path: str, text: str, task: Mapping[str, str] | None = None) -> _Module:
    """Read one RAPID module; raises ImportError_ (E510) when it is not one. `task`: every
    module given (path -> text): their global data are this module's too."""
    module = _Module(path, text)
    for other_path, other_text in (task or {}).items():
        other = _Module(other_path, other_text)
        if other_path != path and other.stmts and other.stmts[0].word == "MODULE":
            other.changed = {**module.changed, **other.changed}  # data this module assigns is not the other's constant
            other.predeclare(local=False)
            module.changed = {**other.changed, **module.changed}  # data another module assigns is not constant here
            module.flow.foreign |= {s.word for s in other.stmts}
            module.share(other)
    module.read()
    return module
