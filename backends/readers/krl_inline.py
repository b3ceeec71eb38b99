"""KRL inline forms read from their fold header.

An inline form (KUKA KSS 5.x / KSS 8.x Operating and Programming Instructions for System
Integrators, "Programming for user group Expert", inline forms) is a `;FOLD` whose header names the
whole motion, `PTP P1 CONT Vel=100 % PDAT1 Tool[1] Base[0]` (KR C2) or `SLIN P2 Vel=0.2 m/s CPDAT4
Tool[1]:name Base[1]:name` (KR C4, the tool and base data's names after the index); the statements
inside are what the controller runs, generated from the header and the `.dat`'s XP1 and
PPDAT1/LCPDAT1 (its APO_DIST mm the approximation distance of a CONT motion).
"""

from __future__ import annotations

import re
from collections.abc import Callable

from rmot.backends.readers.common import Tally
from rmot.backends.readers.krl_data import Data, numbered
from rmot.backends.readers.model import FrameData, Move, Target, ToolData, Where

__all__ = ["MOTIONS", "inline_move"]

MOTIONS = {"PTP": "joint", "SPTP": "joint", "LIN": "linear", "SLIN": "linear", "CIRC": "circular",
           "SCIRC": "circular"}

Found = tuple[str, str | None, Target | None]  # (rmot expression, name as written, declaration)
Targets = Callable[[str, "Where | None"], "Found | None"]  # a target by name (at: where HOME may be read)


def inline_move(word: str, text: str, where: Where, target: Targets, tables: tuple[dict[str, Data], dict[str, Data]],
                frames: tuple[dict[str, ToolData], dict[str, FrameData]], tally: Tally) -> Move | None:
    """`P1 [P2] [CONT] Vel=100 % PDAT1 Tool[1][:name] Base[0][:name]`; `tables` are the .dat's and
    $config.dat's declarations, `frames` the tools and bases the import knows."""
    data, config = tables
    tools, bases = frames
    m = re.match(r"(?i)(\w+)(?:\s+(\w+))?\s+(CONT\s+)?Vel\s*=\s*([\d.]+)\s*(%|m/s|mm/s)\s+(\w+)"
                 r"(?:\s+Tool\[(\d+)\](?::(\S+))?)?(?:\s+Base\[(\d+)\](?::(\S+))?)?", text)
    kind = MOTIONS[word]
    second = m.group(2) if m and m.group(2) and m.group(2).upper() != "CONT" else None
    cont = m is not None and (m.group(3) is not None or (m.group(2) or "").upper() == "CONT")
    if m is None or (kind == "circular") != (second is not None):
        return None
    points = [m.group(1)] + ([second] if second else [])
    found = [target("X" + p, None) or target(p, where) for p in points]
    if any(f is None for f in found):
        return None
    vel, unit = float(m.group(4)), m.group(5)
    zone = None
    if cont:
        key = ("P" if kind == "joint" else "L") + m.group(6).upper()  # PDEFAULT: $config.dat's
        found_data = data.get(key) or data.get(m.group(6).upper()) or config.get(key)
        apo = found_data[2].get("APO_DIST") if found_data and isinstance(found_data[2], dict) else None
        if not isinstance(apo, float):
            return None
        zone = apo
    tool = numbered(tools, bases, tally, "tool", m.group(7), m.group(8), where)
    frame = numbered(tools, bases, tally, "base", m.group(9), m.group(10), where)
    expr, name, decl = found[-1]  # type: ignore[misc]
    config_ = decl.config if kind == "joint" and decl is not None and decl.pose is not None else None
    speed = vel * 1000.0 if unit == "m/s" else vel
    return Move(kind, expr, name, where, via=found[0][0] if kind == "circular" else None,  # type: ignore[index]
                speed=speed if kind != "joint" else None, joint_pct=vel if kind == "joint" else None,
                zone=zone, tool=tool, frame=frame, config=config_,
                pose=decl.pose if decl else None, joints=decl.joints if decl else None, slots=decl.slots if decl else (),
                source=f"{word} {text.strip()}")  # the header, as the reader keeps a form it cannot read
