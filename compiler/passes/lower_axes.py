"""External axes in the cell and in a program: tracks, positioners, `on`, `with`, `ext(...)`,
`move axes` -> lang/ir_axes.py values and ir.Move.ext.

Cell (`CellAxes`, used by lower_cell's builder):
  * `track NAME = linear(axis x, range(0mm, 4000mm)) speed V accel A at POSE` and
    `positioner NAME = axes(revolute(axis y, range(...)) speed V accel A, ...) at POSE`; the
    axis directions are those of the mechanism's own frame (`at`, in world). A track has one
    linear axis; a positioner one or two axes of either kind.
  * Each axis is named after its mechanism: `rail` for a one-axis mechanism, else `pos.1`,
    `pos.2`. Its home value (where the cell's listing places what it carries) is 0 when the
    range holds 0, else the range's nearer end.
  * `robot r1 = ... on rail at POSE`: POSE on the carriage; a robot rides on a track only.
    `fixture jig = ... on pos at POSE`: POSE on the flange. A frame whose value names a
    mechanism (`frame work = pos * pose(z=40mm)`) rides on it, at its value at home.
Program (`ProgramAxes`, used by the task lowering):
  * `program p on r1 with rail, pos`: the mechanisms the task drives; a robot on a track must
    drive it. All of them start at home.
  * `ext(rail=1200mm, pos=(30deg, 90deg))` sets axis values at a move's target (a one-axis
    mechanism by its name and one value, a two-axis one by its name and a pair); an axis not
    set keeps its value. The target's pose resolves with the axes there:
    the arm's base rides on its track, a frame on a positioner moves with its flange.
  * A joint move and `move axes` move the axes time-synchronously with the arm: the move lasts
    at least each axis' shortest rest-to-rest time (ir.Motion.min_duration), and stops exactly
    at both ends. A linear or circular move whose axes change is *coordinated*
    (ir_axes.Coordinated): the TCP on its path in the move's frame while the axes move along.
    In a frame fixed in world only the track carrying the robot may move; in a frame riding on
    a positioner, that positioner's axes and the robot's track (else E606 / E609); the robot's
    base frame (it moves with the track) is E606. It too stops exactly at both ends. A move in
    a frame riding on a mechanism the program does not drive is E610.
  * Inside an if, each arm starts from the values before it and both must end at the same
    values; a while body must end at the values it started from (every pass then starts and is
    timed alike); a `for`/`repeat` is unrolled, each round from the values the last left.
    Otherwise E606, as is an axis change inside a wait's timeout branch.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import replace

from rmot.lang import codes_axes, ir
from rmot.lang.ir_axes import AXIS_DIRECTIONS, Coordinated, ExtAxis, ExternalAxes, Mechanism, Mount, axis_time
from rmot.lang.ir_tree import Runs, flow, walk
from rmot.compiler.passes.context import Reporter, Scope
from rmot.compiler.passes.evaluate import eval_expr, expect_quantity
from rmot.compiler.passes.limits import MAX_SIZE_M
from rmot.compiler.passes.lower_axis_solids import axis_mass, axis_solids
from rmot.compiler.passes.lower_model import GeometryFn
from rmot.compiler.passes.values import ACCEL, ANGLE, ANGULAR_ACCEL, ANGULAR_SPEED, DIMENSIONLESS, LENGTH, SPEED, Dim, VectorV, Value
from rmot.lang import ast
from rmot.lang.source import Span

__all__ = ["CellAxes", "ProgramAxes", "check_axis_branches", "names_in", "program_axes", "refuse_track_in_tasks"]

_KINDS = ("linear", "revolute")
MAX_TURNS = 100  # policy: a revolute axis' range at most +-100 turns (a turntable that never unwinds)


def names_in(e: ast.Expr) -> set[str]:
    """Every plain name an expression reads (a frame riding on a mechanism names it)."""
    out: set[str] = set()
    stack: list[object] = [e]
    while stack:
        node = stack.pop()
        if isinstance(node, ast.Name):
            out.add(node.name)
        elif isinstance(node, ast.BinOp):
            stack += [node.left, node.right]
        elif isinstance(node, ast.Neg):
            stack.append(node.operand)
        elif isinstance(node, (ast.Call, ast.Vector)):
            stack += [a.value for a in (node.args if isinstance(node, ast.Call) else node.items)]
    return out


class CellAxes:
    """The mechanisms and mounts of one cell, built declaration by declaration."""

    def __init__(self, rep: Reporter, scope: Scope) -> None:
        self.rep = rep
        self.scope = scope
        self.mechanisms: dict[str, Mechanism] = {}
        self.mounts: list[Mount] = []

    def result(self) -> ExternalAxes | None:
        return ExternalAxes(tuple(self.mechanisms.values()), tuple(self.mounts)) if self.mechanisms else None

    def mechanism(self, s: ast.MechanismDecl, base: ir.Pose | None) -> ir.Pose | None:
        """The mechanism's flange at home in world (None after an error)."""
        many = len(s.axes) > 1
        axes = [self._axis(a, f"{s.name.name}.{i + 1}" if many else s.name.name) for i, a in enumerate(s.axes)]
        if s.kind == "track" and axes and axes[0] is not None and not axes[0].linear:
            self.rep.error(codes_axes.EXT_AXIS_DEFINITION, f"a track's axis must be linear (got {s.axes[0].kind.name})", s.axes[0].kind.span)
            return None
        if len(axes) > 2:
            self.rep.error(codes_axes.EXT_AXIS_DEFINITION, f"a positioner must have 1 or 2 axes (got {len(axes)})", s.span)
            return None
        if s.on is not None and base is not None:  # stacked: `at` is on the carrier's flange (at its home)
            carrier = self.mechanisms.get(s.on.name)
            if carrier is None:
                self.rep.unknown(s.on.name, "track or positioner declared before it", s.on.span, list(self.mechanisms),
                                 codes_axes.EXT_MOUNT)
                return None
            base = carrier.flange(carrier.home()) * base
        if base is None or any(a is None for a in axes):
            return None
        mech = Mechanism(s.name.name, s.kind, tuple(a for a in axes if a is not None), base, s.span,
                         s.on.name if s.on is not None else None)
        self.mechanisms[mech.name] = mech
        return mech.flange(mech.home())

    def _axis(self, a: ast.ExtAxisDecl, name: str) -> ExtAxis | None:
        rep = self.rep
        if a.kind.name not in _KINDS:
            rep.error(codes_axes.EXT_AXIS_DEFINITION, f"an external axis must be linear or revolute (got '{a.kind.name}')", a.kind.span)
            return None
        linear = a.kind.name == "linear"
        direction = AXIS_DIRECTIONS.get(a.axis.name)
        if direction is None:
            rep.error(codes_axes.EXT_AXIS_DEFINITION, f"an external axis must move along x, y or z (got 'axis {a.axis.name}')", a.axis.span)
            return None
        bounds = self._range(a, LENGTH if linear else ANGLE)
        speed = self._positive(a.speed, SPEED if linear else ANGULAR_SPEED, f"speed of axis '{name}'", a.span)
        accel = self._positive(a.accel, ACCEL if linear else ANGULAR_ACCEL, f"accel of axis '{name}'", a.span)
        if bounds is None or speed is None or accel is None:
            return None
        low, high = bounds
        home = min(max(0.0, low), high)
        pulses = None if a.inform is None else self._pulses(a.inform, linear, name)  # after E608: kept, unscaled
        mass = axis_mass(a.mass, name, self.scope, rep)
        if mass is None:
            return None
        return ExtAxis(name, linear, direction, low, high, speed, accel, home, a.span, pulses, mass)

    def _pulses(self, call: ast.Call, linear: bool, name: str) -> float | None:
        """The INFORM binding `inform(pulses_per_mm=N)` (linear) or `inform(pulses_per_deg=N)`
        (revolute): the axis' encoder pulses per unit, machine data of the controller (a job
        writes base and station positions in pulses), one finite number > 0."""
        key = "pulses_per_mm" if linear else "pulses_per_deg"
        arg = call.args[0] if len(call.args) == 1 else None
        if arg is None or arg.name is None or arg.name.name != key:
            self.rep.error(codes_axes.EXT_INFORM_BINDING, f"the INFORM binding of axis '{name}' must be inform({key}=N)", call.span)
            return None
        x = expect_quantity(eval_expr(arg.value, self.scope, self.rep), DIMENSIONLESS, f"{key} of axis '{name}'", arg.span, self.rep)
        if x is not None and not (math.isfinite(x) and x > 0):
            self.rep.error(codes_axes.EXT_INFORM_BINDING, f"{key} of axis '{name}' must be a finite number > 0 (got {x:g})", arg.value.span)
            return None
        return x

    def _range(self, a: ast.ExtAxisDecl, dim: Dim) -> tuple[float, float] | None:
        call = a.args[0].value if len(a.args) == 1 else None
        if not isinstance(call, ast.Call) or call.func.name != "range" or len(call.args) != 2:
            self.rep.error(codes_axes.EXT_AXIS_DEFINITION, "an external axis must give its travel as range(low, high) after the axis",
                           a.args[0].span if a.args else a.span)
            return None
        what = "the low end of the range", "the high end of the range"
        ends = [self._finite(eval_expr(arg.value, self.scope, self.rep), dim, w, arg.span) for arg, w in zip(call.args, what)]
        low, high = ends
        if low is None or high is None:
            return None
        if not low < high:
            self.rep.error(codes_axes.EXT_AXIS_DEFINITION, "range(low, high) must have low < high (got "
                           f"{_shown(low, dim)} .. {_shown(high, dim)})", call.span)
            return None
        bound = MAX_SIZE_M if dim == LENGTH else MAX_TURNS * 2 * math.pi  # a cell's size; a few turns
        if max(-low, high) > bound:
            self.rep.error(codes_axes.EXT_AXIS_DEFINITION, f"range(low, high) must stay within +-{_shown(bound, dim)} "
                           f"(got {_shown(low, dim)} .. {_shown(high, dim)})", call.span)
            return None
        return low, high

    def _finite(self, v: Value | None, dim: Dim, what: str, span: Span) -> float | None:
        x = expect_quantity(v, dim, what, span, self.rep)
        if x is not None and not math.isfinite(x):
            self.rep.error(codes_axes.EXT_AXIS_DEFINITION, f"{what} must be finite (got {x})", span)
            return None
        return x

    def _positive(self, e: ast.Expr | None, dim: Dim, what: str, span: Span) -> float | None:
        if e is None:
            self.rep.error(codes_axes.EXT_AXIS_DEFINITION, f"{what} must be given (the controller's machine data for it)", span)
            return None
        x = self._finite(eval_expr(e, self.scope, self.rep), dim, what, e.span)
        if x is not None and x <= 0:
            self.rep.error(codes_axes.EXT_AXIS_DEFINITION, f"{what} must be > 0 (got {_shown(x, dim)})", e.span)
            return None
        return x

    def solids(self, s: ast.MechanismDecl, geometry: GeometryFn) -> list[ir.Fixture]:
        """The fixtures of the solids mechanism `s`'s axes carry (lower_axis_solids.py)."""
        mech = self.mechanisms.get(s.name.name)
        if mech is None:
            return []
        fixtures, mounts = axis_solids(s, mech, self.scope, self.rep, geometry)
        self.mounts += mounts
        return fixtures

    def carried(self, on: ast.Ident, local: ir.Pose | None, kind: str, body: str, span: Span) -> ir.Pose | None:
        """`body` rides on mechanism `on` at `local`: its world pose at home (None after an error)."""
        mech = self.mechanisms.get(on.name)
        if mech is None:
            self.rep.unknown(on.name, "track or positioner", on.span, list(self.mechanisms), codes_axes.EXT_MOUNT)
            return None
        if kind == "robot" and mech.kind != "track":
            self.rep.error(codes_axes.EXT_MOUNT, f"a robot must ride on a track (got positioner '{on.name}')", on.span)
            return None
        if local is None:
            return None
        self.mounts.append(Mount(body, kind, mech.name, local, span))
        return mech.flange(mech.home()) * local

    def frame(self, name: str, value: ast.Expr, world: ir.Pose, span: Span, number: ast.Expr | None = None) -> None:
        """A frame whose value names a mechanism, or a frame riding on one, rides on it (at its
        place at home): `frame seam = work * pose(x=-150mm)` moves with `work`'s positioner."""
        carried = {m.body: m.mechanism for m in self.mounts if m.kind == "frame"}
        riding = sorted({carried.get(n, n) for n in names_in(value) if n in self.mechanisms or n in carried})
        if len(riding) > 1:
            self.rep.error(codes_axes.EXT_MOUNT, f"frame '{name}' must ride on one mechanism (got {', '.join(riding)})", value.span)
        elif riding:
            mech = self.mechanisms[riding[0]]
            self.mounts.append(Mount(name, "frame", mech.name, mech.flange(mech.home()).inverse() * world, span))
            if number is not None:
                self.rep.warning(codes_axes.EXT_FRAME_NUMBER, f"frame '{name}' rides on '{mech.name}': its number is not "
                                 "used (a program that moves it writes the frame through the mechanism: RAPID's "
                                 "coordinated wobjdata, KRL's EK() base, Fanuc's UFRAME 0 at the axis values)", number.span)


