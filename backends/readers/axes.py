"""External axes read back: the slot values a vendor writes beside a target, mapped to the axes
of the cell's track and positioners (`ext(rail=600mm, pos=(0deg, 90deg))`, `with rail, pos`).

The readers record each target's slot values as written (`Target.slots`, `Move.slots`), as the
backends write them (backends/ext_axes.py, inform_axes.py): RAPID robtarget/jointtarget `extax`
eax_a..eax_f, 9E+09 for a slot no axis takes (ABB RAPID reference, "extjoint"); KRL E1..E6 of an
E6POS/E6AXIS, 0 for a slot no axis takes; Fanuc TP the arm group's `E1=` (an integrated rail),
then each further group's `J1=`.. (`GP2:`); INFORM a move's `BCn` and the station's `+MOVJ
ECn`, encoder pulses or mm. `resolve_axes` maps them with the cell by the backends' own slot
rule (the driven mechanisms' axes in turn, a mechanism's axes in their order; mm for a linear
axis, degrees for a revolute one): the program drives the mechanisms of the cell whose axes
fill exactly the slots the files use, the track carrying the robot always among them, in the
order the vendor's own structure (TP, INFORM) or the file's machine-data header (RAPID, KRL)
states. Where no such choice exists, or more than one, or where no cell is given (a stub cell
cannot declare a track's or positioner's geometry), every move with axis values stays native
with W523 naming why, the whole statement as the reader keeps one (`Move.source`): an axis
value is never guessed. The one reading without a mechanism is RAPID's 0 in every slot on a cell
without axes, which the controller ignores (W544, `_not_connected`). Frames the backends write through a
mechanism come back as the cell's frame riding on it (KRL `$BASE=EK(..)`, a TP COORD move, an
INFORM SMOVL/SMOVC placed in it).
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Mapping
from dataclasses import replace
from itertools import combinations

from rmot.backends.readers import codes
from rmot.backends.readers.axes_only import absorb_move_ext_j, one_mechanism, si_value
from rmot.backends.readers.common import native_line, rmot_name
from rmot.backends.readers.rapid import num_text, pose_expr
from rmot.backends.readers.writer import map_leaves
from rmot.backends.readers.axes_slots import ABSURD, COORD_FRAME, EK_FRAME, SLOTS
from rmot.backends.readers.model import (
    Document, FileCount, For, If, Move, Native, Pulse, Routine, SetOut, Stmt, Target, Wait, WaitIn, Where, While, walk,
)
from rmot.lang import ir
from rmot.lang.diagnostics import Diagnostic, Severity
from rmot.lang.ir_axes import Mechanism
from rmot.lang.source import Span

__all__ = ["resolve_axes", "slot_change"]

def _ek_frame(frame: str | None, cell: ir.Cell | None) -> str | None:
    """The cell's frame a `$BASE=EK(..)` placeholder names: the frame riding on mechanism n - 2
    (MACHINE_DEF[1] is the robot, mechanisms follow in cell order: ext_axes.mechanism_index) at
    that offset (1 um, 1e-6 in each quaternion component); None where none does."""
    head, _, numbers = (frame or "").removeprefix(EK_FRAME).partition("@")
    if cell is None or cell.external is None or not head.isdigit():
        return None
    values = [float(v) for v in numbers.split(",")]
    index = int(head) - 2
    mechanisms = cell.external.mechanisms
    if not 0 <= index < len(mechanisms):
        return None
    for mount in cell.external.mounts:
        if mount.kind == "frame" and mount.mechanism == mechanisms[index].name:
            near = all(abs(a - b) < 1e-6 for a, b in zip(mount.local.position, values))
            if near and abs(sum(a * b for a, b in zip(mount.local.quaternion, values[3:]))) > 1 - 1e-10:
                return mount.body
    return None


def _slot_name(vendor: str, k: int) -> str:
    return {"rapid": f"eax_{'abcdef'[k]}" if k < SLOTS else "", "krl": f"E{k + 1}"}.get(vendor) or f"external axis {k + 1}"


def slot_change(vendor: str, a: tuple[float | None, ...], b: tuple[float | None, ...]) -> str | None:
    """What a touch-up changed in a target's external-axis values (`rmot diff`): each slot whose
    value moved by more than 0.001 (mm or deg, what the vendors print), or was set or unset."""
    changes = []
    for k in range(max(len(a), len(b))):
        x, y = (a[k] if k < len(a) else None), (b[k] if k < len(b) else None)
        if (x is None) != (y is None) or x is not None and y is not None and abs(x - y) > 0.001:
            shown = ["unset" if v is None else num_text(v, 6) for v in (x, y)]
            changes.append(f"{_slot_name(vendor, k)} {shown[0]} -> {shown[1]}")
    return f"external axes changed: {', '.join(changes)}" if changes else None


def _value_text(mech: Mechanism, values: tuple[float, ...]) -> str:
    texts = [f"{num_text(v, 6)}{'mm' if a.linear else 'deg'}" for a, v in zip(mech.axes, values)]
    return texts[0] if len(texts) == 1 else f"({', '.join(texts)})"


def _drivable(cell: ir.Cell, robot: str) -> tuple[list[Mechanism], Mechanism | None]:
    """(the mechanisms a program on `robot` may drive, in cell order; the track carrying it)."""
    external = cell.external
    if external is None:
        return [], None
    mount = external.mount(robot)
    track = external.mechanism(mount.mechanism) if mount is not None and mount.kind == "robot" else None
    return [m for m in external.mechanisms if m.on is None and (m.kind != "track" or m is track)], track


def _choose(cell: ir.Cell | None, robot: str, used: int, vendor: str) -> tuple[tuple[Mechanism, ...], str]:
    """(the mechanisms whose axes take slots 1..`used`, or () with the reason why none can)."""
    if cell is None or cell.external is None:
        return (), "the cell declares no track or positioner (give --cell with the one that does)"
    candidates, track = _drivable(cell, robot)
    if vendor in ("fanuc", "inform"):  # the arm group's axes (a track: TP E1, INFORM BC) first, then the positioners
        candidates.sort(key=lambda m: m.kind != "track")
    fits = [combo for n in range(1, len(candidates) + 1) for combo in combinations(candidates, n)
            if (sum(len(m.axes) for m in combo) == used or vendor == "krl" and sum(len(m.axes) for m in combo) > used)
            and (track is None or track in combo)]
    if fits and vendor == "krl":  # KRL: the fewest axes that take every slot with a value not 0
        fits = [f for f in fits if sum(len(m.axes) for m in f) == min(sum(len(m.axes) for m in g) for g in fits)]
    if len(fits) == 1:
        return fits[0], ""
    names = ", ".join(f"'{m.name}' ({len(m.axes)})" for m in candidates) or "none"
    why = "no choice" if not fits else "more than one choice"
    return (), f"{used} external-axis slot(s) written; of the cell's mechanisms {names} {why} fills them"


def _slots_of(move: Move, named: Mapping[str, tuple[float | None, ...]]) -> tuple[float | None, ...]:
    """A move's slot values: its own, else those of the declared target it names."""
    return move.slots or named.get(rmot_name(move.target_name) if move.target_name else "", ())


