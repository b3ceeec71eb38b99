"""A task's timeline: instructions in order, turned into Pieces and InstructionRecords.

* Moves gather into a *chain* while their zones blend; a chain ends at a `fine` zone, at the
  task's last move, at a move with a `time` modifier (timed on its own: blending into or out of
  it is not done), and before any instruction that makes the robot wait (`wait`,
  `wait until`, `sync`, `if`). Then the chain is timed (compiler.plan.move_chain). In a program
  of one task (`lone`) a `sync` is a no-op: it is recorded at its instant like a `set` and
  neither stops nor breaks a blend.
* `set`, `pulse` and `native` do not stop the robot: they happen at the instant the preceding
  move ends — its zone entry when it is blended (as RAPID does for a zone point), its stop
  otherwise. A pulse's record lasts the pulse (t_end = t_start + duration).
* `wait T` holds the robot for T. `wait until` cannot know the input in simulation: it is
  assumed to hold at once (zero time; the timeout is in the IR for the simulator to report).
* A move's record: t_start where it leaves the previous move's path (the previous zone entry),
  t_end at its own zone entry or stop.
* Runtime `if`: the main timeline takes the `then` arm; the `otherwise` arm is planned from
  the `if`'s start state as a Variant k, *followed by the rest of the task* (the instructions
  after the `if`, up the enclosing arms and proc calls, to the task's end), planned from the
  end of the `otherwise` arm; all its records carry variant=k. In that continuation later
  `if`s take their `then` arm: each `if` with an `otherwise` arm gets exactly one variant
  (linear in the number of ifs, not 2^k paths); an `if` nested in an `otherwise` arm gets its
  own variant, started from that arm's state. Diagnostics found only on a variant's path carry
  a note naming the `if`; the same finding as on the main timeline is not repeated.
  W223: a move after the `if` whose target joints differ on the `otherwise` path from the main
  timeline's (e.g. another IK branch, chosen nearest to a different start) — the controller
  program is written from the main timeline's solution, so the verified path would not be the
  one the robot drives. A `sync` in a continuation is recorded in VariantDraft.syncs and held
  to the main timeline's barrier time after alignment (sync.hold_variants).
* A failing move is reported at its span and skipped: the robot holds where it is and the
  rest of the task is planned from there, so every error in a file is reported at once.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from rmot.lang import ir
from rmot.lang.ir_tree import (
    describe_iteration, flow, handler, iteration_paths, require_kinds, walk, walk_bodies,
)
from rmot.compiler.plan import codes
from rmot.compiler.plan.move_chain import TimedChain, chain_accel_share, time_chain
from rmot.compiler.plan.coordinated import CoordinatedSegment, coordinated_axes, coordinated_segment, time_coordinated
from rmot.compiler.plan.torque import TorqueLimits
from rmot.compiler.plan.segments import Segment, build_segment
from rmot.compiler.plan.targets import Finding
from rmot.compiler.plan.timing import HoldPiece, Piece
from rmot.lang.plan_types import InstructionRecord, path_words
from rmot.lang.diagnostics import Diagnostic, Severity
from rmot.compiler.plan.robot_model import RobotModel

__all__ = ["TaskDraft", "VariantDraft", "build_task", "proc_records"]

_EVENTS = (ir.SetDigital, ir.SetAnalog, ir.Pulse, ir.Native, ir.VarDecl, ir.Assign)
WHILE_BOUND = 3  # iterations of a while planned at most to reach its fixed point (REFERENCE.md §7)
_SAME_Q = 1e-6  # rad (m): a while iteration ends where it started when every joint is this close


@dataclass(eq=False)
class VariantDraft:
    index: int
    if_uid: int
    arm: str
    t0: float
    pieces: list[Piece]
    order: int  # records created before it (for sync shifting)
    q0: np.ndarray | None = None  # joints at the if's start (dof,)
    sync_base: int = 0  # main-timeline syncs before the if: the variant's i-th sync is main's sync_base+i
    syncs: list[tuple[int, int]] = field(default_factory=list)  # (piece pos, record idx) of its syncs


@dataclass(eq=False)
class TaskDraft:
    """The unsampled timeline: pieces back to back from t=0, records, sync points, variants."""

    pieces: list[Piece] = field(default_factory=list)
    records: list[InstructionRecord] = field(default_factory=list)
    syncs: list[tuple[ir.Sync, int, int]] = field(default_factory=list)  # (sync, piece pos, record idx)
    variants: list[VariantDraft] = field(default_factory=list)
    continuations: list[tuple[int, int]] = field(default_factory=list)  # (variant, first record idx after its arm)
    diagnostics: list[Diagnostic] = field(default_factory=list)
    q: np.ndarray | None = None  # the final joints


@dataclass(frozen=True, slots=True)
class _Tail:
    """What runs after an instruction: body[start:], then `parent`."""

    body: tuple[ir.Instr, ...]
    start: int
    parent: _Rest


@dataclass(frozen=True, slots=True)
class _Iterations:
    """What runs after a loop iteration: the loop's iterations from `start`, then `parent`."""

    loop: ir.Loop
    start: int
    parent: _Rest


