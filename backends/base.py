"""The Backend base class; it re-exports what every vendor shares (EmitResult and TaskContext:
backends/task_context.py; the formatting helpers: backends/conventions.py).

A backend (sqlglot's dialect generator) is a table plus small formatting methods:

    class RapidBackend(Backend):
        name = "rapid"; file_ext = ".mod"; COMMENT = "!"
        NAME_RULES = RAPID_RULES                           # legal identifiers
        SIX_AXIS_DATA = "RAPID robtarget/jointtarget data"  # moves need a 6-axis arm
        def emit_task(self, ctx: TaskContext) -> dict[str, str]: ...      # one program per task
        def move(self, node: ir.Move, ctx: RapidContext) -> list[str]: ...  # one per EMIT entry

`Backend.EMIT` maps every IR node type to a method name (`move`, `set_digital`, ..., the same
for every vendor); a vendor writes those methods and extends the table (`{**Backend.EMIT, ...}`)
only for node types it prints differently. `native` (passes NATIVE_NAMES blocks through),
`sync` (the comment for a sync the handshake left in place), the move preamble
(`move_record`) and the opening of `emit_task` (`open_task`, `routine_table`, `split_parts`)
are shared. Proc calls whose routines would print the same text share one routine
(`routine_table`, keyed by `routine_key`); each call line carries its call site's `file:line`
and its arguments as written (`call_args_comment`).

Input is a `plan_types.Plan`: every target's joints, branch and TCP pose come from
`ctx.record(instr)` (the planner's `InstructionRecord`). A backend only formats: no IK, no
unit conversion beyond the vendor's units (named in each module's docstring), no modal hidden
state — each instruction's text depends on that instruction and its record only. What a vendor collects while printing a
task (names, data declarations, routines) lives in its subclass of TaskContext, made by
`ctx.with_state(VendorContext, ...)` in `emit_task` and passed explicitly to every method.

Gaps: `self.unsupported(code, message, span)` records an error (the instruction has no faithful
form); `self.warn(...)` records a warning (an exact or nearest-faithful lowering was applied).
Nothing is ever dropped without one of them. `emit()` always returns files *and* diagnostics;
callers (the CLI) refuse to write files when any diagnostic is an error.

Conventions every vendor follows (so one program means the same on every controller):
  * wait with timeout: when `wait until in[n] == v timeout T` runs out, the program STOPS
    with a message naming the input (RAPID's default ERR_WAIT_MAXTIME without \\TimeFlag).
    Each vendor prints its own stop: RAPID WaitDI\\MaxTime, KRL HALT, Fanuc ABORT, URScript
    popup(error) + halt, INFORM MSG + PAUSE, VAL3 popUpMsg + stopMove/resetMotion + return.
  * acceleration: the front end's defaults (DEFAULT_TCP_ACCEL, DEFAULT_JOINT_ACCEL, from
    lang/ir.py) mean "the controller's own"; a vendor that cannot express a
    programmed acceleration warns W408 once per task, only when a move sets a non-default one.
  * I/O ports: each vendor declares DIGITAL_PORTS (inclusive range, with its source); every
    port goes through `port_ok` (E404 outside it).
  * tool payload: the tool's mass with its centre of gravity half way along the flange->TCP
    vector (`tool_cog`; the verification's torque check uses the same point). A vendor whose
    program cannot carry a payload warns W411 once per tool and task, naming what the
    integrator must set on the controller.

The per-emit diagnostics list lives on the instance, which `emit()` resets: create one backend
object per call or reuse it sequentially (never share one between threads).

Over 600 lines: the Backend class alone is 513 lines, and a class is written in one piece (its
methods read its flags and tables)."""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Hashable, Iterable
from enum import Enum
from typing import Any, ClassVar

from rmot.backends import codes, controller_data, handshake
from rmot.backends.conventions import (
    axis_quadrant, euler_xyz_moving_deg, euler_zyx_deg, fmt, fmt_list, position_mm, quaternion_wxyz,
    rotation_vector, tool_cog, turn_bits,
)
from rmot.backends.ext_axes import stacked_mechanisms
from rmot.backends.lowering import count_instructions, routine_names, split_body
from rmot.backends.names import NameRules, NameTable
from rmot.backends.part_load import held_load
from rmot.lang import ir, ir_tree, plan_types
from rmot.lang.motion_kinds import MissingMotionHandler, require_handlers
from rmot.lang.diagnostics import Code, Diagnostic, Severity
from rmot.lang.source import Span
from rmot.backends.safe_text import comment_safe
from rmot.backends.routine_keys import fingerprint, key_value
from rmot.backends.task_context import (
    DEFAULT_JOINT_ACCEL, DEFAULT_TCP_ACCEL, EmitResult, Emission, TaskContext, accel_is_default, header_lines,
    name_clash, source_ref, unique,
)
from rmot.backends import controllers

