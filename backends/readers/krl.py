"""Read KUKA KRL (`.src` with its `.dat`) back into a neutral Document.

Conventions are the KRL backend's, read in reverse (KUKA KSS 8.x Operating and Programming
Instructions for System Integrators): E6POS/POS/FRAME `{X,Y,Z mm, A,B,C deg}` with
R = Rz(A)·Ry(B)·Rx(C) (= rmot's rz, ry, rx); Status S bit 0 shoulder back, bit 1 elbow up,
bit 2 wrist flip (inverted through `backends.krl.status_of`); `$VEL.CP` m/s, `$VEL_AXIS` /
`BAS(#VEL_PTP)` %, `$APO.CDIS` mm for C_DIS, `$APO.CPTP` % for C_PTP (the backend's 1 mm per %,
`KrlBackend.CPTP_MM`), `$APO.CDIS` mm for a PTP blended into a LIN/CIRC (`C_PTP C_DIS`);
`$TOOL`/`$BASE` name module FRAMEs (or `TOOL_DATA[n]`/`BASE_DATA[n]`,
stored on the controller); the work-copy offset `P_loop=P`, `P_loop.X=P.X+d` is `shift`.
Inline forms of KSS 5 (KR C2) and KSS 8 (KR C4), `;FOLD PTP P1 CONT Vel=100 % PDAT1 Tool[1]
Base[0]` (also SPTP/SLIN/SCIRC), are read from their header and the `.dat`'s XP1, PPDAT1/LCPDAT1
(APO_DIST mm).
"""

from __future__ import annotations

import re
from functools import partial
from dataclasses import replace

from rmot.backends.krl import KrlBackend
from rmot.backends.readers import axes_slots, codes
from rmot.backends.readers.jump_spans import goto_spans
from rmot.backends.readers.common import Tally, rmot_name, split_top
from rmot.backends.readers.krl_text import (
    Line, MotionState, aggregate, branch_of_status, fold_end, has_test, in_cond, krl_pose, lines,
)
from rmot.backends.readers.krl_data import (
    data_objects, declared, data_list, home, numbered, keep_block, load_switch, skip_function, with_state, named_loads, position, timed_wait,
)
from rmot.backends.readers.krl_globals import ASSIGNMENT, public_globals
from rmot.backends.readers.krl_flow import KnownPositions, data_value, known_target, literal
from rmot.backends.readers.krl_inline import MOTIONS, inline_move
from rmot.backends.readers.krl_unroll import unrolled_for
from rmot.backends.readers.krl_work import WorkCopies
from rmot.backends.readers.krl_logic import KrlVars
from rmot.backends.readers.krl_vars import SETUP_FOLD, axis_speed_loop, counted_loop
from rmot.backends.readers.krl_why import (
    Names, UnreadCalls, inline_why, mode_why, motion_why, other_why,
)
from rmot.backends.readers.krl_names import (
    Params, call_args, config_near, declared_names, group_names, is_group_input, param_names, port_of, signals, signatures, switch_cases)
from rmot.backends.readers.model import (
    Call, Cond, Conds, Signal, For, FrameData, If, Move, NamedLoad, Pulse, SetOut, Stmt, Target, ToolData, Wait, WaitIn, Where, While, Routine)
from rmot.backends.readers.rapid import mm, num_text, pose_expr
from rmot.lang import ir

__all__ = ["read_krl", "branch_of_status", "krl_pose"]

