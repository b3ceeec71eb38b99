"""The semantic difference of two programs read back (`rmot diff A B`).

Targets are matched by name and compared by position (mm), orientation (the angle of the
relative rotation, deg), joint values (deg) and configuration; instructions are aligned per
routine (difflib's longest matching blocks over each instruction's kind and target, so an
inserted line does not shift every later comparison) and compared by speed, zone, time,
tool, frame and I/O value; a line kept native on both sides by the words that changed. The
data the moves use is compared too: each tool's TCP and mass, each frame's pose and each named
load by name, and the declarations kept as comments by their text (a re-taught TCP or user
frame moves every point the robot reaches). Every item names both places, `file:line`.
"""

from __future__ import annotations

import math
from difflib import SequenceMatcher

from rmot.backends.readers.model import (
    Call, Cond, Conds, Document, For, Grip, If, Move, Native, Pulse, SetOut, Stmt, Stop, Wait, WaitIn, While, leaves, walk,
)
from rmot.backends.readers.axes import slot_change
from rmot.backends.readers.model import Assign, FrameData, GroupIn, ToolData, VarDecl
from rmot.lang import ir

__all__ = ["diff_documents", "TOLERANCE_MM", "TOLERANCE_DEG"]

TOLERANCE_MM = 0.001  # what the vendors print (RAPID, KRL 3 decimals of a mm)
TOLERANCE_DEG = 0.001
TOLERANCE_KG = 0.0006  # the backends print masses to 3 decimals of a kg


def _angle_deg(a: ir.Pose, b: ir.Pose) -> float:
    dot = abs(sum(x * y for x, y in zip(a.quaternion, b.quaternion)))
    return math.degrees(2 * math.acos(min(1.0, dot)))


def _distance_mm(a: ir.Pose, b: ir.Pose) -> float:
    return 1000 * math.dist(a.position, b.position)


def _pose_change(a: ir.Pose | None, b: ir.Pose | None, ja: tuple[float, ...] | None,
                 jb: tuple[float, ...] | None) -> str | None:
    if a is not None and b is not None:
        d, r = _distance_mm(a, b), _angle_deg(a, b)
        if d > TOLERANCE_MM or r > TOLERANCE_DEG:
            return f"moved {d:.3f} mm, turned {r:.3f} deg"
    elif ja is not None and jb is not None:
        worst = max((abs(x - y) for x, y in zip(ja, jb)), default=0.0)
        if len(ja) != len(jb) or worst > TOLERANCE_DEG:
            joint = max(range(min(len(ja), len(jb))), key=lambda i: abs(ja[i] - jb[i]), default=0)
            return f"joints changed by up to {worst:.3f} deg (joint {joint + 1})"
    elif (a is None) != (b is None):
        return "changed between a pose and joint values"
    return None


def _targets(a: Document, b: Document) -> list[str]:
    out = []
    tb = {t.name.upper(): t for t in b.targets}
    ta = {t.name.upper(): t for t in a.targets}
    for key, t in ta.items():
        other = tb.get(key)
        if other is None:
            out.append(f"{t.where}: target {t.name} removed")
            continue
        change = _pose_change(t.pose, other.pose, t.joints, other.joints)
        if change:
            out.append(f"{t.where} -> {other.where}: target {t.name} {change}")
        axes_change = slot_change(a.vendor, t.slots, other.slots)
        if axes_change:
            out.append(f"{t.where} -> {other.where}: target {t.name} {axes_change}")
        if t.config != other.config and t.config is not None and other.config is not None:
            out.append(f"{t.where} -> {other.where}: target {t.name} configuration {t.config} -> {other.config}")
    out += [f"{t.where}: target {t.name} added" for key, t in tb.items() if key not in ta]
    return out


def _named_data(kind: str, xs: tuple[ToolData, ...] | tuple[FrameData, ...],
                ys: tuple[ToolData, ...] | tuple[FrameData, ...]) -> list[str]:
    """Each tool's TCP (in the flange frame) and mass, or each frame's pose (in the robot base),
    by name."""
    by_name = {y.name.upper(): y for y in ys}
    out = []
    for x in xs:
        y = by_name.get(x.name.upper())
        if y is None:
            out.append(f"{x.where}: {kind} {x.name} removed")
            continue
        out += _data_change(kind, x, y)
        if isinstance(x, ToolData) and isinstance(y, ToolData) and abs(x.mass - y.mass) > TOLERANCE_KG:
            out.append(f"{x.where} -> {y.where}: tool {x.name} mass {x.mass:g} kg -> {y.mass:g} kg")
    known = {x.name.upper() for x in xs}
    return out + [f"{y.where}: {kind} {y.name} added" for y in ys if y.name.upper() not in known]