def _shown(x: float, dim: Dim) -> str:
    return f"{x * 1000:.6g} mm" if dim == LENGTH else f"{math.degrees(x):.6g} deg"


def check_axis_branches(body: tuple[ir.Instr, ...], rep: Reporter) -> None:
    """E606 for an axis change inside a body that runs zero times or once (a wait's timeout
    branch): the axes' values after it would depend on whether it ran. An if or while is checked
    while it is lowered (ProgramAxes.join_arms, ProgramAxes.check_pass)."""
    for instr in walk(body):
        runs, bodies = flow(instr)
        if runs is not Runs.MAYBE:
            continue
        for inner in walk(tuple(i for b in bodies for i in b)):
            if isinstance(inner, ir.Move) and inner.motion.min_duration is not None:
                rep.error(codes_axes.EXT_MOTION, "external axes must not move inside a branch that may not run (their "
                          "values after it would depend on the path taken); move them before or after it", inner.span)
                return


def program_axes(prog: ast.ProgramDecl, robot: ir.RobotInstance, cell: ir.Cell, rep: Reporter) -> ProgramAxes | None:
    """The axes a single-robot program drives (`with ...`), or None when it drives none or
    after an error (E603)."""
    external = cell.external or ExternalAxes()
    names: list[str] = []
    for ident in prog.axes:
        if external.mechanism(ident.name) is None:
            rep.unknown(ident.name, "track or positioner", ident.span, [m.name for m in external.mechanisms], codes_axes.EXT_PROGRAM_AXES)
            return None
        names.append(ident.name)
    mount = external.mount(robot.name)
    if mount is not None and mount.mechanism not in names:
        rep.error(codes_axes.EXT_PROGRAM_AXES, f"program '{prog.name.name}' must drive the track robot '{robot.name}' rides on "
                  f"(add 'with {mount.mechanism}')", prog.name.span)
        return None
    return ProgramAxes(external, tuple(names), robot, rep) if names else None