_Rest = _Tail | _Iterations | None


class _Builder:
    """Walks one instruction list; `variant` > 0 for an if-arm planned off the main timeline."""

    def __init__(self, robot: RobotModel, task: str, q0: np.ndarray, t0: float, variant: int,
                 draft: TaskDraft, counter: list[int], lone: bool = False,
                 torque: TorqueLimits | None = None) -> None:
        self.robot, self.task, self.variant, self.lone = robot, task, variant, lone
        self.torque = torque  # the task's joint torque limits for time_chain (None: no ratings)
        self.spawn = True  # False while walking a variant's continuation: later ifs belong to main
        self.note: tuple[str, object] | None = None  # set on variants: which if's otherwise path
        self.syncs: list[tuple[int, int]] = []  # a variant's syncs (piece pos, record idx)
        self.q, self.t = q0.copy(), t0
        self.t0 = t0
        self.budget_s = float("inf")  # walking stops once this path is longer: the plan is refused (E124) anyway
        self.pieces: list[Piece] = []
        self.draft, self.counter = draft, counter
        self.chain: list[Segment] = []
        self.events: list[tuple[ir.Instr, int]] = []
        self.pending: list[tuple[Finding, int]] = []  # warnings of chain moves, by chain index
        self.stopped = False  # a `stop` ended this path: nothing after it is planned
        self.tool: str | None = None  # the tool of the last move, and the parts held: with q, the
        self.held: tuple[str, ...] = ()  # state a while's iteration must end in to be proved
        self.paths: dict[int, tuple] = {}  # type: ignore[type-arg]  # uid -> loop iterations
        self.repeat_quiet = False  # a while's later iterations: only findings not already reported
        self.while_round: str | None = None  # "round 2 of the while at line 9" in later rounds
        self.failed: ir.Move | None = None  # the last move, when it failed: the next starts where it began

    # ------------------------------------------------------------------ helpers
    def _diag(self, f: Finding, span, time: float | None = None,  # type: ignore[no-untyped-def]
              uid: int | None = None, after: ir.Move | None = None) -> None:
        message = f.message
        if uid is not None and uid in self.paths:  # inside a for/repeat: name the iteration
            message += f" (in iteration {describe_iteration(self.paths[uid])})"
        if self.note is not None or self.repeat_quiet:  # only what was not already reported
            seen = ((d.code, d.span, d.message.split(" (in round ")[0])
                    for d in self.draft.diagnostics)
            if (f.code, span, message) in seen:
                return
        if self.while_round is not None:  # found only in a later round of a while
            message += f" (in {self.while_round}, from where the round before it ends)"
        notes: tuple = (self.note,) if self.note is not None else ()  # type: ignore[type-arg]
        if after is not None:  # planned from an assumed start: say which error it follows from
            message += " (a consequence of the failed move before it: planned from where that move began)"
            notes += (("the failed move; the robot is assumed to stay where it began", after.span),)
        self.draft.diagnostics.append(
            Diagnostic(f.code, f.severity, message, span, notes, time_s=time, task=self.task))

    def _record(self, instr: ir.Instr, t0: float, t1: float, **extra: object) -> None:
        self.draft.records.append(InstructionRecord(
            instr.uid, instr.span, t0, t1, variant=self.variant, **extra))  # type: ignore[arg-type]

    def _q_end(self) -> np.ndarray:
        return self.chain[-1].q_end if self.chain else self.q

    # ------------------------------------------------------------------ walking
    def walk(self, body: tuple[ir.Instr, ...], rest: _Rest = None, start: int = 0) -> None:
        """Walk body[start:]; `rest`: what runs after it (enclosing bodies' tails, innermost
        first), the continuation a variant of an `if` inside `body` is planned along. Each
        instruction's continuation is one new link (_Rest), not a copy of what follows it: the
        walk is linear in the number of instructions and loop iterations."""
        for i in range(start, len(body)):
            if self.stopped or self.t - self.t0 > self.budget_s:
                return
            instr = body[i]
            plan = _PLAN.get(type(instr)) or handler(_PLAN, instr)
            plan(self, instr, _Tail(body, i + 1, rest))

    def walk_rest(self, rest: _Rest) -> None:
        while rest is not None:
            if isinstance(rest, _Tail):
                self.walk(rest.body, rest.parent, rest.start)
            else:
                iterations = rest.loop.iterations
                for k in range(rest.start, len(iterations)):
                    self.walk(iterations[k].body, _Iterations(rest.loop, k + 1, rest.parent))
            rest = rest.parent

    def _move(self, move: ir.Move) -> None:
        alone = move.motion.duration is not None or move.motion.min_duration is not None  # timed on its own
        if alone:
            self.flush()
        self.tool = move.tool.name
        build = build_segment if move.coordinated is None else coordinated_segment  # a frame carried by moving axes
        seg, findings = build(self.robot, move, self._q_end())
        if seg is None:
            self.flush()
            # a joint move to joint values fails for its target alone; any other depends on its start
            alone = move.kind is ir.MotionKind.JOINT and isinstance(move.target, ir.JointTarget)
            for f in findings:
                self._diag(f, move.span, self.t, move.uid, after=None if alone else self.failed)
            self._record(move, self.t, self.t)
            self.failed = move
            return
        self.failed = None
        self.pending += [(f, len(self.chain)) for f in findings]  # timed when the chain is
        self.chain.append(seg)
        if move.motion.zone.is_fine or alone:
            self.flush()

    def _event(self, instr: ir.Instr) -> None:
        if self.chain:
            self.events.append((instr, len(self.chain) - 1))
        else:
            self._event_record(instr, self.t)

    def _event_record(self, instr: ir.Instr, t: float) -> None:
        end = t + instr.duration if isinstance(instr, ir.Pulse) else t
        self._record(instr, t, end)

    def _blocking(self, instr: ir.Instr) -> None:
        self.flush()
        t0 = self.t
        if isinstance(instr, (ir.Attach, ir.Detach)):
            self.held = instr.held
        if isinstance(instr, ir.WaitTime) and instr.duration > 0:
            self._append(HoldPiece(self.q.copy(), instr.duration))
        self._record(instr, t0, self.t)
        if isinstance(instr, ir.Sync):
            entry = (len(self.pieces), len(self.draft.records) - 1)
            if self.variant == 0:
                self.draft.syncs.append((instr, *entry))
            else:  # held at the main timeline's barrier time after alignment (sync.hold_variants)
                self.syncs.append(entry)

    def _append(self, piece: Piece) -> None:
        self.pieces.append(piece)
        self.t += piece.duration
        self.q = piece.end_q()

    # ------------------------------------------------------------------ if
    def _if(self, instr: ir.If, rest: _Rest) -> None:
        self.flush()
        t0, q0 = self.t, self.q.copy()
        n_records = len(self.draft.records)
        self._record(instr, t0, t0)  # placeholder, completed below (keeps record indexes stable)
        state = (self.tool, self.held)
        self.walk(instr.then, rest)
        self.flush()
        self.draft.records[n_records] = replace(self.draft.records[n_records], t_end=self.t)
        # a `stop` in the then arm: the other path goes on, planned as a variant
        if (instr.otherwise or self.stopped) and self.spawn:
            self._variant(instr, instr.otherwise, "otherwise", rest, t0, q0, n_records, state)

    def _variant(
        self,
        instr: ir.Instr,
        arm: tuple[ir.Instr, ...],
        kind: str,
        rest: _Rest,
        t0: float,
        q0: np.ndarray,
        n_records: int,
        state: tuple[str | None, tuple[str, ...]],
        hold: float = 0.0,
    ) -> None:
        """`arm` from (t0, q0) (after a hold of `hold` s: a wait's timeout), then the rest of the
        task from the arm's end; `kind` names the path (PATHS)."""
        self.counter[0] += 1
        index = self.counter[0]
        sub = _Builder(self.robot, self.task, q0, t0, index, self.draft, self.counter, self.lone,
                       self.torque)
        sub.paths, (sub.tool, sub.held), sub.budget_s = self.paths, state, self.budget_s
        line = instr.span.start.line if instr.span is not None else "?"
        sub.note = (f"on {path_words(kind, line)}", instr.span)
        if hold > 0:
            sub._append(HoldPiece(q0.copy(), hold))
            sub._record(instr, t0, sub.t)
        sub.walk(arm, rest)
        sub.flush()
        n_if = len(self.draft.records)
        sub.spawn = False
        sub.walk_rest(rest)
        sub.flush()
        self.draft.variants.append(
            VariantDraft(
                index,
                instr.uid,
                kind,
                t0,
                sub.pieces,
                n_records,
                q0,
                len(self.draft.syncs),
                sub.syncs,
            )
        )
        self.draft.continuations.append((index, n_if))

    # ------------------------------------------------------------------ runtime logic
    def _wait_branch(
        self, instr: ir.WaitInput | ir.WaitCondition, rest: _Rest
    ) -> None:
        """The main timeline: the condition holds at once (as for every `wait until`); a variant:
        the timeout passes (the robot stands for T), the timeout branch runs, then the rest."""
        self.flush()
        t0, q0, state = self.t, self.q.copy(), (self.tool, self.held)
        n_records = len(self.draft.records)
        self._record(instr, t0, t0)
        if self.spawn:
            self._variant(
                instr,
                instr.on_timeout,
                "timeout",
                rest,
                t0,
                q0,
                n_records,
                state,
                hold=instr.timeout or 0.0,
            )

    def _state(self) -> tuple[np.ndarray, str | None, tuple[str, ...]]:
        return self.q.copy(), self.tool, tuple(sorted(self.held))

    def _while(self, instr: ir.While, rest: _Rest) -> None:
        """The body from the state before the loop, then again from the state at its end, until an
        iteration ends in the state it started from (joints within _SAME_Q, same tool, same parts
        held): every later iteration repeats that one. No fixed point in WHILE_BOUND iterations:
        E240. The code after the loop: on the main timeline from the fixed point, and as a variant
        from the state before the loop (no iteration)."""
        self.flush()
        t0, q0, state0 = self.t, self.q.copy(), (self.tool, self.held)
        n_records = len(self.draft.records)
        self._record(instr, t0, t0)
        quiet, outer_round = self.repeat_quiet, self.while_round
        line = instr.span.start.line if instr.span is not None else "?"
        proved = False
        for k in range(WHILE_BOUND):
            start = self._state()
            self.repeat_quiet = quiet or k > 0
            later = f"round {k + 1} of the while at line {line}"
            self.while_round = later if k > 0 else outer_round
            self.walk(instr.body, rest)
            self.flush()
            if self.stopped:
                proved = True  # the body ends the task: no further iteration
                break
            end = self._state()
            if (
                start[1:] == end[1:]
                and start[0].shape == end[0].shape
                and np.max(np.abs(start[0] - end[0]), initial=0.0) <= _SAME_Q
            ):
                proved = True
                break
        self.repeat_quiet, self.while_round = quiet, outer_round
        self.draft.records[n_records] = replace(self.draft.records[n_records], t_end=self.t)
        if not proved:
            line = instr.span.start.line if instr.span is not None else "?"
            msg = (
                f"the while loop at line {line} must reach a repeating state: an iteration must "
                "end in the joints, tool and held parts it started from (got a different end state "
                f"after each of {WHILE_BOUND} iterations), so its later iterations cannot be "
                "verified; make the body end where it starts "
                "(e.g. return to a joint target)"
            )
            self._diag(Finding(codes.WHILE_NO_FIXED_POINT, Severity.ERROR, msg), instr.span, self.t)
        if self.spawn:  # the loop may run no iteration (also when its body stops)
            self._variant(instr, (), "no iteration", rest, t0, q0, n_records, state0)

    # ------------------------------------------------------------------ chains
    def flush(self) -> None:
        if not self.chain:
            return
        chain, events, pending, t0 = self.chain, self.events, self.pending, self.t
        self.chain, self.events, self.pending = [], [], []
        coordinated = len(chain) == 1 and chain[0].move.coordinated is not None  # timed with its axes
        timed = time_coordinated(self.robot, chain[0]) if coordinated else time_chain(self.robot, chain, self.torque)
        self._append(timed.piece)
        for i, seg in enumerate(chain):
            self._move_record(seg, timed, i, t0, chain_accel_share(chain))
        if timed.error is not None:
            code = codes.TIME_TOO_SHORT if timed.error_is_time else codes.TIMING_FAILED
            at = 0 if timed.error_is_time else (timed.error_at if timed.error_at is not None else len(chain) - 1)
            self._diag(Finding(code, Severity.ERROR, timed.error), chain[at].move.span,
                       t0 + timed.starts[at], chain[at].move.uid)
        for k in timed.stops:
            msg = (f"the blended motion through this move could not be timed ({timed.stop_reason}); the robot "
                   f"stops exactly at this move's target at t = {t0 + timed.ends[k]:.3f} s")
            self._diag(Finding(codes.TIMING_EXACT_STOP, Severity.WARNING, msg), chain[k].move.span,
                       t0 + timed.ends[k], chain[k].move.uid)
        for f, k in pending:
            self._diag(f, chain[k].move.span, t0 + timed.starts[k], chain[k].move.uid)
        for instr, k in events:
            self._event_record(instr, t0 + timed.ends[k])
        for k, f in (timed.path.findings if timed.path is not None else ()):
            self._diag(f, chain[k].move.span, t0 + timed.ends[k], chain[k].move.uid)

    def _move_record(self, seg: Segment, timed: TimedChain, i: int, t0: float,
                     accel_share: float) -> None:
        robot, move = self.robot, seg.move
        flange = robot.fk(seg.q_end)
        tcp = move.target.pose if isinstance(move.target, ir.CartesianTarget) else \
            ir.Pose.from_matrix(flange @ move.tool.tcp.matrix())
        branch = robot.branch(seg.q_end)
        self._record(
            move, t0 + timed.starts[i], t0 + timed.ends[i], q_target=seg.q_end.copy(),
            branch=branch if branch.shoulder is not None else None, tcp_pose=tcp,
            flange_pose=ir.Pose.from_matrix(flange), blend_radius=timed.radii[i],
            accel_share=accel_share, axes_path=coordinated_axes(timed, t0),
            q_via=seg.q[seg.via_index].copy() if seg.via_index is not None else None,
            ext_via=seg.via_axes() if isinstance(seg, CoordinatedSegment) else None)


