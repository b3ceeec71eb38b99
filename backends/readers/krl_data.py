"""A KRL program's data lists read as values: declarations, positions, loads; and the backend's
timed wait, read back from its eight lines.

KRL (KUKA KSS 8.x Operating and Programming Instructions for System Integrators): a data list
(`DEFDAT name .. ENDDAT`) declares `DECL TYPE name=value`; positions are E6POS/POS/FRAME
`{X, Y, Z mm, A, B, C deg, S, T}` (R = Rz(A)·Ry(B)·Rx(C)) or E6AXIS/AXIS `{A1 .. A6 deg}`;
`LOAD` `{M kg, CM {X, Y, Z mm, ..}}`.
"""

from __future__ import annotations

import re
from copy import copy

from rmot.backends.readers import codes
from rmot.backends.readers.axes_slots import krl_slots
from rmot.backends.readers.common import Tally, number, split_top
from rmot.backends.readers.krl_text import Line, MotionState, aggregate, branch_of_status, declarations, in_cond, krl_pose, lines
from rmot.backends.readers.model import FrameData, Move, NamedLoad, Stmt, Target, ToolData, WaitIn, Where
from rmot.lang import ir

__all__ = [
    "Data", "data_list", "position", "declared", "named_loads", "timed_wait", "keep_block",
    "skip_function", "with_state", "home", "numbered", "data_objects", "load_switch",
]

Data = tuple[str, str, object, Where]  # type, name as written, value (aggregate or number), where


def data_list(dat: tuple[str, str] | None) -> dict[str, Data]:
    """NAME -> the declaration of every data object of a data list (none without one)."""
    return {} if dat is None else {d.name.upper(): (d.type, d.name, aggregate(d.value) if d.value else
                                                    number(d.value or ""), d.where) for d in declarations(lines(*dat))}


def position(type_: str, name: str, value: object, where: Where) -> Target | None:
    """A position declaration as a target: E6POS/POS/FRAME (with the Status' branch), E6AXIS/AXIS."""
    if not isinstance(value, dict):
        return None
    pose = krl_pose(value)
    if type_ in ("E6POS", "POS", "FRAME") and pose is not None:
        s = value.get("S")
        return Target(name, pose, None, branch_of_status(int(s)) if isinstance(s, float) else None, where,
                      slots=krl_slots(value))
    joints = [value.get(f"A{i}") for i in range(1, 7)]
    if type_ in ("E6AXIS", "AXIS") and all(isinstance(j, float) for j in joints):
        return Target(name, None, tuple(joints), None, where, slots=krl_slots(value))  # type: ignore[arg-type]
    return None


def declared(move: Move) -> Target:
    """The target a move went to, as a declaration (its pose; no name of its own)."""
    return Target(move.target_name or "", move.pose, move.joints, move.config, move.where)


def named_loads(data: dict[str, Data]) -> tuple[NamedLoad, ...]:
    """The .dat's LOAD data: (name, mass kg, centre of mass mm in the flange frame)."""
    out = []
    for type_, name, value, where in data.values():
        cm = value.get("CM") if isinstance(value, dict) and type_.upper() == "LOAD" else None
        mass = value.get("M") if isinstance(value, dict) else None
        if isinstance(cm, dict) and isinstance(mass, float) and all(isinstance(cm.get(k), float) for k in "XYZ"):
            out.append((name, mass, (float(cm["X"]), float(cm["Y"]), float(cm["Z"])), where))
    return tuple(out)


def timed_wait(found: list[Line], i: int) -> WaitIn | None:
    """The backend's 8-line timed wait: timer reset, WAIT FOR (c) OR ($TIMER[k]>=ms), and
    HALT when c did not come."""
    texts = [ln.text.replace(" ", "").upper() for ln in found[i:i + 8]]
    m = re.fullmatch(r"\$TIMER_STOP\[(\d+)\]=TRUE", texts[0])
    if m is None:
        return None
    k = m.group(1)
    w = re.fullmatch(rf"WAITFOR\((.*)\)OR\(\$TIMER\[{k}\]>=(\d+)\)", texts[3])
    ok = (texts[1] == f"$TIMER[{k}]=0" and texts[2] == f"$TIMER_STOP[{k}]=FALSE" and w is not None
          and texts[4] == f"$TIMER_STOP[{k}]=TRUE" and texts[6] == "HALT" and texts[7] == "ENDIF")
    cond = in_cond(w.group(1)) if ok and w else None
    if cond is None or texts[5] != f"IFNOT({w.group(1)})THEN":  # type: ignore[union-attr]
        return None
    return WaitIn(cond, int(w.group(2)) / 1000.0, found[i + 3].where)  # type: ignore[union-attr]


def keep_block(found: list[Line], tally: Tally, i: int, start: str, end: str,
               why: str | None = None) -> tuple[list[Stmt], int]:
    """The block `start` .. `end` at `i` (nested ones included) kept native line by line (`why`:
    the reason each line's warning gives, by default that `start` has no rmot form)."""
    out: list[Stmt] = []
    depth = 0
    while i < len(found):
        ln = found[i]
        depth += ln.word == start
        depth -= ln.word == end
        if ln.text:
            out.append(tally.keep(ln.text, ln.where, why or f"{start} has no rmot form"))
        i += 1
        if depth <= 0:
            break
    return out, i


def skip_function(found: list[Line], tally: Tally, i: int) -> int:
    """A DEFFCT .. ENDFCT at `i` into the comment block (W511); the index after it."""
    tally.warn(codes.DECLARATION_KEPT, "a KRL function (DEFFCT) has no rmot form: kept as a comment", found[i].where)
    while i < len(found) and found[i].word != "ENDFCT":
        if found[i].text:
            tally.comment(found[i].text, found[i].where)
        i += 1
    if i < len(found):
        tally.comment(found[i].text, found[i].where)
    return i + 1


