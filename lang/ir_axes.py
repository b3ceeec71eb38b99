"""External axes as data: tracks and positioners, what they carry, and how an axis moves.

A *mechanism* is a chain of external axes fixed in the world at `base`: a `track` (one
linear axis whose carriage carries a robot) or a `positioner` (one or two axes whose flange
carries fixtures and frames). Each axis moves along (linear) or about (revolute) a unit
direction of the frame it sits in; the axes of one mechanism are stacked without offsets, so
the flange is `base * A1(q1) * A2(q2)` (the KUKA `$ETn` chain, root then one transform per
axis, with every local offset zero; KSS 8.5 "Configuration of Kinematic Systems").

Bodies ride on a mechanism through a `Mount`: the pose of the robot base, fixture or frame in
the mechanism's flange frame. Everything the cell lists in world (ir.Cell) is placed at the
mechanisms' *home* values; `ExternalAxes.world` places a mounted body for any axis values.

Time-synchronous motion (KUKA synchronous PTP with E1..E6; RAPID's MoveJ/MoveExtJ over a
robot and its units): every axis of a move starts and stops with the arm; each axis follows a
trapezoidal profile with its own speed and acceleration limits, stretched to the move's
duration (`synced_position`). `axis_time` is the shortest such profile of one axis.
"""

from __future__ import annotations

import math

import numpy as np

from rmot.lang import ir
from rmot.lang.record import record
from rmot.lang.source import Span

__all__ = ["AXIS_DIRECTIONS", "Coordinated", "ExtAxis", "ExternalAxes", "Mechanism", "Mount", "axis_time", "synced_position"]

AXIS_DIRECTIONS = {"x": (1.0, 0.0, 0.0), "y": (0.0, 1.0, 0.0), "z": (0.0, 0.0, 1.0)}


@record(slots=True)
class ExtAxis:
    """One external axis. `name`: how messages and vendors name it (`rail`, `pos.2`); SI units
    (m, m/s, m/s^2 for linear axes; rad, rad/s, rad/s^2 for revolute ones)."""

    name: str
    linear: bool
    direction: tuple[float, float, float]
    low: float
    high: float
    speed: float
    accel: float
    home: float
    span: Span | None = None
    pulses: float | None = None  # INFORM encoder pulses per mm (linear) or per degree (revolute), as declared
    mass: float = 0.0  # kg the axis moves (`mass M`: its solids, as the cell declares)

    def unit(self) -> str:
        return "mm" if self.linear else "deg"

    def shown(self, value: float) -> str:
        """`value` in the unit the program writes (mm or deg)."""
        return f"{value * 1000.0:.6g} mm" if self.linear else f"{math.degrees(value):.6g} deg"

    def beyond_half_turn(self) -> bool:
        """A revolute axis whose range passes +-180 deg: its targets are absolute axis values
        (every vendor's axis data: RAPID extax, KRL E1..E6, Fanuc J, INFORM EC pulses), so a
        move turns it through the programmed difference, never the shortest way round."""
        return not self.linear and (self.low < -math.pi or self.high > math.pi)

    def transform(self, value: float) -> ir.Pose:
        if self.linear:
            d = self.direction
            return ir.Pose((d[0] * value, d[1] * value, d[2] * value))
        half = 0.5 * value
        s = math.sin(half)
        d = self.direction
        return ir.Pose((0.0, 0.0, 0.0), (math.cos(half), d[0] * s, d[1] * s, d[2] * s))


@record(slots=True)
class Mechanism:
    name: str
    kind: str  # track | positioner
    axes: tuple[ExtAxis, ...]
    base: ir.Pose  # the first axis' frame in world (with the mechanism it stands on at home)
    span: Span | None = None
    on: str | None = None  # the mechanism whose flange carries this one (stacked), or None

    def flange(self, values: tuple[float, ...], through: int | None = None) -> ir.Pose:
        """The frame the last axis carries, in world, at `values` (one per axis); with
        `through`, the frame axis `through` (1-based) carries: its solids ride there."""
        pose = self.base
        for axis, value in list(zip(self.axes, values, strict=True))[:through]:
            pose = pose * axis.transform(value)
        return pose

    def home(self) -> tuple[float, ...]:
        return tuple(a.home for a in self.axes)


