"""The VAL3 backend's vocabulary: reserved names, the XML attribute formats of a `trsf` and a
`config`, and what printing a task collects (`Val3Context`: names, the application's global
data, each program's code). The backend itself is backends/val3.py.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from rmot.backends.base import TaskContext, euler_xyz_moving_deg, fmt, position_mm
from rmot.backends.loops import LoopTemplate
from rmot.backends.names import NameRules, NameTable
from rmot.lang import ir
from rmot.lang.record import record

__all__ = ["NO_LIMIT", "VAL3_BUILTINS", "VAL3_RULES", "XSI", "Val3Context", "config_attrs", "trsf_attrs"]

# VAL3 instructions, functions, types and keywords a program or datum of the same name would
# hide (Stäubli VAL3 Reference Manual, s7: "Instructions", "Simple types", "Motion control",
# "Input/output", "User interface", "Tasks")
VAL3_BUILTINS = frozenset(name.upper() for name in (
    "movej", "movel", "movec", "stopMove", "resetMotion", "restartMove", "waitEndMove",
    "isEmpty", "isSettled", "autoConnectMove", "getSpeed", "getMoveId", "setMoveId", "delay",
    "wait", "watch", "call", "return", "popUpMsg", "logMsg", "userPage", "title", "cls", "put",
    "putln", "get", "getKey", "aioSet", "aioGet", "aioLink", "dioSet", "dioGet", "dioLink",
    "abs", "sqrt", "sin", "cos", "tan", "asin", "acos", "atan", "min", "max", "limit", "sel",
    "round", "roundUp", "roundDown", "size", "resize", "taskCreate", "taskKill",
    "taskSuspend", "taskResume", "taskStatus", "clock", "enablePower", "disablePower",
    "isPowered", "herej", "here", "appro", "compose", "distance", "interpolateL",
    "interpolateC", "pointToJoint", "jointToPoint", "position", "setFrame", "bool", "num",
    "string", "dio", "aio", "sio", "joint", "trsf", "frame", "tool", "point", "config",
    "mdesc", "screen", "do", "until", "for", "to", "step", "endFor", "endWhile", "switch",
    "case", "default", "break", "endSwitch", "and", "or", "xor", "not", "true", "false",
    "local", "global", "begin", "endIf",
))
VAL3_RULES = NameRules(max_len=15, allowed="A-Za-z0-9_", first="A-Za-z", prefix="p",
                      reserved=frozenset({"BEGIN", "END", "IF", "ELSE", "ENDIF", "WHILE", "CALL",
                                          "RETURN", "START", "STOP", "WORLD", "FLANGE"}) | VAL3_BUILTINS)
XSI = 'xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"'
NO_LIMIT = "9999"


def trsf_attrs(pose: ir.Pose) -> str:
    """`x=".." y=".." z=".." rx=".." ry=".." rz=".."`: mm (3 places), deg (4 places)."""
    x, y, z = position_mm(pose)
    rx, ry, rz = euler_xyz_moving_deg(pose)
    return (f'x="{fmt(x, 3)}" y="{fmt(y, 3)}" z="{fmt(z, 3)}" '
            f'rx="{fmt(rx, 4)}" ry="{fmt(ry, 4)}" rz="{fmt(rz, 4)}"')


def config_attrs(branch: ir.Config) -> str:
    shoulder = "righty" if branch.shoulder is ir.Shoulder.BACK else "lefty"
    elbow = "enegative" if branch.elbow is ir.Elbow.DOWN else "epositive"
    wrist = "wnegative" if branch.wrist is ir.Wrist.FLIP else "wpositive"
    return f'shoulder="{shoulder}" elbow="{elbow}" wrist="{wrist}"'


@dataclass
class _Data:
    """The application's global data, collected while printing (values in first-use order)."""

    points: list[str] = field(default_factory=list)
    joints: list[str] = field(default_factory=list)
    mdescs: list[str] = field(default_factory=list)
    frames: dict[str, str] = field(default_factory=dict)  # VAL3 name -> value attributes
    tools: dict[str, str] = field(default_factory=dict)
    outputs: int = 0  # size of dOut (highest port + 1)
    inputs: int = 0
    analog: int = 0  # size of aOut
    analog_in: int = 0  # size of aIn
    variables: dict[str, tuple[str, str]] = field(default_factory=dict)  # name -> (type, value)

    def index(self, table: list[str], value: str) -> int:
        if value not in table:
            table.append(value)
        return table.index(value)


@record
class Val3Context(TaskContext):
    """One task's context plus what printing it collects: names, routine names, the global
    data, the programs' code, warnings given once."""

    names: NameTable
    routine_of: dict[int, str]
    data: _Data = field(default_factory=_Data)
    programs: dict[str, list[str]] = field(default_factory=dict)  # program name -> code lines
    # runtime logic: each program's locals, the program being printed, the loop
    # counters in scope (IR name -> VAL3 name), nested loop templates, shifts
    locals: dict[str, dict[str, str]] = field(default_factory=dict)
    where: list[str] = field(default_factory=lambda: ["start"])
    scopes: list[dict[str, str]] = field(default_factory=list)
    inner: dict[int, LoopTemplate] = field(default_factory=dict)
    shifts: dict[object, str] = field(default_factory=dict)
    offsets: dict[tuple[int, str], str] = field(default_factory=dict)
    counters: dict[int, str] = field(default_factory=dict)
    loop_programs: dict[object, str] = field(default_factory=dict)  # (program, shifts) -> its own
