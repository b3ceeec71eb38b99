"""A stable text dump and a JSON form of the IR (for `rmot ir`, golden tests and tooling).

Text: one line per declaration or instruction, SI values with at most 6 decimals, poses
as [x y z | qw qx qy qz], each instruction's uid first and its source line:col last (no
paths, so dumps compare across machines). Same IR -> byte-identical text.
JSON: every dataclass as an object with a "type" (its class name), enums by name, poses
as {"position": [...], "quaternion": [...]}, spans as {"file", "line", "col"}.
"""

from __future__ import annotations

import dataclasses
import json
from enum import Enum
from collections.abc import Callable
from typing import Any

from rmot.lang import ir, ir_tree
from rmot.lang.source import Span
from rmot.lang.model_spec import model_name

__all__ = ["dump_cell", "dump_program", "to_json", "to_jsonable"]


def _f(x: float) -> str:
    text = f"{x:.6f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def _pose(p: ir.Pose) -> str:
    return "[" + " ".join(_f(c) for c in p.position) + " | " + " ".join(_f(c) for c in p.quaternion) + "]"


def _geometry(g: ir.Geometry | None) -> str:
    if g is None:
        return "none"
    if isinstance(g, ir.Box):
        return "box(" + " ".join(_f(c) for c in g.size) + ")"
    if isinstance(g, ir.Cylinder):
        return f"cylinder(r={_f(g.radius)} h={_f(g.height)})"
    if isinstance(g, ir.Sphere):
        return f"sphere(r={_f(g.radius)})"
    if isinstance(g, ir.Capsule):
        return f"capsule(r={_f(g.radius)} length={_f(g.length)})"
    return f"mesh({g.path.rsplit('/', 1)[-1]!r} scale={_f(g.scale)})"


def _at(span: Span | None, main: str) -> str:
    """`  @line:col`, with the file's name when it is not the program's own file (`main`)."""
    if span is None:
        return ""
    where = "" if span.path == main else span.path.replace("\\", "/").rsplit("/", 1)[-1] + ":"
    return f"  @{where}{span.start.line}:{span.start.col}"


def dump_cell(cell: ir.Cell) -> str:
    lines = [f"cell {cell.name}"]
    for r in cell.robots:
        ref = r.source.ref if r.source.kind is ir.RobotSourceKind.LIBRARY else r.source.ref.rsplit("/", 1)[-1]
        if r.source.kind is ir.RobotSourceKind.MODEL:

            ref = model_name(r.source.ref)
        elif r.source.kind is ir.RobotSourceKind.URDF_CHAIN:
            path, base, tip, *maker = json.loads(r.source.ref.split(":", 1)[1])  # maker: urdf(controller=)
            ref = path.rsplit('/', 1)[-1] + ("" if base is None else f"[{base}..{tip}]") + "".join(f" controller={m}" for m in maker)
        lines.append(f"  robot {r.name} {r.source.kind.name.lower()}:{ref} dof={r.dof} base={_pose(r.base)}")
    for f in cell.fixtures:
        lines.append(f"  fixture {f.name} {_geometry(f.geometry)} at {_pose(f.pose)}")
    for t in cell.tools:
        lines.append(f"  tool {t.name} on {t.robot} {_geometry(t.geometry)} at {_pose(t.geometry_pose)} "
                     f"tcp={_pose(t.tcp)} mass={_f(t.mass)}" + (f" number={t.number}" if t.number is not None else ""))
    for fr in cell.frames:
        lines.append(f"  frame {fr.name} {_pose(fr.pose)}" + (f" number={fr.number}" if fr.number is not None else ""))
    for s in cell.io:
        owner = f" on {s.robot}" if s.robot else ""
        bits = f" bits={s.bits}" if s.bits is not None else ""
        lines.append(f"  io {s.direction.name.lower()}[{s.port}] {json.dumps(s.name)}{bits}{owner}")
    return "\n".join(lines)


