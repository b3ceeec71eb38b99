"""Procs: argument binding with type checks, and the recursion check (a pass of its own).

Parameter types: pose, joints, target (pose or joints), number, length, angle, time, speed,
angular_speed, accel, mass, ratio, bool, string. Arguments bind by position, then by name
(`pick(p=home)`); every parameter must be given exactly once. Arguments are evaluated in
the caller's scope; the body sees the proc's defining scope plus its parameters
(lexical scoping, as in RAPID).

Recursion (direct or through other procs) is an error even when the proc is never called:
inlining could not terminate. It is reported at the call that closes the cycle, with the
chain as notes.
"""

from __future__ import annotations

from rmot.compiler import codes
from rmot.compiler.passes.context import Entry, Reporter, Scope
from rmot.compiler.passes.evaluate import eval_expr, expect_quantity, match_args
from rmot.compiler.passes.state import FrontendState
from rmot.compiler.passes.values import (
    article,
    ACCEL, ANGLE, ANGULAR_SPEED, DIMENSIONLESS, LENGTH, MASS, RATIO, SPEED, TIME, BoolV, JointsV,
    PoseV, StringV, Value, type_name,
)
from rmot.lang import ast

__all__ = ["PARAM_TYPES", "bind_call", "check_recursion"]

PARAM_TYPES: dict[str, object] = {
    "pose": PoseV, "joints": JointsV, "target": (PoseV, JointsV), "bool": BoolV, "string": StringV,
    "number": DIMENSIONLESS, "length": LENGTH, "angle": ANGLE, "time": TIME, "speed": SPEED,
    "angular_speed": ANGULAR_SPEED, "accel": ACCEL, "mass": MASS, "ratio": RATIO,
}


def _check_type(v: Value | None, type_: str, what: str, span: object, rep: Reporter) -> bool:
    wanted = PARAM_TYPES[type_]
    if v is None:
        return False
    if isinstance(wanted, tuple) and isinstance(wanted[0], int):
        return expect_quantity(v, wanted, what, span, rep) is not None  # type: ignore[arg-type]
    if isinstance(v, wanted):  # type: ignore[arg-type]
        return True
    rep.error(codes.WRONG_TYPE, f"{what} must be {article(type_)} (got {article(type_name(v))})", span)  # type: ignore[arg-type]
    return False


def bind_call(entry: Entry, call: ast.CallStmt, scope: Scope, rep: Reporter) -> Scope | None:
    """The scope the proc body runs in, or None after reporting an argument problem."""
    decl: ast.ProcDecl = entry.value
    names = tuple(p.name.name for p in decl.params)
    note = ((f"'{decl.name.name}' is defined here", decl.name.span),)
    n_pos = sum(1 for a in call.args if a.name is None)
    if len(call.args) != len(names) and n_pos == len(call.args):
        rep.error(codes.ARITY, f"{decl.name.name}() must have {len(names)} argument{'s' * (len(names) != 1)} "
                  f"(got {len(call.args)})", call.span, note)
        return None
    bound = match_args(call.args, names, decl.name.name, call.span, rep, required=len(names))
    if bound is None:
        return None
    inner = Scope(entry.closure)
    ok = True
    for p in decl.params:
        type_ = p.type.name
        if type_ not in PARAM_TYPES:
            rep.unknown(type_, "parameter type", p.type.span, list(PARAM_TYPES))
            ok = False
            continue
        arg = bound[p.name.name]
        v = eval_expr(arg.value, scope, rep)
        if _check_type(v, type_, f"argument '{p.name.name}' of {decl.name.name}()", arg.span, rep):
            inner.names[p.name.name] = Entry("param", p.name.name, v, p.name.span)
        else:
            ok = False
    return inner if ok else None


def _calls(body: tuple[ast.Stmt, ...]) -> list[ast.CallStmt]:
    out: list[ast.CallStmt] = []
    for s in body:
        if isinstance(s, ast.CallStmt):
            out.append(s)
        elif isinstance(s, (ast.For, ast.Repeat)):
            out += _calls(s.body)
        elif isinstance(s, ast.IfStmt):
            out += _calls(s.then) + _calls(s.otherwise)
    return out


def check_recursion(state: FrontendState) -> FrontendState:
    """Depth-first search over the call graph of every declared proc; report each cycle once."""
    procs: list[Entry] = state.extra.get("procs", [])
    rep = state.reporter
    done: set[int] = set()

    def visit(entry: Entry, path: list[tuple[Entry, ast.CallStmt | None]]) -> None:
        if id(entry) in done:
            return
        for call in _calls(entry.value.body):
            callee = entry.closure.lookup(call.name.name) if entry.closure is not None else None
            if callee is None or callee.kind != "proc":
                continue
            on_path = [id(e) for e, _ in path]
            if id(callee) in on_path:
                cycle = path[on_path.index(id(callee)):]
                chain = " -> ".join(e.name for e, _ in cycle) + f" -> {callee.name}"
                notes = tuple((f"'{e.name}' calls '{c.name.name}' here", c.span) for e, c in
                              zip([x for x, _ in cycle], [c for _, c in cycle[1:]]) if c is not None)
                rep.error(codes.RECURSION, f"proc '{callee.name}' must not call itself (got {chain})", call.span, notes)
                continue
            visit(callee, [*path, (callee, call)])
        done.add(id(entry))

    for entry in procs:
        visit(entry, [(entry, None)])
    return state
