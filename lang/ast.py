"""The .rmot abstract syntax tree: frozen dataclasses, one per construct.

Every node has a `span` (where it came from) excluded from equality, so two parses of the
same text compare equal whatever their layout. Values stay as written (numbers with their
unit text); the compiler checks dimensions and converts to SI.

Node families:
  Expr  — Number, Name, Call, Joints, Vector, String, BinOp, Neg, Attr (Arg for arguments)
  Stmt  — file level (UseCell, Import, CellDecl, ProgramDecl, TaskDecl), cell declarations
          (RobotDecl, FixtureDecl, ToolDecl, FrameDecl, IoDecl), program declarations
          (TargetDecl, ConstDecl, ProcDecl), settings (Setting), Move, SetIo, Pulse,
          WaitTime, WaitUntil, For, Repeat, IfStmt, SyncStmt, NativeStmt, CallStmt
  Module — the statements of one file
"""

from __future__ import annotations

from dataclasses import field
from enum import StrEnum
from typing import Union

from rmot.lang.record import record
from rmot.lang.source import SourceFile, Span

__all__ = [
    "Arg", "Attr", "BinOp", "Call", "CallStmt", "CellDecl", "Condition", "ConstDecl", "Expr",
    "FixtureDecl", "For", "FrameDecl", "Geometry", "Ident", "IfStmt", "Import", "IoDecl",
    "IoRef", "Joints", "Modifier", "Module", "Move", "Name", "NativeStmt", "Neg", "Number",
    "Param", "ProcDecl", "ProgramDecl", "Pulse", "Repeat", "RobotDecl", "SetIo", "Setting",
    "Stmt", "String", "SyncStmt", "TargetDecl", "TaskDecl", "ToolDecl", "UseCell", "Vector",
    "WaitTime", "WaitUntil",
    "PartDecl", "AttachStmt", "SettingKind", "FeederDecl",
]


def _span() -> Span:
    return field(compare=False, hash=False, repr=False)  # type: ignore[no-any-return]


@record(slots=True)
class Ident:
    """A name as written where something is declared or referred to by name (not an Expr)."""

    name: str
    span: Span = _span()


# --------------------------------------------------------------------------- expressions


@record(slots=True)
class Number:
    value: float
    unit: str | None  # as written: "mm", "deg/s", "%"; None for a bare number
    span: Span = _span()


@record(slots=True)
class Name:
    name: str
    span: Span = _span()


@record(slots=True)
class Arg:
    """A call argument, positional (name None) or keyword (`x=10mm`)."""

    name: Ident | None
    value: Expr
    span: Span = _span()


@record(slots=True)
class Call:
    func: Ident
    args: tuple[Arg, ...]
    span: Span = _span()


@record(slots=True)
class Joints:
    """`joints(0, -90, 90, 0, 90, 0) deg`: `unit` applies to the values written without one."""

    args: tuple[Arg, ...]
    unit: str | None
    span: Span = _span()


@record(slots=True)
class Vector:
    """`(a, b, ...)`, and `(30, 90) deg`: `unit` applies to the items written without one."""

    items: tuple[Arg, ...]
    unit: str | None
    span: Span = _span()


@record(slots=True)
class String:
    value: str
    span: Span = _span()


@record(slots=True)
class BinOp:
    op: str  # one of + - * /
    left: Expr
    right: Expr
    span: Span = _span()


@record(slots=True)
class Neg:
    operand: Expr
    span: Span = _span()


@record(slots=True)
class Attr:
    """Component access: `p.x`, `p.rz`."""

    obj: Expr
    name: Ident
    span: Span = _span()


Expr = Union[Number, Name, Call, Joints, Vector, String, BinOp, Neg, Attr]


# --------------------------------------------------------------------------- statements


@record(slots=True)
class UseCell:
    path: String
    span: Span = _span()


@record(slots=True)
class Import:
    path: String
    span: Span = _span()