def _stated_order(doc: Document, cell: ir.Cell | None, chosen: tuple[Mechanism, ...],
                  span_of: Callable[[Where], Span]) -> tuple[tuple[Mechanism, ...], str]:
    """RAPID's eax_a.. and KRL's E1.. take the driven mechanisms' axes in the order the
    controller's machine data gives them (rmot's: the program's `with` order), which the slots
    do not show: the order the files' own header states (`eax_a = pos.1:`, `E1 = rail:`, as the
    backends write their machine-data checklist), or none (W523)."""
    pattern = r"(?m)^[ \t]*![ \t]+eax_([a-f]) = ([\w.]+):" if doc.vendor == "rapid" else r"(?m)^[ \t]*;[ \t]+E([1-6]) = ([\w.]+):"
    stated: dict[int, str] = {}
    for c in doc.counts:
        for slot, axis in re.findall(pattern, span_of(Where(c.path, 1)).file.text):
            stated.setdefault("abcdef".index(slot) if doc.vendor == "rapid" else int(slot) - 1, axis)
    by_axis = {a.name: m for m in chosen for a in m.axes}
    order = [by_axis.get(stated[k]) for k in sorted(stated)]
    mechanisms = tuple(dict.fromkeys(m for m in order if m is not None))
    laid_out = [a.name for m in mechanisms for a in m.axes]
    if set(mechanisms) == set(chosen) and laid_out == [stated[k] for k in sorted(stated)] and sorted(stated) == list(range(len(laid_out))):
        return mechanisms, ""
    names = ", ".join(f"'{m.name}'" for m in chosen)
    return (), (f"the slots take the axes of {names} in an order the controller's machine data sets and the files "
                "do not state (rmot writes it in the header: `eax_a = NAME:` / `E1 = NAME:`)")


