"""Read Fanuc TP programs (`.ls`, the ASCII form) back into a neutral Document.

Conventions are the Fanuc backend's, read in reverse (FANUC R-30iB Operator's Manual, Basic
Operation): `/PROG NAME`, `/MN` numbered lines ending `;` (a line starting `:` continues the
one before, as a circular move's second point), `/POS` positions `P[n:"name"]{ GP1: UF, UT,
CONFIG : 'F|N U|D T|B, t4, t5, t6', X Y Z mm, W P R deg }` (R = Rz(R)·Ry(P)·Rx(W): rx=W, ry=P,
rz=R) or `J1..J6 deg`; CONFIG N = wrist flip (the backend's `config_string`), U elbow up, T
shoulder front (turn numbers are not read: the planner takes the nearest, as the program did);
`J P[n] v% FINE|CNTn`, `L P[n] v mm/sec ..`, `C P[a] : P[b] ..`, `n.nnsec` a fixed time, CNT
1 mm per step (`FanucBackend.CNT_MM`); `UTOOL_NUM`/`UFRAME_NUM` (0 = robot base) with the
tool/frame written through `PR[k]=LPOS`, `PR[k,i]=v`, `UTOOL[n]=PR[k]` and named by the
`!UTOOL[n] = name` comment; `DO[n]=ON|OFF|PULSE,t sec`, `AO[n]=`, `WAIT t(sec)`, `WAIT DI[n]=..`
with `$WAITTMOUT` (1/100 s) and the ABORT label; the counting loop `R[v]=a`, `LBL[t]`, ..,
`R[v]=R[v]+1`, `IF R[v]<=b,JMP LBL[t]` with `Offset,PR[k]`, `PR[k,i]=R[v]*d` as `shift`."""

from __future__ import annotations

import re
from dataclasses import replace

from rmot.backends.fanuc_tp import FanucBackend
from rmot.backends.readers import axes_slots, codes
from rmot.backends.readers.common import Tally, counter_alone, label_arms, label_loop, match_simple, reaches, rmot_name
from rmot.backends.readers.position_records import native_positions
from rmot.backends.readers.fanuc_regs import Registers, negated
from rmot.backends.readers.fanuc_va import Controller, empty
from rmot.backends.readers.fanuc_values import RegisterValues
from rmot.backends.readers.fanuc_text import (
    CALLERS, caller_selection, kept_option, label_of, names_label, selected_by_call, motion_options, output_expression, path_points,
    position_blocks, position_values, timed_wait, tp_branch, tp_pose, tp_speed, wait_condition,
)
from rmot.backends.readers.jump_spans import keep_jumped_spans
from rmot.backends.readers.jumps import Jump, jump_chain, jumped_to_elsewhere
from rmot.backends.readers.model import (
    Call, Cond, Conds, For, FrameData, If, Move, NamedLoad, Native, Pulse, PulsePose, SetOut, Stmt, Stop, Target, ToolData, WaitIn,
    Where, Routine)
from rmot.backends.readers.rapid import mm
from rmot.lang import ir

__all__ = ["read_fanuc"]

_MOTION = re.compile(r"(?i)^(J|L)\s+(PR?)\[(\d+)(?::[^\]]*)?\]\s+(.*?)\s+(FINE|CNT\s*\d+)\s*(.*)$")
_CIRC = re.compile(r"(?i)^C\s+P\[(\d+)(?::[^\]]*)?\]\s*:\s*P\[(\d+)(?::[^\]]*)?\]\s+(.*?)\s+(FINE|CNT\s*\d+)\s*(.*)$")
_SIG = r"\[(\d+)(?::[^\]]*)?\]"
_NATIVE_JMP = re.compile(r"\bJMP\s+LBL\[(\d+)")  # a jump kept native (not TIMEOUT,LBL: the wait's error exit)
_THEN = re.compile(r"IF\s*(\(.*\))\s*THEN")
_FOR = re.compile(r"FOR\s+\S.*")
_JMP = re.compile(r"JMP LBL\[(\d+)\]")
# TP standard instructions (B-83284EN): outputs, pulses, analog outputs, timed and input waits, calls
_SIMPLE = (
    ("out", re.compile(rf"DO{_SIG}\s*=\s*\(?(ON|OFF)\)?")),  # the pendant writes `DO[n]=(ON)` too
    ("pulse", re.compile(rf"DO{_SIG}\s*=\s*PULSE,\s*([\d.]+)\s*sec")),
    ("aout", re.compile(rf"AO{_SIG}\s*=\s*(-?[\d.]+)")),
    ("wait", re.compile(r"WAIT\s+([\d.]+)\s*\(sec\)")),
    ("wait_in", re.compile(rf"WAIT DI{_SIG}\s*=\s*(ON|OFF)")),
    ("wait_true", re.compile(r"WAIT\s*\(\s*(?P<neg>!?)DI\[(?P<sig>\d+)(?::[^\]]*)?\]\s*\)")),
    ("call", re.compile(r"CALL\s+(\w+)")),
)