@record(slots=True)
class CellDecl:
    name: Ident
    body: tuple[Stmt, ...]
    span: Span = _span()


@record(slots=True)
class ProgramDecl:
    name: Ident
    robot: Ident | None  # `program p on r1`
    body: tuple[Stmt, ...]
    span: Span = _span()
    axes: tuple[Ident, ...] = ()  # `program p on r1 with rail, pos`: the mechanisms it drives


@record(slots=True)
class TaskDecl:
    robot: Ident
    body: tuple[Stmt, ...]
    span: Span = _span()


@record(slots=True)
class RobotDecl:
    name: Ident
    library: Ident | None  # a library name, or None for a URDF
    urdf: String | None
    at: Expr | None
    span: Span = _span()
    urdf_args: tuple[Arg, ...] = ()  # `urdf("f.urdf", base="base_link", tip="tool0")`
    shares: tuple[Setting, ...] = ()  # `speed R %` / `accel R %`: the arm's limits scaled
    software: tuple[Ident, Expr] | None = None  # `controller kss 8.3`: the controller's software
    on: Ident | None = None  # `on rail`: the track whose carriage carries it (`at` is then on the carriage)


@record(slots=True)
class Geometry:
    """`box(...)`, `cylinder(...)`, `sphere(...)`, `capsule(...)`, `mesh(...)`, checked later."""

    kind: Ident
    args: tuple[Arg, ...]
    span: Span = _span()


@record(slots=True)
class FixtureDecl:
    name: Ident
    geometry: Geometry
    at: Expr | None
    span: Span = _span()
    on: Ident | None = None  # `on pos`: the mechanism that carries it (`at` is then on its flange)


@record(slots=True)
class ToolDecl:
    name: Ident
    geometry: Geometry | None  # None: `tool t = none ...`
    at: Expr | None  # where the geometry sits in the flange frame
    tcp: Expr | None
    mass: Expr | None
    robot: Ident
    span: Span = _span()
    number: Expr | None = None  # `number n`: the controller's tool number


@record(slots=True)
class FrameDecl:
    name: Ident
    value: Expr
    span: Span = _span()
    number: Expr | None = None  # `number n`: the controller's frame number


@record(slots=True)
class IoRef:
    kind: str  # in | out | ain | aout | gin
    index: Expr
    span: Span = _span()


@record(slots=True)
class IoDecl:
    io: IoRef
    signal: String
    robot: Ident | None
    span: Span = _span()
    bits: Expr | None = None  # `bits B`: a group input's width (gin[n] reads 0..2^B-1)


@record(slots=True)
class TargetDecl:
    name: Ident
    value: Expr
    span: Span = _span()


@record(slots=True)
class ConstDecl:
    name: Ident
    value: Expr
    span: Span = _span()


@record(slots=True)
class Param:
    name: Ident
    type: Ident
    span: Span = _span()


@record(slots=True)
class ProcDecl:
    name: Ident
    params: tuple[Param, ...]
    body: tuple[Stmt, ...]
    span: Span = _span()


class SettingKind(StrEnum):
    """What a Setting sets: the keyword as written (a str, so `kind == "tool"` holds).

    Modal settings and move modifiers: tool, frame, speed, joint_speed, accel, zone; move
    modifiers only: config, time; options of a `move free` only: clearance, samples, budget;
    lines of a `model` block: torque, mass, flange, payload, controller.
    Each consumer keeps a table with an entry for every kind, checked when it is imported
    (compiler/passes/modal.SETTING_HANDLERS)."""

    TOOL = "tool"
    FRAME = "frame"
    SPEED = "speed"
    JOINT_SPEED = "joint_speed"
    ACCEL = "accel"
    ZONE = "zone"
    CONFIG = "config"
    TIME = "time"
    TORQUE = "torque"
    MASS = "mass"
    FLANGE = "flange"
    PAYLOAD = "payload"
    CONTROLLER = "controller"
    CLEARANCE = "clearance"
    SAMPLES = "samples"
    BUDGET = "budget"
    EXT = "ext"  # a move modifier: external-axis values at the target, `ext(rail=1200mm)`


