"""Universal Robots URScript (.script) backend.

Vendor conventions (URScript Programming Language manual, e-series / PolyScope 5):
  * units: metres, radians, seconds; linear speed m/s, acceleration m/s^2, joint speed rad/s,
    joint acceleration rad/s^2, blend radius `r` in metres;
  * a pose is `p[x, y, z, rx, ry, rz]`: position in metres and a rotation vector (axis * angle,
    rad), always in the robot *base* frame — URScript has no work object, so targets are the
    IR's `CartesianTarget.pose` (TCP in base, frames already composed);
  * the tool is `set_tcp(p[...])` (TCP in the flange frame), set at the start of every block,
    wherever the move's tool changes within that block, and after a call, a block or a native
    line that may leave another TCP (set_tcp sets the controller's TCP: a function's outlives it);
  * `movej([q1..q6], a, v, t, r)` for joint moves, always to the *planned* joint values (a pose
    target of a joint move is never re-solved on the controller), `movel(p, a, v, t, r)`,
    `movec(p_via, p_to, a, v, r, mode=0)` (mode 0: orientation interpolated to the target, as
    the IR's SLERP); there is no configuration data: movel/movec follow the path from the
    current joints, which the plan already fixed;
  * movej `v`/`a` are the leading axis' speed and acceleration: the plan's (the leading axis'
    peak speed and acceleration over the move, TaskPlan.leading_axis_rates), so the
    controller's trapezoid runs the verified timing; where the plan has no motion for a move,
    the IR's fractions of `JOINT_LIMITS[model]`, the slowest joint's datasheet maximum;
  * I/O: `set_standard_digital_out(n, b)` (n 0..7), `set_configurable_digital_out(n - 8, b)`
    (n 8..15), `get_standard_digital_in(n)` / `get_configurable_digital_in(n - 8)`
    (DIGITAL_PORTS = 0..15: the control box's 8 standard + 8 configurable I/O);
    analog out in volts on the 0–10 V domain: `set_analog_outputdomain(n, 1)` then
    `set_standard_analog_out(n, volts / 10)`;
  * a pulse runs in a URScript `thread` (set, sleep, reset) started with `run`, so the program
    does not wait for it — the same timing as a controller pulse instruction;
  * wait with timeout: a `while` loop counting `get_steptime()` per `sync()`; when the input
    still does not match, `popup(..., error=True, blocking=True)` names the input and `halt`
    stops the program (rmot's timeout semantics, see base.py);
  * payload: `set_payload(m, [cx, cy, cz])` (kg, m in the flange frame) next to `set_tcp` for
    every named tool, the centre of gravity half way along the flange->TCP vector
    (base.tool_cog); the bare flange leaves the installation's payload as configured;
  * procs: each call becomes a nested `def` before the main body (URScript needs a function
    defined before it is called);
  * comments: `# file.rmot:12` above each instruction.
  * sync: URScript has no multi-robot barrier, so the k-th sync of a task is the I/O
    handshake of backends/handshake.py: `set_standard_digital_out(o, True)` (odd k) or False
    (even k) then a `while not (get_standard_digital_in(i) == ...)` loop, o and i being the
    robot's `io out[o] = "sync"` / `io in[i] = "sync"` of the cell (wired crosswise).

Program size: URScript sets no documented limit on a program's length (the controller
compiles the whole script on load), so programs are never split.

The file is one `def <program>():` ... `end` followed by the call `<program>()`: send it to the
controller as a program (primary interface) or load it in a Script node; it runs as it is.

Support (checked by tests/backends/test_urscript.py):
  exact     movej/movel/movec, speeds, accelerations, blend r, fixed duration (t= on movej and
            movel), set_tcp, digital out 0..15, analog out 0..10 V, pulse, wait, wait for an
            input with or without timeout (a timeout stops the program), payload, if/else, procs, native urscript, source comments;
  warned    joint speed of a model missing from JOINT_LIMITS (W452), fixed duration of movec
            (W409), other vendors' native blocks (W407), legalised names (W400/W401);
  lowered   sync as the I/O handshake (no warning: exact given the wiring; odd count W410);
  refused   sync without the cell's "sync" signals (E409) or inside an if arm (E405), ports
            outside 0..15 (E404), analog outside 0..1 / 0..10 V (E450),
            moves without a planned solution or TCP pose (E401), circular without via (E451).
"""

from __future__ import annotations

