r"""ABB RAPID (.mod) backend: one module per task, procs as PROCs, data as CONST/PERS.

Conventions (ABB "Technical reference manual – RAPID Instructions, Functions and Data types"):
  * positions mm, orientations unit quaternions q1..q4 = w, x, y, z (robtarget.rot);
    joints in degrees (jointtarget.robax), the controller's zero and direction.
  * Cartesian targets are written in the move's work object (wobjdata.uframe = the rmot frame
    in the robot base frame; the controller's world frame is assumed to coincide with the robot
    base, ABB's default single-robot setup), with the tool declared as tooldata (robhold TRUE).
  * confdata [cf1, cf4, cf6, cfx]: cf1/cf4/cf6 = quadrant of axis 1/4/6, floor(q / 90 deg)
    (-1 for [-90, 0) deg); cfx (6-axis serial arms) = 4*(wrist centre behind axis 1)
    + 2*(wrist centre behind the lower arm) + (axis 5 negative), i.e. with rmot's branch
    (rmot.sim.robots.branches) shoulder back -> +4, elbow down -> +2, wrist flip -> +1.
  * speeddata: the predefined v5 ... v7000 when the TCP speed is one of them, else a CONST
    speeddata [v_tcp, 500, 5000, 1000] (exact). Joint moves: `vmax` at a joint speed share of
    100 %; RAPID has no per-move joint-speed share, so a smaller share is emitted as the planned
    duration `\T:=` (nearest faithful; warning W402). A `time` modifier is emitted as `\T:=`.
  * zonedata: `fine` wherever the plan stops (Backend.planned_zone: before WaitDI, IF,
    WaitSyncTask, WaitTime, at the end), else a predefined z0 ... z200 when the radius matches, else a CONST zonedata
    with the exact TCP radius (orientation zones scaled like the predefined table).
  * joint moves to joint targets -> MoveAbsJ; joint moves to pose targets -> MoveJ with
    the robtarget's confdata (ConfJ\\On, the default, makes the controller take that branch).
  * tooldata: the TCP pose, the tool's mass (0 kg is declared as 0.001 kg, RAPID's minimum,
    warning W413), the centre of gravity half way along the flange->TCP vector (rmot's payload
    convention, base.tool_cog), inertia 0.
  * acceleration: in a task whose joint moves set an acceleration share, `AccSet n, 100;`
    before every move (modal, so written each time); a TCP acceleration (m/s^2) has no AccSet
    form (warning W408 once per task).
  * I/O: SetDO / SetAO / PulseDO\\PLength / WaitDI ...\\MaxTime (an unhandled
    ERR_WAIT_MAXTIME stops the program with its message: rmot's timeout semantics, see
    base.py) / IF DInput(..) = 1 THEN; signal names from the cell
    (else do<n> / di<n> / ao<n>), which must exist in the controller's I/O configuration.
  * sync -> WaitSyncTask with a `tasks` list T_ROB1..T_ROBn in task order (MultiMove).
  * I/O ports: RAPID addresses signals by name; the port only builds the default name do<n>,
    so any non-negative n is accepted (DIGITAL_PORTS; E404 below 0).
  * identifiers: at most 32 characters, a letter first, letters, digits and '_'.
  * Program size: RAPID has no line limit (program memory is the limit); nothing is split.
  * native data: a native statement that is a data declaration (`CONST robtarget p10:=[..];`,
    what `rmot import` keeps beside the native lines naming p10) is declared at module level,
    where RAPID data lives, unless the backend declares data of that rmot name itself (the same
    datum: the import names rmot's targets, tools, variables and syncidents after the file's).
    Two such declarations of one name that differ, and one whose name the backend gave other
    data, are E411.
"""

from __future__ import annotations

from collections.abc import Hashable
from dataclasses import field

from rmot.backends import codes, native_refs
from rmot.backends import loops as _loops
from rmot.backends import runtime as _rt
from rmot.backends.ext_axes import RAPID_UNUSED, driven_axes, machine_data, rapid_extax, rapid_wobj
from rmot.backends.base import (
    Backend,
    TaskContext,
    accel_is_default,
    axis_quadrant,
    fmt,
    fmt_list,
    tool_cog,
)
from rmot.backends.names import DataPool, NameTable
from rmot.backends.runtime import LoopState
from rmot.lang import ir, ir_tree, plan_types
from rmot.lang.ir_axes import ExtAxis
from rmot.lang.record import record
from rmot.lang.source import Span
from rmot.backends.rapid_text import (
    SPEEDS_MM_S,
    ZONES_MM,
    RAPID_RULES,
    DATA_ORDER,
    EXTAX,
    cfx_of,
    num_name,
    pose_text,
    _RAPID_TYPES,
    _offs,
    _expr,
    _timed,
    rapid_conf,
    rapid_conf_match,
)
import math
import re
from rmot.backends.part_load import held_load

