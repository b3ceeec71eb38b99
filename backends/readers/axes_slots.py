"""The external-axis values of vendor lines, as the readers call them while reading (RAPID
extax, KRL E1..E6 and its external-axis settings, TP E1/GP2 blocks, INFORM BC/EC operands), and
why a line of external axes stays native. A leaf module: the vendor readers import it, and
readers/axes.py, which maps the values to the cell's axes (`resolve_axes`), imports it too.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping

from rmot.backends.readers.krl_text import MotionState, aggregate, krl_pose

__all__ = ["rapid_slots", "robax_read", "krl_slots", "krl_setting", "fanuc_slots", "inform_base_position",
           "inform_operands", "inform_frame", "why_native", "RAPID_UNUSED_FROM", "SLOTS", "ABSURD", "EK_FRAME",
           "COORD_FRAME"]

# RAPID's "no position defined" is 9E9 (the reference's extjoint); anything from 8.9E9 up is it
RAPID_UNUSED_FROM = 8.9e9
SLOTS = 6  # RAPID eax_a..eax_f
# no axis value beyond this is data (mm, deg or encoder pulses: 1000 km, thousands of turns
# even at 1000 pulses/deg); the language bounds an axis' range to +-1000 m or +-100 turns
ABSURD = 1e9


def rapid_slots(lit: object, index: int) -> tuple[float | None, ...] | None:
    """The extax of a robtarget (`index` 3) or jointtarget (1) literal: six numbers, None for
    9E+09; () where the literal has no extax; None where it is not six numbers (not read)."""
    if not isinstance(lit, list) or len(lit) <= index:
        return ()
    extax = lit[index]
    if not (isinstance(extax, list) and len(extax) == SLOTS and all(isinstance(v, float) for v in extax)):
        return None
    return tuple(None if v >= RAPID_UNUSED_FROM else float(v) for v in extax)


def robax_read(lit: list[object]) -> bool:
    """Whether a jointtarget literal is arm joints rmot reads: every robax value a number below
    9E+09 (a MoveExtJ target leaves the arm's six at 9E+09: no joint values, the arm holds) and
    its extax six numbers (rapid_slots)."""
    robax = lit[0] if isinstance(lit[0], list) else []
    return all(isinstance(v, float) and abs(v) < RAPID_UNUSED_FROM for v in robax) and rapid_slots(lit, 1) is not None


def krl_slots(value: Mapping[str, object]) -> tuple[float | None, ...]:
    """E1..E6 of an E6POS or E6AXIS aggregate (None where absent: a POS or AXIS has none; NaN
    where present but no finite number, which resolve_axes refuses)."""
    found = [value.get(f"E{k}") for k in range(1, SLOTS + 1)]
    return tuple(v if isinstance(v, float) else None if v is None else math.nan for v in found)


# the KRL base on an external kinematic the backend writes (ext_axes.py, KSS 8.5 "Configuration
# of Kinematic Systems"): `$BASE=EK(MACHINE_DEF[n].ROOT,MACHINE_DEF[n].MECH_TYPE,{X .., C ..})`
_EK = re.compile(r"(?is)\$BASE\s*=\s*EK\s*\(\s*MACHINE_DEF\[(\d+)\]\.ROOT\s*,\s*MACHINE_DEF\[(\d+)\]\.MECH_TYPE\s*,\s*(\{.*\})\s*\)")
EK_FRAME = "@EK"  # Move.frame of a base on kinematic n until resolve_axes names the cell's frame
# Move.frame of a coordinated move (TP COORD in UFRAME 0, INFORM SMOVL/SMOVC) until resolve_axes
# places it in the frame riding on the positioner
COORD_FRAME = "@COORD"


def krl_setting(state: MotionState, text: str) -> bool:
    """The KRL lines of external axes that set the motions after them: `$VEL_EXTAX[n]=100` and
    `$ACC_EXTAX[n]=100` (each axis at its full speed and acceleration, as rmot moves it; KSS 8.x
    System Variables) and a `$BASE=EK(..)` on kinematic n (True when the line is one of them)."""
    if re.fullmatch(r"(?i)\$(VEL|ACC)_EXTAX\s*\[\s*[1-6]\s*\]\s*=\s*100(?:\.0*)?", text):
        return True
    m = _EK.fullmatch(text)
    agg = aggregate(m.group(3)) if m and m.group(1) == m.group(2) else None
    pose = krl_pose(agg) if agg is not None else None
    if m is None or pose is None:
        return False
    state.frame = f"{EK_FRAME}{m.group(1)}@" + ",".join(repr(v) for v in (*pose.position, *pose.quaternion))
    return True


def fanuc_slots(body: str) -> tuple[float | None, ...]:
    """The external-axis values of a TP position (the text between its braces) in the backend's
    slot order (ext_axes.fanuc_groups): the arm group's extended axes `E1= v mm` first, then
    each further motion group `GP2:`, `GP3:` .. its `J1= v`, `J2= v` in turn; () for none."""
    groups = re.split(r"\bGP(\d)\s*:", body)
    values: list[float | None] = []
    for number, text in zip(groups[1::2], groups[2::2]):
        key = r"E\d" if number == "1" else r"J\d"
        values += [float(v) for v in re.findall(rf"\b{key}\s*=\s*(-?\d+(?:\.\d*)?)", text)]
    return tuple(values)


def inform_base_position(table: dict[str, tuple[tuple[float, ...], bool]], line: str, pulse: bool) -> bool:
    """A `BCnnnnn=v[,v]` or `ECnnnnn=v[,v]` line of a job's //POS (its base or station axes'
    position: encoder pulses under ///PULSE, else mm, backends/inform_axes.py) into `table`;
    True when the line is one."""
    m = re.fullmatch(r"([BE]C)(\d+)\s*=\s*(-?\d+(?:\.\d*)?(?:\s*,\s*-?\d+(?:\.\d*)?)*)", line)
    if m is not None:
        table[f"{m.group(1)}{int(m.group(2))}"] = (tuple(float(v) for v in m.group(3).split(",")), pulse)
    return m is not None or re.match(r"[BE]C\d+\s*=", line) is not None  # a malformed one: no move reads it


def inform_operands(table: Mapping[str, tuple[tuple[float, ...], bool]], rest: str, sync: bool,
                    station_in_group: bool = False) -> tuple[tuple[tuple[float, ...], tuple[bool, ...]] | None, str]:
    """((slot values, each in pulses or not), the operands left) of a move's `BCnnnnn` after its
    position and the station's `+MOVJ ECnnnnn VJ=100.00` at its end (no VJ on a coordinated
    SMOVL/SMOVC: the station is the master), as backends/inform_axes.py writes them. An operand
    naming no position, or a station speed other than 100 %, is left in `rest` (the move is then
    not read: rmot moves every axis at its own full speed). `station_in_group`: the job's group
    holds the robot and its station (`///GROUP1 RB1,ST1`): one interpolation, the station's
    `ECnnnnn` right after the robot's position (and base's), as a base axis' BC is."""
    values: tuple[float, ...] = ()
    pulses: tuple[bool, ...] = ()
    m = re.match(r"BC(\d+)\s*", rest)
    if m and f"BC{int(m.group(1))}" in table:
        found, pulse = table[f"BC{int(m.group(1))}"]
        values, pulses, rest = found, (pulse,) * len(found), rest[m.end():]
    m = re.match(r"EC(\d+)\s*", rest) if station_in_group else None
    if m and f"EC{int(m.group(1))}" in table:
        found, pulse = table[f"EC{int(m.group(1))}"]
        values, pulses, rest = values + found, pulses + (pulse,) * len(found), rest[m.end():]
    vj = "" if sync else r"\s+VJ=100(?:\.0*)?"
    m = re.search(rf"\s*\+MOVJ\s+EC(\d+){vj}\s*$", rest)
    if m and f"EC{int(m.group(1))}" in table:
        found, pulse = table[f"EC{int(m.group(1))}"]
        values, pulses, rest = values + found, pulses + (pulse,) * len(found), rest[:m.start()]
    return ((values, pulses) if values else None), rest


