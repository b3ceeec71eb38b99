"""The neutral document a vendor reader produces: what a program does, in rmot's terms.

Every reader (RAPID, KRL, URScript, ...) turns its files into one `Document`: the targets,
tools, frames and routines it declares, each statement located at its vendor file's line.
`writer.py` prints a Document as .rmot text; `diff.py` compares two Documents. Lengths are
millimetres, angles degrees, times seconds, speeds mm/s (as the vendors print them); poses
are `ir.Pose` (metres and a w-first quaternion, the IR's own form).
"""

from __future__ import annotations

from collections.abc import Callable

from rmot.lang import ir
from rmot.lang.diagnostics import Diagnostic
from rmot.lang.record import record

__all__ = [
    "Where", "Target", "ToolData", "FrameData", "Move", "SetOut", "Pulse", "Wait", "WaitIn",
    "Cond", "Conds", "leaves", "If", "While", "For", "Call", "Native", "Stop", "Grip", "Stmt", "Routine", "FileCount",
    "Document", "Signal", "walk",
]
__all__ += ["VarDecl", "Assign"]
__all__ += ["Sync"]
__all__ += ["PulsePose", "NamedLoad"]

# the TCP pose (in the arm's base) of joints in degrees with a named tool, or None where the
# tool is not known: what a caller that loaded the arm gives a reader of joint-only positions
PulsePose = Callable[[tuple[float, ...], str], "ir.Pose | None"]

# a signal by its controller name (RAPID, INFORM names) or by its port number (KRL, TP, UR)
Signal = str | int


@record(slots=True)
class Where:
    """A place in a vendor file (1-based line and column)."""

    path: str
    line: int
    col: int = 1

    def __str__(self) -> str:
        return f"{self.path}:{self.line}:{self.col}"


@record(slots=True)
class Target:
    """A declared target: a pose in its frame or joint values (degrees), with its branch."""

    name: str
    pose: ir.Pose | None
    joints: tuple[float, ...] | None
    config: ir.Config | None
    where: Where
    rconf: str | None = None  # an INFORM position's RCONF as written (resolved with the arm: inform_conf)
    # the external-axis values the vendor writes beside the target, slot by slot (RAPID eax_a..,
    # KRL E1.., TP E1/GP2 J1..) in mm or deg, None where the slot is unused (readers/axes.py)
    slots: tuple[float | None, ...] = ()


@record(slots=True)
class ToolData:
    name: str
    tcp: ir.Pose  # in the flange frame
    mass: float  # kg
    where: Where
    controller: str = ""  # used but not set in the files: the controller's own (`UTOOL[1]`); identity here
    number: int | None = None  # that controller's number of it: the stub cell gives it (`number n`)


@record(slots=True)
class FrameData:
    name: str
    pose: ir.Pose  # in the robot base
    where: Where
    controller: str = ""  # used but not set in the files: the controller's own (`UFRAME[1]`); identity here
    number: int | None = None  # that controller's number of it: the stub cell gives it (`number n`)


@record(slots=True)
class Move:
    """One motion. `target` is the rmot expression of the target (a name, `shift(...)`,
    `pose(...)`, `joints(...) deg`); `target_name` the declared target it refers to."""

    kind: str  # "joint", "linear" or "circular"
    target: str
    target_name: str | None
    where: Where
    via: str | None = None
    speed: float | None = None  # mm/s, linear and circular moves
    joint_pct: float | None = None  # % of each joint's max speed, joint moves
    zone: float | None = None  # mm; None = fine (exact stop)
    time: float | None = None  # s, a move of fixed duration
    tool: str | None = None  # None = keep the active one
    frame: str | None = None  # None = keep; "base" = the robot base
    config: ir.Config | None = None
    pose: ir.Pose | None = None  # the resolved target where known (for diff)
    joints: tuple[float, ...] | None = None
    accel: float | None = None  # mm/s^2, linear and circular moves; None = the controller's own
    joint_accel: float | None = None  # % of each joint's max acceleration (joint moves; TP ACC on any move)
    slots: tuple[float | None, ...] = ()  # the target's external-axis slot values as written (Target.slots)
    # the axis values in rmot, per mechanism: (name, `600mm` or `(0deg, 90deg)`), set by
    # readers/axes.py from `slots` and the cell; printed as `ext(name=value, ...)`
    ext: tuple[tuple[str, str], ...] = ()
    slot_pulses: tuple[bool, ...] = ()  # per slot: encoder pulses (an INFORM BC/EC under ///PULSE), not mm or deg
    via_slots: tuple[float | None, ...] = ()  # a circular via's own slot values where the vendor writes them (INFORM)
    # URScript `get_inverse_kin(P, qnear=Q)`: (Q as written, Q's joints in deg where known here);
    # the controller goes to the solution of P nearest Q (readers/urscript_qnear.py)
    near: tuple[str, tuple[float, ...] | None] | None = None
    axes_only: bool = False  # `move axes`: the mechanisms alone (RAPID MoveExtJ), `time` its duration
    # the statement as the reader would keep it native (every line of it: a RAPID statement over
    # several lines, a KRL inline form's header, an INFORM arc's MOVC lines), for a later stage
    # that keeps the move native (readers/axes.py); "" where the reader did not record it
    source: str = ""


@record(slots=True)
class SetOut:
    signal: Signal
    value: float  # 0/1 for digital outputs, volts for analog
    where: Where
    analog: bool = False


@record(slots=True)
class Pulse:
    signal: Signal
    seconds: float
    where: Where


@record(slots=True)
class Wait:
    seconds: float
    where: Where


