"""A KRL program's data lists read as values: declarations, positions, loads; and the backend's
timed wait, read back from its eight lines.

KRL (KUKA KSS 8.x Operating and Programming Instructions for System Integrators): a data list
(`DEFDAT name .. ENDDAT`) declares `DECL TYPE name=value`; positions are E6POS/POS/FRAME
`{X, Y, Z mm, A, B, C deg, S, T}` (R = Rz(A)·Ry(B)·Rx(C)) or E6AXIS/AXIS `{A1 .. A6 deg}`;
`LOAD` `{M kg, CM {X, Y, Z mm, ..}}`.
"""

from __future__ import annotations

import re

from rmot.backends.readers.common import number
from rmot.backends.readers.krl_text import Line, aggregate, branch_of_status, declarations, in_cond, krl_pose, lines
from rmot.backends.readers.model import Move, Target, WaitIn, Where

__all__ = ["Data", "data_list", "position", "declared", "named_loads", "timed_wait"]

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
        return Target(name, pose, None, branch_of_status(int(s)) if isinstance(s, float) else None, where)
    joints = [value.get(f"A{i}") for i in range(1, 7)]
    if type_ in ("E6AXIS", "AXIS") and all(isinstance(j, float) for j in joints):
        return Target(name, None, tuple(joints), None, where)  # type: ignore[arg-type]
    return None


def declared(move: Move) -> Target:
    """The target a move went to, as a declaration (its pose; no name of its own)."""
    return Target(move.target_name or "", move.pose, move.joints, move.config, move.where)


def named_loads(data: dict[str, Data]) -> tuple[tuple[str, float, tuple[float, float, float]], ...]:
    """The .dat's LOAD data: (name, mass kg, centre of mass mm in the flange frame)."""
    out = []
    for type_, name, value, _ in data.values():
        cm = value.get("CM") if isinstance(value, dict) and type_.upper() == "LOAD" else None
        mass = value.get("M") if isinstance(value, dict) else None
        if isinstance(cm, dict) and isinstance(mass, float) and all(isinstance(cm.get(k), float) for k in "XYZ"):
            out.append((name, mass, (float(cm["X"]), float(cm["Y"]), float(cm["Z"]))))
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

