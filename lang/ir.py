"""The IR: what the program means, checked, in SI units, with no modal state left.

This is the contract between the front end (lang + compiler.check), the planner, the
simulator and the backends. Everything is a frozen dataclass; sequences are tuples.

Units inside the IR are SI, always: metres, radians, seconds, kilograms, m/s, m/s^2, rad/s.
Ratios are fractions (50 % is 0.5). Orientation is a unit quaternion (w, x, y, z).

Frames:
  * world     — the cell's frame; robot bases, fixtures and cell frames are placed in it.
  * base      — a robot's base frame (`RobotInstance.base` is its pose in world).
  * flange    — the robot's mounting flange (vendor "tool0"), what `Robot.fk(q)` returns.
  * tcp       — the active tool's centre point: flange * Tool.tcp.
A Cartesian target's `pose` is the TCP pose in the robot's *base* frame (frame offsets and
robot placement already composed); `in_frame` is the same target as written, relative to
the move's active frame (what the backends emit together with the frame declaration).

Every instruction carries `uid`, unique within its Program (assigned in source order by
the lowering), so the planner's records and the simulator's findings can point back at it
even when two instructions are otherwise equal; and `span`, excluded from equality.

Over 600 lines: the IR's node classes are the one vocabulary every stage reads as `ir.<Name>`;
each is a few lines and splitting them would scatter that vocabulary."""

from __future__ import annotations

import math
from dataclasses import field
from enum import Enum, auto
from typing import TYPE_CHECKING, Union

from rmot.lang.record import record
from rmot.lang.source import Span
import json

if TYPE_CHECKING:

    import numpy as np
    from rmot.lang.ir_axes import Coordinated, ExternalAxes

__all__ = [
    "DEFAULT_JOINT_ACCEL", "DEFAULT_JOINT_SPEED", "DEFAULT_TCP_ACCEL", "DEFAULT_TCP_SPEED",
    "Box", "Capsule", "Cell", "CartesianTarget", "Config", "Cylinder", "Elbow", "Fixture",
    "Frame", "FrameRef", "Geometry", "If", "InputCondition", "Instr", "IoDirection",
    "IoSignal", "JointTarget", "Mesh", "Motion", "MotionKind", "Move", "Native", "Pose",
    "ProcCall", "Program", "Pulse", "RobotInstance", "RobotSource", "SetAnalog",
    "SetDigital", "Shoulder", "Sphere", "Sync", "Task", "Tool", "ToolRef", "WaitInput",
    "WaitTime", "Wrist", "Zone", "payload_cog",
    "Attach", "Detach", "Part",
    "AnalogInput", "Arith", "GroupInput", "OutputRead", "Assign", "Compare", "CompareOp", "Condition", "Const", "Logic",
    "Loop", "LoopIteration", "Not", "RtExpr", "Stop", "ValueType", "VarDecl", "VarRef",
    "WaitCondition", "While",
    "FreeMotion",
]


def _span_field() -> Span | None:
    return field(default=None, compare=False, hash=False, repr=False)


# --------------------------------------------------------------------------- poses