def refuse_track_in_tasks(robot: ir.RobotInstance, cell: ir.Cell, span: Span, rep: Reporter) -> None:
    """E603 for a task block of a robot on a track: only a program on one robot drives axes."""
    mount = cell.external.mount(robot.name) if cell.external is not None else None
    if mount is not None:
        rep.error(codes_axes.EXT_PROGRAM_AXES, f"robot '{robot.name}' rides on track '{mount.mechanism}': its program must "
                  f"be a program on one robot that drives it (`program p on {robot.name} with {mount.mechanism}`), not a task",
                  span)


class ProgramAxes:
    """The axes one task drives, and their values as the lowering walks the program in order."""

    def __init__(self, external: ExternalAxes, mechanisms: tuple[str, ...], robot: ir.RobotInstance, rep: Reporter) -> None:
        self.external = external
        self.mechanisms = mechanisms
        self.axes = external.axes(mechanisms)
        self.robot = robot
        self.rep = rep
        self.values = {a.name: a.home for a in self.axes}
        self.last: ir.Move | None = None  # the last move lowered: what `move axes` holds

    def state(self) -> dict[str, float]:
        """The axis values so far (before an if or while)."""
        return dict(self.values)

    def restart(self, before: dict[str, float]) -> None:
        """The next arm of an if starts from the values before the if."""
        self.values = dict(before)

    def join_arms(self, after_then: dict[str, float], span: Span) -> None:
        """After both arms of an if (self at the end of the other arm): they must leave every
        axis at one value, since every later target's pose and timing start from it (E606)."""
        self._same(after_then, "both arms of an if must leave the external axes at the same values", "after one arm",
                   "after the other", span)

    def check_pass(self, before: dict[str, float], span: Span) -> None:
        """After a while body: it must end with the axes where it started, so every pass (and
        the code after the loop, which may follow no pass at all) starts from the same values
        (E606); the moves inside are then timed alike on every pass."""
        self._same(before, "a while body must end with the external axes where it started", "at its start",
                   "at its end", span)
        self.values = dict(before)

    def _same(self, other: dict[str, float], what: str, other_at: str, here_at: str, span: Span) -> None:
        differ = [a for a in self.axes if other[a.name] != self.values[a.name]]
        if differ:
            got = ", ".join(f"'{a.name}' {a.shown(other[a.name])} {other_at}, {a.shown(self.values[a.name])} {here_at}"
                            for a in differ)
            self.rep.error(codes_axes.EXT_MOTION, f"{what} (got {got}): every later move starts from them; "
                           "move the axes back inside it, or before or after it", span)

    def read_at_home(self, e: ast.Expr, what: str) -> None:
        """W607 where an expression reads, as a pose, a frame riding on a mechanism this program
        moves (or the mechanism): that is its place with every axis at home, and a target built
        from it stays there when the part moves; a pose given in the riding frame follows it."""
        riding = {m.body: m.mechanism for m in self.external.mounts if m.kind == "frame" and m.mechanism in self.mechanisms}
        riding |= {name: name for name in self.mechanisms}
        named = sorted(names_in(e) & set(riding))
        if named:
            name = named[0]
            how = f"`frame {name}`" if name != riding[name] else f"a frame riding on '{name}'"
            self.rep.warning(codes_axes.EXT_VALUE_AT_HOME, f"{what} reads '{name}' as a pose: its place with the axes at "
                             f"home, which stays there when '{riding[name]}' moves; give the pose in {how} to follow it", e.span)

    def move(self, move: ir.Move, s: ast.Move, scope: Scope) -> ir.Move | None:
        """`move` with the axis values at its target (its `ext(...)` over the values so far)."""
        self.read_at_home(s.target, "the move's target")
        if s.via is not None:
            self.read_at_home(s.via, "the move's via point")
        values = dict(self.values)
        for m in s.modifiers:
            if m.kind == "ext" and not self._ext(m.value, scope, values):  # type: ignore[arg-type]
                return None
        if not self._frame_driven(move, s):
            return None
        coordinated = None
        if values != self.values and move.kind is not ir.MotionKind.JOINT:
            coordinated = self._coordinated(move, values, s)
            if coordinated is None:
                return None
        timed = self._timed(self._resolved(move, values), values)
        if timed is not None and coordinated is not None:
            timed = replace(timed, coordinated=coordinated)
            self.last = timed
        return timed

    def _frame_driven(self, move: ir.Move, s: ast.Move) -> bool:
        """E610 for a move in a frame riding on a mechanism this program does not drive: where
        that mechanism stands is unknown to the program (its axes take no value here)."""
        mount = self.external.mount(move.frame.name) if move.frame.name is not None else None
        if mount is None or mount.kind != "frame" or mount.mechanism in self.mechanisms:
            return True
        self.rep.error(codes_axes.EXT_FRAME_UNDRIVEN, f"frame '{move.frame.name}' rides on '{mount.mechanism}', which this "
                       f"program does not drive: add it to the program's `with` (`with {', '.join((*self.mechanisms, mount.mechanism))}`)",
                       s.span)
        return False

    def _coordinated(self, move: ir.Move, values: dict[str, float], s: ast.Move) -> Coordinated | None:
        """The coordinated form of a linear or circular move that changes axis values: the TCP
        on its path in the move's frame while the axes move along. The frame is fixed in world
        (then only the track carrying the robot may move) or rides on a positioner (its axes and
        the robot's track may move). The robot's own base frame moves with the track and a frame
        on a track is no part carrier (E606, E609); any other mechanism's change is E606 in a
        fixed frame, E609 in a positioner's."""
        changed = [a.name for a in self.axes if values[a.name] != self.values[a.name]]
        kind = move.kind.name.lower()
        if move.frame.name is None:
            self.rep.error(codes_axes.EXT_MOTION, f"a {kind} move that moves external axes ({', '.join(changed)}) must name "
                           "its frame (the robot's base frame moves with the track): use a frame fixed in the world "
                           "(`frame world`) or one riding on the positioner", s.span)
            return None
        mount = self.external.mount(move.frame.name)
        carrier = self.external.mechanism(mount.mechanism) if mount is not None and mount.kind == "frame" else None
        if carrier is not None and carrier.kind != "positioner":
            self.rep.error(codes_axes.EXT_COORDINATED, f"a coordinated {kind} move must be in a frame fixed in the world or "
                           f"riding on a positioner (frame '{move.frame.name}' rides on track '{carrier.name}'); move the track "
                           "with a joint move or 'move axes' first", s.span)
            return None
        robot_mount = self.external.mount(self.robot.name)
        track = self.external.mechanism(robot_mount.mechanism) if robot_mount is not None else None
        allowed = {a.name for m in (track, carrier) if m is not None for a in m.axes}
        others = [n for n in changed if n not in allowed]
        if others and carrier is None:
            self.rep.error(codes_axes.EXT_MOTION, f"a {kind} move in frame '{move.frame.name}', which no moving mechanism "
                           f"carries, may move only the track the robot rides on (got a change of {', '.join(others)}); "
                           "a positioner's axes move during a linear or circular move only when its frame rides on "
                           "the positioner (coordinated motion): move them with a joint move or 'move axes' first", s.span)
            return None
        if others:
            assert carrier is not None
            self.rep.error(codes_axes.EXT_COORDINATED, f"a coordinated {kind} move in frame '{move.frame.name}' may move only the "
                           f"axes of '{carrier.name}', which carries the frame, and the track the robot rides on (got a change "
                           f"of {', '.join(others)}); move those with a joint move or 'move axes' first", s.span)
            return None
        moving = carrier is not None and any(a.name in changed for a in carrier.axes)
        return Coordinated(carrier.name if moving and carrier is not None else None, move.frame.name, self.robot.name,
                           self.robot.base, tuple((a.name, self.values[a.name]) for a in self.axes), self.external,
                           None if carrier is not None else move.frame.world)

    def move_axes(self, s: ast.MoveAxes, scope: Scope, timer: Callable[[ast.Expr, Scope, str], float | None]) -> ir.Move | None:
        """`move axes M to VALUES`: the arm holds the joints of the last move. Its only modifier
        is `time T` (`timer` evaluates it): the axes move at their own speed and acceleration,
        so a speed, zone, tool or frame there would be silently meaningless (E611)."""
        duration = None
        for m in s.modifiers:
            if m.kind != "time":
                self.rep.error(codes_axes.EXT_AXES_MODIFIER, f"'move axes' takes no '{m.kind}' (its axes move at their own "
                               "speed and acceleration, the arm holds its joints); only 'time' may slow it", m.span)
                return None
            duration = timer(m.value, scope, "move time")  # type: ignore[arg-type]
            if duration is None:
                return None
        if s.mechanism.name not in self.mechanisms:
            self.rep.unknown(s.mechanism.name, "mechanism this program drives", s.mechanism.span, list(self.mechanisms),
                             codes_axes.EXT_VALUES)
            return None
        if self.last is None:
            self.rep.error(codes_axes.EXT_MOTION, "'move axes' must follow a move of the arm (the arm holds the joints it "
                           "reached; got none before it)", s.span)
            return None
        values = dict(self.values)
        if not self._assign(s.mechanism.name, s.values, scope, values):
            return None
        held = replace(self.last, axes_only=True, kind=ir.MotionKind.JOINT, via=None, span=s.span, uid=0, free=None, coordinated=None,
                       motion=replace(self.last.motion, duration=duration))
        return self._timed(self._resolved(held, values, keep_base_pose=True), values)

    def _timed(self, move: ir.Move | None, values: dict[str, float]) -> ir.Move | None:
        if move is None:
            return None
        changed = [a for a in self.axes if values[a.name] != self.values[a.name]]
        ext = tuple((a.name, values[a.name]) for a in self.axes)
        if changed:
            if move.motion.zone.radius > 0 or (self.last is not None and self.last.motion.zone.radius > 0):
                self.rep.warning(codes_axes.EXT_STOPS, "a move that moves external axes stops exactly, and so does the "
                                 "move before it (their zones are planned as fine)", move.span)
            need = max(axis_time(values[a.name] - self.values[a.name], a.speed, a.accel) for a in changed)
            move = replace(move, motion=replace(move.motion, min_duration=need, zone=ir.Zone(0.0)))
        self.values = values
        move = replace(move, ext=ext)
        self.last = move
        return move

    def _ext(self, args: tuple[ast.Arg, ...], scope: Scope, values: dict[str, float]) -> bool:
        named: set[str] = set()
        for arg in args:
            if arg.name is None:
                self.rep.error(codes_axes.EXT_VALUES, "ext(...) must name each mechanism (`ext(rail=1200mm)`)", arg.span)
                return False
            if arg.name.name in named:
                self.rep.error(codes_axes.EXT_VALUES, f"ext(...) must set '{arg.name.name}' once (got it twice)", arg.span)
                return False
            named.add(arg.name.name)
            if arg.name.name not in self.mechanisms:
                self.rep.unknown(arg.name.name, "mechanism this program drives", arg.name.span, list(self.mechanisms),
                                 codes_axes.EXT_VALUES)
                return False
            if not self._assign(arg.name.name, arg.value, scope, values):
                return False
        return True

    def _assign(self, name: str, e: ast.Expr, scope: Scope, values: dict[str, float]) -> bool:
        mech = self.external.mechanism(name)
        assert mech is not None
        v = eval_expr(e, scope, self.rep)
        items = v.items if isinstance(v, VectorV) else (v,)
        if v is None or len(items) != len(mech.axes):
            if v is not None:
                self.rep.error(codes_axes.EXT_VALUES, f"'{name}' must get {len(mech.axes)} value{'s' * (len(mech.axes) > 1)}, "
                               f"one per axis (got {len(items)})", e.span)
            return False
        for axis, item in zip(mech.axes, items):
            x = expect_quantity(item, LENGTH if axis.linear else ANGLE, f"value of axis '{axis.name}'", e.span, self.rep)
            if x is None:
                return False
            if not math.isfinite(x):
                self.rep.error(codes_axes.EXT_VALUES, f"value of axis '{axis.name}' must be finite (got {x})", e.span)
                return False
            values[axis.name] = x
        return True

    def _resolved(self, move: ir.Move, values: dict[str, float], keep_base_pose: bool = False) -> ir.Move:
        """The move's frame and targets with the axes at `values`: the arm's base on its track,
        a frame on a positioner with its flange. `keep_base_pose`: the TCP stays where it is in
        the robot's base frame (the arm holds its joints) and its pose in the frame follows."""
        base = self.external.world(self.robot.name, values) or self.robot.base
        frame = move.frame
        if frame.name is None:
            return move
        world = self.external.world(frame.name, values) or frame.world
        frame = ir.FrameRef(frame.name, base.inverse() * world, world)

        def place(t: ir.CartesianTarget | None) -> ir.CartesianTarget | None:
            if t is None:
                return None
            if keep_base_pose:
                return replace(t, in_frame=frame.pose.inverse() * t.pose)
            return replace(t, pose=frame.pose * t.in_frame)

        target = move.target if isinstance(move.target, ir.JointTarget) else place(move.target)
        return replace(move, frame=frame, target=target, via=place(move.via))  # type: ignore[arg-type]