@record(slots=True)
class Setting:
    """A modal setting or a per-move modifier (or a line of a `model` block).

    `value` is an Ident for tool/frame, None for `zone fine`, the argument tuple for config,
    else an Expr.
    """

    kind: SettingKind
    value: Expr | Ident | tuple[Arg, ...] | None
    span: Span = _span()


Modifier = Setting


@record(slots=True)
class Move:
    kind: str  # joint | linear | circular | free
    target: Expr
    via: Expr | None
    modifiers: tuple[Setting, ...]
    span: Span = _span()


@record(slots=True)
class SetIo:
    io: IoRef
    value: Expr
    span: Span = _span()


@record(slots=True)
class Pulse:
    io: IoRef
    duration: Expr
    span: Span = _span()


@record(slots=True)
class WaitTime:
    duration: Expr
    span: Span = _span()


@record(slots=True)
class Condition:
    io: IoRef
    op: str  # == or != ; a bare `in[2]` is `in[2] == on`
    value: Expr | None
    span: Span = _span()


@record(slots=True)
class WaitUntil:
    condition: Condition | RtCond
    timeout: Expr | None
    span: Span = _span()
    on_timeout: tuple[Stmt, ...] | None = None  # `timeout T else { ... }`


@record(slots=True)
class For:
    var: Ident
    start: Expr
    stop: Expr | None  # None: `for i in n { }`, written without `a .. b` (an error, E155)
    body: tuple[Stmt, ...]
    span: Span = _span()


@record(slots=True)
class Repeat:
    count: Expr
    body: tuple[Stmt, ...]
    span: Span = _span()


@record(slots=True)
class IfStmt:
    condition: Condition | RtCond
    then: tuple[Stmt, ...]
    otherwise: tuple[Stmt, ...]
    span: Span = _span()


@record(slots=True)
class SyncStmt:
    name: Ident
    span: Span = _span()


@record(slots=True)
class NativeStmt:
    vendor: Ident
    text: String
    span: Span = _span()


@record(slots=True)
class CallStmt:
    name: Ident
    args: tuple[Arg, ...]
    span: Span = _span()


@record(slots=True)
class PartDecl:
    """`part NAME = GEOMETRY [at POSE] [mass M]`: a movable object of the cell."""

    name: Ident
    geometry: Geometry
    at: Expr | None
    mass: Expr | None
    span: Span = _span()


@record(slots=True)
class AttachStmt:
    """`attach NAME` (attach=True) or `detach NAME` (attach=False)."""

    part: Ident
    attach: bool
    span: Span = _span()


@record(slots=True)
class FeederDecl:
    """`feeder NAME = GEOMETRY [at POSE] [mass M] [count N]`: a source of parts of one solid,
    presenting a fresh one at its pose whenever the last one has been taken (N in all, or
    without end)."""

    name: Ident
    geometry: Geometry
    at: Expr | None
    mass: Expr | None
    count: Expr | None
    span: Span = _span()


Stmt = Union[
    UseCell, Import, CellDecl, ProgramDecl, TaskDecl, RobotDecl, FixtureDecl, ToolDecl,
    FrameDecl, IoDecl, TargetDecl, ConstDecl, ProcDecl, Setting, Move, SetIo, Pulse, WaitTime,
    WaitUntil, For, Repeat, IfStmt, SyncStmt, NativeStmt, CallStmt, PartDecl, AttachStmt, FeederDecl,
]


@record(slots=True)
class Module:
    """The statements of one file, in source order."""

    file: SourceFile
    body: tuple[Stmt, ...]


# --------------------------------------------------------------------------- robot models


@record(slots=True)
class ModelJoint:
    """`joint revolute dh(...) range(...) speed ... accel ...`: `parts` are the Calls
    (dh/mdh/range) and Settings (speed/accel) as written, checked by the compiler."""

    kind: Ident  # revolute | prismatic as written (checked later)
    parts: tuple[Call | Setting, ...]
    span: Span = _span()