import math
from dataclasses import field

from rmot.backends import codes
from rmot.backends import loops as _loops
from rmot.backends import runtime as _rt
from rmot.backends.base import Backend, TaskContext, fmt, fmt_list, rotation_vector, tool_cog
from rmot.backends.names import NameRules, NameTable
from rmot.backends.runtime import LoopState
from rmot.lang import ir, ir_tree, plan_types
from rmot.lang.record import record
from rmot.backends.part_load import state_at_moves, held_load
from rmot.lang.model_spec import model_name

__all__ = ["JOINT_LIMITS", "UrScriptBackend"]

# model -> (slowest joint's max speed rad/s, max joint acceleration rad/s^2).
# Speeds: UR e-series datasheets (UR3e base/shoulder/elbow 180 deg/s, UR5e all 180 deg/s,
# UR10e base/shoulder 120 deg/s). Acceleration: PolyScope's joint-acceleration maximum for a
# Move node (800 deg/s^2).
JOINT_LIMITS: dict[str, tuple[float, float]] = {
    "ur3e": (math.radians(180.0), math.radians(800.0)),
    "ur5e": (math.radians(180.0), math.radians(800.0)),
    "ur10e": (math.radians(120.0), math.radians(800.0)),
}
DEFAULT_LIMITS = (math.radians(180.0), math.radians(800.0))

# Built-in functions a program-level `def` of the same name would hide (Universal Robots,
# "The URScript Programming Language" e-Series 5.x: Module motion, internals, urmath,
# interfaces, ioconfiguration), and rmot's own helper variables.
UR_BUILTINS = frozenset(name.upper() for name in (
    "movej", "movel", "movep", "movec", "servoj", "servoc", "speedj", "speedl", "stopj", "stopl",
    "set_tcp", "set_payload", "set_payload_cog", "set_payload_mass", "set_gravity", "sleep",
    "sync", "popup", "textmsg", "get_steptime", "force_mode", "end_force_mode",
    "freedrive_mode", "end_freedrive_mode", "teach_mode", "end_teach_mode",
    "get_actual_joint_positions", "get_actual_tcp_pose", "get_target_tcp_pose",
    "get_target_joint_positions", "get_inverse_kin", "get_forward_kin", "pose_trans",
    "pose_inv", "pose_add", "pose_sub", "pose_dist", "interpolate_pose", "point_dist",
    "is_steady", "is_within_safety_limits", "set_standard_digital_out",
    "set_configurable_digital_out", "set_tool_digital_out", "get_standard_digital_in",
    "get_configurable_digital_in", "get_tool_digital_in", "get_standard_digital_out",
    "set_analog_outputdomain", "set_standard_analog_out", "get_standard_analog_in",
    "set_digital_out", "get_digital_in", "set_analog_out", "socket_open", "socket_close",
    "socket_send_string", "socket_read_ascii_float", "rpc_factory", "sqrt", "sin", "cos",
    "tan", "acos", "asin", "atan", "atan2", "pow", "log", "floor", "ceil", "norm", "d2r",
    "r2d", "length", "to_str", "str_cat", "random", "binary_list_to_integer",
    "integer_to_binary_list", "get_list_length", "abs", "rmot_waited", "rmot_thread",
))
UR_RULES = NameRules(
    max_len=63, allowed="A-Za-z0-9_", first="A-Za-z_", prefix="p_",
    reserved=frozenset({"DEF", "END", "IF", "ELIF", "ELSE", "WHILE", "THREAD", "RUN", "KILL",
                        "RETURN", "TRUE", "FALSE", "AND", "OR", "NOT", "XOR", "GLOBAL",
                        "LOCAL", "HALT", "BREAK", "CONTINUE", "SEC"}) | UR_BUILTINS,
)
POS_DECIMALS = 6  # metres: 1 micrometre
ANGLE_DECIMALS = 6  # radians: 0.00006 deg
RATE_DECIMALS = 6


def pose_text(pose: ir.Pose) -> str:
    """`p[x, y, z, rx, ry, rz]`: metres and a rotation vector in radians."""
    return "p[" + fmt_list((*pose.position, *rotation_vector(pose)), POS_DECIMALS, ", ") + "]"


