"""KUKA KRL backend (.src + .dat per module; KR C4 / KSS 8 syntax).

Conventions (KUKA "KSS 8.x Operating and Programming Instructions for System Integrators"):
  * positions mm; orientation A, B, C in degrees with R = Rz(A)·Ry(B)·Rx(C); joints A1..A6 in
    degrees (the controller's zero and direction); E1..E6 written as 0 (no external axes).
  * Cartesian targets are E6POS in the move's $BASE (= the rmot frame in the robot base frame;
    $BASE is relative to $WORLD, assumed to coincide with $ROBROOT, KUKA's default floor
    mounting) with $TOOL = the tool's TCP in the flange frame and $LOAD its mass, centre of
    gravity half way along the flange->TCP vector (rmot's payload convention, base.tool_cog).
  * Status S (from rmot's branch, rmot.sim.robots.branches): bit 0 = wrist point behind
    A1 (overhead area = shoulder back), bit 1 = A3 >= its stretched angle (elbow up; KUKA's
    home A3 = 90 deg gives S 'B010'), bit 2 = A5 < 0 (wrist flip).
    Turn T: bit i set when axis i+1 < 0.
  * joint moves to joint targets: PTP with an E6AXIS; joint moves to pose targets: PTP with an
    E6POS whose S and T select the planned branch (PTP is the only motion that reads S/T).
  * speeds: $VEL.CP in m/s, $ACC.CP in m/s^2 (LIN, CIRC); $VEL_AXIS[i] / $ACC_AXIS[i] in % of
    each axis's maximum (PTP, set by the local routine RMOT_PTP). A fixed move `time` has no
    KRL form: the programmed speeds are used (warning W409).
  * zones: exact stop without approximation wherever the plan stops (Backend.planned_zone:
    before WAIT FOR, IF, a handshake, at the end); LIN/CIRC: C_DIS with $APO.CDIS in mm
    (exact); PTP: C_PTP with $APO.CPTP in % (1 % per mm, clamped 1..100: no exact form, W403);
    a PTP blended into a LIN/CIRC: C_PTP C_DIS, $APO.CDIS too (mxAutomation manual, PTP); on a
    robot the cell declares KSS >= 8.2 (`controller kss 8.3`), PTP: C_DIS with $APO.CDIS (exact).
  * I/O: $OUT[n]=TRUE, PULSE($OUT[n],TRUE,t), WAIT SEC t, WAIT FOR $IN[n]==TRUE,
    IF $IN[n]==TRUE THEN; $ANOUT[n] = volts / 10 (KRL's -1.0..1.0 is -10..10 V).
    KRL's WAIT FOR has no timeout: a timed wait is lowered to a wait on the input OR timer
    $TIMER[TIMER_INDEX] (ms) followed by HALT when the input did not come (warning W405):
    the program stops, rmot's timeout semantics (base.py).
  * digital ports: $IN[n] / $OUT[n] with n in DIGITAL_PORTS = 1..4096 (KSS 8.1-8.3 "System
    Variables": $IN[1]..$IN[4096], $OUT[1]..$OUT[4096]); E404 outside.
  * numbered tools and frames (the cell's `number n`): `$TOOL=TOOL_DATA[n]`,
    `$LOAD=LOAD_DATA[n]`, `$BASE=BASE_DATA[n]` select the controller's stored data, which
    is never written unless --write-frames (then `TOOL_DATA[n]=...` at the module's start);
    the header comments give the values it must hold. Unnumbered ones are module data (.dat)
    assigned to $TOOL/$BASE directly: nothing stored on the controller is overwritten.
  * every motion writes the system variables it needs right before it ($TOOL, $LOAD, $BASE,
    speeds, $APO.CDIS): an instruction never depends on the text of another one. (A move
    with the bare flange sets $TOOL=$NULLFRAME and leaves $LOAD as configured: rmot has no
    load for the flange alone.)
  * procs are local DEFs of the module.
  * sync: KRL has no barrier between controllers without the RoboTeam option, so the k-th
    sync of a task is the I/O handshake of backends/handshake.py: `$OUT[o]=TRUE` (odd k) or
    FALSE (even k) then `WAIT FOR $IN[i]==` the same level, o and i being the robot's
    `io out[o] = "sync"` / `io in[i] = "sync"` of the cell (r1's out wired to r2's in and
    back). Missing signals: error E409 at the sync; a sync in an if arm: error E405.
  * identifiers: at most 24 characters, a letter or '_' first, letters, digits, '_'.
  * size: a module body longer than MAX_INSTRUCTIONS instructions is split into modules
    NAME_part1.. called from NAME (each with its own .dat); KRL itself has no line limit,
    the split keeps programs loadable and editable on the smartPAD (warning W406).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field, replace
from typing import ClassVar

import numpy as np

from rmot.backends import codes, native_refs, turns
from rmot.backends import loops as _loops
from rmot.backends import runtime as _rt
from rmot.backends.controller_data import frame_number, tool_number
from rmot.backends.ext_axes import coordinated, driven_axes, krl_e_axes, machine_data, mechanism_index, riding_frame
from rmot.backends.base import Backend, TaskContext, fmt, turn_bits
from rmot.backends.names import DataPool, NameTable
from rmot.backends.runtime import LoopState
from rmot.lang import ir, ir_tree, plan_types
from rmot.backends.safe_text import comment_safe
from rmot.lang.ir_axes import ExtAxis
from rmot.lang.record import record
from rmot.backends.krl_text import (
    KRL_RULES,
    E_AXES,
    PTP_HELPER,
    status_of,
    frame_text,
    load_text,
    _load_data,
    _held_load_name,
    _KRL_TYPES,
    _STOP_FLAG,
    _declare_var,
    _kexpr,
    _k_timed,
    krl_config,
    SHORTEST,
    _krl_extra,
)
from rmot.backends.part_load import state_at_moves

__all__ = ["KrlBackend"]

# a .dat data declaration (KUKA System Software 8, "DECL"; DECL optional for the predefined types):
# its name in group 1
_NATIVE_DATA = re.compile(r"(?i)^\s*(?:DECL\s+(?:GLOBAL\s+)?\w+|(?:GLOBAL\s+)?(?:E6POS|E6AXIS|POS|AXIS|FRAME|FDAT|PDAT|LDAT|INT|REAL|BOOL))"
                          r"\s+(\w+)\s*(?:=|;|$)")


@dataclass
class _Module:
    """Data and local routines collected while printing one module."""

    data: DataPool
    routines: dict[str, list[str]] = field(default_factory=dict)
    uses_ptp_helper: bool = False
    # numbered tools/frames used: (array, n) -> (rmot name, value text); selected by number,
    # written into the controller's arrays only with --write-frames
    stored: dict[tuple[str, int], tuple[str, str]] = field(default_factory=dict)
    native_data: dict[str, tuple[str, ir.Native]] = field(default_factory=dict)  # NAME -> a native declaration, its node


@record
class KrlContext(TaskContext):
    """One task's context plus its names, its routines' names and the module being printed."""

    names: NameTable
    routine_of: dict[int, str]
    module: _Module
    loops: LoopState = field(default_factory=LoopState)  # the vendor loop being written
    axes: tuple[ExtAxis, ...] = ()  # the external axes the task drives, in E1.. order


class KrlBackend(Backend):
    name = "krl"
    PRINTS_LOOPS = True  # FOR ... ENDFOR, with offsets per iteration (loop, _pos)
    RUNTIME_CONDITIONS = True  # writes and/or/not, $ANIN, variables and timeout branches
    EXTERNAL_AXES = True  # E1..E6 in E6POS/E6AXIS, EK() bases (backends/ext_axes.py)
    DIGITAL_PORTS = (1, 4096)  # $IN / $OUT, KSS 8.x System Variables
    file_ext = ".src"
    COMMENT = ";"
    NAME_RULES = KRL_RULES
    MAX_INSTRUCTIONS = 1000
    SPLIT_UNITS = ("KRL module", "modules")
    TIMER_INDEX: ClassVar[int] = 16
    MAX_TCP_SPEED = 2.0  # m/s
    MAX_TCP_SPEED_SOURCE = "KSS 8.x Programming Instructions for System Integrators, LIN/CIRC inline form: velocity 0.001..2 m/s"
    MAX_TOOL_DATA: ClassVar[int] = 16  # TOOL_DATA[16] in KSS 8.x $config.dat
    MAX_BASE_DATA: ClassVar[int] = 32  # BASE_DATA[32] in KSS 8.x $config.dat
    CPTP_MM: ClassVar[float] = 1.0  # mm of blend radius per % of $APO.CPTP (documented heuristic)
    SYNC_HANDSHAKE = True  # sync -> the I/O handshake of backends/handshake.py
    SIX_AXIS_DATA = "E6POS/E6AXIS data"
    BRANCH_DATA = "Status/Turn"

    # ------------------------------------------------------------------ program

    def emit_task(self, task: TaskContext) -> dict[str, str]:
        names, main_name, body = self.open_task(task)
        ctx = task.with_state(KrlContext, names=names, module=_Module(DataPool(names)),
                              routine_of=self.routine_table(names, body, task),
                              axes=driven_axes(task.task, task.plan.program.cell))
        files: dict[str, str] = {}
        parts = self.split_parts(body, ctx, main_name)
        if parts is not None:
            calls = []
            for part in parts:
                assert isinstance(part, ir.ProcCall)
                pname = names.name(part.proc)
                files.update(self._module(pname, part.body, ctx))
                calls.append(f"{pname}()")
            files = {**self._module(main_name, (), ctx, calls=calls), **files}
        else:
            files.update(self._module(main_name, body, ctx))
        self.extend(names.diagnostics)
        return files

    def _module(self, name: str, body: tuple[ir.Instr, ...], task: KrlContext,
                calls: list[str] | None = None) -> dict[str, str]:
        """The .src and .dat of one module: `body`, or calls to part modules."""
        ctx = replace(task, module=_Module(DataPool(task.names)))
        main = list(calls) if calls is not None else self.body(body, ctx)
        head = self.header(ctx) + [self.comment(line) for line in
                                   machine_data(ctx.plan.program.cell, ctx.robot, ctx.axes, "krl", coordinated(ctx.task))]
        stored = []
        for (array, n), (rname, value) in sorted(ctx.module.stored.items()):
            if self.write_frames:
                stored.append(f"{array}[{n}]={value} ; {rname} (--write-frames)")
            else:
                head = head + [self.comment(f"{array}[{n}] must hold {rname}: {value}")]
        main = stored + main
        src = ["&ACCESS RVP", f"DEF {name}( )"] + self.indent(head + main, "  ") + ["END"]
        for rname, rlines in ctx.module.routines.items():
            src += ["", f"DEF {rname}( )"] + self.indent(rlines, "  ") + ["END"]
        if ctx.module.uses_ptp_helper:
            src += [""] + PTP_HELPER
        dat = ["&ACCESS RVP", f"DEFDAT {name}"] + self.indent(head, "  ")
        dat += [f"  DECL {value.split(':', 1)[0]} {dname}={value.split(':', 1)[1]}"
                for dname, value in ctx.module.data.items]
        dat += ["  " + text for text in self._native_data(ctx)]
        dat.append("ENDDAT")
        return {f"{name}.src": "\n".join(src) + "\n", f"{name}.dat": "\n".join(dat) + "\n"}

    def native(self, node: ir.Native, ctx: KrlContext) -> list[str]:  # type: ignore[override]
        """A native data declaration (`DECL E6POS XP1={..}`, what `rmot import` keeps beside the
        native lines naming XP1) goes into the module's .dat, where KRL data lives."""
        declared = _NATIVE_DATA.match(node.text) if node.vendor.lower() == self.name else None
        if declared is None:
            return super().native(node, ctx)
        if not native_refs.keep_declaration(ctx.module.native_data, declared.group(1), node):
            self.unsupported(codes.NATIVE_CLASH, f"native declaration of {declared.group(1)} must be the only one of "
                             "that name in the module (another declares it differently)", node.span)
        return []

    def _native_data(self, ctx: KrlContext) -> list[str]:
        """The module's native declarations to write (native_refs.native_data)."""
        own = {name.upper() for name, _ in ctx.module.data.items}
        write, clash = native_refs.native_data(ctx.module.native_data, own, ctx.names.taken)
        for node, source in clash:
            self.unsupported(codes.NATIVE_CLASH, f"native declaration of {_NATIVE_DATA.match(node.text).group(1)} names "  # type: ignore[union-attr]
                             f"data this backend declares for '{source}': the native lines would read that; rename it", node.span)
        return write

    # ------------------------------------------------------------------ motion

    def _move_plain(self, node: ir.Move, ctx: KrlContext) -> list[str]:
        rec = self.move_record(node, ctx)
        if isinstance(rec, list):
            return rec
        if node.motion.duration is not None:
            self.warn(codes.DURATION_IGNORED, f"a fixed move time ({fmt(node.motion.duration, 3)} s) has no "
                      "KRL form; the programmed speeds are used", node.span)
        lines = self._tool_base(node, ctx)
        return self.by_kind(node)(node, rec, ctx, lines)

    def move_joint(self, node: ir.Move, rec: plan_types.InstructionRecord, ctx: KrlContext,
                   lines: list[str]) -> list[str]:
        m = node.motion
        stop = self.planned_zone(node, rec)
        ctx.module.uses_ptp_helper = True
        # the acceleration share the plan timed this move with (its chain's, decided once)
        lines.append(f"RMOT_PTP({fmt(m.joint_speed * 100.0, 3)},{fmt(rec.accel_share * 100.0, 3)})")
        if ctx.robot.exact_ptp_approximation and not stop.is_fine:
            # KSS >= 8.2: a PTP is approximated by the distance from the end point in mm, as
            # LIN/CIRC are ($APO.CDIS; KUKA System Software 8.2/8.3 Operating and Programming
            # Instructions for System Integrators, "Approximate positioning", PTP "C_DIS"):
            # the plan's blend radius, exact, into a PTP or a LIN/CIRC alike
            lines.append(f"$APO.CDIS={fmt(stop.radius * 1000.0, 3)}")
            zone = " C_DIS"
        else:
            zone = self._ptp_zone(node, stop, lines)
        following = ctx.task_plan.next_move(rec)
        if (zone.startswith(" C_PTP") and following is not None
                and following.kind is not ir.MotionKind.JOINT):
            # PTP -> LIN/CIRC: the CP part of the corner needs its own parameter (KUKA
            # mxAutomation manual, PTP approximation "C_PTP C_DIS"; KSS 8.x "PTP-CP approximate
            # positioning"): the plan's blend radius, as for LIN/CIRC
            lines.append(f"$APO.CDIS={fmt(stop.radius * 1000.0, 3)}")
            zone += " C_DIS"
        if node.motion.min_duration is not None:  # axes move: at their full speed and acceleration, as planned
            # ($VEL_EXTAX[n] / $ACC_EXTAX[n]: % of the external axis' maximum, KSS 8.x System Variables)
            lines += [f"${kind}_EXTAX[{k + 1}]=100" for k in range(len(ctx.axes)) for kind in ("VEL", "ACC")]
        if node.axes_only:  # the arm holds its planned joints; E1.. move (a synchronous PTP)
            held = ir.JointTarget(tuple(float(v) for v in rec.q_target), "jext")  # type: ignore[union-attr]
            return lines + [f"PTP {self._axis(held, ctx, node)}{zone}"]
        if isinstance(node.target, ir.JointTarget):
            return lines + [f"PTP {self._axis(node.target, ctx, node)}{zone}"]
        return lines + [f"PTP {self._pos(node.target, rec.q_target, rec.branch, node, ctx)}{zone}"]

    def _cp_head(self, node: ir.Move, rec: plan_types.InstructionRecord, lines: list[str]) -> str:
        """What LIN and CIRC share: the approximation and $VEL.CP/$ACC.CP lines (appended to
        `lines`); returns the zone suffix."""
        m = node.motion
        stop = self.planned_zone(node, rec)
        zone = "" if stop.is_fine else " C_DIS"
        if not stop.is_fine:
            lines.append(f"$APO.CDIS={fmt(stop.radius * 1000.0, 3)}")
        lines += [f"$VEL.CP={fmt(self.tcp_speed_within_limit(node), 4)}", f"$ACC.CP={fmt(m.tcp_accel, 4)}"]
        return zone

    def move_linear(self, node: ir.Move, rec: plan_types.InstructionRecord, ctx: KrlContext,
                    lines: list[str]) -> list[str]:
        zone = self._cp_head(node, rec, lines)
        if self.joint_target_refused(node):
            return lines
        assert isinstance(node.target, ir.CartesianTarget)  # refused above otherwise
        to = self._pos(node.target, rec.q_target, rec.branch, node, ctx)
        return lines + [f"LIN {to}{zone}"]

    def move_circular(self, node: ir.Move, rec: plan_types.InstructionRecord, ctx: KrlContext,
                      lines: list[str]) -> list[str]:
        zone = self._cp_head(node, rec, lines)
        if self.joint_target_refused(node):
            return lines
        assert isinstance(node.target, ir.CartesianTarget)  # refused above otherwise
        to = self._pos(node.target, rec.q_target, rec.branch, node, ctx)
        if self.via_refused(node):
            return lines
        assert node.via is not None  # refused above otherwise
        q_via = rec.q_via if rec.q_via is not None else rec.q_target
        via = self._pos(node.via, q_via, rec.branch, node, ctx, hint=node.via.name or "via")
        return lines + [f"CIRC {via},{to}{zone}"]

    def _ptp_zone(self, node: ir.Move, zone: ir.Zone, lines: list[str]) -> str:
        """` C_PTP` with `$APO.CPTP=n` appended to `lines` for an approximated PTP, "" for an
        exact stop. KRL approximates PTP only with C_PTP, whose distance $APO.CPTP is a % (1..100)
        of the axis-specific maximum in machine data ($APO_DIS_PTP), not a TCP radius
        (KSS 8.x Operating and Programming Instructions for System Integrators, "PTP",
        "Approximation parameters": C_DIS is for CP motions only): rmot writes
        n = round(radius / CPTP_MM) clamped to 1..100, the nearest faithful choice, warning W403."""
        if zone.is_fine:
            return ""
        r = zone.radius * 1000.0
        pct = max(1, min(100, round(r / self.CPTP_MM)))
        self.warn(codes.ZONE_ROUNDED, f"zone {fmt(r, 3)} mm has no exact KRL PTP form ($APO.CPTP is a % "
                  f"of the axes' approximation distance, not a radius); emitted as $APO.CPTP={pct}", node.span)
        lines.append(f"$APO.CPTP={pct}")
        return " C_PTP"

    def _tool_base(self, node: ir.Move, ctx: KrlContext) -> list[str]:
        lines = []
        cell, robot = ctx.plan.program.cell, ctx.robot.name
        tool_n, base_n = tool_number(cell, robot, node.tool.name), frame_number(cell, node.frame.name)
        if node.tool.name is None:
            lines += ["$TOOL=$NULLFRAME"]
        elif tool_n is not None:
            self._stored(ctx, "TOOL_DATA", tool_n, node.tool.name, f"{{{frame_text(node.tool.tcp)}}}", node)
            self._stored(ctx, "LOAD_DATA", tool_n, node.tool.name, load_text(node.tool), node)
            held = _held_load_name(node, ctx)  # holding parts: the stored LOAD_DATA is the tool's alone
            lines += [f"$TOOL=TOOL_DATA[{tool_n}]", f"$LOAD={held}" if held is not None else f"$LOAD=LOAD_DATA[{tool_n}]"]
        else:
            tname = ctx.module.data.add(node.tool.name, f"FRAME:{{{frame_text(node.tool.tcp)}}}")
            lname = ctx.module.data.add(f"{node.tool.name}_load", f"LOAD:{load_text(node.tool)}")
            held = _held_load_name(node, ctx)  # parts held: tool + parts, see _part_load
            if held is not None:
                lname = held
            lines += [f"$TOOL={tname}", f"$LOAD={lname}"]
        if node.frame.name is None:
            lines.append("$BASE=$NULLFRAME")
        elif ctx.axes:
            lines.append(self._axes_base(node, base_n, ctx))
        elif base_n is not None:
            self._stored(ctx, "BASE_DATA", base_n, node.frame.name, f"{{{frame_text(node.frame.pose)}}}", node)
            lines.append(f"$BASE=BASE_DATA[{base_n}]")
        else:
            bname = ctx.module.data.add(node.frame.name, f"FRAME:{{{frame_text(node.frame.pose)}}}")
            lines.append(f"$BASE={bname}")
        return lines

    def _stored(self, ctx: KrlContext, array: str, n: int, name: str, value: str, node: ir.Move) -> None:
        """Record a numbered tool/base (E410 outside the controller's array: TOOL_DATA[1..16],
        BASE_DATA[1..32], KSS 8.x $config.dat)."""
        limit = self.MAX_BASE_DATA if array == "BASE_DATA" else self.MAX_TOOL_DATA
        if not 1 <= n <= limit:
            self.unsupported(codes.NUMBER_OUT_OF_RANGE, f"{'frame' if array == 'BASE_DATA' else 'tool'} "
                             f"'{name}' number must be in 1..{limit} for {array} (got {n})", node.span)
        ctx.module.stored[(array, n)] = (name, value)

    def _axes_base(self, node: ir.Move, base_n: int | None, ctx: KrlContext) -> str:
        """$BASE in a task with external axes: a frame on a positioner through EK() (the frame in
        the kinematic's flange frame), any other in $WORLD (the robot base with the axes at home),
        from BASE_DATA[n] when the cell numbers it."""
        cell = ctx.plan.program.cell
        riding = riding_frame(node.frame, cell.external)
        if riding is not None:
            n = mechanism_index(riding[0], cell)
            return f"$BASE=EK(MACHINE_DEF[{n}].ROOT,MACHINE_DEF[{n}].MECH_TYPE,{{{frame_text(riding[1])}}})"
        assert node.frame.name is not None
        value = f"{{{frame_text(ctx.robot.base.inverse() * node.frame.world)}}}"
        if base_n is not None:
            self._stored(ctx, "BASE_DATA", base_n, node.frame.name, value, node)
            return f"$BASE=BASE_DATA[{base_n}]"
        return f"$BASE={ctx.module.data.add(node.frame.name, 'FRAME:' + value)}"

    @staticmethod
    def _e_axes(node: ir.Move, ctx: KrlContext) -> str:
        return krl_e_axes(node, ctx.axes) if ctx.axes else E_AXES

    def _axis(self, target: ir.JointTarget, ctx: KrlContext, node: ir.Move | None = None) -> str:
        values = ",".join(f"A{i + 1} {fmt(math.degrees(v), 4)}" for i, v in enumerate(target.values))
        e_axes = self._e_axes(node, ctx) if node is not None else E_AXES
        return ctx.module.data.add(target.name or "j", f"E6AXIS:{{{values}{e_axes}}}")

    def _pos_plain(self, target: ir.CartesianTarget, q: np.ndarray | None,
                   branch: ir.Config | None, node: ir.Move, ctx: KrlContext,
                   hint: str | None = None) -> str:
        assert q is not None
        branch = self.branch_or_default(branch, node)
        far = turns.beyond_one_turn(q, range(min(6, len(q))))  # Turn is a sign
        if far and node.kind is ir.MotionKind.JOINT:  # LIN/CIRC run on from the current joints
            self.unsupported(codes.TURN_NOT_EXPRESSIBLE,
                             turns.message(q, far, "KRL's Turn (the sign of each axis)"), node.span)
        st = f",S {status_of(branch)},T {turn_bits(q)}"
        return ctx.module.data.add(hint or target.name or "p", f"E6POS:{{{frame_text(target.in_frame)}{st}{self._e_axes(node, ctx)}}}",
                                   node.span)

    # ------------------------------------------------------------------ I/O and flow

    @staticmethod
    def _level(value: bool) -> str:
        return "TRUE" if value else "FALSE"

    def set_digital(self, node: ir.SetDigital, ctx: KrlContext) -> list[str]:
        if not self.port_ok(node.port, "digital output", node.span):
            return []
        return [f"$OUT[{node.port}]={self._level(node.value)}" + self._signal_note(node.signal)]

    def set_analog(self, node: ir.SetAnalog, ctx: KrlContext) -> list[str]:
        if abs(node.value) > 10.0:
            self.unsupported(codes.BAD_PORT, f"analog value must be within -10..10 V for $ANOUT "
                             f"(got {fmt(node.value, 3)})", node.span)
        return [f"$ANOUT[{node.port}]={fmt(node.value / 10.0, 4)}" + self._signal_note(node.signal)]

    def pulse(self, node: ir.Pulse, ctx: KrlContext) -> list[str]:
        if not self.port_ok(node.port, "digital output", node.span):
            return []
        return [f"PULSE($OUT[{node.port}],TRUE,{fmt(node.duration, 3)})" + self._signal_note(node.signal)]

    def wait_time(self, node: ir.WaitTime, ctx: KrlContext) -> list[str]:
        return [f"WAIT SEC {fmt(node.duration, 3)}"]

    def _wait_input_halt(self, node: ir.WaitInput, ctx: KrlContext) -> list[str]:
        c = node.condition
        if not self.port_ok(c.port, "digital input", node.span):
            return []
        cond = f"$IN[{c.port}]=={self._level(c.value)}"
        if node.timeout is None:
            return [f"WAIT FOR {cond}" + self._signal_note(c.signal)]
        self.warn(codes.TIMEOUT_LOWERED, f"KRL WAIT FOR has no timeout; lowered to a wait on $TIMER"
                  f"[{self.TIMER_INDEX}] and HALT after {fmt(node.timeout, 3)} s", node.span)
        t = f"$TIMER[{self.TIMER_INDEX}]"
        return [
            f"$TIMER_STOP[{self.TIMER_INDEX}]=TRUE", f"{t}=0", f"$TIMER_STOP[{self.TIMER_INDEX}]=FALSE",
            f"WAIT FOR ({cond}) OR ({t}>={int(round(node.timeout * 1000))})" + self._signal_note(c.signal),
            f"$TIMER_STOP[{self.TIMER_INDEX}]=TRUE",
            f"IF NOT ({cond}) THEN", "  HALT ; timeout", "ENDIF",
        ]

    @staticmethod
    def _signal_note(signal: str | None) -> str:
        return f" ; {comment_safe(signal)}" if signal else ""

    def _if_input(self, node: ir.If, ctx: KrlContext) -> list[str]:
        """An `if` on one digital input (`if_` writes the other conditions)."""
        c = node.condition
        assert isinstance(c, ir.InputCondition)  # if_ sends the other conditions elsewhere
        self.port_ok(c.port, "digital input", node.span)
        lines = [f"IF $IN[{c.port}]=={self._level(c.value)} THEN" + self._signal_note(c.signal)]
        lines += self.indent(self.body(node.then, ctx), "  ")
        if node.otherwise:
            lines += ["ELSE"] + self.indent(self.body(node.otherwise, ctx), "  ")
        return lines + ["ENDIF"]

    def _routine_call(self, node: ir.ProcCall, ctx: KrlContext) -> list[str]:
        name = ctx.routine_of[node.uid]
        if name not in ctx.module.routines:  # calls printing the same routine share it
            ctx.module.routines[name] = []
            ctx.module.routines[name] = [self.comment(f"proc {node.proc}")] + self.body(node.body, ctx)
        return self.call_args_comment(node) + [f"{name}()"]

    # ------------------------------------------------------------------ parts

    def attach(self, node: ir.Attach, ctx: KrlContext) -> list[str]:
        return self.part_load(node, ctx)

    def detach(self, node: ir.Detach, ctx: KrlContext) -> list[str]:
        return self.part_load(node, ctx)

    def part_load(self, node: ir.Attach | ir.Detach, ctx: KrlContext) -> list[str]:
        """`$LOAD=...` after an attach or detach: tool + held parts as one load on the flange, and
        every later motion of the same tool writes that load instead of the tool's alone.

        KUKA System Software 8.x, Operating and Programming Instructions for System Integrators,
        system variable $LOAD: the load on the flange, {M mass kg, CM centre of mass in the flange
        coordinate system (mm, A/B/C deg), J inertia}. ($LOAD_A3 is a supplementary load on axis 3,
        not a gripped part.) Inertia is written as 0 (a point mass, as for tools)."""
        if node.tool.name is None:
            return self.part_payload_comment(node, ctx)
        return [f"$LOAD={_load_data(node, ctx)}"]

    def context_key(self, node: ir.Instr, ctx: TaskContext) -> object:
        """A motion's routine key also depends on the parts held then (its `$LOAD` line), so a
        proc called once empty-handed and once holding a part prints two routines."""

        key = super().context_key(node, ctx)
        if isinstance(node, ir.Move) and ctx.plan.program.cell.parts:
            event = state_at_moves(ctx).get(node.uid)
            return (key, None if event is None else (event.held, event.tool.name))
        return key

    # ------------------------------------------------------------------ runtime logic
    # (KRL sources: the comment above _KRL_TYPES)

    def var_decl(self, node: ir.VarDecl, ctx: KrlContext) -> list[str]:
        name = ctx.names.name(node.name, node.span)
        krl_type, zero = _KRL_TYPES[node.type]
        _declare_var(ctx, name, krl_type, zero)
        return [f"{name}={_kexpr(self, node.init, ctx, node.span)}"]

    def assign(self, node: ir.Assign, ctx: KrlContext) -> list[str]:
        return [f"{ctx.names.name(node.name, node.span)}={_kexpr(self, node.value, ctx, node.span)}"]

    def if_(self, node: ir.If, ctx: KrlContext) -> list[str]:
        if isinstance(node.condition, ir.InputCondition):
            return self._if_input(node, ctx)
        lines = [f"IF {_kexpr(self, node.condition, ctx, node.span)} THEN"]
        lines += self.indent(self.body(node.then, ctx), "  ")
        if node.otherwise:
            lines += ["ELSE"] + self.indent(self.body(node.otherwise, ctx), "  ")
        return lines + ["ENDIF"]

    def while_(self, node: ir.While, ctx: KrlContext) -> list[str]:
        return ([f"WHILE {_kexpr(self, node.condition, ctx, node.span)}"]
                + self.indent(self.body(node.body, ctx), "  ") + ["ENDWHILE"])

    def wait_input(self, node: ir.WaitInput, ctx: KrlContext) -> list[str]:
        if node.timeout is None or not node.on_timeout:
            return self._wait_input_halt(node, ctx)
        c = node.condition
        if not self.port_ok(c.port, "digital input", node.span):
            return []
        cond = f"$IN[{c.port}]=={self._level(c.value)}"
        return _k_timed(self, cond, node.timeout, node.on_timeout, ctx, node.span)

    def wait_condition(self, node: ir.WaitCondition, ctx: KrlContext) -> list[str]:
        cond = _kexpr(self, node.condition, ctx, node.span)
        if node.timeout is None:
            return [f"WAIT FOR {cond}"]
        return _k_timed(self, cond, node.timeout, node.on_timeout, ctx, node.span)

    def stop(self, node: ir.Stop, ctx: KrlContext) -> list[str]:
        if ctx.loops.in_routine == 0:
            return ["RETURN ; stop: ends the program"]
        _declare_var(ctx, _STOP_FLAG, "BOOL", "FALSE")
        self.warn_once(ctx, "stop-flag", codes.STOP_IN_ROUTINE,
                       "stop inside a routine: KRL cannot end the program from a routine; it sets "
                       f"{_STOP_FLAG} and returns, and every call "
                       "returns in turn", node.span)
        return [f"{_STOP_FLAG}=TRUE", "RETURN ; stop"]

    def proc_call(self, node: ir.ProcCall, ctx: KrlContext) -> list[str]:
        if _rt.inline_call(node, ctx.loops):  # written inline in a vendor loop, like RAPID and URScript
            return [self.comment(f"{node.proc}({', '.join(node.args)})")] + self.body(node.body, ctx)
        ctx.loops.in_routine += 1
        try:
            lines = self._routine_call(node, ctx)
        finally:
            ctx.loops.in_routine -= 1
        if any(isinstance(n, ir.Stop) for n in ir_tree.walk(node.body)):
            _declare_var(ctx, _STOP_FLAG, "BOOL", "FALSE")
            ret = "RETURN ; stop: ends the program" if ctx.loops.in_routine == 0 else "RETURN ; stop"
            lines += [f"IF {_STOP_FLAG} THEN", f"  {ret}", "ENDIF"]
        return lines

    def _pos(self, target: ir.CartesianTarget, q: np.ndarray | None, branch: ir.Config | None,
             node: ir.Move, ctx: KrlContext, hint: str | None = None) -> str:
        """The E6POS (or FRAME) data a motion goes to, as _pos_plain; in a vendor loop, a PTP target every iteration reaches only as a
        FRAME (see _ptp_key) is one, and an offset target is a work copy moved by the counters."""
        forms = ctx.loops.choices.get(node.uid, frozenset())
        if node.kind is ir.MotionKind.JOINT and forms and all(f[1] == SHORTEST for f in forms):
            self.branch_or_default(branch, node)
            frame = f"FRAME:{{{frame_text(target.in_frame)}}}"
            name = ctx.module.data.add(hint or target.name or "p", frame,
                                       node.span)
        else:
            name = self._pos_plain(target, q, branch, node, ctx, hint)
        offset = ctx.loops.offsets.get((node.uid, "via" if target is node.via else "target"))
        if offset is None:
            return name
        terms = _rt.offset_terms(offset, ctx.loops.counters, 1000.0, lambda v: _rt.trimmed(fmt(v, 6)))
        if terms == ("0", "0", "0"):
            return name
        value = next(v for n, v in ctx.module.data.items if n == name)
        work = ctx.module.data.add(f"{name}_loop", value)
        ctx.loops.pending.append(f"{work}={name}")
        for axis, term in zip("XYZ", terms, strict=True):
            if term != "0":
                sign = "" if term.startswith("-") else "+"
                ctx.loops.pending.append(f"{work}.{axis}={name}.{axis}{sign}{term}")
        return work

    def move(self, node: ir.Move, ctx: KrlContext) -> list[str]:
        """A motion; in a vendor loop, the lines moving its work copies by the loop counters
        (queued by `_pos`) go right before the motion line."""
        lines = self._move_plain(node, ctx)
        if ctx.loops.pending and lines:
            lines = lines[:-1] + ctx.loops.pending + lines[-1:]
        ctx.loops.pending.clear()
        return lines

    def loop(self, node: ir.Loop, ctx: KrlContext) -> list[str]:
        def write(template: _loops.LoopTemplate) -> list[str]:
            counter = ctx.names.name(template.var.name or f"rmot_rep{template.loop.uid}", node.span)
            _declare_var(ctx, counter, "INT", "0")
            ctx.loops.enter(template, counter)
            head = f"FOR {counter}={template.var.first} TO {template.var.last}"
            return [head] + self.indent(self.body(template.body, ctx), "  ") + ["ENDFOR"]

        return _rt.loop_lines(self, node, ctx, write, lambda body: self.body(body, ctx),
                              move_config=krl_config,
                              extra_key=lambda n, r: _krl_extra(self, n, r, ctx))