__all__ = ["RapidBackend"]

# a RAPID data declaration (RAPID Overview, "Data declarations"): its name in group 1
_NATIVE_DATA = re.compile(r"(?i)^\s*(?:(?:LOCAL|TASK)\s+)*(?:CONST|PERS|VAR)\s+\w+\s+(\w+)\b")


@record
class RapidContext(TaskContext):
    """One task's context plus the declarations collected while printing it (emitted above
    the routines)."""

    names: NameTable
    data: DataPool
    decls: dict[str, list[str]] = field(default_factory=dict)  # kind -> declaration lines
    routines: dict[str, list[str]] = field(default_factory=dict)
    routine_of: dict[int, str] = field(default_factory=dict)
    massless_tools: set[str] = field(default_factory=set)
    axes: tuple[ExtAxis, ...] = ()  # the external axes the task drives, in eax_a.. order
    loops: LoopState = field(default_factory=LoopState)  # the vendor loop being written
    native_data: dict[str, tuple[str, ir.Native]] = field(default_factory=dict)  # NAME -> a native declaration, its node


class RapidBackend(Backend):
    name = "rapid"
    DIGITAL_PORTS = (0, 2**31 - 1)  # signals are named (do<n>): any non-negative number
    file_ext = ".mod"
    COMMENT = "!"
    NAME_RULES = RAPID_RULES
    SIX_AXIS_DATA = "RAPID robtarget/jointtarget data"
    BRANCH_DATA = "confdata"
    PRINTS_LOOPS = True  # FOR ... ENDFOR, targets moved by Offs
    RUNTIME_CONDITIONS = True  # writes and/or/not, AInput, variables and timeout flags
    EXTERNAL_AXES = True  # extax, MoveExtJ, coordinated wobjdata (backends/ext_axes.py)

    # ------------------------------------------------------------------ program

    def emit_task(self, task: TaskContext) -> dict[str, str]:
        names, module, body = self.open_task(task, reserved=("main",))
        ctx = task.with_state(RapidContext, names=names, data=DataPool(names),
                              routine_of=self.routine_table(names, body, task),
                              axes=driven_axes(task.task, task.plan.program.cell))
        main = self.body(body, ctx)
        lines = [f"MODULE {module}"] + self.indent(self.header(ctx), self.INDENT)
        lines += self.indent([self.comment(line) for line in machine_data(ctx.plan.program.cell, ctx.robot, ctx.axes, "rapid")],
                             self.INDENT)
        lines += self.indent(self._native_data(ctx), self.INDENT)
        for kind in ("tooldata", "wobjdata", "loaddata", "sync", "var"):
            lines += self.indent(ctx.decls.get(kind, []), self.INDENT)
        lines += self.indent(self._data_lines(ctx), self.INDENT)
        lines += [""] + self._routine("main", main)
        for rname, rlines in ctx.routines.items():
            lines += [""] + self._routine(rname, rlines)
        lines.append("ENDMODULE")
        self.extend(names.diagnostics)
        return {f"{module}{self.file_ext}": "\n".join(lines) + "\n"}

    def _routine(self, name: str, body: list[str]) -> list[str]:
        return self.indent([f"PROC {name}()"] + self.indent(body, self.INDENT) + ["ENDPROC"], self.INDENT)

    @staticmethod
    def _data_lines(ctx: RapidContext) -> list[str]:
        """CONST data grouped by type (first-use order within a type)."""
        rows = [(value.split(":", 1), name) for name, value in ctx.data.items]
        return [f"CONST {kind} {name}:={literal};" for kind in DATA_ORDER
                for (k, literal), name in rows if k == kind]

    def native(self, node: ir.Native, ctx: RapidContext) -> list[str]:  # type: ignore[override]
        declared = _NATIVE_DATA.match(node.text) if node.vendor.lower() == self.name else None
        if declared is None:
            return super().native(node, ctx)
        if not native_refs.keep_declaration(ctx.native_data, declared.group(1), node):
            self.unsupported(codes.NATIVE_CLASH, f"native declaration of {declared.group(1)} must be the only one of "
                             "that name in the task (another declares it differently)", node.span)
        return []  # declared at module level (emit_task)

    def _native_data(self, ctx: RapidContext) -> list[str]:
        """The native declarations to write (native_refs.native_data)."""
        own = {m.group(1).upper() for line in [*(d for ds in ctx.decls.values() for d in ds), *self._data_lines(ctx)]
               if (m := _NATIVE_DATA.match(line))}
        write, clash = native_refs.native_data(ctx.native_data, own, ctx.names.taken)
        for node, source in clash:
            self.unsupported(codes.NATIVE_CLASH, f"native declaration of {_NATIVE_DATA.match(node.text).group(1)} names "  # type: ignore[union-attr]
                             f"data this backend declares for '{source}': the native lines would read that; rename it", node.span)
        return write

    @staticmethod
    def _declare(ctx: RapidContext, kind: str, line: str) -> None:
        lines = ctx.decls.setdefault(kind, [])
        if line not in lines:
            lines.append(line)

    # ------------------------------------------------------------------ motion

    def move(self, node: ir.Move, ctx: RapidContext) -> list[str]:
        rec = self.move_record(node, ctx)
        if isinstance(rec, list):
            return rec
        tool, wobj = self._tool(node.tool, node.span, ctx), self._wobj(node.frame, ctx)
        zone = self._zone(self.planned_zone(node, rec), ctx)
        return self._accset(node, ctx) + self.by_kind(node)(node, rec, ctx, zone, tool, wobj)

    def _accset(self, node: ir.Move, ctx: RapidContext) -> list[str]:
        """`AccSet n, 100;` before every move of a task whose joint moves set an acceleration
        share (ABB RAPID reference, AccSet Acc, Ramp: Acc 20..100 % of the normal acceleration,
        modal, so it is written with every move and no move depends on the text of another);
        n is the move's joint acceleration share, which the plan applies to the joints of every
        move in its chain (compiler/plan/move_chain.py). A Cartesian move's TCP acceleration
        (m/s^2) has no AccSet form (W408), nor has a share outside 20..100 % (W408, 100 %)."""
        if node.kind is not ir.MotionKind.JOINT:
            self.warn_accel(node, ctx, "AccSet is a share of the normal acceleration, not a TCP acceleration")
        if not any(isinstance(i, ir.Move) and i.kind is ir.MotionKind.JOINT
                   and not accel_is_default(i.motion, i.kind) for i in ir_tree.walk(ctx.task.body)):
            return []
        share = node.motion.joint_accel * 100.0
        if abs(share - round(share)) < 1e-9 and 20 <= round(share) <= 100:
            return [f"AccSet {round(share)}, 100;"]
        self.warn_accel(node, ctx, "AccSet takes a whole 20..100 %")
        return ["AccSet 100, 100;"]

    def move_joint(self, node: ir.Move, rec: plan_types.InstructionRecord, ctx: RapidContext,
                   zone: str, tool: str, wobj: str) -> list[str]:
        if node.axes_only:  # the units alone, the arm holds its joints: MoveExtJ (backends/ext_axes.py)
            target = ctx.data.add("jext", f"jointtarget:[[{','.join([RAPID_UNUSED] * 6)}],{rapid_extax(node, ctx.axes)}]")
            return [f"MoveExtJ {target}, vmax\\T:={fmt(rec.t_end - rec.t_start, 3)}, {zone};"]
        if isinstance(node.target, ir.JointTarget):
            target = self._jointtarget(node.target, ctx, self._extax(node, ctx))
            speed = self._joint_speed(node, rec)
            return [f"MoveAbsJ {target}\\NoEOffs, {speed}, {zone}, {tool};"]
        to = self._robtarget(node.target, rec.q_target, rec.branch, node, ctx)
        return [f"MoveJ {to}, {self._joint_speed(node, rec)}, {zone}, {tool}{wobj};"]

    def move_linear(self, node: ir.Move, rec: plan_types.InstructionRecord, ctx: RapidContext,
                    zone: str, tool: str, wobj: str) -> list[str]:
        if self.joint_target_refused(node):
            return []
        assert isinstance(node.target, ir.CartesianTarget)  # refused above otherwise
        to = self._robtarget(node.target, rec.q_target, rec.branch, node, ctx)
        return [f"MoveL {to}, {self._tcp_speed(node, ctx)}, {zone}, {tool}{wobj};"]

    def move_circular(self, node: ir.Move, rec: plan_types.InstructionRecord, ctx: RapidContext,
                      zone: str, tool: str, wobj: str) -> list[str]:
        if self.joint_target_refused(node):
            return []
        assert isinstance(node.target, ir.CartesianTarget)  # refused above otherwise
        to = self._robtarget(node.target, rec.q_target, rec.branch, node, ctx)
        speed = self._tcp_speed(node, ctx)
        if self.via_refused(node):
            return [self.comment("circular move without via point not emitted")]
        assert node.via is not None  # refused above otherwise
        q_via = rec.q_via if rec.q_via is not None else rec.q_target
        via = self._robtarget(node.via, q_via, rec.branch, node, ctx, hint=node.via.name or "via")
        return [f"MoveC {via}, {to}, {speed}, {zone}, {tool}{wobj};"]

    def _tcp_speed(self, node: ir.Move, ctx: RapidContext) -> str:
        v = node.motion.tcp_speed * 1000.0
        name = next((f"v{s}" for s in SPEEDS_MM_S if abs(s - v) < 1e-6), None)
        if name is None:
            name = ctx.data.add(f"v{num_name(v)}", f"speeddata:[{fmt(v, 3)},500,5000,1000]")
        if node.motion.duration is not None:
            return f"{name}\\T:={fmt(node.motion.duration, 3)}"
        return name

    def context_key(self, node: ir.Instr, ctx: TaskContext) -> Hashable:
        """A joint move without a RAPID speed prints its planned duration (see _joint_speed)."""
        rec = ctx.record(node)
        if (isinstance(node, ir.Move) and rec is not None and node.motion.duration is None
                and node.motion.joint_speed < 1.0
                and (node.kind is ir.MotionKind.JOINT or isinstance(node.target, ir.JointTarget))):
            return round(rec.t_end - rec.t_start, 9)
        return None

    def _joint_speed(self, node: ir.Move, rec: plan_types.InstructionRecord) -> str:
        if node.motion.duration is not None:
            return f"vmax\\T:={fmt(node.motion.duration, 3)}"
        if node.motion.joint_speed >= 1.0:
            return "vmax"
        duration = rec.t_end - rec.t_start
        if duration < 0.001:  # a zero-length move (already at the target): any speed is the same
            return "vmax"
        self.warn(codes.SPEED_ROUNDED, f"joint speed {fmt(node.motion.joint_speed * 100, 1)} % has no "
                  "RAPID form; emitted as the planned move duration (\\T)", node.span)
        return f"vmax\\T:={fmt(duration, 3)}"

    def _zone(self, zone: ir.Zone, ctx: RapidContext) -> str:
        if zone.is_fine:
            return "fine"
        r = zone.radius * 1000.0
        match = next((z for z in ZONES_MM[1:] if abs(z - r) < 1e-6), None)
        if match is not None:
            return f"z{match}"
        o = 1.5 * r
        return ctx.data.add(f"z{num_name(r)}", "zonedata:[FALSE," + ",".join(
            fmt(x, 3) for x in (r, o, o, 0.1 * o, o, 0.1 * o)) + "]")

    def _jointtarget(self, target: ir.JointTarget, ctx: RapidContext, extax: str = EXTAX) -> str:

        values = fmt_list((math.degrees(v) for v in target.values), 3)
        return ctx.data.add(target.name or "j", f"jointtarget:[[{values}],{extax}]")

    @staticmethod
    def _extax(node: ir.Move, ctx: RapidContext) -> str:
        return rapid_extax(node, ctx.axes) if ctx.axes else EXTAX

    def _robtarget(self, target: ir.CartesianTarget, q: object, branch: ir.Config | None,
                   node: ir.Move, ctx: RapidContext, hint: str | None = None) -> str:
        branch = self.branch_or_default(branch, node)
        cf = (axis_quadrant(q[0]), axis_quadrant(q[3]), axis_quadrant(q[5]), cfx_of(branch))  # type: ignore[index]
        conf = ",".join(str(c) for c in cf)
        value = f"robtarget:[{pose_text(target.in_frame)[1:-1]},[{conf}],{self._extax(node, ctx)}]"
        name = ctx.data.add(hint or target.name or "p", value, node.span)
        return _offs(ctx, node, "via" if target is node.via else "target", name)

    def _tool(self, tool: ir.ToolRef, span: Span | None, ctx: RapidContext) -> str:
        if tool.name is None:
            return "tool0"
        name = ctx.names.name(tool.name)
        mass = tool.mass if tool.mass > 0 else 0.001  # RAPID rejects a tool load of 0 kg
        if tool.mass <= 0 and name not in ctx.massless_tools:
            ctx.massless_tools.add(name)
            self.warn(codes.MASS_RAISED, f"tool '{tool.name}' must have a mass for RAPID tooldata (got 0 kg); "
                      "declared with 0.001 kg", span)
        cog = tuple(c * 1000.0 for c in tool_cog(tool))  # mm, half way to the TCP (base.tool_cog)
        load = f"[{fmt(mass, 3)},[{fmt_list(cog, 3)}],[1,0,0,0],0,0,0]"
        self._declare(ctx, "tooldata", f"PERS tooldata {name}:=[TRUE,{pose_text(tool.tcp)},{load}];")
        return name

    def _wobj(self, frame: ir.FrameRef, ctx: RapidContext) -> str:
        if frame.name is None:
            return ""
        name = ctx.names.name(frame.name)
        if ctx.axes:  # a unit moves the frame, or the controller's world is the base at home
            self._declare(ctx, "wobjdata", f"TASK PERS wobjdata {name}:={rapid_wobj(frame, ctx.robot, ctx.plan.program.cell)};")
            return f"\\WObj:={name}"
        self._declare(ctx, "wobjdata", f"TASK PERS wobjdata {name}:=[FALSE,TRUE,\"\","
                      f"{pose_text(frame.pose)},[[0,0,0],[1,0,0,0]]];")
        return f"\\WObj:={name}"

    # ------------------------------------------------------------------ I/O and flow

    def _signal(self, ctx: RapidContext, prefix: str, port: int, signal: str | None, span: object = None) -> str:
        if signal is None:  # a named signal does not use the number
            self.port_ok(port, "analog" if prefix == "ao" else "digital", span)  # type: ignore[arg-type]
        return ctx.names.name(signal or f"{prefix}{port}")

    def set_digital(self, node: ir.SetDigital, ctx: RapidContext) -> list[str]:
        return [f"SetDO {self._signal(ctx, 'do', node.port, node.signal, node.span)}, {int(node.value)};"]

    def set_analog(self, node: ir.SetAnalog, ctx: RapidContext) -> list[str]:
        return [f"SetAO {self._signal(ctx, 'ao', node.port, node.signal, node.span)}, {fmt(node.value, 3)};"]

    def pulse(self, node: ir.Pulse, ctx: RapidContext) -> list[str]:
        return [f"PulseDO\\PLength:={fmt(node.duration, 3)}, {self._signal(ctx, 'do', node.port, node.signal, node.span)};"]

    def wait_time(self, node: ir.WaitTime, ctx: RapidContext) -> list[str]:
        return [f"WaitTime {fmt(node.duration, 3)};"]

    def sync(self, node: ir.Sync, ctx: RapidContext) -> list[str]:  # type: ignore[override]
        n = len(ctx.plan.tasks)
        task_list = ",".join(f'["T_ROB{k + 1}"]' for k in range(n))
        name = ctx.names.name(node.name, node.span)
        self._declare(ctx, "sync", f"VAR syncident {name};")
        self._declare(ctx, "sync", f"PERS tasks all_tasks{{{n}}}:=[{task_list}];")
        return [f"WaitSyncTask {name}, all_tasks;"]

    def _routine_call(self, node: ir.ProcCall, ctx: RapidContext) -> list[str]:
        name = ctx.routine_of[node.uid]
        if name not in ctx.routines:  # calls printing the same routine share it (routine_table)
            ctx.routines[name] = []  # reserve the slot first: routines print in call order
            ctx.routines[name] = [self.comment(f"proc {node.proc}")] + self.body(node.body, ctx)
        return self.call_args_comment(node) + [f"{name};"]

    # ------------------------------------------------------------------ parts

    def attach(self, node: ir.Attach, ctx: RapidContext) -> list[str]:
        return self.grip_load(node, ctx)

    def detach(self, node: ir.Detach, ctx: RapidContext) -> list[str]:
        return self.grip_load(node, ctx)

    def grip_load(self, node: ir.Attach | ir.Detach, ctx: RapidContext) -> list[str]:
        """`GripLoad piece;` after an attach or detach: the held parts' payload (the tool's own mass
        stays in its tooldata), `GripLoad load0;` once nothing is held.

        ABB, Technical reference manual "RAPID Instructions, Functions and Data types": GripLoad
        ("defines the payload which the robot holds in its gripper"; load0 = no payload) and
        loaddata [mass kg, cog [x,y,z] mm, aom, ix, iy, iz], the payload's centre of gravity in the
        tool coordinate system when the robot holds the tool. Inertia is written as 0 (a point
        mass, as rmot's torque check assumes for tools)."""

        mass, cog, _, _ = held_load(node, ctx)
        if mass <= 0.0:
            return ["GripLoad load0;"]
        in_tool = (node.tool.tcp.inverse() * ir.Pose(tuple(float(c) for c in cog))).position  # type: ignore[arg-type]
        name = ctx.names.name("load_" + "_".join(node.held))
        cog_mm = fmt_list((c * 1000.0 for c in in_tool), 3)
        self._declare(ctx, "loaddata", f"PERS loaddata {name}:=[{fmt(mass, 3)},[{cog_mm}],[1,0,0,0],0,0,0];")
        return [f"GripLoad {name};"]

    # ------------------------------------------------------------------ runtime logic
    # (RAPID sources: the comment above _RAPID_TYPES)

    def var_decl(self, node: ir.VarDecl, ctx: RapidContext) -> list[str]:
        name = ctx.names.name(node.name, node.span)
        self._declare(ctx, "var", f"VAR {_RAPID_TYPES[node.type]} {name};")
        return [f"{name} := {_expr(self, node.init, ctx, node.span)};"]

    def assign(self, node: ir.Assign, ctx: RapidContext) -> list[str]:
        return [f"{ctx.names.name(node.name, node.span)} := {_expr(self, node.value, ctx, node.span)};"]

    def if_(self, node: ir.If, ctx: RapidContext) -> list[str]:
        lines = [f"IF {_expr(self, node.condition, ctx, node.span)} THEN"]
        lines += self.indent(self.body(node.then, ctx), self.INDENT)
        if node.otherwise:
            lines += ["ELSE"] + self.indent(self.body(node.otherwise, ctx), self.INDENT)
        return lines + ["ENDIF"]

    def while_(self, node: ir.While, ctx: RapidContext) -> list[str]:
        lines = [f"WHILE {_expr(self, node.condition, ctx, node.span)} DO"]
        return lines + self.indent(self.body(node.body, ctx), self.INDENT) + ["ENDWHILE"]

    def wait_input(self, node: ir.WaitInput, ctx: RapidContext) -> list[str]:
        c = node.condition
        head = f"WaitDI {self._signal(ctx, 'di', c.port, c.signal, node.span)}, {int(c.value)}"
        return _timed(self, head, node.timeout, node.on_timeout, ctx)

    def wait_condition(self, node: ir.WaitCondition, ctx: RapidContext) -> list[str]:
        head = f"WaitUntil {_expr(self, node.condition, ctx, node.span)}"
        return _timed(self, head, node.timeout, node.on_timeout, ctx)

    def stop(self, node: ir.Stop, ctx: RapidContext) -> list[str]:
        return ["EXIT;"]

    def loop(self, node: ir.Loop, ctx: RapidContext) -> list[str]:
        def write(template: _loops.LoopTemplate) -> list[str]:
            counter = ctx.names.name(template.var.name or f"rmot_rep{template.loop.uid}", node.span)
            ctx.loops.enter(template, counter)
            head = f"FOR {counter} FROM {template.var.first} TO {template.var.last} DO"
            return [head] + self.indent(self.body(template.body, ctx), self.INDENT) + ["ENDFOR"]

        return _rt.loop_lines(self, node, ctx, write, lambda body: self.body(body, ctx),
                              config_key=rapid_conf, config_match=rapid_conf_match,
                              extra_key=lambda n, r: self.context_key(n, ctx))

    def proc_call(self, node: ir.ProcCall, ctx: RapidContext) -> list[str]:
        """A call inside a FOR whose body the loop offsets is written inline (the FOR counter is
        local to the loop: RAPID overview, "FOR": not known in another routine)."""
        if _rt.inline_call(node, ctx.loops):
            return [self.comment(f"{node.proc}({', '.join(node.args)})")] + self.body(node.body, ctx)
        return self._routine_call(node, ctx)