# ---------------------------------------------------------------- one handler per instruction kind
# (the planner plans each kind its own way: a dispatcher, checked complete at import against
# lang/ir_tree.KINDS; `after` is what runs after the instruction, as in `_Builder.walk`)


def _plan_loop(b: _Builder, instr: ir.Loop, after: _Rest) -> None:
    """Every iteration in order, each continued by the later ones (one link each: linear)."""
    for k, it in enumerate(instr.iterations):
        b.walk(it.body, _Iterations(instr, k + 1, after))


def _plan_wait(b: _Builder, instr: ir.WaitInput | ir.WaitCondition, after: _Rest) -> None:
    if instr.on_timeout:
        b._wait_branch(instr, after)
    else:
        b._blocking(instr)


def _plan_sync(b: _Builder, instr: ir.Sync, after: _Rest) -> None:
    """A lone task's sync waits for nobody: an event; else a barrier the robot stands at."""
    if b.lone:
        b._event(instr)
    else:
        b._blocking(instr)


def _plan_stop(b: _Builder, instr: ir.Stop, after: _Rest) -> None:
    b.flush()
    b._record(instr, b.t, b.t)
    b.stopped = True


def _plan_event(b: _Builder, instr: ir.Instr, after: _Rest) -> None:
    b._event(instr)