def _used(doc: Document, named: Mapping[str, tuple[float | None, ...]]) -> int:
    """How many slots the files use: the last slot any target gives a value (KRL declares all
    six E1..E6, 0 where no axis takes the slot: the last one not 0)."""
    slots = [_slots_of(s, named) for r in doc.routines for s in walk(r.body) if isinstance(s, Move)]
    return max((k + 1 for values in slots for k, v in enumerate(values)
                if v is not None and (doc.vendor != "krl" or v != 0)), default=0)


def _via_slots(doc: Document, via: str | None) -> tuple[float | None, ...] | None:
    """The slots of the target a circular move's via names (its first word), None if unknown."""
    m = re.match(r"\w+", via or "")
    target: Target | None = {rmot_name(t.name): t for t in doc.targets}.get(m.group(0)) if m else None
    return target.slots if target is not None else None


def _bodies(body: tuple[Stmt, ...], fn: Callable[[tuple[Stmt, ...]], tuple[Stmt, ...]]) -> tuple[Stmt, ...]:
    """`body` with `fn` applied to it and to every block's body inside it."""
    out: list[Stmt] = []
    for s in fn(body):
        if isinstance(s, If):
            s = replace(s, then=_bodies(s.then, fn), orelse=_bodies(s.orelse, fn))
        elif isinstance(s, (While, For)):
            s = replace(s, body=_bodies(s.body, fn))
        elif isinstance(s, WaitIn) and s.orelse:
            s = replace(s, orelse=_bodies(s.orelse, fn))
        out.append(s)
    return tuple(out)


def _absorb_coord(doc: Document, named: Mapping[str, tuple[float | None, ...]],
                  span_of: Callable[[Where], Span]) -> Document:
    """A TP linear or circular move followed by its `COORD` option (kept by the reader as the
    comment `!COORD ;`, W517), the option dropped: in UFRAME 0 the move marked coordinated (its
    frame COORD_FRAME);
    in a user frame, where the positioner stands still during the move (its values those of the
    move before it in the block), the plain move, which follows the same path relative to a part
    that does not move; else the move kept native (W523): its path relative to a moving part is
    not one rmot reads in a user frame."""
    taken: set[tuple[str, int]] = set()
    diags: list[Diagnostic] = []
    kept: list[Where] = []
    was: dict[int, Move] = {}  # a move kept native here, by the native's id

    def absorb(body: tuple[Stmt, ...]) -> tuple[Stmt, ...]:
        out: list[Stmt] = []
        for s in body:
            prev = out[-1] if out else None
            if not (isinstance(s, Native) and s.text == "!COORD ;" and isinstance(prev, Move) and prev.kind != "joint"
                    and s.where == prev.where):
                out.append(s)
                continue
            taken.add((s.where.path, s.where.line))
            before = _move_before(out[:-1], was)
            if prev.frame == "base":
                out[-1] = replace(prev, frame=COORD_FRAME)
            elif not (before is not None and _slots_of(before, named) and
                      _slots_of(before, named) == _slots_of(prev, named)):
                span = span_of(prev.where)
                diags.append(Diagnostic(codes.AXES_KEPT, Severity.WARNING, "external-axis values must map to the cell's "
                                        "axes: a coordinated move (COORD) in a user frame, its positioner not known to "
                                        "stand still during it, follows a path relative to the moving part, which rmot "
                                        "reads only in UFRAME 0; kept native", span))
                kept.append(prev.where)
                out[-1] = _native(prev, "fanuc", span)
                was[id(out[-1])] = prev  # its axis values still end where the next move starts
        return tuple(out)

    if doc.vendor != "fanuc":
        return doc
    routines = tuple(replace(r, body=_bodies(r.body, absorb)) for r in doc.routines)
    others = tuple(d for d in doc.diagnostics if not (d.code == codes.MOTION_OPTION_KEPT and "`COORD`" in d.message
                                                      and d.span is not None and (d.span.file.path, d.span.start.line) in taken))
    counts = tuple(replace(c, imported=c.imported - sum(1 for w in kept if w.path == c.path),
                           native=c.native - sum(1 for path, _ in taken if path == c.path) + sum(1 for w in kept if w.path == c.path))
                   for c in doc.counts)
    return replace(doc, routines=routines, diagnostics=others + tuple(diags), counts=counts)


