"""Why a KRL motion stays native: the precise reason, for the import's W510 warning.

A motion is read only where its target, speed and approximation are certain from the program and
its data lists. Where one is not, the reason names it: a position the program assigns (KSS 8.x
Operating and Programming Instructions for System Integrators: a data object holds its data-list
value only until a statement assigns it), one declared without a value or in no data list found
(of other modules' data lists, only the GLOBAL declarations of public ones in the program's folder
are read), an index computed at run time, `$POS_ACT` (the robot's current position, read when the
line runs), an approximation whose system variable no line before sets, or an inline form whose
velocity is a variable or whose motion data set is declared nowhere the import sees.
"""

from __future__ import annotations

import re
from collections.abc import Collection, Iterator, Mapping

from rmot.backends.readers import codes
from rmot.backends.readers.common import Tally, split_top
from rmot.backends.readers.krl_text import Line, MotionState
from rmot.backends.readers.model import Call, Move, Stmt, Where

__all__ = ["Names", "motion_why", "inline_why", "mode_why", "other_why", "UnreadCalls"]

Names = tuple[Collection[str], Collection[str], Collection[str], Mapping[str, object]]
"""(positions read, names the program assigns, names declared anywhere seen, data lists' NAME ->
declaration), all upper case."""


def _point_why(point: str, names: Names) -> str | None:
    """Why one target is not read, None when nothing certain can be said of it."""
    targets, assigned, declared, data = names
    text = re.sub(r"\s+", "", point).upper()
    if text in ("$POS_ACT", "$AXIS_ACT"):
        return f"`{point.strip()}` is where the robot stands when the line runs: known only at run time"
    m = re.fullmatch(r"([A-Z_]\w*)(?:\[(\w+)\])?", text)
    if m is None or text in targets:
        return None
    base = m.group(1)
    if base in assigned:
        how = assigned.get(base) if isinstance(assigned, Mapping) else None
        if how:  # the line that made its value one known only at run time (krl_flow.py)
            return f"`{point.strip()}` is {how}"
        return f"`{point.strip()}` is assigned in the program: its value is known only at run time"
    if m.group(2) is not None and not m.group(2).isdigit():
        return f"`{point.strip()}` is chosen by an index known only at run time"
    if text not in data and (base in declared or base in data):
        return f"`{point.strip()}` is declared without a value: it is set at run time"
    if text not in data:
        return (f"`{point.strip()}` is declared in neither the program's .dat nor a $config.dat found, nor GLOBAL "
                "in a public data list (DEFDAT .. PUBLIC) of its folder")
    return None


def motion_why(rest: str, names: Names, state: MotionState) -> str | None:
    """Why `PTP|LIN|CIRC rest` was not read (None: no more precise reason than "no rmot form")."""
    with_ = re.match(r"(?is)(.*?)\s+WITH\b", rest)
    if with_ is not None:  # the settings after WITH are the reader's; only the point is told here
        return _point_why(split_top(with_.group(1), ":")[0], names)
    m = re.fullmatch(r"(?is)(.*?)\s*(C_PTP\s+C_DIS|C_DIS\s+C_DIS|C_PTP|C_DIS|C_VEL|C_ORI|C_SPL)?", rest.strip())
    if m is None:
        return None
    for point in split_top(m.group(1)):
        why = _point_why(split_top(point, ":")[0], names)
        if why is not None:
            return why
    approx = (m.group(2) or "").upper().split()
    if approx[:1] == ["C_PTP"] and len(approx) == 1 and state.cptp is None:
        return "C_PTP blends by $APO.CPTP, which no line before it sets (a routine or the run time does)"
    if "C_DIS" in approx and state.cdis is None:
        return "C_DIS blends by $APO.CDIS, which no line before it sets (a routine or the run time does)"
    return None