def _data_change(kind: str, x: ToolData | FrameData, y: ToolData | FrameData) -> list[str]:
    """A tool's or frame's place changed, or it is set in one file and the controller's own in
    the other (whose value the files do not hold)."""
    where = f"{x.where} -> {y.where}: {kind} {x.name}"
    if x.controller != y.controller:
        own = [f"the controller's {c}" if c else "set in the file" for c in (x.controller, y.controller)]
        return [f"{where} {own[0]} -> {own[1]}"]
    change = _pose_change(x.tcp if isinstance(x, ToolData) else x.pose,
                          y.tcp if isinstance(y, ToolData) else y.pose, None, None)
    return [f"{where} {change}"] if change else []


def _loads(a: Document, b: Document) -> list[str]:
    """Each named load's mass and centre of mass (mm in the flange frame), by name."""
    lb = {name.upper(): (mass, cm, where) for name, mass, cm, where in b.loads}
    out = []
    for name, mass, cm, where in a.loads:
        other = lb.get(name.upper())
        if other is None:
            out.append(f"{where}: load {name} removed")
            continue
        moved = math.dist(cm, other[1])  # NaN where a TP schedule's centre is the controller's
        at = f"{where} -> {other[2]}: load {name}"
        if abs(mass - other[0]) > TOLERANCE_KG:
            out.append(f"{at} mass {mass:g} kg -> {other[0]:g} kg")
        if moved > TOLERANCE_MM:
            out.append(f"{at} centre of mass moved {moved:.3f} mm")
    known = {name.upper() for name, _, _, _ in a.loads}
    return out + [f"{where}: load {name} added" for name, _, _, where in b.loads if name.upper() not in known]


def _kept(a: Document, b: Document) -> list[str]:
    """The declarations and routines kept as comments, aligned by their text: one rmot does not
    read (a RAPID loaddata, a PERS num) still changes what the program does."""
    ka, kb = a.kept, b.kept
    out: list[str] = []
    matcher = SequenceMatcher(a=[k.text.split("=")[0] for k in ka], b=[k.text.split("=")[0] for k in kb],
                              autojunk=False)
    for op, i1, i2, j1, j2 in matcher.get_opcodes():
        if op == "equal" or (op == "replace" and i2 - i1 == j2 - j1):
            for i, j in zip(range(i1, i2), range(j1, j2)):
                out += _native_change(ka[i], kb[j], "kept line")
            continue
        out += [f"{ka[i].where}: removed kept line {ka[i].text}" for i in range(i1, i2)]
        out += [f"{kb[j].where}: added kept line {kb[j].text}" for j in range(j1, j2)]
    return out


def describe(s: Stmt) -> str:
    """What an instruction is, without the details a touch-up changes (the alignment key)."""
    if isinstance(s, Move):
        return f"move {s.kind} {s.target_name or s.target.split('(')[0]}"
    if isinstance(s, SetOut):
        return f"set {'aout' if s.analog else 'out'} {s.signal}"
    if isinstance(s, Pulse):
        return f"pulse {s.signal}"
    if isinstance(s, WaitIn):
        return f"wait until {_inputs(s.cond)}"
    if isinstance(s, (If, While)):
        return f"{type(s).__name__.lower()} {_inputs(s.cond)}"
    if isinstance(s, For):
        return f"for {s.var}"
    if isinstance(s, Call):
        return f"call {s.name}"
    if isinstance(s, Native):
        return f"native {s.text}"
    if isinstance(s, Grip):
        return f"{'attach' if s.take else 'detach'} {s.part}"
    if isinstance(s, (VarDecl, Assign)):
        return f"{'var' if isinstance(s, VarDecl) else 'assign'} {s.name}"
    return "stop" if isinstance(s, Stop) else "wait"


def _inputs(c: Cond | Conds) -> str:
    """The inputs a condition reads (the alignment key: a touch-up changes levels, not inputs)."""
    return " ".join(str(leaf.signal) for leaf in leaves(c))


def _levels(c: Cond | Conds | GroupIn) -> str:
    if isinstance(c, GroupIn):
        return f"gin {c.signal}"
    if isinstance(c, Cond):
        return "on" if c.on else "off"
    if c.op == "expr":
        return c.text
    if c.op == "logic":
        return c.text.format(*(_levels(p) for p in c.parts))
    parts = [_levels(p) if isinstance(p, Cond) else f"({_levels(p)})" for p in c.parts]
    return f"not {parts[0]}" if c.op == "not" else f" {c.op} ".join(parts)


