"""Read Yaskawa INFORM jobs (`.JBI`) back into a neutral Document.

Conventions are the INFORM backend's, read in reverse (Yaskawa DX100/YRC1000 INFORM manual,
156191-1CD): `/JOB`, `//NAME`, `//POS` with `///TOOL n`, `///POSTYPE ROBOT|USER` (`///USER n`),
`///RECTAN`, `///RCONF l,m,n,..` then `Cnnnnn=X,Y,Z,Rx,Ry,Rz` (mm, deg, R = Rz·Ry·Rx); RCONF m
0 elbow up / 1 down, n 0 front / 1 rear (the backend's `rconf`; l is Yaskawa's own flip on R
and is not the rmot wrist, so the wrist stays free: the planner takes the nearest); `//INST`
`MOVJ C VJ=% PL=n`, `MOVL C V=mm/s PL=n`, `MOVC` start, via, end `FPT` (the start is where the
robot stands), PL 0..4 = 0 / 12.5 / 25 / 50 / 100 mm (the backend's levels); `DOUT OT#(n)
ON|OFF`, `PULSE OT#(n) T=`, `AOUT AO#(n) v`, `TIMER T=`, `WAIT IN#(n)=.. [T=]` (with the
backend's JUMP/MSG/PAUSE: `timeout`), `JUMP *La IF IN#(n)=..` .. `*La` as `if`, `CALL JOB:`,
the tool named by the `'TOOL n = name` comment. Position variables (`P00100=` in //POS, `MOVJ
P100`) are read as the C positions are. Pulse positions (`///PULSE`, or any position before a
`///RECTAN`) are encoder counts: with the arm's pulses per degree (`rmot import
--pulses-per-degree S,L,U,R,B,T`, the controller's own values) they are read as joint targets,
degrees = pulses / scale (the ROS-Industrial motoman_driver's Ros_CtrlGroup_ConvertToRosPos,
radians = pulses / pulses-per-radian with no offset: 0 pulses is the axis's zero; the job holds
command positions, which the controller already corrects for axis coupling, CtrlGroup.c
Ros_CtrlGroup_GetFBPulsePos); a MOVL or MOVC to one goes to its TCP pose where the CLI hands in
the cell arm's forward kinematics and tools (`pulse_pose`), else stays native; without the
scales their moves stay native, but for a position with every axis at 0 pulses (a generator's
home), which is every axis at its zero whatever the scales.
"""

from __future__ import annotations

import math
import re
from dataclasses import replace

from rmot.backends.inform_text import PL_DISTANCES_MM
from rmot.backends.readers import axes_slots, codes
from rmot.backends.readers.fanuc_text import group_test
from rmot.backends.readers.common import (
    Tally, counter_alone, label_arms, label_loop, match_simple, reaches, rmot_name, same_pose,
)
from rmot.backends.readers.jump_spans import keep_jumped_spans
from rmot.backends.readers.jumps import Jump, jump_chain, jumped_to_elsewhere
from rmot.backends.readers.position_records import inform_record, native_positions
from rmot.backends.readers.model import (
    Cond, For, FrameData, If, Move, Native, PulsePose, Routine, Stmt, Stop, Target, ToolData, WaitIn, Where,
)
from rmot.backends.readers.rapid import mm
from rmot.lang import ir

__all__ = ["read_inform", "PL_MM", "pulse_scales"]

_JUMP = re.compile(r"JUMP \*(L\w+)")
_NATIVE_JUMP = re.compile(r"\bJUMP\s+\*(\w+)")  # a jump to a label kept native (JUMP JOB: is a call)


def _label_of(text: str) -> str | None:
    """The label of a `*NAME` line."""
    m = re.fullmatch(r"\*(\w+)", text.strip())
    return m.group(1) if m else None


# INFORM instructions (the forms backends/inform.py writes): outputs, pulses, analog outputs,
# timers, input waits, job calls
_SIMPLE = (
    ("out", re.compile(r"DOUT OT#\((\d+)\) (ON|OFF)")),
    ("pulse", re.compile(r"PULSE OT#\((\d+)\) T=([\d.]+)")),
    ("aout", re.compile(r"AOUT AO#\((\d+)\) (-?[\d.]+)")),
    ("wait", re.compile(r"TIMER T=([\d.]+)")),
    ("wait_in", re.compile(r"WAIT IN#\((\d+)\)=(ON|OFF)")),
    ("wait_out", re.compile(r"WAIT OT#\((\d+)\)=(ON|OFF)")),  # the general output's state
    ("call_renamed", re.compile(r"CALL JOB:(\w+)")),
)