def _target(t: ir.CartesianTarget | ir.JointTarget) -> str:
    name = f" name={t.name}" if t.name else ""
    if isinstance(t, ir.JointTarget):
        return "joints(" + " ".join(_f(v) for v in t.values) + ")" + name
    return f"{_pose(t.pose)} in_frame={_pose(t.in_frame)}{name}"


def _move(m: ir.Move) -> str:
    via = f" via {_target(m.via)}" if m.via is not None else ""
    mo = m.motion
    timing = f" time={_f(mo.duration)}" if mo.duration is not None else ""
    free = (f" free(clearance={_f(m.free.clearance)} samples={m.free.samples} budget={_f(m.free.budget)})"
            if m.free is not None else "")
    return (f"move {m.kind.name.lower()}{via} to {_target(m.target)} tool={m.tool.name or 'flange'} "
            f"frame={m.frame.name or 'base'} speed={_f(mo.tcp_speed)} accel={_f(mo.tcp_accel)} "
            f"joint_speed={_f(mo.joint_speed)} joint_accel={_f(mo.joint_accel)} zone={_f(mo.zone.radius)}{timing} "
            f"config={m.config}{free}")


def _cond(c: ir.RtExpr) -> str:
    if isinstance(c, ir.InputCondition):
        signal = f" ({c.signal})" if c.signal else ""
        return f"in[{c.port}] == {'on' if c.value else 'off'}{signal}"
    return rt_text(c)


def rt_text(e: ir.RtExpr) -> str:
    """A runtime expression in rmot's own syntax, fully parenthesised."""
    if isinstance(e, ir.Const):
        if e.type is ir.ValueType.BOOL:
            return "on" if e.value else "off"
        return str(e.value) if e.type is ir.ValueType.INT else repr(float(e.value))
    if isinstance(e, ir.VarRef):
        return e.name
    if isinstance(e, ir.AnalogInput):
        return f"ain[{e.port}]"
    if isinstance(e, ir.GroupInput):
        return f"gin[{e.port}]"
    if isinstance(e, ir.OutputRead):
        return f"out[{e.port}]"
    if isinstance(e, ir.InputCondition):
        return f"in[{e.port}] == {'on' if e.value else 'off'}"
    if isinstance(e, ir.Arith):
        return f"({rt_text(e.left)} {e.op} {rt_text(e.right)})"
    if isinstance(e, ir.Compare):
        return f"({rt_text(e.left)} {e.op.value} {rt_text(e.right)})"
    if isinstance(e, ir.Logic):
        return "(" + f" {e.op} ".join(rt_text(x) for x in e.operands) + ")"
    if isinstance(e, ir.Not):
        return f"not {rt_text(e.operand)}"
    raise TypeError(f"rt_text: {type(e).__name__} is no runtime expression")


def _signal(s: str | None) -> str:
    return f" ({s})" if s else ""


def _timeout(t: float | None) -> str:
    return f" timeout {_f(t)}" if t is not None else ""