__all__ = [
    "Backend", "EmitResult", "TaskContext",
    "fmt", "fmt_list", "source_ref", "header_lines",
    "euler_zyx_deg", "euler_xyz_moving_deg", "rotation_vector", "quaternion_wxyz",
    "position_mm", "turn_bits", "axis_quadrant", "tool_cog",
    "DEFAULT_TCP_ACCEL", "DEFAULT_JOINT_ACCEL", "key_value", "accel_is_default",
]

# --------------------------------------------------------------------------- base class


class Backend:
    """Subclass per vendor; override the class constants and the EMIT table.

    Class constants (all documented with the vendor source in each subclass):
      name      the --target value ("rapid")
      file_ext  extension of the main program file (".mod")
      COMMENT   the line-comment marker ("!", ";", "#")
      NAME_RULES  the legal identifiers (the NameTable that `open_task` starts)
      MAX_INSTRUCTIONS / SPLIT_UNITS  vendors that split long programs: the most instructions
                of one program and what its parts are called ("KRL module", "modules")
      SYNC_HANDSHAKE  True for vendors without a multi-robot barrier: `sync` is lowered to the
                I/O handshake of backends/handshake.py before printing
      EMIT      IR node type -> name of the method printing it: method(node, ctx) -> list[str];
                the default names one method per node type, the same for every vendor
      MOVES     ir.MotionKind -> name of the method printing a move of that kind (the vendor's
                `move` prints the shared preamble, then calls `self.by_kind(node)(...)`); every
                kind needs one, checked when the class is created (`validate_kinds`)
      NATIVE_NAMES  vendor names of the native blocks passed through (default: {name})
      SIX_AXIS_DATA / NO_RECORD_NOTE / NOT_SIX_AXIS_NOTE  see `move_record`
      BRANCH_DATA  what a Cartesian target needs its IK branch for (see `branch_or_default`)
      DIGITAL_PORTS  the digital I/O numbers the vendor accepts, inclusive (see `port_ok`)
    """

    name: ClassVar[str] = ""
    file_ext: ClassVar[str] = ""
    COMMENT: ClassVar[str] = "#"
    NAME_RULES: ClassVar[NameRules] = NameRules(max_len=32)
    MAX_INSTRUCTIONS: ClassVar[int | None] = None
    SPLIT_UNITS: ClassVar[tuple[str, str]] = ("program", "programs")
    SYNC_HANDSHAKE: ClassVar[bool] = False
    EMIT: ClassVar[dict[type, str]] = {
        ir.Move: "move", ir.SetDigital: "set_digital", ir.SetAnalog: "set_analog",
        ir.Pulse: "pulse", ir.WaitTime: "wait_time", ir.WaitInput: "wait_input", ir.If: "if_",
        ir.Sync: "sync", ir.Native: "native", ir.ProcCall: "proc_call",
        ir.Attach: "attach", ir.Detach: "detach",
        ir.Loop: "loop", ir.VarDecl: "var_decl", ir.Assign: "assign", ir.While: "while_",
        ir.WaitCondition: "wait_condition", ir.Stop: "stop",
    }
    MOVES: ClassVar[dict[ir.MotionKind, str]] = {
        ir.MotionKind.JOINT: "move_joint", ir.MotionKind.LINEAR: "move_linear",
        ir.MotionKind.CIRCULAR: "move_circular",
    }
    NATIVE_NAMES: ClassVar[frozenset[str]] = frozenset()
    SIX_AXIS_DATA: ClassVar[str | None] = None
    NO_RECORD_NOTE: ClassVar[str | None] = "move (uid {uid}) not emitted: no planned joints"
    NOT_SIX_AXIS_NOTE: ClassVar[str] = "move not emitted: robot is not a 6-axis arm"
    EXTERNAL_AXES: ClassVar[bool] = False  # writes the values of external axes (backends/ext_axes.py)
    BRANCH_DATA: ClassVar[str] = "the configuration data"
    INDENT: ClassVar[str] = "  "
    DIGITAL_PORTS: ClassVar[tuple[int, int]] = (1, 4096)
    # the fastest TCP speed the vendor's linear/circular instruction takes (m/s), with its
    # source; None: no documented limit in the language (the controller limits it itself)
    MAX_TCP_SPEED: ClassVar[float | None] = None
    MAX_TCP_SPEED_SOURCE: ClassVar[str] = ""
    # True: the vendor prints `for`/`repeat` loops as loops (its own `loop` method). False:
    # `lowered_plan` unrolls every loop before printing (the loop variable bound to each value).
    PRINTS_LOOPS: ClassVar[bool] = False
    # True: the vendor writes runtime conditions itself (and/or/not, analog inputs, variables,
    # timeout branches). False: an `if` on such a condition or a wait with a timeout branch is
    # E165 (`needs_runtime_conditions`) instead of a condition or branch silently dropped.
    RUNTIME_CONDITIONS: ClassVar[bool] = False

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        # a backend of this package fails at import when a motion kind has no handler; any
        # other (a test's, a plug-in's) when the target registry hands it out (lang/vendors)
        if cls.name and cls.__module__.startswith("rmot.backends."):
            cls.validate_kinds()
        own_loop = getattr(cls, cls.EMIT[ir.Loop], None) is not Backend.loop
        if own_loop != cls.PRINTS_LOOPS:  # the flag and the Loop printer must tell the same
            raise TypeError(f"backend {cls.__name__}: PRINTS_LOOPS is {cls.PRINTS_LOOPS} but its "
                            f"Loop printer is {'its own' if own_loop else 'the unrolling default'}")

    @classmethod
    def kind_tables(cls) -> dict[str, dict[ir.MotionKind, str]]:
        """The tables keyed by motion kind this backend prints by (MOVES; the neutral
        backends, which print no moves, their row labels)."""
        return {"MOVES": cls.MOVES}

    @classmethod
    def validate_kinds(cls, kinds: Iterable[Enum] = ir.MotionKind) -> None:
        """MissingMotionHandler unless every kind has an entry in each of `kind_tables`, and
        every MOVES entry names a method of this class."""
        for table_name, table in cls.kind_tables().items():
            require_handlers(f"backend {cls.__name__}.{table_name}", table, kinds)
        absent = sorted(m for m in cls.MOVES.values() if not callable(getattr(cls, m, None)))
        if absent and "MOVES" in cls.kind_tables():
            raise MissingMotionHandler(f"backend {cls.__name__}.MOVES names no method "
                                       f"{', '.join(absent)}")

    def __init__(self, *, allow_findings_header: bool = False, write_frames: bool = False,
                 unroll: bool = False) -> None:
        self.findings_header = allow_findings_header
        # `--unroll`: every `for` loop written iteration by iteration
        self.unroll = unroll
        # `--write-frames`: numbered tools and frames are also written into the controller's
        # stored data (Fanuc UTOOL/UFRAME, KUKA TOOL_DATA/BASE_DATA); off, they are only selected
        self.write_frames = write_frames
        self._emission = Emission()

    # ------------------------------------------------------------------ entry point

    def emit(self, plan: plan_types.Plan, *, source_map: bool = True) -> EmitResult:
        """Format every task of `plan` (after `lowered_plan`); one output program (one or
        more files) per task."""
        plan = self.lowered_plan(plan)
        self._emission = Emission()
        files: dict[str, str] = {}
        owner: dict[str, str] = {}  # case-folded file name -> the task that wrote it
        clashed: set[tuple[str, str]] = set()
        for task_plan in plan.tasks:
            ctx = TaskContext(plan, task_plan, plan.program.cell.robot(task_plan.robot),
                              self.program_name(plan, task_plan), source_map=source_map)
            self.check_brand(ctx.robot)
            for fname, text in self.emit_task(ctx).items():
                first = owner.setdefault(fname.casefold(), task_plan.task.name)
                if first != task_plan.task.name:  # names equal after the vendor's cut or case folding
                    if (first, task_plan.task.name) not in clashed:
                        clashed.add((first, task_plan.task.name))
                        self._emission.diagnostics.append(name_clash(self, fname, first, task_plan))
                    continue
                files[fname] = text
        return EmitResult(files, unique(self._emission.diagnostics))

    def lowered_plan(self, plan: plan_types.Plan) -> plan_types.Plan:
        """`plan` as this vendor prints it, by the class flags: unless PRINTS_LOOPS, every task
        body with its loops unrolled (ir_tree.unroll_loops) before anything of it is printed, so
        the vendor's walkers (routines, predecessors, lowerings, handshake) see plain lists."""
        if self.PRINTS_LOOPS:
            return plan
        tasks = tuple(dataclasses.replace(tp, task=dataclasses.replace(
            tp.task, body=ir_tree.unroll_loops(tp.task.body))) for tp in plan.tasks)
        return dataclasses.replace(plan, tasks=tasks)

    def check_brand(self, robot: ir.RobotInstance) -> None:
        """W415 at the robot's declaration when a library arm is of another brand than this
        vendor's controller (backends/controller_data.py; URDF arms are not judged)."""
        mine = controller_data.TARGET_BRANDS.get(self.name)
        brand = controller_data.brand_of(robot)
        if mine is not None and brand is not None and brand != mine[0]:
            self.warn(codes.OTHER_BRAND, f"robot '{robot.name}' ({robot.source.ref}) is made by {brand}; "
                      f"a {self.name} program runs on a {mine[0]} controller", robot.span)

    def emit_task(self, ctx: TaskContext) -> dict[str, str]:
        """Print one task: filename -> text. Subclasses implement."""
        raise NotImplementedError

    def program_name(self, plan: plan_types.Plan, task_plan: plan_types.TaskPlan) -> str:
        """Program name for a task: the program's name, suffixed by the task when there are several."""
        if len(plan.tasks) == 1:
            return plan.program.name
        return f"{plan.program.name}_{task_plan.task.name}"

    def open_task(self, ctx: TaskContext, *, reserved: Iterable[str] = ()
                  ) -> tuple[NameTable, str, tuple[ir.Instr, ...]]:
        """What every emit_task starts with: a NameTable under NAME_RULES with the backend's
        own `reserved` names taken, the task program's legal name, and the lowered body.

        The caller hands `names.diagnostics` to `extend` once the task is printed."""
        names = NameTable(self.NAME_RULES, self.name)
        for legal in reserved:
            names.reserve(legal)
        return names, names.name(ctx.program_name, ctx.task.span), self.lowered_body(ctx)

    def routine_table(self, names: NameTable, body: tuple[ir.Instr, ...], ctx: TaskContext,
                      prefix: str = "") -> dict[int, str]:
        """ProcCall uid -> legal routine name (lowering.routine_names keyed by `routine_key`,
        then `prefix` + legalised): calls whose routines would print the same share one."""
        table = routine_names(body, key=lambda call: self.routine_key(call, ctx))
        return {uid: names.name(prefix + routine) for uid, routine in table.items()}

    def routine_key(self, call: ir.ProcCall, ctx: TaskContext) -> Hashable:
        """What the routine printed for `call` depends on: every instruction of its body
        without uid and span (the source comment's `file:line` instead), with the planner's
        record of it (floats rounded to 1e-9, far below any printed precision; not its
        timing, which depends on where the call starts) and `context_key` (what else a vendor
        prints: RAPID a move's planned duration, INFORM an arc's start point)."""
        return fingerprint(call.body, ctx, self.context_key)

    def call_args_comment(self, node: ir.ProcCall) -> list[str]:
        """A comment with the call's arguments as written, above the call line (the routine
        may be shared by calls written differently, so its own header names only the proc)."""
        return [self.comment(f"{node.proc}({', '.join(node.args)})")] if node.args else []

    def context_key(self, node: ir.Instr, ctx: TaskContext) -> Hashable:
        """What the text of `node` reads beyond its own instruction and its record's geometry
        (RAPID: the planned duration; INFORM: an arc's start point). None for most vendors."""
        return None

    def split_parts(self, body: tuple[ir.Instr, ...], ctx: TaskContext, stem: str) -> tuple[ir.Instr, ...] | None:
        """`body` as ProcCalls `stem_part1`.. (W406) when it has more than MAX_INSTRUCTIONS
        instructions; None when it fits (or the vendor never splits)."""
        n = count_instructions(body)
        if self.MAX_INSTRUCTIONS is None or n <= self.MAX_INSTRUCTIONS:
            return None
        parts = split_body(body, self.MAX_INSTRUCTIONS, stem)
        unit, units = self.SPLIT_UNITS
        self.warn(codes.PROGRAM_SPLIT, f"program has {n} instructions, more than {self.MAX_INSTRUCTIONS} "
                  f"per {unit}; split into {len(parts)} {units}", ctx.task.span)
        return parts

    def lowered_body(self, ctx: TaskContext) -> tuple[ir.Instr, ...]:
        """The task body as printed: after the sync handshake for SYNC_HANDSHAKE vendors."""
        return self.sync_handshake(ctx) if self.SYNC_HANDSHAKE else ctx.task.body

    def sync_handshake(self, ctx: TaskContext) -> tuple[ir.Instr, ...]:
        """The task body with every sync lowered to the I/O handshake (backends/handshake.py).

        Left unchanged, with the syncs printed by `sync_not_lowered`, when the program has a
        single task (syncs are no-ops) or the handshake cannot be built (errors reported here).
        """
        body = ctx.task.body
        if len(ctx.plan.program.tasks) < 2:
            return body
        found = handshake.check_handshake(body, ctx.plan.program.cell, ctx.robot.name, self.name)
        self.extend(found)
        ports = handshake.handshake_ports(ctx.plan.program.cell, ctx.robot.name)
        if ports is None or any(d.is_error for d in found):
            return body
        return handshake.sync_as_handshake(body, ports)

    def sync_not_lowered(self, node: ir.Sync, ctx: TaskContext) -> list[str]:
        """A comment for a sync the handshake left in place: a no-op in a single-task program,
        otherwise one whose error `sync_handshake` has already reported."""
        if len(ctx.plan.program.tasks) < 2:
            return [self.comment(f"sync {node.name}: no-op (single task)")]
        return [self.comment(f"sync {node.name} not emitted (see error)")]

    # ------------------------------------------------------------------ dispatch

    def instr(self, node: ir.Instr, ctx: TaskContext) -> list[str]:
        """The lines of one instruction (source comment first), via the EMIT table.

        By the class flags first: a Loop reaching a vendor that does not print loops is its
        iterations' lines only (no source comment of its own: the same text as the unrolled
        body); unless RUNTIME_CONDITIONS, a node that needs them is E165."""
        if isinstance(node, ir.Loop) and not self.PRINTS_LOOPS:
            return self.loop(node, ctx)
        if not self.RUNTIME_CONDITIONS and self.needs_runtime_conditions(node):
            return self.runtime_unsupported(node, ctx)
        # by the node's class or its nearest base (a HandshakeSet prints as a SetDigital)
        method = next((self.EMIT[c] for c in type(node).__mro__ if c in self.EMIT), None)
        if method is None:
            self.unsupported(codes.UNSUPPORTED,
                             f"{type(node).__name__} must be expressible for {self.name} (it is not)",
                             getattr(node, "span", None))
            return [self.comment(f"UNSUPPORTED {type(node).__name__}")]
        lines: list[str] = getattr(self, method)(node, ctx)
        notes = [c for c in (self.source_comment(node, ctx), self.handshake_comment(node)) if c]
        return notes + lines

    def by_kind(self, node: ir.Move) -> Callable[..., list[str]]:
        """The method printing a move of `node.kind` (MOVES; complete by `validate_kinds`)."""
        method: Callable[..., list[str]] = getattr(self, self.MOVES[node.kind])
        return method

    def joint_target_refused(self, node: ir.Move) -> bool:
        """True, after E400, when a linear or circular move has a joint target (the front end
        never builds one; only an IR made by hand has)."""
        if not isinstance(node.target, ir.JointTarget):
            return False
        self.unsupported(codes.UNSUPPORTED, f"a {node.kind.name.lower()} move must have a "
                         "Cartesian target (got joints)", node.span)
        return True

    def via_refused(self, node: ir.Move) -> bool:
        """True, after E451, when a circular move has no via point."""
        if node.via is not None:
            return False
        self.unsupported(codes.CIRCULAR_VIA_MISSING, "circular move must have a via point "
                         "(got none)", node.span)
        return True

    def body(self, nodes: Iterable[ir.Instr], ctx: TaskContext) -> list[str]:
        out: list[str] = []
        for node in nodes:
            out.extend(self.instr(node, ctx))
        return out

    def move_record(self, node: ir.Move, ctx: TaskContext) -> plan_types.InstructionRecord | list[str]:
        """The preamble of every vendor's `move`: the move's record (with its joint solution),
        or, after reporting the error, the lines printed instead of the move: NO_RECORD_NOTE
        (E401; None prints nothing) or, when SIX_AXIS_DATA is set, NOT_SIX_AXIS_NOTE (E403)."""
        rec = ctx.record(node)
        if rec is None or rec.q_target is None:
            self.unsupported(codes.MISSING_RECORD,
                             f"move (uid {node.uid}) must have a planned joint solution (got none)",
                             node.span)
            note = self.NO_RECORD_NOTE
            return [] if note is None else [self.comment(note.format(uid=node.uid))]
        stacked = stacked_mechanisms(ctx.plan.program.cell, node) if node.ext else ""
        if node.ext and (stacked or not self.EXTERNAL_AXES):
            if "external axes" not in ctx.warned:  # once per task: every move would say the same
                ctx.warned.add("external axes")
                why = (f", which rmot cannot write for this controller: a mechanism stacked on another ({stacked})"
                       if stacked else ", which rmot writes for rapid, krl, fanuc and inform only: this controller's "
                       "programs move the arm alone; compile the task for one of those")
                self.unsupported(codes.EXT_AXES_UNSUPPORTED, f"task '{ctx.task.name}' drives external axes "
                                 f"({', '.join(name for name, _ in node.ext)}){why}", node.span)
            return [self.comment("move with external axes not emitted")]
        if self.SIX_AXIS_DATA is not None and ctx.robot.dof != 6:
            self.unsupported(codes.NOT_SIX_AXIS, f"robot '{ctx.robot.name}' must have 6 axes for "
                             f"{self.SIX_AXIS_DATA} (got {ctx.robot.dof})", node.span)
            return [self.comment(self.NOT_SIX_AXIS_NOTE)]
        return rec

    @staticmethod
    def planned_zone(node: ir.Move, rec: plan_types.InstructionRecord) -> ir.Zone:
        """The zone a vendor prints for `node`: the record's blend radius, the one the plan
        verified (at most the programmed zone: compiler/plan/blend.py shrinks it to half of
        each neighbouring move and halves it where the blend would leave its sphere), `fine`
        where the plan stops (before a wait, wait until, if, sync, at a timed move, at the
        task's end, wherever a blend could not be built). The controller then blends inside
        the sphere that was verified and stops where the verified path stops
        (lang/REFERENCE.md §8, stop points)."""
        return ir.Zone(rec.blend_radius) if rec.blend_radius > 0.0 else ir.Zone(0.0)

    def branch_or_default(self, branch: ir.Config | None, node: ir.Move) -> ir.Config:
        """`branch` when it names shoulder, elbow and wrist; else E402 and front/up/no-flip
        (the text stays well-formed; the error keeps it from being written)."""
        if branch is None or None in (branch.shoulder, branch.elbow, branch.wrist):
            self.unsupported(codes.NO_BRANCH, "Cartesian target must have a planned IK branch for "
                             f"{self.BRANCH_DATA} (got none)", node.span)
            return ir.Config(ir.Shoulder.FRONT, ir.Elbow.UP, ir.Wrist.NOFLIP)
        return branch

    # ------------------------------------------------------------------ shared instructions

    def native(self, node: ir.Native, ctx: TaskContext) -> list[str]:
        """A native block: its text for this vendor (NATIVE_NAMES, default {name}), else skipped."""
        if node.vendor.lower() not in (self.NATIVE_NAMES or {self.name}):
            return self.native_other(node)
        return node.text.splitlines()

    def sync(self, node: ir.Sync, ctx: TaskContext) -> list[str]:
        """Only reached when the I/O handshake was not built (see Backend.sync_handshake)."""
        return self.sync_not_lowered(node, ctx)

    # ------------------------------------------------------------------ text helpers

    def comment(self, text: str) -> str:
        return f"{self.COMMENT} {comment_safe(text)}" if text else self.COMMENT

    def source_comment(self, node: ir.Instr, ctx: TaskContext) -> str | None:
        """`! file.rmot:12` above an instruction's text, when source maps are on."""
        ref = ctx.source_ref(node)
        return self.comment(ref) if ref else None

    def handshake_comment(self, node: ir.Instr) -> str | None:
        """`! sync meet (handshake 1)` above the first line of a lowered sync (always printed:
        it names the barrier, which the I/O lines alone do not)."""
        note = handshake.handshake_note(node)
        return self.comment(note) if note else None

    def header(self, ctx: TaskContext) -> list[str]:
        return [self.comment(line) for line in header_lines(ctx.plan, self.name, self.findings_header)]

    @staticmethod
    def indent(lines: Iterable[str], prefix: str) -> list[str]:
        return [prefix + line if line else line for line in lines]

    # ------------------------------------------------------------------ diagnostics

    def unsupported(self, code: Code, message: str, span: Span | None) -> None:
        """Record an error: the program cannot be expressed faithfully (never dropped silently)."""
        self._emission.diagnostics.append(Diagnostic(code, Severity.ERROR, f"{self.name}: {message}", span))

    def warn(self, code: Code, message: str, span: Span | None) -> None:
        """Record a warning: an exact or nearest-faithful lowering was applied."""
        self._emission.diagnostics.append(Diagnostic(code, Severity.WARNING, f"{self.name}: {message}", span))

    def extend(self, diagnostics: Iterable[Diagnostic]) -> None:
        self._emission.diagnostics.extend(diagnostics)

    def warn_once(self, ctx: TaskContext, key: str, code: Code, message: str, span: Span | None) -> None:
        """`warn`, only the first time `key` comes up in this task."""
        if key not in ctx.warned:
            ctx.warned.add(key)
            self.warn(code, message, span)

    def warn_accel(self, node: ir.Move, ctx: TaskContext, how: str) -> None:
        """W408 once per task when `node` sets a non-default acceleration the vendor cannot
        express (`how`: what the controller does instead)."""
        if not accel_is_default(node.motion, node.kind):
            self.warn_once(ctx, "accel", codes.ACCEL_IGNORED,
                           f"programmed accelerations are not expressed ({how})", node.span)

    def accel_percent(self, node: ir.Move, rec: plan_types.InstructionRecord, ctx: TaskContext,
                      low: int, how: str) -> int | None:
        """The joint acceleration share the plan timed the move with (`rec.accel_share`: its
        blended chain's smallest `accel`, compiler/plan/move_chain.py) as a whole percentage in
        low..100, for a vendor whose acceleration form takes that range (Fanuc ACC, INFORM
        ACC=/DEC=).
        None for the default 100 % and for a Cartesian move, whose programmed TCP acceleration
        (m/s^2) none of them takes (W408 when it is not the default). A ratio outside the range
        or not a whole percentage is not expressed either: W408 (`how`)."""
        ratio = rec.accel_share * 100.0
        if node.kind is not ir.MotionKind.JOINT:
            self.warn_accel(node, ctx, how)
            return None
        if abs(ratio - round(ratio)) < 1e-9 and low <= round(ratio) <= 100:
            return None if round(ratio) == 100 else round(ratio)
        # also a move of default `accel` in a chain timed with another share: said once
        self.warn_once(ctx, "accel", codes.ACCEL_IGNORED, "programmed accelerations are not "
                       f"expressed ({how}; the plan timed this move with {fmt(ratio, 3)} %)",
                       node.span)
        return None

    def tcp_speed_within_limit(self, node: ir.Move) -> float:
        """The move's TCP speed (m/s), clamped to MAX_TCP_SPEED with W417 at the move."""
        v = node.motion.tcp_speed
        limit = self.MAX_TCP_SPEED
        if limit is None or v <= limit + 1e-12:
            return v
        self.warn(codes.LIMIT_CLAMPED, f"TCP speed {fmt(v * 1000.0, 1)} mm/s must be at most "
                  f"{fmt(limit * 1000.0, 1)} mm/s for {self.name} ({self.MAX_TCP_SPEED_SOURCE}); "
                  f"clamped to {fmt(limit * 1000.0, 1)} mm/s", node.span)
        return limit

    def port_ok(self, port: int, what: str, span: Span | None, ports: tuple[int, int] | None = None) -> bool:
        """True when `port` is in `ports` (default DIGITAL_PORTS); else E404 and False."""
        low, high = ports or self.DIGITAL_PORTS
        if low <= port <= high:
            return True
        self.unsupported(codes.BAD_PORT, f"{what} port must be in {low}..{high} (got {port})", span)
        return False

    def warn_payload(self, node: ir.Move, ctx: TaskContext, where: str) -> None:
        """W411 once per tool and task: the tool's mass cannot be carried by this vendor's
        program; `where` names the controller setting the integrator must fill in."""
        tool = node.tool
        if tool.mass <= 0.0:
            return
        cog = fmt_list((c * 1000.0 for c in tool_cog(tool)), 1)
        self.warn_once(ctx, f"payload:{tool.name}", codes.PAYLOAD_NOT_EXPRESSED,
                       f"tool '{tool.name}' payload ({fmt(tool.mass, 3)} kg, centre of gravity "
                       f"[{cog}] mm in the flange frame) must be set in {where}", node.span)

    def native_other(self, node: ir.Native) -> list[str]:
        """A native block for another controller: not emitted, with a warning and a comment
        (the front end refuses any vendor outside the registry's `controllers()` with E116, so
        only an IR built by hand names another; it is skipped the same way, never printed)."""

        known = node.vendor in controllers()
        self.warn(codes.NATIVE_SKIPPED, f"native {node.vendor} block is not emitted for {self.name}"
                  + ("" if known else f" (not one of {', '.join(controllers())})"), node.span)
        return [self.comment(f"native {node.vendor} block skipped")]

    # ------------------------------------------------------------------ defaults: parts, runtime
    # (`ctx: Any`: each vendor's override takes its own TaskContext subclass)

    def attach(self, node: ir.Attach, ctx: Any) -> list[str]:
        """A comment plus W460 once per part and task with the payload to enter on the
        controller (RAPID, KRL and URScript write the held load themselves)."""
        return self.part_payload_comment(node, ctx)

    def detach(self, node: ir.Detach, ctx: Any) -> list[str]:
        """A comment with the payload left on the flange (see `attach`)."""
        return self.part_payload_comment(node, ctx)

    def part_payload_comment(self, node: ir.Attach | ir.Detach, ctx: TaskContext) -> list[str]:
        """`attach`/`detach` for a vendor whose program cannot carry a held part's load."""
        _, _, total, cog = held_load(node, ctx)
        word = "attach" if isinstance(node, ir.Attach) else "detach"
        if isinstance(node, ir.Attach):
            cog_mm = fmt_list((c * 1000.0 for c in cog), 1)
            self.warn_once(ctx, f"part-payload:{node.part}", codes.PART_PAYLOAD_NOT_EXPRESSED,
                           f"part '{node.part}' held: the payload ({fmt(total, 3)} kg with the tool, "
                           f"centre of gravity [{cog_mm}] mm in the flange frame) must be set on the "
                           f"controller while it is held ({self.name} programs cannot carry it)",
                           node.span)
        return [self.comment(f"{word} {node.part}: payload {fmt(total, 3)} kg")]

    def loop(self, node: ir.Loop, ctx: Any) -> list[str]:
        """A `for` / `repeat` loop written as its iterations one after another, the loop
        variable bound to each value (no lines of its own); vendors that print loops override
        it and set PRINTS_LOOPS."""
        out: list[str] = []
        for it in node.iterations:
            body = (ir_tree.bind_loop_variable(it.body, node.var, it.value)
                    if node.var is not None else it.body)
            out.extend(self.body(body, ctx))
        return out

    @staticmethod
    def needs_runtime_conditions(node: ir.Instr) -> bool:
        """An `if` on a condition other than one input, or a wait with a timeout branch."""
        return ((isinstance(node, ir.If) and not isinstance(node.condition, ir.InputCondition))
                or (isinstance(node, ir.WaitInput) and bool(node.on_timeout)))

    def runtime_unsupported(self, node: ir.Instr, ctx: TaskContext) -> list[str]:
        """E165: runtime logic this vendor's backend does not write (never dropped silently)."""
        kind = type(node).__name__
        what = {"If": "an if on a general condition",
                "WaitInput": "a wait with a timeout branch"}.get(kind, kind)
        self.unsupported(codes.RUNTIME_UNSUPPORTED, f"{what} must be expressible for {self.name} "
                         "(its backend writes no runtime logic for it yet)", node.span)
        return [self.comment(f"UNSUPPORTED {kind}")]

    def var_decl(self, node: ir.VarDecl, ctx: Any) -> list[str]:
        return self.runtime_unsupported(node, ctx)

    def assign(self, node: ir.Assign, ctx: Any) -> list[str]:
        return self.runtime_unsupported(node, ctx)

    def while_(self, node: ir.While, ctx: Any) -> list[str]:
        return self.runtime_unsupported(node, ctx)

    def wait_condition(self, node: ir.WaitCondition, ctx: Any) -> list[str]:
        return self.runtime_unsupported(node, ctx)

    def stop(self, node: ir.Stop, ctx: Any) -> list[str]:
        return self.runtime_unsupported(node, ctx)


# Every instruction kind has a printer (the defaults of the class body included): a kind added
# to the IR without one is an import-time error here, never a silent default.
ir_tree.require_kinds("backends/base.Backend.EMIT", Backend.EMIT)
