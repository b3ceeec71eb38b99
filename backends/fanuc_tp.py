"""Fanuc TP backend (.ls ASCII programs, R-30iA/iB; loaded with the ASCII Upload option).

Conventions (Fanuc "R-30iB Controller Operator's Manual (Basic Operation)"):
  * positions in mm; orientation W, P, R in degrees, fixed axes X then Y then Z:
    R = Rz(R)·Ry(P)·Rx(W); joints J1..J6 in degrees (the controller's values; rmot's robot
    library already uses Fanuc's J2/J3 convention).
  * Cartesian positions carry `UF : n, UT : m, CONFIG : 'F|N U|D T|B, t4, t5, t6'`:
    N (no flip) when J5 < 0 and F when J5 > 0 on Fanuc's own J5 (the LR Mate's home with
    the tool down, J5 = -90 deg, shows 'N U T'); note rmot's branch calls J5 < 0 "flip"
    (rmot.sim.robots.branches), so rmot FLIP -> 'N', NOFLIP -> 'F'. U = elbow up,
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
  * acceleration: a joint move's acceleration share is the motion option `ACCn` (n %); a TCP
    acceleration (m/s^2) has no TP form (W408 once per task).
  * payload: a .ls program can only select a payload schedule (PAYLOAD[i]) whose mass and
    centre of gravity live on the controller ($PLST_GRP1[i]): a tool with a mass warns W411
    once, giving the mass and rmot's centre of gravity (half way flange->TCP, base.tool_cog);
    each attach/detach selects the schedule of the new load with PAYLOAD[i] (W460 gives the
    values to enter in schedule i).
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
  * runtime logic (the block at the end of the class): variables as R registers,
    one operator per line, IF/WAIT conditions in standard logic or as jump chains, while as
    LBL/JMP, timeout branches at the TIMEOUT label, polled waits with TIMER[10] (W431), stop =
    ABORT, `for` loops as LBL/JMP with Offset,PR[i] or unrolled (W420).
  * size: a program longer than MAX_INSTRUCTIONS instructions is split into programs
    NAME_PART1.. called from NAME (warning W406), keeping pendant loading and editing
    practical; TP itself numbers lines up to 9999.

Over 600 lines: the FanucBackend class alone is 686 lines, and a class is written in one piece
(its methods read its flags and tables)."""

from __future__ import annotations

import math
from collections import Counter
from dataclasses import dataclass, field, replace
from typing import ClassVar

import numpy as np

from rmot.backends import codes, fanuc_records, native_refs
from rmot.backends.ext_axes import coordinated, driven_axes, fanuc_coord, fanuc_default_group, fanuc_groups, fanuc_in_world, machine_data
from rmot.backends.base import Backend, TaskContext, euler_zyx_deg, fmt, fmt_list, header_lines, position_mm
from rmot.backends.part_load import held_load
from rmot.backends.controller_data import NumberedData, frame_number, tool_number
from rmot.backends.runtime import blocked_loop_lines
from rmot.backends.loops import (
    LoopTemplate, LoopVar, TargetOffset, analyse, bind_loop_var, level_moves,
)
from rmot.backends.names import NameTable
from rmot.lang import ir, ir_tree, plan_types
from rmot.lang.ir_axes import ExtAxis
from rmot.backends.safe_text import comment_safe, tp_io_comment
from rmot.lang.record import record
from rmot.lang.source import Span
from rmot.backends.fanuc_tp_text import (
    FANUC_RULES,
    COMMENT_MAX,
    config_string,
    held_frame_values,
    _TP_OP,
    _tp_number,
    _leaf,
    _config_key,
    _rounded,
    _offset_signature,
    _fanuc_blocker,
    _sig,
    _pieces,
    _loop_head,
)

__all__ = ["FanucBackend"]


@dataclass
class _Program:
    """One .ls program being printed: its numbered positions and labels (skipping the labels
    its native lines name), the lines those native lines were written as, and the position
    records they move to (fanuc_records: the number they name -> the number, UFRAME and UTOOL
    written, or why the record cannot be)."""

    positions: list[str] = field(default_factory=list)
    labels: int = 0
    reserved: frozenset[str] = frozenset()
    native: list[str] = field(default_factory=list)
    records: dict[int, tuple[int, int, int] | str] = field(default_factory=dict)

    def label(self) -> int:
        self.labels += 1
        while str(self.labels) in self.reserved:
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


@record
class FanucContext(TaskContext):
    """One task's context plus its names, frame numbers, routine programs and the program
    being printed."""

    names: NameTable
    routine_of: dict[int, str]
    frames: _Frames
    files: dict[str, str] = field(default_factory=dict)  # routine programs: file name -> text
    program: _Program = field(default_factory=_Program)
    regs: _Registers = field(default_factory=lambda: _Registers({}))  # runtime logic
    axes: tuple[ExtAxis, ...] = ()  # the external axes the task drives (backends/ext_axes.py)
    natives: list[tuple[ir.Native, list[str]]] = field(default_factory=list)  # the task's, as written
    own: list[str] = field(default_factory=list)  # the task's lines the backend wrote itself


