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

Runtime logic (the block at the end of the class): D/R/B variables from 050 with
SET/ADD/SUB/MUL/DIV/INC/DEC, one-comparison `JUMP *L IF` chains, while loops with labels, the
timeout branch by testing the input again after `WAIT ... T=`, polled waits (W431), `stop` =
PAUSE (+ the job's end in the main job; W432 in a called job), `for` loops with INC and SFTON
shifts set by SETE in P variables from P050, or unrolled (W420); analog inputs refused (E430);
a group input read into a byte temporary, `IN Bnnn IG#(n)`, and compared (at most 8 bits; stored or
computed with: E430).

Size limits: a job holds at most `MAX_POSITIONS` (999) taught positions and we keep jobs below
`MAX_INSTRUCTIONS` (300) top-level IR instructions (~1800 INFORM lines); a longer main body is
split into parts `NAME_PART1`, ... called from the main job (W406); a part or routine that is
still too large is an error (E406). Names: job names are upper-case, at most 32 characters
(DX200/YRC1000). The ///DATE line is fixed (2000/01/01 00:00) so output is deterministic.

Support (checked by tests/backends/test_inform.py):
  exact     MOVL/MOVC/MOVJ with Cartesian positions and full RCONF, V/VJ on their steps, PL at
            0/12.5/25/50/100 mm, DOUT, PULSE, AOUT, WAIT (with T), TIMER, if/else, procs as
            jobs, native inform, source comments; a track and a positioner as base (BS1) and
            station (ST1) axes in pulses at the cell's declared scale, a track without one in
            mm (backends/inform_axes.py); a line or arc relative to the turning station as
            SMOVL/SMOVC (backends/inform_coordinated.py);
  warned    joint targets as Cartesian + RCONF (W450), acceleration (W408, once), fixed
            duration (W409), speed / zone / time rounding (W402 / W403 / W412), tool payload (W411), split jobs
            (W406), legalised names (W400/W401), other vendors' native blocks (W407), the
            station's own VJ (W604), whole pulses moving a target > 0.01 mm (W605), station
            axes without a declared scale at an assumed one (W610);
  lowered   sync as the I/O handshake (odd count W410);
  refused   a revolute track or linear station axis without its pulse scale, two
            positioners, or a line or arc while the track moves (E607),
            sync without the cell's "sync" signals (E409) or inside an if arm (E405), ports
            outside OT#/IN# 1..1024, AO# 1..40 or +-14 V (E404), positions without a full branch
            (E402), an arc with no preceding move (E451), a job above 999 positions (E406), moves
            without a planned solution (E401).

Over 600 lines: the InformBackend class alone is 625 lines, and a class is written in one piece
(its methods read its flags and tables)."""

from __future__ import annotations

from collections import Counter
from collections.abc import Hashable
from dataclasses import dataclass, field, replace
from typing import ClassVar

import numpy as np

from rmot.backends import codes, inform_records, native_refs, turns
from rmot.backends.base import Backend, TaskContext, key_value, euler_zyx_deg, fmt, fmt_list, header_lines, position_mm, tool_cog
from rmot.backends.controller_data import NumberedData, frame_number
from rmot.backends.inform_axes import InformAxes, task_axes, warn_pulse_rounding
from rmot.backends.inform_coordinated import is_coordinated, via_pose
from rmot.backends.runtime import blocked_loop_lines
from rmot.backends.loops import (
    LoopTemplate, LoopVar, TargetOffset, analyse, bind_loop_var, level_moves,
)
from rmot.backends.lowering import routine_names, split_body
from rmot.lang import ir, ir_tree, plan_types
from rmot.backends.safe_text import comment_safe
from rmot.lang.record import record
from rmot.backends.inform_text import (
    PL_DISTANCES_MM,
    MAX_POSITIONS,
    MAX_TOOL_FILE,
    MAX_USER_FRAME,
    MAX_INSTRUCTIONS,
    COMMENT_WIDTH,
    INFORM_RULES,
    DATE,
    rconf,
    position_values,
    predecessors,
    _INFORM_OP,
    _INFORM_CMP,
    _Shift,
    _inform_number,
    _value_type,
    _reads,
    _rconf_key,
    _inform_blocker,
    _loop_head,
)

__all__ = ["InformBackend"]


@dataclass
class _Position:
    tool: int
    conf: str
    values: str
    user: int | None = None  # user frame number (`///USER n`, POSTYPE USER); None: ROBOT
    kind: str = ""  # a native record's POSTYPE (PULSE, ROBOT, BASE, USER: inform_records); "": rmot's own


@dataclass
class _Job:
    """One job being printed: its taught positions, its label counter (skipping the labels its
    native lines name), its lines."""

    name: str
    positions: list[_Position] = field(default_factory=list)
    labels: int = 0
    reserved: frozenset[str] = frozenset()
    native: list[str] = field(default_factory=list)  # the lines its native statements were written as
    shifts: list[int] = field(default_factory=list)  # P variables the job declares
    stop_label: str | None = None  # `*Lnnn` before END, where a main job's `stop` jumps
    axes: InformAxes | None = None  # base / station positions (backends/inform_axes.py)
    records: dict[int, int | str] = field(default_factory=dict)  # native records: number named -> written, or why not

    def add(self, pos: _Position) -> str:
        self.positions.append(pos)
        return f"C{len(self.positions) - 1:05d}"


@record
class InformContext(TaskContext):
    """One task's context plus what printing it uses and collects: routine names, each move's
    predecessor, tool numbers, the finished job files and the job being printed."""

    routine_of: dict[int, str]
    preds: dict[int, ir.Move | None]
    tools: dict[str | None, int]
    user_frames: dict[int, tuple[str, ir.Pose]] = field(default_factory=dict)  # numbered frames used
    files: dict[str, str] = field(default_factory=dict)
    job: _Job = field(default_factory=lambda: _Job(""))
    main: str = ""  # the main job's name (where `stop` can end the program)
    vars: _Variables = field(default_factory=lambda: _Variables({}))  # runtime logic
    natives: list[tuple[ir.Native, list[str]]] = field(default_factory=list)  # the task's, as written
    own: list[str] = field(default_factory=list)  # the task's lines the backend wrote itself
    axes: InformAxes | None = None  # the external axes the task drives (backends/inform_axes.py)


GROUP_INPUT_BITS = 8  # IG#(n): one group of 8 general inputs, read into a byte variable


class InformBackend(Backend):
    name = "inform"
    file_ext = ".JBI"
    COMMENT = "'"
    SYNC_HANDSHAKE = True  # sync -> the I/O handshake of backends/handshake.py
    NAME_RULES = INFORM_RULES
    PRINTS_LOOPS = True  # INC on a counting variable with labels and JUMP, targets by SFTON
    RUNTIME_CONDITIONS = True  # JUMP chains over I/O and variables, timeout branches (AIN: E430)
    DIGITAL_PORTS = (1, 1024)  # OT# / IN# general-purpose I/O
    ANALOG_PORTS = (1, 40)  # AO#
    MAX_TCP_SPEED = 1.5  # m/s
    MAX_TCP_SPEED_SOURCE = "DX100/DX200 INFORM manual, MOVL/MOVC: V= 0.1..1500.0 mm/s"
    NO_RECORD_NOTE = None
    EXTERNAL_AXES = True  # BS1 base and ST1 station positions in pulses (backends/inform_axes.py)

    # ------------------------------------------------------------------ jobs

    def emit_task(self, task: TaskContext) -> dict[str, str]:
        names, main, body = self.open_task(task)
        axes = task_axes(self, task, body)
        if isinstance(axes, str):
            return {}
        split = split_body(body, MAX_INSTRUCTIONS, task.program_name)
        if split is not body:
            self.warn(codes.PROGRAM_SPLIT, f"job '{main}' must hold at most {MAX_INSTRUCTIONS} "
                      f"instructions (got more); split into {len(split)} parts", task.task.span)
        ctx = task.with_state(InformContext, routine_of={},
                              preds=predecessors(body)[0], tools=self.tool_numbers(task),
                              main=main, vars=_Variables.of_task(task, body), axes=axes)
        # job names are global on the controller: a proc's job carries the program's name
        # (MAIN_APPROACH), so two programs' procs of one name never overwrite each other; the
        # split parts already do (NAME_PART1)
        parts = {p.uid for p in split} if split is not body else set()
        table = routine_names(split, key=lambda call: self.routine_key(call, ctx))  # keys read ctx.preds
        ctx.routine_of.update({uid: names.name(r if uid in parts else f"{main}_{r}")
                               for uid, r in table.items()})
        self.job(main, split, ctx)
        for node, var in native_refs.clashes(native_refs.INFORM, ctx.natives, ctx.own):
            self.unsupported(codes.NATIVE_CLASH, f"native line names {var}, which this task's jobs also use "
                             "(rmot's variables and loop shifts): it would read or change rmot's value; use "
                             "another number", node.span)
        self.extend(names.diagnostics)
        return dict(sorted(ctx.files.items()))

    def job(self, name: str, body: tuple[ir.Instr, ...], task: InformContext) -> None:
        ctx = replace(task, job=_Job(name, axes=task.axes.fresh() if task.axes else None,
                                     reserved=native_refs.reserved_labels(native_refs.INFORM, body)))
        job = ctx.job
        self._place_records(body, ctx)
        inst = self.body(body, ctx)
        if len(job.positions) > MAX_POSITIONS:
            self.unsupported(codes.PROGRAM_TOO_LONG, f"job '{name}' must hold at most "
                             f"{MAX_POSITIONS} positions (got {len(job.positions)})", ctx.task.span)
        head = [c for line in header_lines(ctx.plan, self.name, self.findings_header)
                for c in self.wrap(line)] + self.tool_comments(ctx)
        head += [c for line in (job.axes.checklist() if job.axes else []) for c in self.wrap(line)]
        inst += [job.stop_label] if job.stop_label else []
        text = (["/JOB", f"//NAME {name}"] + self.pos_section(job) +
                ["//INST", f"///DATE {DATE}", f"///COMM {ctx.plan.program.name[:32]}",
                 "///ATTR SC,RW", *(job.axes.groups() if job.axes else ["///GROUP1 RB1"]), "NOP"]
                + head + ctx.vars.comments() + inst + ["END"])
        ctx.own.extend((Counter(text) - Counter(job.native)).elements())
        ctx.files[f"{name}{self.file_ext}"] = "\n".join(text) + "\n"

    @staticmethod
    def _place_records(body: tuple[ir.Instr, ...], ctx: InformContext) -> None:
        """The job's native position records first in //POS, with the tool file and user frame
        numbers of the compiled job (inform_records)."""
        cell, robot = ctx.plan.program.cell, ctx.robot.name
        for n, rec in inform_records.records_of(body).items():
            tool = next((t for t in cell.tools if t.name == rec.tool and t.robot == robot), None)
            frame = next((f for f in cell.frames if f.name == rec.user), None)
            why = rec.problem
            if not why and ctx.axes:
                why = "the job drives a base axis or a station: its BC/EC positions pair with the C ones"
            elif not why and tool is None and rec.tool != "flange":
                why = f"its TOOL `{rec.tool}` names no tool of robot '{robot}' (or flange)"
            elif not why and rec.user and (frame is None or frame.number is None):
                why = f"its USER `{rec.user}` names no frame the cell numbers (`number n`)"
            if why:
                ctx.job.records[n] = why
                continue
            user = frame.number if frame is not None else None
            if frame is not None and user is not None:
                ctx.user_frames[user] = (frame.name, cell.robot(robot).base.inverse() * frame.pose)
            position = _Position(ctx.tools.get(tool.name if tool else None, 0), rec.conf, rec.values, user, rec.postype)
            ctx.job.records[n] = int(ctx.job.add(position)[1:])

    @staticmethod
    def pos_section(job: _Job) -> list[str]:
        lines = ["//POS", job.axes.npos(len(job.positions), len(job.shifts)) if job.axes
                 else f"///NPOS {len(job.positions)},0,0,{len(job.shifts)},0,0"]
        tool: int | None = None
        conf: str | None = None
        user: int | None = None
        kind = ""
        for k, pos in enumerate(job.positions):
            if k > 0 and (pos.user, pos.kind) != (user, kind):  # another coordinate system: restate it all
                tool = conf = None
            if pos.user is not None and (k == 0 or (pos.user, pos.kind) != (user, kind)):
                lines.append(f"///USER {pos.user}")
            if pos.tool != tool:
                lines.append(f"///TOOL {pos.tool}")
                tool = pos.tool
            if k == 0 or (pos.user, pos.kind) != (user, kind):
                postype = pos.kind or ("ROBOT" if pos.user is None else "USER")
                lines += [f"///POSTYPE {postype}", "///PULSE" if postype == "PULSE" else "///RECTAN"]
                user, kind = pos.user, pos.kind
            if pos.conf != conf and pos.kind != "PULSE":
                lines.append(f"///RCONF {pos.conf}")
                conf = pos.conf
            lines.append(f"C{k:05d}={pos.values}")
        lines += job.axes.pulse_lines() if job.axes else []
        if job.shifts:  # the loop shifts, Cartesian zeros the job sets per iteration
            lines += ["///POSTYPE ROBOT", "///RECTAN"]
            lines += [f"P{n:04d}=0.000,0.000,0.000,0.0000,0.0000,0.0000" for n in job.shifts]
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

    def position(self, rec: plan_types.InstructionRecord, q: np.ndarray | None, pose: ir.Pose | None,
                 node: ir.Move, ctx: InformContext) -> str | None:
        """Register a taught position (TCP pose + RCONF) in the current job; its C name."""
        branch = rec.branch
        if pose is None or q is None or branch is None or None in (branch.shoulder, branch.elbow, branch.wrist):
            self.unsupported(codes.NO_BRANCH, "INFORM positions must have a TCP pose and a full "
                             "6-axis branch (got none: not a 6R arm, or no plan)", node.span)
            return None
        tool = ctx.tools.get(node.tool.name, 0)
        # with external axes every position is in ROBOT coordinates (backends/inform_axes.py)
        user = None if ctx.axes else frame_number(ctx.plan.program.cell, node.frame.name)
        if user is not None:  # a numbered cell frame: the position in that user frame
            if not 1 <= user <= MAX_USER_FRAME:
                self.unsupported(codes.NUMBER_OUT_OF_RANGE, f"frame '{node.frame.name}' number must be "
                                 f"in 1..{MAX_USER_FRAME} for a user frame (got {user})", node.span)
            ctx.user_frames[user] = (node.frame.name, node.frame.pose)  # type: ignore[assignment]
            pose = node.frame.pose.inverse() * pose
        far = turns.beyond_one_turn(q, (0, 3, 5))  # RCONF's flags
        if far and node.kind is ir.MotionKind.JOINT:  # MOVL/MOVC run on from the current joints
            self.unsupported(codes.TURN_NOT_EXPRESSIBLE,
                             turns.message(q, far, "RCONF's R/T/S flags"), node.span)
        return ctx.job.add(_Position(tool, rconf(branch, q), position_values(pose), user))

    def move(self, node: ir.Move, ctx: InformContext) -> list[str]:
        rec = self.move_record(node, ctx)
        if isinstance(rec, list):
            return rec
        self.motion_notes(node, ctx)
        lines = self.by_kind(node)(node, rec, ctx, self.zone(rec.blend_radius, node))
        axes = ctx.job.axes
        if axes is None:
            return lines
        warn_pulse_rounding(self, node, rec, axes, ctx)
        if is_coordinated(node):  # SMOVL/SMOVC relative to the station (backends/inform_coordinated.py)
            return axes.coordinated_lines(lines, node, rec)
        vj = self.joint_speed(node) if axes.station else ""  # the station's +MOVJ speed
        return [axes.operands(line, dict(node.ext), vj) for line in lines]

    def move_joint(self, node: ir.Move, rec: plan_types.InstructionRecord, ctx: InformContext,
                   pl: str) -> list[str]:
        c = self.position(rec, rec.q_target, rec.tcp_pose, node, ctx)
        if isinstance(node.target, ir.JointTarget):
            self.warn(codes.JOINT_AS_CARTESIAN, "joint target written as the Cartesian "
                      "position of its planned joints with full RCONF (pulse counts per "
                      "degree are robot-specific)", node.span)
        # ACC=/DEC=: acceleration and deceleration ratios, 20..100 % (YRC1000 INFORM manual,
        # MOVJ tags): the plan's joint acceleration share
        pct = self.accel_percent(node, rec, ctx, 20, "INFORM's ACC=/DEC= take 20..100 % of the maximum")
        acc = "" if pct is None else f" ACC={pct} DEC={pct}"
        movj = [f"MOVJ {c} VJ={self.joint_speed(node)}{pl}{acc}"] if c else []
        return self.shifted(node, movj, ctx)

    def move_linear(self, node: ir.Move, rec: plan_types.InstructionRecord, ctx: InformContext,
                    pl: str) -> list[str]:
        v = self.linear_speed(node)
        c = self.position(rec, rec.q_target, rec.tcp_pose, node, ctx)
        return self.shifted(node, [f"MOVL {c} V={v}{pl}"] if c else [], ctx)

    def move_circular(self, node: ir.Move, rec: plan_types.InstructionRecord, ctx: InformContext,
                      pl: str) -> list[str]:
        return self.circular(node, rec, ctx, self.linear_speed(node), pl)

    def context_key(self, node: ir.Instr, ctx: TaskContext) -> Hashable:
        """An arc's printed start point is the move before it (maybe outside the proc)."""
        if not isinstance(node, ir.Move) or node.kind is not ir.MotionKind.CIRCULAR:
            return None
        prev = ctx.preds.get(node.uid)  # type: ignore[attr-defined]
        rec = ctx.record(prev) if prev is not None else None
        if prev is None or rec is None:
            return ("no-start",)
        return (prev.kind, is_coordinated(prev), key_value(rec.q_target), key_value(rec.tcp_pose),
                key_value(prev.tool))

    def circular(self, node: ir.Move, rec: plan_types.InstructionRecord, ctx: InformContext,
                 v: str, pl: str) -> list[str]:
        """MOVC start (the previous target), via, end `FPT`.

        FPT marks the arc's end point, so a following arc starts there: after an arc only the
        via and end lines are printed (continuous arcs, DX100 circular interpolation rules).
        """
        prev = ctx.preds.get(node.uid)
        prev_rec = ctx.record(prev) if prev is not None else None
        if node.via is None or rec.q_via is None or prev_rec is None or prev_rec.q_target is None:
            self.unsupported(codes.CIRCULAR_VIA_MISSING, "an INFORM circular move must follow a "
                             "move in the same block and carry its planned via point (got none)",
                             node.span)
            return []
        lines: list[str] = []
        # an arc after a move that is no arc, or after an arc of the other kind (MOVC / SMOVC), restates its start
        if prev.kind is not ir.MotionKind.CIRCULAR or is_coordinated(prev) != is_coordinated(node):  # type: ignore[union-attr,arg-type]
            start = self.position(prev_rec, prev_rec.q_target, prev_rec.tcp_pose, node, ctx)
            lines.append(f"MOVC {start} V={v}")
        via = self.position(rec, rec.q_via, via_pose(node, rec), node, ctx)
        end = self.position(rec, rec.q_target, rec.tcp_pose, node, ctx)
        if any(c is None for c in (via, end)) or any("None" in line for line in lines):
            return []
        return lines + [f"MOVC {via} V={v}", f"MOVC {end} V={v}{pl} FPT"]

    def motion_notes(self, node: ir.Move, ctx: InformContext) -> None:
        if node.kind is not ir.MotionKind.JOINT:  # joint moves write ACC=/DEC= (move_joint)
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
        branch = (self.body(node.on_timeout, ctx) if node.on_timeout
                  else [f'MSG "{message}"', "PAUSE"])
        return [f"WAIT {test} T={self.seconds(node.timeout, node, 'timeout')}",
                f"JUMP {done} IF {test}", *branch, done]

    @staticmethod
    def label(ctx: InformContext) -> str:
        job = ctx.job
        job.labels += 1
        while f"L{job.labels:03d}" in job.reserved:
            job.labels += 1
        return f"*L{job.labels:03d}"

    def native(self, node: ir.Native, ctx: InformContext) -> list[str]:  # type: ignore[override]
        if node.vendor.lower() == self.name and inform_records.number_of(node.text) is not None:
            return []  # a position record: in //POS (_place_records), refused at the lines that move to it
        lines = super().native(node, ctx)
        if node.vendor.lower() != self.name:
            return lines
        lines = self._to_records(node, lines, ctx)
        ctx.job.native.extend(lines)
        ctx.natives.append((node, lines))
        return lines

    def _to_records(self, node: ir.Native, lines: list[str], ctx: InformContext) -> list[str]:
        """Native lines moving to robot positions of their job, renamed to where the records
        were written (inform_records); a position with no record written is refused."""
        named = native_refs.positions_named(native_refs.INFORM, lines)
        placed = {p: ctx.job.records.get(int(p[1:])) if p.startswith("C") else None for p in named}
        why = next((f"{p}, whose record cannot be written: {w}" for p, w in placed.items() if isinstance(w, str)), None)
        why = why or next((f"{p}, a position of the job it came from with no native position record `{p}{{..}}` in this "
                           f"job: this backend numbers the job's positions for rmot's moves, so {p} here is another "
                           "point or none (write the move as an rmot `move`)" for p, w in placed.items() if w is None), None)
        if why is not None:
            self.unsupported(codes.NATIVE_CLASH, f"native line names {why}", node.span)
            return lines
        numbers = {int(p[1:]): w for p, w in placed.items() if isinstance(w, int)}
        return [inform_records.renamed(line, numbers) for line in lines]

    def if_(self, node: ir.If, ctx: InformContext) -> list[str]:
        if not isinstance(node.condition, ir.InputCondition):  # any condition
            return self._if_condition(node, ctx)
        test = self.condition(node.condition, node.span, negate=True)
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
        shifted = tuple(ctx.vars.offsets.get((m.uid, "target"), (None,))[0]
                        for m in ir_tree.walk(node.body) if isinstance(m, ir.Move))
        if any(s is not None for s in shifted):  # a call in a loop with shifted moves
            key = (name, shifted)
            if key not in ctx.vars.loop_jobs:
                ctx.vars.loop_jobs[key] = f"{name}_L{len(ctx.vars.loop_jobs) + 1}"[:32]
            name = ctx.vars.loop_jobs[key]
        if f"{name}{self.file_ext}" not in ctx.files:  # calls printing the same job share it
            self.job(name, node.body, ctx)
        return [f"CALL JOB:{name}"]

    # ------------------------------------------------------------------ runtime logic
    # Variables are the controller's numbered variables (YRC1000 INSTRUCTIONS manual, "Variables";
    # the arithmetic instructions SET, ADD, SUB, MUL, DIV, INC work in place on their first
    # operand): int -> D (32-bit integer), num -> R (real), bool -> B (0/1), from VAR_FIRST in
    # order of first declaration, then the current statement's temporaries (a job cannot name
    # them: a comment lists them at the top of each job). `JUMP *L IF` takes one comparison
    # (variable on the left, variable or constant on the right; =, <>, <, <=, >, >=), so
    # and/or/not become chains of jumps. Loop shifts are P variables from PVAR_FIRST, declared
    # in //POS (`///NPOS c,0,0,p,0,0`, `Pnnnn=` lines, as real jobs carry them) and set per
    # iteration with SETE (elements in 0.001 mm); a shifted move is wrapped in `SFTON Pnnn RF`
    # (or `UF#(n)` for a numbered user frame) ... `SFTOF` (YRC1000 INSTRUCTIONS, SFTON/SFTOF,
    # SETE; real jobs: `SFTON P013` / `CALL JOB:..` / `SFTOF`, `SETE P000 (3) D000`).

    VAR_FIRST: ClassVar[int] = 50
    MAX_VAR: ClassVar[int] = 99  # B/I/D/R/P000..099: the default variable counts of DX200/YRC1000
    PVAR_FIRST: ClassVar[int] = 50
    # Variables are global on the controller, which the program's tasks may share: each task
    # numbers its own slice of 050..099 (TaskContext.register_slice; lang/REFERENCE.md §8).
    POLL_STEP: ClassVar[float] = 0.01  # s, the TIMER step of a polled wait
    LETTER: ClassVar[dict[ir.ValueType, str]] = {ir.ValueType.INT: "D", ir.ValueType.NUM: "R",
                                                 ir.ValueType.BOOL: "B"}

    def _var(self, name: str, ctx: InformContext, span: object) -> str:
        found = ctx.vars.variables.get(name)
        if found is None:
            self.unsupported(codes.LOGIC_UNSUPPORTED,
                             f"variable '{name}' must be declared in the task (got a reference to "
                             "an undeclared one)", span)  # type: ignore[arg-type]
            return "D000"
        return self._numbered(found[0], found[1], span, ctx)

    def _numbered(self, vtype: ir.ValueType, n: int, span: object, ctx: InformContext) -> str:
        if n > ctx.vars.last:
            self.unsupported(codes.REGISTERS_EXHAUSTED, f"the program must fit variables "
                             f"{ctx.vars.first:03d}..{ctx.vars.last:03d} of each type (needs "
                             f"{self.LETTER[vtype]}{n:03d})", span)  # type: ignore[arg-type]
        return f"{self.LETTER[vtype]}{n:03d}"

    def _temp(self, vtype: ir.ValueType, ctx: InformContext, span: object) -> str:
        return self._numbered(vtype, ctx.vars.temp(vtype), span, ctx)

    def var_decl(self, node: ir.VarDecl, ctx: InformContext) -> list[str]:
        return self._store(node.name, node.init, node, ctx)

    def assign(self, node: ir.Assign, ctx: InformContext) -> list[str]:
        return self._store(node.name, node.value, node, ctx)

    def _store(self, name: str, value: ir.RtExpr, node: ir.Instr, ctx: InformContext) -> list[str]:
        ctx.vars.reset()
        target = self._var(name, ctx, node.span)
        if isinstance(value, ir.Arith) and not _reads(value.right, name):  # in place, no temporary
            lines, a = self._value(value.left, ctx, node)
            more, b = self._value(value.right, ctx, node)
            if a != target:
                lines.append(f"SET {target} {a}")
            if b == "1" and value.op in "+-" and value.type is ir.ValueType.INT:
                return lines + more + [f"{'INC' if value.op == '+' else 'DEC'} {target}"]
            return lines + more + [f"{_INFORM_OP[value.op]} {target} {b}"]
        lines, a = self._value(value, ctx, node)
        return lines + [f"SET {target} {a}"]

    def _value(self, e: ir.RtExpr, ctx: InformContext, node: ir.Instr) -> tuple[list[str], str]:
        """(lines computing it, the operand): a constant, a variable or a temporary."""
        if isinstance(e, ir.Const):
            return [], _inform_number(e.value)
        if isinstance(e, ir.VarRef):
            return [], self._var(e.name, ctx, node.span)
        if isinstance(e, ir.Arith):
            lines, a = self._value(e.left, ctx, node)
            more, b = self._value(e.right, ctx, node)
            t = self._temp(e.type, ctx, node.span)
            return lines + more + [f"SET {t} {a}", f"{_INFORM_OP[e.op]} {t} {b}"], t
        if isinstance(e, ir.GroupInput):  # a byte IG# fills: compared (`_test`), not computed with
            self.unsupported(codes.LOGIC_UNSUPPORTED, f"gin[{e.port}] must be compared with a value on INFORM "
                             "(a job tests the byte IN ... IG# fills; rmot does not store or compute with it)", node.span)
            return [], "0"
        if isinstance(e, ir.AnalogInput):
            self.unsupported(codes.LOGIC_UNSUPPORTED, f"analog input ain[{e.port}] must be "
                             "readable by a job (INFORM reads analog inputs only through the "
                             "optional analog I/O functions; rmot does not write them)", node.span)
            return [], "0"
        t, skip = self._temp(ir.ValueType.BOOL, ctx, node.span), self.label(ctx)
        return [f"SET {t} 0", *self._jump(e, skip, False, ctx, node), f"SET {t} 1", skip], t

    def _operand(self, e: ir.RtExpr, ctx: InformContext, node: ir.Instr) -> tuple[list[str], str]:
        """A comparison's operand: a group input's byte, or any value (`_value`)."""
        return self._group_input(e, ctx, node) if isinstance(e, ir.GroupInput) else self._value(e, ctx, node)

    def _group_input(self, e: ir.GroupInput, ctx: InformContext, node: ir.Instr) -> tuple[list[str], str]:
        """`IN Bt IG#(n)`: group input n (8 general inputs) read into a byte variable, 0..255
        (DX100/YRC1000 INFORM manual, I/O instructions: IN <byte variable> IG#(n)); a byte is
        what a job compares. A group the cell does not declare at most 8 bits wide could hold
        more than IG# reads: refused."""
        if e.bits is None or e.bits > GROUP_INPUT_BITS:
            self.unsupported(codes.LOGIC_UNSUPPORTED, f"gin[{e.port}] must be declared at most {GROUP_INPUT_BITS} "
                             f"bits wide (`bits B` on its io line) for INFORM, whose IG#(n) reads 8 inputs into a byte "
                             f"(got {'no width' if e.bits is None else f'{e.bits} bits'})", node.span)
            return [], "0"
        t = self._temp(ir.ValueType.BOOL, ctx, node.span)  # a B variable: the byte IG# fills
        return [f"IN {t} IG#({e.port})"], t

    def _test(self, c: ir.Condition | ir.RtExpr, negate: bool, ctx: InformContext,
              node: ir.Instr) -> tuple[list[str], str] | None:
        """One comparison for `JUMP *L IF`: its lines and text, None when `c` is not one."""
        if isinstance(c, ir.Not):
            return self._test(c.operand, not negate, ctx, node)
        if isinstance(c, ir.InputCondition):
            test = self.condition(c, node.span, negate)
            return ([], test) if test is not None else None
        if isinstance(c, ir.OutputRead):
            # OT#(n) is the general output's state, tested as IN#(n) is in JUMP ... IF and
            # WAIT (YRC1000 INFORM Language manual, "JUMP", "WAIT": OT#(n)=ON/OFF)
            if not self.port_ok(c.port, "digital output", node.span):
                return None
            return [], f"OT#({c.port})={'OFF' if negate else 'ON'}"
        if isinstance(c, ir.VarRef):
            return [], f"{self._var(c.name, ctx, node.span)}{'=' if negate else '<>'}0"
        if not isinstance(c, ir.Compare):
            return None
        op, left, right = c.op, c.left, c.right
        if isinstance(left, ir.Const) and not isinstance(right, ir.Const):
            op, left, right = op.mirrored(), right, left
        lines, a = self._operand(left, ctx, node)
        if not isinstance(left, ir.VarRef) and not a.startswith(("D", "R", "B")):
            t = self._temp(_value_type(left), ctx, node.span)
            lines, a = lines + [f"SET {t} {a}"], t
        more, b = self._operand(right, ctx, node)
        return lines + more, f"{a}{_INFORM_CMP[op.negated() if negate else op]}{b}"

    def _jump(self, c: ir.Condition | ir.RtExpr, label: str, when: bool, ctx: InformContext,
              node: ir.Instr) -> list[str]:
        """Lines that jump to `label` when `c` evaluates to `when` and fall through otherwise."""
        if isinstance(c, ir.Not):
            return self._jump(c.operand, label, not when, ctx, node)
        if isinstance(c, ir.Const):
            return [f"JUMP {label}"] if bool(c.value) == when else []
        if isinstance(c, ir.Logic):
            out: list[str] = []
            if (c.op == "and") == when:  # every operand must hold: skip out at the first that fails
                skip = self.label(ctx)
                for operand in c.operands[:-1]:
                    out += self._jump(operand, skip, not when, ctx, node)
                return out + self._jump(c.operands[-1], label, when, ctx, node) + [skip]
            for operand in c.operands:
                out += self._jump(operand, label, when, ctx, node)
            return out
        test = self._test(c, not when, ctx, node)
        if test is None:
            return []
        return test[0] + [f"JUMP {label} IF {test[1]}"]

    def _if_condition(self, node: ir.If, ctx: InformContext) -> list[str]:
        ctx.vars.reset()
        skip = self.label(ctx)
        lines = self._jump(node.condition, skip, False, ctx, node) + self.body(node.then, ctx)
        if not node.otherwise:
            return lines + [skip]
        done = self.label(ctx)
        return lines + [f"JUMP {done}", skip, *self.body(node.otherwise, ctx), done]

    def while_(self, node: ir.While, ctx: InformContext) -> list[str]:
        ctx.vars.reset()
        top, end = self.label(ctx), self.label(ctx)
        lines = [top, *self._jump(node.condition, end, False, ctx, node)]
        return lines + self.body(node.body, ctx) + [f"JUMP {top}", end]

    def stop(self, node: ir.Stop, ctx: InformContext) -> list[str]:
        """PAUSE holds the job where it is (YRC1000 INSTRUCTIONS, PAUSE); in the main job a
        jump to the label before END follows, so a restart ends the job (END: the job's end)
        instead of running on. A called job cannot end its caller: PAUSE only (W432)."""
        if ctx.job.name != ctx.main:
            self.warn(codes.STOP_AS_PAUSE,
                      f"stop in the called job '{ctx.job.name}' is written as PAUSE (a called "
                      "job's END returns to its caller); a restart runs on", node.span)
            return ['MSG "STOP"', "PAUSE"]
        if ctx.job.stop_label is None:
            ctx.job.stop_label = self.label(ctx)
        return ['MSG "STOP"', "PAUSE", f"JUMP {ctx.job.stop_label}"]

    def wait_condition(self, node: ir.WaitCondition, ctx: InformContext) -> list[str]:
        """A condition other than one input: polled (`TIMER T=0.01` per test, W431); the timeout
        counts the polls in a D temporary (each poll lasts at least POLL_STEP). One output's
        state without a timeout is INFORM's own `WAIT OT#(n)=ON|OFF` (INFORM manual, "WAIT")."""
        ctx.vars.reset()
        read = node.condition.operand if isinstance(node.condition, ir.Not) else node.condition
        if node.timeout is None and isinstance(read, ir.OutputRead):
            one = self._test(node.condition, False, ctx, node)
            return [f"WAIT {one[1]}"] if one is not None else []
        counted = (" and its timeout counted in polls (the wait lasts at least the timeout)"
                   if node.timeout is not None else "")
        self.warn(codes.WAIT_POLLED, "INFORM's WAIT must test one signal; this condition "
                  f"is polled every {self.POLL_STEP:g} s{counted}", node.span)
        poll, done = self.label(ctx), self.label(ctx)
        test = self._jump(node.condition, done, True, ctx, node)
        step = f"TIMER T={fmt(self.POLL_STEP, 2)}"
        if node.timeout is None:
            return [poll, *test, step, f"JUMP {poll}", done]
        ticks = self._temp(ir.ValueType.INT, ctx, node.span)
        limit = max(1, round(node.timeout / self.POLL_STEP))
        branch = (self.body(node.on_timeout, ctx) if node.on_timeout
                  else ['MSG "WAIT TIMEOUT"', "PAUSE"])
        timed_out = self.label(ctx)
        return [f"SET {ticks} 0", poll, *test, f"JUMP {timed_out} IF {ticks}>={limit}", step,
                f"INC {ticks}", f"JUMP {poll}", timed_out, *branch, done]

    # ---------------------------------------------------------------- loops

    def loop(self, node: ir.Loop, ctx: InformContext) -> list[str]:
        template = ctx.vars.inner.pop(node.uid, None)
        if template is not None:  # a nested loop of a vendor loop being written
            return self._vendor_loop(template, ctx)
        found = analyse(node, ctx.record, config_key=_rconf_key,
                        unroll=bool(getattr(self, "unroll", False)))

        def write(template: LoopTemplate) -> list[str]:
            self._number_shifts(template, ctx)
            return self._vendor_loop(template, ctx)

        return blocked_loop_lines(self, node, found, _inform_blocker, write,
                                  lambda n: self._unrolled(n, ctx))

    def _unrolled(self, node: ir.Loop, ctx: InformContext) -> list[str]:
        lines: list[str] = []
        for it in node.iterations:
            body = bind_loop_var(it.body, node.var, it.value) if node.var else it.body
            lines += self.wrap(f"{node.var or 'iteration'} = {it.value}") + self.body(body, ctx)
        return lines

    def _number_shifts(self, template: LoopTemplate, ctx: InformContext) -> None:
        """One P variable per distinct shift of the nest (its steps in the coordinates the job
        writes the position in: the robot frame, or the numbered user frame)."""
        for (uid, role), offset in sorted(template.targets.items()):
            node = next(n for n in ir_tree.walk(template.body) if n.uid == uid)
            assert isinstance(node, ir.Move)
            system, steps = self._shift_steps(node, offset, ctx)
            if not any(any(s) for s in steps):
                continue
            key = (system, tuple(v.uid for v in offset.loops), steps)
            if key not in ctx.vars.shifts:
                ctx.vars.shifts[key] = ctx.vars.pvar_first + len(ctx.vars.shifts)
                if ctx.vars.shifts[key] > ctx.vars.pvar_last:
                    self.unsupported(codes.REGISTERS_EXHAUSTED, "loop shifts must fit "
                                     f"P{ctx.vars.pvar_first:03d}..P{ctx.vars.pvar_last:03d} "
                                     f"(needs P{ctx.vars.shifts[key]:03d})", template.loop.span)
            ctx.vars.offsets[(uid, role)] = (ctx.vars.shifts[key], system, offset.loops, steps)

    def _shift_steps(self, node: ir.Move, offset: TargetOffset,
                     ctx: InformContext) -> tuple[str, tuple[tuple[int, int, int], ...]]:
        """(coordinate system, integer steps in 0.001 mm per loop variable)."""
        # with external axes no user frame: the steps in ROBOT coordinates, as the positions
        user = None if ctx.axes else frame_number(ctx.plan.program.cell, node.frame.name)
        rot = np.eye(3) if user is not None else node.frame.pose.matrix()[:3, :3]
        system = f"UF#({user})" if user is not None else "RF"
        steps = tuple(tuple(int(round(float(v) * 1e6)) for v in rot @ np.array(s))
                      for s in offset.steps)
        return system, steps  # type: ignore[return-value]

    def _vendor_loop(self, template: LoopTemplate, ctx: InformContext) -> list[str]:
        """`SET Dv first`, `*Ltop`, this level's shifts, the body, `INC Dv`,
        `JUMP *Ltop IF Dv<=last` (the range is never empty here: loops.analyse)."""
        var = template.var
        counter = self._counter(var, ctx, template.loop.span)
        ctx.vars.inner.update(template.inner)
        top = self.label(ctx)
        head = self.wrap(_loop_head(var))
        head += [f"SET {counter} {var.first}", top]
        ctx.vars.reset()
        shifts = self._shift_lines(template, ctx)
        return head + shifts + self.body(template.body, ctx) + [
            f"INC {counter}", f"JUMP {top} IF {counter}<={var.last}"]

    def _counter(self, var: LoopVar, ctx: InformContext, span: object) -> str:
        if var.name is not None:
            return self._var(var.name, ctx, span)
        if var.uid not in ctx.vars.repeat:
            ctx.vars.repeat[var.uid] = self._numbered(ir.ValueType.INT, ctx.vars.counter(), span, ctx)
        return ctx.vars.repeat[var.uid]

    def _shift_lines(self, template: LoopTemplate, ctx: InformContext) -> list[str]:
        """SETE Pnnn (axis) D.. for every shift this level's own moves use: the sum over the
        loops of (counter - first) * step, in 0.001 mm."""
        done: set[int] = set()
        lines: list[str] = []
        for uid in level_moves(template.body):
            for role in ("target", "via"):
                found = ctx.vars.offsets.get((uid, role))
                if found is None or found[0] in done:
                    continue
                pvar, _, loops, steps = found
                done.add(pvar)
                if pvar not in ctx.job.shifts:
                    ctx.job.shifts.append(pvar)
                for axis in range(3):
                    terms = [(v, s[axis]) for v, s in zip(loops, steps) if s[axis]]
                    if not terms:
                        continue
                    acc = self._temp(ir.ValueType.INT, ctx, template.loop.span)
                    for k, (v, step) in enumerate(terms):
                        t = acc if k == 0 else self._temp(ir.ValueType.INT, ctx, template.loop.span)
                        lines.append(f"SET {t} {self._counter(v, ctx, template.loop.span)}")
                        lines += [f"SUB {t} {v.first}"] if v.first else []
                        lines.append(f"MUL {t} {step}")
                        lines += [f"ADD {acc} {t}"] if k else []
                    lines.append(f"SETE P{pvar:03d} ({axis + 1}) {acc}")
        return lines

    def shifted(self, node: ir.Move, lines: list[str], ctx: InformContext) -> list[str]:
        """A loop move whose target shifts per iteration, inside SFTON ... SFTOF."""
        found = ctx.vars.offsets.get((node.uid, "target"))
        if found is None or not lines:
            return lines
        return [f"SFTON P{found[0]:03d} {found[1]}", *lines, "SFTOF"]


"""A shifted target: (P variable, coordinate system, the loops, steps in 0.001 mm per loop)."""


@dataclass
class _Variables:
    """One task's variables: name -> (type, number), fixed for the task (variables are global
    on the controller, so called jobs read the same ones); temporaries of the current
    statement above them per type; loop shifts (P variables) and repeat counters."""

    variables: dict[str, tuple[ir.ValueType, int]]
    first: int = 50  # this task's B/D/R numbers first..last (TaskContext.register_slice)
    last: int = 99
    pvar_first: int = 50  # this task's loop shift P variables
    pvar_last: int = 99
    used: dict[ir.ValueType, int] = field(default_factory=dict)
    shifts: dict[object, int] = field(default_factory=dict)
    offsets: dict[tuple[int, str], _Shift] = field(default_factory=dict)
    inner: dict[int, LoopTemplate] = field(default_factory=dict)
    repeat: dict[int, str] = field(default_factory=dict)
    counters: int = 0
    loop_jobs: dict[object, str] = field(default_factory=dict)  # (job, shifts) -> its own job

    @classmethod
    def of_task(cls, task: TaskContext, body: tuple[ir.Instr, ...]) -> _Variables:
        """The variables of `task`: its own slice of 050..099 for B/D/R and for P."""
        first, last = task.register_slice(InformBackend.VAR_FIRST, InformBackend.MAX_VAR)
        pvar_first, pvar_last = task.register_slice(InformBackend.PVAR_FIRST, InformBackend.MAX_VAR)
        return cls(task_variables(body, first), first=first, last=last,
                   pvar_first=pvar_first, pvar_last=pvar_last)

    def reset(self) -> None:
        self.used = {}

    def _top(self, vtype: ir.ValueType) -> int:
        n = sum(1 for t, _ in self.variables.values() if t is vtype)
        return self.first + n + (self.counters if vtype is ir.ValueType.INT else 0)

    def temp(self, vtype: ir.ValueType) -> int:
        self.used[vtype] = self.used.get(vtype, 0) + 1
        return self._top(vtype) + self.used[vtype] - 1

    def counter(self) -> int:
        self.counters += 1
        return self._top(ir.ValueType.INT) - 1

    def comments(self) -> list[str]:
        return [f"'{InformBackend.LETTER[t]}{n:03d} = {name}"[:COMMENT_WIDTH]
                for name, (t, n) in self.variables.items()]


def task_variables(body: tuple[ir.Instr, ...], first: int = InformBackend.VAR_FIRST,
                   ) -> dict[str, tuple[ir.ValueType, int]]:
    """Every variable and loop variable of a task with its type and number (per type from
    `first`, in order of first appearance)."""
    out: dict[str, tuple[ir.ValueType, int]] = {}
    for node in ir_tree.walk(body):
        if isinstance(node, ir.VarDecl):
            name, vtype = node.name, node.type
        elif isinstance(node, ir.Loop) and node.var is not None:
            name, vtype = node.var, ir.ValueType.INT
        else:
            continue
        if name not in out:
            n = sum(1 for t, _ in out.values() if t is vtype)
            out[name] = (vtype, first + n)
    return out