@record
class UrContext(TaskContext):
    """One task's context plus what printing it collects: routine names and definitions,
    pulse threads, warnings given once."""

    routine_of: dict[int, str]
    routine_defs: list[str] = field(default_factory=list)
    defined: set[str] = field(default_factory=set)  # routine names already in routine_defs
    threads: dict[str, list[str]] = field(default_factory=dict)
    names: NameTable | None = None  # variables and loop counters
    loops: LoopState = field(default_factory=LoopState)  # the vendor loop being written


class UrScriptBackend(Backend):
    name = "urscript"
    file_ext = ".script"
    COMMENT = "#"
    SYNC_HANDSHAKE = True  # sync -> the I/O handshake of backends/handshake.py
    NAME_RULES = UR_RULES
    PRINTS_LOOPS = True  # a counter and `while counter <= last:`, targets moved by pose_add
    RUNTIME_CONDITIONS = True  # writes and/or/not, analog inputs, variables, timeout branches
    DIGITAL_PORTS = (0, 15)  # standard 0..7, configurable 8..15 (control box)
    NO_RECORD_NOTE = "move uid {uid} has no plan"
    SIX_AXIS_DATA = "movej/movel/movec (a UR controller drives six joints)"  # URScript manual: q is a 6-vector

    # ------------------------------------------------------------------ program

    def emit_task(self, task: TaskContext) -> dict[str, str]:
        names, prog, body = self.open_task(task)
        ctx = task.with_state(UrContext, routine_of=self.routine_table(names, body, task),
                              names=names)
        main = self.block(body, ctx)
        self.extend(names.diagnostics)
        lines = self.header(ctx) + [f"def {prog}():"]
        lines += self.indent(ctx.loops.decls, self.INDENT)  # globals and input domains
        for thread_lines in ctx.threads.values():
            lines += self.indent(thread_lines, self.INDENT)
        lines += self.indent(ctx.routine_defs, self.INDENT)
        # the call after the def: a .script run as a program (primary interface) or pasted in a
        # Script node executes its top level, so without it nothing would move (UR Script
        # Manual, "The structure of a URScript program"; RoboDK's UR post ends with the call)
        lines += self.indent(main, self.INDENT) + ["end", f"{prog}()"]
        return {f"{prog}{self.file_ext}": "\n".join(lines) + "\n"}

    def block(self, nodes: tuple[ir.Instr, ...], ctx: UrContext) -> list[str]:
        """A body with `set_tcp` at its first move and wherever the tool may have changed, with
        the payload the move carries: the tool and the parts it holds there (the state after the
        last attach/detach on the move's path, part_load.state_at_moves, as KRL's $LOAD), so a
        loop body, an `if` arm or a proc never sets the tool alone while a part is held. After a
        call, a block or a native line the TCP is the one they left, so the next move sets its own."""
        out: list[str] = []
        current: ir.ToolRef | None = None
        for node in nodes:
            if not isinstance(node, ir.Move) and self.may_change_tcp(node, current):
                current = None  # whatever TCP it leaves, the next move states its own
            if isinstance(node, ir.Move) and node.tool != current:
                current = node.tool
                out.append(f"set_tcp({pose_text(node.tool.tcp)})")
                event = state_at_moves(ctx).get(node.uid)
                if event is not None and event.held and event.tool.name == node.tool.name:
                    out += self.set_payload(event, ctx)
                elif node.tool.name is not None:
                    cog = fmt_list(tool_cog(node.tool), POS_DECIMALS, ", ")
                    out.append(f"set_payload({fmt(node.tool.mass, 3)}, [{cog}])")
            out.extend(self.instr(node, ctx))
        return out

    def may_change_tcp(self, node: ir.Instr, current: ir.ToolRef | None) -> bool:
        """Whether `node` (a call's or block's moves, a native URScript line) may leave another TCP."""
        return any((isinstance(n, ir.Move) and n.tool != current)
                   or (isinstance(n, ir.Native) and n.vendor.lower() == self.name) for n in ir_tree.walk((node,)))

    # ------------------------------------------------------------------ motion

    def _move_plain(self, node: ir.Move, ctx: UrContext) -> list[str]:
        rec = self.move_record(node, ctx)
        if isinstance(rec, list):
            return rec
        return self.by_kind(node)(node, rec, ctx, fmt(rec.blend_radius, POS_DECIMALS))

    def move_joint(self, node: ir.Move, rec: plan_types.InstructionRecord, ctx: UrContext,
                   r: str) -> list[str]:
        assert rec.q_target is not None  # move_record returns a record with joints
        q = "[" + fmt_list(rec.q_target, ANGLE_DECIMALS, ", ") + "]"
        return [f"movej({q}, {self.movej_rates(node, rec, ctx)}{self.duration_arg(node.motion)}, r={r})"]

    def movej_rates(self, node: ir.Move, rec: plan_types.InstructionRecord, ctx: UrContext) -> str:
        """`a=.., v=..` of a movej, the leading axis' acceleration and speed (URScript manual,
        movej): the plan's (TaskPlan.leading_axis_rates), so the controller's trapezoid is the
        verified timing; the IR's fractions of JOINT_LIMITS only where the plan has no motion."""
        rates = ctx.task_plan.leading_axis_rates(rec)
        if rates is None:
            v_max, a_max = self.joint_limits(ctx, node)
            rates = (node.motion.joint_speed * v_max, node.motion.joint_accel * a_max)
        return f"a={fmt(rates[1], RATE_DECIMALS)}, v={fmt(rates[0], RATE_DECIMALS)}"

    def _tcp_args(self, node: ir.Move, rec: plan_types.InstructionRecord) -> tuple[str, str] | None:
        """(speed arguments, target pose) of movel/movec; None (E401) without a TCP pose."""
        m = node.motion
        if rec.tcp_pose is None:
            self.unsupported(codes.MISSING_RECORD, f"a {node.kind.name.lower()} move must have a "
                             "planned TCP pose (got none)", node.span)
            return None
        speed = f"a={fmt(m.tcp_accel, RATE_DECIMALS)}, v={fmt(m.tcp_speed, RATE_DECIMALS)}"
        return speed, pose_text(rec.tcp_pose)

    def move_linear(self, node: ir.Move, rec: plan_types.InstructionRecord, ctx: UrContext,
                    r: str) -> list[str]:
        args = self._tcp_args(node, rec)
        if args is None:
            return []
        speed, to = args
        return [f"movel({to}, {speed}{self.duration_arg(node.motion)}, r={r})"]

    def move_circular(self, node: ir.Move, rec: plan_types.InstructionRecord, ctx: UrContext,
                      r: str) -> list[str]:
        m = node.motion
        args = self._tcp_args(node, rec)
        if args is None:
            return []
        speed, to = args
        if self.via_refused(node):
            return [self.comment("circular move without via")]
        assert node.via is not None  # refused above otherwise
        if m.duration is not None:
            self.warn(codes.DURATION_IGNORED, f"movec has no time argument; the fixed duration "
                      f"{m.duration:g} s is expressed by the speed only", node.span)
        return [f"movec({pose_text(node.via.pose)}, {to}, {speed}, r={r}, mode=0)"]

    @staticmethod
    def duration_arg(m: ir.Motion) -> str:
        """`, t=...`: URScript's exact fixed-duration argument of movej/movel."""
        return "" if m.duration is None else f", t={fmt(m.duration, 4)}"

    def joint_limits(self, ctx: UrContext, node: ir.Move) -> tuple[float, float]:
        model = ctx.robot.source.ref
        shown = f"'{model}'"
        if ctx.robot.source.kind is ir.RobotSourceKind.MODEL:  # a cell's model: name it, not its key

            shown = f"'{model_name(model)}' (a cell model)"
        if model in JOINT_LIMITS:
            return JOINT_LIMITS[model]
        if "model" in ctx.warned:
            return DEFAULT_LIMITS
        ctx.warned.add("model")
        self.warn(codes.SPEED_TABLE_UNKNOWN, f"robot model {shown} must be in the URScript "
                  f"joint speed table (it is not); assumed 180 deg/s and 800 deg/s^2", node.span)
        return DEFAULT_LIMITS

    # ------------------------------------------------------------------ I/O

    def digital(self, port: int, span: object, kind: str) -> str | None:
        """`standard_digital_out(3` or `configurable_digital_out(0`; None after an error."""
        if not self.port_ok(port, f"digital {kind}put", span):  # type: ignore[arg-type]
            return None
        if port <= 7:
            return f"standard_digital_{kind}({port}"
        return f"configurable_digital_{kind}({port - 8}"

    def set_digital(self, node: ir.SetDigital, ctx: UrContext) -> list[str]:
        sig = self.digital(node.port, node.span, "out")
        return [f"set_{sig}, {node.value})"] if sig else []

    def set_analog(self, node: ir.SetAnalog, ctx: UrContext) -> list[str]:
        if node.port not in (0, 1) or not 0.0 <= node.value <= 10.0:
            self.unsupported(codes.ANALOG_UNSUPPORTED, "analog output must be port 0..1 with 0..10 V "
                             f"(got port {node.port}, {node.value:g} V)", node.span)
            return []
        return [f"set_analog_outputdomain({node.port}, 1)",
                f"set_standard_analog_out({node.port}, {fmt(node.value / 10.0, 6)})"]

    def pulse(self, node: ir.Pulse, ctx: UrContext) -> list[str]:
        sig = self.digital(node.port, node.span, "out")
        if sig is None:
            return []
        name = f"rmot_pulse_{node.port}_{round(node.duration * 1000)}ms"
        if abs(round(node.duration * 1000) - node.duration * 1000) > 1e-9:
            name = f"rmot_pulse_{node.port}_{round(node.duration * 1e6)}us"
        ctx.threads[name] = [f"thread {name}():", f"  set_{sig}, True)",
                               f"  sleep({fmt(node.duration, 4)})", f"  set_{sig}, False)", "end"]
        return [f"rmot_thread = run {name}()"]

    def wait_time(self, node: ir.WaitTime, ctx: UrContext) -> list[str]:
        return [f"sleep({fmt(node.duration, 4)})"]

    def condition(self, cond: ir.InputCondition, span: object) -> str | None:
        sig = self.digital(cond.port, span, "in")
        return f"get_{sig}) == {cond.value}" if sig else None

    def _wait_input_halt(self, node: ir.WaitInput, ctx: UrContext) -> list[str]:
        test = self.condition(node.condition, node.span)
        if test is None:
            return []
        if node.timeout is None:
            return [f"while not ({test}):", "  sync()", "end"]
        c = node.condition
        message = (f"wait for input {c.port} == {c.value} timed out after "
                   f"{fmt(node.timeout, 3)} s; program stopped")
        return ["rmot_waited = 0.0",
                f"while not ({test}) and rmot_waited < {fmt(node.timeout, 4)}:",
                "  sync()", "  rmot_waited = rmot_waited + get_steptime()", "end",
                f"if not ({test}):",
                f'  popup("{message}", title="rmot", error=True, blocking=True)',
                "  halt", "end"]

    def _if_input(self, node: ir.If, ctx: UrContext) -> list[str]:
        """An `if` on one digital input (`if_` writes the other conditions)."""
        c = node.condition
        assert isinstance(c, ir.InputCondition)  # if_ sends the other conditions elsewhere
        test = self.condition(c, node.span)
        if test is None:
            return []
        lines = [f"if {test}:"] + self.indent(self.block(node.then, ctx), self.INDENT)
        if node.otherwise:
            lines += ["else:"] + self.indent(self.block(node.otherwise, ctx), self.INDENT)
        return lines + ["end"]

    # ------------------------------------------------------------------ structure

    def _routine_call(self, node: ir.ProcCall, ctx: UrContext) -> list[str]:
        name = ctx.routine_of[node.uid]
        if name not in ctx.defined:  # calls printing the same routine share it (routine_table)
            ctx.defined.add(name)
            body = self.block(node.body, ctx) or ["sleep(0.0)"]
            ctx.routine_defs.extend([self.comment(f"proc {node.proc}"), f"def {name}():"])
            ctx.routine_defs.extend(self.indent(body, self.INDENT) + ["end"])
        return self.call_args_comment(node) + [f"{name}()"]

    # ------------------------------------------------------------------ parts

    def attach(self, node: ir.Attach, ctx: UrContext) -> list[str]:
        return self.set_payload(node, ctx)

    def detach(self, node: ir.Detach, ctx: UrContext) -> list[str]:
        return self.set_payload(node, ctx)

    def set_payload(self, node: ir.Attach | ir.Detach, ctx: UrContext) -> list[str]:
        """`set_payload(m, [cx, cy, cz])` after an attach or detach: tool + held parts.

        Universal Robots, "The URScript Programming Language" (e-Series), set_payload(m, cog):
        m the payload mass in kg, cog the centre of gravity's displacement from the tool flange
        in metres. The bare flange with parts held writes the parts alone."""

        _, _, total, cog = held_load(node, ctx)
        return [f"set_payload({fmt(total, 3)}, [{fmt_list(cog, POS_DECIMALS, ', ')}])"]

    # ------------------------------------------------------------------ runtime logic
    # (URScript sources: the comment above _UR_ZERO)

    def var_decl(self, node: ir.VarDecl, ctx: UrContext) -> list[str]:
        name = _uname(ctx, node.name, node.span)
        decl = f"global {name} = {_UR_ZERO[node.type]}"
        if decl not in ctx.loops.decls:
            ctx.loops.decls.append(decl)
        return [f"{name} = {_uexpr(self, node.init, ctx, node.span)}"]

    def assign(self, node: ir.Assign, ctx: UrContext) -> list[str]:
        return [f"{_uname(ctx, node.name, node.span)} = {_uexpr(self, node.value, ctx, node.span)}"]

    def if_(self, node: ir.If, ctx: UrContext) -> list[str]:
        if isinstance(node.condition, ir.InputCondition):
            return self._if_input(node, ctx)
        lines = [f"if {_uexpr(self, node.condition, ctx, node.span)}:"]
        lines += self.indent(self.block(node.then, ctx), self.INDENT)
        if node.otherwise:
            lines += ["else:"] + self.indent(self.block(node.otherwise, ctx), self.INDENT)
        return lines + ["end"]

    def while_(self, node: ir.While, ctx: UrContext) -> list[str]:
        return ([f"while {_uexpr(self, node.condition, ctx, node.span)}:"]
                + self.indent(_loop_body(self, node.body, ctx), self.INDENT) + ["end"])

    def wait_input(self, node: ir.WaitInput, ctx: UrContext) -> list[str]:
        if node.timeout is None or not node.on_timeout:
            return self._wait_input_halt(node, ctx)
        test = self.condition(node.condition, node.span)
        if test is None:
            return []
        return _u_timed(self, test, node.timeout, node.on_timeout, ctx)

    def wait_condition(self, node: ir.WaitCondition, ctx: UrContext) -> list[str]:
        test = _uexpr(self, node.condition, ctx, node.span)
        if node.timeout is None:
            return [f"while not ({test}):", "  sync()", "end"]
        if node.on_timeout:
            return _u_timed(self, test, node.timeout, node.on_timeout, ctx)
        message = f"wait until timed out after {fmt(node.timeout, 3)} s; program stopped"
        return _u_timed(self, test, node.timeout, (), ctx)[:-1] + [
            f'  popup("{message}", title="rmot", error=True, blocking=True)', "  halt", "end"]

    def stop(self, node: ir.Stop, ctx: UrContext) -> list[str]:
        return ["halt"]

    def move(self, node: ir.Move, ctx: UrContext) -> list[str]:
        """As _move_plain; a target a vendor loop offsets is written as a pose_add (and a
        joint move to it through get_inverse_kin near the first iteration's joints)."""
        moving = _rt.moving_offset(ctx.loops, node.uid, "target")
        if moving is None or not isinstance(node.target, ir.CartesianTarget):
            return self._move_plain(node, ctx)
        rec = self.move_record(node, ctx)
        if isinstance(rec, list):
            return rec
        if rec.tcp_pose is None:
            return self._move_plain(node, ctx)
        m = node.motion
        r = fmt(rec.blend_radius, POS_DECIMALS)
        to = _offset_pose(self, rec.tcp_pose, node, "target", ctx)
        if node.kind is ir.MotionKind.JOINT:
            q = "[" + fmt_list(rec.q_target, ANGLE_DECIMALS, ", ") + "]"  # type: ignore[arg-type]
            return [f"movej(get_inverse_kin({to}, qnear={q}), {self.movej_rates(node, rec, ctx)}"
                    f"{self.duration_arg(m)}, r={r})"]
        speed = f"a={fmt(m.tcp_accel, RATE_DECIMALS)}, v={fmt(m.tcp_speed, RATE_DECIMALS)}"
        if node.kind is ir.MotionKind.LINEAR:
            return [f"movel({to}, {speed}{self.duration_arg(m)}, r={r})"]
        if node.via is None:
            return self._move_plain(node, ctx)
        via = _offset_pose(self, node.via.pose, node, "via", ctx)
        return [f"movec({via}, {to}, {speed}, r={r}, mode=0)"]

    def loop(self, node: ir.Loop, ctx: UrContext) -> list[str]:
        def write(template: _loops.LoopTemplate) -> list[str]:
            counter = _uname(ctx, template.var.name or f"rmot_rep{template.loop.uid}", node.span)
            ctx.loops.enter(template, counter)
            body = _loop_body(self, template.body, ctx)
            return ([f"{counter} = {template.var.first}", f"while {counter} <= {template.var.last}:"]
                    + self.indent(body + [f"{counter} = {counter} + 1"], self.INDENT) + ["end"])

        return _rt.loop_lines(self, node, ctx, write, lambda body: self.block(body, ctx),
                              extra_key=_ur_extra)

    def proc_call(self, node: ir.ProcCall, ctx: UrContext) -> list[str]:
        """A call inside a vendor loop whose body the loop offsets is written inline (the counter
        is a local of the program's def, not known inside the proc's own def)."""
        if _rt.inline_call(node, ctx.loops):
            return [self.comment(f"{node.proc}({', '.join(node.args)})")] + self.block(node.body, ctx)
        return self._routine_call(node, ctx)