# One line per instruction kind: its text after `#uid ` and before the source location.
_HEADS: dict[type, Callable[[Any], str]] = {
    ir.Move: _move,
    ir.SetDigital: lambda i: f"set out[{i.port}] = {'on' if i.value else 'off'}{_signal(i.signal)}",
    ir.SetAnalog: lambda i: f"set aout[{i.port}] = {_f(i.value)}{_signal(i.signal)}",
    ir.Pulse: lambda i: f"pulse out[{i.port}] for {_f(i.duration)}{_signal(i.signal)}",
    ir.WaitTime: lambda i: f"wait {_f(i.duration)}",
    ir.WaitInput: lambda i: f"wait until {_cond(i.condition)}{_timeout(i.timeout)}",
    ir.Sync: lambda i: f"sync {i.name}",
    ir.Native: lambda i: f"native {i.vendor} {json.dumps(i.text)}",
    ir.If: lambda i: f"if {_cond(i.condition)}",
    ir.ProcCall: lambda i: f"call {i.proc}({', '.join(i.args)})",
    ir.Attach: lambda i: f"attach {i.part} (load {_f(i.load)} kg)",
    ir.Detach: lambda i: f"detach {i.part} (load {_f(i.load)} kg)",
    ir.VarDecl: lambda i: f"var {i.name}: {i.type.value} = {rt_text(i.init)}",
    ir.Assign: lambda i: f"{i.name} = {rt_text(i.value)}",
    ir.Loop: lambda i: (f"for {i.var} in {i.first} .. {i.last}" if i.var is not None
                        else f"repeat {i.last}")
    + f" ({len(i.iterations)} iterations)",
    ir.While: lambda i: f"while {_cond(i.condition)}",
    ir.WaitCondition: lambda i: f"wait until {_cond(i.condition)}{_timeout(i.timeout)}",
    ir.Stop: lambda i: "stop",
}


# The label above each body `ir_tree.children` gives (None: the body follows unlabelled).
_LABELS: dict[type, Callable[[Any], tuple[str | None, ...]]] = {
    **{kind: lambda i: () for kind in ir_tree.LEAVES},
    ir.If: lambda i: ("then:", "else:"),
    ir.ProcCall: lambda i: (None,),
    ir.While: lambda i: (None,),
    ir.Loop: lambda i: tuple(f"{i.var or 'round'} = {it.value}:" for it in i.iterations),
    ir.WaitInput: lambda i: ("on timeout:",) if i.on_timeout else (),
    ir.WaitCondition: lambda i: ("on timeout:",) if i.on_timeout else (),
}
ir_tree.require_kinds("compiler/ir_dump._HEADS", _HEADS)
ir_tree.require_kinds("compiler/ir_dump._LABELS", _LABELS)


def _instr(i: ir.Instr, indent: str, out: list[str], main: str) -> None:
    out.append(f"{indent}#{i.uid} " + ir_tree.handler(_HEADS, i)(i) + _at(i.span, main))
    for label, body in zip(ir_tree.handler(_LABELS, i)(i), ir_tree.children(i)):
        if label is not None:
            out.append(f"{indent}  {label}")
        inner = indent + ("    " if label is not None else "  ")
        for j in body:
            _instr(j, inner, out, main)


def dump_program(prog: ir.Program) -> str:
    """The whole program: its cell, then each task's instructions."""
    main = prog.span.path if prog.span is not None else ""
    out = [f"program {prog.name}", dump_cell(prog.cell)]
    for t in prog.tasks:
        out.append(f"task {t.name} on {t.robot}")
        for i in t.body:
            _instr(i, "  ", out, main)
    return "\n".join(out) + "\n"


_ONLY_WHEN_SET = frozenset({"external", "min_duration", "ext", "axes_only", "coordinated"})


def to_jsonable(x: Any) -> Any:
    if isinstance(x, Span):
        return {"file": x.path, "line": x.start.line, "col": x.start.col}
    if isinstance(x, ir.Pose):
        return {"position": list(x.position), "quaternion": list(x.quaternion)}
    if isinstance(x, Enum):
        return x.name.lower()
    if dataclasses.is_dataclass(x) and not isinstance(x, type):
        obj: dict[str, Any] = {"type": type(x).__name__}
        for f in dataclasses.fields(x):
            value = getattr(x, f.name)
            if f.name in _ONLY_WHEN_SET and value == f.default:  # external axes: only in a cell that has them
                continue
            if value is not None or f.name not in ("span", "free"):  # a Move's `free`: only on `move free`
                obj[f.name] = to_jsonable(value)
        return obj
    if isinstance(x, (tuple, list)):
        return [to_jsonable(v) for v in x]
    return x


def to_json(prog: ir.Program | ir.Cell) -> str:
    return json.dumps(to_jsonable(prog), indent=2, ensure_ascii=False) + "\n"