class FanucBackend(Backend):
    name = "fanuc"
    DIGITAL_PORTS = (1, 512)  # DI / DO logical numbers, R-30iA/iB
    file_ext = ".ls"
    EXTERNAL_AXES = True  # a track as E1.. of group 1, a positioner as its own group (backends/ext_axes.py)
    COMMENT = "!"
    NAME_RULES = FANUC_RULES
    PRINTS_LOOPS = True  # a counting R register with LBL/JMP, targets moved by Offset,PR
    RUNTIME_CONDITIONS = True  # writes and/or/not, AI, R registers and timeout branches
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
                              frames=_Frames(task.plan.program.cell, task.robot.name),
                              regs=_Registers.of_task(task, body), axes=driven_axes(task.task, task.plan.program.cell))
        parts = self.split_parts(body, ctx, main_name)
        if parts is not None:
            for part in parts:
                assert isinstance(part, ir.ProcCall)
                routine_of[part.uid] = names.name(part.proc)
            body = parts
        main = self._program(main_name, body, ctx, is_main=True)
        for node, name in native_refs.clashes(native_refs.FANUC, ctx.natives, ctx.own):
            self.unsupported(codes.NATIVE_CLASH, f"native line names {name}, which this task's program also uses "
                             "(rmot's variables, loops, waits, tools and frames): it would read or change rmot's "
                             "value; use another number", node.span)
        self.extend(names.diagnostics)
        return {f"{main_name}.ls": main, **dict(sorted(ctx.files.items()))}

    def _program(self, name: str, body: tuple[ir.Instr, ...], task: FanucContext, *, is_main: bool) -> str:
        ctx = replace(task, program=_Program(reserved=native_refs.reserved_labels(native_refs.FANUC, body)))
        self._place_records(body, ctx)
        head = header_lines(ctx.plan, self.name, self.findings_header)
        head += machine_data(ctx.plan.program.cell, ctx.robot, ctx.axes, "fanuc", coordinated(ctx.task)) if is_main else []
        lines = [self.comment(piece) for text in head for piece in _pieces(text)]
        main = self.body(body, ctx)
        if is_main:
            lines += self._frame_setup(ctx)
        lines += main
        ctx.own.extend((Counter(lines) - Counter(ctx.program.native)).elements())
        groups = fanuc_default_group(ctx.axes, ctx.plan.program.cell) if ctx.axes else "1,*,*,*,*"
        return self._ls(name, lines, ctx.program.positions, groups)

    @staticmethod
    def _place_records(body: tuple[ir.Instr, ...], ctx: FanucContext) -> None:
        """The program's native position records first in /POS, at the numbers, frames and
        tools of the compiled program (fanuc_records)."""
        cell, robot = ctx.plan.program.cell, ctx.robot.name
        for n, rec in fanuc_records.records_of(body, bool(ctx.axes)).items():
            frame, tool = fanuc_records.frame_ref(cell, robot, rec.frame), fanuc_records.tool_ref(cell, robot, rec.tool)
            if rec.problem or frame is None or tool is None:
                ctx.program.records[n] = rec.problem or (f"its UF `{rec.frame}` names no frame of the cell (base, world or a "
                                                         "cell frame)" if frame is None else
                                                         f"its UT `{rec.tool}` names no tool of robot '{robot}' (or flange)")
                continue
            uf, ut, k = ctx.frames.uframe(frame), ctx.frames.utool(tool), len(ctx.program.positions) + 1
            ctx.program.positions.append(fanuc_records.layout(rec, k, uf, ut))
            ctx.program.records[n] = (k, uf, ut)

    def _ls(self, name: str, lines: list[str], positions: list[str], groups: str = "1,*,*,*,*") -> str:
        out = [f"/PROG  {name}", "/ATTR", "OWNER\t\t= MNEDITOR;", 'COMMENT\t\t= "rmot";',
               "PROG_SIZE\t= 0;", "FILE_NAME\t= ;", "VERSION\t\t= 0;", f"LINE_COUNT\t= {sum(not x.startswith(':') for x in lines)};",
               "MEMORY_SIZE\t= 0;", "PROTECT\t\t= READ_WRITE;",
               "TCD:  STACK_SIZE\t= 0,", "      TASK_PRIORITY\t= 50,", "      TIME_SLICE\t= 0,",
               "      BUSY_LAMP_OFF\t= 0,", "      ABORT_REQUEST\t= 0,", "      PAUSE_REQUEST\t= 0;",
               f"DEFAULT_GROUP\t= {groups};", "CONTROL_CODE\t= 00000000 00000000;", "/MN"]
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
                    lines += [self.comment(text) for text in held_frame_values(x, y, z, w, p, r)]
                    continue
                k += 1
                pr = ctx.regs.frame_prs[0] + k - 1
                if pr > ctx.regs.frame_prs[1]:
                    self.unsupported(codes.REGISTERS_EXHAUSTED, f"this task's tool and frame setup "
                                     f"must fit PR[{ctx.regs.frame_prs[0]}..{ctx.regs.frame_prs[1]}] "
                                     f"(needs PR[{pr}])", self._decl_span(ctx, kind, fname))
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
        if ctx.axes:  # no coordinated motion: targets in fixed user frames (backends/ext_axes.py)
            node = fanuc_in_world(node, ctx.robot, ctx.plan.program.cell)
        if node.kind is not ir.MotionKind.JOINT:  # joint moves write ACC (move_joint)
            self.warn_accel(node, ctx, "TP's ACC is a share of the motion profile, not a TCP acceleration")
        self.warn_payload(node, ctx, "the controller's payload schedule ($PLST_GRP1) selected by PAYLOAD[i]")
        uf, ut = ctx.frames.uframe(node.frame), ctx.frames.utool(node.tool)
        zone = self._zone(node, self.planned_zone(node, rec)) + fanuc_coord(node)
        return self.by_kind(node)(node, rec, ctx, uf, ut, zone)

    def move_joint(self, node: ir.Move, rec: plan_types.InstructionRecord, ctx: FanucContext,
                   uf: int, ut: int, zone: str) -> list[str]:
        speed = self._joint_speed(node)
        if isinstance(node.target, ir.JointTarget):
            p = self._joint_position(node.target, uf, ut, ctx, node)
        else:
            p = self._cart_position(node.target, rec.q_target, rec.branch, uf, ut, node, ctx)
        # ACC: acceleration override of the motion, % (FANUC R-30iB Operator's Manual, motion
        # options "ACC": 0..150); rmot writes the plan's joint acceleration share, 1..100 %
        pct = self.accel_percent(node, rec, ctx, 1, "TP's ACC is a share of the joint motion profile")
        acc = "" if pct is None else f" ACC{pct}"
        return [f"UFRAME_NUM={uf}", f"UTOOL_NUM={ut}", f"J P[{p}] {speed} {zone}{acc}{self._offset(node, ctx)}"]

    def move_linear(self, node: ir.Move, rec: plan_types.InstructionRecord, ctx: FanucContext,
                    uf: int, ut: int, zone: str) -> list[str]:
        if self.joint_target_refused(node):
            return []
        assert isinstance(node.target, ir.CartesianTarget)  # refused above otherwise
        speed = self._tcp_speed(node)
        to = self._cart_position(node.target, rec.q_target, rec.branch, uf, ut, node, ctx)
        return [f"UFRAME_NUM={uf}", f"UTOOL_NUM={ut}", f"L P[{to}] {speed} {zone}{self._offset(node, ctx)}"]

    def move_circular(self, node: ir.Move, rec: plan_types.InstructionRecord, ctx: FanucContext,
                      uf: int, ut: int, zone: str) -> list[str]:
        if self.joint_target_refused(node):
            return []
        assert isinstance(node.target, ir.CartesianTarget)  # refused above otherwise
        if self.via_refused(node):
            return [f"UFRAME_NUM={uf}", f"UTOOL_NUM={ut}"]
        assert node.via is not None  # refused above otherwise
        speed = self._tcp_speed(node)
        q_via = rec.q_via if rec.q_via is not None else rec.q_target
        # P[via] numbered first
        via = self._cart_position(node.via, q_via, rec.branch, uf, ut, node, ctx)
        to = self._cart_position(node.target, rec.q_target, rec.branch, uf, ut, node, ctx)
        return [f"UFRAME_NUM={uf}", f"UTOOL_NUM={ut}", f"C P[{via}]", f":  P[{to}] {speed} {zone}"]

    @staticmethod
    def _offset(node: ir.Move, ctx: FanucContext) -> str:
        """` Offset,PR[i]` on a move of a loop whose target moves per iteration:
        the destination shifted by PR[i] in the selected user frame (HandlingTool V9.40
        Operator's Manual sec 7.3.13, "Offset,PR[i]"; real programs: `L P[2] 2000mm/sec FINE
        Offset,PR[100]`)."""
        pr = ctx.regs.offsets.get((node.uid, "target"))
        return f" Offset,PR[{pr}]" if pr is not None else ""

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

    def _joint_position(self, target: ir.JointTarget, uf: int, ut: int, ctx: FanucContext, node: ir.Move) -> int:
        values = [math.degrees(v) for v in target.values]
        cells = [f"J{i + 1}= {fmt(v, 3):>9} deg" for i, v in enumerate(values)]
        body = [f"\tUF : {uf}, UT : {ut},", "\t" + ",\t".join(cells[:3]) + ",", "\t" + ",\t".join(cells[3:])]
        return self._position(self._with_groups(body, node, uf, ut, ctx), target.name, ctx)

    @staticmethod
    def _with_groups(body: list[str], node: ir.Move, uf: int, ut: int, ctx: FanucContext) -> list[str]:
        """The GP1 lines of a position, with the task's external axes: a track's as E1.. of GP1,
        each positioner's as its own group block (backends/ext_axes.py)."""
        if not ctx.axes:
            return body
        extended, groups = fanuc_groups(node, ctx.axes, ctx.plan.program.cell, uf, ut)
        if extended:
            body = body[:-1] + [body[-1] + ","] + extended
        return body + groups

    def _cart_position(self, target: ir.CartesianTarget, q: np.ndarray | None, branch: ir.Config | None,
                       uf: int, ut: int, node: ir.Move, ctx: FanucContext) -> int:
        assert q is not None
        branch = self.branch_or_default(branch, node)
        x, y, z = position_mm(target.in_frame)
        w, p, r = reversed(euler_zyx_deg(target.in_frame))
        body = [f"\tUF : {uf}, UT : {ut},\t\tCONFIG : '{config_string(branch, q)}',",
                f"\tX = {fmt(x, 3):>9}  mm,\tY = {fmt(y, 3):>9}  mm,\tZ = {fmt(z, 3):>9}  mm,",
                f"\tW = {fmt(w, 3):>9} deg,\tP = {fmt(p, 3):>9} deg,\tR = {fmt(r, 3):>9} deg"]
        return self._position(self._with_groups(body, node, uf, ut, ctx), target.name, ctx)

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
        return self._timed_wait(cond, node.timeout, node.on_timeout, ctx)

    def if_(self, node: ir.If, ctx: FanucContext) -> list[str]:
        c = node.condition
        if not isinstance(c, ir.InputCondition):  # any condition
            return self._if_condition(node, ctx)
        self.port_ok(c.port, "digital input", node.span)
        other, done = ctx.program.label(), ctx.program.label()
        lines = [f"IF DI[{c.port}{_sig(c.signal)}]<>{self._level(c.value)},JMP LBL[{other}]"]
        lines += self.body(node.then, ctx) + [f"JMP LBL[{done}]", f"LBL[{other}]"]
        return lines + self.body(node.otherwise, ctx) + [f"LBL[{done}]"]

    # A held part's load: TP's payload instruction `PAYLOAD[i]` switches the active payload
    # schedule i (R-30iB Operator's Manual B-83284EN, "Payload instruction": i = payload schedule
    # number 1..10), whose mass and centre of gravity are entered on the controller's payload
    # setting screen ($PLST_GRP1[i]); a program selects a schedule, it does not write its
    # numbers. Each distinct load of the task (tool + held parts after an attach or detach)
    # gets its own schedule, numbered in order of first use; W460 once per schedule gives the
    # values to enter there.
    MAX_PAYLOAD_SCHEDULE: ClassVar[int] = 10

    def attach(self, node: ir.Attach, ctx: FanucContext) -> list[str]:
        return self._payload_switch(node, ctx)

    def detach(self, node: ir.Detach, ctx: FanucContext) -> list[str]:
        return self._payload_switch(node, ctx)

    def _payload_switch(self, node: ir.Attach | ir.Detach, ctx: FanucContext) -> list[str]:
        _, _, total, cog = held_load(node, ctx)
        cog_mm = fmt_list((c * 1000.0 for c in cog), 1)
        schedules = ctx.regs.payloads
        key = f"{fmt(total, 3)} kg [{cog_mm}]"
        if key not in schedules:
            schedules[key] = len(schedules) + 1
            if schedules[key] > self.MAX_PAYLOAD_SCHEDULE:
                self.unsupported(codes.NUMBER_OUT_OF_RANGE, f"the task's loads must fit payload "
                                 f"schedules 1..{self.MAX_PAYLOAD_SCHEDULE} (needs "
                                 f"{schedules[key]})", node.span)
            self.warn(codes.PART_PAYLOAD_NOT_EXPRESSED, f"payload schedule {schedules[key]} "
                      f"($PLST_GRP1[{schedules[key]}]) must hold {fmt(total, 3)} kg with centre of "
                      f"gravity [{cog_mm}] mm in the flange frame (tool and held parts): the "
                      f"program selects it with PAYLOAD[{schedules[key]}] at this "
                      f"{'attach' if isinstance(node, ir.Attach) else 'detach'}", node.span)
        word = "attach" if isinstance(node, ir.Attach) else "detach"
        return [self.comment(f"{word} {node.part}: {fmt(total, 3)} kg"[:COMMENT_MAX]),
                f"PAYLOAD[{schedules[key]}]"]

    def sync(self, node: ir.Sync, ctx: FanucContext) -> list[str]:  # type: ignore[override]
        """Only reached when the I/O handshake was not built (see Backend.sync_handshake)."""
        return [line[:COMMENT_MAX + 1] for line in self.sync_not_lowered(node, ctx)]

    def handshake_comment(self, node: ir.Instr) -> str | None:
        note = super().handshake_comment(node)
        return note[:COMMENT_MAX + 1] if note else None

    def native(self, node: ir.Native, ctx: FanucContext) -> list[str]:  # type: ignore[override]
        if node.vendor.lower() != self.name:
            return self.native_other(node)
        if fanuc_records.number_of(node.text) is not None:  # a position record: in /POS (_place_records), refused at
            return []  # the lines that move to it
        lines = [line.strip().rstrip(";").rstrip() for line in node.text.splitlines() if line.strip()]
        lines, selection = self._to_records(node, lines, ctx)
        ctx.program.native.extend(lines)
        ctx.natives.append((node, lines))
        return selection + lines

    def _to_records(self, node: ir.Native, lines: list[str], ctx: FanucContext) -> tuple[list[str], list[str]]:
        """Native lines moving to positions of their program: renamed to where their records
        were written, and the records' frame and tool selected before them (fanuc_records)."""
        named = fanuc_records.named(lines)
        placed = {n: ctx.program.records.get(n) for n in named}
        written = {n: p for n, p in placed.items() if isinstance(p, tuple)}
        why = next((f"P[{n}], whose record cannot be written: {p}" for n, p in placed.items() if isinstance(p, str)), None)
        why = why or next((f"P[{n}], a position of the program it came from with no native position record `P[{n}]{{GP1: ..}}` "
                           f"in this program: this backend numbers the program's positions for rmot's moves, so P[{n}] here "
                           "is another point or none (write the move as an rmot `move`)" for n, p in placed.items() if p is None), None)
        if why is None and len({p[1:] for p in written.values()}) > 1:
            why = f"positions taught in different frames or tools ({', '.join(f'P[{n}]' for n in written)})"
        if why is not None:
            self.unsupported(codes.NATIVE_CLASH, f"native line names {why}", node.span)
        if why is not None or not written:
            return lines, []
        (_, uf, ut), numbers = next(iter(written.values())), {n: p[0] for n, p in written.items()}
        return [fanuc_records.renamed(line, numbers) for line in lines], [f"UFRAME_NUM={uf}", f"UTOOL_NUM={ut}"]

    def native_other(self, node: ir.Native) -> list[str]:
        super().native_other(node)
        return [self.comment(f"native {node.vendor} skipped"[:COMMENT_MAX])]

    def proc_call(self, node: ir.ProcCall, ctx: FanucContext) -> list[str]:
        name = ctx.routine_of[node.uid]
        shifted = _offset_signature(node.body, ctx.regs.offsets)
        if shifted is not None:  # a call whose moves take Offset,PR: its own routine
            key = (name, shifted)
            if key not in ctx.regs.loop_routines:
                k = len(ctx.regs.loop_routines) + 1
                ctx.regs.loop_routines[key] = ctx.names.name(f"{name}_L{k}")
            name = ctx.regs.loop_routines[key]
        if f"{name}.ls" not in ctx.files:
            ctx.files[f"{name}.ls"] = ""  # reserve: a recursive print sees it as taken
            ctx.files[f"{name}.ls"] = self._program(name, node.body, ctx, is_main=False)
        return [f"CALL {name}"]

    # ------------------------------------------------------------------ runtime logic
    # Variables are numeric registers R[n:name] (R-30iB Operator's Manual B-83284EN, "Register
    # instructions": a register holds an integer or a real); a bool is R 0/1 (one register type
    # for every variable, so conditions and assignments read alike). Numbering: the task's
    # variables R[REG_FIRST..] in order of first declaration, then the temporaries of the
    # current statement; loop offsets are PR[LOOP_PR + 1 ..] (below FRAME_PR + 1, where the
    # frame setup starts); labels count per program with the backend's own (no collision).
    # Arithmetic is one operator per line (standard register instruction `R[i]=(value)
    # (operator)(value)`; mixing + - with * / or AND with OR in one line needs the Mixed Logic
    # option: Fanuc America "Advanced TPP" ch. 7, which also gives "in standard logic a maximum
    # of five logical conditions"). Conditions: `IF a AND b ...,JMP LBL[n]` with up to
    # MAX_CONDITIONS leaves of one operator (real programs: `IF DI[101]=ON AND UO[3]=OFF AND
    # DI[104]=OFF,JMP LBL[20]`), else a chain of one-condition jumps.

    # Registers, position registers and timers are global on the controller, which the
    # program's tasks may share: each task numbers its own slice of every range
    # (TaskContext.register_slice; lang/REFERENCE.md §8), the whole range for a single task.
    REG_FIRST: ClassVar[int] = 1
    MAX_REGISTER: ClassVar[int] = 200  # R-30iB: R[1]..R[200] by default (Operator's Manual)
    LOOP_PR: ClassVar[int] = 60  # loop offsets PR[61..90]: below FRAME_PR + 1
    MAX_PR: ClassVar[int] = 100  # R-30iB: PR[1]..PR[100] by default; frame setup PR[91..100]
    TIMERS: ClassVar[int] = 10  # TIMER[1..10]
    MAX_CONDITIONS: ClassVar[int] = 5

    def _reg(self, name: str, ctx: FanucContext, span: object) -> str:
        n = ctx.regs.variables.get(name)
        if n is None:
            self.unsupported(codes.LOGIC_UNSUPPORTED,
                             f"variable '{name}' must be declared in the task (got a reference to "
                             "an undeclared one)", span)  # type: ignore[arg-type]
            n = 0
        self._within(n, ctx, span)
        return f"R[{n}:{tp_io_comment(name)[:16]}]"

    def _within(self, n: int, ctx: FanucContext, span: object) -> None:
        """E4xx when R[n] lies beyond this task's slice of the registers."""
        if n > ctx.regs.last:
            self.unsupported(codes.REGISTERS_EXHAUSTED,
                             f"the program must fit registers R[{ctx.regs.first}.."
                             f"{ctx.regs.last}] (needs R[{n}])", span)  # type: ignore[arg-type]

    def _temp(self, ctx: FanucContext, span: object) -> str:
        n = ctx.regs.temp()
        self._within(n, ctx, span)
        return f"R[{n}:rmot tmp]"

    def var_decl(self, node: ir.VarDecl, ctx: FanucContext) -> list[str]:
        return self._store(node.name, node.init, node, ctx)

    def assign(self, node: ir.Assign, ctx: FanucContext) -> list[str]:
        return self._store(node.name, node.value, node, ctx)

    def _store(self, name: str, value: ir.RtExpr, node: ir.Instr, ctx: FanucContext) -> list[str]:
        ctx.regs.reset()
        target = self._reg(name, ctx, node.span)
        if isinstance(value, ir.Arith):  # one operator straight into the variable
            lines, a = self._operand(value.left, ctx, node)
            more, b = self._operand(value.right, ctx, node)
            return lines + more + [f"{target}={a}{value.op}{b}"]
        lines, a = self._operand(value, ctx, node)
        return lines + [f"{target}={a}"]

    def _operand(self, e: ir.RtExpr, ctx: FanucContext, node: ir.Instr) -> tuple[list[str], str]:
        """(lines computing it, the operand text): a constant, R[n], AI[n] or a temporary."""
        if isinstance(e, ir.Const):
            return [], _tp_number(e.value)
        if isinstance(e, ir.VarRef):
            return [], self._reg(e.name, ctx, node.span)
        if isinstance(e, ir.AnalogInput):
            # AI[n] is the raw A/D count of the input (FANUC B-63943EN/02 §8.4.14), whose
            # scale (counts per volt) depends on the I/O module: volts have no TP form
            self.unsupported(codes.ANALOG_RAW_COUNTS, f"analog input {e.port} is a value in volts in "
                             "rmot, but Fanuc's AI[n] holds the controller's raw A/D counts (counts per volt "
                             "depend on the I/O module): no TP form reads it in volts", node.span)
            return [], f"AI[{e.port}{_sig(e.signal)}]"
        if isinstance(e, ir.GroupInput):
            # GI[n]: the group's inputs read as one unsigned integer, a value an IF compares
            # and a register takes (FANUC B-83284EN §4.3 "Group I/O", §4.15 IF "(variable)
            # (operator) (value)", variable: R[i] or an I/O such as GI[i])
            return [], f"GI[{e.port}{_sig(e.signal)}]"
        if isinstance(e, ir.Arith):
            lines, a = self._operand(e.left, ctx, node)
            more, b = self._operand(e.right, ctx, node)
            t = self._temp(ctx, node.span)
            return lines + more + [f"{t}={a}{e.op}{b}"], t
        t, skip = self._temp(ctx, node.span), ctx.program.label()  # a condition's value, 0 or 1
        return [f"{t}=0", *self._jump(e, skip, False, ctx, node), f"{t}=1", f"LBL[{skip}]"], t

    def _test(self, c: ir.Condition | ir.RtExpr, negate: bool, ctx: FanucContext,
              node: ir.Instr) -> tuple[list[str], str] | None:
        """One comparison for IF/WAIT (`DI[1]=ON`, `R[2]>=3`, `AI[1]>4.5`): its lines and text,
        or None when `c` is not a single comparison."""
        if isinstance(c, ir.Not):
            return self._test(c.operand, not negate, ctx, node)
        if isinstance(c, ir.InputCondition):
            self.port_ok(c.port, "digital input", node.span)
            return [], f"DI[{c.port}{_sig(c.signal)}]={self._level(c.value != negate)}"
        if isinstance(c, ir.OutputRead):
            # IF and WAIT compare DO[i] with ON/OFF as they do DI[i] (FANUC B-83284EN §4.15
            # IF "(variable) (operator) (value)", variable: I/O such as DO[i]; §4.16 WAIT)
            self.port_ok(c.port, "digital output", node.span)
            return [], f"DO[{c.port}{_sig(c.signal)}]={self._level(not negate)}"
        if isinstance(c, ir.VarRef):
            return [], f"{self._reg(c.name, ctx, node.span)}{'=' if negate else '<>'}0"
        if not isinstance(c, ir.Compare):
            return None
        op, left, right = c.op, c.left, c.right
        if isinstance(left, ir.Const) and not isinstance(right, ir.Const):  # register on the left
            op, left, right = op.mirrored(), right, left
        lines: list[str] = []
        if isinstance(left, (ir.VarRef, ir.AnalogInput, ir.GroupInput)):
            a = self._operand(left, ctx, node)[1]
        else:
            lines, value = self._operand(left, ctx, node)
            a = self._temp(ctx, node.span)
            lines.append(f"{a}={value}")
        if isinstance(right, (ir.Const, ir.VarRef)):
            b = self._operand(right, ctx, node)[1]
        else:  # the right of a TP comparison is a constant or a register
            more, value = self._operand(right, ctx, node)
            b = self._temp(ctx, node.span)
            lines += more + [f"{b}={value}"]
        return lines, f"{a}{_TP_OP[op.negated() if negate else op]}{b}"

    def _jump(self, c: ir.Condition | ir.RtExpr, label: int, when: bool, ctx: FanucContext,
              node: ir.Instr) -> list[str]:
        """Lines that jump to LBL[label] when `c` evaluates to `when` and fall through otherwise."""
        if isinstance(c, ir.Not):
            return self._jump(c.operand, label, not when, ctx, node)
        if isinstance(c, ir.Const):
            return [f"JMP LBL[{label}]"] if bool(c.value) == when else []
        if isinstance(c, ir.Logic):
            one = self._one_line(c, not when, ctx, node)
            if one is not None:
                return one[0] + [f"IF {one[1]},JMP LBL[{label}]"]
            out: list[str] = []
            if (c.op == "and") == when:  # every operand must hold: skip out at the first that fails
                skip = ctx.program.label()
                for operand in c.operands[:-1]:
                    out += self._jump(operand, skip, not when, ctx, node)
                return out + self._jump(c.operands[-1], label, when, ctx, node) + [f"LBL[{skip}]"]
            for operand in c.operands:  # any operand decides
                out += self._jump(operand, label, when, ctx, node)
            return out
        test = self._test(c, not when, ctx, node)
        if test is None:
            self.unsupported(codes.LOGIC_UNSUPPORTED, f"a condition must be a comparison, an "
                             f"input, a variable or and/or/not (got {type(c).__name__})", node.span)
            return []
        return test[0] + [f"IF {test[1]},JMP LBL[{label}]"]

    def _one_line(self, c: ir.Logic, negate: bool, ctx: FanucContext,
                  node: ir.Instr) -> tuple[list[str], str] | None:
        """`a AND b AND ...` (or OR) for one IF/WAIT line when every operand is one comparison
        and there are at most MAX_CONDITIONS; with `negate`, De Morgan's dual."""
        if len(c.operands) > self.MAX_CONDITIONS or any(
                isinstance(o, (ir.Logic, ir.Const))
                or (isinstance(o, ir.Not) and not _leaf(o.operand))
                for o in c.operands):
            return None
        tests = [self._test(o, negate, ctx, node) for o in c.operands]
        if any(t is None for t in tests):
            return None
        joiner = " AND " if (c.op == "and") != negate else " OR "
        return [line for t in tests if t for line in t[0]], joiner.join(t[1] for t in tests if t)

    def _if_condition(self, node: ir.If, ctx: FanucContext) -> list[str]:
        ctx.regs.reset()
        other, done = ctx.program.label(), ctx.program.label()
        lines = self._jump(node.condition, other, False, ctx, node)
        lines += self.body(node.then, ctx) + [f"JMP LBL[{done}]", f"LBL[{other}]"]
        return lines + self.body(node.otherwise, ctx) + [f"LBL[{done}]"]

    def while_(self, node: ir.While, ctx: FanucContext) -> list[str]:
        ctx.regs.reset()
        top, end = ctx.program.label(), ctx.program.label()
        lines = [f"LBL[{top}]", *self._jump(node.condition, end, False, ctx, node)]
        return lines + self.body(node.body, ctx) + [f"JMP LBL[{top}]", f"LBL[{end}]"]

    def stop(self, node: ir.Stop, ctx: FanucContext) -> list[str]:
        # ABORT ends the program and every program that called it; it cannot be resumed
        # (R-30iB Operator's Manual B-83284EN, "Program control instructions": ABORT)
        return ["ABORT"]

    def _timed_wait(self, cond: str, timeout: float, on_timeout: tuple[ir.Instr, ...],
                    ctx: FanucContext) -> list[str]:
        """`$WAITTMOUT` (1/100 s) then `WAIT cond TIMEOUT,LBL[t]`: the label runs the timeout
        branch and goes on after the wait, or aborts when the program gave none."""
        timed_out, done = ctx.program.label(), ctx.program.label()
        branch = (self.body(on_timeout, ctx) if on_timeout
                  else [self.comment("wait timed out"), "ABORT"])
        return [f"$WAITTMOUT={int(round(timeout * 100))}", f"WAIT {cond} TIMEOUT,LBL[{timed_out}]",
                f"JMP LBL[{done}]", f"LBL[{timed_out}]", *branch, f"LBL[{done}]"]

    def wait_condition(self, node: ir.WaitCondition, ctx: FanucContext) -> list[str]:
        ctx.regs.reset()
        c = node.condition
        one = (self._one_line(c, False, ctx, node) if isinstance(c, ir.Logic)
               else self._test(c, False, ctx, node) if _leaf(c) else None)
        if one is not None and not one[0]:  # one WAIT line tests it (no value computed before)
            if node.timeout is None:
                return [f"WAIT {one[1]}"]
            return self._timed_wait(one[1], node.timeout, node.on_timeout, ctx)
        self.warn(codes.WAIT_POLLED, "TP's WAIT must test comparisons of one and/or kind, at "
                  f"most {self.MAX_CONDITIONS}, on registers and I/O; this condition is polled "
                  "in a loop" + (f" with TIMER[{ctx.regs.timer}] counting the timeout"
                                 if node.timeout else ""),
                  node.span)
        poll, done = ctx.program.label(), ctx.program.label()
        if node.timeout is None:
            return [f"LBL[{poll}]", *self._jump(c, done, True, ctx, node), f"JMP LBL[{poll}]",
                    f"LBL[{done}]"]
        timer = f"TIMER[{ctx.regs.timer}]"  # seconds (real programs: `R[181]=TIMER[5]`, `>=3`)
        lines = [f"{timer}=RESET", f"{timer}=START", f"LBL[{poll}]",
                 *self._jump(c, done, True, ctx, node)]
        t = self._temp(ctx, node.span)
        lines += [f"{t}={timer}", f"IF {t}<{_tp_number(node.timeout)},JMP LBL[{poll}]"]
        branch = (self.body(node.on_timeout, ctx) if node.on_timeout
                  else [self.comment("wait timed out"), "ABORT"])
        return lines + branch + [f"LBL[{done}]", f"{timer}=STOP"]

    # ---------------------------------------------------------------- loops

    def loop(self, node: ir.Loop, ctx: FanucContext) -> list[str]:
        template = ctx.regs.inner.pop(node.uid, None)
        if template is not None:  # a nested loop of a vendor loop being written
            return self._vendor_loop(template, ctx)
        found = analyse(node, ctx.record, config_key=_config_key,
                        unroll=bool(getattr(self, "unroll", False)))
        return blocked_loop_lines(
            self, node, found, _fanuc_blocker,
            lambda t: self._zero_offsets(t, ctx) + self._vendor_loop(t, ctx),
            lambda n: self._unrolled(n, ctx))

    def _unrolled(self, node: ir.Loop, ctx: FanucContext) -> list[str]:
        lines: list[str] = []
        for it in node.iterations:
            body = bind_loop_var(it.body, node.var, it.value) if node.var else it.body
            label = f"{node.var or 'iteration'} = {it.value}"[:COMMENT_MAX]
            lines += [self.comment(label)] + self.body(body, ctx)
        return lines

    def _zero_offsets(self, template: LoopTemplate, ctx: FanucContext) -> list[str]:
        """Number the PR of every offset of the nest (one per distinct set of steps) and clear
        them: `PR[i]=LPOS-LPOS` is a Cartesian zero (as in real programs)."""
        lines = []
        for key, offset in sorted(template.targets.items()):
            if not any(any(s) for s in offset.steps):
                continue
            steps = (tuple(v.uid for v in offset.loops), _rounded(offset.steps))
            if steps not in ctx.regs.prs:
                ctx.regs.prs[steps] = ctx.regs.loop_prs[0] + len(ctx.regs.prs)
                pr = ctx.regs.prs[steps]
                if pr > ctx.regs.loop_prs[1]:
                    self.unsupported(codes.REGISTERS_EXHAUSTED,
                                     f"loop offsets must fit PR[{ctx.regs.loop_prs[0]}.."
                                     f"{ctx.regs.loop_prs[1]}] (needs PR[{pr}])", template.loop.span)
                lines.append(f"PR[{pr}]=LPOS-LPOS")
            ctx.regs.offsets[key] = ctx.regs.prs[steps]
        return lines

    def _vendor_loop(self, template: LoopTemplate, ctx: FanucContext) -> list[str]:
        """`R[v]=first`, `LBL[top]`, this level's offsets, the body, `R[v]=R[v]+1`,
        `IF R[v]<=last,JMP LBL[top]` (the range is never empty here: loops.analyse)."""
        var = template.var
        counter = self._counter(var, ctx, template.loop.span)
        ctx.regs.inner.update(template.inner)
        top = ctx.program.label()
        head = [self.comment(_loop_head(var)[:COMMENT_MAX]),
                f"{counter}={var.first}", f"LBL[{top}]"]
        ctx.regs.reset()
        offsets = self._offset_lines(template, ctx)
        return head + offsets + self.body(template.body, ctx) + [
            f"{counter}={counter}+1", f"IF {counter}<={_tp_number(var.last)},JMP LBL[{top}]"]

    def _counter(self, var: LoopVar, ctx: FanucContext, span: object) -> str:
        """The loop's counter: its variable's register, or one of its own for `repeat`."""
        if var.name is not None:
            return self._reg(var.name, ctx, span)
        if var.uid not in ctx.regs.repeat:
            n = ctx.regs.counter()
            self._within(n, ctx, span)
            ctx.regs.repeat[var.uid] = f"R[{n}:rmot repeat]"
        return ctx.regs.repeat[var.uid]

    def _offset_lines(self, template: LoopTemplate, ctx: FanucContext) -> list[str]:
        """PR[i,j] for every offset used by this level's own moves (not those of nested
        loops): sum over the loops (R[v] - first) * step, one operator per line."""
        done: set[int] = set()
        lines: list[str] = []
        for uid in level_moves(template.body):
            for role in ("target", "via"):
                offset = template.targets.get((uid, role))
                pr = ctx.regs.offsets.get((uid, role))
                if offset is None or pr is None or pr in done:
                    continue
                done.add(pr)
                lines += self._pr_value(pr, offset, ctx, template.loop.span)
        return lines

    def _pr_value(self, pr: int, offset: TargetOffset, ctx: FanucContext,
                  span: object) -> list[str]:
        lines: list[str] = []
        for axis in range(3):
            terms = [(var, step[axis] * 1000.0) for var, step in zip(offset.loops, offset.steps)
                     if abs(step[axis]) > 1e-12]
            if not terms:
                continue
            acc: str | None = None
            for var, mm in terms:
                source = self._counter(var, ctx, span)
                if var.first != 0:
                    t = self._temp(ctx, span)
                    lines.append(f"{t}={source}-{_tp_number(var.first)}")
                    source = t
                if len(terms) == 1:
                    lines.append(f"PR[{pr},{axis + 1}]={source}*{_tp_number(round(mm, 3))}")
                    break
                t = self._temp(ctx, span)
                lines.append(f"{t}={source}*{_tp_number(round(mm, 3))}")
                if acc is None:
                    acc = t
                else:
                    lines.append(f"{acc}={acc}+{t}")
            if acc is not None:
                lines.append(f"PR[{pr},{axis + 1}]={acc}")
        return lines