# the remark the backend writes where the program attaches or detaches a part (INFORM selects
# loads only as tool files: backends/inform.py, W460): the tool and parts' mass
_PAYLOAD_REMARK = re.compile(r"'(?:attach|detach) \w+: payload \d+(?:\.\d+)? kg")
PL_MM = PL_DISTANCES_MM  # the PL levels the backend writes (one table: backends/inform_text.py)


class _Job:
    def __init__(self, path: str, text: str, jobs: dict[str, tuple[str, str]] | None = None,
                 pulses_per_degree: tuple[float, ...] | None = None, pulse_pose: PulsePose | None = None) -> None:
        self.tally = Tally(path, text, "inform")
        self.pulses_per_degree = pulses_per_degree  # the arm's scales, S, L, U, R, B, T (None: not given)
        self.pulse_pose = pulse_pose  # (joints deg, tool name) -> the TCP pose in the base (the cell's arm)
        self.jobs = jobs or {}  # the import's jobs by name (a job called in a shifting loop is inlined)
        self.inlined: set[str] = set()
        self.var_names: dict[str, str] = {}  # `'D050 = row`: the loop counters' names
        self.counters: dict[str, str] = {}  # D variable -> the rmot loop variable, inside its loop
        self.shifts: dict[str, dict[str, str]] = {}  # P variable -> axis -> offset expression (mm)
        self.shift: str | None = None  # the P variable between SFTON and SFTOF
        self.path = path
        self.raw = text.split("\n")
        self.name = ""
        self.positions: dict[str, Target] = {}
        self.pulse_positions: dict[str, str] = {}  # `///PULSE` positions not read: why (encoder counts of the arm's axes)
        self.base_positions: dict[str, tuple[tuple[float, ...], bool]] = {}  # BCn, ECn: values, in pulses (readers/axes_slots.py)
        self.position_tool: dict[str, int] = {}
        self.station_in_group = False  # `///GROUP1 RB1,ST1`: the station moves in the robot's own moves
        self.position_user: dict[str, int | None] = {}
        self.tool_names: dict[int, str] = {}
        self.tools: dict[int, ToolData] = {}
        self.frames: dict[int, FrameData] = {}
        self.inst: list[tuple[str, Where]] = []
        self.routine = Routine("", (), (), Where(path, 1))
        # each robot position's data as //POS gives it: tool, POSTYPE, user frame, RCONF, values, line
        self.raw_positions: dict[str, tuple[int, str, int | None, str, str, int]] = {}
        self.records: tuple[Native, ...] = ()  # those its native lines move to (position_records)

    def read(self) -> None:
        first = next(((n, ln) for n, ln in enumerate(self.raw, 1) if ln.strip()), (1, ""))
        if first[1].strip() != "/JOB":
            raise self.tally.fail("an INFORM job must start with `/JOB`", Where(self.path, first[0]))
        # a position is Cartesian only after `///RECTAN` ("Cartesian data is defined during and
        # after this pseudo instruction", DX100 manual 4.1): before it, or after `///PULSE` or
        # `///ANGLE`, its numbers are not mm (a job written without either holds pulse counts)
        section, conf, tool, user, rectan, postype = "", "0,0,0", 0, None, False, "ROBOT"
        for n, line in enumerate(self.raw, 1):
            s = line.strip()
            if s.startswith("//NAME"):
                self.name = s.split()[1] if len(s.split()) > 1 else "JOB"
            elif s in ("//POS", "//INST") or s.startswith("//"):
                section = s.split()[0] if s.startswith("//") and not s.startswith("///") else section
            if s.startswith("///"):
                key, _, rest = s[3:].partition(" ")
                if key == "COMM" and rest.strip().upper() == self.name.upper():
                    self.name = rest.strip()  # the job's own name as its comment gives it (its case)
                conf = rest if key == "RCONF" else conf
                tool = int(rest) if key == "TOOL" and rest.isdigit() else tool
                postype = rest.strip() if key == "POSTYPE" else postype  # ROBOT, BASE (no base axis: the same), USER
                user = int(rest) if key == "USER" and rest.isdigit() else user
                rectan = key == "RECTAN" or (rectan and key not in ("PULSE", "ANGLE"))
                self.station_in_group |= key.startswith("GROUP") and bool(re.search(r"\bRB\d.*\bST\d|\bST\d.*\bRB\d", rest))
                continue
            if section == "//POS":
                raw = re.fullmatch(r"(C\d+)\s*=\s*(.*)", s)
                if raw:
                    self.raw_positions[_key(raw.group(1))] = (tool, "PULSE" if not rectan else postype,
                                                              user if postype == "USER" else None, conf, raw.group(2), n)
                self._position(s, n, conf, tool, user if postype == "USER" else None, not rectan)
            elif section == "//INST" and s and not s.startswith("//"):
                m = re.match(r"'\s*TOOL\s+(\d+)\s*=\s*(\w+)", s)
                if m:
                    self.tool_names[int(m.group(1))] = m.group(2)
                m = re.fullmatch(r"'(D\d+) = (\w+)", s)
                if m:
                    self.var_names[m.group(1)] = m.group(2)
                if (not s.startswith("'") or _PAYLOAD_REMARK.fullmatch(s)) and s not in ("NOP", "END"):
                    self.inst.append((_uncommented(s), Where(self.path, n, len(line) - len(line.lstrip()) + 1)))
        if not self.name:
            raise self.tally.fail("an INFORM job must name itself (`//NAME NAME`)", Where(self.path, first[0]))
        body, _ = self._block(0, len(self.inst))
        kept = keep_jumped_spans(tuple(body), self.tally, _NATIVE_JUMP, _label_of, self.inst,
                                 lambda t: t)
        self.records = tuple(self._record(f"C{n:05d}") for n in native_positions(kept, self.path, "inform")
                             if f"C{n:05d}" in self.raw_positions)
        self.routine = Routine(self.name, (), kept, Where(self.path, first[0]))

    def _record(self, key: str) -> Native:
        """The record of a position a native line moves to, its tool and user frame named as the
        job's moves name them (stub entries for the controller's)."""
        tool, postype, user, conf, values, line = self.raw_positions[key]
        where = Where(self.path, line)
        if user is not None and user not in self.frames:
            self.frames[user] = FrameData(f"user{user}", ir.Pose(), where, f"user frame {user}", user)
        return inform_record(key, self._tool(tool, where), postype, self.frames[user].name if user is not None else "",
                             conf.strip(), values.strip(), where)

    def _position(self, s: str, n: int, conf: str, tool: int, user: int | None, pulse: bool) -> None:
        if axes_slots.inform_base_position(self.base_positions, s, pulse):
            return
        m = re.fullmatch(r"([CP]\d+)\s*=\s*(.*)", s)
        if m is not None and pulse:
            self._pulse_position(_key(m.group(1)), m.group(2), n, tool)
        if m is None or pulse:
            return
        try:
            v = [float(x) for x in m.group(2).split(",")]
        except ValueError:
            v = []
        if len(v) < 6 or not all(math.isfinite(x) for x in v):
            self.tally.comments.append(Native("inform", s, Where(self.path, n)))  # kept, so `rmot diff` sees a touch-up
            return
        pose = ir.Pose.from_xyz_rpy(v[0] / 1000, v[1] / 1000, v[2] / 1000, *(math.radians(a) for a in v[3:6]))
        q = tuple(0.0 if abs(c) < 1e-12 else c for c in pose.quaternion)  # cos(90 deg) noise
        bits = conf.split(",")
        branch = None
        if len(bits) >= 3 and bits[1].strip() in "01" and bits[2].strip() in "01":
            branch = ir.Config(ir.Shoulder.FRONT if bits[2].strip() == "0" else ir.Shoulder.BACK,
                               ir.Elbow.UP if bits[1].strip() == "0" else ir.Elbow.DOWN, None)
        key = _key(m.group(1))
        name = rmot_name(f"{self.name.lower()}_{key.lower()}")  # a job `001-R1-HOME`: an rmot name
        self.positions[key] = Target(name, ir.Pose(pose.position, q), None, branch,  # type: ignore[arg-type]
                                            Where(self.path, n), ",".join(b.strip() for b in bits))
        self.position_tool[key] = tool
        self.position_user[key] = user

    def _pulse_position(self, key: str, values: str, n: int, tool: int) -> None:
        """A pulse position: a joint target where the arm's pulses per degree are given and
        its count is theirs; else the reason its moves stay native."""
        counts = [int(x) for x in values.split(",") if re.fullmatch(r"\s*-?\d+\s*", x)]
        whole = len(counts) == len(values.split(","))
        # every axis at 0 pulses is every axis at its zero, whatever the scales (a generator's home)
        scales = self.pulses_per_degree or ((1.0,) * len(counts) if whole and counts and not any(counts) else None)
        if scales is None or not whole or len(counts) != len(scales):
            # its data is kept as a comment (nothing lost; `rmot diff` names a touch-up of it)
            self.tally.comments.append(Native("inform", f"{key}={values}", Where(self.path, n)))
        if scales is None:
            self.pulse_positions[key] = ("is a pulse position (///PULSE, or no ///RECTAN before it): encoder counts "
                                         "whose per-axis scales are the arm's controller's; pass them as `rmot import "
                                         "--pulses-per-degree S,L,U,R,B,T` (its pulses per degree) to read it")
        elif not whole or len(counts) != len(scales):
            self.pulse_positions[key] = (f"is a pulse position of {len(values.split(','))} values, not the "
                                         f"{len(scales)} whole pulse counts --pulses-per-degree gives scales for")
        else:
            joints = tuple(c / k for c, k in zip(counts, scales))
            self.positions[key] = Target(rmot_name(f"{self.name.lower()}_{key.lower()}"), None, joints, None, Where(self.path, n))
            self.position_tool[key] = tool
            self.position_user[key] = None

    # ---------------------------------------------------------------- instructions

    def _block(self, i: int, end: int) -> tuple[list[Stmt], int]:
        where = self.inst[min(i, len(self.inst) - 1)][1] if self.inst else Where(self.path, 1)
        return self.tally.nested(where, lambda: self._block_body(i, end))

    def _block_body(self, i: int, end: int) -> tuple[list[Stmt], int]:
        body: list[Stmt] = []
        while i < end:
            stmts, i = self._statement(i, end)
            body += stmts
        return body, i

    def _text(self, i: int) -> str:
        return self.inst[i][0] if i < len(self.inst) else ""

    def _statement(self, i: int, end: int) -> tuple[list[Stmt], int]:
        text, where = self.inst[i]
        shifting = self._shift_data(i)
        if shifting is not None:
            return [], shifting
        call = re.fullmatch(r"CALL JOB:(\w+)", text)
        inlined = self._inline_body(call.group(1)) if call else None
        if inlined is not None:
            self.tally.imported += 1
            return list(inlined), i + 1
        if _PAYLOAD_REMARK.fullmatch(text):  # INFORM has no load instruction: the backend's remark
            return [self.tally.keep(text, where, "a payload remark (`rmot import --cell` reads an attach or detach)")], i + 1
        if _label_of(text) is not None and self._stop_label(_label_of(text) or ""):
            return [], i + 1  # the label the backend's stop jumps to, before END: nothing runs there
        for pattern in (self._stop, self._loop, self._arc, self._timed_wait, self._if):
            found = pattern(i, end)
            if found is not None:
                self.tally.imported += 1
                return found
        stmt = self._simple(text, where)
        if stmt is None:
            named = sorted({_key(r) for r in re.findall(r"\b[CP]\d+\b", text)})
            pulses = [k for k in named if k in self.pulse_positions]
            joints = [k for k in named if k in self.positions and self.positions[k].pose is None]
            why = (f"{pulses[0]} {self.pulse_positions[pulses[0]]}" if pulses else
                   f"{joints[0]} is a pulse position, read as joints: a linear or circular move to it goes to its TCP "
                   "pose, which the arm's forward kinematics and the job's tool give (`--cell` with the robot and a "
                   "tool of that name)" if joints and not text.startswith("MOVJ") else
                   axes_slots.why_native(text) or _why_native(text))
            if why == "no rmot form" and re.match(r"S?MOVC\b", text):
                why = ("an arc is read where its first MOVC is where the move before it ended (no call, jump or "
                       "label between) and its three MOVC stand alone or the last has FPT")
            return [self.tally.keep(text, where, why)], i + 1
        self.tally.imported += 1
        return [stmt], i + 1

    def _loop(self, i: int, end: int) -> tuple[list[Stmt], int] | None:
        """`SET Dv a`, `*Lk`, body, `INC Dv`, `JUMP *Lk IF Dv<=b` (the backend's counted loop)."""
        found = label_loop(self._text, i, end, r"SET (D\d+) (\d+)", r"\*(L\w+)",
                           lambda v, k: rf"JUMP \*{k} IF {v}<=(\d+)", lambda v: f"INC {v}")
        if found is None or jumped_to_elsewhere(self._text, len(self.inst), (_label_of(self._text(i + 1)) or "",), _names_label, {i + 1, found[3]}):
            return None
        if not counter_alone(self._text, len(self.inst), i, found[3], rf"\b{found[0]}\b", (rf"SET D\d+ {found[0]}",),
                             (rf"SET {found[0]} \d+", f"INC {found[0]}", rf"JUMP \*L\w+ IF {found[0]}<=\d+")):
            return None  # the counter written in the body, read after the loop, or a jump into it
        var, first, last, j = found
        name = rmot_name(self.var_names.get(var, var.lower()))
        self.counters[var] = name
        body, _ = self._block(i + 2, j - 1)
        del self.counters[var]
        return [For(name, first, last + 1, tuple(body), self.inst[i][1])], j + 1

    def _shift_data(self, i: int) -> int | None:
        """A shift being built or switched: `SET Dt Dv`, `MUL Dt m`, `SETE Pn (e) Dt` (element e
        of Pn, X/Y/Z in µm, = the counter × m µm), `SFTON Pn RF`, `SFTOF`: the next line, or None."""
        text = self._text(i)
        m = re.fullmatch(r"SET (D\d+) (D\d+)", text)
        mul = re.fullmatch(rf"MUL {m.group(1)} (-?\d+)", self._text(i + 1)) if m else None
        sete = re.fullmatch(rf"SETE (P\d+) \(([123])\) {m.group(1)}", self._text(i + 2)) if m and mul else None
        if m and mul and sete and m.group(2) in self.counters:
            offset = f"{self.counters[m.group(2)]} * {int(mul.group(1)) / 1000:g}"  # µm per step -> mm
            self.shifts.setdefault(sete.group(1), {})["xyz"[int(sete.group(2)) - 1]] = offset
            return i + 3
        on = re.fullmatch(r"SFTON (P\d+) RF", text)
        if on and on.group(1) in self.shifts:
            self.shift = on.group(1)
            return i + 1
        if text == "SFTOF" and self.shift is not None:
            self.shift = None
            return i + 1
        return None

    def _shifted(self, name: str) -> str:
        """A target moved by the active shift (robot frame: rmot's `shift` in the base)."""
        if self.shift is None:
            return name
        terms = ", ".join(f"{a}={mm(e)}" for a, e in sorted(self.shifts[self.shift].items()))
        return f"shift({name}, {terms})" if terms else name

    def _inline_body(self, name: str) -> tuple[Stmt, ...] | None:
        """The body of job `name` read with this job's loop counters and shifts, when it
        switches on one of them (else None: it is called)."""
        source = self.jobs.get(name.upper())
        shifted = [rf"(?m)^SFTON {p} RF" for p in self.shifts]  # a job that switches one on
        if source is None or not self.counters or not reaches(
                self.jobs, name, lambda text: any(re.search(p, text) for p in shifted), r"(?m)^CALL JOB:(\w+)"):
            return None
        callee = _Job(source[0], source[1], self.jobs, self.pulses_per_degree, self.pulse_pose)
        callee.counters, callee.shifts = self.counters, self.shifts
        callee.tools, callee.tool_names = self.tools, {**self.tool_names}
        callee.read()
        for key, target in callee.positions.items():
            self.positions[f"{callee.name}:{key}"] = target
        self.inlined.add(name.upper())
        self.inlined |= callee.inlined
        return callee.routine.body

    def _path_key(self, key: str) -> str:
        """The position a linear or circular move to `key` goes to: `key` itself, or for a pulse
        position whose TCP pose the cell's arm and the job's tool give, `key_TCP` (a pose target
        of its own, `<name>_tcp`); `key` where they do not (its move then stays native)."""
        decl = self.positions.get(key)
        if decl is None or decl.pose is not None or decl.joints is None or self.pulse_pose is None:
            return key
        if f"{key}_TCP" not in self.positions:
            tool = self.position_tool[key]
            pose = self.pulse_pose(decl.joints, self.tool_names.get(tool, f"tool{tool}"))
            if pose is None:
                return key
            self.positions[f"{key}_TCP"] = Target(f"{decl.name}_tcp", pose, None, None, decl.where)
            self.position_tool[f"{key}_TCP"], self.position_user[f"{key}_TCP"] = tool, None
        return f"{key}_TCP"

    def _move(self, kind: str, names: list[str], rest: str, where: Where, sync: bool = False, via_rest: str = "") -> Move | None:
        names = names if kind == "joint" else [self._path_key(n) for n in names]
        decls = [self.positions.get(n) for n in names]
        base, rest = axes_slots.inform_operands(self.base_positions, rest, sync, self.station_in_group)
        via_base = axes_slots.inform_operands(self.base_positions, via_rest, sync, self.station_in_group)[0] \
            if via_rest else None
        speed = re.search(r"\bV=([\d.]+)", rest)
        vj = re.search(r"\bVJ=([\d.]+)", rest)
        pl = re.search(r"\bPL=(\d)", rest)
        # ACC=/DEC=: acceleration and deceleration ratios, 20..100 % (YRC1000 INFORM manual, MOVJ,
        # MOVL and MOVC tags); rmot has one joint acceleration share, so both must be equal
        acc = re.search(r"\bACC=(\d+)\s+DEC=(\d+)\b", rest)
        extra = re.sub(r"\b(VJ?=[\d.]+|PL=\d|FPT|ACC=\d+\s+DEC=\d+|NWAIT)\b", "", rest).strip()

        if any(d is None or (kind != "joint" and d.pose is None) for d in decls) or extra or (vj is None) != (kind != "joint") or \
                (kind != "joint" and speed is None) or (pl and int(pl.group(1)) > 4):
            return None
        if acc is not None and (acc.group(1) != acc.group(2) or not 20 <= int(acc.group(1)) <= 100):
            return None
        if acc is not None and acc.group(1) != "100" and kind != "joint":  # ACC=/DEC= on MOVL, MOVC too
            self.tally.warn(codes.ACCEL_SHARE_ON_PATH, f"ACC={acc.group(1)} DEC={acc.group(2)} on a {kind} move is "
                            f"read as `accel {acc.group(1)} %` (the joint acceleration share); its TCP acceleration "
                            "stays the default", where)
        decl = decls[-1]
        assert decl is not None
        user = self.position_user[names[-1]]
        if re.search(r"\bNWAIT\b", rest):  # the next instructions run during the move
            self.tally.warn(codes.MOTION_OPTION_KEPT, "NWAIT is not read: the instructions after this move "
                            "run once it ends, not while it runs", where)
        if user is not None and not sync and user not in self.frames:  # the controller's user frame: a stub entry
            self.frames[user] = FrameData(f"user{user}", ir.Pose(), where, f"user frame {user}", user)
        return Move(kind, self._shifted(decl.name), decl.name, where,
                    via=self._shifted(decls[0].name) if kind == "circular" else None,  # type: ignore[union-attr]
                    speed=float(speed.group(1)) if speed and kind != "joint" else None,
                    joint_pct=float(vj.group(1)) if vj else None,
                    zone=PL_MM[int(pl.group(1))] if pl and int(pl.group(1)) > 0 else None,
                    tool=self._tool(self.position_tool[names[-1]], where), frame=axes_slots.inform_frame(user, sync),
                    config=decl.config if kind == "joint" else None, pose=decl.pose, joints=decl.joints,
                    joint_accel=float(acc.group(1)) if acc is not None and acc.group(1) != "100" else None,
                    slots=base[0] if base else (), slot_pulses=base[1] if base else (), via_slots=via_base[0] if via_base else ())

    def _tool(self, n: int, where: Where) -> str:
        if n not in self.tools:
            self.tools[n] = ToolData(self.tool_names.get(n, f"tool{n}"), ir.Pose(), 0.0, where, f"tool file entry {n}", n)
        return self.tools[n].name

    def _arc(self, i: int, end: int) -> tuple[list[Stmt], int] | None:
        """MOVC start, via, end FPT: a circular move from the start, where the move before it
        ended; right after an arc, MOVC via, end FPT (the arc before ended at the start). Three
        MOVC alone (no MOVC before or after them, as RoboDK's post writes an arc) are one arc
        without FPT (DX100 INFORM manual, MOVC: three points make the arc; FPT only separates
        continuous arcs). An arc whose start is not where the move before it ended (the robot
        first goes to the start) stays native."""
        chained = re.fullmatch(r"S?MOVC\s+[CP]\d+.*\bFPT\b.*", self._text(i - 1)) is not None if i else False
        n = 2 if chained else 3
        texts = [self._text(k) for k in range(i, min(i + n, end))]
        ms = [re.fullmatch(r"(S?)MOVC\s+([CP]\d+)\s*(.*)", t) for t in texts]
        alone = not any(re.match(r"S?MOVC\b", self._text(k)) for k in (i - 1, i + n)) and not any("FPT" in t for t in texts)
        if len(ms) < n or not all(ms) or not (alone or "FPT" in texts[-1]) or any("FPT" in t for t in texts[:-1]) or \
                len({m.group(1) for m in ms}) != 1 or not (chained or self._stands_at(i, _key(ms[0].group(2)))):  # type: ignore[union-attr]
            return None
        move = self._move("circular", [_key(ms[-2].group(2)), _key(ms[-1].group(2))], ms[-1].group(3),  # type: ignore[union-attr]
                          self.inst[i + n - 2][1], ms[-1].group(1) == "S", ms[-2].group(3))  # type: ignore[union-attr]
        return ([replace(move, source="\n".join(texts))], i + n) if move else None

    def _stands_at(self, i: int, key: str) -> bool:
        """Whether the last move before instruction `i` (over outputs, waits and timers) ended at
        position `key`: the same position, or one with the same pose, tool and user frame."""
        k = i - 1
        while k >= 0 and re.match(r"(DOUT|PULSE|AOUT|TIMER|WAIT)\b|'", self._text(k)):
            k -= 1
        m = re.fullmatch(r"S?MOV[JL]\s+([CP]\d+).*", self._text(k)) if k >= 0 else None
        last = _key(m.group(1)) if m else ""
        a, b = self.positions.get(last), self.positions.get(key)
        return last == key or (a is not None and b is not None and a.pose is not None and b.pose is not None and
                               self.position_tool.get(last) == self.position_tool.get(key) and
                               self.position_user.get(last) == self.position_user.get(key) and same_pose(a.pose, b.pose))

    def _timed_wait(self, i: int, end: int) -> tuple[list[Stmt], int] | None:
        m = re.fullmatch(r"WAIT IN#\((\d+)\)=(ON|OFF) T=([\d.]+)", self._text(i))
        jump = re.fullmatch(rf"JUMP \*(L\w+) IF IN#\({m.group(1)}\)={m.group(2)}", self._text(i + 1)) if m else None
        if m is None or jump is None or not self._text(i + 2).startswith("MSG") or self._text(i + 3) != "PAUSE" \
                or self._text(i + 4) != f"*{jump.group(1)}":
            return None
        return [WaitIn(Cond(int(m.group(1)), m.group(2) == "ON"), float(m.group(3)), self.inst[i][1])], i + 5

    def _stop(self, i: int, end: int) -> tuple[list[Stmt], int] | None:
        """The backend's `stop`: `MSG "STOP"`, `PAUSE`, in the main job a `JUMP *Lk` to the label
        before END (a restart ends the job); in a called job those two alone (W432)."""
        if self._text(i) != 'MSG "STOP"' or self._text(i + 1) != "PAUSE":
            return None
        jump = re.fullmatch(r"JUMP \*(\w+)", self._text(i + 2))
        ends = jump is not None and self._stop_label(jump.group(1))
        return [Stop(self.inst[i][1])], i + (3 if ends else 2)

    def _stop_label(self, label: str) -> bool:
        """Whether `*label` is the job's last line and every jump to it follows the backend's
        `MSG "STOP"`, `PAUSE` (so reading those as `stop` leaves the label nothing to do)."""
        jumps = [k for k, (t, _) in enumerate(self.inst) if _names_label(t, label) and t != f"*{label}"]
        return self._text(len(self.inst) - 1) == f"*{label}" and bool(jumps) and all(
            re.fullmatch(rf"JUMP \*{label}", self._text(k)) and self._text(k - 1) == "PAUSE"
            and self._text(k - 2) == 'MSG "STOP"' for k in jumps)

    def _jump_at(self, i: int) -> Jump | None:
        """`JUMP *La IF IN#(n)=X` (or an output, `OT#(n)`); or a group input read into a byte and
        tested, `IN Bt IG#(n)`, `JUMP *La IF Bt<op>v`: its label, when it is taken and when not."""
        m = re.fullmatch(r"JUMP \*(L\w+) IF (IN|OT)#\((\d+)\)=(ON|OFF)", self._text(i))
        if m is not None:
            taken = Cond(int(m.group(3)), m.group(4) == "ON", m.group(2) == "OT")
            return m.group(1), taken, taken.negated(), i + 1
        read = re.fullmatch(r"IN (B\d+) IG#\((\d+)\)", self._text(i))
        test = re.fullmatch(rf"JUMP \*(L\w+) IF {read.group(1)}(<>|<=|>=|=|<|>)(\d+)", self._text(i + 1)) if read else None
        if read is None or test is None:
            return None
        # INFORM compares with TP's operators (=, <>, <, >, <=, >=): the TP reader's group test
        compare = f"GI[{read.group(2)}]{test.group(2)}{test.group(3)}"
        return test.group(1), group_test(compare), group_test(compare, negate=True), i + 2  # type: ignore[return-value]

    def _if(self, i: int, end: int) -> tuple[list[Stmt], int] | None:
        """An if as the backend writes it: conditional jumps (`_jump_at`) to `*La`, all of them
        (`and`) or a chain to `*Ls` and one to `*La` then `*Ls` (`or`, readers/jumps.py), then,
        [`JUMP *Lb`, `*La`, else, `*Lb`] (then runs when no jump to `*La` is taken)."""
        chain = jump_chain(self._jump_at, self._text, i, lambda n: f"*{n}")
        if chain is None:
            return None
        label, cond, start, more = chain
        arms = label_arms(self._text, start - 1, end, f"*{label}", _JUMP, lambda n: f"*{n}")
        if arms is None:
            return None
        ja, jb = arms
        labels = (label, *more) + ((_JUMP.fullmatch(self._text(ja - 1)).group(1),) if jb is not None else ())  # type: ignore[union-attr]
        consumed = set(range(i, start)) | {ja} | ({ja - 1, jb} if jb is not None else set())
        if jumped_to_elsewhere(self._text, len(self.inst), labels, _names_label, consumed):
            return None
        then, _ = self._block(start, ja - 1 if jb is not None else ja)
        orelse, _ = self._block(ja + 1, jb) if jb is not None else ([], ja)
        return [If(cond, tuple(then), tuple(orelse), self.inst[i][1])], (jb if jb is not None else ja) + 1

    def _simple(self, text: str, where: Where) -> Stmt | None:
        m = re.fullmatch(r"(MOVJ|S?MOVL)\s+([CP]\d+)\s*(.*)", text)
        if m:
            return self._move("joint" if m.group(1) == "MOVJ" else "linear", [_key(m.group(2))], m.group(3), where,
                              m.group(1) == "SMOVL")
        return match_simple(text, _SIMPLE, where)


