"""Position records an INFORM job's native lines move to.

An INFORM move names a robot position of its own job, `MOVL C00001 V=211.7`, whose data lives in
the job's //POS section, set by the pseudo-instructions before it (YRC1000 INSTRUCTIONS /
DX100 manual, "Position data": `///TOOL n` the tool file it was taught with, `///POSTYPE
PULSE|ROBOT|BASE|USER`, `///USER n`, `///RECTAN`, `///RCONF ..`; `///PULSE` encoder counts or,
after `///RECTAN`, X, Y, Z mm and Rx, Ry, Rz deg). A native statement whose text is such a
record,

    native inform "C00001{ TOOL : gripper; PULSE : -204317,-90930,-87249,-44324,-63766,32764 }"
    native inform "C00002{ TOOL : gripper; POSTYPE : USER; USER : table; RCONF : 0,0,0,0,0,0,0,0; RECTAN : 10,0,5,180,0,0 }"

(what `rmot import` keeps beside the native lines that move to C00001), is the record of C00001
for the native lines of the same job: the backend writes it into //POS under a number its own
positions do not take, with the tool file number and user frame number its own moves use for
that tool and frame, and renames `C00001` in those lines. A position's tool and frame travel
with it (the move uses the tool number its position records), so nothing is selected before
the line.

A record rmot cannot vouch for is refused (E411 at each line that moves to it): items other
than `KEY : value` of those keys, a PULSE that is not six whole numbers, a RECTAN that is not
six finite numbers, a POSTYPE other than ROBOT, BASE and USER beside RECTAN, a USER frame the cell
does not number, a tool the robot lacks, two records of one number that differ, and any record
in a job that drives a base axis or a station (its BC/EC positions pair with the C ones).
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable

from rmot.backends.native_refs import program_natives
from rmot.lang import ir
from rmot.lang.record import record

__all__ = ["Record", "number_of", "records_of", "renamed"]

_HEAD = re.compile(r"\s*C(\d{4,5})\s*\{(.*)\}\s*", re.S)
_KEYS = ("TOOL", "POSTYPE", "USER", "RCONF", "PULSE", "RECTAN")
_POSITION = re.compile(r"\bC(\d{4,5})\b")


@record(slots=True)
class Record:
    """One position record: its number, the tool and user frame it names, its POSTYPE (PULSE,
    or ROBOT, BASE, USER for a RECTAN one), RCONF and values as written, or why it cannot be."""

    number: int
    tool: str = ""
    postype: str = ""
    user: str = ""
    conf: str = ""
    values: str = ""
    problem: str = ""


def number_of(text: str) -> int | None:
    """The position number of a record's text (None: the text is no record)."""
    m = _HEAD.fullmatch(text)
    return int(m.group(1)) if m else None


def _numbers(text: str, whole: bool) -> bool:
    parts = text.split(",")
    if whole:
        return len(parts) == 6 and all(re.fullmatch(r"\s*-?\d+\s*", p) for p in parts)
    try:
        return len(parts) == 6 and all(math.isfinite(float(p)) for p in parts)
    except ValueError:
        return False


def _parse(text: str) -> Record:
    m = _HEAD.fullmatch(text)
    assert m is not None
    number, items = int(m.group(1)), {}
    for item in (i.strip() for i in m.group(2).split(";") if i.strip()):
        key, colon, value = (part.strip() for part in item.partition(":"))
        if key not in _KEYS or not colon or key in items or not value:
            return Record(number, problem=f"`{item[:40]}` is not one of the items TOOL, POSTYPE, USER, RCONF, PULSE, RECTAN")
        items[key] = value
    pulse, rectan = items.get("PULSE"), items.get("RECTAN")
    postype = "PULSE" if pulse is not None else items.get("POSTYPE", "ROBOT")
    if "TOOL" not in items or (pulse is None) == (rectan is None):
        return Record(number, problem="it must give TOOL and one of PULSE and RECTAN")
    if pulse is not None and (not _numbers(pulse, whole=True) or {"POSTYPE", "USER", "RCONF"} & set(items)):
        return Record(number, problem="its PULSE must be six whole encoder counts, with no POSTYPE, USER or RCONF")
    if rectan is not None and (not _numbers(rectan, whole=False) or postype not in ("ROBOT", "BASE", "USER")
                               or (postype == "USER") != ("USER" in items)
                               or not re.fullmatch(r"\d(,\d)*", items.get("RCONF", "0").replace(" ", ""))):
        return Record(number, problem="its RECTAN must be six finite numbers in POSTYPE ROBOT, BASE or USER (with USER) "
                                      "and an RCONF of digits")
    return Record(number, items["TOOL"], postype, items.get("USER", ""), items.get("RCONF", "").replace(" ", ""),
                  (pulse or rectan or "").replace(" ", ""))


def records_of(body: Iterable[ir.Instr]) -> dict[int, Record]:
    """The position records of one job, by number; two that differ under one number are refused."""
    out: dict[int, Record] = {}
    for node in program_natives(body, "inform"):
        if number_of(node.text) is None:
            continue
        rec = _parse(node.text)
        seen = out.setdefault(rec.number, rec)
        if seen != rec:
            out[rec.number] = Record(rec.number, problem=f"two records give C{rec.number:05d} different data")
    return out


def renamed(line: str, numbers: dict[int, int]) -> str:
    """`line` with each robot position it names at its number in the compiled job."""
    return _POSITION.sub(lambda m: f"C{numbers.get(int(m.group(1)), int(m.group(1))):05d}", line)
