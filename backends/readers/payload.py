"""Payload switches back to `attach PART` / `detach PART`, when the import runs in a cell.

A backend writes an `attach`/`detach` as the vendor's payload instruction at the same place:
RAPID `GripLoad piece;` / `GripLoad load0;`, KRL `$LOAD=name`, URScript `set_payload(m, cog)`,
TP `PAYLOAD[i]`. A reader keeps such a line native (W510); with the cell known,
`match_payloads` turns it back:

  * a switch to a load whose parts' share (the load less the tool's mass and centre, where the
    vendor writes tool + parts) has one part's (or feeder's) mass and a centre within that
    part's bounding sphere around the TCP (the gripper holds the part there) becomes
    `attach PART`; several parts that fit, or none, keep the line native with W516 naming
    the candidates;
  * a switch to the tool alone becomes `detach PART` of the part the routine attached last,
    or of the cell's only part; otherwise it stays native with W516.

Vendor data: ABB Technical reference manual "RAPID Instructions, Functions and Data types"
(loaddata [mass kg, cog [x, y, z] mm in the tool frame, ...]; GripLoad, load0 = no payload),
read from the module's loaddata declarations the reader keeps as comments; KUKA System
Software 8.x, system variable $LOAD {M kg, CM {X, Y, Z mm} in the flange frame}, from the
.dat's LOAD data; URScript manual set_payload(m kg, cog m from the flange); Fanuc TP
PAYLOAD[i] selects a schedule whose data lives on the controller: its mass is taken from a
`!...: M kg` remark right before the line (the backend writes one), its centre is unknown.
INFORM has no load instruction and VAL3 tool data no mass: the backends write the remark
`'attach P: payload M kg` / `// attach P: payload M kg` (tool and parts, kg), read the same
way, by mass.
The tool's own centre is rmot's convention, ir.payload_cog (half way along flange->TCP).
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from dataclasses import replace

from rmot.backends.readers import codes
from rmot.backends.readers.model import Document, FileCount, Grip, Native, Stmt, Where
from rmot.backends.readers.writer import map_leaves
from rmot.lang import ir
from rmot.lang.diagnostics import Diagnostic, Severity
from rmot.lang.record import record
from rmot.lang.source import Span

__all__ = ["PartSpec", "cell_parts", "match_payloads"]

MASS_TOLERANCE = 0.0006  # kg: the backends print masses to 3 decimals
COG_TOLERANCE = 0.0006  # m: centres of gravity to 0.001 mm .. 1 mm (RAPID mm with 3 decimals)
_NUM = r"[-+]?\d+(?:\.\d*)?(?:[eE][-+]?\d+)?"


@record(slots=True)
class PartSpec:
    """A part or feeder of the cell as the matcher needs it."""

    name: str
    mass: float  # kg
    reach: float  # m: the radius of its bounding sphere (a held part's centre is this close to the TCP)


def _reach(g: ir.Geometry | None) -> float:
    if isinstance(g, ir.Box):
        return 0.5 * math.sqrt(sum(s * s for s in g.size))
    if isinstance(g, ir.Cylinder):
        return math.hypot(g.radius, 0.5 * g.height)
    if isinstance(g, ir.Sphere):
        return g.radius
    if isinstance(g, ir.Capsule):
        return g.radius + 0.5 * g.length
    return math.inf  # a mesh: its extent is the sim's to load; the mass alone decides


def cell_parts(cell: ir.Cell) -> tuple[PartSpec, ...]:
    """The cell's parts and feeders."""
    return tuple(PartSpec(p.name, p.mass, _reach(p.geometry)) for p in cell.parts)


Load = tuple[float, tuple[float, float, float], Where | None]  # mass kg, cog m (tool frame), declared at


