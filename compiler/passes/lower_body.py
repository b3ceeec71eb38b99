"""Statements -> IR instructions for one task: loops unrolled, procs inlined, settings resolved.

The lowering runs the program at compile time: every value is a constant, so `for` and
`repeat` are unrolled, proc calls become ir.ProcCall nodes holding their substituted body,
and each Move gets the modal settings in force where it stands (its own modifiers win).
Runtime `if` on an input stays an ir.If; both arms are lowered.

Choices (LANGUAGE.md is silent):
  * `for i in a .. b` is half open (0 .. 3 runs 0, 1, 2), as in LANGUAGE.md's example;
    bounds are whole numbers; a .. b with b <= a runs no iteration.
  * A task may hold at most MAX_INSTRUCTIONS instructions after unrolling.
  * I/O ports are whole numbers >= 0; the cell's `io` declaration (for this robot or
    cell-wide) gives the signal name. `if`/`wait until` test digital inputs in[n];
    `a != on` is `a == off`; a bare `in[2]` means `in[2] == on`.
  * A pose target is the TCP pose in the active frame; the IR's CartesianTarget.pose is
    inv(robot base) * frame(world) * target. Linear and circular moves need pose targets;
    a joint move takes joints or a pose.
  * `time T` fixes a move's duration (Motion.duration); `config(...)` fills ir.Config.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

from rmot.compiler import codes, ir
from rmot.compiler.passes.context import Entry, Reporter, RobotInfo, Scope
from rmot.compiler.passes.lower_cell import IO_DIRECTIONS
from rmot.compiler.passes.evaluate import eval_expr, expect_bool, expect_integer, expect_quantity
from rmot.compiler.passes.limits import MAX_DURATION_S, MAX_ITERATIONS, MAX_PORT, MAX_POSITION_M, MAX_WORK_STEPS, within
from rmot.compiler.passes.modal import Modal, apply_setting
from rmot.compiler.passes.procs import bind_call
from rmot.lang.source import Span
from rmot.compiler.passes.scopes import declare, declare_procs, declare_value, misplaced
from rmot.compiler.passes.values import article, ANGLE, DIMENSIONLESS, LENGTH, TIME, JointsV, PoseV, Quantity, fmt_quantity, type_name
from rmot.lang import ast
from rmot.lang.parse import RESERVED

__all__ = ["MAX_INSTRUCTIONS", "TaskLowering", "VENDORS"]

MAX_INSTRUCTIONS = 200_000
VENDORS = ("rapid", "krl", "fanuc", "urscript", "inform", "val3")
_KINDS = {"joint": ir.MotionKind.JOINT, "linear": ir.MotionKind.LINEAR, "circular": ir.MotionKind.CIRCULAR}
_CONFIG = {"shoulder": ir.Shoulder, "elbow": ir.Elbow, "wrist": ir.Wrist}


_CALL_STEPS = 4  # measured: a proc call costs about five statements of lowering (issue #20)


class _TooLarge(Exception):
    pass


@dataclass
class TaskLowering:
    """Lowers the statements of one task (robot `robot`) of the program."""

    robot: str
    info: RobotInfo
    base: ir.Pose
    cell: ir.Cell
    rep: Reporter
    procs: list[Entry]
    count: int = 0
    steps: int = 0  # statements visited and loop rounds begun (bounded: MAX_WORK_STEPS)
    rounds: int = 0  # loop rounds begun in this task (bounded: MAX_ITERATIONS)
    stack: list[int] = field(default_factory=list)  # ids of the procs being inlined
    called: set[int] = field(default_factory=set)  # ids of the ProcDecls inlined at least once
    held: dict[str, Span | None] = field(default_factory=dict)  # parts held now -> where attached (issue #14)

    def run(self, body: tuple[ast.Stmt, ...], scope: Scope, modal: Modal, where: str) -> tuple[ir.Instr, ...]:
        try:
            out, _ = self.block(body, scope, modal, where)
        except _TooLarge:
            return ()
        for name, span in self.held.items():
            self.rep.warning(codes.PART_HELD_AT_END, f"part '{name}' is still held when task '{self.robot}' ends; "
                             f"detach it before the end", span)
        return tuple(out)

    def block(self, body: tuple[ast.Stmt, ...], scope: Scope, modal: Modal, where: str) -> tuple[list[ir.Instr], Modal]:
        out: list[ir.Instr] = []
        declare_procs(body, scope, self.rep, self.procs)
        for stmt in body:
            self.steps += 1
            if self.steps > MAX_WORK_STEPS:
                self.rep.error(codes.TOO_MUCH_WORK, f"a task must make the compiler visit at most {MAX_WORK_STEPS} statements "
                               "while unrolling loops and inlining procs (got more at this statement)", stmt.span)
                raise _TooLarge
            if isinstance(stmt, ast.Setting):
                modal = apply_setting(modal, stmt, scope, self.robot, self.base, self.rep)
                continue
            if isinstance(stmt, ast.For):
                out += self.for_loop(stmt, scope, modal, where)
                continue
            if isinstance(stmt, ast.Repeat):
                out += self.repeat(stmt, scope, modal, where)
                continue
            instr = self.statement(stmt, scope, modal, where)
            if instr is None:
                continue
            self.count += 1
            if self.count > MAX_INSTRUCTIONS:
                self.rep.error(codes.TOO_LARGE_UNROLLED, f"a task must have at most {MAX_INSTRUCTIONS} instructions after "
                               f"unrolling loops and inlining procs (got more at this statement)", stmt.span)
                raise _TooLarge
            out.append(instr)
        return out, modal

    def statement(self, s: ast.Stmt, scope: Scope, modal: Modal, where: str) -> ir.Instr | None:
        if isinstance(s, ast.Move):
            return self.move(s, scope, modal)
        if isinstance(s, (ast.TargetDecl, ast.ConstDecl)):
            declare_value(s, scope, self.rep)
        elif isinstance(s, ast.FrameDecl):
            v = eval_expr(s.value, scope, self.rep)
            if isinstance(v, PoseV):
                declare(scope, Entry("frame", s.name.name, PoseV(v.pose, s.name.name), s.name.span), self.rep)
            elif v is not None:
                self.rep.error(codes.WRONG_TYPE, f"frame '{s.name.name}' must be a pose (got {article(type_name(v))})", s.value.span)
        elif isinstance(s, ast.ProcDecl):
            if not where.startswith(("program", "task")):
                misplaced(s, where, self.rep)
        elif isinstance(s, ast.SetIo):
            return self.set_io(s, scope)
        elif isinstance(s, ast.Pulse):
            return self.pulse(s, scope)
        elif isinstance(s, ast.WaitTime):
            t = self._time(s.duration, scope, "wait time", allow_zero=True)
            return None if t is None else ir.WaitTime(uid=0, duration=t, span=s.span)
        elif isinstance(s, ast.WaitUntil):
            return self.wait_until(s, scope)
        elif isinstance(s, ast.IfStmt):
            return self.if_stmt(s, scope, modal, where)
        elif isinstance(s, ast.SyncStmt):
            return ir.Sync(uid=0, name=s.name.name, span=s.span)
        elif isinstance(s, ast.NativeStmt):
            return self.native(s)
        elif isinstance(s, ast.CallStmt):
            return self.call(s, scope, modal, where)
        elif isinstance(s, ast.AttachStmt):
            return self.attach(s, modal)
        else:
            misplaced(s, where, self.rep)
        return None

    # ---------------------------------------------------------------- loops and branches

    def for_loop(self, s: ast.For, scope: Scope, modal: Modal, where: str) -> list[ir.Instr]:
        lo = expect_integer(eval_expr(s.start, scope, self.rep), "loop start", s.start.span, self.rep, minimum=-(10**9))
        hi = expect_integer(eval_expr(s.stop, scope, self.rep), "loop end", s.stop.span, self.rep, minimum=-(10**9))
        out: list[ir.Instr] = []
        if lo is None or hi is None:
            return out
        self._rounds(hi - lo, s)
        for i in range(lo, hi):
            inner = scope.child()
            inner.names[s.var.name] = Entry("var", s.var.name, Quantity(float(i), DIMENSIONLESS, None, float(i)), s.var.span)
            errors = len(self.rep.sink)
            out += self.block(s.body, inner, modal, where)[0]
            if self._failed_since(errors):
                break  # the next rounds would only repeat the same diagnostics
        return out

    def repeat(self, s: ast.Repeat, scope: Scope, modal: Modal, where: str) -> list[ir.Instr]:
        n = expect_integer(eval_expr(s.count, scope, self.rep), "repeat count", s.count.span, self.rep)
        out: list[ir.Instr] = []
        self._rounds(n or 0, s)
        for _ in range(n or 0):
            errors = len(self.rep.sink)
            out += self.block(s.body, scope.child(), modal, where)[0]
            if self._failed_since(errors):
                break
        return out

    def _rounds(self, n: int, s: ast.Stmt) -> None:
        """Count n loop rounds against the task's budget before running any (issue #20)."""
        self.rounds += max(0, n)
        if self.rounds > MAX_ITERATIONS:
            self.rep.error(codes.TOO_MUCH_WORK, f"loops of a task must run at most {MAX_ITERATIONS} rounds in all "
                           f"(got {n} more here, {self.rounds} in all)", s.span)
            raise _TooLarge

    def _failed_since(self, before: int) -> bool:
        return self.rep.sink.errors_since(before)

    def if_stmt(self, s: ast.IfStmt, scope: Scope, modal: Modal, where: str) -> ir.Instr | None:
        cond = self.condition(s.condition, scope)
        before = dict(self.held)
        then = self.nested(s.then, scope.child(), modal, where)
        after_then, self.held = self.held, dict(before)
        otherwise = self.nested(s.otherwise, scope.child(), modal, where)
        if set(after_then) != set(self.held):
            differ = sorted(set(after_then) ^ set(self.held))
            self.rep.error(codes.PART_ARMS_DIFFER, f"both arms of an if must leave the same parts held (part "
                           f"{', '.join(repr(p) for p in differ)} is held after one arm only)", s.span)
        self.held = after_then
        if cond is None:
            return None
        return ir.If(uid=0, condition=cond, then=then, otherwise=otherwise, span=s.span)

    def nested(self, body: tuple[ast.Stmt, ...], scope: Scope, modal: Modal, where: str) -> tuple[ir.Instr, ...]:
        return tuple(self.block(body, scope, modal, where)[0])

    # ---------------------------------------------------------------- procs

    def call(self, s: ast.CallStmt, scope: Scope, modal: Modal, where: str) -> ir.Instr | None:
        entry = scope.lookup(s.name.name)
        if entry is None:
            if s.name.name not in RESERVED:  # `return()`: the parser said it is reserved (E008)
                procs = [n for n in scope.visible() if (e := scope.lookup(n)) is not None and e.kind == "proc"]
                self.rep.unknown(s.name.name, "proc", s.name.span, procs)
            return None
        if entry.kind != "proc":
            self.rep.error(codes.WRONG_TYPE, f"'{s.name.name}' must be a proc to be called (got {article(entry.kind)})", s.name.span,
                           ((f"'{s.name.name}' is defined here", entry.span),))
            return None
        if id(entry) in self.stack:  # recursion: reported by the check_recursion pass
            return None
        self.called.add(id(entry.value))
        self.steps += _CALL_STEPS  # binding arguments and a scope: several statements' worth of work
        inner = bind_call(entry, s, scope, self.rep)
        if inner is None:
            return None
        self.stack.append(id(entry))
        try:
            body = self.nested(entry.value.body, inner, modal, f"proc '{entry.name}'")
        finally:
            self.stack.pop()
        self.steps += _node_count(body)  # re-spanning the inlined body is work too: a fan-out of empty procs
        if self.steps > MAX_WORK_STEPS:  # costs one step per nested node per level (issue #20)
            self.rep.error(codes.TOO_MUCH_WORK, f"a task must make the compiler visit at most {MAX_WORK_STEPS} statements "
                           "while unrolling loops and inlining procs (got more at this call)", s.span)
            raise _TooLarge
        text = s.span.file.text
        args = tuple(text[a.span.start.offset:a.span.end.offset] for a in s.args)
        body = tuple(_expanded_at(instr, s.span) for instr in body)
        return ir.ProcCall(uid=0, proc=entry.name, args=args, body=body, span=s.span)

    # ---------------------------------------------------------------- I/O and timing

    def _time(self, e: ast.Expr, scope: Scope, what: str, allow_zero: bool = False) -> float | None:
        t = expect_quantity(eval_expr(e, scope, self.rep), TIME, what, e.span, self.rep)
        if t is not None and (t < 0 or (t == 0 and not allow_zero)):
            self.rep.error(codes.OUT_OF_RANGE, f"{what} must be {'>= 0' if allow_zero else '> 0'} s (got {t:g} s)", e.span)
            return None
        return within(t, 0.0, MAX_DURATION_S, what, "s", 1.0, e.span, self.rep)

    def port(self, io: ast.IoRef, scope: Scope, allowed: tuple[str, ...], what: str) -> tuple[int, str | None] | None:
        if io.kind not in allowed:
            names = " or ".join(f"{k}[n]" for k in allowed)
            self.rep.error(codes.WRONG_TYPE, f"{what} must use {names} (got {io.kind}[...])", io.span)
            return None
        port = expect_integer(eval_expr(io.index, scope, self.rep), "I/O port", io.index.span, self.rep)
        if port is None or within(port, 0, MAX_PORT, "I/O port", "", 1, io.index.span, self.rep) is None:
            return None
        direction = IO_DIRECTIONS[io.kind]
        for sig in self.cell.io:
            if sig.direction is direction and sig.port == port and sig.robot in (self.robot, None):
                return port, sig.name
        return port, None

    def set_io(self, s: ast.SetIo, scope: Scope) -> ir.Instr | None:
        p = self.port(s.io, scope, ("out", "aout"), "set")
        v = eval_expr(s.value, scope, self.rep)
        if p is None or v is None:
            return None
        if s.io.kind == "out":
            level = expect_bool(v, f"value of out[{p[0]}]", s.value.span, self.rep)
            return None if level is None else ir.SetDigital(uid=0, port=p[0], value=level, signal=p[1], span=s.span)
        x = expect_quantity(v, DIMENSIONLESS, f"value of aout[{p[0]}]", s.value.span, self.rep)
        return None if x is None else ir.SetAnalog(uid=0, port=p[0], value=x, signal=p[1], span=s.span)

    def pulse(self, s: ast.Pulse, scope: Scope) -> ir.Instr | None:
        p = self.port(s.io, scope, ("out",), "pulse")
        t = self._time(s.duration, scope, "pulse length")
        if p is None or t is None:
            return None
        return ir.Pulse(uid=0, port=p[0], duration=t, signal=p[1], span=s.span)

    def condition(self, c: ast.Condition, scope: Scope) -> ir.InputCondition | None:
        p = self.port(c.io, scope, ("in",), "a condition")
        level = True if c.value is None else expect_bool(eval_expr(c.value, scope, self.rep), "the compared level", c.value.span, self.rep)
        if p is None or level is None:
            return None
        return ir.InputCondition(port=p[0], value=level if c.op == "==" else not level, signal=p[1])

    def wait_until(self, s: ast.WaitUntil, scope: Scope) -> ir.Instr | None:
        cond = self.condition(s.condition, scope)
        timeout = self._time(s.timeout, scope, "timeout") if s.timeout is not None else None
        if cond is None or (s.timeout is not None and timeout is None):
            return None
        return ir.WaitInput(uid=0, condition=cond, timeout=timeout, span=s.span)

    def native(self, s: ast.NativeStmt) -> ir.Instr | None:
        if s.vendor.name not in VENDORS:
            self.rep.unknown(s.vendor.name, "controller language", s.vendor.span, list(VENDORS), codes.UNKNOWN_VENDOR)
            return None
        return ir.Native(uid=0, vendor=s.vendor.name, text=s.text.value, span=s.span)

    # ---------------------------------------------------------------- parts (issue #14)

    def attach(self, s: ast.AttachStmt, modal: Modal) -> ir.Instr | None:
        """`attach NAME` / `detach NAME` (issue #14): the part must be a part of the cell, not held
        yet for attach, held by this task for detach. Whether the tool touches it is known only
        once the motion is planned (sim/parts.py, E330)."""
        name = s.part.name
        part = next((p for p in self.cell.parts if p.name == name), None)
        word = "attach" if s.attach else "detach"
        if part is None:
            self.rep.unknown(name, "part", s.part.span, [p.name for p in self.cell.parts], codes.UNKNOWN_PART)
            return None
        if s.attach and name in self.held:
            self.rep.error(codes.PART_ALREADY_HELD, f"part '{name}' must not be held already to attach it "
                           f"(task '{self.robot}' holds it)", s.part.span, (("attached here", self.held[name]),))
            return None
        if not s.attach and name not in self.held:
            self.rep.error(codes.PART_NOT_HELD, f"part '{name}' must be held by task '{self.robot}' to {word} it "
                           f"(got no attach before)", s.part.span)
            return None
        if s.attach:
            self.held[name] = s.span
        else:
            del self.held[name]
        masses = {p.name: p.mass for p in self.cell.parts}
        held = tuple(self.held)
        load = modal.tool.mass + sum(masses[p] for p in held)
        cls = ir.Attach if s.attach else ir.Detach
        return cls(uid=0, part=name, tool=modal.tool, held=held, load=load, span=s.span)

    # ---------------------------------------------------------------- motion

    def move(self, s: ast.Move, scope: Scope, modal: Modal) -> ir.Instr | None:
        config, duration, ok = ir.Config(), None, True
        for m in s.modifiers:
            if m.kind == "config":
                config = self.config(m) or config
            elif m.kind == "time":
                duration = self._time(m.value, scope, "move time")  # type: ignore[arg-type]
                ok = ok and duration is not None
            else:
                modal = apply_setting(modal, m, scope, self.robot, self.base, self.rep)
        kind = _KINDS[s.kind]
        target = self.target(s.target, scope, modal, kind, "target")
        via = self.target(s.via, scope, modal, kind, "via point") if s.via is not None else None
        if target is None or (s.via is not None and via is None) or not ok:
            return None
        if isinstance(target, ir.JointTarget):
            for m in s.modifiers:
                if m.kind == "config":  # joints fix the branch already: the planner ignores config here
                    self.rep.warning(codes.CONFIG_IGNORED, "config(...) must go with a pose target (got a joint target: "
                                     "joints fix the arm's configuration, there is no IK branch to choose); it is ignored", m.span)
        motion = ir.Motion(modal.tcp_speed, modal.tcp_accel, modal.joint_speed, modal.joint_accel, modal.zone, duration)
        return ir.Move(uid=0, kind=kind, target=target, via=via, motion=motion, tool=modal.tool,  # type: ignore[arg-type]
                       frame=modal.frame, config=config, span=s.span)

    def config(self, m: ast.Setting) -> ir.Config | None:
        values: dict[str, object] = {}
        for arg in m.value:  # type: ignore[union-attr]
            key = arg.name.name if arg.name is not None else None
            enum = _CONFIG.get(key or "")
            if enum is None:
                self.rep.unknown(key or "?", "config field", arg.span, list(_CONFIG))
                continue
            word = arg.value.name if isinstance(arg.value, ast.Name) else None
            choices = [e.value for e in enum]
            if word not in choices:
                self.rep.error(codes.BAD_ARGUMENT, f"config {key} must be {' or '.join(choices)} (got '{word or '?'}')", arg.value.span)
                continue
            values[key] = enum(word)  # type: ignore[index]
        return ir.Config(**values)  # type: ignore[arg-type]

    def target(self, e: ast.Expr, scope: Scope, modal: Modal, kind: ir.MotionKind, what: str) -> ir.CartesianTarget | ir.JointTarget | None:
        v = eval_expr(e, scope, self.rep)
        if v is None:
            return None
        if isinstance(v, PoseV):
            pose = modal.frame.pose * v.pose
            far = sum(c * c for c in pose.position) ** 0.5
            if within(far, 0.0, MAX_POSITION_M, f"{what} distance from the robot base", "m", 1.0, e.span, self.rep) is None:
                return None
            return ir.CartesianTarget(pose, v.pose, v.name)
        if isinstance(v, JointsV) and kind is ir.MotionKind.JOINT:
            return self.joints(v, e)
        wanted = "pose or joints" if kind is ir.MotionKind.JOINT else "pose"
        self.rep.error(codes.WRONG_TYPE, f"{what} of a {kind.name.lower()} move must be a {wanted} (got {article(type_name(v))})", e.span)
        return None

    def joints(self, v: JointsV, e: ast.Expr) -> ir.JointTarget | None:
        n = self.info.dof
        span = v.span or e.span
        notes = (("used by this move", e.span),) if v.span is not None and v.span != e.span else ()
        if len(v.values) != n:
            self.rep.error(codes.JOINT_COUNT, f"joints() must have {n} value{'s' * (n != 1)} for robot "
                           f"'{self.robot}' (got {len(v.values)})", span, notes)
            return None
        values = []
        for i, (q, jt) in enumerate(zip(v.values, self.info.joint_types)):
            dim = LENGTH if jt == "P" else ANGLE
            if q.dim != dim:
                self.rep.error(codes.WRONG_DIMENSION, f"joint {i + 1} of robot '{self.robot}' must be "
                               f"{'a length' if jt == 'P' else 'an angle'} (got {fmt_quantity(q)})", span, notes)
                return None
            values.append(q.value)
        return ir.JointTarget(tuple(values), v.name)


def _node_count(body: tuple[ir.Instr, ...]) -> int:
    n = 0
    for instr in body:
        n += 1
        if isinstance(instr, ir.If):
            n += _node_count(instr.then) + _node_count(instr.otherwise)
        elif isinstance(instr, ir.ProcCall):
            n += _node_count(instr.body)
    return n


def _expanded_at(instr: ir.Instr, call_site: Span | None) -> ir.Instr:
    """`instr` inlined at `call_site`: its span (and its children's) records the call, so a
    finding in a proc body can say which call it came through (Span.parent)."""
    if call_site is None:
        return instr
    changes: dict[str, object] = {}
    if instr.span is not None:
        changes["span"] = instr.span.with_parent(call_site)
    if isinstance(instr, ir.If):
        changes["then"] = tuple(_expanded_at(i, call_site) for i in instr.then)
        changes["otherwise"] = tuple(_expanded_at(i, call_site) for i in instr.otherwise)
    elif isinstance(instr, ir.ProcCall):
        changes["body"] = tuple(_expanded_at(i, call_site) for i in instr.body)
    return dataclasses.replace(instr, **changes)  # type: ignore[arg-type]
