"""Numbered data a native line names that the backend also numbers.

Fanuc TP and INFORM number a program's positions and labels and the controller's registers,
variables and timers; a line kept native from another program (what `rmot import` keeps)
still carries that program's numbers. Written as they stand, they would mean other data:

  * a label the line names (`LBL[3]`, `*L001`) is reserved: the backend's own labels skip it,
    so the line's jumps land where they did;
  * a position it names (`P[2]`, `C00001`) is not in the compiled program, whose positions
    the backend numbers for rmot's moves: `P[2]` there is another point, or none. Refused;
  * a register, position register, timer, variable or tool/frame datum it names that the
    backend's own lines also use would be read or changed behind rmot's back. Refused.

Refusals are E411 at the native statement (`native_clash`): the backend cannot vouch for the
line. Sources: B-83284EN (R-30iB Operator's Manual), "Position data", "Register instructions",
"Label instruction" (labels and positions are the program's own, registers the controller's);
YRC1000 INSTRUCTIONS manual, "Variables" and "JUMP/label" (C positions the job's, variables
the controller's).
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Iterator

from rmot.lang import ir, ir_tree
from rmot.lang.record import record

__all__ = ["Scheme", "FANUC", "INFORM", "program_natives", "reserved_labels", "positions_named", "clashes", "native_data", "keep_declaration"]


@record(slots=True)
class Scheme:
    """What a vendor's lines number: positions and labels of the program, and the shared data
    (a native line's mention, the backend's own use, and how one name is written)."""

    vendor: str
    comment: str  # a line starting with this names nothing
    positions: re.Pattern[str]
    labels: re.Pattern[str]  # group 1: the label's name as the backend would write it
    shared: tuple[tuple[re.Pattern[str], re.Pattern[str]], ...]  # (named by a native line, used by the backend)
    name: str  # how one shared datum is written (its kind and number): `R[5]`, `D050`


def _shared(pattern: str, own: str | None = None) -> tuple[re.Pattern[str], re.Pattern[str]]:
    return re.compile(pattern), re.compile(own or pattern)


FANUC = Scheme(
    "fanuc",
    "!",
    re.compile(r"\bP\[\d+"),
    re.compile(r"\bLBL\[(\d+)"),
    (_shared(r"\b(R)\[(\d+)"), _shared(r"\b(PR)\[(\d+)"), _shared(r"\b(TIMER)\[(\d+)"),
     # a native line writing a tool or frame the backend selects changes what rmot's moves run with
     _shared(r"\b(UTOOL)\[(\d+)\]\s*=", r"\b(UTOOL)(?:_NUM\s*=\s*|\[)(\d+)"),
     _shared(r"\b(UFRAME)\[(\d+)\]\s*=", r"\b(UFRAME)(?:_NUM\s*=\s*|\[)(\d+)")),
    "{0}[{1}]",
)
INFORM = Scheme(
    "inform",
    "'",
    re.compile(r"\b(?:C|BC|EC)\d{4,5}\b"),
    re.compile(r"\*(\w+)"),
    (_shared(r"\b(L?[BIDRSP])(\d{3,4})\b"),),
    "{0}{1:03d}",
)


def _name(scheme: Scheme, m: re.Match[str]) -> str:
    """One datum's name whatever its comment or padding: `R[5:count]` -> R[5], `P0050` -> P050."""
    return scheme.name.format(m.group(1).upper(), int(m.group(2)))


def _code(scheme: Scheme, lines: Iterable[str]) -> list[str]:
    return [line for line in lines if not line.lstrip().startswith(scheme.comment)]


def _natives(body: Iterable[ir.Instr], vendor: str) -> Iterable[ir.Native]:
    return (n for n in ir_tree.walk(body) if isinstance(n, ir.Native) and n.vendor.lower() == vendor)


def program_natives(body: Iterable[ir.Instr], vendor: str) -> Iterator[ir.Native]:
    """The native statements of one program's body for `vendor`: not those of the procs it calls,
    which are programs (TP) or jobs (INFORM) of their own."""
    for instr in body:
        if isinstance(instr, ir.Native) and instr.vendor.lower() == vendor:
            yield instr
        runs, bodies = ir_tree.flow(instr)
        for sub in bodies if runs is not ir_tree.Runs.CALL else ():
            yield from program_natives(sub, vendor)


def reserved_labels(scheme: Scheme, body: Iterable[ir.Instr]) -> frozenset[str]:
    """The labels the native lines of `body` name (upper case, as the backend would write them)."""
    return frozenset(m.group(1).upper() for n in _natives(body, scheme.vendor)
                     for line in _code(scheme, n.text.splitlines()) for m in scheme.labels.finditer(line))


def positions_named(scheme: Scheme, lines: Iterable[str]) -> list[str]:
    """The program positions native lines name, in order."""
    return [m.group(0) + ("]" if "[" in m.group(0) else "") for line in _code(scheme, lines)
            for m in scheme.positions.finditer(line)]


def clashes(scheme: Scheme, natives: Iterable[tuple[ir.Native, list[str]]], own: Iterable[str]) -> list[tuple[ir.Native, str]]:
    """The natives (with the lines they were written as) naming shared data the backend's own
    lines `own` also use: (native, the first such datum) each."""
    used = {_name(scheme, m) for line in _code(scheme, own) for _, pattern in scheme.shared for m in pattern.finditer(line)}
    out = []
    for node, lines in natives:
        named = [_name(scheme, m) for line in _code(scheme, lines) for pattern, _ in scheme.shared for m in pattern.finditer(line)]
        hit = next((name for name in named if name in used), None)
        if hit is not None:
            out.append((node, hit))
    return out


def native_data(declared: dict[str, tuple[str, ir.Native]], own: set[str],
                taken: dict[str, str]) -> tuple[list[str], list[tuple[ir.Native, str]]]:
    """RAPID and KRL name their data: of the data declarations native statements hold (`NAME` ->
    (text, statement)), (those to write, those naming data the backend gave other data: each with
    the rmot name it gave it). Data the backend declares under the same rmot name (`own`, upper
    case; `taken`: the NameTable's legal -> source names) is the same datum, written once: the
    import names rmot's targets, tools and variables after the file's."""
    write, clash = [], []
    for key, (text, node) in declared.items():
        source = taken.get(key)
        if key not in own and source is None:
            write.append(text)
        elif source is not None and source.upper() != key:
            clash.append((node, source))
    return write, clash


def keep_declaration(declared: dict[str, tuple[str, ir.Native]], name: str, node: ir.Native) -> bool:
    """Record a native data declaration of `name` (case-insensitive); False where another of that
    name declares it differently (E411 at the caller)."""
    text = node.text.strip()
    return declared.setdefault(name.upper(), (text, node))[0] == text
