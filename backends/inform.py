"""Yaskawa Motoman INFORM job files (.JBI) for DX200 / YRC1000 controllers.

Vendor conventions (DX100/DX200 "Job data format" of the offline-teaching interface):
  * file layout: `/JOB`, `//NAME`, `//POS` (`///NPOS C,BC,EC,P,BP,EX`, `///TOOL n`,
    `///POSTYPE ROBOT`, `///RECTAN`, `///RCONF ...`, `Cxxxxx=X,Y,Z,Rx,Ry,Rz`), `//INST`
    (`///DATE`, `///ATTR SC,RW`, `///GROUP1 RB1`), `NOP`, instructions, `END`; one job per
    file, jobs call each other with `CALL JOB:NAME`;
  * numbered tools and frames (the cell's `number n`): a tool's number is its tool file
    (`///TOOL n`); a position moved in a numbered frame is written in that user frame
    (`///USER n`, `///POSTYPE USER`, the TCP relative to the frame) so the controller's
    stored user frame is used; nothing stored is ever written (the job has no instruction
    for it): the header comments give the values the tool files and user frames must hold;
  * other positions are Cartesian in the ROBOT coordinate system (the robot base, as the IR's
    `CartesianTarget.pose`: frames already composed, so no user frame is needed), X Y Z in mm
    and Rx Ry Rz in degrees with R = Rz(Rz)·Ry(Ry)·Rx(Rx) (roll, pitch, yaw about fixed axes);
    the values are the *TCP* of tool file `///TOOL n` — tool n is the n-th tool of the robot
    in the cell (0 = the flange); the tool data to enter in the tool file is printed as
    comments at the top of the job;
  * `///RCONF l,m,n,o,p,q,0,0` from the planned branch and joints: m 0 upper arm (elbow up) /
    1 lower arm and n 0 front / 1 rear from the branch; l 0 flip / 1 no-flip by Yaskawa's own
    rule on the R-axis (J4) position (flip when -90 < R <= 90 deg, modulo 360: NX100 manual,
    "Manipulator Types" — a different cut than ir.Wrist's J5 sign, so it is read from the
    planned J4); o/p/q 1 when the R, T, S axis (J4, J6, J1) lies outside -180 < a <= 180 deg;
  * joint targets: a job's joint positions are encoder pulses (`///POSTYPE PULSE`), whose
    pulses-per-degree are specific to each robot and not in the robot library; a joint move
    is therefore written as `MOVJ` to the Cartesian position of its planned joints with the
    full RCONF (manipulator type + turn flags), which selects exactly those joints — an exact
    lowering, reported as a warning (W450);
  * speeds: `VJ=` % of max joint speed (0.01 % steps), `V=` mm/s (0.1 mm/s steps);
    zones: `PL=0..4` positioning levels with the factory distances `PL_DISTANCES_MM`
    (parameters S1CxG033–036); the nearest level is used with a warning when the blend is
    not one of them; accelerations are not programmable in mm/s^2 (ACC=/DEC= are % of the
    controller's maximum): the controller default is used, with one warning per program
    when the program set a non-default acceleration;
  * I/O: `DOUT OT#(n) ON`, `PULSE OT#(n) T=s` (runs in the background, 0.01 s steps),
    `AOUT AO#(n) volts`, `TIMER T=s`; a wait with timeout is `WAIT IN#(n)=ON T=s` then
    `JUMP *Lk IF IN#(n)=ON`, `MSG "..."`, `PAUSE`, `*Lk`: when the input did not come the job
    stops with a message on the pendant (rmot's timeout semantics, see base.py; WAIT with T=
    alone would continue: NX100/DX100 INFORM manual, WAIT and PAUSE instructions);
  * digital ports: OT#(n) / IN#(n) with n in DIGITAL_PORTS = 1..1024 (general-purpose I/O of
    DX200/YRC1000), AO#(n) in 1..40;
  * payload: a job cannot carry a load: the tool file's weight W and centre of gravity
    Xg/Yg/Zg are printed as comments with the tool data and a tool with a mass warns W411
    once (rmot's centre of gravity: half way flange->TCP, base.tool_cog);
  * circular moves: `MOVC` start (the previous target), via, end with `FPT` (the arc's final
    point), so an arc that follows an arc continues from that point with its via and end only;
  * runtime if: `JUMP *Lnnn IF IN#(n)=...` with labels; procs: one job per routine, named
    `<PROGRAM>_<PROC>` (job names are global on the controller);
  * comments: `'file.rmot:12` (a comment line holds at most 32 characters).
  * sync: independent jobs per controller have no barrier, so the k-th sync of a task is the
    I/O handshake of backends/handshake.py: `DOUT OT#(o) ON` (odd k) or OFF (even k) then
    `WAIT IN#(i)=` the same level, o and i being the robot's `io out[o] = "sync"` /
    `io in[i] = "sync"` of the cell (wired crosswise).

Size limits: a job holds at most `MAX_POSITIONS` (999) taught positions and we keep jobs below
`MAX_INSTRUCTIONS` (300) top-level IR instructions (~1800 INFORM lines); a longer main body is
split into parts `NAME_PART1`, ... called from the main job (W406); a part or routine that is
still too large is an error (E406). Names: job names are upper-case, at most 32 characters
(DX200/YRC1000). The ///DATE line is fixed (2000/01/01 00:00) so output is deterministic.

Support (checked by tests/backends/test_inform.py):
  exact     MOVL/MOVC/MOVJ with Cartesian positions and full RCONF, V/VJ on their steps, PL at
            0/12.5/25/50/100 mm, DOUT, PULSE, AOUT, WAIT (with T), TIMER, if/else, procs as
            jobs, native inform, source comments;
  warned    joint targets as Cartesian + RCONF (W450), acceleration (W408, once), fixed
            duration (W409), speed / zone / time rounding (W402 / W403 / W412), tool payload (W411), split jobs
            (W406), legalised names (W400/W401), other vendors' native blocks (W407);
  lowered   sync as the I/O handshake (odd count W410);
  refused   sync without the cell's "sync" signals (E409) or inside an if arm (E405), ports
            outside OT#/IN# 1..1024, AO# 1..40 or +-14 V (E404), positions without a full branch
            (E402), an arc with no preceding move (E451), a job above 999 positions (E406), moves
            without a planned solution (E401).
"""

