"""Fanuc TP backend (.ls ASCII programs, R-30iA/iB; loaded with the ASCII Upload option).

Conventions (Fanuc "R-30iB Controller Operator's Manual (Basic Operation)"):
  * positions in mm; orientation W, P, R in degrees, fixed axes X then Y then Z:
    R = Rz(R)·Ry(P)·Rx(W); joints J1..J6 in degrees (the controller's values; rmot's robot
    library already uses Fanuc's J2/J3 convention).
  * Cartesian positions carry `UF : n, UT : m, CONFIG : 'F|N U|D T|B, t4, t5, t6'`:
    N (no flip) when J5 < 0 and F when J5 > 0 on Fanuc's own J5 (the LR Mate's home with
    the tool down, J5 = -90 deg, shows 'N U T'); note rmot's branch calls J5 < 0 "flip"
    (rmot.compiler.robots.branches), so rmot FLIP -> 'N', NOFLIP -> 'F'. U = elbow up,
    D = down; T = wrist centre in front of J1 (toward), B = behind. t4..t6 are the turn
    numbers of J4, J5, J6 (as in Fanuc's RMI Turn4..Turn6): 0 for (-180, 180] deg, 1 for
    (180, 540], -1 for (-540, -180].
  * joint moves to joint targets use the joint representation (J1= ... deg);
    joint moves to pose targets use the Cartesian representation with the CONFIG above.
  * frames: UFRAME 0 is the robot's world (= base) frame. A tool or frame the cell gives a
    controller number (`number n`) is selected by that number (UTOOL_NUM/UFRAME_NUM) and
    never written, unless --write-frames: the header comments give the values it must hold.
    Every other named frame gets the smallest UFRAME 1, 2, ... and every other tool (the
    bare flange included) the smallest UTOOL no cell item is given, in order of first use;
    the main program writes those at its start through position registers PR[FRAME_PR + k]
    (`PR[i]=LPOS`, `PR[i,j]=value`, `UFRAME[n]=PR[i]`), overwriting them (W416 names each).
  * speeds: J moves in % of the maximum joint speed (integer 1..100), L/C moves in mm/sec
    (integer, at most MAX_TCP_MM_S = 2000); a `time` modifier is emitted exactly as `n.nnsec`.
    Other values are rounded or clamped to the nearest legal one (warning W402).
  * times: WAIT in steps of 0.01 s, PULSE in steps of 0.1 s (other values rounded, W412).
  * acceleration: TP's ACC is a % of the motion's own profile, not m/s^2 or a share of each
    axis's maximum: a non-default programmed acceleration is not expressed (W408 once per task).
  * payload: a .ls program can only select a payload schedule (PAYLOAD[i]) whose mass and
    centre of gravity live on the controller ($PLST_GRP1[i]): a tool with a mass warns W411
    once, giving the mass and rmot's centre of gravity (half way flange->TCP, base.tool_cog).
  * digital ports: DI[n] / DO[n] with n in DIGITAL_PORTS = 1..512 (the R-30iA/iB standard
    DI[1]-DI[512] / DO[1]-DO[512] logical range); E404 outside.
  * zones: FINE, else CNTn. CNT is not a radius (it scales the corner rounding with speed):
    rmot emits CNT = round(radius / CNT_MM) clamped to 1..100, the nearest faithful choice
    (warning W403 on every blended move).
  * I/O: DO[n]=ON/OFF, DO[n]=PULSE,t sec, AO[n]=value, WAIT t(sec), WAIT DI[n]=ON;
    with a timeout: $WAITTMOUT (1/100 s) then `WAIT ... TIMEOUT,LBL[k]`, the label aborting
    the program (rmot's timeout semantics: the program stops, see base.py). Runtime if: `IF DI[n]<>ON,JMP LBL[else]` ... `JMP LBL[end]`.
  * procs: each routine is its own program NAME_PROC.ls (TP program names are global on the
    controller, hence the prefix) called with CALL.
  * sync: TP has no barrier between controllers without the multi-arm option, so the k-th
    sync of a task is the I/O handshake of backends/handshake.py: `DO[o:sync]=ON` (odd k) or
    OFF (even k) then `WAIT DI[i:sync]=` the same level, o and i being the robot's
    `io out[o] = "sync"` / `io in[i] = "sync"` of the cell (r1's DO wired to r2's DI and
    back). Missing signals: error E409 at the sync; a sync in an if arm: error E405.
  * names: program names at most 36 characters (R-30iA and later), upper case, a letter
    first, letters, digits and '_'; comments are cut into pieces of at most 32 characters.
  * size: a program longer than MAX_INSTRUCTIONS instructions is split into programs
    NAME_PART1.. called from NAME (warning W406), keeping pendant loading and editing
    practical; TP itself numbers lines up to 9999.
"""