@record(slots=True)
class ModelDecl:
    """`model NAME { joint ... ; flange pose(...) ; payload 5 kg }` in a cell.

    items: ModelJoint lines and Settings of kind flange / payload / controller (an Ident),
    in source order."""

    name: Ident
    items: tuple[ModelJoint | Setting, ...]
    span: Span = _span()


__all__ += ["ModelDecl", "ModelJoint"]
Stmt = Union[Stmt, ModelDecl]  # type: ignore[misc]


# ------------------------------------------------------------------ runtime logic


@record(slots=True)
class Compare:
    """`left op right` in a condition, op one of == != < <= > >= (an I/O read may be `left`)."""

    op: str
    left: Expr | IoRef
    right: Expr
    span: Span = _span()


@record(slots=True)
class Logic:
    """`a and b ...` (op "and") or `a or b ...` (op "or"), operands flattened."""

    op: str
    operands: tuple[RtCond, ...]
    span: Span = _span()


@record(slots=True)
class NotCond:
    operand: RtCond
    span: Span = _span()


# What `if`, `while`, `wait until`, `var` and assignments take: an expression, an I/O read
# (`in[1]`, `ain[2]`), a comparison (Condition for `in[n] ==/!= level`), and/or/not.
RtCond = Union[Expr, IoRef, Condition, Compare, Logic, NotCond]


@record(slots=True)
class VarDecl:
    """`var NAME[: int|num|bool] = EXPR`: a task variable (runtime state)."""

    name: Ident
    type: Ident | None
    value: RtCond
    span: Span = _span()


@record(slots=True)
class AssignStmt:
    name: Ident
    value: RtCond
    span: Span = _span()


@record(slots=True)
class StopStmt:
    span: Span = _span()


@record(slots=True)
class While:
    condition: RtCond | None  # None: `while { }` (an error, E156)
    body: tuple[Stmt, ...]
    span: Span = _span()


__all__ += ["AssignStmt", "Compare", "Logic", "NotCond", "RtCond", "StopStmt", "VarDecl", "While"]
Stmt = Union[Stmt, VarDecl, AssignStmt, StopStmt, While]  # type: ignore[misc]


# --------------------------------------------------------------------------- external axes


@record(slots=True)
class ExtAxisDecl:
    """One axis of a track or positioner: `linear(axis x, range(0mm, 4000mm)) speed V accel A`."""

    kind: Ident  # linear | revolute
    axis: Ident  # x | y | z
    args: tuple[Arg, ...]  # range(lo, hi)
    speed: Expr | None
    accel: Expr | None
    span: Span = _span()
    inform: Call | None = None  # the INFORM binding: `inform(pulses_per_mm=N)` or `inform(pulses_per_deg=N)`
    solids: tuple[Call, ...] = ()  # `solid(box(...), at=POSE)`: solids riding on this axis (in its frame)
    mass: Expr | None = None  # `mass M`: what the axis moves, its solids' mass


@record(slots=True)
class MechanismDecl:
    """`track NAME = linear(...)` or `positioner NAME = axes(revolute(...), ...)`."""

    kind: str  # track | positioner
    name: Ident
    axes: tuple[ExtAxisDecl, ...]
    at: Expr | None
    span: Span = _span()
    on: Ident | None = None  # stacked on this mechanism's flange (`at` is then on that flange)


@record(slots=True)
class MoveAxes:
    """`move axes pos to (0deg, 180deg)`: the mechanism's axes alone; the arm holds its joints."""

    mechanism: Ident
    values: Expr
    modifiers: tuple[Setting, ...]
    span: Span = _span()


__all__ += ["ExtAxisDecl", "MechanismDecl", "MoveAxes"]
Stmt = Union[Stmt, MechanismDecl, MoveAxes]  # type: ignore[misc]