def _native(move: Move, vendor: str, span: Span) -> Native:
    """The move as a native statement: the statement as its reader keeps one (`Move.source`), else
    its source line (TP's without the line number)."""
    return Native(vendor, move.source or native_line(vendor, span.file.line_text(move.where.line)) or "move", move.where)


def _move_before(body: list[Stmt], was: Mapping[int, Move]) -> Move | None:
    """The last move of `body` (or one `was` kept native) where nothing after it can move the
    axes: outputs, waits and native lines that are no TP motion or call may stand between."""
    for s in reversed(body):
        if isinstance(s, Move) or id(s) in was:
            return s if isinstance(s, Move) else was[id(s)]
        if not isinstance(s, (SetOut, Pulse, Wait, WaitIn, Native)) or (
                isinstance(s, Native) and re.match(r"(?i)\s*(?:[JLCA]\s|CALL\b|RUN\b)", s.text)):
            return None
    return None


def _in_riding_frame(move: Move, doc: Document, chosen: tuple[Mechanism, ...], values: tuple[float | None, ...],
                     cell: ir.Cell | None, robot: str) -> Move | str:
    """A coordinated TP move (its targets in UFRAME 0, the controller's world: the robot base
    with the axes at home, ext_axes.fanuc_in_world) as the move in the cell's first frame riding
    on the positioner it drives, its target and via there at the move's axis values; or why not."""
    riding = [(m, k) for m, k in _offsets(chosen) if m.kind == "positioner"]
    external = cell.external if cell is not None else None
    mount = next((x for x in external.mounts if x.kind == "frame" and len(riding) == 1
                  and x.mechanism == riding[0][0].name), None) if external is not None else None
    by_name = {rmot_name(t.name): t.pose for t in doc.targets}
    points = [by_name.get(move.target)] + ([by_name.get(move.via or "")] if move.kind == "circular" else [])
    if mount is None or cell is None or external is None or move.frame != COORD_FRAME or any(p is None for p in points):
        return ("a coordinated move must name its positions in the robot's base coordinates and drive one "
                "positioner a frame of the cell rides on")
    at = [values] + ([_scaled_via(move, values, chosen)] if move.kind == "circular" else [])
    exprs = []
    for point, where in zip(points, at):
        si = {a.name: si_value(a.linear, v) for a, v in zip((a for m in chosen for a in m.axes), where)}
        mech = riding[0][0]
        frame = mech.flange(external.values_of(mech, si)) * mount.local
        # the controller's world: TP UFRAME 0 the robot base with the axes at home, INFORM
        # ROBOT coordinates the arm's base where its track stands
        base = (external.world(robot, si) if doc.vendor == "inform" else None) or cell.robot(robot).base
        exprs.append(pose_expr(frame.inverse() * base * point))  # type: ignore[operator]
    return replace(move, target=exprs[0], target_name=None, via=exprs[1] if len(exprs) > 1 else None,
                   frame=mount.body, pose=None)