from __future__ import annotations

import math
import textwrap
from dataclasses import dataclass, field, replace
from typing import ClassVar

import numpy as np

from rmot.backends import codes
from rmot.backends.base import Backend, TaskContext, euler_zyx_deg, fmt, header_lines, position_mm
from rmot.backends.controller_data import NumberedData, frame_number, tool_number
from rmot.backends.names import NameRules, NameTable
from rmot.compiler import ir
from rmot.backends.safe_text import comment_safe, tp_io_comment
from rmot.lang.source import Span

__all__ = ["FanucBackend", "FANUC_RULES", "config_string", "turn_number"]

FANUC_RULES = NameRules(max_len=36, upper=True, reserved=frozenset({"MAIN"}), prefix="P")
COMMENT_MAX = 32


def turn_number(angle: float) -> int:
    """Fanuc turn number: 0 for (-180, 180] deg, 1 for (180, 540], -1 for (-540, -180]."""
    return math.ceil((angle - math.pi) / (2 * math.pi) - 1e-12)


def config_string(branch: ir.Config, q: np.ndarray) -> str:
    """'N U T, t4, t5, t6' from the planned branch and joints (see the module docstring)."""
    # Fanuc's F (flip) is J5 >= 0 and N (no flip) J5 < 0, on Fanuc's own J5: RoboDK's Fanuc
    # post (Fanuc_R30iA.py, "F means axis 5 >= 0, N means axis 5 < 0") and SwRI's tesseract
    # (tesseract_motion_planners/robot_config.h: J5 >= 0 -> F.., J5 < 0 -> N..) agree, as does
    # the usual 'N U T' of a tool-down pose with J5 = -90 deg. rmot's FLIP is J5 < 0 -> 'N'.
    flip = "N" if branch.wrist is ir.Wrist.FLIP else "F"
    up = "U" if branch.elbow is ir.Elbow.UP else "D"
    top = "T" if branch.shoulder is ir.Shoulder.FRONT else "B"
    turns = ", ".join(str(turn_number(q[i])) for i in (3, 4, 5))
    return f"{flip} {up} {top}, {turns}"


@dataclass
class _Program:
    """One .ls program being printed: its numbered positions and labels."""

    positions: list[str] = field(default_factory=list)
    labels: int = 0

    def label(self) -> int:
        self.labels += 1
        return self.labels


class _Frames:
    """UFRAME / UTOOL numbers of one task: the cell's `number n` where given, else the
    smallest number no cell tool/frame is given, in order of first use (controller_data)."""

    def __init__(self, cell: ir.Cell, robot: str) -> None:
        self.cell, self.robot = cell, robot
        self.frames = NumberedData({f.number for f in cell.frames if f.number is not None}, 1)
        self.tools = NumberedData({t.number for t in cell.tools
                                   if t.robot == robot and t.number is not None}, 1)

    def uframe(self, frame: ir.FrameRef) -> int:
        if frame.name is None:
            return 0
        return self.frames.number(frame.name, frame_number(self.cell, frame.name), frame.pose)

    def utool(self, tool: ir.ToolRef) -> int:
        return self.tools.number(tool.name, tool_number(self.cell, self.robot, tool.name), tool.tcp)


@dataclass(frozen=True)
class FanucContext(TaskContext):
    """One task's context plus its names, frame numbers, routine programs and the program
    being printed."""

    names: NameTable
    routine_of: dict[int, str]
    frames: _Frames
    files: dict[str, str] = field(default_factory=dict)  # routine programs: file name -> text
    program: _Program = field(default_factory=_Program)