class _Krl:
    def __init__(self, src: tuple[str, str], dat: tuple[str, str] | None, others: dict[str, Params | None]) -> None:
        self.tally = Tally(src[0], src[1], "krl")
        self.lines = lines(*src)
        self.data = data_list(dat)
        self.dat = dat
        config = config_near(src[0])
        self.config = {**public_globals(src[0], dat[0] if dat else None), **data_list(config)}  # $config.dat's, public ones
        self.config_file = config  # its path and text (globals the program sets: krl_vars.py)
        texts = [src[1]] + [t[1] for t in (dat, config) if t is not None]
        self.signals = {k: v for text in texts for k, v in signals(text).items()}
        self.variables = set().union(*(declared_names(text) for text in texts))
        self.config_groups = group_names(config, texts)  # None: no $config.dat read
        self.inputs_named: set[str] = set()  # names read as inputs (W521 at the first use)
        self.signatures = {**others, **signatures(self.lines)}  # the other files' routines, this one's own first
        self.params: dict[str, tuple[str, str]] = {}  # the parameters of the routine being read
        # a data object the program assigns holds its .dat value only until then: no constant target
        self.assigned = {m.upper() for m in ASSIGNMENT.findall(src[1])}
        self.tools, self.frames, self.targets = data_objects(self.data, src[1], self.assigned)
        self.routines: list[Routine] = []
        self.names: set[str] = set()
        self.work = WorkCopies()  # P_loop -> (P, axis offsets)
        self.state = MotionState()
        self.name = "imported"
        # the Cartesian target the last move went to, in straight-line code (None where a block
        # starts or ends, or after a move not read): where a LIN_REL starts
        self.last: tuple[str, str | None, Target | None] | None = None
        self.at: Where | None = None  # the line being read
        # calls kept native or of routines that change the settings: W527 at the motion after one
        self.calls = UnreadCalls(self.tally, self.lines)
        self.logic = KrlVars([], "", None, set(), lambda n: None)  # task variables (krl_logic.py), set in read()
        self.flow = KnownPositions(re.search(r"(?im)^\s*(?:GLOBAL\s+)?INTERRUPT\s+DECL\b", src[1]) is not None)

    def _named(self, name: str, kind: str, pending: list[str]) -> Signal | None:
        """The input (kind "IN") a condition or the output ("OUT") a PULSE names: its SIGNAL's port;
        a name declared nowhere the import sees (the program, its .dat, a $config.dat found) and never
        assigned here is a signal of the controller's: that name (W521 at its first use)."""
        key = name.upper()
        if key in self.signals:
            return port_of(self.signals, key, kind)
        if key in self.variables or key in self.assigned or key in self.data or self.config_groups is not None:
            return None
        pending.append(name)
        return name

    def _warn_named(self, pending: list[str], kind: str) -> None:
        for name in pending:
            if name.upper() not in self.inputs_named:
                self.inputs_named.add(name.upper())
                self.tally.warn(codes.NAME_READ_AS_INPUT, f"`{name}` is declared neither in the program nor in a "
                                f"$config.dat found beside it: read as the {kind} signal of that name (a SIGNAL of "
                                "$config.dat, or a global BOOL another task sets); give --cell to check it",
                                self.at or Where(self.tally.path, 1))

    def _cond(self, text: str) -> Cond | Conds | None:
        """A condition over inputs (and names read as inputs, each warned at its first use)."""
        pending: list[str] = []
        cond = in_cond(text, lambda name: self._named(name, "IN", pending), lambda name: self.params.get(name.upper()))
        self._warn_named(pending if cond is not None else [], "input")
        return cond or self.logic.condition(text, self.at)

    # ---------------------------------------------------------------- structure

    def read(self) -> None:
        i = 0
        while i < len(self.lines) and self.lines[i].fold is None and not self.lines[i].text:
            i += 1
        starts = [ln for ln in self.lines if ln.text]
        # a module starts with DEF name( ) or, holding only functions, DEFFCT type name( ) (KSS 8.x)
        head = re.match(r"(?i)(?:GLOBAL\s+)?(?:DEF|DEFFCT\s+\w+)\s+(\w+)\s*\(", starts[0].text) if starts else None
        if head is None:
            where = starts[0].where if starts else Where(self.tally.path, 1)
            raise self.tally.fail("a KRL .src must start with `DEF name( )` (after &ACCESS lines and folds)", where)
        self.name = head.group(1)
        taken = {*self.targets, *self.tools, *self.frames, *self.signals}
        self.logic = KrlVars(self.lines, self.name, self.dat, taken, lambda n: port_of(self.signals, n, "IN"), self.tally,
                             partial(is_group_input, self.config_groups, {*self.signals, *self.variables, *self.assigned, *self.data}),
                             self.config_file, lambda n: port_of(self.signals, n, "OUT"))
        i = 0
        while i < len(self.lines):
            ln = self.lines[i]
            m = re.match(r"(?i)(?:GLOBAL\s+)?DEF\s+(\w+)\s*\((.*)\)\s*$", ln.text)
            if m and m.group(1).upper() == "RMOT_PTP":  # rmot's own helper: read as the speed it sets
                while i < len(self.lines) and self.lines[i].word != "END":
                    i += 1
            elif m:
                params = self.signatures.get(m.group(1).upper())
                self.state = MotionState(inherited=m.group(1).upper() != self.name.upper() or bool(params))  # a proc: its caller's
                self.calls.pending = None
                if params and m.group(1).upper() == self.name.upper():
                    self.tally.warn(codes.MODULE_IS_PROC, f"`{m.group(1)}` takes parameters: a routine other programs "
                                    "call, written as a proc (import it after its caller; alone, nothing runs it)",
                                    ln.where)
                self.params = param_names(params)
                self.flow.routine(self.lines, i)
                self.work.routine()
                start = i
                body, i = self.logic.routine(m.group(1).upper() == self.name.upper() and not params,  # a proc has no vars
                                             partial(self._block, i + 1, ("END",)))
                body = list(goto_spans(body, self.tally, self.lines[start + 1:i]))
                self.routines.append(Routine(m.group(1), params or (), tuple(body), ln.where))
            elif ln.text and re.match(r"(?i)(GLOBAL\s+)?DEFFCT\b", ln.text):
                i = skip_function(self.lines, self.tally, i)
                continue
            i += 1

    def _block(self, i: int, ends: tuple[str, ...]) -> tuple[list[Stmt], int]:
        """The statements from `i` to the block's end; a setting it changes is unsure after it (MotionState.unsure)."""
        before = {name: getattr(self.state, name) for name in MotionState.SETTINGS}
        found = self.tally.nested(self.lines[min(i, len(self.lines) - 1)].where, lambda: self._block_body(i, ends))
        at = f"in the block at line {self.lines[max(i - 1, 0)].where.line}, which may not run (or runs more than once)"
        self.state.unsure.update({n: (at, getattr(self.state, n)) for n, v in before.items() if getattr(self.state, n) != v})
        return found

    def _block_body(self, i: int, ends: tuple[str, ...]) -> tuple[list[Stmt], int]:
        body: list[Stmt] = []
        self.last = None
        while i < len(self.lines):
            ln = self.lines[i]
            if ln.word in ends and not ln.fold:
                self.last = None
                return body, i
            stmts, i = self._statement(i)
            body += stmts
        raise self.tally.fail(f"missing {' or '.join(ends)}", self.lines[-1].where if self.lines else
                              Where(self.tally.path, 1))

    def _statement(self, i: int) -> tuple[list[Stmt], int]:
        """The statement at `i`, the positions known there observed first and forgotten after a block."""
        self.flow.observe(self.lines, i, lambda key: data_value(key, (self.data, self.config), self.assigned))
        out, j = self._statement_read(i)
        if j > i + 1:
            self.flow.disturb(self.lines[i:j])
        return out, j

    def _statement_read(self, i: int) -> tuple[list[Stmt], int]:
        ln = self.lines[i]
        self.at = ln.where  # where a setting read from the line's text is located
        if ln.endfold:
            return [], i + 1
        if ln.fold is not None:
            return self._fold(i)
        word = ln.word
        if word in ("FOR", "IF", "WHILE"):
            return self._compound(i)
        if word == "SPLINE":
            return self._spline(i)
        if word == "LOOP" and not self.routines and self.tally.depth == 1 and not any(
                ln.word == "EXIT" for ln in self.lines[i:]):
            return self._forever(i)
        if word == "SWITCH" and switch_cases(self.lines, i, self.logic.switchable(self.params, ln.text)) is not None:
            return self._switch(i)
        looped = self.logic.loop(self.lines, i, self._block, self._cond) if word in ("LOOP", "REPEAT") else None
        if looped is not None:
            self.tally.imported += 1
            return looped
        if word in ("LOOP", "REPEAT", "SWITCH"):
            end = {"LOOP": "ENDLOOP", "REPEAT": "UNTIL", "SWITCH": "ENDSWITCH"}[word]
            return keep_block(self.lines, self.tally, i, word, end)
        if word in ("DECL", "INT", "REAL", "BOOL", "CHAR", "E6POS", "POS", "FRAME", "E6AXIS", "AXIS", "SIGNAL"):
            return [], i + 1
        if ln.where in self.logic.skipped:  # a stepped loop's own increment (counted_loop)
            return [], i + 1
        assign = self.logic.statement(ln)
        if assign is not None:
            self.tally.imported += 1
            return [assign], i + 1
        if load_switch(self.lines, i):
            return [self.tally.keep(ln.text, ln.where, "a payload switch (`rmot import --cell` reads an attach or detach)")], i + 1
        if self.state.setting(lambda: self._setting(ln.text)):
            return [], i + 1
        if self.work.read(self.lines, i, self.flow, self.targets, self.data, self.names):
            return [], i + 1
        timed = timed_wait(self.lines, i) if i + 7 < len(self.lines) else None
        if timed is not None or self.logic.timed_else(self.lines, i, self._cond):
            self.tally.imported += 1
            return self.logic.with_else(timed, self.lines, i, self._block, self._cond)
        stmt = self._simple(ln)
        if stmt is None:
            why = self.state.unsure_of(word in ("PTP", "SPTP"), ln.text) or motion_why(ln.text[len(word):], self._names(), self.state) \
                if word in MOTIONS else \
                other_why(word, ln.text, self.last is not None) or self.logic.why(ln.text) or self.calls.why_call(ln.text, self.state)
            self.calls.called(ln.text, ln.where, self.state)
            kept = self.tally.keep(ln.text, ln.where, why or "no rmot form")
            return [*(self.state.restate(ln.text, ln.where) if word in MOTIONS else []), kept], i + 1
        self.tally.imported += 1
        self.calls.moved(stmt, self.state)
        return [stmt], i + 1

    def _spline(self, i: int) -> tuple[list[Stmt], int]:
        """A SPLINE block of SLIN/SCIRC segments only passes exactly through every point (KSS 8.3 System
        Integrators, spline block): linear/circular moves without zone, the last one blended by
        `ENDSPLINE C_SPL` with $APO.CDIS. SPL segments (a spline curve), WITH or folds: kept native."""
        j = next((k for k in range(i, len(self.lines)) if self.lines[k].word == "ENDSPLINE"), None)
        if j is None or not re.fullmatch(r"(?i)SPLINE", self.lines[i].text.strip()) or not re.fullmatch(
                r"(?i)ENDSPLINE(\s+C_SPL)?", self.lines[j].text.strip()):
            return keep_block(self.lines, self.tally, i, "SPLINE", "ENDSPLINE")
        segments = [ln for ln in self.lines[i + 1:j] if ln.text.strip() or ln.fold or ln.endfold]
        moves = [self._motion(ln.word, ln.text.strip()[len(ln.word):].strip(), ln.where)
                 if ln.word in ("SLIN", "SCIRC") and ln.fold is None and not re.search(r"(?i)\bWITH\b|C_SPL", ln.text)
                 else None for ln in segments]
        kept = [m for m in moves if m is not None]
        blended = self.lines[j].text.strip().upper() != "ENDSPLINE"
        if not kept or len(kept) != len(moves) or (blended and self.state.cdis is None):
            return keep_block(self.lines, self.tally, i, "SPLINE", "ENDSPLINE")
        if blended:
            kept[-1] = replace(kept[-1], zone=self.state.cdis)
        self.tally.imported += len(kept)
        self.last = None
        return list(kept), j + 1

    def _forever(self, i: int) -> tuple[list[Stmt], int]:
        """The main routine's outermost LOOP .. ENDLOOP without EXIT: the cycle the controller repeats."""
        self.tally.warn(codes.LOOP_READ_ONCE, "an outermost `LOOP` is read as one cycle of the program "
                        "(the controller repeats an rmot program)", self.lines[i].where)
        self.tally.imported += 1
        body, j = self._block(i + 1, ("ENDLOOP",))
        return body, j + 1

    def _compound(self, i: int) -> tuple[list[Stmt], int]:
        ln = self.lines[i]
        word = ln.word
        end = {"FOR": "ENDFOR", "IF": "ENDIF", "WHILE": "ENDWHILE"}[word]
        speeds = axis_speed_loop(self.lines, i) if word == "FOR" else None
        if speeds is not None and self._setting(speeds[0]):  # every axis's speed set by a loop
            return [], speeds[1]
        if word == "FOR":
            loop = counted_loop(self.lines, i)  # (counter, first, stop, its increment to leave out) or why not
            if not isinstance(loop, tuple):
                return keep_block(self.lines, self.tally, i, word, end, loop)
            flat = unrolled_for(self, i, loop[0], loop[1], loop[2] - 1) if loop[3] is None else None
            if flat is not None:
                return flat
            name, first, stop, self.logic.skipped = loop[0], loop[1], loop[2], {*self.logic.skipped, loop[3]}
            saved, params = set(self.names), self.params
            self.names.add(name)
            self.params = {**params, name.upper(): (name, "number")}  # known at each iteration
            body, j = self._block(i + 1, (end,))
            self.names, self.params = saved, params
            self.tally.imported += 1
            return [For(name, first, stop, tuple(body), ln.where)], j + 1
        m = re.fullmatch(r"(?i)(?:IF|WHILE)\s+(.*?)(?:\s+THEN)?", ln.text)
        cond = self._cond(m.group(1)) if m else None
        if cond is None or (word == "WHILE" and has_test(cond)):  # a while on a test the compiler decides: native
            return keep_block(self.lines, self.tally, i, word, end, mode_why(word, ln.text) or self.logic.why(ln.text))
        then, j = self._block(i + 1, (end, "ELSE") if word == "IF" else (end,))
        orelse: list[Stmt] = []
        if self.lines[j].word == "ELSE":
            orelse, j = self._block(j + 1, (end,))
        self.tally.imported += 1
        if word == "WHILE":
            return [While(cond, tuple(then), ln.where)], j + 1
        return [If(cond, tuple(then), tuple(orelse), ln.where)], j + 1

    def _switch(self, i: int) -> tuple[list[Stmt], int]:
        """`SWITCH k` .. `CASE 1, 2` .. `DEFAULT` .. `ENDSWITCH` on a number parameter (KSS 8.x: the
        first CASE with a value equal to k runs, else DEFAULT) → `if k == 1 or k == 2 { } else ..`."""
        name, op, parts = self.logic.switch_head(self.lines[i], self.params)
        arms = []
        for j, values in switch_cases(self.lines, i, self.logic.switchable(self.params, self.lines[i].text)) or []:
            body, end = self._block(j + 1, ("CASE", "DEFAULT", "ENDSWITCH"))
            arms.append((values, body, self.lines[j].where))
        orelse: tuple[Stmt, ...] = tuple(arms.pop()[1]) if arms and not arms[-1][0] else ()
        for values, body, where in reversed(arms):
            test = " or ".join(f"{name} == {int(v)}" for v in values)
            orelse = (If(Conds(op, parts, test), tuple(body), orelse, where),)
        self.tally.imported += 1
        return list(orelse), end + 1

    def _names(self) -> Names:
        """What the program's names are, for saying why a motion stays native."""
        return (self.targets, {n: self.flow.lost.get(n, "") for n in self.assigned}, self.variables, {**self.config, **self.data})

    # ---------------------------------------------------------------- modal variables

    def _setting(self, text: str) -> bool:
        """$VEL.CP, $APO, $TOOL, $BASE, $LOAD, $ACC, RMOT_PTP, BAS(#VEL_..): the state of the
        motions after them (True when the line is one of them)."""
        st = self.state
        m = re.fullmatch(r"(?i)\$(VEL\.CP|APO\.CDIS|APO\.CPTP)\s*=\s*([-\d.eE+]+)", text)
        if m:
            value = float(m.group(2))
            key = m.group(1).upper()
            if key == "VEL.CP":
                st.vel_cp = value * 1000.0
            elif key == "APO.CDIS":
                st.cdis = value
            else:
                st.cptp = value
            return True
        m = re.fullmatch(r"(?i)RMOT_PTP\s*\(\s*([\d.]+)\s*,\s*([\d.]+)\s*\)|BAS\s*\(\s*#VEL_PTP\s*,\s*([\d.]+)\s*\)", text)
        if m:
            st.vel_ptp = float(m.group(1) or m.group(3))
            if m.group(2):
                st.acc_ptp = None if float(m.group(2)) == 100.0 else float(m.group(2))
            return True
        m = re.fullmatch(r"(?i)\$ACC\.CP\s*=\s*([\d.]+)", text)
        if m:
            st.acc_cp = None if float(m.group(1)) == 2.0 else float(m.group(1)) * 1000.0
            return True
        m = re.fullmatch(r"(?i)BAS\s*\(\s*#VEL_CP\s*,\s*([\d.]+)\s*\)", text)
        if m:
            st.vel_cp = float(m.group(1)) * 1000.0
            return True
        m = re.fullmatch(r"(?i)\$(TOOL|BASE)\s*=\s*(\$NULLFRAME|\w+)", text)
        if m:
            read = self._tool_base(m.group(1).upper(), m.group(2))
            if not read:  # kept native: a motion after it reads a value the import does not know
                name = "tool" if m.group(1).upper() == "TOOL" else "frame"
                st.unsure[name] = (f"at line {self.at.line if self.at else 0} to a value the import does not read", getattr(st, name))
            return read
        m = re.fullmatch(r"(?is)\$(TOOL|BASE)\s*=\s*(\{.*\})", text)
        if m:
            return self._inline_frame(m.group(1).upper(), m.group(2))
        m = re.fullmatch(r"(?i)BAS\s*\(\s*#(TOOL|BASE)\s*,\s*(\d+)\s*\)|\$(TOOL)\s*=\s*TOOL_DATA\[(\d+)\]|\$(BASE)\s*=\s*BASE_DATA\[(\d+)\]", text)
        if m:  # KSS BAS.SRC: $TOOL = TOOL_DATA[n] / $BASE = BASE_DATA[n] (n 0: the flange / robot base)
            kind, n = [g for g in m.groups() if g is not None][0].lower(), [g for g in m.groups() if g is not None][1]
            if kind == "tool" and n == "0":
                st.tool = "flange"
            else:
                chosen = numbered(self.tools, self.frames, self.tally, kind, n, None, self.at or Where(self.tally.path, 1))
                st.tool, st.frame = (chosen, st.frame) if kind == "tool" else (st.tool, chosen)
            return True
        return re.fullmatch(r"(?i)\$LOAD\s*=\s*\w+", text) is not None or axes_slots.krl_setting(st, text)

    def named_loads(self) -> tuple[NamedLoad, ...]:
        """The .dat's LOAD data: (name, mass kg, centre of mass mm in the flange frame)."""
        return named_loads(self.data)

    def _tool_base(self, which: str, name: str) -> bool:
        key = name.upper()
        if which == "TOOL":
            if key == "$NULLFRAME":
                self.state.tool = "flange"
            elif key in self.tools:
                self.state.tool = self.tools[key].name
            else:
                return False
        elif key == "$NULLFRAME":
            self.state.frame = "base"
        elif key in self.frames:
            self.state.frame = self.frames[key].name
        else:
            return False
        return True

    def _inline_frame(self, which: str, text: str) -> bool:
        """`$TOOL = {FRAME: X .., C ..}` / `$BASE = {..}` written in the program (RoboDK, hand
        programs): a tool or work object of that pose, one per distinct value; an identity base is
        the robot base."""
        agg = aggregate(text)
        pose = krl_pose(agg) if agg is not None else None
        if pose is None:
            return False
        table: dict[str, ToolData] | dict[str, FrameData] = self.tools if which == "TOOL" else self.frames
        if which == "BASE" and pose == ir.Pose():
            self.state.frame = "base"
            return True
        same = next((v.name for v in table.values() if (v.tcp if isinstance(v, ToolData) else v.pose) == pose), None)
        if same is None:
            same = f"{which.lower()}_{len(table) + 1}"
            at = self.at or Where(self.tally.path, 1)
            if which == "TOOL":
                self.tools[same.upper()] = ToolData(same, pose, 0.0, at)
            else:
                self.frames[same.upper()] = FrameData(same, pose, at)
        if which == "TOOL":
            self.state.tool = same
        else:
            self.state.frame = same
        return True

    def _simple(self, ln: Line) -> Stmt | None:
        text, word, where = ln.text, ln.word, ln.where
        if word in MOTIONS:
            move = self._motion(word, text[len(word):].strip(), where)
            self.last = (move.target, move.target_name, declared(move)) if move and move.pose else None
            return move
        if word in ("LIN_REL", "PTP_REL"):
            return self._relative(word, text[len(word):].strip(), where)
        m = re.fullmatch(r"(?i)(?:\$OUT(?:_C)?\[(\d+)\]|(\w+))\s*=\s*(TRUE|FALSE)", text)
        port = (int(m.group(1)) if m.group(1) else port_of(self.signals, m.group(2), "OUT")) if m else None
        if m and port is not None:
            return SetOut(port, 1.0 if m.group(3).upper() == "TRUE" else 0.0, where)
        m = re.fullmatch(r"(?i)\$ANOUT\[(\d+)\]\s*=\s*(-?[\d.]+)", text)
        if m:
            return SetOut(int(m.group(1)), float(m.group(2)) * 10.0, where, analog=True)
        # PULSE(signal, TRUE, t): the signal is an output, `$OUT[n]` or a SIGNAL's name (KSS 8.x, PULSE)
        m = re.fullmatch(r"(?i)PULSE\s*\(\s*(?:\$OUT\[(\d+)\]|(\w+))\s*,\s*TRUE\s*,\s*([\d.]+)\s*\)", text)
        pending: list[str] = []
        pulsed = (int(m.group(1)) if m.group(1) else self._named(m.group(2), "OUT", pending)) if m else None
        if m and pulsed is not None:
            self._warn_named(pending, "output")
            return Pulse(pulsed, float(m.group(3)), where)
        m = re.fullmatch(r"(?i)WAIT\s+SEC\s+([\d.]+)", text)
        if m:
            return Wait(float(m.group(1)), where)
        m = re.fullmatch(r"(?i)WAIT\s+FOR\s+(.+)", text)
        if m:
            cond = self._cond(m.group(1))
            return WaitIn(cond, None, where) if cond else None
        m = re.fullmatch(r"(\w+)\s*\((.*)\)", text)
        sig = (self.signatures.get(m.group(1).upper()) if m.group(2).strip() else ()) if m else None
        args = call_args(m.group(2), sig, self.params) if m and sig is not None else None
        if m and args is not None and m.group(1).upper() not in ("HALT", "BAS") and (at := self.calls.at_call(text, self.state)) is not None:
            return Call(m.group(1), args, where, **at)  # type: ignore[arg-type]
        return None

    def _target(self, text: str, at: Where | None = None) -> tuple[str, str | None, Target | None] | None:
        text = text.strip()
        key = re.sub(r"\s+", "", text).upper() if re.fullmatch(r"\w+\s*\[\s*\d+\s*\]", text) else text.upper()
        if key in self.work.copies:
            base, offsets = self.work.copies[key]
            decl = self.targets[base]
            terms = ", ".join(f"{axis}={mm(e)}" for axis, e in sorted(offsets.items()))
            named = rmot_name(decl.name)
            return (f"shift({named}, {terms})" if terms else named, decl.name, decl)
        known = self.flow.get(key)
        if known is not None:
            return known_target(known, at or Where(self.tally.path, 1), self._target)
        if key not in self.targets and key in self.config and key.split("[")[0] not in self.assigned:
            found = position(*self.config[key])  # a global position of the robot's $config.dat
            if found is not None:
                self.targets[key] = found
        if key in self.targets:
            decl = self.targets[key]
            return (rmot_name(decl.name), decl.name, decl)
        if key in ("HOME", "XHOME") and at is not None:
            decl = home(self.targets, self.config, self.tally, at)
            return (rmot_name(decl.name), decl.name, decl)
        parts = split_top(text, ":")
        if len(parts) == 2:  # `P:{X .., C ..}` (KSS 8.x geometric operator: the frame in P's own frame)
            left, agg = self._target(parts[0], at), aggregate(parts[1])
            offset = krl_pose(agg) if agg is not None else None
            if left is None or left[2] is None or left[2].pose is None or offset is None:
                return None
            return (f"{left[0]} * {pose_expr(offset)}", left[1], Target("", left[2].pose * offset, None, None, left[2].where))
        agg = aggregate(text)  # a literal position: Cartesian where it has X..C, else axes A1..A6
        found = position("E6POS" if krl_pose(agg) else "E6AXIS", "", agg, Where("", 0)) if agg is not None else None
        if found is None:
            return None
        return (literal(found), None, found)

    def _relative(self, word: str, rest: str, where: Where) -> Move | None:
        """`LIN_REL {X dx, Y dy, Z dz} [C_DIS] [#BASE|#TOOL]` (KSS 8.x, relative motions: the
        offset in the base, or with #TOOL in the tool frame, from where the last move ended) →
        `shift(last, ..)` / `last * pose(..)`; only a translation, and only after a move whose
        target is known in straight-line code (a relative move's own, an expression, included)."""
        m = re.fullmatch(r"(?is)(\{.*\})\s*(C_DIS|C_PTP)?\s*(#BASE|#TOOL)?", rest)
        agg = aggregate(m.group(1)) if m else None
        last = self.last
        if m is None or agg is None or last is None or set(agg) - {"X", "Y", "Z"} or \
                not all(isinstance(v, float) for v in agg.values()):
            return None
        terms = ", ".join(f"{k.lower()}={num_text(float(v))}mm" for k, v in sorted(agg.items()) if v != 0.0)  # type: ignore[arg-type]
        expr = (f"{last[0]} * pose({terms})" if (m.group(3) or "").upper() == "#TOOL" else
                f"shift({last[0]}, {terms})") if terms else last[0]
        move = self._motion("PTP" if word == "PTP_REL" else "LIN", f"_ {m.group(2) or ''}", where,
                            (expr, last[1], None))
        self.last = (expr, last[1], None) if move is not None else None  # the next one starts here
        return move

    def _motion(self, word: str, rest: str, where: Where,
                point: tuple[str, str | None, Target | None] | None = None) -> Move | None:
        """A motion statement; `point`: its target already read (a relative move's)."""
        if re.search(r"(?i)\bWITH\b", rest):
            return self._with(word, rest, where)
        kind = MOTIONS[word]
        m = re.fullmatch(r"(?is)(.*?)\s*(C_PTP\s+C_DIS|C_DIS\s+C_DIS|C_PTP|C_DIS|C_VEL|C_ORI|C_SPL)?", rest)
        points = split_top(m.group(1)) if m else []
        if kind == "joint" and any(len(split_top(p, ":")) > 1 for p in points):
            return None  # a PTP to `P:{..}`: which Status the result takes is not read
        approx = " ".join((m.group(2) or "").upper().split()) if m else ""
        # the KSS 8 inline form's own statement names the approximation twice, `LIN XP2 C_DIS C_DIS`
        # (its header's `%P 3:C_DIS C_DIS`): one C_DIS
        approx = "C_DIS" if approx == "C_DIS C_DIS" else approx
        # C_SPL on a SLIN/SCIRC single motion blends by $APO.CDIS as C_DIS does on LIN/CIRC (KSS 8.3
        # System Integrators, spline single motions); on SPTP (and on PTP/LIN/CIRC) it stays native
        if approx == "C_SPL" and word in ("SLIN", "SCIRC"):
            approx = "C_DIS"
        if len(points) != (2 if kind == "circular" else 1) or approx in ("C_VEL", "C_ORI", "C_SPL"):
            return None
        found = [point] if point is not None else [self._target(p, where) for p in points]
        if any(f is None for f in found):
            return None
        st = self.state
        if st.unsure_of(kind == "joint", approx) is not None:
            return None
        if kind == "joint":  # a PTP blended into a LIN/CIRC: `C_PTP C_DIS`, its radius $APO.CDIS
            zone = (st.cptp * KrlBackend.CPTP_MM if approx == "C_PTP" and st.cptp is not None else
                    st.cdis if approx in ("C_DIS", "C_PTP C_DIS") else None)
        else:
            zone = st.cdis if approx == "C_DIS" else None
        if approx and zone is None:
            return None
        expr, name, decl = found[-1]  # type: ignore[misc]
        config = decl.config if kind == "joint" and decl is not None and decl.pose is not None else None
        return Move(kind, expr, name, where, via=found[0][0] if kind == "circular" else None,  # type: ignore[index]
                    speed=st.vel_cp if kind != "joint" else None, joint_pct=st.vel_ptp if kind == "joint" else None,
                    zone=zone, tool=st.tool, frame=st.frame, config=config,
                    pose=decl.pose if decl else None, joints=decl.joints if decl else None, slots=decl.slots if decl else (),
                    accel=st.acc_cp if kind != "joint" else None, joint_accel=st.acc_ptp if kind == "joint" else None)

    def _with(self, word: str, rest: str, where: Where) -> Move | None:
        """`SLIN P WITH $VEL.CP = v, $APO.CDIS = d C_SPL`, `SPTP P WITH $VEL_AXIS[1] = v, .., [6] = v`
        (all six equal): the motion with these values, the modal ones unchanged after it."""
        m = re.fullmatch(r"(?is)(\S.*?)\s+WITH\s+(.*?)\s*(C_DIS|C_SPL|C_PTP)?", rest)
        state = with_state(self.state, m.group(2)) if m else None
        if m is None or state is None:
            return None
        saved, self.state = self.state, state
        try:
            return self._motion(word, f"{m.group(1)} {m.group(3) or ''}", where)
        finally:
            self.state = saved

    def _fold(self, i: int) -> tuple[list[Stmt], int]:
        """An inline form: a motion read from its header (its statements skipped), anything
        else read from the statements inside; the INI fold is set-up, kept as a comment."""
        header = self.lines[i].fold or ""
        end = fold_end(self.lines, i)
        if SETUP_FOLD.match(header):
            self.tally.warn(codes.DECLARATION_KEPT, f"the `{header[:30]}` fold is controller set-up: kept as a "
                            "comment", self.lines[i].where)
            return [], end + 1
        m = re.match(r"(?i)(S?PTP|S?LIN|S?CIRC)\s+(.*)", header)
        if m is None:
            return [], i + 1  # the statements inside are read as they come
        if not any(ln.word in MOTIONS for ln in self.lines[i + 1:end]):
            self.tally.warn(codes.FOLD_DISABLED, f"the inline form `{header[:40]}` has its statements commented "
                            "out: the controller skips it, and so does the import", self.lines[i].where)
            return [], end + 1
        move = inline_move(m.group(1).upper(), m.group(2), self.lines[i].where, lambda p, at: self._target(p, at),
                           (self.data, self.config), (self.tools, self.frames), self.tally)
        self.last = (move.target, move.target_name, declared(move)) if move and move.pose else None
        if move is None:
            why = inline_why(m.group(2), self._names(), [*self.data, *self.config])
            return [self.tally.keep(header, self.lines[i].where, "an inline form rmot cannot read" +
                                    (f": {why}" if why else ""))], end + 1
        self.tally.imported += 1
        self.calls.moved(move, self.state)
        return [move], end + 1


def read_krl(src: tuple[str, str], dat: tuple[str, str] | None, others: dict[str, Params | None] | None = None) -> _Krl:
    """Read a KRL .src (and its .dat; `others`: the routines of the other files given, by name
    with their parameters); raises ImportError_ (E510) when it is not KRL."""
    module = _Krl(src, dat, others or {})
    module.read()
    return module
