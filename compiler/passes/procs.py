"""Procs: argument binding with type checks, and the recursion check (a pass of its own).

Parameter types: pose, joints, target (pose or joints), number, length, angle, time, speed,
angular_speed, accel, mass, ratio, bool, string. Arguments bind by position, then by name
(`pick(p=home)`); every parameter must be given exactly once. Arguments are evaluated in
the caller's scope; the body sees the proc's defining scope plus its parameters
(lexical scoping, as in RAPID).

A proc that is never called is still checked for unknown names, proc names and parameter
types (its body cannot be lowered without arguments, so units and types are checked only
where it is called).

Recursion (direct or through other procs) is an error even when the proc is never called:
inlining could not terminate. It is reported at the call that closes the cycle, with the
chain as notes.
"""

from __future__ import annotations

from rmot.lang import check_codes as codes
from rmot.compiler.passes.context import Entry, Reporter, Scope
from rmot.compiler.passes.evaluate import eval_expr, expect_quantity, match_args
from rmot.compiler.passes.state import FrontendState
from rmot.compiler.passes.values import (
    article,
    ACCEL, ANGLE, ANGULAR_SPEED, DIMENSIONLESS, LENGTH, MASS, RATIO, SPEED, TIME, BoolV, JointsV,
    PoseV, StringV, Value, type_name,
)
from rmot.lang import ast
from rmot.lang.parse import RESERVED

__all__ = ["PARAM_TYPES", "bind_call", "check_recursion", "check_uncalled_procs"]

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
        elif isinstance(s, (ast.For, ast.Repeat, ast.While)):
            out += _calls(s.body)
        elif isinstance(s, ast.IfStmt):
            out += _calls(s.then) + _calls(s.otherwise)
        elif isinstance(s, ast.WaitUntil) and s.on_timeout:
            out += _calls(s.on_timeout)
    return out


def check_recursion(state: FrontendState) -> FrontendState:
    """Depth-first search over the call graph of every declared proc; report each cycle once."""
    procs = state.procs
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


_BUILTIN_NAMES = frozenset({"on", "off", "true", "false"})


def _names_in(e: object, out: list[ast.Name]) -> None:
    """Every Name an expression reads (not config words, not keyword-argument names)."""
    if isinstance(e, ast.Name):
        out.append(e)
    elif isinstance(e, ast.BinOp):
        _names_in(e.left, out)
        _names_in(e.right, out)
    elif isinstance(e, (ast.Neg,)):
        _names_in(e.operand, out)
    elif isinstance(e, ast.Attr):
        _names_in(e.obj, out)
    elif isinstance(e, (ast.Call, ast.Joints)):
        for a in e.args:
            _names_in(a.value, out)
    elif isinstance(e, ast.Vector):
        for a in e.items:
            _names_in(a.value, out)
    elif isinstance(e, (ast.Condition, ast.IoRef)):  # conditions
        _names_in(e.io.index if isinstance(e, ast.Condition) else e.index, out)
        if isinstance(e, ast.Condition):
            _names_in(e.value, out)
    elif isinstance(e, ast.Compare):
        _names_in(e.left, out)
        _names_in(e.right, out)
    elif isinstance(e, ast.Logic):
        for x in e.operands:
            _names_in(x, out)
    elif isinstance(e, ast.NotCond):
        _names_in(e.operand, out)


def _check_body(body: tuple[ast.Stmt, ...], known: set[str], scope: Scope, rep: Reporter) -> None:
    local = set(known)
    for s in body:
        if isinstance(s, (ast.TargetDecl, ast.ConstDecl, ast.FrameDecl)):
            _check_exprs([s.value], local, scope, rep)
            local.add(s.name.name)
        elif isinstance(s, ast.Move):
            mods = [m.value for m in s.modifiers if m.kind not in ("config", "tool", "frame")]
            _check_exprs([s.target, s.via, *mods], local, scope, rep)
        elif isinstance(s, ast.Setting) and s.kind not in ("tool", "frame"):
            _check_exprs([s.value], local, scope, rep)
        elif isinstance(s, (ast.SetIo, ast.Pulse)):
            _check_exprs([s.io.index, s.value if isinstance(s, ast.SetIo) else s.duration], local, scope, rep)
        elif isinstance(s, ast.WaitTime):
            _check_exprs([s.duration], local, scope, rep)
        elif isinstance(s, ast.WaitUntil):
            _check_exprs([s.condition, s.timeout], local, scope, rep)
            _check_body(s.on_timeout or (), local, scope, rep)
        elif isinstance(s, ast.For):
            _check_exprs([s.start, s.stop], local, scope, rep)
            _check_body(s.body, local | {s.var.name}, scope, rep)
        elif isinstance(s, ast.Repeat):
            _check_exprs([s.count], local, scope, rep)
            _check_body(s.body, local, scope, rep)
        elif isinstance(s, ast.IfStmt):
            _check_exprs([s.condition], local, scope, rep)
            _check_body(s.then, local, scope, rep)
            _check_body(s.otherwise, local, scope, rep)
        elif isinstance(s, ast.While):
            _check_exprs([s.condition], local, scope, rep)
            _check_body(s.body, local, scope, rep)
        elif isinstance(s, (ast.VarDecl, ast.AssignStmt)):
            _check_exprs([s.value], local, scope, rep)
            local.add(s.name.name)
        elif isinstance(s, ast.CallStmt):
            entry = scope.lookup(s.name.name)
            if (entry is None or entry.kind != "proc") and s.name.name not in RESERVED:  # `return()`: E008 already
                procs = [n for n in scope.visible() if (e := scope.lookup(n)) is not None and e.kind == "proc"]
                rep.unknown(s.name.name, "proc", s.name.span, procs)
            _check_exprs([a.value for a in s.args], local, scope, rep)


def _check_exprs(exprs: list[object], known: set[str], scope: Scope, rep: Reporter) -> None:
    names: list[ast.Name] = []
    for e in exprs:
        if e is not None:
            _names_in(e, names)
    for n in names:
        if n.name not in known and n.name not in _BUILTIN_NAMES and scope.lookup(n.name) is None:
            rep.unknown(n.name, "name", n.span, [*known, *scope.visible()])


def check_uncalled_procs(state: FrontendState) -> FrontendState:
    """Names in the bodies of procs no task called (called ones were checked by lowering), and
    W153 at each one the program's own file declares: nothing plans, verifies or writes it (a
    vendor file holds the routines its program calls), so an imported library of routines with
    no main of its own compiles to none of them, which the user is told. A library file's procs
    are for the programs that import it: none is warned of."""
    called = state.called_procs
    seen: set[int] = set()
    main = state.main
    own = main.path if main is not None and any(isinstance(s, ast.ProgramDecl) for s in main.module.body) else None
    for entry in state.procs:
        decl: ast.ProcDecl = entry.value
        if id(decl) in called or id(decl) in seen or entry.closure is None:
            continue
        seen.add(id(decl))
        if decl.span.path == own:
            state.reporter.warning(codes.PROC_NEVER_CALLED, f"proc '{decl.name.name}' is never called: it is checked, but "
                                   "not planned, verified or written to the controller files", decl.name.span)
        for p in decl.params:
            if p.type.name not in PARAM_TYPES:
                state.reporter.unknown(p.type.name, "parameter type", p.type.span, list(PARAM_TYPES))
        _check_body(decl.body, {p.name.name for p in decl.params}, entry.closure, state.reporter)
    return state