from __future__ import annotations

import math
from collections.abc import Hashable
from dataclasses import dataclass, field, replace

import numpy as np

from rmot.backends import codes, codes_b
from rmot.backends.base import Backend, TaskContext, key_value, euler_zyx_deg, fmt, fmt_list, header_lines, position_mm, tool_cog
from rmot.backends.controller_data import NumberedData, frame_number
from rmot.backends.lowering import routine_names, split_body
from rmot.backends.names import NameRules
from rmot.compiler import ir, planned
from rmot.backends.safe_text import comment_safe

__all__ = ["InformBackend", "PL_DISTANCES_MM", "rconf"]

PL_DISTANCES_MM = (0.0, 12.5, 25.0, 50.0, 100.0)
MAX_POSITIONS = 999
MAX_TOOL_FILE = 63  # DX200/YRC1000 tool files 0..63 (YRC1000 INSTRUCTIONS, "Tool file")
MAX_USER_FRAME = 63  # user coordinates 1..63 (YRC1000 INSTRUCTIONS, "User coordinates")
MAX_INSTRUCTIONS = 300
COMMENT_WIDTH = 32
INFORM_RULES = NameRules(max_len=32, allowed="A-Za-z0-9_", first="A-Za-z", upper=True, prefix="J",
                         # INFORM instruction words (YRC1000 INSTRUCTIONS manual, instruction list)
                         reserved=frozenset({"NOP", "END", "CALL", "JUMP", "MOVJ", "MOVL", "MOVC",
                                             "MOVS", "IMOV", "DOUT", "DIN", "AOUT", "PULSE", "WAIT",
                                             "TIMER", "PAUSE", "MSG", "RET", "IF", "ENDIF", "ELSE",
                                             "WHILE", "ENDWHILE", "FOR", "NEXT", "SET", "ADD", "SUB",
                                             "MUL", "DIV", "INC", "DEC", "GETS", "CLEAR", "SFTON",
                                             "SFTOF", "TOOLON", "TOOLOF", "SPEED", "LABEL"}))