@record(slots=True)
class Mount:
    """A robot, fixture or frame riding on `mechanism` at `local` (in its flange frame)."""

    body: str
    kind: str  # robot | fixture | frame
    mechanism: str
    local: ir.Pose
    span: Span | None = None
    through: int | None = None  # rides on axis `through` (1-based: an axis' solid), not the flange

    def group(self) -> str:
        """What moves it: the mechanism's name, or `name#k` for a body on its axis k."""
        return self.mechanism if self.through is None else f"{self.mechanism}#{self.through}"


@record(slots=True)
class ExternalAxes:
    mechanisms: tuple[Mechanism, ...] = ()
    mounts: tuple[Mount, ...] = ()

    def mechanism(self, name: str) -> Mechanism | None:
        return next((m for m in self.mechanisms if m.name == name), None)

    def mount(self, body: str) -> Mount | None:
        return next((m for m in self.mounts if m.body == body), None)

    def axes(self, mechanisms: tuple[str, ...]) -> tuple[ExtAxis, ...]:
        """Every axis of `mechanisms`, in that order: the order of a program's axis values."""
        out: list[ExtAxis] = []
        for name in mechanisms:
            mech = self.mechanism(name)
            out += mech.axes if mech is not None else ()
        return tuple(out)

    def values_of(self, mech: Mechanism, values: dict[str, float]) -> tuple[float, ...]:
        return tuple(values.get(a.name, a.home) for a in mech.axes)

    def moved(self, mech: Mechanism, values: dict[str, float]) -> ir.Pose:
        """How the mechanisms `mech` stands on move its base from its place at home (identity
        for one on the world): each carrier's flange(values) * flange(home)^-1, outermost first."""
        carrier = self.mechanism(mech.on) if mech.on is not None else None
        if carrier is None:
            return ir.Pose()
        return (self.moved(carrier, values) * carrier.flange(self.values_of(carrier, values))
                * carrier.flange(carrier.home()).inverse())

    def world(self, body: str, values: dict[str, float]) -> ir.Pose | None:
        """The world pose of a mounted body when the axes are at `values` (axis name -> value;
        an axis not given is at home), or None when `body` rides on no mechanism."""
        mount = self.mount(body)
        mech = None if mount is None else self.mechanism(mount.mechanism)
        if mount is None or mech is None:
            return None
        return self.moved(mech, values) * mech.flange(self.values_of(mech, values), mount.through) * mount.local


