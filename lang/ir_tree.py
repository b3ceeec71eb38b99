"""The nesting of IR instructions, in one place: which instruction holds which bodies.

`children(instr)` gives the instruction lists an instruction holds, in execution order (If:
then, otherwise; ProcCall and While: body; Loop: each iteration's body; WaitInput and
WaitCondition: the timeout branch); `rebuilt(instr, bodies)` is the same instruction with new
ones. An instruction kind this module does not know raises TypeError: a walker never skips a
node kind silently. `iteration_paths(body)` maps each instruction's uid to the loop iterations
it lies in, for messages that name the iteration (`layer = 2, row = 1, col = 0`).

`flow(instr)` is how those bodies run: a proc call's body once, a loop's iterations
once each in order, exactly one of an if's arms, a while's body zero or more times, a timeout
branch zero times or once. A pass that follows the program's paths (which syncs always run,
which move comes first, the move before each move, the parts held at a move) asks `flow` and
decides per `Runs`, never per instruction kind, so a new kind that holds bodies needs only its
line here. `walk(body)` is every instruction in source order at every depth. A pass that prints
or plans each kind its own way is a dispatcher instead: a table kind -> handler, checked
against `KINDS` (tests/core/test_ir_walks.py keeps hand-written walks out of the code).
"""

from __future__ import annotations

import dataclasses
import typing
from collections.abc import Iterable, Iterator, Mapping
from enum import Enum

from rmot.lang import ir

__all__ = [
    "KINDS",
    "LEAVES",
    "NESTING",
    "Runs",
    "bind_loop_variable",
    "children",
    "describe_iteration",
    "flow",
    "handler",
    "iteration_paths",
    "rebuilt",
    "require_kinds",
    "unroll_loops",
    "walk",
    "walk_bodies",
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


class Runs(Enum):
    """How the bodies an instruction holds run, each time the instruction runs."""

    LEAF = "holds no body"
    CALL = "its body once (a routine of its own)"
    ITERATIONS = "each body once, in order"
    ONE_OF = "exactly one of its bodies"
    REPEATED = "its body zero or more times"
    MAYBE = "its body zero times or once"

    @property
    def sure(self) -> bool:
        """Every instruction of the bodies runs whenever the instruction runs."""
        return self in (Runs.CALL, Runs.ITERATIONS)


# instructions that hold bodies, and how those run (`children` gives the bodies)
NESTING: dict[type, Runs] = {
    ir.If: Runs.ONE_OF,
    ir.ProcCall: Runs.CALL,
    ir.Loop: Runs.ITERATIONS,
    ir.While: Runs.REPEATED,
    ir.WaitInput: Runs.MAYBE,
    ir.WaitCondition: Runs.MAYBE,
}
# every instruction kind: a table keyed by kind (a printer, a planner) must cover these
KINDS: tuple[type, ...] = LEAVES + tuple(NESTING)
V = typing.TypeVar("V")
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


def flow(instr: ir.Instr) -> tuple[Runs, tuple[tuple[ir.Instr, ...], ...]]:
    """How `instr`'s bodies run, and the bodies (those of `children`, in the same order)."""
    bodies = children(instr)  # raises for a kind this module does not know
    if isinstance(instr, LEAVES):
        return Runs.LEAF, bodies
    for cls in type(instr).__mro__:
        if cls in NESTING:
            return NESTING[cls], bodies
    raise TypeError(f"ir_tree: {type(instr).__name__} holds bodies but has no NESTING entry")


def require_kinds(owner: str, table: Mapping[type, object]) -> None:
    """Raise TypeError unless `table` (a dispatcher: kind -> handler) has an entry for every
    instruction kind of KINDS; called where the table is built, so a kind added to the IR
    without a handler there fails at import, never as a silent default."""
    missing = [k.__name__ for k in KINDS if k not in table]
    if missing:
        raise TypeError(f"{owner}: no handler for instruction kind {', '.join(missing)} "
                        "(every kind of lang/ir_tree.KINDS needs one)")


def handler(table: Mapping[type, V], instr: ir.Instr) -> V:
    """`table`'s entry for `instr`'s kind or its nearest base (a subclass a backend adds)."""
    for cls in type(instr).__mro__:
        if cls in table:
            return table[cls]
    raise TypeError(f"no handler for instruction kind {type(instr).__name__}")


def walk(body: Iterable[ir.Instr]) -> Iterator[ir.Instr]:
    """Every instruction of `body` in source order, each before the bodies it holds."""
    for instr in body:
        yield instr
        for sub in children(instr):
            yield from walk(sub)


def walk_bodies(bodies: Iterable[tuple[ir.Instr, ...]]) -> Iterator[ir.Instr]:
    """`walk` over several bodies one after another (an if's arms, a loop's iterations)."""
    for body in bodies:
        yield from walk(body)


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
        return e  # Const, AnalogInput, GroupInput, OutputRead, InputCondition

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


def _check_tables() -> None:
    """KINDS is ir.Instr, each kind once: a leaf, or a kind with bodies and a Runs."""
    instr_kinds = set(typing.get_args(ir.Instr))
    both = set(LEAVES) & set(NESTING)
    missing = instr_kinds - set(KINDS)
    if both or missing or len(KINDS) != len(instr_kinds):
        names = sorted(c.__name__ for c in both | missing)
        raise TypeError(f"ir_tree: LEAVES and NESTING must name each ir.Instr kind once ({names})")


_check_tables()


def _folded(e: ir.Arith) -> ir.RtExpr:
    """`e` computed when both operands are constants (a bound loop variable), else `e`."""
    if not (isinstance(e.left, ir.Const) and isinstance(e.right, ir.Const)) or (
        e.op == "/" and e.right.value == 0
    ):
        return e
    a, b = float(e.left.value), float(e.right.value)
    value = {"+": a + b, "-": a - b, "*": a * b, "/": a / b if b else 0.0}[e.op]
    return ir.Const(int(value) if e.type is ir.ValueType.INT else value, e.type)