DATE = "2000/01/01 00:00"


def rconf(branch: ir.Config, q: np.ndarray) -> str:
    """`l,m,n,o,p,q,0,0` (NX100/DX100 "manipulator type").

    l: 0 flip / 1 no-flip by Yaskawa's rule on the R axis (J4) position: flip when
    -90 < R <= 90, 270 < R <= 360 or -360 < R <= -270 (not the J5 sign ir.Wrist uses);
    m: 0 upper arm (elbow UP) / 1 lower arm; n: 0 front / 1 rear (from the branch);
    o, p, q: 1 when the R, T, S axis angle lies outside -180 < angle <= 180.
    """
    r = math.degrees(q[3])
    flip = -90.0 < r <= 90.0 or r > 270.0 or r <= -270.0
    turn = [0 if -180.0 < math.degrees(q[i]) <= 180.0 else 1 for i in (3, 5, 0)]
    bits = [0 if flip else 1,
            0 if branch.elbow is ir.Elbow.UP else 1,
            0 if branch.shoulder is ir.Shoulder.FRONT else 1, *turn, 0, 0]
    return ",".join(str(b) for b in bits)


def position_values(pose: ir.Pose) -> str:
    """`X,Y,Z,Rx,Ry,Rz`: mm with 3 places, degrees with 4 places."""
    rz, ry, rx = euler_zyx_deg(pose)
    return ",".join([*(fmt(v, 3) for v in position_mm(pose)), *(fmt(v, 4) for v in (rx, ry, rz))])


@dataclass
class _Position:
    tool: int
    conf: str
    values: str
    user: int | None = None  # user frame number (`///USER n`, POSTYPE USER); None: ROBOT


@dataclass
class _Job:
    """One job being printed: its taught positions, its label counter, its lines."""

    name: str
    positions: list[_Position] = field(default_factory=list)
    labels: int = 0

    def add(self, pos: _Position) -> str:
        self.positions.append(pos)
        return f"C{len(self.positions) - 1:05d}"


def predecessors(body: tuple[ir.Instr, ...], last: ir.Move | None = None,
                 out: dict[int, ir.Move | None] | None = None) -> tuple[dict[int, ir.Move | None], ir.Move | None]:
    """For each move uid, the move executed just before it (None when unknown statically)."""
    out = {} if out is None else out
    for node in body:
        if isinstance(node, ir.Move):
            out[node.uid] = last
            last = node
        elif isinstance(node, ir.ProcCall):
            _, last = predecessors(node.body, last, out)
        elif isinstance(node, ir.If):
            _, a = predecessors(node.then, last, out)
            _, b = predecessors(node.otherwise, last, out)
            last = a if a is b else None
    return out, last


@dataclass(frozen=True)
class InformContext(TaskContext):
    """One task's context plus what printing it uses and collects: routine names, each move's
    predecessor, tool numbers, the finished job files and the job being printed."""

    routine_of: dict[int, str]
    preds: dict[int, ir.Move | None]
    tools: dict[str | None, int]
    user_frames: dict[int, tuple[str, ir.Pose]] = field(default_factory=dict)  # numbered frames used
    files: dict[str, str] = field(default_factory=dict)
    job: _Job = field(default_factory=lambda: _Job(""))