def _from_pulses(values: tuple[float | None, ...], pulsed: tuple[bool, ...],
                 chosen: tuple[Mechanism, ...]) -> tuple[float | None, ...] | str:
    """Encoder pulses (an INFORM job's ///PULSE BC, EC) in mm or deg at each axis' declared
    `inform(pulses_per_...)`, a revolute axis without one at the backend's assumed scale
    (backends/inform_axes.py); why not where a linear axis declares none."""
    from rmot.backends.inform_axes import ASSUMED_PULSES_PER_DEG  # late: loads the backends only when this runs

    axes = [a for m in chosen for a in m.axes]
    out: list[float | None] = []
    for axis, v, pulse in zip(axes, values, pulsed):
        if not pulse:
            out.append(v)
            continue
        if axis.pulses is None and axis.linear:
            return f"'{axis.name}' is written in pulses but the cell declares no inform(pulses_per_mm=N) for it"
        out.append(None if v is None else v / (axis.pulses or ASSUMED_PULSES_PER_DEG))
    return tuple(out)


def _in_world(move: Move, doc: Document, cell: ir.Cell | None, robot: str) -> Move | str:
    """A TP move in UFRAME 0 of a robot on its rail: the controller's world is the robot base
    with every axis at home, fixed while the rail carries the arm (ext_axes.fanuc_in_world), so
    the move is in rmot's `frame world` at that base's pose, not in the arm's moving base."""
    if move.joints is not None and move.kind == "joint" and move.pose is None:
        return move  # joint values: no frame
    by_name = {rmot_name(t.name): t.pose for t in doc.targets}
    points = [by_name.get(move.target)] + ([by_name.get(move.via or "")] if move.kind == "circular" else [])
    if cell is None or any(p is None for p in points):
        return "a UFRAME 0 position of a robot on its rail must be a position of the program (it is in the world)"
    base = cell.robot(robot).base
    exprs = [pose_expr(base * p) for p in points]  # type: ignore[operator]
    return replace(move, target=exprs[0], target_name=None, via=exprs[1] if len(exprs) > 1 else None,
                   frame="world", pose=None)


def _scaled_via(move: Move, values: tuple[float | None, ...], chosen: tuple[Mechanism, ...]) -> tuple[float | None, ...]:
    """The axis values (mm, deg) where a coordinated arc's via is taught: its own where the job
    writes them (INFORM's via line), else the target's."""
    if not move.via_slots:
        return values
    scaled = _from_pulses(move.via_slots[:len(values)], move.slot_pulses, chosen)
    return values if isinstance(scaled, str) else scaled


def _offsets(chosen: tuple[Mechanism, ...]) -> list[tuple[Mechanism, int]]:
    """Each chosen mechanism with the index of its first slot."""
    out, k = [], 0
    for mech in chosen:
        out.append((mech, k))
        k += len(mech.axes)
    return out


