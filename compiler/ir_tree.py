"""The nesting of IR instructions, in one place (issue #15): which instruction holds which bodies.

`children(instr)` gives the instruction lists an instruction holds, in execution order (If:
then, otherwise; ProcCall and While: body; Loop: each iteration's body; WaitInput and
WaitCondition: the timeout branch); `rebuilt(instr, bodies)` is the same instruction with new
ones. An instruction kind this module does not know raises TypeError: a walker never skips a
node kind silently. `iteration_paths(body)` maps each instruction's uid to the loop iterations
it lies in, for messages that name the iteration (`layer = 2, row = 1, col = 0`).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterator

from rmot.compiler import ir

__all__ = [
    "LEAVES",
    "bind_loop_variable",
    "children",
    "describe_iteration",
    "iteration_paths",
    "rebuilt",
    "unroll_loops",
    "walk_with_paths",
]

# instructions that hold no other instruction
LEAVES: tuple[type, ...] = (
    ir.Move,
    ir.SetDigital,
    ir.SetAnalog,
    ir.Pulse,
    ir.WaitTime,
    ir.Sync,
    ir.Native,
    ir.Attach,
    ir.Detach,
    ir.VarDecl,
    ir.Assign,
    ir.Stop,
)
# one step of an iteration path: (loop uid, loop variable or None for `repeat`, value)
Step = tuple[int, "str | None", int]


def children(instr: ir.Instr) -> tuple[tuple[ir.Instr, ...], ...]:
    if isinstance(instr, LEAVES):
        return ()
    if isinstance(instr, ir.If):
        return (instr.then, instr.otherwise)
    if isinstance(instr, (ir.ProcCall, ir.While)):
        return (instr.body,)
    if isinstance(instr, ir.Loop):
        return tuple(it.body for it in instr.iterations)
    if isinstance(instr, (ir.WaitInput, ir.WaitCondition)):
        return (instr.on_timeout,)
    raise TypeError(
        f"ir_tree: instruction kind {type(instr).__name__} is not known (add it to ir_tree)"
    )


def rebuilt(
    instr: ir.Instr, bodies: tuple[tuple[ir.Instr, ...], ...], **changes: object
) -> ir.Instr:
    """`instr` with the bodies `children` gave replaced by `bodies` (same count), plus `changes`."""
    if isinstance(instr, ir.If):
        changes.update(then=bodies[0], otherwise=bodies[1])
    elif isinstance(instr, (ir.ProcCall, ir.While)):
        changes["body"] = bodies[0]
    elif isinstance(instr, ir.Loop):
        changes["iterations"] = tuple(
            dataclasses.replace(it, body=b) for it, b in zip(instr.iterations, bodies)
        )
    elif isinstance(instr, (ir.WaitInput, ir.WaitCondition)):
        changes["on_timeout"] = bodies[0]
    else:
        children(instr)  # raises for an unknown kind
    return dataclasses.replace(instr, **changes) if changes else instr  # type: ignore[arg-type]


def walk_with_paths(
    body: tuple[ir.Instr, ...], path: tuple[Step, ...] = ()
) -> Iterator[tuple[ir.Instr, tuple[Step, ...]]]:
    """Every instruction in source order with the loop iterations it lies in (outermost first)."""
    for instr in body:
        yield instr, path
        if isinstance(instr, ir.Loop):
            for it in instr.iterations:
                yield from walk_with_paths(it.body, path + ((instr.uid, instr.var, it.value),))
        else:
            for sub in children(instr):
                yield from walk_with_paths(sub, path)


def iteration_paths(body: tuple[ir.Instr, ...]) -> dict[int, tuple[Step, ...]]:
    """uid -> the iterations (loop uid, variable, value) it lies in; only uids inside a loop."""
    return {instr.uid: path for instr, path in walk_with_paths(body) if path}


def describe_iteration(path: tuple[Step, ...]) -> str:
    """`layer = 2, row = 1, col = 0` (a `repeat` round is `round 3 of repeat`, counted from 1)."""
    return ", ".join(
        f"{var} = {value}" if var is not None else f"repeat round {value + 1}"
        for _, var, value in path
    )


def bind_loop_variable(body: tuple[ir.Instr, ...], name: str, value: int) -> tuple[ir.Instr, ...]:
    """`body` (one Loop iteration) with the loop variable `name` replaced by the constant `value`
    in every runtime expression: what a backend writes when it unrolls the iterations."""
    const = ir.Const(value, ir.ValueType.INT)

    def expr(e: ir.RtExpr) -> ir.RtExpr:
        if isinstance(e, ir.VarRef):
            return const if e.name == name else e
        if isinstance(e, ir.Arith):
            return _folded(dataclasses.replace(e, left=expr(e.left), right=expr(e.right)))
        if isinstance(e, ir.Compare):
            return dataclasses.replace(e, left=expr(e.left), right=expr(e.right))
        if isinstance(e, ir.Logic):
            operands = tuple(expr(x) for x in e.operands)
            return dataclasses.replace(e, operands=operands)  # type: ignore[arg-type]
        if isinstance(e, ir.Not):
            return ir.Not(expr(e.operand))  # type: ignore[arg-type]
        return e  # Const, AnalogInput, InputCondition

    def instr(i: ir.Instr) -> ir.Instr:
        changes: dict[str, object] = {}
        if isinstance(i, (ir.If, ir.While, ir.WaitCondition)):
            changes["condition"] = expr(i.condition)
        elif isinstance(i, ir.VarDecl):
            changes["init"] = expr(i.init)
        elif isinstance(i, ir.Assign):
            changes["value"] = expr(i.value)
        return rebuilt(i, tuple(tuple(instr(x) for x in sub) for sub in children(i)), **changes)

    return tuple(instr(i) for i in body)


def unroll_loops(body: tuple[ir.Instr, ...]) -> tuple[ir.Instr, ...]:
    """`body` with every Loop replaced by its iterations' instructions one after another (each
    with the loop variable bound to its value), at every depth: the IR as it was before loops
    stayed loops, for a consumer that writes no loops. uids and spans are kept."""
    out: list[ir.Instr] = []
    for instr in body:
        if isinstance(instr, ir.Loop):
            for it in instr.iterations:
                inner = (
                    bind_loop_variable(it.body, instr.var, it.value)
                    if instr.var is not None
                    else it.body
                )
                out.extend(unroll_loops(inner))
        else:
            out.append(rebuilt(instr, tuple(unroll_loops(sub) for sub in children(instr))))
    return tuple(out)


def _folded(e: ir.Arith) -> ir.RtExpr:
    """`e` computed when both operands are constants (a bound loop variable), else `e`."""
    if not (isinstance(e.left, ir.Const) and isinstance(e.right, ir.Const)) or (
        e.op == "/" and e.right.value == 0
    ):
        return e
    a, b = float(e.left.value), float(e.right.value)
    value = {"+": a + b, "-": a - b, "*": a * b, "/": a / b if b else 0.0}[e.op]
    return ir.Const(int(value) if e.type is ir.ValueType.INT else value, e.type)