class FanucBackend(Backend):
    name = "fanuc"
    DIGITAL_PORTS = (1, 512)  # DI / DO logical numbers, R-30iA/iB
    file_ext = ".ls"
    COMMENT = "!"
    UNITS: ClassVar[dict[str, str]] = {"length": "mm", "angle": "deg", "tcp_speed": "mm/sec",
                                       "joint_speed": "%", "time": "sec", "wait_timeout": "1/100 s"}
    NAME_RULES = FANUC_RULES
    MAX_INSTRUCTIONS = 1000
    SPLIT_UNITS = ("TP program", "programs")
    FRAME_PR: ClassVar[int] = 90
    MAX_UTOOL: ClassVar[int] = 10  # R-30iB: tool frames 1..10 (Operator's Manual, "Setting a tool frame")
    MAX_UFRAME: ClassVar[int] = 9  # R-30iB: user frames 1..9 (0 = world; "Setting a user frame")
    CNT_MM: ClassVar[float] = 1.0  # mm of blend radius per CNT step (documented heuristic)
    MAX_TCP_MM_S: ClassVar[int] = 2000  # the L/C speed limit of the R-30iB motion software
    MAX_TCP_SPEED = 2.0  # m/s, the same limit for the shared clamp (W417)
    MAX_TCP_SPEED_SOURCE = "R-30iB Operator's Manual, motion instruction speed: L/C 1..2000 mm/sec"
    SYNC_HANDSHAKE = True  # sync -> the I/O handshake of backends/handshake.py
    SIX_AXIS_DATA = "TP positions"
    BRANCH_DATA = "the CONFIG string"
    NO_RECORD_NOTE = "move {uid} not emitted"
    NOT_SIX_AXIS_NOTE = "move not emitted: not a 6-axis arm"

    # ------------------------------------------------------------------ programs

    def emit_task(self, task: TaskContext) -> dict[str, str]:
        names, main_name, body = self.open_task(task)
        # TP programs share one namespace on the controller: routines carry the program's name
        routine_of = self.routine_table(names, body, task, prefix=f"{main_name}_")
        ctx = task.with_state(FanucContext, names=names, routine_of=routine_of,
                              frames=_Frames(task.plan.program.cell, task.robot.name))
        parts = self.split_parts(body, ctx, main_name)
        if parts is not None:
            for part in parts:
                assert isinstance(part, ir.ProcCall)
                routine_of[part.uid] = names.name(part.proc)
            body = parts
        main = self._program(main_name, body, ctx, is_main=True)
        self.extend(names.diagnostics)
        return {f"{main_name}.ls": main, **dict(sorted(ctx.files.items()))}

    def _program(self, name: str, body: tuple[ir.Instr, ...], task: FanucContext, *, is_main: bool) -> str:
        ctx = replace(task, program=_Program())
        lines = [self.comment(piece) for text in header_lines(ctx.plan, self.name, self.findings_header)
                 for piece in _pieces(text)]
        main = self.body(body, ctx)
        if is_main:
            lines += self._frame_setup(ctx)
        lines += main
        return self._ls(name, lines, ctx.program.positions)

    def _ls(self, name: str, lines: list[str], positions: list[str]) -> str:
        out = [f"/PROG  {name}", "/ATTR", "OWNER\t\t= MNEDITOR;", 'COMMENT\t\t= "rmot";',
               "PROG_SIZE\t= 0;", "FILE_NAME\t= ;", "VERSION\t\t= 0;", f"LINE_COUNT\t= {sum(not x.startswith(':') for x in lines)};",
               "MEMORY_SIZE\t= 0;", "PROTECT\t\t= READ_WRITE;",
               "TCD:  STACK_SIZE\t= 0,", "      TASK_PRIORITY\t= 50,", "      TIME_SLICE\t= 0,",
               "      BUSY_LAMP_OFF\t= 0,", "      ABORT_REQUEST\t= 0,", "      PAUSE_REQUEST\t= 0;",
               "DEFAULT_GROUP\t= 1,*,*,*,*;", "CONTROL_CODE\t= 00000000 00000000;", "/MN"]
        n = 0
        for k, line in enumerate(lines):
            if line.startswith(":"):  # continuation of a circular move: no line number
                out.append(f"    {line} ;")
                continue
            n += 1
            # `C P[via]` is not a complete instruction: only its `: P[to] speed zone ;`
            # continuation ends with ';' (R-30iB Operator's Manual, circular motion; RoboDK
            # Fanuc_R30iA.py writes `C P[n]` then `:  P[m] ... ;`)
            continued = k + 1 < len(lines) and lines[k + 1].startswith(":")
            out.append(f"{n:>4}:  {line}" + ("" if continued else " ;"))
        out += ["/POS"] + positions + ["/END"]
        return "\n".join(out) + "\n"

    def comment(self, text: str) -> str:
        return f"!{comment_safe(text)}"

    def source_comment(self, node: ir.Instr, ctx: TaskContext) -> str | None:
        ref = ctx.source_ref(node)
        return self.comment(ref[-COMMENT_MAX:]) if ref else None

    def _frame_setup(self, ctx: FanucContext) -> list[str]:
        """UTOOL/UFRAME values written through position registers (see the module docstring):
        tools and frames without a cell number (W416, naming what is overwritten), and numbered
        ones only with --write-frames. A numbered one not written gets comments with the
        values the controller's UTOOL/UFRAME must hold."""
        lines: list[str] = []
        k = 0
        for kind, table, limit in (("UTOOL", ctx.frames.tools, self.MAX_UTOOL),
                                   ("UFRAME", ctx.frames.frames, self.MAX_UFRAME)):
            for fname, (index, given) in table.numbers.items():
                pose = table.poses[fname]
                x, y, z = position_mm(pose)
                w, p, r = reversed(euler_zyx_deg(pose))
                what = "tool" if kind == "UTOOL" else "frame"
                label = f"{kind}[{index}] = {fname or 'flange'}"[:COMMENT_MAX]
                if given and not 1 <= index <= limit:
                    self.unsupported(codes.NUMBER_OUT_OF_RANGE, f"{what} '{fname}' number must be in "
                                     f"1..{limit} for {kind} (got {index})", self._decl_span(ctx, kind, fname))
                if given and not self.write_frames:
                    lines.append(self.comment(f"{label} must hold:"[:COMMENT_MAX]))
                    lines.append(self.comment(f"X {fmt(x, 1)} Y {fmt(y, 1)} Z {fmt(z, 1)}"[:COMMENT_MAX]))
                    lines.append(self.comment(f"W {fmt(w, 1)} P {fmt(p, 1)} R {fmt(r, 1)}"[:COMMENT_MAX]))
                    continue
                k += 1
                pr = self.FRAME_PR + k
                if not given:
                    self.warn(codes.STORED_DATA_WRITTEN, f"{what} '{fname or 'flange'}' has no controller "
                              f"number: the program overwrites {kind}[{index}] and PR[{pr}] (give it "
                              f"`number n` in the cell to select the taught one)", self._decl_span(ctx, kind, fname))
                lines.append(self.comment(label))
                lines.append(f"PR[{pr}]=LPOS")
                lines += [f"PR[{pr},{j}]={fmt(v, 4)}" for j, v in enumerate((x, y, z, w, p, r), start=1)]
                lines.append(f"{kind}[{index}]=PR[{pr}]")
        return lines

    @staticmethod
    def _decl_span(ctx: FanucContext, kind: str, name: str | None) -> Span | None:
        """The cell declaration of a tool or frame (the task's span for the bare flange)."""
        items = ctx.plan.program.cell.tools if kind == "UTOOL" else ctx.plan.program.cell.frames
        return next((i.span for i in items if i.name == name), ctx.task.span)

    # ------------------------------------------------------------------ motion

    def move(self, node: ir.Move, ctx: FanucContext) -> list[str]:
        rec = self.move_record(node, ctx)
        if isinstance(rec, list):
            return rec
        self.warn_accel(node, ctx, "TP's ACC is a % of the motion profile; the controller's own applies")
        self.warn_payload(node, ctx, "the controller's payload schedule ($PLST_GRP1) selected by PAYLOAD[i]")
        uf, ut = ctx.frames.uframe(node.frame), ctx.frames.utool(node.tool)
        zone = self._zone(node, self.planned_zone(node, rec))
        if node.kind is ir.MotionKind.JOINT:
            speed = self._joint_speed(node)
            if isinstance(node.target, ir.JointTarget):
                p = self._joint_position(node.target, uf, ut, ctx)
            else:
                p = self._cart_position(node.target, rec.q_target, rec.branch, uf, ut, node, ctx)
            return [f"UFRAME_NUM={uf}", f"UTOOL_NUM={ut}", f"J P[{p}] {speed} {zone}"]
        if isinstance(node.target, ir.JointTarget):
            self.unsupported(codes.UNSUPPORTED, "a linear move must have a Cartesian target (got joints)", node.span)
            return []
        speed = self._tcp_speed(node)
        if node.kind is ir.MotionKind.CIRCULAR and node.via is not None:  # P[via] numbered first
            q_via = rec.q_via if rec.q_via is not None else rec.q_target
            via = self._cart_position(node.via, q_via, rec.branch, uf, ut, node, ctx)
        to = self._cart_position(node.target, rec.q_target, rec.branch, uf, ut, node, ctx)
        head = [f"UFRAME_NUM={uf}", f"UTOOL_NUM={ut}"]
        if node.kind is ir.MotionKind.LINEAR:
            return head + [f"L P[{to}] {speed} {zone}"]
        if node.via is None:
            self.unsupported(codes.UNSUPPORTED, "circular move must have a via point (got none)", node.span)
            return head
        return head + [f"C P[{via}]", f":  P[{to}] {speed} {zone}"]

    def _joint_speed(self, node: ir.Move) -> str:
        if node.motion.duration is not None:
            return f"{fmt(node.motion.duration, 2)}sec"
        pct = node.motion.joint_speed * 100.0
        n = max(1, min(100, round(pct)))
        if abs(n - pct) > 1e-9:
            self.warn(codes.SPEED_ROUNDED, f"joint speed {fmt(pct, 3)} % must be an integer for TP; "
                      f"emitted as {n}%", node.span)
        return f"{n}%"

    def _tcp_speed(self, node: ir.Move) -> str:
        if node.motion.duration is not None:
            return f"{fmt(node.motion.duration, 2)}sec"
        v = self.tcp_speed_within_limit(node) * 1000.0  # W417 above MAX_TCP_SPEED
        n = max(1, min(self.MAX_TCP_MM_S, round(v)))
        if abs(n - v) > 1e-9:
            self.warn(codes.SPEED_ROUNDED, f"TCP speed {fmt(v, 3)} mm/sec must be an integer for TP; "
                      f"emitted as {n}mm/sec", node.span)
        return f"{n}mm/sec"

    def _zone(self, node: ir.Move, zone: ir.Zone) -> str:
        """FINE where the plan stops (Backend.planned_zone), else CNTn."""
        if zone.is_fine:
            return "FINE"
        r = zone.radius * 1000.0
        cnt = max(1, min(100, round(r / self.CNT_MM)))
        self.warn(codes.ZONE_ROUNDED, f"zone {fmt(r, 3)} mm has no exact TP form (CNT is not a radius); "
                  f"emitted as CNT{cnt}", node.span)
        return f"CNT{cnt}"

    def _joint_position(self, target: ir.JointTarget, uf: int, ut: int, ctx: FanucContext) -> int:
        values = [math.degrees(v) for v in target.values]
        cells = [f"J{i + 1}= {fmt(v, 3):>9} deg" for i, v in enumerate(values)]
        body = [f"\tUF : {uf}, UT : {ut},", "\t" + ",\t".join(cells[:3]) + ",", "\t" + ",\t".join(cells[3:])]
        return self._position(body, target.name, ctx)

    def _cart_position(self, target: ir.CartesianTarget, q: np.ndarray | None, branch: ir.Config | None,
                       uf: int, ut: int, node: ir.Move, ctx: FanucContext) -> int:
        assert q is not None
        branch = self.branch_or_default(branch, node)
        x, y, z = position_mm(target.in_frame)
        w, p, r = reversed(euler_zyx_deg(target.in_frame))
        body = [f"\tUF : {uf}, UT : {ut},\t\tCONFIG : '{config_string(branch, q)}',",
                f"\tX = {fmt(x, 3):>9}  mm,\tY = {fmt(y, 3):>9}  mm,\tZ = {fmt(z, 3):>9}  mm,",
                f"\tW = {fmt(w, 3):>9} deg,\tP = {fmt(p, 3):>9} deg,\tR = {fmt(r, 3):>9} deg"]
        return self._position(body, target.name, ctx)

    @staticmethod
    def _position(body: list[str], name: str | None, ctx: FanucContext) -> int:
        n = len(ctx.program.positions) + 1
        label = f':"{name[:16]}"' if name else ""
        ctx.program.positions.append("\n".join([f"P[{n}{label}]{{", "   GP1:"] + body + ["};"]))
        return n

    # ------------------------------------------------------------------ I/O and flow

    @staticmethod
    def _level(value: bool) -> str:
        return "ON" if value else "OFF"

    def set_digital(self, node: ir.SetDigital, ctx: FanucContext) -> list[str]:
        if not self.port_ok(node.port, "digital output", node.span):
            return []
        return [f"DO[{node.port}{_sig(node.signal)}]={self._level(node.value)}"]

    def set_analog(self, node: ir.SetAnalog, ctx: FanucContext) -> list[str]:
        return [f"AO[{node.port}{_sig(node.signal)}]={fmt(node.value, 3)}"]

    def pulse(self, node: ir.Pulse, ctx: FanucContext) -> list[str]:
        if not self.port_ok(node.port, "digital output", node.span):
            return []
        return [f"DO[{node.port}{_sig(node.signal)}]=PULSE,{self._seconds(node.duration, 1, 'pulse', node)}sec"]

    def wait_time(self, node: ir.WaitTime, ctx: FanucContext) -> list[str]:
        return [f"WAIT {self._seconds(node.duration, 2, 'wait', node)}(sec)"]

    def _seconds(self, value: float, decimals: int, what: str, node: ir.Instr) -> str:
        """TP times have a fixed resolution (WAIT 0.01 s, PULSE 0.1 s): round, warn if changed."""
        text = fmt(value, decimals)
        if abs(float(text) - value) > 1e-9:
            self.warn(codes.TIME_ROUNDED, f"{what} time {fmt(value, 4)} s must be a multiple of "
                      f"{10.0 ** -decimals:g} s for TP; emitted as {text} s", node.span)
        return text

    def wait_input(self, node: ir.WaitInput, ctx: FanucContext) -> list[str]:
        c = node.condition
        if not self.port_ok(c.port, "digital input", node.span):
            return []
        cond = f"DI[{c.port}{_sig(c.signal)}]={self._level(c.value)}"
        if node.timeout is None:
            return [f"WAIT {cond}"]
        timeout, done = ctx.program.label(), ctx.program.label()
        return [f"$WAITTMOUT={int(round(node.timeout * 100))}", f"WAIT {cond} TIMEOUT,LBL[{timeout}]",
                f"JMP LBL[{done}]", f"LBL[{timeout}]", self.comment("wait timed out"), "ABORT",
                f"LBL[{done}]"]

    def if_(self, node: ir.If, ctx: FanucContext) -> list[str]:
        c = node.condition
        if not isinstance(c, ir.InputCondition):  # conditions over variables: issue #15
            self.unsupported(codes.UNSUPPORTED, f"if on a {type(c).__name__} must be expressible "
                             f"for {self.name} (it is not yet)", node.span)
            return [self.comment(f"UNSUPPORTED if on a {type(c).__name__}")]
        self.port_ok(c.port, "digital input", node.span)
        other, done = ctx.program.label(), ctx.program.label()
        lines = [f"IF DI[{c.port}{_sig(c.signal)}]<>{self._level(c.value)},JMP LBL[{other}]"]
        lines += self.body(node.then, ctx) + [f"JMP LBL[{done}]", f"LBL[{other}]"]
        return lines + self.body(node.otherwise, ctx) + [f"LBL[{done}]"]

    def sync(self, node: ir.Sync, ctx: FanucContext) -> list[str]:  # type: ignore[override]
        """Only reached when the I/O handshake was not built (see Backend.sync_handshake)."""
        return [line[:COMMENT_MAX + 1] for line in self.sync_not_lowered(node, ctx)]

    def handshake_comment(self, node: ir.Instr) -> str | None:
        note = super().handshake_comment(node)
        return note[:COMMENT_MAX + 1] if note else None

    def native(self, node: ir.Native, ctx: FanucContext) -> list[str]:  # type: ignore[override]
        if node.vendor.lower() != self.name:
            return self.native_other(node)
        return [line.strip().rstrip(";").rstrip() for line in node.text.splitlines() if line.strip()]

    def native_other(self, node: ir.Native) -> list[str]:
        super().native_other(node)
        return [self.comment(f"native {node.vendor} skipped"[:COMMENT_MAX])]

    def proc_call(self, node: ir.ProcCall, ctx: FanucContext) -> list[str]:
        name = ctx.routine_of[node.uid]
        if f"{name}.ls" not in ctx.files:
            ctx.files[f"{name}.ls"] = ""  # reserve: a recursive print sees it as taken
            ctx.files[f"{name}.ls"] = self._program(name, node.body, ctx, is_main=False)
        return [f"CALL {name}"]


def _sig(signal: str | None) -> str:
    """The cell's signal name as a TP I/O comment: DO[1:gripper_close]."""
    return f":{tp_io_comment(signal)[:24]}" if signal else ""


def _pieces(text: str) -> list[str]:
    """Comment text wrapped into lines of at most COMMENT_MAX characters."""
    return textwrap.wrap(text, COMMENT_MAX, break_long_words=True) or [""]