class InformBackend(Backend):
    name = "inform"
    file_ext = ".JBI"
    COMMENT = "'"
    UNITS = {"length": "mm", "angle": "deg", "linear_speed": "mm/s", "joint_speed": "%",
             "zone": "PL level", "time": "s", "analog": "V"}
    SYNC_HANDSHAKE = True  # sync -> the I/O handshake of backends/handshake.py
    NAME_RULES = INFORM_RULES
    DIGITAL_PORTS = (1, 1024)  # OT# / IN# general-purpose I/O
    ANALOG_PORTS = (1, 40)  # AO#
    MAX_TCP_SPEED = 1.5  # m/s
    MAX_TCP_SPEED_SOURCE = "DX100/DX200 INFORM manual, MOVL/MOVC: V= 0.1..1500.0 mm/s"
    NO_RECORD_NOTE = None

    # ------------------------------------------------------------------ jobs

    def emit_task(self, task: TaskContext) -> dict[str, str]:
        names, main, body = self.open_task(task)
        split = split_body(body, MAX_INSTRUCTIONS, task.program_name)
        if split is not body:
            self.warn(codes.PROGRAM_SPLIT, f"job '{main}' must hold at most {MAX_INSTRUCTIONS} "
                      f"instructions (got more); split into {len(split)} parts", task.task.span)
        ctx = task.with_state(InformContext, routine_of={},
                              preds=predecessors(body)[0], tools=self.tool_numbers(task))
        # job names are global on the controller: a proc's job carries the program's name
        # (MAIN_APPROACH), so two programs' procs of one name never overwrite each other; the
        # split parts already do (NAME_PART1)
        parts = {p.uid for p in split} if split is not body else set()
        table = routine_names(split, key=lambda call: self.routine_key(call, ctx))  # keys read ctx.preds
        ctx.routine_of.update({uid: names.name(r if uid in parts else f"{main}_{r}")
                               for uid, r in table.items()})
        self.job(main, split, ctx)
        self.extend(names.diagnostics)
        return dict(sorted(ctx.files.items()))

    def job(self, name: str, body: tuple[ir.Instr, ...], task: InformContext) -> None:
        ctx = replace(task, job=_Job(name))
        job = ctx.job
        inst = self.body(body, ctx)
        if len(job.positions) > MAX_POSITIONS:
            self.unsupported(codes.PROGRAM_TOO_LONG, f"job '{name}' must hold at most "
                             f"{MAX_POSITIONS} positions (got {len(job.positions)})", ctx.task.span)
        head = [c for line in header_lines(ctx.plan, self.name, self.findings_header)
                for c in self.wrap(line)] + self.tool_comments(ctx)
        text = (["/JOB", f"//NAME {name}"] + self.pos_section(job) +
                ["//INST", f"///DATE {DATE}", f"///COMM {ctx.plan.program.name[:32]}",
                 "///ATTR SC,RW", "///GROUP1 RB1", "NOP"] + head + inst + ["END"])
        ctx.files[f"{name}{self.file_ext}"] = "\n".join(text) + "\n"

    @staticmethod
    def pos_section(job: _Job) -> list[str]:
        lines = ["//POS", f"///NPOS {len(job.positions)},0,0,0,0,0"]
        tool: int | None = None
        conf: str | None = None
        user: int | None = None
        for k, pos in enumerate(job.positions):
            if k > 0 and pos.user != user:  # another coordinate system: restate it all
                tool = conf = None
            if pos.user is not None and (k == 0 or pos.user != user):
                lines.append(f"///USER {pos.user}")
            if pos.tool != tool:
                lines.append(f"///TOOL {pos.tool}")
                tool = pos.tool
            if k == 0 or pos.user != user:
                lines += [f"///POSTYPE {'ROBOT' if pos.user is None else 'USER'}", "///RECTAN"]
                user = pos.user
            if pos.conf != conf:
                lines.append(f"///RCONF {pos.conf}")
                conf = pos.conf
            lines.append(f"C{k:05d}={pos.values}")
        return lines

    # ------------------------------------------------------------------ text helpers

    def comment(self, text: str) -> str:
        """`'text`, cut to the controller's 32 characters (the end is kept: `file:line`)."""
        return "'" + comment_safe(text)[-(COMMENT_WIDTH - 1):] if text else "'"

    def wrap(self, text: str) -> list[str]:
        """A long comment as several 32-character comment lines."""
        step, text = COMMENT_WIDTH - 1, comment_safe(text)
        return ["'" + text[i:i + step] for i in range(0, len(text), step)] or ["'"]

    def tool_numbers(self, ctx: TaskContext) -> dict[str | None, int]:
        """Tool file numbers: the cell's `number n` where given (0..MAX_TOOL_FILE, else E410),
        the others 1, 2, ... in cell order skipping every given number; 0 = the flange."""
        tools = [t for t in ctx.plan.program.cell.tools if t.robot == ctx.robot.name]
        table = NumberedData({t.number for t in tools if t.number is not None}, 1)
        for t in tools:
            if t.number is not None and not 0 <= t.number <= MAX_TOOL_FILE:
                self.unsupported(codes.NUMBER_OUT_OF_RANGE, f"tool '{t.name}' number must be in "
                                 f"0..{MAX_TOOL_FILE} for a tool file (got {t.number})", t.span)
        return {None: 0, **{t.name: table.number(t.name, t.number, t.tcp) for t in tools}}

    def tool_comments(self, ctx: InformContext) -> list[str]:
        out: list[str] = []
        for t in ctx.plan.program.cell.tools:
            if t.robot != ctx.robot.name:
                continue
            rz, ry, rx = euler_zyx_deg(t.tcp)
            x, y, z = position_mm(t.tcp)
            out += self.wrap(f"TOOL {ctx.tools[t.name]} = {t.name}")
            out.append(f"'XYZ {fmt(x, 3)},{fmt(y, 3)},{fmt(z, 3)}"[:COMMENT_WIDTH])
            out.append(f"'RXYZ {fmt(rx, 4)},{fmt(ry, 4)},{fmt(rz, 4)}"[:COMMENT_WIDTH])
            if t.mass > 0:
                cog = fmt_list((c * 1000.0 for c in tool_cog(t)), 1)
                out.append(f"'W {fmt(t.mass, 3)} G {cog}"[:COMMENT_WIDTH])
        for n, (fname, pose) in sorted(ctx.user_frames.items()):
            rz, ry, rx = euler_zyx_deg(pose)
            x, y, z = position_mm(pose)
            out += self.wrap(f"USER {n} = {fname}")
            out.append(f"'XYZ {fmt(x, 3)},{fmt(y, 3)},{fmt(z, 3)}"[:COMMENT_WIDTH])
            out.append(f"'RXYZ {fmt(rx, 4)},{fmt(ry, 4)},{fmt(rz, 4)}"[:COMMENT_WIDTH])
        return out

    # ------------------------------------------------------------------ motion

    def position(self, rec: planned.InstructionRecord, q: np.ndarray | None, pose: ir.Pose | None,
                 node: ir.Move, ctx: InformContext) -> str | None:
        """Register a taught position (TCP pose + RCONF) in the current job; its C name."""
        branch = rec.branch
        if pose is None or q is None or branch is None or None in (branch.shoulder, branch.elbow, branch.wrist):
            self.unsupported(codes.NO_BRANCH, "INFORM positions must have a TCP pose and a full "
                             "6-axis branch (got none: not a 6R arm, or no plan)", node.span)
            return None
        tool = ctx.tools.get(node.tool.name, 0)
        user = frame_number(ctx.plan.program.cell, node.frame.name)
        if user is not None:  # a numbered cell frame: the position in that user frame
            if not 1 <= user <= MAX_USER_FRAME:
                self.unsupported(codes.NUMBER_OUT_OF_RANGE, f"frame '{node.frame.name}' number must be "
                                 f"in 1..{MAX_USER_FRAME} for a user frame (got {user})", node.span)
            ctx.user_frames[user] = (node.frame.name, node.frame.pose)  # type: ignore[assignment]
            pose = node.frame.pose.inverse() * pose
        return ctx.job.add(_Position(tool, rconf(branch, q), position_values(pose), user))

    def move(self, node: ir.Move, ctx: InformContext) -> list[str]:
        rec = self.move_record(node, ctx)
        if isinstance(rec, list):
            return rec
        self.motion_notes(node, ctx)
        pl = self.zone(rec.blend_radius, node)
        if node.kind is ir.MotionKind.JOINT:
            c = self.position(rec, rec.q_target, rec.tcp_pose, node, ctx)
            if isinstance(node.target, ir.JointTarget):
                self.warn(codes_b.JOINT_AS_CARTESIAN, "joint target written as the Cartesian "
                          "position of its planned joints with full RCONF (pulse counts per "
                          "degree are robot-specific)", node.span)
            return [f"MOVJ {c} VJ={self.joint_speed(node)}{pl}"] if c else []
        v = self.linear_speed(node)
        if node.kind is ir.MotionKind.LINEAR:
            c = self.position(rec, rec.q_target, rec.tcp_pose, node, ctx)
            return [f"MOVL {c} V={v}{pl}"] if c else []
        return self.circular(node, rec, ctx, v, pl)

    def context_key(self, node: ir.Instr, ctx: TaskContext) -> Hashable:
        """An arc's printed start point is the move before it (maybe outside the proc)."""
        if not isinstance(node, ir.Move) or node.kind is not ir.MotionKind.CIRCULAR:
            return None
        prev = ctx.preds.get(node.uid)  # type: ignore[attr-defined]
        rec = ctx.record(prev) if prev is not None else None
        if prev is None or rec is None:
            return ("no-start",)
        return (prev.kind, key_value(rec.q_target), key_value(rec.tcp_pose), key_value(prev.tool))

    def circular(self, node: ir.Move, rec: planned.InstructionRecord, ctx: InformContext,
                 v: str, pl: str) -> list[str]:
        """MOVC start (the previous target), via, end `FPT`.

        FPT marks the arc's end point, so a following arc starts there: after an arc only the
        via and end lines are printed (continuous arcs, DX100 circular interpolation rules).
        """
        prev = ctx.preds.get(node.uid)
        prev_rec = ctx.record(prev) if prev is not None else None
        if node.via is None or rec.q_via is None or prev_rec is None or prev_rec.q_target is None:
            self.unsupported(codes_b.CIRCULAR_VIA_MISSING, "an INFORM circular move must follow a "
                             "move in the same block and carry its planned via point (got none)",
                             node.span)
            return []
        lines: list[str] = []
        if prev.kind is not ir.MotionKind.CIRCULAR:  # type: ignore[union-attr]
            start = self.position(prev_rec, prev_rec.q_target, prev_rec.tcp_pose, node, ctx)
            lines.append(f"MOVC {start} V={v}")
        via = self.position(rec, rec.q_via, node.via.pose, node, ctx)
        end = self.position(rec, rec.q_target, rec.tcp_pose, node, ctx)
        if any(c is None for c in (via, end)) or any("None" in line for line in lines):
            return []
        return lines + [f"MOVC {via} V={v}", f"MOVC {end} V={v}{pl} FPT"]

    def motion_notes(self, node: ir.Move, ctx: InformContext) -> None:
        self.warn_accel(node, ctx, "INFORM sets acceleration only as % of the controller's "
                        "maximum (ACC=/DEC=); the controller default is used")
        self.warn_payload(node, ctx, f"tool file {ctx.tools.get(node.tool.name, 0)} (W, Xg, Yg, Zg)")
        if node.motion.duration is not None:
            self.warn(codes.DURATION_IGNORED, f"INFORM has no fixed-duration move; the duration "
                      f"{node.motion.duration:g} s is expressed by the speed only", node.span)

    def joint_speed(self, node: ir.Move) -> str:
        pct = node.motion.joint_speed * 100.0
        text = fmt(min(100.0, max(0.01, pct)), 2)
        if abs(float(text) - pct) > 1e-9:
            self.warn(codes.SPEED_ROUNDED, f"joint speed must be a multiple of 0.01 % in 0.01..100 % "
                      f"(got {pct:g} %); VJ={text} used", node.span)
        return text

    def linear_speed(self, node: ir.Move) -> str:
        mm_s = self.tcp_speed_within_limit(node) * 1000.0  # W417 above MAX_TCP_SPEED
        text = fmt(max(0.1, mm_s), 1)
        if abs(float(text) - mm_s) > 1e-6:
            self.warn(codes.SPEED_ROUNDED, f"TCP speed must be a multiple of 0.1 mm/s "
                      f"(got {mm_s:g} mm/s); V={text} used", node.span)
        return text

    def zone(self, radius: float, node: ir.Move) -> str:
        mm = radius * 1000.0
        level = min(range(len(PL_DISTANCES_MM)), key=lambda k: (abs(PL_DISTANCES_MM[k] - mm), k))
        if abs(PL_DISTANCES_MM[level] - mm) > 1e-6:
            self.warn(codes.ZONE_ROUNDED, f"blend radius must be one of the PL distances "
                      f"{', '.join(f'{d:g}' for d in PL_DISTANCES_MM)} mm (got {mm:g} mm); "
                      f"PL={level} ({PL_DISTANCES_MM[level]:g} mm) used", node.span)
        return f" PL={level}"

    # ------------------------------------------------------------------ I/O and timing

    def seconds(self, value: float, node: ir.Instr, what: str) -> str:
        text = fmt(value, 2)
        if abs(float(text) - value) > 1e-9:
            self.warn(codes.TIME_ROUNDED, f"{what} must be a multiple of 0.01 s (got {value:g} s); "
                      f"T={text} used", getattr(node, "span", None))
        return text

    def set_digital(self, node: ir.SetDigital, ctx: InformContext) -> list[str]:
        if not self.port_ok(node.port, "digital output", node.span):
            return []
        return [f"DOUT OT#({node.port}) {'ON' if node.value else 'OFF'}"]

    def set_analog(self, node: ir.SetAnalog, ctx: InformContext) -> list[str]:
        if not self.port_ok(node.port, "analog output", node.span, self.ANALOG_PORTS):
            return []
        if not -14.0 <= node.value <= 14.0:
            self.unsupported(codes.BAD_PORT, f"analog output must be in -14..14 V (got {node.value:g} V)", node.span)
            return []
        return [f"AOUT AO#({node.port}) {fmt(node.value, 2)}"]

    def pulse(self, node: ir.Pulse, ctx: InformContext) -> list[str]:
        if not self.port_ok(node.port, "digital output", node.span):
            return []
        return [f"PULSE OT#({node.port}) T={self.seconds(node.duration, node, 'pulse time')}"]

    def wait_time(self, node: ir.WaitTime, ctx: InformContext) -> list[str]:
        # TIMER takes at most 655.35 s: longer waits are several TIMERs (exact).
        out, left = [], node.duration
        while left > 655.35:
            out.append("TIMER T=655.35")
            left -= 655.35
        return out + [f"TIMER T={self.seconds(left, node, 'wait time')}"]

    def condition(self, cond: ir.InputCondition, span: object, negate: bool = False) -> str | None:
        if not self.port_ok(cond.port, "digital input", span):  # type: ignore[arg-type]
            return None
        return f"IN#({cond.port})={'ON' if cond.value != negate else 'OFF'}"

    def wait_input(self, node: ir.WaitInput, ctx: InformContext) -> list[str]:
        test = self.condition(node.condition, node.span)
        if test is None:
            return []
        if node.timeout is None:
            return [f"WAIT {test}"]
        done, c = self.label(ctx), node.condition
        message = f"IN#({c.port}) TIMEOUT"  # MSG holds at most 32 characters
        return [f"WAIT {test} T={self.seconds(node.timeout, node, 'timeout')}",
                f"JUMP {done} IF {test}", f'MSG "{message}"', "PAUSE", done]

    @staticmethod
    def label(ctx: InformContext) -> str:
        job = ctx.job
        job.labels += 1
        return f"*L{job.labels:03d}"

    def if_(self, node: ir.If, ctx: InformContext) -> list[str]:
        c = node.condition
        if not isinstance(c, ir.InputCondition):  # conditions over variables: issue #15
            self.unsupported(codes.UNSUPPORTED, f"if on a {type(c).__name__} must be expressible "
                             f"for {self.name} (it is not yet)", node.span)
            return [self.comment(f"UNSUPPORTED if on a {type(c).__name__}")]
        test = self.condition(c, node.span, negate=True)
        if test is None:
            return []
        skip = self.label(ctx)
        then = self.body(node.then, ctx)
        if not node.otherwise:
            return [f"JUMP {skip} IF {test}", *then, skip]
        done = self.label(ctx)
        return [f"JUMP {skip} IF {test}", *then, f"JUMP {done}", skip, *self.body(node.otherwise, ctx), done]

    # ------------------------------------------------------------------ structure

    def proc_call(self, node: ir.ProcCall, ctx: InformContext) -> list[str]:
        name = ctx.routine_of[node.uid]
        if f"{name}{self.file_ext}" not in ctx.files:  # calls printing the same job share it
            self.job(name, node.body, ctx)
        return [f"CALL JOB:{name}"]