class _Ls:
    def __init__(self, path: str, text: str, labels: dict[str, dict[int, str]],
                 programs: dict[str, tuple[str, str]] | None = None, pulse_pose: PulsePose | None = None,
                 not_vars: frozenset[tuple[str, int]] = frozenset(), controller: Controller | None = None) -> None:
        self.tally = Tally(path, text, "fanuc")
        self.controller = controller or Controller(empty(), [text])  # the registers and frames a backup's .VA files saved
        self.values = RegisterValues(self.controller, [])  # the register values its motion lines read (once read)
        self.not_vars = not_vars  # registers and flags not read as task variables (read_fanuc)
        self.path = path
        self.raw = text.split("\n")
        self.name = ""
        self.instructions: list[tuple[str, Where]] = []
        self.positions: dict[int, Target] = {}
        self.tools: dict[int, ToolData] = {}
        self.frames: dict[int, FrameData] = {}
        self.labels = {kind: dict(names) for kind, names in labels.items()}
        self.pr: dict[int, list[float]] = {}
        self.offsets: dict[int, dict[str, str]] = {}
        self.loop_vars: dict[str, str] = {}
        self.state: dict[str, int] = {"UTOOL": CALLERS, "UFRAME": CALLERS}  # until the program selects one
        self.taught: dict[int, dict[str, int]] = {}  # position -> the UFRAME and UTOOL numbers it records
        self.inherited: dict[str, int] = {}  # the caller's UFRAME/UTOOL numbers, read from the first move's position
        self.timeout: float | None = None
        self.routine = Routine("", (), (), Where(path, 1))  # the program, once read
        self.programs = programs or {}
        self.inlined: set[str] = set()  # programs read again at a call inside a loop
        self.loads: list[NamedLoad] = []  # PAYLOAD[i] schedules, the mass a remark before the line gives
        self.pulse_pose = pulse_pose  # (joints deg, tool name) -> the TCP pose in the base (the cell's arm)
        self.tcp: dict[tuple[str, str], Target] = {}  # (joint-form position, tool) -> its TCP pose target
        self.regs: Registers | None = None  # the registers and flags read as variables or group inputs

    # ---------------------------------------------------------------- sections

    def read(self) -> Routine:
        first = next(((n, ln) for n, ln in enumerate(self.raw, 1) if ln.strip()), (1, ""))
        m = re.match(r"\s*/PROG\s+([\w-]+)", first[1])  # the pendant names its background-edit copies -BCKEDT-
        if m is None:
            raise self.tally.fail("a Fanuc TP .ls program must start with `/PROG NAME`", Where(self.path, first[0]))
        self.name = m.group(1)
        section = ""
        for n, line in enumerate(self.raw, 1):
            stripped = line.strip()
            if stripped.startswith("/"):
                section = stripped.split()[0].upper()
                continue
            if section == "/MN" and stripped:
                self._mn_line(line, n)
        self._positions()
        main = not self.programs or next(iter(self.programs)) == self.name.upper()  # the job's first program runs
        others = [text for name, (_, text) in self.programs.items() if name != self.name.upper()]
        taken = [t.name for t in self.positions.values()] + [n for names in self.labels.values() for n in names.values()]
        taken += [rmot_name(name) for name in self.programs]  # the procs
        self.regs = Registers(self.tally, self.instructions, others, main, taken, self.not_vars)
        self.values = RegisterValues(self.controller, [t for t, _ in self.instructions])
        body, _ = self._block(0, None)
        kept = (*self.regs.decls, *keep_jumped_spans(tuple(body), self.tally, _NATIVE_JMP, label_of, self.instructions,
                                                     lambda t: t + " ;"))
        self.regs.warn_reads(kept)
        for n in native_positions(kept, self.path, "fanuc"):  # the frame and tool its record names: in the stub too
            for kind, number in self.taught.get(n, {}).items():
                self._named(kind, self.positions[n].where if n in self.positions else Where(self.path, 1), number)
        self.routine = Routine(self.name, (), kept, Where(self.path, first[0]))
        return self.routine

    def _mn_line(self, line: str, n: int) -> None:
        if re.fullmatch(r"\s*-+\s*;?\s*", line):  # the end of a move's point-logic lines (its own
            return  # numbered lines, listed after the move, run at the point: read in sequence)
        m = re.match(r"\s*(\d+)?\s*:\s*(.*?)\s*;?\s*$", line) or (  # `C P[a]` on its line, `P[b] ..` on the next
            re.match(r"()\s*(P\[.*?)\s*;?\s*$", line) if self.instructions and re.fullmatch(
                r"C\s+PR?\[[^\]]*\]", self.instructions[-1][0]) else None)  # (as RoboDK's post writes it, without `:`)
        if m is None:
            raise self.tally.fail(f"a /MN line must be `N:  instruction ;` (got `{line.strip()[:40]}`)", Where(self.path, n))
        text = m.group(2)
        if not m.group(1) and self.instructions and re.match(r"P\[", text):  # `: P[b] ..` continues C P[a]
            prev, where = self.instructions[-1]
            self.instructions[-1] = (f"{prev} : {text}", where)
        else:
            self.instructions.append((text, Where(self.path, n, len(line) - len(line.lstrip()) + 1)))

    def _positions(self) -> None:
        for n, label, whole, line in position_blocks("\n".join(self.raw)):
            body, where = re.split(r"\bGP[2-9]\s*:", whole)[0], Where(self.path, line)  # the arm's group
            values = position_values(body, f"P[{n}]", where, self.tally.fail)
            conf = re.search(r"CONFIG\s*:\s*'([^']*)'", body)
            name = rmot_name(label) if label else rmot_name(f"{self.name.lower()}_p{n}")  # `-BCKED8-`: a name
            name = f"{name}_{n}" if any(t.name == name for t in self.positions.values()) else name  # a label twice
            taught = re.search(r"\bUF\s*:\s*(\d+)\s*,\s*UT\s*:\s*(\d+)", body)
            self.taught.update({n: {"UFRAME": int(taught.group(1)), "UTOOL": int(taught.group(2))}} if taught else {})
            if all(k in values for k in "XYZWPR"):
                self.positions[n] = Target(name, tp_pose([values[k] for k in "XYZWPR"]), None,
                                           tp_branch(conf.group(1)) if conf else None, where, slots=axes_slots.fanuc_slots(whole))
            elif all(f"J{i}" in values for i in range(1, 7)):
                self.positions[n] = Target(name, None, tuple(values[f"J{i}"] for i in range(1, 7)), None, where,
                                           slots=axes_slots.fanuc_slots(whole))
            else:  # coordinates rmot does not read (`RX =` ..): kept as a comment, so `rmot diff` sees a touch-up
                self.tally.comments.append(Native("fanuc", f"P[{n}]{{{' '.join(whole.split())}}}", where))

    # ---------------------------------------------------------------- instructions

    def _block(self, i: int, stop: int | None) -> tuple[list[Stmt], int]:
        """The statements from `i` to the block's end (nesting bounded by Tally.nested)."""
        where = self.instructions[min(i, len(self.instructions) - 1)][1] if self.instructions else Where(self.path, 1)
        before = dict(self.state)
        found = self.tally.nested(where, lambda: self._block_body(i, stop))
        if i > 0:  # a tool or frame the block selects: after it, the block's line decides (it may not run)
            self.state.update({k: -i for k, v in before.items() if self.state[k] != v})
        return found

    def _block_body(self, i: int, stop: int | None) -> tuple[list[Stmt], int]:
        end = len(self.instructions) if stop is None else stop
        body: list[Stmt] = []
        while i < end:
            stmts, after = self._statement(i, end)  # then what a program the line calls selects holds
            self.state.update({k: -1 - i for k in selected_by_call(self.programs, self._text(i))})
            body, i = body + stmts, after
        return body, i

    def _text(self, i: int) -> str:
        return self.instructions[i][0] if i < len(self.instructions) else ""

    def _statement(self, i: int, end: int) -> tuple[list[Stmt], int]:
        text, where = self.instructions[i]
        if text.startswith("!"):
            m = re.fullmatch(r"!\s*(UTOOL|UFRAME)\[(\d+)\]\s*=\s*(\w+)", text)
            if m:
                self.labels[m.group(1)][int(m.group(2))] = m.group(3)
            return [], i + 1
        if not text:
            return [], i + 1
        call = re.fullmatch(r"CALL\s+(\w+)", text)
        inlined = self._inline_body(call.group(1)) if call else None
        if inlined is not None:
            self.tally.imported += 1
            return list(inlined), i + 1
        for pattern in (self._data, self._loop, self._timed_wait, self._if, self._structured, self._register,
                        self._if_call):
            found = pattern(i, end)
            if found is not None:
                return found
        self.values.start(i)
        moved = self._motion(text, where) if text.startswith(("J ", "L ", "C ")) else None
        if moved is not None:
            self.values.note(self.tally, where)  # W543: the move is read with a value a backup saved
            self.tally.imported += 1
            return [replace(moved[0], source=f"{text} ;"), *moved[1]], i + 1
        stmt = self._simple(text, where)
        payload = re.fullmatch(r"PAYLOAD\[(\d+)\]", text)
        remark = re.fullmatch(r"!.*:\s*(\d+(?:\.\d+)?)\s*kg", self._text(i - 1)) if payload and i > 0 else None
        if remark:  # (its centre is not known)
            self.loads.append((f"PAYLOAD[{payload.group(1)}]", float(remark.group(1)), (float("nan"),) * 3, where))  # type: ignore[union-attr]
        if stmt is None:
            selected = caller_selection(self.state, [self.taught.get(p) for p in path_points(text)], self.inherited)
            joint_form = [why for why in (self._tcp_of(p, where, selected["UTOOL"]) for p in path_points(text))
                          if isinstance(why, str)] if isinstance(selected, dict) else []
            why = joint_form[0] if joint_form else self.values.unread or "no rmot form"
            return [self.tally.keep(text + " ;", where, why)], i + 1
        self.tally.imported += 1
        return [stmt], i + 1

    def _data(self, i: int, end: int) -> tuple[list[Stmt], int] | None:
        """PR writes (a tool, frame or loop offset being built) and UTOOL/UFRAME selections."""
        text = self._text(i)
        m = re.fullmatch(r"PR\[(\d+)(?::[^\]]*)?\]\s*=\s*LPOS(-LPOS)?", text)
        if m:
            self.pr[int(m.group(1))] = [0.0] * 6
            if m.group(2):
                self.offsets[int(m.group(1))] = {}
            return [], i + 1
        m = re.fullmatch(r"PR\[(\d+),(\d)\]\s*=\s*(-?[\d.]+)", text)
        if m and int(m.group(1)) in self.pr and 1 <= int(m.group(2)) <= 6:
            self.pr[int(m.group(1))][int(m.group(2)) - 1] = float(m.group(3))
            return [], i + 1
        m = re.fullmatch(r"PR\[(\d+),([123])\]\s*=\s*R\[(\d+)(?::[^\]]*)?\]\*(-?[\d.]+)", text)
        if m and int(m.group(1)) in self.offsets and m.group(3) in self.loop_vars:
            self.offsets[int(m.group(1))]["xyz"[int(m.group(2)) - 1]] = f"{self.loop_vars[m.group(3)]} * {m.group(4)}"
            return [], i + 1
        m = re.fullmatch(r"(UTOOL|UFRAME)\[(\d+)\]\s*=\s*PR\[(\d+)\]", text)
        if m and int(m.group(3)) in self.pr:
            self._define(m.group(1), int(m.group(2)), self.pr[int(m.group(3))], self.instructions[i][1])
            return [], i + 1
        m = re.fullmatch(r"(UTOOL|UFRAME)_NUM\s*=\s*(.+)", text)
        if m:  # a number selects the frame; anything else (`UFRAME_NUM=R[5]`) leaves it to run time
            self.state[m.group(1)] = int(m.group(2)) if m.group(2).isdigit() else -1 - i
            return ([], i + 1) if m.group(2).isdigit() else None
        m = re.fullmatch(r"\$WAITTMOUT\s*=\s*(\d+)", text)
        if m:
            self.timeout = int(m.group(1)) / 100.0
            return [], i + 1
        return None

    def _define(self, kind: str, n: int, v: list[float] | tuple[float, ...], where: Where) -> None:
        pose = tp_pose(v)
        name = self.labels[kind].get(n, f"{kind.lower()}{n}")
        if kind == "UTOOL":
            self.tools[n] = ToolData(name, pose, 0.0, where)
        else:
            self.frames[n] = FrameData(name, pose, where)

    def _named(self, kind: str, at: Where, n: int) -> str:
        if kind == "UFRAME" and n == 0:
            return "base"
        table = self.tools if kind == "UTOOL" else self.frames
        saved = self.controller.data.utool if kind == "UTOOL" else self.controller.data.uframe
        if n not in table and n in saved and saved[n].xyzwpr is not None:
            self._define(kind, n, saved[n].xyzwpr or [], saved[n].where)  # SYSFRAME.VA's $MNUTOOL/$MNUFRAME
        if n not in table:
            label = self.labels[kind].get(n, f"{kind.lower()}{n}")
            if kind == "UTOOL":  # UTOOL 0: the faceplate (B-83284EN, tool frame), no controller data
                self.tools[n] = ToolData(label, ir.Pose(), 0.0, at, f"UTOOL[{n}]" if n else "", n or None)
            else:
                self.frames[n] = FrameData(label, ir.Pose(), at, f"UFRAME[{n}]", n)
        return table[n].name

    def _loop(self, i: int, end: int) -> tuple[list[Stmt], int] | None:
        found = label_loop(self._text, i, end, r"R\[(\d+)(?::[^\]]*)?\]\s*=\s*(-?\d+)", r"LBL\[(\d+)\]",
                           lambda r, k: rf"IF R\[{r}(?::[^\]]*)?\]<=(-?\d+),JMP LBL\[{k}\]",
                           lambda r: rf"R\[{r}(?::[^\]]*)?\]=R\[{r}(?::[^\]]*)?\]\+1")
        if found is None or not self._counter_alone(found[0], i, found[3]) or jumped_to_elsewhere(
                self._text, len(self.instructions), (label_of(self._text(i + 1)) or "",), names_label, {i + 1, found[3]}):
            return None  # the counter not the loop's alone, or a jump into the loop
        reg, first, last, j = found
        label = re.match(r"R\[\d+:([^\]]*)\]", self._text(i))
        self.loop_vars[reg] = var = rmot_name((label.group(1) if label else f"r{reg}").replace(" ", "_"))
        body, _ = self._block(i + 2, j - 1)
        del self.loop_vars[reg]
        self.tally.imported += 1
        return [For(var, first, last + 1, tuple(body), self.instructions[i][1])], j + 1

    def _counter_alone(self, reg: str, i: int, j: int, own: tuple[int, ...] = ()) -> bool:
        """Whether no register is written through another and R[reg] is the loop's (lines `i` to
        `j`) alone (common.counter_alone): counted by labels, or by FOR .. ENDFOR (`own` = (i, j))."""
        c = rf"R\[{reg}(?::[^\]]*)?\]"
        return self.regs is not None and not self.regs.indirect and counter_alone(
            self._text, len(self.instructions), i, j, rf"\b{c}", (rf"PR\[\d+,[123]\]\s*=\s*{c}\*-?[\d.]+",),
            (rf"{c}\s*=\s*-?\d+", rf"{c}={c}\+1", rf"IF {c}<=-?\d+,JMP LBL\[\d+\]", rf"FOR {c}=-?\d+ TO -?\d+"), own)

    def _for(self, i: int, j: int) -> tuple[list[Stmt], int] | None:
        """`FOR R[v]=a TO b` .. `ENDFOR` with whole numbers a <= b (B-83284EN "FOR/ENDFOR": R[v]
        from a while it is at most b, one up at ENDFOR) where R[v] is the loop's alone: `for`."""
        m = re.fullmatch(r"FOR R\[(\d+)(?::([^\]]*))?\]=(-?\d+) TO (-?\d+)", self._text(i))
        if m is None or int(m.group(3)) > int(m.group(4)) or not self._counter_alone(m.group(1), i, j, (i, j)):
            return None
        self.loop_vars[m.group(1)] = var = rmot_name((m.group(2) or f"r{m.group(1)}").replace(" ", "_"))
        body, _ = self._block(i + 1, j)
        del self.loop_vars[m.group(1)]
        self.tally.imported += 1
        return [For(var, int(m.group(3)), int(m.group(4)) + 1, tuple(body), self.instructions[i][1])], j + 1

    def _register(self, i: int, end: int) -> tuple[list[Stmt], int] | None:
        """`R[i]=v`, `F[i]=(ON)` on a task variable (fanuc_regs.py); `DO[n]=(cond)` as an if setting on or off."""
        text, where = self.instructions[i]
        out = output_expression(text)  # (an output's line: never a register's)
        cond = self._condition(out[1]) if out is not None else None
        stmt = If(cond, (SetOut(out[0], 1.0, where),), (SetOut(out[0], 0.0, where),), where) if out and cond else (
            self.regs.assignment(text, where) if self.regs is not None else None)
        if stmt is None:
            return None
        self.tally.imported += 1
        return [stmt], i + 1

    def _if_call(self, i: int, end: int) -> tuple[list[Stmt], int] | None:
        """`IF (cond),action` (B-83284EN, IF with an action) where `_action` reads the action."""
        text, where = self.instructions[i]
        m = re.fullmatch(r"IF\s*(.+?),\s*(.+)", text)
        act = self._action(m.group(2), where) if m else None
        cond = self._condition(m.group(1)) if m and act is not None else None
        if cond is None or act is None:
            return None
        self.tally.imported += 1
        return [If(cond, (act,), (), where)], i + 1

    def _action(self, text: str, where: Where) -> Stmt | None:
        """An IF's action: a CALL of a program of the job, an output set or pulsed (`DO[n]=ON`,
        `DO[n]=PULSE,3.0sec`) or a task variable's assignment; None for any other."""
        call = re.fullmatch(r"CALL\s+(\w+)", text)
        if call:
            return Call(call.group(1), (), where) if call.group(1).upper() in self.programs else None
        simple = match_simple(text, _SIMPLE, where)
        return simple if isinstance(simple, (SetOut, Pulse)) else self.regs.assignment(text, where) if self.regs else None

    def _condition(self, text: str) -> Cond | Conds | None:
        """A TP condition on inputs and outputs (as `WAIT` reads it), or on registers and flags."""
        found = wait_condition(f"WAIT {text}")
        return found if found is not None or self.regs is None else self.regs.condition(text)

    def _jump_at(self, i: int) -> Jump | None:
        """`IF DI[n]<>ON,JMP LBL[a]` (or an output, `DO[n]`), or a jump on any condition
        `_condition` reads (a group input's test `IF GI[n]<>v,JMP`, registers, flags): its label,
        when it is taken and when not."""
        m = re.fullmatch(rf"IF (DI|DO){_SIG}\s*(<>|=)\s*(ON|OFF),\s*JMP LBL\[(\d+)\]", self._text(i))
        if m is not None:
            # taken when the signal is at the level `=` names, or at the other one with `<>`
            taken = Cond(int(m.group(2)), (m.group(4) == "ON") == (m.group(3) == "="), m.group(1) == "DO")
            return m.group(5), taken, taken.negated(), i + 1
        # any other condition `_condition` reads: `IF (DI[1]),JMP`, `IF GI[1]<>3,JMP`, registers, flags
        r = re.fullmatch(r"IF\s*(.+?),\s*JMP LBL\[(\d+)\]", self._text(i))
        test = self._condition(r.group(1)) if r else None
        if r is None or test is None:
            return None
        return r.group(2), test, negated(test), i + 1

    def _if(self, i: int, end: int) -> tuple[list[Stmt], int] | None:
        """Conditional jumps to `LBL[a]` (`_jump_at`: all of them, `and`; or a chain to `LBL[s]`
        and one to `LBL[a]` then `LBL[s]`, `or`: readers/jumps.py), then-body, [`JMP LBL[b]`,
        `LBL[a]`, else-body,] `LBL[b]`."""
        chain = jump_chain(self._jump_at, self._text, i, lambda n: f"LBL[{n}]")
        if chain is None:
            return None
        label, cond, start, more = chain
        arms = label_arms(self._text, start - 1, end, f"LBL[{label}]", _JMP, lambda n: f"LBL[{n}]")
        if arms is None:
            return None
        ja, jb = arms
        labels = (label, *more) + ((_JMP.fullmatch(self._text(ja - 1)).group(1),) if jb is not None else ())  # type: ignore[union-attr]
        consumed = set(range(i, start)) | {ja} | ({ja - 1, jb} if jb is not None else set())
        if jumped_to_elsewhere(self._text, len(self.instructions), labels, names_label, consumed):
            return None
        then, _ = self._block(start, ja - 1 if jb is not None else ja)
        orelse, _ = self._block(ja + 1, jb) if jb is not None else ([], ja)
        self.tally.imported += 1
        return [If(cond, tuple(then), tuple(orelse), self.instructions[i][1])], (jb if jb is not None else ja) + 1

    def _structured(self, i: int, end: int) -> tuple[list[Stmt], int] | None:
        """`IF (cond) THEN` .. [`ELSE` ..] `ENDIF` and `FOR R[i]=a TO b` .. `ENDFOR` (B-83284EN,
        "IF ... THEN" and "FOR/ENDFOR"): an `if` on a condition `_condition` reads, a `for` (`_for`);
        any other block is kept native whole: its body runs zero, once or many times as a run-time
        value decides, and read as straight-line code one run would be planned as always happening."""
        text, where = self.instructions[i]
        test = _THEN.fullmatch(text)
        if test is None and not _FOR.fullmatch(text):
            return None
        close, depth, j, split = "ENDIF" if test else "ENDFOR", 0, i + 1, None
        while j < end and not (depth == 0 and self._text(j) in ("ENDIF", "ENDFOR")):
            t = self._text(j)
            depth += 1 if _THEN.fullmatch(t) or _FOR.fullmatch(t) else -1 if t in ("ENDIF", "ENDFOR") else 0
            split = j if test and depth == 0 and t == "ELSE" else split
            j += 1
        if j >= end or self._text(j) != close:
            return None  # not closed before the routine ends: read line by line
        cond = self._condition(test.group(1)) if test else None
        counted = self._for(i, j) if test is None else None
        if counted is not None:
            return counted
        if cond is not None:
            then, _ = self._block(i + 1, split if split is not None else j)
            orelse, _ = self._block(split + 1, j) if split is not None else ([], j)
            self.tally.imported += 1
            return [If(cond, tuple(then), tuple(orelse), where)], j + 1
        why = (f"inside `{text}` at line {where.line}, a block whose body runs as a value known only at run time "
               "decides (zero, once or many times); the block is kept native whole")
        return [self.tally.keep(self._text(k) + " ;", self.instructions[k][1], why)
                for k in range(i, j + 1) if self._text(k) and not self._text(k).startswith("!")], j + 1

    def _timed_wait(self, i: int, end: int) -> tuple[list[Stmt], int] | None:
        """The backend's wait with a timeout (fanuc_text.timed_wait), after `$WAITTMOUT`."""
        found = timed_wait(self._text, i, end) if self.timeout is not None else None
        if found is None:
            return None
        self.tally.imported += 1
        return [WaitIn(found[0], self.timeout, self.instructions[i][1])], found[1]

    def _simple(self, text: str, where: Where) -> Stmt | None:
        if text.startswith(("J ", "L ", "C ")):
            return None  # a move this reader could not read (`_motion`)
        stmt = match_simple(text, _SIMPLE, where) or (Stop(where) if text == "ABORT" else None)
        cond = self._condition(text[4:].strip()) if stmt is None and text.startswith("WAIT") else None
        return stmt or (WaitIn(cond, None, where) if cond is not None else None)

    def _motion(self, text: str, where: Where) -> tuple[Move, list[Stmt]] | None:
        """The move of a motion line and the options kept native after it (W517), or None."""
        circ = _CIRC.match(text)
        lin = None if circ else _MOTION.match(text)
        if circ:
            kind, points, speed, zone, rest = "circular", [int(circ.group(1)), int(circ.group(2))], *circ.group(3, 4, 5)
        elif lin:
            kind = "joint" if lin.group(1).upper() == "J" else "linear"
            point = int(lin.group(3)) if lin.group(2).upper() == "P" else self._register_point(int(lin.group(3)))
            if point is None:
                return None
            points, speed, zone, rest = [point], *lin.group(4, 5, 6)
        else:
            return None
        selected = self._selection(points, where)
        if selected is None:
            return None
        decls = [self.positions.get(p) for p in points]
        if kind != "joint":  # a point stored in joint form: the move goes to its TCP pose
            tcps = [self._tcp_of(p, where, selected["UTOOL"]) for p in points]
            decls = [t if isinstance(t, Target) else d for t, d in zip(tcps, decls)]
            if any(isinstance(t, str) for t in tcps):
                return None
        options = motion_options(rest)
        if options is None or any(d is None for d in decls):
            return None
        acc, offset_of, kept = options
        offset, in_tool = offset_of or (None, False)
        if acc is not None and not 1 <= acc <= 100:
            return None  # rmot's joint acceleration share takes 1..100 %
        if acc is not None and acc != 100 and kind != "joint":
            # ACC overrides the motion's acceleration and deceleration, J, L or C alike (R-30iB
            # Operator's Manual, motion option "Acceleration override"); rmot's plan bounds a
            # linear move's joints by the same share (compiler/plan/move_chain.py)
            self.tally.warn(codes.ACCEL_SHARE_ON_PATH, f"ACC{acc} on a {kind} move is read as `accel {acc} %` "
                            "(the joint acceleration share); its TCP acceleration stays the default", where)
        shifts = {} if offset is None else self.values.offset(offset, self.offsets.get(offset))
        if shifts is None:
            return None
        exprs = [d.name for d in decls]  # type: ignore[union-attr]
        # Offset,PR[k] moves along the user frame (`shift`), Tool_Offset,PR[k] along the tool at the
        # target (`p * pose(..)`, as RelTool): R-30iB Operator's Manual, offset and tool offset instructions
        terms = ", ".join(f"{a}={mm(e)}" for a, e in sorted(shifts.items()))
        exprs = [e if not terms else f"{e} * pose({terms})" if in_tool else f"shift({e}, {terms})" for e in exprs]
        timing = tp_speed(kind, self.values.speed(speed).replace(" ", ""))
        if timing is None:
            return None
        cnt = re.fullmatch(r"(?i)CNT\s*(\d+)", zone)
        decl = decls[-1]
        assert decl is not None
        move = Move(kind, exprs[-1], decl.name, where, via=exprs[0] if kind == "circular" else None,
                    speed=timing[0], joint_pct=timing[1], time=timing[2],
                    zone=float(cnt.group(1)) * FanucBackend.CNT_MM if cnt else None,
                    tool=self._named("UTOOL", where, selected["UTOOL"]),
                    frame="base" if decl.name in {t.name for t in self.tcp.values()} else self._named("UFRAME", where,
                                                                                                    selected["UFRAME"]),
                    config=decl.config if kind == "joint" and decl.pose is not None else None,
                    pose=decl.pose, joints=decl.joints, joint_accel=float(acc) if acc is not None and acc != 100 else None)
        return move, [self._option(text, where) for text in kept]

    def _selection(self, points: list[int], where: Where) -> dict[str, int] | None:
        """The UFRAME and UTOOL numbers a move to `points` runs with: the program's selection, or
        its caller's (fanuc_text.caller_selection; W545 at the first move that takes it); None,
        the reason in `values.unread`, where the selection is known only at run time."""
        chosen = [self._text(-1 - n) for n in self.state.values() if n < 0]
        if chosen:
            self.values.unread = f"the frame or tool here depends on `{chosen[0]}`: which one is known only at run time"
            return None
        selected = caller_selection(self.state, [self.taught.get(p) for p in points], self.inherited)
        if isinstance(selected, str):
            self.values.unread = selected
            return None
        taken = {k: selected[k] for k, n in self.state.items() if n == CALLERS}
        if taken and not self.inherited:  # once per program
            self.tally.warn(codes.CALLERS_SELECTION_READ, f"the program selects no {' or '.join(k + '_NUM' for k in taken)} "
                            "before this move: read in the numbers its position was taught in ("
                            + ", ".join(f"{'UT' if k == 'UTOOL' else 'UF'} {n}" for k, n in taken.items())
                            + "), which the caller must select", where)
        self.inherited.update(taken)
        return selected

    # ---------------------------------------------------------------- a position register as a target

    def _register_point(self, n: int) -> int | None:
        """The position key of a move to PR[n] at its saved value (a target `pr<n>` or its comment's name)."""
        saved, key = self.values.position(n), -1_000_000 - n
        if saved is not None and key not in self.positions:
            name = rmot_name(saved.comment.replace(" ", "_") or f"pr{n}")
            name = f"{name}_pr{n}" if any(t.name == name for t in self.positions.values()) else name
            self.positions[key] = Target(name, tp_pose(saved.xyzwpr) if saved.xyzwpr else None, saved.joints,
                                         tp_branch(saved.config or ""), saved.where)
        return None if saved is None else key

    def _tcp_of(self, n: int, where: Where, tool_no: int) -> Target | str | None:
        """P[n] of a linear or circular move where it is stored in joint form: its TCP pose in the
        robot's base, a target `<name>_tcp` of its own (the cell arm's forward kinematics times the
        active tool's TCP: a joint-form position is no frame's, R-30iB Operator's Manual, position
        data "joint coordinates"), or why the move stays native; None where P[n] is Cartesian."""
        decl = self.positions.get(n)
        if decl is None or decl.pose is not None or decl.joints is None:
            return None
        tool = self._named("UTOOL", where, tool_no)
        if (decl.name, tool) not in self.tcp:
            pose = self.pulse_pose(decl.joints, tool) if self.pulse_pose is not None else None
            if pose is None:
                return (f"{decl.name} is stored in joint form: a linear or circular move to it goes to its TCP pose, "
                        f"which the arm's forward kinematics and the program's tool give (`--cell` with the robot "
                        f"and a tool named `{tool}`)")
            name = f"{decl.name}_tcp" + (f"_{tool}" if any(k[0] == decl.name for k in self.tcp) else "")
            self.tcp[(decl.name, tool)] = Target(name, pose, None, None, decl.where)
            self.positions[-(len(self.positions) + 1)] = self.tcp[(decl.name, tool)]
        return self.tcp[(decl.name, tool)]

    def _option(self, text: str, where: Where) -> Stmt:
        """A motion option kept after its move: an action (`DO[n]=ON`, `CALL p`) read as its
        statement, else kept (fanuc_text.kept_option); W517 says the option was the move's."""
        action = re.fullmatch(r"(?i)(?:TB|TA|DB)\s+[\d.]+\s*(?:sec|mm)\s*,\s*(.+)", text)
        stmt = match_simple(action.group(1).strip(), _SIMPLE, where) if action else None
        kept = kept_option(text) if stmt is None else ""
        self.tally.warn(codes.MOTION_OPTION_KEPT, f"the move's option `{text[:50]}` is kept after the move"
                        + (" as a comment (a TP motion option cannot stand on its own line)" if kept[:1] == "!" else "")
                        + (" (an action timed before or after arrival runs once the move ends)" if action else ""), where)
        if stmt is not None:
            return stmt
        self.tally.native += 1
        return Native("fanuc", kept, where)

    def _inline_body(self, name: str) -> tuple[Stmt, ...] | None:
        """The body of program `name` read with this program's loop counters and offset
        registers, when it moves a target by one of them (else None: it is called)."""
        source = self.programs.get(name.upper())
        offsets = [rf"Offset,PR\[{k}\]" for k in self.offsets]  # a program that moves by one
        if source is None or not self.loop_vars or not reaches(
                self.programs, name, lambda text: any(re.search(p, text) for p in offsets), r"CALL\s+(\w+)"):
            return None
        callee = _Ls(source[0], source[1], self.labels, self.programs, controller=self.controller)
        callee.offsets, callee.loop_vars = self.offsets, self.loop_vars
        callee.state = dict(self.state)
        callee.tools, callee.frames = self.tools, self.frames
        callee.read()
        self.positions.update({-(len(self.positions) + k + 1): t for k, t in enumerate(callee.positions.values())})
        self.inlined.add(name.upper())
        self.inlined |= callee.inlined
        return callee.routine.body


def read_fanuc(path: str, text: str, labels: dict[str, dict[int, str]] | None = None,
               programs: dict[str, tuple[str, str]] | None = None, pulse_pose: PulsePose | None = None,
               controller: Controller | None = None) -> _Ls:
    """Read one TP program; raises ImportError_ (E510) when it is not one. `labels`: tool and
    frame names by number, from all the program's files; `programs`: those files by program
    name (a program called inside a loop that moves its targets is inlined at the call);
    `controller`: the registers and frames of the backup's .VA files given (fanuc_va)."""
    not_vars: frozenset[tuple[str, int]] = frozenset()
    for attempt in range(4):  # a native line using a register read as a variable: read it again without
        ls = _Ls(path, text, labels or {"UTOOL": {}, "UFRAME": {}}, programs, pulse_pose, not_vars, controller)
        ls.read()
        assert ls.regs is not None
        touched = ls.regs.used_natively(ls.routine.body)
        if not touched:
            break
        # after three tries, none at all: what is read only shrinks as more are excluded
        not_vars |= touched if attempt < 2 else frozenset(ls.regs.vars)
    return ls