# ----------------------------------------------------------------- runtime logic
#
# Sources: Universal Robots, "The URScript Programming Language" (e-Series, PolyScope 5.x):
#   * variables: `global NAME = value` at the top of the program makes NAME visible in every
#     function defined in it (the procs' `def`s); a plain assignment in a function makes a
#     local ("Scoping rules"); PolyScope writes its own programs' variables the same way,
#     `global Waypoint_1_p=p[...]` right inside `def <program>():` (the .script files PolyScope
#     saves, e.g. as quoted in public UR/ROS repositories). Types int, float, bool ("Variables
#     and types"); `True`/`False`.
#   * flow: `if c:` ... `elif`/`else:` ... `end`, `while c:` ... `end`; operators `and`,
#     `or`, `not`, `==`, `!=`, `<`, `<=`, `>`, `>=` ("Flow of control", "Operators").
#     A loop must use up physical time in every iteration (a thread that never does is
#     stopped by the controller, "Threads" / the "Runtime too much behind" protective stop
#     of Module internals sync()): a loop body that may not move or wait ends with `sync()`.
#   * `for` loops: a counter and `while counter <= last:` (URScript has no for statement);
#     targets are `pose_add(p_base, p[dx, dy, dz, 0, 0, 0])`: pose_add adds the positions and
#     composes the rotations (Module urmath, pose_add(p_1, p_2): p_3.P = p_1.P + p_2.P,
#     p_3.R = p_1.R * p_2.R), so a zero rotation gives the base pose moved by (dx, dy, dz) in
#     the robot base frame; the in-frame step of backends/loops.py is turned into the base
#     frame by the move's frame rotation first (URScript targets are in the base frame).
#   * a joint move to a Cartesian target in a loop: `movej(get_inverse_kin(pose, qnear=q0))`
#     (Module urmath, get_inverse_kin(x, qnear, ...): the solution closest to qnear), q0 the
#     joints planned for the first iteration: the loop analysis requires every iteration's
#     branch and turns to be q0's, so the closest solution is the planned one.
#   * `get_standard_analog_in(n)` (Module interfaces): the control box analog input n in 0..1,
#     in volts after `set_standard_analog_input_domain(n, 1)` (domain 1 = voltage).
#   * stop -> `halt` (Module internals, halt(): terminates the program).
#   * wait with a timeout branch: the same counted loop as wait_input above, then
#     `if not (cond):` runs the branch instead of popup + halt.