def _plan_blocking(b: _Builder, instr: ir.Instr, after: _Rest) -> None:
    b._blocking(instr)


_PLAN: dict[type, Callable[[_Builder, Any, _Rest], None]] = {
    ir.Move: lambda b, instr, after: b._move(instr),
    **{kind: _plan_event for kind in _EVENTS},
    ir.Sync: _plan_sync,
    ir.ProcCall: lambda b, instr, after: b.walk(instr.body, after),
    ir.If: lambda b, instr, after: b._if(instr, after),
    ir.Loop: _plan_loop,
    ir.While: lambda b, instr, after: b._while(instr, after),
    ir.WaitInput: _plan_wait,
    ir.WaitCondition: _plan_wait,
    **{kind: _plan_blocking for kind in (ir.WaitTime, ir.Attach, ir.Detach)},
    ir.Stop: _plan_stop,
}
require_kinds("compiler/plan/timeline._PLAN", _PLAN)


def build_task(robot: RobotModel, task: ir.Task, q0: np.ndarray, *, lone: bool = False,
               torque: TorqueLimits | None = None, budget_s: float = float("inf")) -> TaskDraft:
    """The timeline of one task from joints q0 (dof,); `lone`: the program's only task (syncs are no-ops);
    `torque`: the task's joint torque limits (compiler/plan/torque.py), None where there are none;
    `budget_s`: a path (main or variant) longer than this is not walked further, as the planner
    refuses it (E124): the timing work stays bounded by the time the planner accepts."""
    draft = TaskDraft()
    builder = _Builder(robot, task.name, q0, 0.0, 0, draft, [0], lone, torque)
    builder.paths, builder.budget_s = iteration_paths(task.body), budget_s
    builder.walk(task.body)
    builder.flush()
    draft.pieces = builder.pieces
    draft.q = builder.q
    draft.diagnostics += _continuations_apart(draft, task.name)
    return draft