def with_state(state: MotionState, text: str) -> MotionState | None:
    """The motion state a spline motion's WITH list gives it (a copy of `state`; all six
    $VEL_AXIS equal → the joint speed share); None where the list has no rmot form."""
    values = with_values(text)
    axes = {v for k, v in (values or {}).items() if k.startswith("VEL_AXIS")}
    if values is None or (axes and (len(axes) != 1 or sum(k.startswith("VEL_AXIS") for k in values) != 6)):
        return None
    out = copy(state)
    out.vel_cp = values["VEL.CP"] * 1000.0 if "VEL.CP" in values else state.vel_cp
    out.cdis = values.get("APO.CDIS", state.cdis)
    out.vel_ptp = axes.pop() if axes else state.vel_ptp
    return out


def with_values(text: str) -> dict[str, float] | None:
    """`$VEL.CP = 0.2, $APO.CDIS = 5, $VEL_AXIS[1] = 50, ..` of a spline motion's WITH (KSS 8.3
    System Integrators, SPTP/SLIN/SCIRC: the values hold for that motion only) as VEL.CP /
    APO.CDIS / VEL_AXIS[n] -> number; None where an item is another variable or not a number."""
    out: dict[str, float] = {}
    for item in split_top(text):
        m = re.fullmatch(r"(?i)\$(VEL\.CP|APO\.CDIS|VEL_AXIS\[\s*[1-6]\s*\])\s*=\s*(\S+)", item.strip())
        value = number(m.group(2)) if m else None
        if m is None or value is None:
            return None
        out[re.sub(r"\s+", "", m.group(1)).upper()] = value
    return out


def home(targets: dict[str, Target], config: dict[str, Data], tally: Tally, where: Where) -> Target:
    """`PTP HOME` / `PTP XHOME`: the home position lives in the controller's $config.dat
    (`DECL E6AXIS XHOME`), not in the program: the one of the $config.dat found, else KUKA's
    shipped value {A1 0, A2 -90, A3 90, A4 0, A5 0, A6 0} (KSS 8.x $config.dat, BAS home) with
    W511 at the first use."""
    found = position(*config["XHOME"]) if "XHOME" not in targets and "XHOME" in config else None
    if found is not None:
        targets["XHOME"] = found
    if "XHOME" not in targets:
        tally.warn(codes.DECLARATION_KEPT, "HOME is XHOME of the controller's $config.dat, not in the program: read "
                   "as KUKA's shipped {A1 0, A2 -90, A3 90, A4 0, A5 0, A6 0} (check it against the controller, "
                   "or give its .dat)", where)
        targets["XHOME"] = Target("HOME", None, (0.0, -90.0, 90.0, 0.0, 0.0, 0.0), None, where)
    return targets["XHOME"]


def numbered(tools: dict[str, ToolData], frames: dict[str, FrameData], tally: Tally, what: str, n: str | None,
             name: str | None, at: Where) -> str | None:
    """A tool or base selected by its controller number: a stub entry (its data lives in
    $config.dat, not in the program: the stub puts it at the flange / robot base, W511)."""
    if n is None:
        return None
    if what == "base" and n == "0":
        return "base"
    label = re.sub(r"\W", "_", name) if name else f"{what}{n}"
    key = label.upper()
    stored = f"{'TOOL_DATA' if what == 'tool' else 'BASE_DATA'}[{n}] of $config.dat"
    if what == "tool" and key not in tools:
        tools[key] = ToolData(label, ir.Pose(), 0.0, at, stored, int(n))
    elif what == "base" and key not in frames:
        frames[key] = FrameData(label, ir.Pose(), at, stored, int(n))
    return label


def data_objects(data: dict[str, Data], src: str, assigned: set[str]
                 ) -> tuple[dict[str, ToolData], dict[str, FrameData], dict[str, Target]]:
    """The tools (`$TOOL = name` in `src`, with `name_LOAD`'s mass), bases (`$BASE = name`) and
    targets (positions `src` never assigns) of a data list, by NAME."""
    tool_names = {m.upper() for m in re.findall(r"(?im)^\s*\$TOOL\s*=\s*(\w+)", src)}
    base_names = {m.upper() for m in re.findall(r"(?im)^\s*\$BASE\s*=\s*(\w+)", src)}
    tools: dict[str, ToolData] = {}
    frames: dict[str, FrameData] = {}
    targets: dict[str, Target] = {}
    for key, (type_, name, value, where) in data.items():
        pose = krl_pose(value) if isinstance(value, dict) else None
        if key in tool_names and pose is not None:
            load = data.get(f"{key}_LOAD")
            mass = load[2].get("M") if load and isinstance(load[2], dict) else 0.0
            tools[key] = ToolData(name, pose, mass if isinstance(mass, float) else 0.0, where)
        elif key in base_names and pose is not None:
            frames[key] = FrameData(name, pose, where)
        elif key.split("[")[0] not in assigned:
            found = position(type_, name, value, where)
            if found is not None:
                targets[key] = found
    return tools, frames, targets


def load_switch(found: list[Line], i: int) -> bool:
    """`$LOAD=name` that is not the load of the tool the line before selects: a switch of the
    held load (an attach or detach)."""
    if re.fullmatch(r"(?i)\$LOAD\s*=\s*\w+", found[i].text) is None:
        return False
    before = next((ln.text for ln in reversed(found[:i]) if ln.text), "")
    return re.match(r"(?i)\$TOOL\s*=", before) is None