@record(slots=True)
class Coordinated:
    """A linear or circular move while external axes move: the TCP follows its line or arc *in
    the move's frame*, and the axes move in step with it. The path parameter u in [0, 1] is
    shared: at u the axes are at start + u (end - start) (ir.Move.ext is the end) and the TCP at
    the path's point u in the frame. The frame either rides on a positioner whose axes move
    (`mechanism`: the path is relative to the moving part, the reading of ABB's coordinated
    work object, KUKA's coupled EK base and Fanuc's COORD) or stays put in world during the
    move (`mechanism` None: a fixed frame, `frame_world`, or a positioner's frame while it
    stands still) while the track carries the robot along (ABB TRACK unit, KUKA ROBROOT
    kinematic, Fanuc integrated rail); see compiler/plan/coordinated.py."""

    mechanism: str | None  # the positioner carrying the frame when its axes move, else None
    frame: str
    robot: str
    robot_base: ir.Pose  # the robot's base in world with every axis at home
    start: tuple[tuple[str, float], ...]  # every axis of the program at the move's start (SI)
    external: ExternalAxes
    frame_world: ir.Pose | None = None  # the frame in world when it rides on no mechanism

    def relative(self) -> bool:
        """Whether the path is relative to a moving part (a positioner's axes move with it)."""
        return self.mechanism is not None

    def part_in_base(self, names: tuple[str, ...], values: np.ndarray) -> np.ndarray:
        """(N, 4, 4): the frame in the robot's base frame with the axes `names` at `values`
        (N, len(names)); an axis not named is at its start value."""
        columns = dict(self.start)
        rows = values.shape[0]

        def chain(body: str) -> np.ndarray | None:
            mount = self.external.mount(body)
            mech = None if mount is None else self.external.mechanism(mount.mechanism)
            if mount is None or mech is None:
                return None
            out = np.tile(mech.base.matrix(), (rows, 1, 1))
            for axis in mech.axes:
                v = values[:, names.index(axis.name)] if axis.name in names else np.full(rows, columns.get(axis.name, axis.home))
                out = out @ _axis_matrices(axis, v)
            placed: np.ndarray = out @ mount.local.matrix()
            return placed

        base = chain(self.robot)
        base = np.tile(self.robot_base.matrix(), (rows, 1, 1)) if base is None else base
        frame = chain(self.frame)
        if frame is None:  # a frame fixed in world
            assert self.frame_world is not None  # set for a frame that rides on no mechanism
            frame = np.tile(self.frame_world.matrix(), (rows, 1, 1))
        out: np.ndarray = np.linalg.inv(base) @ frame
        return out


def _axis_matrices(axis: ExtAxis, values: np.ndarray) -> np.ndarray:
    """(N, 4, 4) transforms of one axis at `values` (N,): a translation along, or a rotation
    about (Rodrigues), its unit direction; the same as ExtAxis.transform, vectorised."""
    out = np.tile(np.eye(4), (values.shape[0], 1, 1))
    d = np.asarray(axis.direction)
    if axis.linear:
        out[:, :3, 3] = values[:, None] * d
        return out
    k = np.array([[0.0, -d[2], d[1]], [d[2], 0.0, -d[0]], [-d[1], d[0], 0.0]])
    s, c = np.sin(values)[:, None, None], np.cos(values)[:, None, None]
    out[:, :3, :3] = np.eye(3) + s * k + (1.0 - c) * (k @ k)
    return out


def axis_time(delta: float, speed: float, accel: float) -> float:
    """The shortest rest-to-rest time over `delta` with speed and acceleration limits: a
    trapezoid, or a triangle when the top speed is never reached."""
    d = abs(delta)
    if d == 0.0:
        return 0.0
    if speed * speed / accel >= d:
        return 2.0 * math.sqrt(d / accel)
    return d / speed + speed / accel


def synced_position(start: float, end: float, duration: float, accel: float, t: np.ndarray) -> np.ndarray:
    """The axis' value at times `t` (0..duration) of a rest-to-rest move start -> end lasting
    exactly `duration` (>= axis_time): a trapezoid with the full acceleration `accel` and the
    cruise speed that makes it end on time (a triangle when that time is the shortest)."""
    delta = end - start
    d = abs(delta)
    if d == 0.0 or duration <= 0.0:
        return np.full(t.shape, end if duration <= 0.0 else start)
    disc = max(accel * accel * duration * duration - 4.0 * accel * d, 0.0)
    v = 0.5 * (accel * duration - math.sqrt(disc))  # cruise speed: d = v * (T - v / a)
    ramp = v / accel
    tc = np.clip(t, 0.0, duration)
    s = np.where(tc < ramp, 0.5 * accel * tc * tc,
                 np.where(tc <= duration - ramp, 0.5 * accel * ramp * ramp + v * (tc - ramp),
                          d - 0.5 * accel * (duration - tc) ** 2))
    out: np.ndarray = start + math.copysign(1.0, delta) * s
    return out