def resolve_axes(doc: Document, cell: ir.Cell | None, robot: str, span_of: Callable[[Where], Span]) -> Document:
    """`doc` with each move's slot values as `ext(...)` on the cell's mechanisms, and `with`
    naming them; a move whose values cannot be mapped stays native (W523)."""
    original, doc = doc, absorb_move_ext_j(doc, _bodies)
    named = {rmot_name(t.name): t.slots for t in doc.targets}
    used = _used(doc, named)
    track = _drivable(cell, robot)[1] if cell is not None else None
    if doc.vendor == "krl" and track is not None and any(_slots_of(s, named) for r in doc.routines for s in walk(r.body)
                                                          if isinstance(s, Move)):
        used = max(used, len(track.axes))  # E1 0 everywhere: the track stands at 0, KRL writes 0 for no axis too
    placeholder = any(isinstance(s, Move) and (s.frame or "").startswith((EK_FRAME, COORD_FRAME))
                      for r in doc.routines for s in walk(r.body))
    if used == 0 and not placeholder:
        return original  # no axis values: a TP COORD stays the native option it was read as (W517)
    unconnected = _not_connected(doc, cell, robot, named, span_of)
    if unconnected is not None:
        return unconnected
    doc = _absorb_coord(doc, named, span_of)
    chosen, why = _choose(cell, robot, used, doc.vendor) if used else ((), "")
    if doc.vendor in ("rapid", "krl") and len(chosen) > 1:  # the slots' order over mechanisms: machine data
        chosen, why = _stated_order(doc, cell, chosen, span_of)
    mapper = _Mapper(doc, cell, robot, span_of, named, used, chosen, why)

    routines = tuple(replace(r, body=map_leaves(r.body, mapper.move)) for r in doc.routines)
    if any(isinstance(x, Move) and x.axes_only for r in routines for x in walk(r.body)):
        routines = mapper.axes_alone(routines)
    counts = tuple(FileCount(c.path, c.imported - mapper.moved.get(c.path, 0), c.native + mapper.moved.get(c.path, 0))
                   for c in doc.counts)
    return replace(doc, routines=routines, counts=counts, diagnostics=doc.diagnostics + tuple(mapper.diags),
                   mechanisms=tuple(m.name for m in chosen) if not why else ())


def _not_connected(doc: Document, cell: ir.Cell | None, robot: str, named: Mapping[str, tuple[float | None, ...]],
                   span_of: Callable[[Where], Span]) -> Document | None:
    """A RAPID program on a cell that declares no track or positioner (the stub cell included)
    whose every external-axis value is 0 (a generator's `[0,9E9,..]` for an arm alone, as KRL
    writes 0 for a slot no axis takes): the controller ignores the value of an axis not
    connected ("If the position is defined in the position data, although the axis is not
    connected, the value will be ignored": RAPID reference, extjoint), so the moves are read
    without them, W544 once per file at its first move with values. None otherwise: a value
    other than 0 places an axis the cell lacks (W523), and MoveExtJ moves axes that exist."""
    if doc.vendor != "rapid" or (cell is not None and _drivable(cell, robot)[0]):
        return None
    moves = [s for r in doc.routines for s in walk(r.body) if isinstance(s, Move)]
    given = [(m, values) for m in moves for values in (_slots_of(m, named), _via_slots(doc, m.via) or ())
             if any(v is not None for v in values)]
    if not given or any(m.axes_only for m in moves) or any(v not in (None, 0.0) for _, vs in given for v in vs):
        return None
    used = sorted({k for _, values in given for k, v in enumerate(values) if v is not None})
    slots = ", ".join(f"eax_{'abcdef'[k]}" for k in used)
    firsts = {m.where.path: m.where for m, _ in reversed(given)}
    diags = tuple(Diagnostic(codes.AXES_NOT_CONNECTED, Severity.WARNING,
                             f"every external-axis value the moves give is 0 ({slots}), which the controller ignores where no axis is connected "
                             "(RAPID reference, extjoint): the cell declares no track or positioner, so the moves are "
                             "read without them (give --cell with the track or positioner if the robot has one)",
                             span_of(w)) for w in sorted(firsts.values(), key=lambda w: (w.path, w.line)))
    return replace(doc, diagnostics=doc.diagnostics + diags)