@record(slots=True)
class Pose:
    """A rigid transform: position in metres and a unit quaternion (w, x, y, z), w >= 0."""

    position: tuple[float, float, float] = (0.0, 0.0, 0.0)
    quaternion: tuple[float, float, float, float] = (1.0, 0.0, 0.0, 0.0)

    def __post_init__(self) -> None:
        w, x, y, z = self.quaternion
        norm = math.sqrt(w * w + x * x + y * y + z * z)
        if not (abs(norm - 1.0) < 1e-6):
            raise ValueError(f"Pose.quaternion must have unit norm (got {self.quaternion}, norm {norm})")

    @staticmethod
    def identity() -> Pose:
        return Pose()

    @staticmethod
    def from_xyz_rpy(x: float, y: float, z: float, rx: float, ry: float, rz: float) -> Pose:
        """LANGUAGE.md convention: R = Rz(rz)·Ry(ry)·Rx(rx) (fixed axes X, then Y, then Z)."""
        cr, sr = math.cos(rx / 2), math.sin(rx / 2)
        cp, sp = math.cos(ry / 2), math.sin(ry / 2)
        cy, sy = math.cos(rz / 2), math.sin(rz / 2)
        q = (
            cr * cp * cy + sr * sp * sy,
            sr * cp * cy - cr * sp * sy,
            cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy,
        )
        return Pose((x, y, z), _canonical(q))

    def rpy(self) -> tuple[float, float, float]:
        """(rx, ry, rz) with R = Rz(rz)·Ry(ry)·Rx(rx); ry in [-pi/2, pi/2]."""
        w, x, y, z = self.quaternion
        sinp = max(-1.0, min(1.0, 2 * (w * y - z * x)))
        rx = math.atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y))
        ry = math.asin(sinp)
        rz = math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))
        return rx, ry, rz

    def __mul__(self, other: Pose) -> Pose:
        """Composition: `a * b` is b expressed in a's frame."""
        rotated = _rotate(self.quaternion, other.position)
        pos = (
            self.position[0] + rotated[0],
            self.position[1] + rotated[1],
            self.position[2] + rotated[2],
        )
        return Pose(pos, _canonical(_qmul(self.quaternion, other.quaternion)))

    def inverse(self) -> Pose:
        w, x, y, z = self.quaternion
        conj = (w, -x, -y, -z)
        p = _rotate(conj, self.position)
        return Pose((-p[0], -p[1], -p[2]), _canonical(conj))

    def matrix(self) -> np.ndarray:
        """The (4, 4) homogeneous matrix."""
        import numpy as np  # late: loads numpy only when this runs

        w, x, y, z = self.quaternion
        m = np.eye(4)
        m[:3, :3] = [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
        m[:3, 3] = self.position
        return m

    @staticmethod
    def from_matrix(m: np.ndarray) -> Pose:
        """From a (4, 4) homogeneous matrix with an orthonormal rotation block."""
        r = m[:3, :3]
        tr = r[0, 0] + r[1, 1] + r[2, 2]
        if tr > 0:
            s = math.sqrt(tr + 1.0) * 2
            q = (0.25 * s, (r[2, 1] - r[1, 2]) / s, (r[0, 2] - r[2, 0]) / s, (r[1, 0] - r[0, 1]) / s)
        elif r[0, 0] > r[1, 1] and r[0, 0] > r[2, 2]:
            s = math.sqrt(1.0 + r[0, 0] - r[1, 1] - r[2, 2]) * 2
            q = ((r[2, 1] - r[1, 2]) / s, 0.25 * s, (r[0, 1] + r[1, 0]) / s, (r[0, 2] + r[2, 0]) / s)
        elif r[1, 1] > r[2, 2]:
            s = math.sqrt(1.0 + r[1, 1] - r[0, 0] - r[2, 2]) * 2
            q = ((r[0, 2] - r[2, 0]) / s, (r[0, 1] + r[1, 0]) / s, 0.25 * s, (r[1, 2] + r[2, 1]) / s)
        else:
            s = math.sqrt(1.0 + r[2, 2] - r[0, 0] - r[1, 1]) * 2
            q = ((r[1, 0] - r[0, 1]) / s, (r[0, 2] + r[2, 0]) / s, (r[1, 2] + r[2, 1]) / s, 0.25 * s)
        n = math.sqrt(sum(c * c for c in q))
        pos = (float(m[0, 3]), float(m[1, 3]), float(m[2, 3]))
        return Pose(pos, _canonical(tuple(float(c) / n for c in q)))


def _canonical(q: tuple[float, ...]) -> tuple[float, float, float, float]:
    """Unit quaternion with w >= 0 (q and -q are the same rotation; one spelling only)."""
    n = math.sqrt(sum(c * c for c in q))
    w, x, y, z = (c / n for c in q)
    if w < 0 or (w == 0 and (x, y, z) < (0.0, 0.0, 0.0)):
        w, x, y, z = -w, -x, -y, -z
    return (w + 0.0, x + 0.0, y + 0.0, z + 0.0)


def _qmul(a: tuple[float, ...], b: tuple[float, ...]) -> tuple[float, float, float, float]:
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return (
        aw * bw - ax * bx - ay * by - az * bz,
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
    )


def _rotate(q: tuple[float, ...], v: tuple[float, ...]) -> tuple[float, float, float]:
    w, x, y, z = q
    vx, vy, vz = v
    # v' = v + 2w(u × v) + 2 u × (u × v), u = (x, y, z)
    cx, cy, cz = y * vz - z * vy, z * vx - x * vz, x * vy - y * vx
    ccx, ccy, ccz = y * cz - z * cy, z * cx - x * cz, x * cy - y * cx
    return (vx + 2 * (w * cx + ccx), vy + 2 * (w * cy + ccy), vz + 2 * (w * cz + ccz))


# --------------------------------------------------------------------------- geometry


@record(slots=True)
class Box:
    """Centred on its pose; full edge lengths along local x, y, z (m)."""

    size: tuple[float, float, float]


@record(slots=True)
class Cylinder:
    """Axis along local z, centred on its pose (as in coal/FCL)."""

    radius: float
    height: float


@record(slots=True)
class Sphere:
    radius: float


@record(slots=True)
class Capsule:
    """Axis along local z, centred on its pose; `length` excludes the two hemispherical caps."""

    radius: float
    length: float


@record(slots=True)
class Mesh:
    """A mesh file, already resolved to an absolute path inside the project; `scale` converts
    the file's unit to metres (unit=mm gives 0.001). Loaded by the sim, not by the compiler."""

    path: str
    scale: float = 1.0
    span: Span | None = _span_field()


Geometry = Union[Box, Cylinder, Sphere, Capsule, Mesh]


# --------------------------------------------------------------------------- cell


class RobotSourceKind(Enum):
    LIBRARY = auto()  # a name from sim.robots.list_robots()
    URDF = auto()  # an absolute path to a URDF file
    MODEL = auto()  # a `model` block of the cell: ref is its load key (lang/model_spec.py)
    URDF_CHAIN = auto()  # urdf(path, base=, tip=, controller=): ref is "urdf-chain:" + JSON [path, base, tip(, maker)]


@record(slots=True)
class RobotSource:
    kind: RobotSourceKind
    ref: str  # library name, absolute URDF path, or the load key of a model / URDF chain
    # the cell's calibration of the arm to its controller (`robot r1 = NAME speed S % accel A %`):
    # shares of the joint speed and acceleration limits (1.0 = the robot's own)
    speed_share: float = 1.0
    accel_share: float = 1.0

    @property
    def load_key(self) -> str:
        """What `sim.robots.load_robot` takes (a calibrated arm: "calibrated:" + JSON)."""
        if self.speed_share == 1.0 and self.accel_share == 1.0:
            return self.ref

        return "calibrated:" + json.dumps([self.ref, self.speed_share, self.accel_share])


@record(slots=True)
class RobotInstance:
    name: str
    source: RobotSource
    base: Pose  # the robot base frame in world
    dof: int  # number of joints (from the robot library or the URDF)
    span: Span | None = _span_field()
    # the KUKA system software release the cell declares (`controller kss 8.3`), else None
    kss_release: float | None = None

    @property
    def exact_ptp_approximation(self) -> bool:
        """True when the cell declares KSS >= 8.2, whose PTP approximation takes a distance in
        mm (`PTP P C_DIS` with $APO.CDIS; KUKA System Software 8.2/8.3 Operating and Programming
        Instructions for System Integrators, "Approximate positioning") instead of C_PTP's
        percentage of half the motion: the corner stays inside the zone sphere."""
        return self.kss_release is not None and self.kss_release >= 8.2 - 1e-9


@record(slots=True)
class Fixture:
    name: str
    geometry: Geometry
    pose: Pose  # in world
    span: Span | None = _span_field()


@record(slots=True)
class Tool:
    name: str
    robot: str  # the robot it is mounted on
    geometry: Geometry | None  # in the flange frame (placed at `geometry_pose`)
    tcp: Pose  # TCP in the flange frame
    mass: float = 0.0  # kg (payload of the tool itself)
    geometry_pose: Pose = Pose()
    span: Span | None = _span_field()
    number: int | None = None  # the controller's tool number (`number n`), if the cell gives one


@record(slots=True)
class Frame:
    name: str
    pose: Pose  # in world
    span: Span | None = _span_field()
    number: int | None = None  # the controller's frame number (`number n`), if the cell gives one


class IoDirection(Enum):
    DIGITAL_OUT = auto()
    DIGITAL_IN = auto()
    ANALOG_OUT = auto()
    ANALOG_IN = auto()
    GROUP_IN = auto()  # gin[n]: several digital inputs read as one unsigned integer


@record(slots=True)
class IoSignal:
    direction: IoDirection
    port: int
    name: str  # the controller's signal name, e.g. "gripper_close"
    robot: str | None
    span: Span | None = _span_field()
    bits: int | None = None  # a group input's width (`bits B`): it reads 0..2^B-1


@record(slots=True)
class Cell:
    name: str
    robots: tuple[RobotInstance, ...]
    fixtures: tuple[Fixture, ...] = ()
    tools: tuple[Tool, ...] = ()
    frames: tuple[Frame, ...] = ()
    io: tuple[IoSignal, ...] = ()
    allowed_contacts: tuple[tuple[str, str], ...] = ()  # body pairs the checker ignores
    span: Span | None = _span_field()
    parts: tuple[Part, ...] = ()  # movable objects, at their starting poses
    external: ExternalAxes | None = None  # tracks and positioners; the bodies above at their home values

    def robot(self, name: str) -> RobotInstance:
        for r in self.robots:
            if r.name == name:
                return r
        raise KeyError(name)


# --------------------------------------------------------------------------- motion


class MotionKind(Enum):
    JOINT = auto()
    LINEAR = auto()
    CIRCULAR = auto()


class Shoulder(Enum):
    FRONT = "front"
    BACK = "back"


class Elbow(Enum):
    UP = "up"
    DOWN = "down"


class Wrist(Enum):
    FLIP = "flip"
    NOFLIP = "noflip"


@record(slots=True)
class Config:
    """An IK branch of a 6R arm; None fields are free (the planner keeps the current one)."""

    shoulder: Shoulder | None = None
    elbow: Elbow | None = None
    wrist: Wrist | None = None
    # fixed turns (joint index from 0, turn n) of joints whose range exceeds 360 deg,
    # sorted by joint; turn n = q in [n*360 - 180, n*360 + 180) deg (turn_of). Empty = free.
    turns: tuple[tuple[int, int], ...] = ()

    def __str__(self) -> str:
        parts = [f"{k}={v.value}" for k, v in (("shoulder", self.shoulder), ("elbow", self.elbow), ("wrist", self.wrist)) if v]
        parts += [f"j{j + 1}={n}" for j, n in self.turns]
        return ", ".join(parts) or "any"


def turn_of(q: float) -> int:
    """The turn of a revolute joint value q (rad): n with q in [n*2pi - pi, n*2pi + pi)
    (lang/REFERENCE.md section 6, "turns")."""
    return math.floor((q + math.pi) / (2 * math.pi))


@record(slots=True)
class Zone:
    """Blending radius in metres; 0.0 means `fine` (exact stop)."""

    radius: float = 0.0

    @property
    def is_fine(self) -> bool:
        return self.radius <= 0.0


# The settings a program has when it never sets them (LANGUAGE.md §4). They live in the IR
# because two stages read them: the front end applies them, and the backends treat a move
# at the default acceleration as "the controller's own" (nothing to express or warn about).
DEFAULT_TCP_SPEED = 0.25  # m/s
DEFAULT_TCP_ACCEL = 2.0  # m/s^2
DEFAULT_JOINT_SPEED = 1.0  # fraction of each joint's maximum speed
DEFAULT_JOINT_ACCEL = 1.0  # fraction of each joint's maximum acceleration


@record(slots=True)
class Motion:
    """Every speed-like setting a move needs, resolved from the modal settings (SI)."""

    tcp_speed: float  # m/s, for linear and circular moves
    tcp_accel: float  # m/s^2
    joint_speed: float  # fraction of each joint's max speed for joint moves, (0, 1]
    joint_accel: float  # fraction of each joint's max acceleration, (0, 1]
    zone: Zone
    duration: float | None = None  # s: a `time` modifier fixes the move's duration
    min_duration: float | None = None  # s: external axes moving with the arm need at least this (lang/ir_axes.py)


@record(slots=True)
class ToolRef:
    """The active tool; name None is the bare flange (tcp identity)."""

    name: str | None
    tcp: Pose = Pose()
    mass: float = 0.0


@record(slots=True)
class FrameRef:
    """The active reference frame; name None is the robot base (pose identity)."""

    name: str | None
    pose: Pose = Pose()  # the frame in the robot's base frame
    world: Pose = Pose()  # the frame in world


@record(slots=True)
class CartesianTarget:
    pose: Pose  # TCP in the robot base frame
    in_frame: Pose  # the same target relative to the move's frame, as written
    name: str | None = None  # the `target` name it came from, if any


@record(slots=True)
class JointTarget:
    values: tuple[float, ...]  # rad for revolute joints, m for prismatic
    name: str | None = None


@record(slots=True)
class FreeMotion:
    """`move free`: the joint move to the target is found by a collision-free search at plan
    time (sim/free/), then written as joint moves through the via points it finds."""

    clearance: float = 0.0  # m: the path keeps at least this distance from everything else
    samples: int = 1000  # configurations the search may draw: the budget that decides
    budget: float = 120.0  # s of search time: a safety stop (reported), never what decides


# --------------------------------------------------------------------------- instructions


@record(slots=True, kw_only=True)
class Move:
    uid: int
    kind: MotionKind
    target: CartesianTarget | JointTarget
    via: CartesianTarget | None = None  # circular moves only
    motion: Motion
    tool: ToolRef
    frame: FrameRef
    config: Config = Config()
    free: FreeMotion | None = None  # `move free` (kind JOINT): the path is searched at plan time
    span: Span | None = _span_field()
    ext: tuple[tuple[str, float], ...] = ()  # every external axis of the program at the target (SI)
    axes_only: bool = False  # `move axes`: the arm holds its joints while the axes move
    coordinated: Coordinated | None = None  # a linear/circular move on a frame its moving axes carry (lang/ir_axes.py)


@record(slots=True, kw_only=True)
class SetDigital:
    uid: int
    port: int
    value: bool
    signal: str | None = None  # the cell's name for the port, if declared
    span: Span | None = _span_field()


@record(slots=True, kw_only=True)
class SetAnalog:
    uid: int
    port: int
    value: float
    signal: str | None = None
    span: Span | None = _span_field()


@record(slots=True, kw_only=True)
class Pulse:
    uid: int
    port: int
    duration: float  # s
    signal: str | None = None
    span: Span | None = _span_field()


@record(slots=True, kw_only=True)
class WaitTime:
    uid: int
    duration: float  # s
    span: Span | None = _span_field()


@record(slots=True, kw_only=True)
class InputCondition:
    port: int
    value: bool
    signal: str | None = None


@record(slots=True, kw_only=True)
class WaitInput:
    uid: int
    condition: InputCondition
    timeout: float | None = None  # s
    span: Span | None = _span_field()
    on_timeout: tuple[Instr, ...] = ()  # `timeout T else { ... }`: runs when T passes first


@record(slots=True, kw_only=True)
class If:
    """A runtime branch; both arms are planned and verified. `condition` is an InputCondition
    for `if in[n] == on|off` (the one-input form every backend writes) or any
    Condition (and/or/not, analog inputs, variables)."""

    uid: int
    condition: Condition
    then: tuple[Instr, ...]
    otherwise: tuple[Instr, ...] = ()
    span: Span | None = _span_field()


@record(slots=True, kw_only=True)
class Sync:
    uid: int
    name: str
    span: Span | None = _span_field()


@record(slots=True, kw_only=True)
class Native:
    """Vendor text passed through by that backend only (`vendor` as written: rapid, krl, ...)."""

    uid: int
    vendor: str
    text: str
    span: Span | None = _span_field()


@record(slots=True, kw_only=True)
class ProcCall:
    """An inlined proc call: `body` is the proc's body with the arguments substituted.

    Kept as a node (not flattened) so backends can show the structure and name routines.
    """

    uid: int
    proc: str
    args: tuple[str, ...]  # the arguments as written, for comments
    body: tuple[Instr, ...]
    span: Span | None = _span_field()


# --------------------------------------------------------------------------- parts


@record(slots=True)
class Part:
    """A movable object: where it starts (world), its solid and its mass (kg). A tool picks it
    up with `attach` and puts it down with `detach`; where it is at any time follows from the
    Plan (sim/parts.py)."""

    name: str
    geometry: Geometry
    pose: Pose  # in world, before any task runs
    mass: float = 0.0
    span: Span | None = _span_field()
    # a feeder (`feeder NAME = ...`): a fresh part of this solid appears at `pose` whenever the
    # last one has been taken; `count` parts in all (None: without end). Each part it presents
    # is named NAME#k (k = 1, 2, ... in the order they are taken; sim/part_phases.py).
    feeder: bool = False
    count: int | None = None


@record(slots=True, kw_only=True)
class Attach:
    """`attach part`: the part is fixed to the active tool at its current relative pose.
    `held`: the parts this task holds after the instruction; `load`: the mass the flange then
    carries (tool + held parts, kg), what a backend writes as the payload."""

    uid: int
    part: str
    tool: ToolRef
    held: tuple[str, ...]
    load: float
    span: Span | None = _span_field()


@record(slots=True, kw_only=True)
class Detach:
    """`detach part`: the part stays where it is in the world (an obstacle from then on)."""

    uid: int
    part: str
    tool: ToolRef
    held: tuple[str, ...]
    load: float
    span: Span | None = _span_field()


# --------------------------------------------------------------------------- runtime logic
#
# Runtime state lives in the controller: typed variables a task declares, assigns and tests,
# conditions over inputs (digital and analog) and variables, loops that stay loops in the
# vendor program, a timeout branch on `wait until`, and `stop`. The front end lowers each `for`
# into a `Loop` whose every iteration is lowered with the loop variable bound (what the planner
# plans and the verifier checks, each instruction with its own uid); the backends decide per
# vendor whether the iterations can be written as one vendor loop (same structure, Cartesian
# targets affine in the loop variables, one IK branch and turn) or must be unrolled.


class ValueType(Enum):
    INT = "int"
    NUM = "num"
    BOOL = "bool"


class CompareOp(Enum):
    EQ = "=="
    NE = "!="
    LT = "<"
    LE = "<="
    GT = ">"
    GE = ">="

    def negated(self) -> CompareOp:
        """The comparison that holds exactly when this one does not (a < b: a >= b)."""
        return CompareOp({"==": "!=", "!=": "==", "<": ">=", ">=": "<", ">": "<=", "<=": ">"}[self.value])

    def mirrored(self) -> CompareOp:
        """The comparison with its operands swapped that means the same (a < b: b > a)."""
        return CompareOp({"==": "==", "!=": "!=", "<": ">", ">": "<", "<=": ">=", ">=": "<="}[self.value])


@record(slots=True)
class Const:
    value: int | float | bool
    type: ValueType


@record(slots=True)
class VarRef:
    """A task variable (declared by `var`) or, inside a `Loop`, the loop variable (INT)."""

    name: str
    type: ValueType


@record(slots=True)
class AnalogInput:
    """`ain[port]`: the controller's analog input value (NUM, in the controller's unit, V)."""

    port: int
    signal: str | None = None


@record(slots=True)
class GroupInput:
    """`gin[port]`: a group of digital inputs read as one unsigned integer (INT), e.g. the
    program number a PLC sends; `bits` is its width when the cell gives it."""

    port: int
    signal: str | None = None
    bits: int | None = None


@record(slots=True)
class OutputRead:
    """`out[port]`: the state the controller holds for its own digital output (BOOL). At
    program start it is whatever the last program left, so both arms of a branch on it are
    planned and verified, as for an input."""

    port: int
    signal: str | None = None


@record(slots=True)
class Arith:
    """`left op right`, op one of + - * / ; type INT unless an operand is NUM or op is '/'."""

    op: str
    left: RtExpr
    right: RtExpr
    type: ValueType


@record(slots=True)
class Compare:
    op: CompareOp
    left: RtExpr
    right: RtExpr


@record(slots=True)
class Logic:
    """`a and b and ...` (op "and") or `a or b ...` (op "or"); operands are conditions."""

    op: str
    operands: tuple[Condition, ...]


@record(slots=True)
class Not:
    operand: Condition


# A value computed at runtime; `InputCondition` (a digital input tested against on/off) is the
# BOOL leaf every backend already writes, so a plain `if in[1] == on` lowers exactly as before.
RtExpr = Union[Const, VarRef, AnalogInput, GroupInput, OutputRead, Arith, Compare, Logic, Not, InputCondition]
Condition = Union[InputCondition, Compare, Logic, Not, VarRef, Const, OutputRead]


@record(slots=True, kw_only=True)
class VarDecl:
    """`var NAME: type = EXPR`: a task variable with its initial value (a task-level
    declaration: backends declare it in the task's data section and assign `init` here)."""

    uid: int
    name: str
    type: ValueType
    init: RtExpr
    span: Span | None = _span_field()


@record(slots=True, kw_only=True)
class Assign:
    uid: int
    name: str
    value: RtExpr
    span: Span | None = _span_field()


@record(slots=True, kw_only=True)
class LoopIteration:
    """One value of the loop variable and the loop body lowered with it bound."""

    value: int
    body: tuple[Instr, ...]


@record(slots=True, kw_only=True)
class Loop:
    """`for var in first .. last { }` (var set) or `repeat n { }` (var None, values 0..n-1).

    `iterations` are in execution order, one per value (an empty range has none). The planner
    and verifier walk every iteration; a backend writes one vendor loop when the iterations
    allow it (backends/loops.py) and writes them one after another otherwise."""

    uid: int
    var: str | None
    first: int
    last: int
    iterations: tuple[LoopIteration, ...]
    span: Span | None = _span_field()


@record(slots=True, kw_only=True)
class While:
    """`while COND { body }` at runtime. The planner plans the body from the state before the
    loop until the state at the end of an iteration equals the state at its start (then every
    further iteration repeats it: REFERENCE.md §7), and the code after the loop from both the
    state before the loop (no iteration) and that fixed point."""

    uid: int
    condition: Condition
    body: tuple[Instr, ...]
    span: Span | None = _span_field()


@record(slots=True, kw_only=True)
class WaitCondition:
    """`wait until COND [timeout T [else { ... }]]` for a condition that is not one digital
    input (those stay `WaitInput`); `on_timeout` runs when T passes first (then the task goes
    on after the wait)."""

    uid: int
    condition: Condition
    timeout: float | None = None  # s
    on_timeout: tuple[Instr, ...] = ()
    span: Span | None = _span_field()


@record(slots=True, kw_only=True)
class Stop:
    """`stop`: the task ends here (the controller halts the program)."""

    uid: int
    span: Span | None = _span_field()


Instr = Union[Move, SetDigital, SetAnalog, Pulse, WaitTime, WaitInput, If, Sync, Native, ProcCall, Attach, Detach,
              VarDecl, Assign, Loop, While, WaitCondition, Stop]


@record(slots=True)
class Task:
    """One robot's instruction list (a single-robot `program ... on r1` has one task)."""

    name: str
    robot: str
    body: tuple[Instr, ...]
    span: Span | None = _span_field()


@record(slots=True)
class Program:
    name: str
    cell: Cell
    tasks: tuple[Task, ...]
    span: Span | None = _span_field()


def payload_cog(tcp: Pose) -> tuple[float, float, float]:
    """A tool's centre of gravity in the flange frame (m), given its TCP (in the flange frame):
    half way along the flange->TCP vector, rmot's one payload convention (a gripper's mass
    sits between flange and fingers). Used by the verification's torque check and by every
    backend that writes a payload."""
    x, y, z = tcp.position
    return (0.5 * x, 0.5 * y, 0.5 * z)