def _rapid_loads(doc: Document) -> dict[str, Load]:
    """loaddata name (lower case) -> (mass kg, cog m in the tool frame, its declaration), from
    the declarations the reader kept as comments."""
    out: dict[str, Load] = {}
    for kept in doc.kept:
        m = re.match(rf"(?i)\s*(?:LOCAL\s+)?(?:PERS|CONST|VAR)\s+loaddata\s+(\w+)\s*:?=\s*\[\s*({_NUM})\s*,"
                     rf"\s*\[\s*({_NUM})\s*,\s*({_NUM})\s*,\s*({_NUM})\s*\]", kept.text)
        if m:
            x, y, z = (float(m.group(i)) / 1000.0 for i in (3, 4, 5))
            out[m.group(1).lower()] = (float(m.group(2)), (x, y, z), kept.where)
    return out


def _switch(doc: Document, s: Native, loads: dict[str, Load]) -> tuple[bool, Load] | None:
    """(whether the load is the tool's and the parts' together in the flange frame, the load
    the native line switches to) -- RAPID's GripLoad is the parts' alone in the tool frame,
    mass 0 the switch back to the tool alone; None when the line is no payload switch (or its
    data is not in the files)."""
    if doc.vendor == "rapid":
        m = re.fullmatch(r"(?i)GripLoad\s+(\w+)\s*;", s.text)
        if m is None:
            return None
        if m.group(1).lower() == "load0":
            return False, (0.0, (0.0, 0.0, 0.0), None)
        found = loads.get(m.group(1).lower())
        return None if found is None else (False, found)
    if doc.vendor == "urscript":  # set_payload(m, [x, y, z]): kg, m from the flange
        m = re.fullmatch(rf"set_payload\(\s*({_NUM})\s*,\s*\[\s*({_NUM})\s*,\s*({_NUM})\s*,\s*({_NUM})\s*\]\s*\)",
                         s.text)
        if m is None:
            return None
        return True, (float(m.group(1)), (float(m.group(2)), float(m.group(3)), float(m.group(4))), None)
    if doc.vendor in ("krl", "fanuc"):  # KRL $LOAD=name: the .dat's LOAD {M kg, CM {X, Y, Z mm}}
        # on the flange; TP PAYLOAD[i]: schedule i, its mass from a remark before it (centre unknown)
        m = re.fullmatch(r"(?i)\$LOAD\s*=\s*(\w+)|(PAYLOAD\[\d+\])\s*;", s.text)
        named = {name.lower(): (mass, (cm[0] / 1000.0, cm[1] / 1000.0, cm[2] / 1000.0))
                 for name, mass, cm, _ in doc.loads}
        entry = named.get((m.group(1) or m.group(2)).lower()) if m else None
        return None if entry is None else (True, (entry[0], entry[1], None))
    if doc.vendor in ("inform", "val3"):  # the backend's remark `'attach P: payload M kg` (tool + parts; no centre)
        m = re.fullmatch(r"(?:'|// )(?:attach|detach) \w+: payload (\d+(?:\.\d+)?) kg", s.text)
        nan = float("nan")
        return None if m is None else (True, (float(m.group(1)), (nan, nan, nan), None))
    return None


def _held(total: Load, tools: tuple[tuple[ir.Pose, float], ...]) -> list[tuple[float, tuple[float, float, float]]]:
    """The parts' load (mass, cog m in the tool frame) a tool + parts load means, for each of
    the robot's tools (TCP in the flange frame, mass); mass 0 where it is the tool's alone. The
    tool's centre is rmot's payload convention (ir.payload_cog)."""
    mass, cog, _ = total
    out = []
    for tcp, tool_mass in tools:
        tool_cog = ir.payload_cog(tcp)
        parts = mass - tool_mass
        known = all(map(math.isfinite, cog))  # a TP schedule's centre is on the controller
        if abs(parts) <= MASS_TOLERANCE:
            if not known or math.dist(cog, tool_cog) <= COG_TOLERANCE:
                out.append((0.0, (0.0, 0.0, 0.0)))
            continue
        if not known:
            out.append((parts, (0.0, 0.0, 0.0)))  # the mass alone decides
            continue
        x, y, z = ((mass * c - tool_mass * t) / parts for c, t in zip(cog, tool_cog, strict=True))
        out.append((parts, (tcp.inverse() * ir.Pose((x, y, z))).position))
    return out


