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

Over 600 lines: the TaskLowering class alone is 625 lines, and a class is written in one piece
(its methods read its flags and tables)."""

from __future__ import annotations

from dataclasses import dataclass, field, replace

from rmot.lang.vendors import controllers
from rmot.lang import codes_axes, check_codes as codes, ir
from rmot.compiler.passes.context import Entry, Reporter, RobotInfo, Scope
from rmot.compiler.passes.lower_cell import IO_DIRECTIONS
from rmot.compiler.passes.evaluate import eval_expr, expect_bool, expect_integer, expect_quantity
from rmot.compiler.passes.limits import MAX_DURATION_S, MAX_ITERATIONS, MAX_PORT, MAX_POSITION_M, MAX_WORK_STEPS, within
from rmot.compiler.passes.modal import Modal, apply_setting, speed_modifier_warnings
from rmot.compiler.passes.lower_axes import ProgramAxes
from rmot.compiler.passes.procs import bind_call
from rmot.compiler.passes.runtime import TYPE_NAMES, RtLowering, expr_type, fits, reads_runtime
from rmot.lang.source import Span
from rmot.compiler.passes.scopes import declare, declare_procs, declare_value, misplaced
from rmot.compiler.passes.turns import TURN_KEY, turn_arg
from rmot.compiler.passes.values import article, ANGLE, DIMENSIONLESS, LENGTH, TIME, JointsV, PoseV, Quantity, fmt_quantity, type_name
from rmot.lang import ast
from rmot.lang.parse import RESERVED
from rmot.compiler.passes.lower_body_limits import (
    MAX_INSTRUCTIONS,
    MAX_NESTING,
    _KINDS,
    _FREE_OPTIONS,
    MAX_FREE_SAMPLES,
    MAX_FREE_CLEARANCE_M,
    _CONFIG,
    _CALL_STEPS,
    _node_count,
    _expanded_at,
)

__all__ = ["TaskLowering"]


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
    held: dict[str, Span | None] = field(default_factory=dict)  # parts held now -> where attached
    depth: int = 0  # blocks entered below the task's body (a `var` belongs to the body)
    axes: ProgramAxes | None = None  # the external axes the task drives (`with`), their values so far

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
        stopped = False
        for stmt in body:
            if stopped and not isinstance(stmt, (ast.ProcDecl, ast.TargetDecl, ast.ConstDecl)):
                self.rep.warning(
                    codes.UNREACHABLE_AFTER_STOP,
                    "this statement never runs: 'stop' before it in the same block ends the task",
                    stmt.span,
                )
                stopped = False  # once per block
            stopped = stopped or isinstance(stmt, ast.StopStmt)
            if self.depth > MAX_NESTING:
                self.rep.error(codes.TOO_LARGE_UNROLLED, f"blocks (loops, ifs, inlined procs) must nest at most {MAX_NESTING} "
                               f"levels deep (got {self.depth} at this statement)", stmt.span)
                raise _TooLarge
            self.steps += 1
            if self.steps > MAX_WORK_STEPS:
                self.rep.error(codes.TOO_MUCH_WORK, f"a task must make the compiler visit at most {MAX_WORK_STEPS} statements "
                               "while unrolling loops and inlining procs (got more at this statement)", stmt.span)
                raise _TooLarge
            if isinstance(stmt, ast.Setting):
                modal = apply_setting(modal, stmt, scope, self.robot, self.base, self.rep)
                continue
            if isinstance(stmt, ast.For):
                instr: ir.Instr | None = self.for_loop(stmt, scope, modal, where)
            elif isinstance(stmt, ast.Repeat):
                instr = self.repeat(stmt, scope, modal, where)
            else:
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
        if isinstance(s, ast.MoveAxes):
            return self.axes.move_axes(s, scope, self._time) if self.axes is not None else self._no_axes(s.span)
        if isinstance(s, (ast.TargetDecl, ast.ConstDecl, ast.FrameDecl)) and self.axes is not None:
            self.axes.read_at_home(s.value, f"'{s.name.name}'")  # a program's frame rides on nothing
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
            return self.wait_until(s, scope, modal, where)
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
        elif isinstance(s, ast.VarDecl):
            return self.var_decl(s, scope)
        elif isinstance(s, ast.AssignStmt):
            return self.assign(s, scope)
        elif isinstance(s, ast.StopStmt):
            return ir.Stop(uid=0, span=s.span)
        elif isinstance(s, ast.While):
            return self.while_loop(s, scope, modal, where)
        else:
            misplaced(s, where, self.rep)
        return None

    # ---------------------------------------------------------------- loops and branches

    def for_loop(self, s: ast.For, scope: Scope, modal: Modal, where: str) -> ir.Instr | None:
        """An ir.Loop with every iteration lowered, the loop variable bound to its value."""
        if s.stop is None:
            self.rep.error(
                codes.FOR_WITHOUT_BOUNDS,
                f"a for loop must have bounds: 'for {s.var.name} in FIRST .. END' "
                "(got no '..'; the end is excluded; use 'while COND' for a loop that runs until a "
                "condition)",
                s.span,
            )
            return None
        lo = expect_integer(
            eval_expr(s.start, scope, self.rep),
            "loop start",
            s.start.span,
            self.rep,
            minimum=-(10**9),
        )
        hi = expect_integer(
            eval_expr(s.stop, scope, self.rep), "loop end", s.stop.span, self.rep, minimum=-(10**9)
        )
        if lo is None or hi is None:
            return None
        self._rounds(hi - lo, s)
        iterations: list[ir.LoopIteration] = []
        for i in range(lo, hi):
            inner = scope.child()
            inner.names[s.var.name] = Entry(
                "var", s.var.name, Quantity(float(i), DIMENSIONLESS, None, float(i)), s.var.span
            )
            errors = len(self.rep.sink)
            self.depth += 1
            try:
                body = self.block(s.body, inner, modal, where)[0]
            finally:
                self.depth -= 1
            iterations.append(ir.LoopIteration(value=i, body=tuple(body)))
            if self._failed_since(errors):
                break  # the next rounds would only repeat the same diagnostics
        return ir.Loop(
            uid=0, var=s.var.name, first=lo, last=hi, iterations=tuple(iterations), span=s.span
        )

    def repeat(self, s: ast.Repeat, scope: Scope, modal: Modal, where: str) -> ir.Instr | None:
        n = expect_integer(
            eval_expr(s.count, scope, self.rep), "repeat count", s.count.span, self.rep
        )
        if n is None:
            return None
        self._rounds(n, s)
        iterations: list[ir.LoopIteration] = []
        for i in range(n):
            errors = len(self.rep.sink)
            self.depth += 1
            try:
                body = self.block(s.body, scope.child(), modal, where)[0]
            finally:
                self.depth -= 1
            iterations.append(ir.LoopIteration(value=i, body=tuple(body)))
            if self._failed_since(errors):
                break
        return ir.Loop(uid=0, var=None, first=0, last=n, iterations=tuple(iterations), span=s.span)

    def _rounds(self, n: int, s: ast.Stmt) -> None:
        """Count n loop rounds against the task's budget before running any."""
        self.rounds += max(0, n)
        if self.rounds > MAX_ITERATIONS:
            self.rep.error(codes.TOO_MUCH_WORK, f"loops of a task must run at most {MAX_ITERATIONS} rounds in all "
                           f"(got {n} more here, {self.rounds} in all)", s.span)
            raise _TooLarge

    def _failed_since(self, before: int) -> bool:
        return self.rep.sink.errors_since(before)

    def if_stmt(self, s: ast.IfStmt, scope: Scope, modal: Modal, where: str) -> ir.Instr | None:
        cond = self.any_condition(s.condition, scope, "the condition of an if")
        before = dict(self.held)
        axes_before = self.axes.state() if self.axes is not None else {}
        then = self.nested(s.then, scope.child(), modal, where)
        after_then, self.held = self.held, dict(before)
        axes_after_then = self.axes.state() if self.axes is not None else {}
        if self.axes is not None:  # each arm from the values before the if (lower_axes.py)
            self.axes.restart(axes_before)
        otherwise = self.nested(s.otherwise, scope.child(), modal, where)
        if self.axes is not None:
            self.axes.join_arms(axes_after_then, s.span)
        if set(after_then) != set(self.held):
            differ = sorted(set(after_then) ^ set(self.held))
            self.rep.error(codes.PART_ARMS_DIFFER, f"both arms of an if must leave the same parts held (part "
                           f"{', '.join(repr(p) for p in differ)} is held after one arm only)", s.span)
        self.held = after_then
        if cond is None:
            return None
        return ir.If(uid=0, condition=cond, then=then, otherwise=otherwise, span=s.span)

    def nested(self, body: tuple[ast.Stmt, ...], scope: Scope, modal: Modal, where: str) -> tuple[ir.Instr, ...]:
        self.depth += 1
        try:
            return tuple(self.block(body, scope, modal, where)[0])
        finally:
            self.depth -= 1

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
        if self.steps > MAX_WORK_STEPS:  # costs one step per nested node per level
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
            if io.kind == "gin":  # an input the controller reads, never an output a program drives
                self.rep.error(codes.GROUP_INPUT_WRITTEN, f"{what} must use {names} (got gin[...]: a group "
                               "input is read in conditions and expressions, never written)", io.span)
                return None
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

    def group_bits(self, port: int) -> int | None:
        """The width the cell gives group input `port` (`io gin[n] = "name" bits B`), if any."""
        for sig in self.cell.io:
            if sig.direction is ir.IoDirection.GROUP_IN and sig.port == port and sig.robot in (self.robot, None):
                return sig.bits
        return None

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

    def wait_until(
        self, s: ast.WaitUntil, scope: Scope, modal: Modal | None = None, where: str = ""
    ) -> ir.Instr | None:
        cond = self.any_condition(s.condition, scope, "the condition of 'wait until'")
        timeout = self._time(s.timeout, scope, "timeout") if s.timeout is not None else None
        on_timeout: tuple[ir.Instr, ...] = ()
        if s.on_timeout is not None and modal is not None:
            if not s.on_timeout:
                self.rep.warning(
                    codes.WAIT_ELSE_WITHOUT_TIMEOUT,
                    "the timeout branch is empty: 'timeout T else { }' is the same as 'timeout T'",
                    s.span,
                )
            before = dict(self.held)
            on_timeout = self.nested(s.on_timeout, scope.child(), modal, where)
            if set(before) != set(self.held):
                differ = sorted(set(before) ^ set(self.held))
                self.rep.error(
                    codes.PART_ARMS_DIFFER,
                    f"the timeout branch of 'wait until' must leave the same parts held "
                    f"as it found (part {', '.join(repr(p) for p in differ)} differs)",
                    s.span,
                )
            self.held = before
        if cond is None or (s.timeout is not None and timeout is None):
            return None
        if isinstance(cond, ir.InputCondition):
            return ir.WaitInput(
                uid=0, condition=cond, timeout=timeout, span=s.span, on_timeout=on_timeout
            )
        return ir.WaitCondition(
            uid=0, condition=cond, timeout=timeout, on_timeout=on_timeout, span=s.span
        )

    # ---------------------------------------------------------------- runtime state

    def rt(self, scope: Scope) -> RtLowering:
        return RtLowering(
            scope, self.rep, lambda io, allowed, what: self.port(io, scope, allowed, what), self.group_bits
        )

    def any_condition(self, c: ast.RtCond, scope: Scope, what: str) -> ir.Condition | None:
        """`in[n] == on|off` lowers as it always has (an InputCondition); anything else through
        compiler/passes/runtime.py (and/or/not, ain[n], variables, comparisons)."""
        if isinstance(c, ast.Condition) and c.io.kind == "in" and not reads_runtime(c.value, scope):
            return self.condition(c, scope)
        return self.rt(scope).condition(c, what)

    def var_decl(self, s: ast.VarDecl, scope: Scope) -> ir.Instr | None:
        name = s.name.name
        if self.depth > 0:
            self.rep.error(
                codes.VAR_MISPLACED,
                f"var '{name}' must be declared in the task's own body, not inside a loop, "
                "an if arm or a proc (a controller variable lives as long as the task)",
                s.span,
            )
            return None
        wanted: ir.ValueType | None = None
        if s.type is not None:
            wanted = TYPE_NAMES.get(s.type.name)
            if wanted is None:
                self.rep.unknown(
                    s.type.name,
                    "variable type (int, num or bool)",
                    s.type.span,
                    list(TYPE_NAMES),
                    codes.RT_BAD_TYPE_NAME,
                )
                return None
        rt = self.rt(scope)
        init = (
            rt.expr(s.value)
            if wanted is None
            else rt.typed(s.value, wanted, f"the initial value of var '{name}'")
        )
        first = scope.lookup(name)
        if first is not None:
            self.rep.error(
                codes.RT_REDECLARED,
                f"var '{name}' must have a name of its own (got the name of "
                f"{article(first.kind if first.kind != 'rtvar' else 'var')} already declared)",
                s.name.span,
                ((f"'{name}' is first declared here", first.span),),
            )
            return None
        if init is None:
            scope.names[name] = Entry(
                "rtvar", name, wanted or ir.ValueType.NUM, s.name.span
            )  # no "unknown" later
            return None
        vtype = wanted or expr_type(init)
        scope.names[name] = Entry("rtvar", name, vtype, s.name.span)
        return ir.VarDecl(uid=0, name=name, type=vtype, init=init, span=s.span)

    def assign(self, s: ast.AssignStmt, scope: Scope) -> ir.Instr | None:
        name = s.name.name
        entry = scope.lookup(name)
        rt = self.rt(scope)
        if entry is None:
            known = [
                n
                for n in scope.visible()
                if (e := scope.lookup(n)) is not None and e.kind == "rtvar"
            ]
            self.rep.unknown(name, "variable", s.name.span, known, codes.RT_UNKNOWN_VAR)
            rt.expr(s.value)  # its own errors too
            return None
        if entry.kind != "rtvar":
            what = "a loop variable" if entry.kind == "var" else article(entry.kind)
            self.rep.error(
                codes.RT_ASSIGN_NOT_VAR,
                f"only a var can be assigned ('{name}' is {what}, fixed when the "
                f"program is compiled; declare 'var NAME = ...' for a value that changes)",
                s.name.span,
                ((f"'{name}' is defined here", entry.span),),
            )
            return None
        value = rt.expr(s.value)
        if value is None:
            return None
        if not fits(expr_type(value), entry.value):
            self.rep.error(
                codes.RT_WRONG_TYPE,
                f"the value assigned to var '{name}' must be {entry.value.value} "
                f"(got {expr_type(value).value})",
                s.value.span,
                ((f"'{name}' is declared here", entry.span),),
            )
            return None
        return ir.Assign(uid=0, name=name, value=value, span=s.span)

    def while_loop(self, s: ast.While, scope: Scope, modal: Modal, where: str) -> ir.Instr | None:
        if s.condition is None:
            self.rep.error(
                codes.WHILE_WITHOUT_CONDITION,
                "a while loop must have a condition: 'while COND { ... }' "
                "(got none; for a fixed count use 'repeat N' or 'for i in a .. b')",
                s.span,
            )
            return None
        cond = self.rt(scope).condition(s.condition, "the condition of a while")
        before = dict(self.held)
        axes_before = self.axes.state() if self.axes is not None else {}
        body = self.nested(s.body, scope.child(), modal, where)
        if self.axes is not None:  # every pass from the same axis values (lower_axes.py)
            self.axes.check_pass(axes_before, s.span)
        if set(before) != set(self.held):
            differ = sorted(set(before) ^ set(self.held))
            self.rep.error(
                codes.WHILE_PARTS_DIFFER,
                f"a while body must end holding the parts it started with (part "
                f"{', '.join(repr(p) for p in differ)} differs): every iteration starts where "
                "the last "
                "ended",
                s.span,
            )
        self.held = before
        if cond is None:
            return None
        return ir.While(uid=0, condition=cond, body=body, span=s.span)

    def native(self, s: ast.NativeStmt) -> ir.Instr | None:
        vendors = controllers()  # the target registry (lang/vendors.py)
        if s.vendor.name not in vendors:
            self.rep.unknown(s.vendor.name, "controller language", s.vendor.span, list(vendors),
                             codes.UNKNOWN_VENDOR)
            return None
        return ir.Native(uid=0, vendor=s.vendor.name, text=s.text.value, span=s.span)

    # ---------------------------------------------------------------- parts

    def attach(self, s: ast.AttachStmt, modal: Modal) -> ir.Instr | None:
        """`attach NAME` / `detach NAME`: the part must be a part of the cell, not held
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
        free = ir.FreeMotion() if s.kind == "free" else None
        for m in s.modifiers:
            if m.kind == "config":
                config = self.config(m, scope) or config
            elif m.kind in _FREE_OPTIONS:
                free = self.free_option(m, scope, free)  # type: ignore[arg-type]
                ok = ok and free is not None
                free = free or ir.FreeMotion()
            elif m.kind == "time" and s.kind == "free":
                self.rep.error(codes.FREE_TIMED, "a 'move free' must not have a 'time' modifier (its path is found "
                               "at plan time; use speed or joint_speed to slow it)", m.span)
                ok = False
            elif m.kind == "time":
                duration = self._time(m.value, scope, "move time")  # type: ignore[arg-type]
                ok = ok and duration is not None
            elif m.kind == "ext":  # the axes' values at the target: ProgramAxes.move
                if self.axes is None:
                    self._no_axes(m.span)
                    ok = False
            else:
                modal = apply_setting(modal, m, scope, self.robot, self.base, self.rep)
        kind = _KINDS[s.kind]
        speed_modifier_warnings(s.modifiers, kind is ir.MotionKind.JOINT, scope, self.rep)
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
        move = ir.Move(uid=0, kind=kind, target=target, via=via, motion=motion, tool=modal.tool,  # type: ignore[arg-type]
                       frame=modal.frame, config=config, free=free, span=s.span)
        return move if self.axes is None else self.axes.move(move, s, scope)

    def _no_axes(self, span: Span | None) -> None:
        self.rep.error(codes_axes.EXT_VALUES, "external-axis values need a program that drives the axes "
                       "(`program p on r1 with rail, pos`)", span)

    def free_option(self, m: ast.Setting, scope: Scope, free: ir.FreeMotion) -> ir.FreeMotion | None:
        """`clearance D`, `samples N`, `budget T` of a `move free` (None after an error)."""
        e: ast.Expr = m.value  # type: ignore[assignment]
        value = eval_expr(e, scope, self.rep)
        if m.kind == "clearance":
            d = within(expect_quantity(value, LENGTH, "free-move clearance", e.span, self.rep),
                       0.0, MAX_FREE_CLEARANCE_M, "free-move clearance", "mm", 1e-3, e.span, self.rep)
            return replace(free, clearance=d) if d is not None else None
        if m.kind == "samples":
            n = expect_integer(value, "free-move samples", e.span, self.rep, minimum=1)
            n = within(n, 1, MAX_FREE_SAMPLES, "free-move samples", "", 1, e.span, self.rep)  # type: ignore[assignment]
            return replace(free, samples=int(n)) if n is not None else None
        t = self._time(e, scope, "free-move search budget")
        return replace(free, budget=t) if t is not None else None

    def config(self, m: ast.Setting, scope: Scope) -> ir.Config | None:
        values: dict[str, object] = {}
        turns: dict[int, int] = {}
        for arg in m.value:  # type: ignore[union-attr]
            key = arg.name.name if arg.name is not None else None
            if key is not None and TURN_KEY.fullmatch(key):  # config(j6=-1): a turn
                turn = turn_arg(arg, scope, self.info, self.robot, self.rep)
                if turn is not None:
                    turns[turn[0]] = turn[1]
                continue
            enum = _CONFIG.get(key or "")
            if enum is None:
                self.rep.unknown(key or "?", "config field", arg.span, [*_CONFIG, "j6"])
                continue
            word = arg.value.name if isinstance(arg.value, ast.Name) else None
            choices = [e.value for e in enum]
            if word not in choices:
                self.rep.error(codes.BAD_ARGUMENT, f"config {key} must be {' or '.join(choices)} (got '{word or '?'}')", arg.value.span)
                continue
            values[key] = enum(word)  # type: ignore[index]
        return ir.Config(**values, turns=tuple(sorted(turns.items())))  # type: ignore[arg-type]

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