def _details(s: Stmt) -> dict[str, str]:
    if isinstance(s, Move):
        return {"speed": f"{s.speed:g} mm/s" if s.speed is not None else f"{s.joint_pct or 100:g} %",
                "zone": "fine" if s.zone is None else f"{s.zone:g} mm",
                "time": "-" if s.time is None else f"{s.time:g} s", "tool": str(s.tool), "frame": str(s.frame),
                "target": s.target, "config": str(s.config)}
    if isinstance(s, SetOut):
        return {"value": f"{s.value:g}"}
    if isinstance(s, Pulse):
        return {"length": f"{s.seconds:g} s"}
    if isinstance(s, Wait):
        return {"time": f"{s.seconds:g} s"}
    if isinstance(s, (WaitIn, If, While)):
        timeout = getattr(s, "timeout", None)
        return {"level": _levels(s.cond), "timeout": "-" if timeout is None else f"{timeout:g} s"}
    if isinstance(s, For):
        return {"range": f"{s.first} .. {s.stop}"}
    if isinstance(s, (VarDecl, Assign)):
        return {"value": _levels(s.init if isinstance(s, VarDecl) else s.value)}
    return {}


def _native_change(x: Native, y: Native, what: str = "native line") -> list[str]:
    """A line kept native on both sides whose text changed: the words that differ, then the
    line (a touch-up of a move rmot cannot read, such as `CNT60` -> `CNT20`, is still named)."""
    if x.text == y.text:
        return []
    wa, wb = x.text.split(), y.text.split()
    words = [f"{' '.join(wa[i1:i2]) or '-'} -> {' '.join(wb[j1:j2]) or '-'}"
             for op, i1, i2, j1, j2 in SequenceMatcher(a=wa, b=wb, autojunk=False).get_opcodes() if op != "equal"]
    return [f"{x.where} -> {y.where}: {what} changed ({'; '.join(words)}): {y.text}"]


def _compare(x: Stmt, y: Stmt) -> list[str]:
    if isinstance(x, Native) and isinstance(y, Native):
        return _native_change(x, y)
    where = f"{x.where} -> {y.where}: {describe(x)}"
    dx, dy = _details(x), _details(y)
    out = [f"{where}: {k} {dx[k]} -> {dy[k]}" for k in dx if dx[k] != dy.get(k) and k != "target"]
    if isinstance(x, Move) and isinstance(y, Move):
        change = _pose_change(x.pose, y.pose, x.joints, y.joints) if x.target_name is None else None
        if change or (dx["target"] != dy["target"] and x.target_name == y.target_name and x.target_name is None):
            out.append(f"{where}: target {change or dx['target'] + ' -> ' + dy['target']}")
        elif dx["target"] != dy["target"]:
            out.append(f"{where}: target {dx['target']} -> {dy['target']}")
    return out


def _routine(ra: tuple[Stmt, ...], rb: tuple[Stmt, ...]) -> list[str]:
    fa, fb = walk(ra), walk(rb)
    out: list[str] = []
    matcher = SequenceMatcher(a=[describe(s) for s in fa], b=[describe(s) for s in fb], autojunk=False)
    for op, i1, i2, j1, j2 in matcher.get_opcodes():
        if op == "equal" or (op == "replace" and i2 - i1 == j2 - j1 and all(
                fa[i].__class__ is fb[j].__class__ for i, j in zip(range(i1, i2), range(j1, j2)))):
            for i, j in zip(range(i1, i2), range(j1, j2)):
                out += _compare(fa[i], fb[j])
            continue
        out += [f"{fa[i].where}: removed {describe(fa[i])}" for i in range(i1, i2)]
        out += [f"{fb[j].where}: added {describe(fb[j])}" for j in range(j1, j2)]
    return out


def diff_documents(a: Document, b: Document) -> list[str]:
    """Every difference, one line each (empty when the programs mean the same)."""
    out = _targets(a, b) + _named_data("tool", a.tools, b.tools) + _named_data("frame", a.frames, b.frames)
    out += _loads(a, b) + _kept(a, b)
    rb = {r.name.upper(): r for r in b.routines}
    ra = {r.name.upper(): r for r in a.routines}
    for key, r in ra.items():
        if key not in rb:
            out.append(f"{r.where}: routine {r.name} removed")
            continue
        out += _routine(r.body, rb[key].body)
    out += [f"{r.where}: routine {r.name} added" for key, r in rb.items() if key not in ra]
    return out