def _candidates(parts: tuple[PartSpec, ...], held: list[tuple[float, tuple[float, float, float]]]) -> list[str]:
    """The parts whose mass is the held load's and whose centre can be that load's centre."""
    return [p.name for p in parts if any(
        abs(p.mass - mass) <= MASS_TOLERANCE and math.hypot(*cog) <= p.reach + COG_TOLERANCE for mass, cog in held)]


def match_payloads(doc: Document, parts: tuple[PartSpec, ...], tools: tuple[tuple[ir.Pose, float], ...],
                   span_of: Callable[[Where], Span]) -> Document:
    """`doc` with every payload switch that matches one part as a `Grip`; the others stay
    native with W516. `tools`: the robot's tools (TCP in the flange frame, mass kg). The
    kept-native counts and W510 warnings of the turned lines go."""
    if not parts:
        return doc
    loads = _rapid_loads(doc)
    turned: list[Where] = []
    unmatched: list[Where] = []
    used: set[Where] = set()  # the declarations of the loads the turned lines switch to
    needed: set[Where] = set()  # ... and of those a line kept native still names
    diags: list[Diagnostic] = []
    held: list[str] = []  # the parts the routine being read attached, in source order

    def fix(s: Stmt) -> Stmt:
        if not isinstance(s, Native):
            return s
        found = _switch(doc, s, loads)
        if found is None:
            return s
        declared = found[1][2]
        loads_held = _held(found[1], tools) if found[0] else [found[1][:2]]
        take = not (loads_held and all(m == 0.0 for m, _ in loads_held))  # else back to the tool alone
        names = _candidates(parts, loads_held) if take else (held[-1:] or [p.name for p in parts])
        if len(names) != 1:
            if not take:
                what = f"the part it leaves is not known here (the cell has {', '.join(names)})"
            elif names:
                what = f"parts {', '.join(names)} all fit"
            else:
                what = f"no part of the cell ({', '.join(p.name for p in parts)}) has its mass and centre"
            diags.append(Diagnostic(codes.PAYLOAD_UNMATCHED, Severity.WARNING,
                                    f"payload switch `{s.text}`: {what}; kept native", span_of(s.where)))
            if declared is not None:
                needed.add(declared)
            unmatched.append(s.where)  # W516 says it; its W510 goes
            return s
        turned.append(s.where)
        if declared is not None:
            used.add(declared)
        if take:
            held.append(names[0])
        return Grip(names[0], take, s.where)

    routines = []
    for r in doc.routines:
        held.clear()
        routines.append(replace(r, body=map_leaves(r.body, fix)))
    return _recount(replace(doc, routines=tuple(routines)), turned, used - needed, unmatched, diags)


def _recount(doc: Document, turned: list[Where], used: set[Where], unmatched: list[Where],
             diags: list[Diagnostic]) -> Document:
    """The turned lines and the load declarations they use count as imported and lose their
    W510/W511 (the declarations leave the comment block); the W516 warnings join, in place of
    the W510 of the lines they keep native."""
    places = {(w.path, w.line, w.col) for w in (*turned, *used, *unmatched)}
    kept = tuple(d for d in doc.diagnostics if not (
        d.code in (codes.KEPT_NATIVE, codes.DECLARATION_KEPT) and d.span is not None
        and (d.span.file.path, d.span.start.line, d.span.start.col) in places))
    per_file: dict[str, int] = {}
    for w in (*turned, *used):
        per_file[w.path] = per_file.get(w.path, 0) + 1
    counts = tuple(FileCount(c.path, c.imported + per_file.get(c.path, 0), c.native - per_file.get(c.path, 0))
                   for c in doc.counts)
    comments = tuple(n for n in doc.kept if n.where not in used)
    return replace(doc, counts=counts, diagnostics=kept + tuple(diags), kept=comments)
