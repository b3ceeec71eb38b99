"""Compile-time values and the unit table: every quantity is converted to SI here, once.

A Quantity keeps its dimension as exponents of (length, angle, time, mass, percent) and the
unit text as written (for messages that name both units). A bare number has dimension
zero and `unit` None, so "missing unit" can be told apart from a dimensionless ratio.
"""

from __future__ import annotations

from typing import Union

from rmot.lang import ir
from rmot.lang.record import record
from rmot.lang.source import Span
from rmot.lang.units import UNIT_TABLE

__all__ = [
    "BoolV", "Dim", "DIMENSIONLESS", "JointsV", "LENGTH", "ANGLE", "TIME", "SPEED", "ACCEL",
    "MASS", "RATIO", "ANGULAR_SPEED", "ANGULAR_ACCEL", "article", "PoseV", "Quantity", "StringV", "UNIT_TABLE",
    "Value", "VectorV", "dim_name", "example_unit", "type_name", "fmt_quantity",
]

Dim = tuple[int, int, int, int, int]  # exponents of length, angle, time, mass, percent
DIMENSIONLESS: Dim = (0, 0, 0, 0, 0)
LENGTH: Dim = (1, 0, 0, 0, 0)
ANGLE: Dim = (0, 1, 0, 0, 0)
TIME: Dim = (0, 0, 1, 0, 0)
MASS: Dim = (0, 0, 0, 1, 0)
RATIO: Dim = (0, 0, 0, 0, 1)
SPEED: Dim = (1, 0, -1, 0, 0)
ANGULAR_SPEED: Dim = (0, 1, -1, 0, 0)
ACCEL: Dim = (1, 0, -2, 0, 0)
ANGULAR_ACCEL: Dim = (0, 1, -2, 0, 0)
FORCE: Dim = (1, 0, -2, 1, 0)  # N: a prismatic model joint's force rating
TORQUE: Dim = (2, 0, -2, 1, 0)  # N*m: a revolute model joint's torque rating
__all__ += ["FORCE", "TORQUE"]

# unit as written -> (factor to SI, dimension): the language's one table (lang/units.py)
_DIM_NAMES = {
    DIMENSIONLESS: ("number", "3"), LENGTH: ("length", "150 mm"), ANGLE: ("angle", "90 deg"),
    TIME: ("time", "0.5 s"), MASS: ("mass", "1.2 kg"), RATIO: ("ratio", "50 %"),
    SPEED: ("speed", "250 mm/s"), ANGULAR_SPEED: ("angular speed", "90 deg/s"),
    ACCEL: ("acceleration", "2 m/s^2"), ANGULAR_ACCEL: ("angular acceleration", "180 deg/s^2"),
    FORCE: ("force", "400 N"), TORQUE: ("torque", "120 N*m"),
}


def article(word: str) -> str:
    """'an angle', 'a length'."""
    return f"{'an' if word[:1] in 'aeiou' else 'a'} {word}"


def dim_name(dim: Dim) -> str:
    return _DIM_NAMES.get(dim, ("quantity", ""))[0]


def example_unit(dim: Dim) -> str:
    """'a length such as 150 mm' — how a message names what it wanted."""
    name, example = _DIM_NAMES.get(dim, ("quantity", ""))
    article = "an" if name[0] in "aeiou" else "a"
    return f"{article} {name} such as {example}" if example else f"{article} {name}"


@record(slots=True)
class Quantity:
    value: float  # SI
    dim: Dim
    unit: str | None  # as written (None: a bare number)
    written: float | None = None  # the number as written, for messages

    def shown(self) -> str:
        return fmt_quantity(self)


def fmt_quantity(q: Quantity) -> str:
    if q.unit is None:
        return f"{q.value:g}"
    factor = UNIT_TABLE.get(q.unit, (1.0, q.dim))[0]
    number = q.written if q.written is not None else q.value / factor
    return f"{number:g} {q.unit}"


@record(slots=True)
class PoseV:
    pose: ir.Pose
    name: str | None = None  # the target/frame/fixture it came from


@record(slots=True)
class JointsV:
    values: tuple[Quantity, ...]
    span: Span | None = None  # the joints(...) literal, for count errors
    name: str | None = None


@record(slots=True)
class VectorV:
    items: tuple[Value, ...]


@record(slots=True)
class BoolV:
    value: bool


@record(slots=True)
class StringV:
    value: str


Value = Union[Quantity, PoseV, JointsV, VectorV, BoolV, StringV]


def type_name(v: Value) -> str:
    if isinstance(v, Quantity):
        return dim_name(v.dim) if v.unit is not None or v.dim != DIMENSIONLESS else "number"
    return {PoseV: "pose", JointsV: "joints() value", VectorV: "vector", BoolV: "on/off value", StringV: "string"}[type(v)]