def inline_why(header: str, names: Names, data_lists: Collection[str]) -> str | None:
    """Why the inline form `PTP P1 CONT Vel=100 % PDAT1 ..` (its header after the motion's name)
    was not read; the form's point P1 is XP1 and its motion data PPDAT1/LCPDAT1 in a data list."""
    m = re.match(r"(?i)(\w+)(?:\s+(\w+))?\s+(CONT\s+)?Vel\s*=\s*(\S+?)\s*(%|m/s|mm/s)\s+(\w+)", header)
    if m is None:
        return None
    if re.fullmatch(r"[\d.]+", m.group(4)) is None:
        return f"its velocity `{m.group(4)}` is a variable: known only at run time"
    second = m.group(2) if m.group(2) and m.group(2).upper() != "CONT" else None
    for point in [m.group(1)] + ([second] if second else []):
        if point.upper() not in names[0] and ("X" + point).upper() not in names[0]:
            why = _point_why(point if point[:1] in "xX" else "X" + point, names)
            if why is not None:
                return f"its point {why}"
    cont = m.group(3) is not None or (m.group(2) or "").upper() == "CONT"
    motion_data = m.group(6).upper()
    if cont and not {motion_data, "P" + motion_data, "L" + motion_data} & set(data_lists):
        return f"its motion data `{m.group(6)}` (the CONT's APO_DIST) is declared in no data list found"
    return None


# the controller's operating mode (KSS 8.x System Integrators, system variables: $T1, $T2, $AUT,
# $EXT are TRUE in that mode; $MODE_OP is #T1, #T2, #AUT or #EX): a pendant switch, not a signal
_MODE = re.compile(r"(?i)\$(?:T1|T2|AUT|EXT|MODE_OP)\b")


def mode_why(word: str, text: str) -> str | None:
    """Why the block `IF|WHILE cond` (or `WAIT FOR cond`) stays native when its condition reads the
    operating mode or an output switched with the motion ($OUT_C[n]: set at the motion's
    start point; rmot reads the output's state, out[n], which is $OUT[n])."""
    if re.search(r"(?i)\$OUT_C\s*\[", text) and _MODE.search(text) is None:
        return f"this {word} tests an output switched with the motion ($OUT_C[n]); rmot reads $OUT[n] only"
    if _MODE.search(text) is None:
        return None
    return f"this {word} tests the operating mode ($T1, $T2, $AUT, $EXT, $MODE_OP): a pendant setting known only at run time"


def other_why(word: str, text: str, started: bool) -> str | None:
    """Why a WAIT or a relative motion stays native; `started`: whether the last move's target is
    known here (where LIN_REL/PTP_REL start, KSS 8.x relative motions)."""
    if word in ("LIN_REL", "PTP_REL") and not started:
        return ("a relative motion starts where the last motion ended, not known here (the start of a block, "
                "or after a motion not read)")
    wait = re.fullmatch(r"(?i)WAIT\s+SEC\s+(.+)", text.strip())
    if wait is not None and re.fullmatch(r"[\d.]+", wait.group(1).strip()) is None:
        return f"the time `{wait.group(1).strip()}` is a variable: known only at run time"
    return mode_why(word, text) if word == "WAIT" else None

# a line that changes the motion settings later motions use: an assignment to $VEL, $ACC, $APO,
# $TOOL or $BASE (or a member of one), or BAS(..), which the inline forms' folds call to set them
# (KSS 8.x System Integrators, system variables; BAS.SRC)
_SETS_MOTION = re.compile(r"(?i)\s*(?:\$(?:VEL|ACC|APO|TOOL|BASE)(?:_\w+)?\b[^=]*=(?!=)|BAS\s*\()")
_MOTION = re.compile(r"(?i)\s*S?(?:PTP|LIN|CIRC)\b")


