"""Stäubli VAL3 applications (CS8/CS9 controllers), written as the SRS application folder.

We write the application as the controller stores it (what Stäubli Robotics Suite opens and
what is copied to `usrapp/`): a folder `<app>/` holding `<app>.pjx` (the project),
`<app>.dtx` (the global data: points, joints, tools, frames, motion descriptors, I/O) and one
`.pgx` XML file per program (`start`, `stop`, one per proc call) with the VAL3 code in CDATA.

Vendor conventions (VAL3 reference manual):
  * lengths mm, angles deg, `trsf` = {x, y, z, rx, ry, rz} with R = Rx(rx)·Ry(ry)·Rz(rz)
    (rotation about x, then about the new y, then the new z);
  * `pointRx` = trsf + config {shoulder lefty|righty, elbow epositive|enegative,
    wrist wpositive|wnegative} from the planned branch (front = lefty, back = righty; elbow up
    = epositive, down = enegative; no-flip = wpositive, flip = wnegative), linked to a frame:
    `world` (the robot base) or a cell frame declared as a `frame` datum when the move names
    one (the point is then the TCP relative to that frame);
  * `jointRx` in degrees: joint moves go to the planned joints with `movej(jointRx, tool, mdesc)`;
    linear and circular moves are `movel(point, tool, mdesc)` and `movec(via, target, tool, mdesc)`;
  * `tool` data = the TCP in the flange (`fatherId="flange[0]"`); the bare flange is `flange`;
  * `mdesc` {accel, vel, decel (% of nominal joint accel/speed), tmax (mm/s), rmax (deg/s),
    blend off|joint|Cartesian, leave, reach (mm)}: joint moves take vel/accel/decel from the
    IR's fractions; linear moves take tmax = the TCP speed; a blend radius r becomes
    leave = reach = r (blend joint for joint moves, Cartesian otherwise); TCP accelerations in
    mm/s^2 have no mdesc field (accel stays 100 %, one warning per program when a non-default
    TCP acceleration was programmed);
  * payload: VAL3 `tool` data carries no mass, so a tool with a mass warns W411 once: its mass
    and centre of gravity (half way flange->TCP, base.tool_cog) must be entered in the arm's
    payload settings on the controller;
  * motion commands are queued: I/O, waits and delays would run before the robot arrives, so
    a `waitEndMove()` precedes each of them (a blend into it becomes an exact stop: warned);
    `start` ends with one so the application does not end before the robot;
  * I/O: `dio` arrays `dOut`/`dIn` linked to `BasicIO-1\\%Qn` / `BasicIO-1\\%In`; set is
    `dOut[n] = true` (n in DIGITAL_PORTS = 0..63, the size rmot declares for the arrays);
    a pulse is set, `delay`, reset (blocking: warned); wait with timeout is
    `bOk = watch(dIn[n] == true, s)` then, when it timed out, `popUpMsg` and `logMsg` name the
    input and `stopMove()`, `resetMotion()`, `return` stop the program (rmot's timeout
    semantics, see base.py; VAL3 reference manual: watch, popUpMsg, logMsg, stopMove,
    resetMotion — `return` ends the current program: inside a proc the caller continues, so
    procs check the same way); if is `if ... else ... endIf`;
    procs are `call name()`; native val3 text is passed through; an analog output is
    `aioSet(aOut[n], value)` with `aOut` declared unlinked (no standard physical name: warned);
  * comments: `// file.rmot:12`.
  * sync: one application per controller has no barrier, so the k-th sync of a task is the
    I/O handshake of backends/handshake.py: `dOut[o] = true` (odd k) or false (even k) then
    `wait(dIn[i] == ...)`, o and i being the robot's `io out[o] = "sync"` /
    `io in[i] = "sync"` of the cell (wired crosswise); a waitEndMove() precedes it like any I/O.

Runtime logic (the block at the end of the class): task variables as global num/bool
data, infix expressions, if/while/for, watch() with the timeout branch, `for` loops with
compose(point, frame, trShift) offsets or unrolled (W420), stop = waitEndMove() + return.

Size limits: VAL3 sets no line limit on a program and data arrays grow dynamically, so
programs are not split. Names: identifiers of letters, digits and `_`, at most 15 characters.

Support (checked by tests/backends/test_val3.py):
  exact     movej (planned joints), movel/movec (points with config, in world or a cell
            frame), tools, mdesc speeds and blends, dio set, delay, wait / watch with timeout,
            if/else, call, native val3, source comments;
  warned    programmed TCP acceleration (W408, once), tool payload (W411, once per tool), fixed duration (W409), pulse made blocking (W451),
            a blend stopped by waitEndMove() before I/O (W453), analog out on an unlinked aio
            (W455), legalised names (W400/W401), other vendors' native blocks (W407);
  lowered   sync as the I/O handshake (odd count W410);
  refused   sync without the cell's "sync" signals (E409) or inside an if arm (E405), ports outside 0..63 (E404), points without a full branch (E402),
            moves without a planned solution (E401), circular without via (E451).
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import ClassVar

from rmot.backends import codes
from rmot.backends.base import Backend, TaskContext, fmt
from rmot.backends.codes import LOOP_UNROLLED, STOP_IN_ROUTINE
from rmot.backends.loops import LoopTemplate, analyse, bind_loop_var, level_moves
from rmot.backends.runtime import loop_plan
from rmot.backends.val3_data import NO_LIMIT, VAL3_RULES, XSI, Val3Context, config_attrs, trsf_attrs
from rmot.lang import ir, ir_tree, plan_types
from rmot.lang.source import Span

__all__ = ["Val3Backend", "config_attrs", "trsf_attrs"]

class Val3Backend(Backend):
    name = "val3"
    file_ext = ".pgx"
    COMMENT = "//"
    SYNC_HANDSHAKE = True  # sync -> the I/O handshake of backends/handshake.py
    NAME_RULES = VAL3_RULES
    DIGITAL_PORTS = (0, 63)  # dIn / dOut arrays linked to BasicIO-1\%I / %Q
    NO_RECORD_NOTE = None
    WAITS_FOR_MOTION: ClassVar[tuple[type, ...]] = (ir.SetDigital, ir.SetAnalog, ir.Pulse,
                                                    ir.WaitTime, ir.WaitInput, ir.If,
                                                    ir.While, ir.WaitCondition, ir.Stop)
    NO_MOTION: ClassVar[tuple[type, ...]] = (ir.SetDigital, ir.SetAnalog, ir.Pulse, ir.WaitTime,
                                             ir.WaitInput, ir.WaitCondition)
    PRINTS_LOOPS = True  # for ... endFor, targets moved by compose(..., trShift)
    RUNTIME_CONDITIONS = True  # writes and/or/not, aIn, variables and timeout branches

    # ------------------------------------------------------------------ application

    def emit_task(self, task: TaskContext) -> dict[str, str]:
        names, app, body = self.open_task(task)
        for reserved in ("start", "stop", "aOut", "dOut", "dIn", "bOk", "pTarget", "jTarget",
                         "mSpeed", "aIn", "bStop"):
            names.reserve(reserved)  # taken after the app is named (the order decides a clash)
        ctx = task.with_state(Val3Context, names=names, routine_of=self.routine_table(names, body, task))
        main = self.block(body, ctx) + ["waitEndMove()"]
        if "bStop" in ctx.data.variables:  # a stop in a called program; clear it first
            main.insert(0, "bStop = false")
        ctx.programs["start"] = main
        ctx.programs["stop"] = []
        self.extend(names.diagnostics)
        files = {f"{app}/{app}.pjx": self.project(app, ctx), f"{app}/{app}.dtx": self.database(ctx)}
        head = self.header(ctx)
        for prog, code in sorted(ctx.programs.items()):
            code = (head if prog == "start" else []) + code
            files[f"{app}/{prog}.pgx"] = self.program(prog, code, ctx.locals.get(prog, {}))
        return dict(sorted(files.items()))

    @staticmethod
    def project(app: str, ctx: Val3Context) -> str:
        programs = "".join(f'    <Program file="{p}.pgx" />\n' for p in sorted(ctx.programs))
        return ('<?xml version="1.0" encoding="utf-8"?>\n'
                '<Project xmlns="http://www.staubli.com/robotics/VAL3/Project/3">\n'
                '  <Parameters version="s7.11" stackSize="5000" millimeterUnit="true" />\n'
                f"  <Programs>\n{programs}  </Programs>\n"
                f'  <Database>\n    <Data file="{app}.dtx" />\n  </Database>\n'
                "  <Libraries />\n</Project>\n")

    def program(self, name: str, code: list[str], extra: dict[str, str] | None = None) -> str:
        text = "\n".join(["begin", *self.indent(code, self.INDENT), "end"]).replace("]]>", "]]]]><![CDATA[>")
        more = "".join(f'      <Local name="{n}" type="{t}" xsi:type="array" size="1" />\n'
                       for n, t in sorted((extra or {}).items()))
        locals_ = ('    <Locals>\n      <Local name="bOk" type="bool" xsi:type="array" size="1" />\n'
                   f'{more}    </Locals>\n')
        return ('<?xml version="1.0" encoding="utf-8"?>\n'
                f'<Programs {XSI} xmlns="http://www.staubli.com/robotics/VAL3/Program/2">\n'
                f'  <Program name="{name}">\n{locals_}'
                f"    <Code><![CDATA[{text}]]></Code>\n  </Program>\n</Programs>\n")

    @staticmethod
    def database(ctx: Val3Context) -> str:
        d = ctx.data
        entries: dict[str, tuple[str, list[str]]] = {
            "aOut": ("aio", ['link=""'] * d.analog),
            "aIn": ("aio", ['link=""'] * d.analog_in),
            "dIn": ("dio", [f'link="BasicIO-1\\%I{k}"' for k in range(d.inputs)]),
            "dOut": ("dio", [f'link="BasicIO-1\\%Q{k}"' for k in range(d.outputs)]),
            "jTarget": ("jointRx", d.joints),
            "mSpeed": ("mdesc", d.mdescs),
            "pTarget": ("pointRx", d.points),
        }
        entries.update({n: ("frame", [v]) for n, v in d.frames.items()})
        entries.update({n: (kind, [v]) for n, (kind, v) in d.variables.items()})
        entries.update({n: ("tool", [v]) for n, v in d.tools.items()})
        out = ['<?xml version="1.0" encoding="utf-8"?>',
               f'<Database {XSI} xmlns="http://www.staubli.com/robotics/VAL3/Data/2">', "  <Datas>"]
        for name, (kind, values) in sorted(entries.items()):
            if not values:
                continue
            out.append(f'    <Data name="{name}" access="private" xsi:type="array" type="{kind}" size="{len(values)}">')
            out += [f'      <Value key="{k}" {v} />' for k, v in enumerate(values)]
            out.append("    </Data>")
        return "\n".join(out + ["  </Datas>", "</Database>"]) + "\n"

    def block(self, nodes: tuple[ir.Instr, ...], ctx: Val3Context, settled: bool = False) -> list[str]:
        """A body with `waitEndMove()` before each instruction that must follow the motion.

        `settled`: no motion is queued when the block starts (an `if` arm: the `if` waited).
        """
        out: list[str] = []
        prev: ir.Instr | None = None
        for node in nodes:
            if isinstance(node, self.WAITS_FOR_MOTION) and not settled:
                self.wait_end_move(prev, node, ctx)
                out.append("waitEndMove()")
            out.extend(self.instr(node, ctx))
            if not isinstance(node, (ir.VarDecl, ir.Assign)):  # these leave the motion queue as is
                settled = isinstance(node, self.NO_MOTION)  # these ran with no motion queued
            prev = node
        return out

    def wait_end_move(self, prev: ir.Instr | None, node: ir.Instr, ctx: TaskContext) -> None:
        last = _last_move(prev)
        rec = ctx.record(last) if last is not None else None
        if rec is not None and rec.blend_radius > 0.0:
            self.warn(codes.WAIT_END_MOVE, "the move before this instruction blends "
                      f"({rec.blend_radius * 1000:g} mm), but VAL3 must waitEndMove() first: it "
                      "stops exactly", getattr(node, "span", None))

    # ------------------------------------------------------------------ motion

    @staticmethod
    def tool(ref: ir.ToolRef, ctx: Val3Context) -> str:
        if ref.name is None:
            return "flange"
        name = ctx.names.name("t_" + ref.name)
        ctx.data.tools[name] = f'{trsf_attrs(ref.tcp)} fatherId="flange[0]" ioLink="" open="0" close="0"'
        return name

    @staticmethod
    def point(pose: ir.Pose, branch: ir.Config, frame: ir.FrameRef, ctx: Val3Context) -> str:
        father = "world[0]"
        if frame.name is not None:
            fname = ctx.names.name("f_" + frame.name)
            ctx.data.frames[fname] = f'{trsf_attrs(frame.pose)} fatherId="world[0]"'
            father = f"{fname}[0]"
            pose = frame.pose.inverse() * pose
        value = f'{trsf_attrs(pose)} {config_attrs(branch)} fatherId="{father}"'
        return f"pTarget[{ctx.data.index(ctx.data.points, value)}]"

    def mdesc(self, node: ir.Move, blend: float, ctx: Val3Context) -> str:
        m = node.motion
        if node.kind is ir.MotionKind.JOINT:
            pct = (fmt(m.joint_accel * 100, 3), fmt(m.joint_speed * 100, 3), fmt(m.joint_accel * 100, 3))
            tmax, kind = NO_LIMIT, "joint"
        else:
            pct, tmax, kind = ("100.000",) * 3, fmt(m.tcp_speed * 1000.0, 3), "Cartesian"
            self.warn_accel(node, ctx, "VAL3 mdesc sets accelerations only as % of nominal "
                            "joint acceleration; this program uses 100 % for TCP moves")
        if m.duration is not None:
            self.warn(codes.DURATION_IGNORED, f"VAL3 has no fixed-duration move; the duration "
                      f"{m.duration:g} s is expressed by the speed only", node.span)
        mm = fmt(blend * 1000.0, 3)
        value = (f'accel="{pct[0]}" vel="{pct[1]}" decel="{pct[2]}" tmax="{tmax}" rmax="{NO_LIMIT}" '
                 f'blend="{kind if blend > 0 else "off"}" leave="{mm}" reach="{mm}"')
        return f"mSpeed[{ctx.data.index(ctx.data.mdescs, value)}]"

    def move(self, node: ir.Move, ctx: Val3Context) -> list[str]:
        rec = self.move_record(node, ctx)
        if isinstance(rec, list):
            return rec
        self.warn_payload(node, ctx, "the arm's payload settings on the controller (VAL3 tool data has no mass)")
        tool, speed = self.tool(node.tool, ctx), self.mdesc(node, rec.blend_radius, ctx)
        return self.by_kind(node)(node, rec, ctx, f"{tool}, {speed}")

    def move_joint(self, node: ir.Move, rec: plan_types.InstructionRecord, ctx: Val3Context,
                   tail: str) -> list[str]:
        if (node.uid, "target") in ctx.offsets:  # a joint move of a vendor loop
            branch = self.branch(rec, node)
            if branch is None or rec.tcp_pose is None:
                return []
            point = self.point(rec.tcp_pose, branch, node.frame, ctx)
            point = self._shifted(point, node, "target", ctx)
            return [f"movej({point}, {tail})"]
        value = " ".join(f'j{k + 1}="{fmt(v, 4)}"' for k, v in enumerate(_degrees(rec.q_target)))
        return [f"movej(jTarget[{ctx.data.index(ctx.data.joints, value)}], {tail})"]

    def move_linear(self, node: ir.Move, rec: plan_types.InstructionRecord, ctx: Val3Context,
                    tail: str) -> list[str]:
        branch = self.branch(rec, node)
        if branch is None or rec.tcp_pose is None:
            return []
        target = self._shifted(self.point(rec.tcp_pose, branch, node.frame, ctx), node, "target", ctx)
        return [f"movel({target}, {tail})"]

    def move_circular(self, node: ir.Move, rec: plan_types.InstructionRecord, ctx: Val3Context,
                      tail: str) -> list[str]:
        branch = self.branch(rec, node)
        if branch is None or rec.tcp_pose is None:
            return []
        target = self.point(rec.tcp_pose, branch, node.frame, ctx)
        target = self._shifted(target, node, "target", ctx)
        if self.via_refused(node):
            return []
        assert node.via is not None  # refused above otherwise
        via = self._shifted(self.point(node.via.pose, branch, node.frame, ctx), node, "via", ctx)
        return [f"movec({via}, {target}, {tail})"]

    def branch(self, rec: plan_types.InstructionRecord, node: ir.Move) -> ir.Config | None:
        b = rec.branch
        if b is None or None in (b.shoulder, b.elbow, b.wrist):
            self.unsupported(codes.NO_BRANCH, "a VAL3 point must have a full 6-axis configuration "
                             "(got none: not a 6R arm, or no plan)", node.span)
            return None
        return b

    # ------------------------------------------------------------------ I/O and timing

    def port(self, port: int, span: object, output: bool, ctx: Val3Context) -> str | None:
        if not self.port_ok(port, f"digital {'output' if output else 'input'}", span):  # type: ignore[arg-type]
            return None
        if output:
            ctx.data.outputs = max(ctx.data.outputs, port + 1)
            return f"dOut[{port}]"
        ctx.data.inputs = max(ctx.data.inputs, port + 1)
        return f"dIn[{port}]"

    def set_digital(self, node: ir.SetDigital, ctx: Val3Context) -> list[str]:
        sig = self.port(node.port, node.span, True, ctx)
        return [f"{sig} = {'true' if node.value else 'false'}"] if sig else []

    def set_analog(self, node: ir.SetAnalog, ctx: Val3Context) -> list[str]:
        if not self.port_ok(node.port, "analog output", node.span):
            return []
        if node.port >= ctx.data.analog:
            ctx.data.analog = node.port + 1
        self.warn(codes.ANALOG_LINK, f"analog outputs have no standard VAL3 name: aOut[{node.port}] "
                  "is declared unlinked; link it to the controller's output in the data file", node.span)
        return [f"aioSet(aOut[{node.port}], {fmt(node.value, 4)})"]

    def pulse(self, node: ir.Pulse, ctx: Val3Context) -> list[str]:
        sig = self.port(node.port, node.span, True, ctx)
        if sig is None:
            return []
        self.warn(codes.PULSE_INLINE, f"VAL3 has no pulse instruction; out[{node.port}] is set, "
                  f"held {node.duration:g} s with delay(), then reset (the program waits)", node.span)
        return [f"{sig} = true", f"delay({fmt(node.duration, 4)})", f"{sig} = false"]

    def wait_time(self, node: ir.WaitTime, ctx: Val3Context) -> list[str]:
        return [f"delay({fmt(node.duration, 4)})"]

    def condition(self, cond: ir.InputCondition, span: object, ctx: Val3Context) -> str | None:
        sig = self.port(cond.port, span, False, ctx)
        return f"{sig} == {'true' if cond.value else 'false'}" if sig else None

    def wait_input(self, node: ir.WaitInput, ctx: Val3Context) -> list[str]:
        test = self.condition(node.condition, node.span, ctx)
        if test is None:
            return []
        if node.timeout is None:
            return [f"wait({test})"]
        c = node.condition
        message = f'"wait for dIn[{c.port}] == {str(c.value).lower()} timed out after {fmt(node.timeout, 3)} s"'
        if not node.on_timeout and ctx.where[-1] == "start":
            return [f"bOk = watch({test}, {fmt(node.timeout, 4)})", "if !bOk",
                    *self.indent([f"popUpMsg({message})", f"logMsg({message})", "stopMove()",
                                  "resetMotion()", "return"], self.INDENT), "endIf"]
        return self._timeout_branch(test, node.timeout, node.on_timeout, message, ctx, node.span)

    def if_(self, node: ir.If, ctx: Val3Context) -> list[str]:
        if not isinstance(node.condition, ir.InputCondition):  # any condition
            return self._if_condition(node, ctx)
        test = self.condition(node.condition, node.span, ctx)
        if test is None:
            return []
        lines = [f"if {test}"] + self.indent(self.block(node.then, ctx, settled=True), self.INDENT)
        if node.otherwise:
            lines += ["else"] + self.indent(self.block(node.otherwise, ctx, settled=True), self.INDENT)
        return lines + ["endIf"]

    # ------------------------------------------------------------------ structure

    def proc_call(self, node: ir.ProcCall, ctx: Val3Context) -> list[str]:
        name = ctx.routine_of[node.uid]
        shifted = tuple(ctx.offsets.get((m.uid, "target"))
                        for m in ir_tree.walk(node.body) if isinstance(m, ir.Move))
        if any(s is not None for s in shifted):  # a call in a loop with shifted moves
            key = (name, shifted)
            if key not in ctx.loop_programs:
                ctx.loop_programs[key] = ctx.names.name(f"{name}_L{len(ctx.loop_programs) + 1}")
            name = ctx.loop_programs[key]
        if name not in ctx.programs:  # calls printing the same routine share it (routine_table)
            ctx.programs[name] = []  # reserve the slot first: programs keep call order
            ctx.where.append(name)
            ctx.programs[name] = [self.comment(f"proc {node.proc}"), *self.block(node.body, ctx)]
            ctx.where.pop()
        after = []
        if _can_stop(node.body):  # a stop in the called program ends this one too
            ctx.data.variables["bStop"] = ("bool", 'value="false"')
            back = self._stop_return(ctx, node.span)
            after = ["if bStop", *self.indent(back, self.INDENT), "endIf"]
        return self.call_args_comment(node) + [f"call {name}()"] + after

    # ------------------------------------------------------------------ runtime logic
    # VAL3 has typed variables and infix expressions (VAL3 Reference Manual s7, "Simple types":
    # num, bool; operators + - * /, == != < <= > >=, and or !), so the IR's expressions are
    # written as they read. A task's `var`s are global data (`num`/`bool` in the .dtx: a called
    # program must read them); a loop's counter is a local of the program holding the loop
    # (<Locals>), its shift (trShiftN) global data (a called program's moves read it).
    # `for v = a to b ... endFor` and `while c ... endWhile` are VAL3's own loops (manual,
    # "Instructions": for, while); a target that moves from one iteration to the next is
    # `compose(point, frame, trShift)` (manual, "Arm positions", compose: the point with the
    # transformation applied, defined relative to the frame; trShift has no rotation, so it
    # translates the point along the frame's axes: the frame the point is linked to). `stop`
    # waits for the queued motion (waitEndMove) and returns from start(), which ends the
    # application's only task (manual 2.1.3 "Start/stop"); in a called program it sets bStop
    # and returns, and every caller returns when bStop is set.

    def _global(self, name: str, vtype: ir.ValueType, ctx: Val3Context) -> str:
        legal = ctx.names.name(name)
        ctx.data.variables[legal] = (("bool", 'value="false"') if vtype is ir.ValueType.BOOL
                                     else ("num", 'value="0"'))
        return legal

    def _local(self, name: str, kind: str, ctx: Val3Context) -> str:
        legal = ctx.names.name(name)
        ctx.locals.setdefault(ctx.where[-1], {})[legal] = kind
        return legal

    def _ref(self, name: str, ctx: Val3Context) -> str:
        """A variable's VAL3 name: a loop counter in scope, else the task variable."""
        for scope in reversed(ctx.scopes):
            if name in scope:
                return scope[name]
        return ctx.names.name(name)

    def var_decl(self, node: ir.VarDecl, ctx: Val3Context) -> list[str]:
        return [f"{self._global(node.name, node.type, ctx)} = {self.expr(node.init, node, ctx)}"]

    def assign(self, node: ir.Assign, ctx: Val3Context) -> list[str]:
        return [f"{self._ref(node.name, ctx)} = {self.expr(node.value, node, ctx)}"]

    def expr(self, e: ir.RtExpr | ir.Condition, node: ir.Instr, ctx: Val3Context,
             nested: bool = False) -> str:
        """`e` as a VAL3 expression (binary operations in parentheses when nested)."""
        if isinstance(e, ir.Const):
            if isinstance(e.value, bool):
                return "true" if e.value else "false"
            return str(e.value) if isinstance(e.value, int) else fmt(e.value, 6).rstrip("0").rstrip(".")
        if isinstance(e, ir.VarRef):
            return self._ref(e.name, ctx)
        if isinstance(e, ir.InputCondition):
            test = self.condition(e, node.span, ctx) or "false"
            return f"({test})" if nested else test
        if isinstance(e, ir.OutputRead):  # a dio linked to an output reads its state (VAL3 manual, "dio")
            test = f"{sig} == true" if (sig := self.port(e.port, node.span, True, ctx)) else "false"
            return f"({test})" if nested else test
        if isinstance(e, ir.AnalogInput):
            if not self.port_ok(e.port, "analog input", node.span):
                return "0"
            ctx.data.analog_in = max(ctx.data.analog_in, e.port + 1)
            self.warn(codes.ANALOG_LINK, f"analog inputs have no standard VAL3 name: aIn[{e.port}] is declared "
                      "unlinked; link it to the controller's input in the data file", node.span)
            return f"aioGet(aIn[{e.port}])"
        if isinstance(e, ir.GroupInput):  # a group needs the cell's own fieldbus mapping, which rmot does not write
            self.unsupported(codes.LOGIC_UNSUPPORTED, f"gin[{e.port}] must be inputs VAL3 reads as one number (its dio reads one bit)", node.span)
            return "0"
        if isinstance(e, ir.Not):
            return f"!{self.expr(e.operand, node, ctx, True)}"
        if isinstance(e, ir.Arith):
            left, right = self.expr(e.left, node, ctx, True), self.expr(e.right, node, ctx, True)
            text = f"{left} {e.op} {right}"
        elif isinstance(e, ir.Compare):
            left, right = self.expr(e.left, node, ctx, True), self.expr(e.right, node, ctx, True)
            text = f"{left} {_VAL3_CMP[e.op]} {right}"
        elif isinstance(e, ir.Logic):
            text = f" {e.op} ".join(self.expr(o, node, ctx, True) for o in e.operands)
        else:
            self.unsupported(codes.LOGIC_UNSUPPORTED, "a value must be a constant, variable, "
                             f"input or an operation on them (got {type(e).__name__})", node.span)
            return "false"
        return f"({text})" if nested else text

    def _if_condition(self, node: ir.If, ctx: Val3Context) -> list[str]:
        lines = [f"if {self.expr(node.condition, node, ctx)}"]
        lines += self.indent(self.block(node.then, ctx, settled=True), self.INDENT)
        if node.otherwise:
            otherwise = self.block(node.otherwise, ctx, settled=True)
            lines += ["else"] + self.indent(otherwise, self.INDENT)
        return lines + ["endIf"]

    def while_(self, node: ir.While, ctx: Val3Context) -> list[str]:
        """`while`: the condition is read with no motion queued (a waitEndMove() ends a body
        that moves, as before the loop), as the plan reads it."""
        body = self.block(node.body, ctx, settled=True)
        moves = any(isinstance(n, ir.Move) for n in ir_tree.walk(node.body))
        if moves and not isinstance(node.body[-1], self.NO_MOTION):
            body.append("waitEndMove()")
        return [f"while {self.expr(node.condition, node, ctx)}", *self.indent(body, self.INDENT),
                "endWhile"]

    def _timeout_branch(self, test: str, timeout: float, on_timeout: tuple[ir.Instr, ...],
                        message: str, ctx: Val3Context, span: Span | None) -> list[str]:
        if not on_timeout:
            branch = [f"popUpMsg({message})", f"logMsg({message})", "stopMove()", "resetMotion()",
                      *self._stop_return(ctx, span)]
        else:
            branch = self.block(on_timeout, ctx, settled=True)
        return [f"bOk = watch({test}, {fmt(timeout, 4)})", "if !bOk",
                *self.indent(branch, self.INDENT), "endIf"]

    def wait_condition(self, node: ir.WaitCondition, ctx: Val3Context) -> list[str]:
        test = self.expr(node.condition, node, ctx)
        if node.timeout is None:
            return [f"wait({test})"]
        message = f'"wait until timed out after {fmt(node.timeout, 3)} s"'
        return self._timeout_branch(test, node.timeout, node.on_timeout, message, ctx, node.span)

    def stop(self, node: ir.Stop, ctx: Val3Context) -> list[str]:
        return self._stop_return(ctx, node.span)  # the waitEndMove() before it: WAITS_FOR_MOTION

    def _stop_return(self, ctx: Val3Context, span: Span | None) -> list[str]:
        if ctx.where[-1] == "start":
            return ["return"]
        ctx.data.variables["bStop"] = ("bool", 'value="false"')
        self.warn_once(ctx, f"stop:{ctx.where[-1]}", STOP_IN_ROUTINE, "stop in the called program "
                       f"'{ctx.where[-1]}' sets bStop and returns; each caller returns when bStop "
                       "is set (a VAL3 program cannot end its caller)", span)
        return ["bStop = true", "return"]

    # ---------------------------------------------------------------- loops

    def loop(self, node: ir.Loop, ctx: Val3Context) -> list[str]:
        template = ctx.inner.pop(node.uid, None)
        if template is not None:  # a nested loop of a vendor loop being written
            return self._vendor_loop(template, ctx)
        found = analyse(node, ctx.record, extra_key=_blend_key,
                        unroll=bool(getattr(self, "unroll", False)))
        plan = loop_plan(node, found)  # the one loop decision (backends/runtime.py)
        if plan.why:  # before the loop's own findings
            self.warn(LOOP_UNROLLED, plan.why, plan.span)
        if plan.template is None:
            return self._unrolled(node, ctx)
        lines = self._vendor_loop(plan.template, ctx)
        if plan.last is None:
            return lines
        return lines + self._unrolled(replace(node, iterations=(plan.last,)), ctx)

    def _unrolled(self, node: ir.Loop, ctx: Val3Context) -> list[str]:
        lines: list[str] = []
        for it in node.iterations:
            body = bind_loop_var(it.body, node.var, it.value) if node.var else it.body
            label = f"{node.var or 'iteration'} = {it.value}"
            lines += [self.comment(label), *self.block(body, ctx)]
        return lines

    def _vendor_loop(self, template: LoopTemplate, ctx: Val3Context) -> list[str]:
        var = template.var
        counter = self._local(f"l_{var.name}" if var.name else "l_repeat", "num", ctx)
        ctx.counters[var.uid] = counter
        ctx.scopes.append({var.name: counter} if var.name else {})
        ctx.inner.update(template.inner)
        shifts = self._shift_lines(template, ctx)
        body = self.block(template.body, ctx)
        ctx.scopes.pop()
        return [f"for {counter} = {var.first} to {var.last}",
                *self.indent(shifts + body, self.INDENT), "endFor"]

    def _shift_lines(self, template: LoopTemplate, ctx: Val3Context) -> list[str]:
        """trShiftN.x/.y/.z = sum over the loops (counter - first) * step (mm) for every shift
        this level's own moves use (one local trsf per distinct shift)."""
        lines: list[str] = []
        done: set[str] = set()
        for uid in level_moves(template.body):
            for role in ("target", "via"):
                offset = template.targets.get((uid, role))
                if offset is None or not any(any(s) for s in offset.steps):
                    continue
                key = (tuple(v.uid for v in offset.loops),
                       tuple(tuple(round(c * 1000.0, 3) for c in s) for s in offset.steps))
                if key not in ctx.shifts:  # global data: a called program's moves read it too
                    ctx.shifts[key] = ctx.names.name(f"trShift{len(ctx.shifts) + 1}")
                    zero = 'x="0" y="0" z="0" rx="0" ry="0" rz="0"'
                    ctx.data.variables[ctx.shifts[key]] = ("trsf", zero)
                name = ctx.shifts[key]
                ctx.offsets[(uid, role)] = name
                if name in done:
                    continue
                done.add(name)
                for axis, field_name in enumerate("xyz"):
                    terms = []
                    for v, s in zip(offset.loops, offset.steps):
                        mm = round(s[axis] * 1000.0, 3)
                        if mm == 0:
                            continue
                        count = ctx.counters[v.uid]
                        base = f"({count} - {v.first})" if v.first else count
                        terms.append(f"{base} * {fmt(mm, 3).rstrip('0').rstrip('.')}")
                    lines.append(f"{name}.{field_name} = {' + '.join(terms) if terms else '0'}")
        return lines

    def _shifted(self, point: str, node: ir.Move, role: str, ctx: Val3Context) -> str:
        """`compose(point, frame, trShift)` for a loop target that moves per iteration."""
        name = ctx.offsets.get((node.uid, role))
        if name is None:
            return point
        frame = "world" if node.frame.name is None else ctx.names.name("f_" + node.frame.name)
        return f"compose({point}, {frame}, {name})"