def _names_label(text: str, label: str) -> bool:
    """Whether an instruction is label `*label` or jumps to it."""
    return re.search(rf"\*{label}\b", text) is not None


def _key(ref: str) -> str:
    """A position's key: `C00012` / `P00100` as //POS writes it, whichever digits an
    instruction names it with (`MOVJ P100`: the position variable P100, DX100/YRC1000 INFORM
    manual, "position variable P")."""
    return f"{ref[0]}{int(ref[1:]):05d}"


# variables of a job (DX100/YRC1000 INFORM manual, "variables": byte, integer, double, real,
# position; L local): a value the job only has at run time
_VARIABLE = r"L?[BIDRP]\d+"


def _why_native(text: str) -> str:
    """Why an INFORM line with no rmot form stays native, as precisely as the line says."""
    indirect = re.search(rf"\bIN#\(({_VARIABLE})\)", text)
    timer = re.fullmatch(rf"TIMER T=({_VARIABLE})", text)
    if re.match(r"IMOV\b", text):
        return ("IMOV moves by an increment from wherever the robot stands (its position variable's value at "
                "run time): rmot's moves go to targets the compiler knows")
    if indirect:
        return (f"the input's number is variable {indirect.group(1)}'s value at run time: rmot's `in[n]` "
                "names its input in the program")
    if timer:
        return f"the time is variable {timer.group(1)}'s value at run time: rmot's `wait T` is a number the compiler knows"
    level = re.search(r"\bPL=([5-8])\b", text) if re.match(r"S?MOV[JLC]\b", text) else None
    if level:
        return (f"PL={level.group(1)}: rmot knows the distances of positioning levels 0..4 only (the factory "
                "0 / 12.5 / 25 / 50 / 100 mm of parameters S1CxG033-036, backends/inform_text.py)")
    if text == "PAUSE":
        return ("PAUSE holds the job until the operator starts it again, and it runs on from there (YRC1000 "
                "INSTRUCTIONS, PAUSE): rmot's `stop` would end the task")
    if re.match(r"MOVJ EX\d+", text):
        return ("moves the station alone to its position variable EXn: rmot reads `move axes` back only from "
                "RAPID's MoveExtJ")
    return "no rmot form"