def _continuations_apart(draft: TaskDraft, task: str) -> list[Diagnostic]:
    """W223 at each move after an if whose target joints on the otherwise path differ from every
    main-timeline solution of that move (the controller program is written from the main one)."""
    main: dict[int, list[np.ndarray]] = {}
    for r in draft.records:
        if r.variant == 0 and r.q_target is not None:
            main.setdefault(r.uid, []).append(r.q_target)
    variants = {v.index: v for v in draft.variants}
    out = []
    for index, first in draft.continuations:
        for r in draft.records[first:]:
            if r.variant != index or r.q_target is None or r.uid not in main:
                continue
            apart = min(float(np.max(np.abs(r.q_target - q))) for q in main[r.uid])
            if apart <= 1e-4:
                continue
            span = next((x.span for x in draft.records if x.uid == variants[index].if_uid), None)
            line = span.start.line if span is not None else "?"
            path = path_words(variants[index].arm, line)
            main_branch = next(x.branch for x in draft.records if x.uid == r.uid and x.variant == 0)
            fix = ("give the move a config(...)" if r.branch != main_branch
                   else "end both arms in the same joint state")  # same branch: a turn of a joint
            msg = (f"on {path} this move must reach the same joints as on the main path (they "
                   f"differ by up to {np.degrees(apart):.1f} deg); the controller program uses the "
                   f"main path's solution: {fix}")
            out.append(Diagnostic(codes.IF_ARMS_DIFFER, Severity.WARNING, msg, r.span, ((
                "the if", span),), time_s=r.t_end, task=task))
            break  # one warning per variant: later moves follow from this one
    return out


def proc_records(body: tuple[ir.Instr, ...], records: list[InstructionRecord]) -> list[InstructionRecord]:
    """Records of proc calls and for/repeat loops: each spans its body's records (per variant)."""
    out = []
    for instr in walk(body):
        runs, bodies = flow(instr)
        if not runs.sure:  # a record spans a proc call's body or a loop's iterations
            continue
        uids = {i.uid for i in walk_bodies(bodies)}
        for variant in sorted({r.variant for r in records if r.uid in uids}):
            inner = [r for r in records if r.uid in uids and r.variant == variant]
            t0, t1 = min(r.t_start for r in inner), max(r.t_end for r in inner)
            out.append(InstructionRecord(instr.uid, instr.span, t0, t1, variant=variant))
    return out