def _last_move(node: ir.Instr | None) -> ir.Move | None:
    """The move that ends `node` (itself, or the last of a proc body), if any."""
    if isinstance(node, ir.Move):
        return node
    if node is None:
        return None
    runs, bodies = ir_tree.flow(node)
    if runs is ir_tree.Runs.CALL and bodies[0]:
        return _last_move(bodies[0][-1])
    return None


def _degrees(q: object) -> list[float]:
    return [math.degrees(float(v)) for v in q]  # type: ignore[attr-defined]


# ---------------------------------------------------------------- runtime logic helpers

_VAL3_CMP = {ir.CompareOp.EQ: "==", ir.CompareOp.NE: "!=", ir.CompareOp.LT: "<",
             ir.CompareOp.LE: "<=", ir.CompareOp.GT: ">", ir.CompareOp.GE: ">="}


def _blend_key(node: ir.Instr, rec: plan_types.InstructionRecord | None) -> object:
    """What VAL3 prints from a move's record beyond its target: the blend (mdesc leave/reach)."""
    return None if rec is None or not isinstance(node, ir.Move) else round(rec.blend_radius, 6)


def _can_stop(body: tuple[ir.Instr, ...]) -> bool:
    return any(isinstance(n, ir.Stop) for n in ir_tree.walk(body))