class _Mapper:
    """Maps each move's slot values to the chosen mechanisms' `ext(...)` (`move`), collecting
    the W523 warnings and how many moves per file it kept native."""

    def __init__(self, doc: Document, cell: ir.Cell | None, robot: str, span_of: Callable[[Where], Span],
                 named: Mapping[str, tuple[float | None, ...]], used: int, chosen: tuple[Mechanism, ...], why: str) -> None:
        self.doc, self.cell, self.robot, self.span_of = doc, cell, robot, span_of
        self.named, self.used, self.chosen, self.why = named, used, chosen, why
        self.diags: list[Diagnostic] = []
        self.moved: dict[str, int] = {}

    def move(self, s: Stmt) -> Stmt:
        if not isinstance(s, Move):
            return s
        full = _slots_of(s, self.named)
        values = full[:self.used]
        frame = _ek_frame(s.frame, self.cell) if (s.frame or "").startswith(EK_FRAME) else s.frame
        if all(v is None for v in values) and not (s.frame or "").startswith((EK_FRAME, COORD_FRAME)) \
                and all(v is None or math.isfinite(v) for v in full):
            return s  # no axis values: the axes stay where they are
        problem = self.problem(s, full, values, frame)
        if not problem and any(s.slot_pulses):
            scaled = _from_pulses(values, s.slot_pulses, self.chosen)
            problem, values = (scaled, values) if isinstance(scaled, str) else ("", scaled)
        placed: Move | str = replace(s, frame=frame)
        if not problem and (frame or "").startswith(COORD_FRAME):
            placed = _in_riding_frame(s, self.doc, self.chosen, values, self.cell, self.robot)
            problem = placed if isinstance(placed, str) else ""
        elif not problem and self.doc.vendor == "fanuc" and frame == "base" and any(m.kind == "track" for m in self.chosen):
            placed = _in_world(s, self.doc, self.cell, self.robot)
            problem = placed if isinstance(placed, str) else ""
        if problem or isinstance(placed, str):
            return self.keep(s, problem)
        ext, k = [], 0
        for mech in self.chosen if any(v is not None for v in values) else ():
            ext.append((mech.name, _value_text(mech, tuple(v for v in values[k:k + len(mech.axes)] if v is not None))))
            k += len(mech.axes)
        return replace(placed, ext=tuple(ext))

    def problem(self, s: Move, full: tuple[float | None, ...], values: tuple[float | None, ...], frame: str | None) -> str:
        """Why the move's values cannot be mapped, or ""."""
        if frame is None and s.frame is not None:
            return "its base on an external kinematic (EK) is no frame of the cell riding on that mechanism"
        if (frame or "").startswith(COORD_FRAME) and all(v is None for v in values):
            return "a coordinated move must give the positioner's position (INFORM `+MOVJ ECn`)"
        if self.why and any(v is not None for v in values):
            return self.why
        if None in values:
            return f"the target leaves slot {values.index(None) + 1} of {self.used} unset"
        absurd = [v for v in full if v is not None and not (math.isfinite(v) and abs(v) <= ABSURD)]
        if absurd:
            return f"a value must be a finite number within +-{ABSURD:g} (got {absurd[0]:g})"
        via = s.via_slots or _via_slots(self.doc, s.via)
        if s.kind == "circular" and via not in (full, None, ()) and not (s.frame or "").startswith(COORD_FRAME):
            return "the circular move's via point has other axis values than its target (rmot's via has none)"
        return ""

    def axes_alone(self, routines: tuple[Routine, ...]) -> tuple[Routine, ...]:
        """Each axes-only move (RAPID MoveExtJ) as `move axes` of the mechanism it moves (axes_only.py)."""
        before = len(self.diags)

        def values_of(m: Move) -> tuple[float | None, ...]:
            return _slots_of(m, self.named)[:self.used]

        out = tuple(replace(r, body=_bodies(r.body, lambda b: one_mechanism(b, self.chosen, values_of, self.span_of,
                                                                             self.diags))) for r in routines)
        for d in self.diags[before:]:
            path = d.span.file.path if d.span is not None else ""
            self.moved[path] = self.moved.get(path, 0) + 1
        return out

    def keep(self, s: Move, problem: str) -> Native:
        """The move kept native, with W523 at its line."""
        span = self.span_of(s.where)
        self.diags.append(Diagnostic(codes.AXES_KEPT, Severity.WARNING,
                                     f"external-axis values must map to the cell's axes: {problem}; kept native", span))
        self.moved[s.where.path] = self.moved.get(s.where.path, 0) + 1
        return _native(s, self.doc.vendor, span)
