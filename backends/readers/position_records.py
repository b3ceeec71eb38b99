"""The position records a TP program's or INFORM job's native lines move to, kept with them.

A line kept native that moves to a position of its program (`L P[2] 100mm/sec FINE Offset,
PR[4]`, `MOVL C00001 V=211.7`) needs that position's data, which lives in the program's /POS
(TP) or //POS (INFORM) section, not in the line. Each such position is kept as a native
statement holding its record at the top of the routine the program became (after its
variables), once, in the order first named, located at the position's line, with the tool and
frame numbers it records turned into the names the import gives them (a number the program
never selects is declared in the stub as the controller's, as a selected one is):

  * TP: `P[2:"label"]{ GP1: UF : base, UT : gripper, CONFIG : 'N U T, 0, 0, 0', X = .. mm, .. }`,
    the /POS block with its whitespace collapsed (backends/fanuc_records.py writes it back);
  * INFORM: `C00001{ TOOL : gripper; PULSE : -204317,-90930,.. }` or `C00002{ TOOL : gripper;
    POSTYPE : USER; USER : table; RCONF : 0,0,0,..; RECTAN : 10,0,5,180,0,0 }`, the values of
    the `Cnnnnn=` line and the pseudo-instructions in force there (backends/inform_records.py).

A routine holding a native line read from another program (one inlined at its call) gets none:
one program's records serve all its lines, and the inlined line's numbers are the other
program's.

RAPID names its data instead of numbering it, so a native line there (`MoveL PontoPega, v1000,
z50, tool0;`) needs the declarations of the data it names: each module-level data declaration
of the files (`CONST robtarget PontoPega:=[..];`, its lines joined) is such a record, and a
routine gets, at its top, those its native lines name and those they name in turn, in the
files' order (a LOCAL one only from its own file). The RAPID backend declares them at module
level under their own names (backends/rapid.py).
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import replace

from rmot.backends.readers.fanuc_text import position_blocks
from rmot.backends.readers.model import Document, FrameData, Native, Routine, Stmt, ToolData, VarDecl, Where, walk

__all__ = ["native_positions", "tp_records", "inform_record", "rapid_records", "krl_records", "with_position_records"]

# how each vendor's lines name a position of their program, and how a comment line starts
_NAMED = {"fanuc": (re.compile(r"\bP\[(\d+)"), "!"), "inform": (re.compile(r"\bC(\d{4,5})\b"), "'")}
_SELECTION = re.compile(r"\bUF\s*:\s*(\d+)\s*,\s*UT\s*:\s*(\d+)")
_RAPID_DECL = re.compile(r"(?i)^\s*((?:LOCAL|TASK)\s+)*(?:CONST|PERS|VAR)\s+\w+\s+(\w+)")
_WORD = re.compile(r"\b[A-Za-z]\w*\b")


def tp_records(path: str, text: str, tools: Mapping[int, ToolData], frames: Mapping[int, FrameData]) -> tuple[Native, ...]:
    """Every position of a TP program as the record a native line may need, its frame and tool
    named as the program's moves name them."""
    def named(m: re.Match[str]) -> str:
        uf, ut = int(m.group(1)), int(m.group(2))
        frame = "base" if uf == 0 else frames[uf].name if uf in frames else str(uf)
        return f"UF : {frame}, UT : {tools[ut].name if ut in tools else ut}"

    return tuple(Native("fanuc", f"P[{n}" + (f':"{label}"' if label else "") + "]{ "
                        + _SELECTION.sub(named, " ".join(whole.split()), count=1) + " }", Where(path, line))
                 for n, label, whole, line in position_blocks(text))


def inform_record(key: str, tool: str, postype: str, user: str, conf: str, values: str, where: Where) -> Native:
    """An INFORM position as the record a native line may need (postype PULSE: encoder counts)."""
    items = [f"TOOL : {tool}"] + ([f"PULSE : {values}"] if postype == "PULSE" else
                                  [f"POSTYPE : {postype}"] + ([f"USER : {user}"] if user else [])
                                  + [f"RCONF : {conf}", f"RECTAN : {values}"])
    return Native("inform", f"{key}{{ {'; '.join(items)} }}", where)


def rapid_records(texts: list[tuple[str, Where]]) -> tuple[Native, ...]:
    """The module-level data declarations of a RAPID module (statement text, where) as records."""
    return tuple(Native("rapid", " ".join(text.split("\n")) + ";", where) for text, where in texts if _RAPID_DECL.match(text))


def krl_records(path: str, text: str) -> tuple[Native, ...]:
    """The data declarations of a KRL `.dat`, one per line, with or without a value (an array's,
    whose elements its later lines set, is left out: a line naming it stays undeclared) as records."""
    return tuple(Native("krl", line.strip(), Where(path, n)) for n, line in enumerate(text.split("\n"), 1)
                 if _DECLARATION["krl"][0].match(line))