@record(slots=True)
class Cond:
    """A digital input at a level: the condition every vendor's IF/WAIT reads; with `output`,
    the state of the controller's own digital output at that level (`out[n] == on`)."""

    signal: Signal
    on: bool
    output: bool = False

    def negated(self) -> Cond:
        """The same signal tested at the other level."""
        return Cond(self.signal, not self.on, self.output)


@record(slots=True)
class GroupIn:
    """A group input read as one unsigned integer (`gin[n]`): a part of a "logic" Conds."""

    signal: Signal


@record(slots=True)
class Conds:
    """Input conditions combined: `op` "and"/"or" over two or more parts, or "not" over one; or
    `op` "expr": a test the compiler decides, `text` in rmot (a proc parameter's `k == 3`), no parts;
    or `op` "logic": a runtime expression over task variables and inputs, `text` in rmot with
    `{0}`, `{1}`, ... where the input conditions `parts` are written (logic.py)."""

    op: str
    parts: tuple[Cond | Conds | GroupIn, ...]
    text: str = ""


def leaves(c: Cond | Conds | GroupIn) -> list[Cond]:
    """The input conditions a condition reads, left to right."""
    if isinstance(c, GroupIn):
        return []
    return [c] if isinstance(c, Cond) else [leaf for part in c.parts for leaf in leaves(part)]


def group_reads(c: Cond | Conds | GroupIn) -> list[GroupIn]:
    """The group inputs a condition or a value reads, left to right."""
    if isinstance(c, Cond):
        return []
    return [c] if isinstance(c, GroupIn) else [g for part in c.parts for g in group_reads(part)]


@record(slots=True)
class WaitIn:
    cond: Cond | Conds
    timeout: float | None
    where: Where
    orelse: tuple[Stmt, ...] = ()  # what runs when the timeout passes first (`timeout T else { }`)


@record(slots=True)
class If:
    cond: Cond | Conds
    then: tuple[Stmt, ...]
    orelse: tuple[Stmt, ...]
    where: Where


@record(slots=True)
class While:
    cond: Cond | Conds
    body: tuple[Stmt, ...]
    where: Where


@record(slots=True)
class For:
    """`for var in first .. stop` (half open, as rmot writes it)."""

    var: str
    first: int
    stop: int
    body: tuple[Stmt, ...]
    where: Where


@record(slots=True)
class Call:
    name: str
    args: tuple[str, ...]  # rmot expressions
    where: Where
    # the settings in force at the call, for the callee's moves that set none of their own (KRL's
    # $VEL/$ACC and URScript's TCP are the controller's: a routine's motions run with its caller's)
    tool: str | None = None
    speed: float | None = None  # mm/s
    joint_pct: float | None = None
    accel: float | None = None  # mm/s^2
    joint_accel: float | None = None


@record(slots=True)
class Native:
    """Vendor text kept as it is (one `native` statement per source line)."""

    vendor: str
    text: str
    where: Where


@record(slots=True)
class Stop:
    where: Where


@record(slots=True)
class Grip:
    """`attach part` (take=True) or `detach part`: a vendor payload switch matched to a part of
    the cell (payload.py)."""

    part: str
    take: bool
    where: Where


@record(slots=True)
class VarDecl:
    """`var name: type = init`: a task variable (type "int", "num" or "bool"), `init` an expression
    (op "logic", logic.py) the reader checked has that type."""

    name: str
    type: str
    init: Conds
    where: Where


@record(slots=True)
class Assign:
    """`name = value` on a task variable."""

    name: str
    value: Conds
    where: Where


@record(slots=True)
class Sync:
    """`sync name`: a barrier of a multi-robot program (RAPID WaitSyncTask, or the I/O handshake
    the other vendors' backends write), recognised across the tasks' files (tasks.py)."""

    name: str
    where: Where


Stmt = Move | SetOut | Pulse | Wait | WaitIn | If | While | For | Call | Native | Stop | Grip | VarDecl | Assign | Sync


def walk(body: tuple[Stmt, ...]) -> list[Stmt]:
    """Every statement of `body` in source order, the statements of blocks after their block."""
    out: list[Stmt] = []
    for s in body:
        out.append(s)
        if isinstance(s, If):
            out += walk(s.then) + walk(s.orelse)
        elif isinstance(s, (While, For)):
            out += walk(s.body)
        elif isinstance(s, WaitIn):
            out += walk(s.orelse)
    return out


@record(slots=True)
class Routine:
    name: str
    params: tuple[tuple[str, str], ...]  # (name, rmot type)
    body: tuple[Stmt, ...]
    where: Where


@record(slots=True)
class FileCount:
    """How many instruction lines of a file were imported and how many kept native."""

    path: str
    imported: int
    native: int


# a named load: (name, mass kg, centre of mass mm in the flange frame, NaN where the controller
# holds it; where it is declared)
NamedLoad = tuple[str, float, tuple[float, float, float], Where]


@record(slots=True)
class Document:
    vendor: str
    name: str  # the program's name (module, DEF, job)
    main: str  # the routine that runs
    targets: tuple[Target, ...]
    tools: tuple[ToolData, ...]
    frames: tuple[FrameData, ...]
    routines: tuple[Routine, ...]
    consts: tuple[tuple[str, float], ...]
    counts: tuple[FileCount, ...]
    diagnostics: tuple[Diagnostic, ...]
    kept: tuple[Native, ...] = ()  # declarations and routines with no rmot form, as comments
    loads: tuple[NamedLoad, ...] = ()  # named loads the files declare (KRL LOAD data, TP payload schedules)
    mechanisms: tuple[str, ...] = ()  # the cell's track and positioners the program drives (`with`)
    records: tuple[Native, ...] = ()  # TP position records a native line may move to (position_records)