def _by_routine(lines: list[Line]) -> Iterator[tuple[str, Line]]:
    """(the routine's upper-case name, line) for each line inside a DEF."""
    routine: str | None = None
    for ln in lines:
        head = re.match(r"(?i)\s*(?:GLOBAL\s+)?DEF\s+(\w+)\s*\(", ln.text)
        if head is not None:
            routine = head.group(1).upper()
        elif routine is not None:
            yield routine, ln


def routines_setting_motion(lines: list[Line]) -> frozenset[str]:
    """The routines (upper-case names) of a module with a line that changes the motion settings."""
    return frozenset(routine for routine, ln in _by_routine(lines) if _SETS_MOTION.match(ln.text))


def routines_inheriting_motion(lines: list[Line]) -> frozenset[str]:
    """The routines (upper-case names) of a module with a motion before any line that changes the
    motion settings: it runs with its caller's."""
    first: dict[str, bool] = {}  # routine -> whether its first setting or motion line is a motion
    for routine, ln in _by_routine(lines):
        if routine not in first and (_SETS_MOTION.match(ln.text) or _MOTION.match(ln.text)):
            first[routine] = _SETS_MOTION.match(ln.text) is None
    return frozenset(routine for routine, motion in first.items() if motion)


class UnreadCalls:
    """The calls after which the motion settings may not be the ones read before. $VEL, $APO,
    $TOOL and $BASE are global (KSS 8.x System Integrators, system variables), so a routine's
    settings hold after it returns, while an rmot proc's settings end with the proc: after a
    call of a read routine that changes them, each is known only at run time
    (MotionState.set_by_call); after a call of a routine the import does not read (kept native)
    the first motion read gets W527, once per routine."""

    def __init__(self, tally: Tally, lines: list[Line]) -> None:
        self.tally = tally
        self.setters = routines_setting_motion(lines)  # read routines that change the settings
        self.inheriting = routines_inheriting_motion(lines)  # routines with a motion that reads its caller's
        self.pending: tuple[str, Where] | None = None  # the last unread call since the last motion read
        self.warned: set[str] = set()

    def at_call(self, text: str, state: MotionState) -> dict[str, float | None] | None:
        """The settings a call carries where its routine runs motions with its caller's
        (MotionState.at_call; none for another routine), None where one of them is known only
        at run time here (`why_call`)."""
        if not self._inherits(text):
            return {}
        return None if self.why_call(text, state) else state.at_call()

    def why_call(self, text: str, state: MotionState) -> str | None:
        """Why a call of a routine that runs motions with its caller's settings cannot be read:
        one of them is unsure here."""
        return state.unsure_of(False, text) or state.unsure_of(True, text) if self._inherits(text) else None

    def _inherits(self, text: str) -> bool:
        m = re.fullmatch(r"(\w+)\s*\(.*\)", text)
        return m is not None and m.group(1).upper() in self.inheriting

    def called(self, text: str, where: Where, state: MotionState) -> None:
        """A line kept native: a call when it is `name(..)` (its routine may write any setting)."""
        m = re.fullmatch(r"(\w+)\s*\(.*\)", text)
        if m is not None:
            self.pending = (m.group(1), where)
            state.forget_written()

    def moved(self, stmt: Stmt, state: MotionState) -> None:
        """A statement read: after a call of a setter its settings are unsure; W527 when it is a
        motion after a pending call of a routine not read and not yet named."""
        if isinstance(stmt, Call) and stmt.name.upper() in self.setters:
            state.set_by_call(stmt.name, stmt.where)
        if isinstance(stmt, Move):
            state.wrote()
        if not isinstance(stmt, Move) or self.pending is None:
            return
        name, at = self.pending
        self.pending = None
        if name.upper() in self.warned:
            return
        self.warned.add(name.upper())
        self.tally.warn(codes.SETTINGS_AFTER_CALL, f"this motion is read with the speed, approximation, tool and base "
                        f"set before `{name}(..)` at line {at.line}, a routine the import does not read: check that "
                        "it leaves $VEL, $APO, $TOOL and $BASE as they were", stmt.where)
