"""Position records a TP program's native lines move to.

A TP move names a position of its own program, `L P[2] 100mm/sec FINE`, whose data lives in
the program's /POS section (B-83284EN, "Position data"): the arm group's `UF : n, UT : m`
(the user frame and tool it was taught in), its CONFIG string and X..R (or J1..J6), then each
further motion group's block. A native statement whose text is such a record,

    native fanuc "P[2:\"above\"]{GP1: UF : fixture, UT : gripper, CONFIG : 'N U T, 0, 0, 0', X = 10.5 mm, ...}"

(what `rmot import` writes beside the native lines that move to P[2]), is the record of P[2] for
the native lines of the same program: the backend writes it into /POS under a number its own
positions do not take, renames `P[2]` in those lines to that number, and selects the record's
frame and tool (`UFRAME_NUM`, `UTOOL_NUM`) right before each of them. UF and UT name the cell's
frame (`base`, `world` or a cell frame) and tool (`flange` or a tool on the robot), numbered as
rmot's own moves number them. The controller runs a move only in the frame and tool its
position was taught in (INTP-250/INTP-252 "frame number mismatch", the default user-frame
check), so the line ran with those selected where it came from, and selecting them keeps it so.

A record rmot cannot vouch for is refused (E411 at each line that moves to it): a
record that is not `KEY : value` and `KEY = number unit` items, a value that is not a finite
number, a second motion group or an extended axis of the arm's group the task does not drive
(the program's DEFAULT_GROUP and rmot's own positions would not hold them), two records of one
number that differ, a frame or tool the cell lacks.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable, Iterator

from rmot.backends.native_refs import program_natives
from rmot.lang import ir
from rmot.lang.record import record

__all__ = ["Record", "number_of", "records_of", "layout", "renamed", "named", "frame_ref", "tool_ref"]

_HEAD = re.compile(r'\s*P\[(\d+)((?::"[^"\n]*")?)\]\s*\{(.*)\}\s*;?\s*', re.S)
_GROUP = re.compile(r"\bGP(\d)\s*:")
_VALUE = re.compile(r"([XYZWPR]|[JE]\d)\s*=\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(mm|deg)")
_SETTING = re.compile(r"(UF|UT|CONFIG)\s*:\s*(\w+|'[^']*')")
_POSITION = re.compile(r"\bP\[(\d+)")


@record(slots=True)
class Record:
    """One position record: its number and label as written, the frame and tool it names, its
    CONFIG, its values (key, number text, unit) in order, or why it cannot be written."""

    number: int
    label: str
    frame: str = ""
    tool: str = ""
    config: str = ""
    values: tuple[tuple[str, str, str], ...] = ()
    problem: str = ""


def number_of(text: str) -> int | None:
    """The position number of a record's text (None: the text is no record)."""
    m = _HEAD.fullmatch(text)
    return int(m.group(1)) if m else None


def _items(group: str) -> Iterator[str]:
    """A group's comma-separated items (a comma inside CONFIG's quotes is the string's)."""
    for item in re.findall(r"(?:'[^']*'|[^,'])+", group):
        if item.strip():
            yield item.strip()


def _parse(text: str, drives_axes: bool) -> Record:
    m = _HEAD.fullmatch(text)
    assert m is not None
    number, label, rest = int(m.group(1)), m.group(2), m.group(3)
    groups = _GROUP.split(rest)
    if groups[0].strip() or len(groups) != 3 or groups[1] != "1":
        extra = next((g for g in groups[1::2] if g != "1"), None)
        why = (f"it moves motion group {extra}, which the program does not drive (give the cell's positioner "
               "when importing: its moves are then rmot's)") if extra else "it must hold one `GP1:` block"
        return Record(number, label, problem=why)
    settings: dict[str, str] = {}
    values: list[tuple[str, str, str]] = []
    for item in _items(groups[2]):
        value, setting = _VALUE.fullmatch(item), _SETTING.fullmatch(item)
        if value and math.isfinite(float(value.group(2))):
            values.append(value.groups())  # type: ignore[arg-type]
        elif setting and setting.group(1) not in settings:
            settings[setting.group(1)] = setting.group(2)
        else:
            return Record(number, label, problem=f"`{item[:40]}` is not a `KEY : value` or `KEY = number mm|deg` item rmot reads")
    keys = [k for k, _, _ in values]
    arm = ["X", "Y", "Z", "W", "P", "R"] if "X" in keys else [f"J{i}" for i in range(1, 7)]
    if keys[:6] != arm or any(not k.startswith("E") for k in keys[6:]) or "UF" not in settings or "UT" not in settings:
        return Record(number, label, problem="it must give UF, UT and X..R or J1..J6 once each, then E1.. only")
    if len(keys) > 6 and not drives_axes:
        return Record(number, label, problem="it gives an extended axis of the arm's group (E1..), which the task does not drive")
    return Record(number, label, settings["UF"], settings["UT"], settings.get("CONFIG", ""), tuple(values))


def records_of(body: Iterable[ir.Instr], drives_axes: bool) -> dict[int, Record]:
    """The position records of one program, by the number its lines name; two that differ
    under one number are refused."""
    out: dict[int, Record] = {}
    for node in program_natives(body, "fanuc"):
        if number_of(node.text) is None:
            continue
        rec = _parse(node.text, drives_axes)
        seen = out.setdefault(rec.number, rec)
        if seen != rec:
            out[rec.number] = Record(rec.number, rec.label, problem=f"two records give P[{rec.number}] different data")
    return out


def layout(rec: Record, number: int, uf: int, ut: int) -> str:
    """The record as /POS holds it, at `number` with the frame and tool numbers given (the
    layout of the backend's own positions)."""
    head = f"\tUF : {uf}, UT : {ut}," + (f"\t\tCONFIG : {rec.config}," if rec.config else "")
    cells = [f"{k}{' ' if len(k) == 1 else ''}= {v:>9} {'' if len(k) > 1 else ' '}{unit}" for k, v, unit in rec.values]
    rows = ["\t" + ",\t".join(cells[i:i + 3]) for i in range(0, len(cells), 3)]
    return "\n".join([f"P[{number}{rec.label}]{{", "   GP1:", head] + [r + "," for r in rows[:-1]] + rows[-1:] + ["};"])


def renamed(line: str, numbers: dict[int, int]) -> str:
    """`line` with each position it names at its number in the compiled program."""
    return _POSITION.sub(lambda m: f"P[{numbers.get(int(m.group(1)), int(m.group(1)))}", line)


def named(lines: Iterable[str]) -> list[int]:
    """The position numbers the lines name, in order."""
    return [int(m.group(1)) for line in lines if not line.lstrip().startswith("!") for m in _POSITION.finditer(line)]


def frame_ref(cell: ir.Cell, robot: str, name: str) -> ir.FrameRef | None:
    """The frame a record's UF names, as rmot's moves refer to it (None: the cell has none)."""
    base = cell.robot(robot).base
    if name == "base":
        return ir.FrameRef(None)
    if name == "world":
        return ir.FrameRef("world", base.inverse(), ir.Pose())
    frame = next((f for f in cell.frames if f.name == name), None)
    return None if frame is None else ir.FrameRef(name, base.inverse() * frame.pose, frame.pose)


def tool_ref(cell: ir.Cell, robot: str, name: str) -> ir.ToolRef | None:
    """The tool a record's UT names (None: the robot carries none of that name)."""
    if name == "flange":
        return ir.ToolRef(None)
    tool = next((t for t in cell.tools if t.name == name and t.robot == robot), None)
    return None if tool is None else ir.ToolRef(tool.name, tool.tcp, tool.mass)