# a data declaration (group 2: its name) and the comment mark, per vendor (RAPID Overview, "Data
# declarations"; KUKA System Software 8, "DECL": a .dat's `DECL [GLOBAL] TYPE NAME=value`, DECL
# optional for the predefined types)
_DECLARATION = {
    "rapid": (_RAPID_DECL, "!"),
    "krl": (re.compile(r"(?i)^\s*(?:DECL\s+(GLOBAL\s+)?\w+|(GLOBAL\s+)?(?:E6POS|E6AXIS|POS|AXIS|FRAME|FDAT|PDAT|LDAT|INT|REAL|BOOL))"
                       r"\s+(\w+)\s*(?:=|;|$)"), ";"),
}


def _declared_name(vendor: str, text: str) -> tuple[str, bool] | None:
    """(the name a declaration record declares, upper case; whether it is LOCAL), or None."""
    m = _DECLARATION[vendor][0].match(text)
    if m is None:
        return None
    return m.group(m.lastindex or 0).upper(), vendor == "rapid" and "LOCAL" in (m.group(1) or "").upper()


def _words(text: str, comment: str) -> set[str]:
    """The names a line uses (upper case), its strings and comment aside."""
    code = re.sub(r'"[^"]*"', "", text).split(comment)[0]
    return {w.upper() for w in _WORD.findall(code)}


def _with_declarations(routine: Routine, records: list[Native], variables: set[str], vendor: str) -> Routine:
    """A routine with the declarations of the data its native lines name, transitively, but not
    of the import's task `variables` (upper case): rmot declares those itself, and a native line
    must read and write the same variable as rmot's lines do."""
    by_name: dict[str, Native] = {}
    for r in records:  # a LOCAL declaration serves its own file only; the routine's file's first
        found = _declared_name(vendor, r.text)
        if found is not None and found[0] not in variables and (not found[1] or r.where.path == routine.where.path):
            if found[0] not in by_name or r.where.path == routine.where.path != by_name[found[0]].where.path:
                by_name[found[0]] = r
    comment = _DECLARATION[vendor][1]
    wanted: set[str] = set()
    todo = [w for s in walk(routine.body) if isinstance(s, Native) for w in _words(s.text, comment)]
    while todo:
        name = todo.pop()
        if name in by_name and name not in wanted:
            wanted.add(name)
            todo += _words(re.split(r":?=", by_name[name].text, maxsplit=1)[-1], comment)
    kept = sorted((by_name[n] for n in wanted), key=lambda r: (r.where.path, r.where.line, r.where.col))
    return _at_top(routine, kept)


def _at_top(routine: Routine, kept: list[Native]) -> Routine:
    if not kept:
        return routine
    top = next((k for k, s in enumerate(routine.body) if not isinstance(s, VarDecl)), len(routine.body))
    return replace(routine, body=(*routine.body[:top], *kept, *routine.body[top:]))


def _named(natives: list[Native], vendor: str) -> list[int]:
    pattern, comment = _NAMED[vendor]
    return list(dict.fromkeys(int(m.group(1)) for s in natives for line in s.text.split("\n")
                              if not line.lstrip().startswith(comment) for m in pattern.finditer(line)))


def native_positions(body: tuple[Stmt, ...], path: str, vendor: str) -> list[int]:
    """The positions the native lines of `body` read from `path` move to, in order."""
    return _named([s for s in walk(body) if isinstance(s, Native) and s.where.path == path], vendor)


def _with_records(routine: Routine, records: Mapping[tuple[str, int], Native], vendor: str) -> Routine:
    natives = [s for s in walk(routine.body) if isinstance(s, Native)]
    if any(s.where.path != routine.where.path for s in natives if _named([s], vendor)):
        return routine
    return _at_top(routine, [records[routine.where.path, n] for n in _named(natives, vendor) if (routine.where.path, n) in records])


def with_position_records(doc: Document) -> Document:
    """`doc` with the records of the positions each routine's native lines move to at its top."""
    if doc.vendor in _DECLARATION and doc.records:
        variables = {s.name.upper() for r in doc.routines for s in walk(r.body) if isinstance(s, VarDecl)}
        return replace(doc, routines=tuple(_with_declarations(r, list(doc.records), variables, doc.vendor) for r in doc.routines))
    if doc.vendor not in _NAMED or not doc.records:
        return doc
    pattern = _NAMED[doc.vendor][0]
    records = {(r.where.path, int(m.group(1))): r for r in doc.records if (m := pattern.match(r.text))}
    return replace(doc, routines=tuple(_with_records(r, records, doc.vendor) for r in doc.routines))