_UR_ZERO = {ir.ValueType.INT: "0", ir.ValueType.NUM: "0.0", ir.ValueType.BOOL: "False"}
_UR_COMPARE = {ir.CompareOp.EQ: "==", ir.CompareOp.NE: "!=", ir.CompareOp.LT: "<",
               ir.CompareOp.LE: "<=", ir.CompareOp.GT: ">", ir.CompareOp.GE: ">="}
ANALOG_IN_PORTS = (0, 1)  # control box standard analog inputs AI0, AI1
_TIMED = (ir.Move, ir.WaitTime, ir.WaitInput, ir.WaitCondition, ir.Stop)


def _uname(ctx: UrContext, name: str, span: object = None) -> str:
    assert ctx.names is not None
    return ctx.names.name(name, span)  # type: ignore[arg-type]


def _ur_dialect(self: UrScriptBackend, ctx: UrContext, span: object) -> _rt.ExprDialect:
    def analog(a: ir.AnalogInput) -> str:
        low, high = ANALOG_IN_PORTS
        if not low <= a.port <= high:
            self.unsupported(codes.ANALOG_IN_PORT,
                             f"analog input port must be in {low}..{high} "
                             f"for get_standard_analog_in (got {a.port})",
                             span)  # type: ignore[arg-type]
        domain = f"set_standard_analog_input_domain({a.port}, 1)"
        if domain not in ctx.loops.decls:
            ctx.loops.decls.append(domain)
        return f"get_standard_analog_in({a.port})"

    def digital(c: ir.InputCondition) -> str:
        return self.condition(c, span) or "False"

    def output(o: ir.OutputRead) -> str:
        # get_standard_digital_out(n) / get_configurable_digital_out(n) return the output's
        # bool state (URScript Programming Language manual, "Interfaces" module)
        sig = self.digital(o.port, span, "out")
        return f"get_{sig})" if sig else "False"

    def group(g: ir.GroupInput) -> str:
        # URScript reads digital inputs one by one (get_standard_digital_in); its integer
        # input registers (read_input_integer_register) are fieldbus/RTDE registers another
        # device writes, not inputs wired as a group: neither is what gin[n] reads.
        self.unsupported(codes.LOGIC_UNSUPPORTED, f"gin[{g.port}] must be a group of digital inputs "
                         "URScript can read as one integer (it has none: its integer input registers "
                         "are fieldbus/RTDE registers, not wired inputs)", span)  # type: ignore[arg-type]
        return "0"

    return _rt.ExprDialect(
        true="True", false="False", and_="and", or_="or", not_="not ", compare=_UR_COMPARE,
        var=lambda v: _uname(ctx, v.name), digital=digital, analog=analog, group=group, output=output,
        real_division=lambda a, b: f"({a} * 1.0) / {b}", number=lambda v: _rt.trimmed(fmt(v, 6)),
    )