def _uncommented(line: str) -> str:
    """An instruction without the comment the pendant appends after `//` (`MOVL P106 V=150.0
    PL=0  //CUT PRE-SLIDE`: YRC1000 INFORM manual, the line comment of an instruction); a
    line with a quoted string keeps it all (`//` may be the string's)."""
    m = re.fullmatch(r"(.*?\S)\s+//.*", line)
    return m.group(1) if m and '"' not in line else line


def pulse_scales(text: str) -> tuple[float, ...] | str:
    """`--pulses-per-degree S,L,U,R,B,T`: the arm's encoder pulses per degree of each axis, as
    its controller's parameters give them (one finite, non-zero number per axis, 1 to 8 axes: an
    INFORM position holds at most 8, DX100/YRC1000 INFORM manual, //POS); else the error text."""
    bits = text.split(",")
    try:
        scales = tuple(float(b) for b in bits)
    except ValueError:
        return f"--pulses-per-degree takes numbers separated by commas (got `{text}`)"
    if not 1 <= len(scales) <= 8:
        return f"--pulses-per-degree takes one number per axis, 1 to 8 axes (got {len(scales)})"
    bad = [b.strip() for b, k in zip(bits, scales) if not math.isfinite(k) or k == 0.0]
    if bad:
        return f"--pulses-per-degree: `{bad[0]}` is not a finite, non-zero number of pulses per degree"
    return scales


def read_inform(path: str, text: str, jobs: dict[str, tuple[str, str]] | None = None,
                pulses_per_degree: tuple[float, ...] | None = None, pulse_pose: PulsePose | None = None) -> _Job:
    """Read one INFORM job; raises ImportError_ (E510) when it is not one. `jobs`: the import's
    files by job name (a job called inside a loop whose shift it switches on is inlined);
    `pulses_per_degree`: the arm's scales, to read pulse positions as joint targets; `pulse_pose`:
    their TCP poses (the cell's arm and tools), for linear and circular moves to them."""
    job = _Job(path, text, jobs, pulses_per_degree, pulse_pose)
    job.read()
    return job