def inform_frame(user: int | None, sync: bool) -> str:
    """A job move's frame: ROBOT coordinates (the arm's base) or user frame n; a coordinated
    SMOVL/SMOVC in ROBOT coordinates placed in the part's frame by resolve_axes."""
    if sync:
        return COORD_FRAME if user is None else f"{COORD_FRAME}user{user}"
    return "base" if user is None else f"user{user}"


def why_native(text: str) -> str:
    """Why a vendor line of external axes the readers do not read stays native, or "": a RAPID
    `MoveExtJ` not in the form axes_only.py reads (another speed or zone, a jointtarget that
    moves the arm too: rmot's `move axes` moves one mechanism at its own speed, the arm still); an
    INFORM station at its own speed (`+MOVJ ECn VJ=50`: rmot moves every axis
    time-synchronously with the arm, at most at its own speed)."""
    if re.match(r"(?i)MoveExtJ\b", text):
        return ("MoveExtJ (the external axes alone) is read only as rmot writes `move axes` (`MoveExtJ T, vmax[\\T:=t], "
                "fine;` to a jointtarget whose arm joints are 9E+09): its axes move at their own speed")
    station = re.search(r"\+MOVJ\s+EC\d+\s+VJ=([\d.]+)", text)
    if station and float(station.group(1)) != 100.0:
        return (f"the station moves at its own VJ={station.group(1)} %: rmot moves every axis time-synchronously "
                "with the arm at up to its full speed")
    if re.search(r"\b[BE]C\d+\b", text):
        return "its base (BC) or station (EC) position is not declared in the job's //POS"
    return ""