@dataclass
class _Registers:
    """One task's registers: variable name -> R number (fixed for the task: registers are
    global on the controller, so routines read the same ones), the current statement's
    temporaries above them, and the loop offsets (PR per (move uid, role))."""

    variables: dict[str, int]
    first: int = 1  # this task's registers R[first..last] (TaskContext.register_slice)
    last: int = 200
    loop_prs: tuple[int, int] = (61, 90)  # this task's loop offsets PR[lo..hi]
    frame_prs: tuple[int, int] = (91, 100)  # this task's tool and frame setup PR[lo..hi]
    timer: int = 10  # the TIMER counting this task's polled waits
    payloads: dict[str, int] = field(default_factory=dict)  # load -> its payload schedule
    used: int = 0
    prs: dict[object, int] = field(default_factory=dict)
    offsets: dict[tuple[int, str], int] = field(default_factory=dict)
    inner: dict[int, LoopTemplate] = field(default_factory=dict)
    repeat: dict[int, str] = field(default_factory=dict)  # repeat loop uid -> its counter
    loop_routines: dict[object, str] = field(default_factory=dict)  # (routine, offsets) -> name
    counters: int = 0

    @classmethod
    def of_task(cls, task: TaskContext, body: tuple[ir.Instr, ...]) -> _Registers:
        """The registers of `task`: its own slice of each global range."""
        first, last = task.register_slice(FanucBackend.REG_FIRST, FanucBackend.MAX_REGISTER)
        return cls(task_variables(body, first), first=first, last=last,
                   loop_prs=task.register_slice(FanucBackend.LOOP_PR + 1, FanucBackend.FRAME_PR),
                   frame_prs=task.register_slice(FanucBackend.FRAME_PR + 1, FanucBackend.MAX_PR),
                   timer=task.register_slice(1, FanucBackend.TIMERS)[1])

    def reset(self) -> None:
        self.used = 0

    def temp(self) -> int:
        self.used += 1
        return self.first + len(self.variables) + self.counters + self.used - 1

    def counter(self) -> int:
        """A register of its own for a `repeat` loop's count (never reused as a temporary)."""
        self.counters += 1
        return self.first + len(self.variables) + self.counters - 1


def task_variables(body: tuple[ir.Instr, ...], first: int = FanucBackend.REG_FIRST) -> dict[str, int]:
    """Every variable and loop variable of a task, numbered from `first` in order of first
    appearance."""
    names: list[str] = []
    for node in ir_tree.walk(body):
        name = (node.name if isinstance(node, ir.VarDecl)
                else node.var if isinstance(node, ir.Loop) else None)
        if name is not None and name not in names:
            names.append(name)
    return {name: first + k for k, name in enumerate(names)}