def _uexpr(self: UrScriptBackend, e: object, ctx: UrContext, span: object) -> str:
    return _rt.expr_text(e, _ur_dialect(self, ctx, span))


def _uses_time(body: tuple[ir.Instr, ...]) -> bool:
    """True when running `body` surely moves or waits (every if arm does, a loop runs)."""
    for node in body:
        if isinstance(node, _TIMED):
            return True
        runs, bodies = ir_tree.flow(node)
        if runs is ir_tree.Runs.ONE_OF and bodies and all(_uses_time(sub) for sub in bodies):
            return True
        # a proc body; a loop's iterations, each like the first
        if runs.sure and bodies and _uses_time(bodies[0]):
            return True
    return False


def _loop_body(self: UrScriptBackend, body: tuple[ir.Instr, ...], ctx: UrContext) -> list[str]:
    """A loop body, ending with `sync()` unless it surely moves or waits."""
    lines = self.block(body, ctx)
    if not _uses_time(body):
        lines.append("sync()")
    return lines


def _u_timed(self: UrScriptBackend, test: str, timeout: float, on_timeout: tuple[ir.Instr, ...],
             ctx: UrContext) -> list[str]:
    return ["rmot_waited = 0.0",
            f"while not ({test}) and rmot_waited < {fmt(timeout, 4)}:",
            "  sync()", "  rmot_waited = rmot_waited + get_steptime()", "end",
            f"if not ({test}):"] + self.indent(self.block(on_timeout, ctx), self.INDENT) + ["end"]


def _offset_pose(self: UrScriptBackend, base: ir.Pose, node: ir.Move, role: str,
                 ctx: UrContext) -> str:
    """`p[...]` or, in a vendor loop, `pose_add(p[...], p[dx, dy, dz, 0, 0, 0])` (base frame)."""
    text = pose_text(base)
    offset = _rt.moving_offset(ctx.loops, node.uid, role)
    if offset is None:
        return text
    rotation = node.frame.pose.matrix()[:3, :3]
    terms = _rt.offset_terms(offset, ctx.loops.counters, 1.0,
                             lambda v: _rt.trimmed(fmt(v, POS_DECIMALS)),
                             frame=rotation)
    if terms == ("0", "0", "0"):
        return text
    return f"pose_add({text}, p[{', '.join(terms)}, 0, 0, 0])"


def _ur_extra(node: ir.Instr, rec: object) -> object:
    """URScript prints each move's planned blend radius (r=): iterations must agree on it."""
    radius = getattr(rec, "blend_radius", None)
    return None if radius is None else fmt(radius, POS_DECIMALS)
