"""Constant folding with dimensional analysis: AST expressions -> compile-time values in SI.

Every .rmot expression is known at compile time (runtime state lives only in `if`/`wait`
on inputs), so evaluation *is* the folding. Errors are reported once and the value is None
("poison"): callers pass None along without another message.

Choices (LANGUAGE.md is silent):
  * `a + b` needs equal dimensions; the result keeps a's unit for messages.
  * `*` and `/` combine dimensions (`r * 80mm` is a length, `100 mm / 2 s` a speed);
    on poses `*` composes. Division by zero is an error.
  * `on`/`true` and `off`/`false` are the two I/O levels unless a name shadows them.
  * `shift(p, x=, y=, z=)` moves p along its *reference* frame's axes (p * offset would
    move along p's own axes, a tool-frame offset).
  * `pose(...)` takes x y z rx ry rz by name or in that order; `q=(w, x, y, z)` instead of
    rx/ry/rz gives a quaternion (normalised; a zero quaternion is an error).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from rmot.lang import check_codes as codes, ir
from rmot.compiler.passes.context import Reporter, Scope
from rmot.compiler.passes.values import (
    article,
    ANGLE, DIMENSIONLESS, LENGTH, UNIT_TABLE, BoolV, Dim, JointsV, PoseV, Quantity, StringV, Value,
    VectorV, dim_name, example_unit, fmt_quantity, type_name,
)
from rmot.lang import ast
from rmot.lang.source import Span

__all__ = ["BOOL_NAMES", "eval_expr", "expect_bool", "expect_integer", "expect_pose", "expect_quantity", "match_args"]

BOOL_NAMES = {"on": True, "true": True, "off": False, "false": False}
_POSE_FIELDS = ("x", "y", "z", "rx", "ry", "rz")


def eval_expr(e: ast.Expr, scope: Scope, rep: Reporter) -> Value | None:
    """The value of `e` in SI units, or None after reporting why it has none."""
    handler = _EVAL.get(type(e))
    if handler is None and isinstance(e, (ast.IoRef, ast.Condition)):
        io = e if isinstance(e, ast.IoRef) else e.io
        index = io.index.value if isinstance(io.index, ast.Number) and io.index.unit is None else None
        port = f"{int(index)}" if index is not None and float(index).is_integer() else "..."
        rep.error(codes.IO_READ_NOT_CONSTANT, f"{io.kind}[{port}] is read by the controller while the program "
                  "runs: it must be used in a runtime expression (var, if, while, wait until), not in a "
                  "value rmot computes before the program runs", e.span)
        return None
    if handler is None:
        rep.error(codes.WRONG_TYPE, f"expression must be a value (got {type(e).__name__})", getattr(e, "span", None))
        return None
    value = handler(e, scope, rep)
    if isinstance(value, Quantity) and not math.isfinite(value.value):
        rep.error(codes.NOT_FINITE, "value must be a finite number (got "
                  f"{'infinity' if math.isinf(value.value) else 'not a number'}: the arithmetic overflows a 64-bit float)", e.span)
        return None
    if isinstance(value, Quantity) and abs(value.value) > MAX_MAGNITUDE:
        rep.error(codes.PHYSICAL_RANGE, f"value must be at most {MAX_MAGNITUDE:g} in size in SI units (got {value.value:.3g}); "
                  "no cell, time or speed is that large", e.span)
        return None
    return value


# Every quantity of a program, in SI units (m, s, rad, kg, ...), is at most this in size: a
# policy bound (not a physical constant) far above any cell (metres), cycle (hours) or mass,
# and far below where float arithmetic loses whole units or overflows.
MAX_MAGNITUDE = 1e9


def _neg(e: ast.Neg, scope: Scope, rep: Reporter) -> Value | None:
    v = eval_expr(e.operand, scope, rep)
    if v is None or isinstance(v, Quantity):
        return None if v is None else Quantity(-v.value, v.dim, v.unit, None if v.written is None else -v.written)
    rep.error(codes.WRONG_TYPE, f"operand of '-' must be a number or quantity (got {article(type_name(v))})", e.span)
    return None


def _vector(e: ast.Vector, scope: Scope, rep: Reporter) -> Value | None:
    """`(a, b, ...)`; with a unit, `(30, 90) deg`, the unit applies to the plain numbers in it."""
    items = tuple(eval_expr(a.value, scope, rep) for a in e.items)
    if any(i is None for i in items):
        return None
    if e.unit is not None:
        if e.unit not in UNIT_TABLE:  # reported by the parser (E007)
            return None
        factor, dim = UNIT_TABLE[e.unit]
        items = tuple(Quantity(v.value * factor, dim, e.unit, v.value)
                      if isinstance(v, Quantity) and v.unit is None and v.dim == DIMENSIONLESS else v for v in items)
    return VectorV(items)  # type: ignore[arg-type]


def _string(e: ast.String, scope: Scope, rep: Reporter) -> Value:
    return StringV(e.value)


def _number(e: ast.Number, scope: Scope, rep: Reporter) -> Quantity | None:
    if e.unit is None:
        return Quantity(e.value, DIMENSIONLESS, None, e.value)
    known = UNIT_TABLE.get(e.unit)
    if known is None:  # not silent: the parser reported this unit (E007, lang/_build.py) at the unit
        return None
    factor, dim = known
    return Quantity(e.value * factor, dim, e.unit, e.value)


def _name(e: ast.Name, scope: Scope, rep: Reporter) -> Value | None:
    entry = scope.lookup(e.name)
    if entry is None:
        if e.name in BOOL_NAMES:
            return BoolV(BOOL_NAMES[e.name])
        rep.unknown(e.name, "name", e.span, scope.visible())
        return None
    if entry.kind in ("proc", "tool"):
        rep.error(codes.WRONG_TYPE, f"'{e.name}' must be a value to be used here (got {article(entry.kind)})", e.span,
                  ((f"'{e.name}' is defined here", entry.span),))
        return None
    if entry.kind == "rtvar":  # a task variable's value is known only at runtime
        rep.error(codes.RT_IN_COMPILE_TIME,
                  f"var '{e.name}' must not be used here: a pose, target, speed, time or loop "
                  "bound "
                  "must be known when the program is compiled (the value of a var is known only at "
                  "runtime, so the compiler cannot bound or verify it)", e.span,
                  ((f"'{e.name}' is declared here", entry.span),))
        return None
    return entry.value  # type: ignore[no-any-return]


def _binop(e: ast.BinOp, scope: Scope, rep: Reporter) -> Value | None:
    a = eval_expr(e.left, scope, rep)
    b = eval_expr(e.right, scope, rep)
    if a is None or b is None:
        return None
    if isinstance(a, PoseV) and isinstance(b, PoseV) and e.op == "*":
        return PoseV(a.pose * b.pose)
    if not (isinstance(a, Quantity) and isinstance(b, Quantity)):
        rep.error(codes.WRONG_TYPE, f"operands of '{e.op}' must be numbers, quantities or (for '*') two poses "
                  f"(got {article(type_name(a))} and {article(type_name(b))})", e.span)
        return None
    if e.op in "+-":
        if a.dim != b.dim:
            rep.error(codes.MIXED_UNITS, f"operands of '{e.op}' must have the same dimension (got {fmt_quantity(a)}, "
                      f"{article(dim_name(a.dim))}, and {fmt_quantity(b)}, {article(dim_name(b.dim))})", e.span)
            return None
        value = a.value + b.value if e.op == "+" else a.value - b.value
        unit = a.unit or b.unit
        total = value / UNIT_TABLE[unit][0] if unit in UNIT_TABLE else value
        return Quantity(value, a.dim, unit, total)
    if e.op == "/" and b.value == 0:
        rep.error(codes.OUT_OF_RANGE, "divisor must not be zero (got 0)", e.right.span)
        return None
    sign = 1 if e.op == "*" else -1
    dim: Dim = tuple(x + sign * y for x, y in zip(a.dim, b.dim))  # type: ignore[assignment]
    value = a.value * b.value if e.op == "*" else a.value / b.value
    unit = _product_unit(a, b, e.op)
    written = value / UNIT_TABLE[unit][0] if unit in UNIT_TABLE and UNIT_TABLE[unit][1] == dim else None
    return Quantity(value, dim, unit, written)


def _product_unit(a: Quantity, b: Quantity, op: str) -> str | None:
    if b.dim == DIMENSIONLESS:
        return a.unit
    if a.dim == DIMENSIONLESS and op == "*":
        return b.unit
    combined = f"{a.unit or 1}{op}{b.unit or 1}"
    return combined if combined in UNIT_TABLE else None


def _attr(e: ast.Attr, scope: Scope, rep: Reporter) -> Value | None:
    v = eval_expr(e.obj, scope, rep)
    if v is None:
        return None
    field = e.name.name
    if isinstance(v, PoseV) and field in _POSE_FIELDS:
        if field in ("x", "y", "z"):
            m = v.pose.position[_POSE_FIELDS.index(field)]
            return Quantity(m, LENGTH, "mm", m * 1000)
        r = v.pose.rpy()[_POSE_FIELDS.index(field) - 3]
        return Quantity(r, ANGLE, "deg", math.degrees(r))
    if isinstance(v, JointsV) and field.startswith("j") and field[1:].isdigit():
        i = int(field[1:]) - 1
        if 0 <= i < len(v.values):
            return v.values[i]
    what = "x, y, z, rx, ry or rz" if isinstance(v, PoseV) else "j1, j2, ..."
    rep.error(codes.UNKNOWN_NAME, f"component of {article(type_name(v))} must be {what} (got '{field}')", e.name.span)
    return None


# --------------------------------------------------------------------------- checks


def expect_quantity(v: Value | None, dim: Dim, what: str, span: Span, rep: Reporter) -> float | None:
    """v's SI value if it has dimension `dim`; else a missing-unit / wrong-dimension error."""
    if v is None:
        return None
    if isinstance(v, Quantity):
        if v.dim == dim:
            return v.value
        if v.unit is None and v.dim == DIMENSIONLESS:
            rep.error(codes.MISSING_UNIT, f"{what} must be {example_unit(dim)} (got {fmt_quantity(v)} without a unit)", span)
            return None
        rep.error(codes.WRONG_DIMENSION, f"{what} must be {example_unit(dim)} (got {fmt_quantity(v)}, {article(dim_name(v.dim))})", span)
        return None
    rep.error(codes.WRONG_TYPE, f"{what} must be {example_unit(dim)} (got {article(type_name(v))})", span)
    return None


def expect_integer(v: Value | None, what: str, span: Span, rep: Reporter, minimum: int = 0) -> int | None:
    x = expect_quantity(v, DIMENSIONLESS, what, span, rep)
    if x is None:
        return None
    if x != int(x) or x < minimum:
        bound = f" >= {minimum}" if minimum > -(10**6) else ""
        rep.error(codes.OUT_OF_RANGE, f"{what} must be a whole number{bound} (got {x:g})", span)
        return None
    return int(x)


def expect_pose(v: Value | None, what: str, span: Span, rep: Reporter) -> ir.Pose | None:
    if v is None:
        return None
    if isinstance(v, PoseV):
        return v.pose
    rep.error(codes.WRONG_TYPE, f"{what} must be a pose (got {article(type_name(v))})", span)
    return None


def expect_bool(v: Value | None, what: str, span: Span, rep: Reporter) -> bool | None:
    if v is None:
        return None
    if isinstance(v, BoolV):
        return v.value
    rep.error(codes.WRONG_TYPE, f"{what} must be on or off (got {article(type_name(v))})", span)
    return None


# --------------------------------------------------------------------------- calls


def match_args(args: tuple[ast.Arg, ...], names: tuple[str, ...], func: str, span: Span, rep: Reporter,
               required: int = 0) -> dict[str, ast.Arg] | None:
    """Positional then keyword arguments onto `names`; unknown, repeated or missing ones are errors."""
    bound: dict[str, ast.Arg] = {}
    ok = True
    positional = [a for a in args if a.name is None]
    if len(positional) > len(names):
        rep.error(codes.ARITY, f"{func}() must have at most {len(names)} arguments (got {len(positional)})", span)
        return None
    for name, arg in zip(names, positional):
        bound[name] = arg
    for arg in args:
        if arg.name is None:
            continue
        key = arg.name.name
        if key not in names:
            rep.unknown(key, f"argument of {func}()", arg.name.span, list(names))
            ok = False
        elif key in bound:
            rep.error(codes.BAD_ARGUMENT, f"argument '{key}' of {func}() must be given once (got it twice)", arg.span)
            ok = False
        else:
            bound[key] = arg
    missing = [n for n in names[:required] if n not in bound]
    if missing:
        rep.error(codes.ARITY, f"{func}() must have argument '{missing[0]}' (got {len(args)} arguments)", span)
        return None
    return bound if ok else None


def _call(e: ast.Call, scope: Scope, rep: Reporter) -> Value | None:
    func = e.func.name
    if func == "pose":
        return _pose(e, scope, rep)
    if func == "inv":
        bound = match_args(e.args, ("p",), "inv", e.span, rep, required=1)
        if bound is None:
            return None
        p = expect_pose(eval_expr(bound["p"].value, scope, rep), "argument of inv()", bound["p"].span, rep)
        return None if p is None else PoseV(p.inverse())
    if func == "shift":
        return _shift(e, scope, rep)
    entry = scope.lookup(func)
    if entry is not None and entry.kind == "proc":
        rep.error(codes.WRONG_TYPE, f"proc '{func}' must be called as a statement (got it inside an expression)", e.span)
        return None
    rep.unknown(func, "function", e.func.span, ["pose", "inv", "shift"])
    return None


def _pose(e: ast.Call, scope: Scope, rep: Reporter) -> Value | None:
    bound = match_args(e.args, (*_POSE_FIELDS, "q"), "pose", e.span, rep)
    if bound is None:
        return None
    vals: dict[str, float] = {}
    ok = True
    for key in _POSE_FIELDS:
        if key in bound:
            dim = LENGTH if key in ("x", "y", "z") else ANGLE
            x = expect_quantity(eval_expr(bound[key].value, scope, rep), dim, f"pose field '{key}'", bound[key].span, rep)
            ok = ok and x is not None
            vals[key] = x or 0.0
    if not ok:
        return None
    if "q" not in bound:
        return PoseV(ir.Pose.from_xyz_rpy(*(vals.get(k, 0.0) for k in _POSE_FIELDS)))
    if any(k in bound for k in ("rx", "ry", "rz")):
        rep.error(codes.BAD_ARGUMENT, "pose() must have either q or rx/ry/rz (got both)", bound["q"].span)
        return None
    q = _quaternion(eval_expr(bound["q"].value, scope, rep), bound["q"].span, rep)
    if q is None:
        return None
    return PoseV(ir.Pose((vals.get("x", 0.0), vals.get("y", 0.0), vals.get("z", 0.0)), q))


def _quaternion(v: Value | None, span: Span, rep: Reporter) -> tuple[float, float, float, float] | None:
    if v is None:
        return None
    if not (isinstance(v, VectorV) and len(v.items) == 4 and all(isinstance(i, Quantity) and i.dim == DIMENSIONLESS for i in v.items)):
        rep.error(codes.WRONG_TYPE, f"pose field 'q' must be four numbers (w, x, y, z) (got {article(type_name(v))})", span)
        return None
    w, x, y, z = (i.value for i in v.items if isinstance(i, Quantity))  # all four are (checked above)
    n = math.hypot(w, x, y, z)  # no overflow for components near 1e200
    if n < 1e-12 or not math.isfinite(n):
        rep.error(codes.OUT_OF_RANGE, "pose field 'q' must not be the zero quaternion (got (0, 0, 0, 0))", span)
        return None
    q = (w / n, x / n, y / n, z / n)
    return q if q[0] >= 0 else (-q[0], -q[1], -q[2], -q[3])


def _shift(e: ast.Call, scope: Scope, rep: Reporter) -> Value | None:
    bound = match_args(e.args, ("p", "x", "y", "z"), "shift", e.span, rep, required=1)
    if bound is None:
        return None
    p = expect_pose(eval_expr(bound["p"].value, scope, rep), "first argument of shift()", bound["p"].span, rep)
    delta = []
    for key in ("x", "y", "z"):
        if key not in bound:
            delta.append(0.0)
            continue
        d = expect_quantity(eval_expr(bound[key].value, scope, rep), LENGTH, f"shift '{key}'", bound[key].span, rep)
        if d is None:
            return None
        delta.append(d)
    if p is None:
        return None
    pos = (p.position[0] + delta[0], p.position[1] + delta[1], p.position[2] + delta[2])
    return PoseV(ir.Pose(pos, p.quaternion))


def _joints(e: ast.Joints, scope: Scope, rep: Reporter) -> Value | None:
    """joints(...) [unit]: the unit applies to bare numbers; keyword form j1=, j2=, ... in any order."""
    keyed = [a for a in e.args if a.name is not None]
    if keyed and len(keyed) != len(e.args):
        rep.error(codes.BAD_ARGUMENT, "joints() must be all positional or all j1=, j2=, ... (got both)", e.span)
        return None
    order = list(e.args)
    if keyed:
        index = {}
        for a in keyed:
            name = a.name.name  # type: ignore[union-attr]
            if not (name.startswith("j") and name[1:].isdigit() and int(name[1:]) >= 1):
                rep.error(codes.BAD_ARGUMENT, f"joints() argument names must be j1, j2, ... (got '{name}')", a.span)
                return None
            index[int(name[1:])] = a
        if sorted(index) != list(range(1, len(index) + 1)):
            named = ", ".join(f"j{i}" for i in sorted(index))
            rep.error(codes.BAD_ARGUMENT, f"joints() must name j1 to j{len(index)} without gaps (got {named})", e.span)
            return None
        order = [index[i] for i in sorted(index)]
    values: list[Quantity] = []
    for a in order:
        v = eval_expr(a.value, scope, rep)
        if v is None:
            return None
        if not isinstance(v, Quantity):
            rep.error(codes.WRONG_TYPE, f"joint value must be an angle or a length (got {article(type_name(v))})", a.span)
            return None
        if v.unit is None and v.dim == DIMENSIONLESS:
            if e.unit is None:
                rep.error(codes.MISSING_UNIT, f"joint value must be an angle such as 90 deg (got {fmt_quantity(v)} without a unit; "
                          "write joints(...) deg to give them all one)", a.span)
                return None
            if e.unit not in UNIT_TABLE:  # reported by the parser (E007)
                return None
            factor, dim = UNIT_TABLE[e.unit]
            v = Quantity(v.value * factor, dim, e.unit, v.value)
        values.append(v)
    return JointsV(tuple(values), e.span)


_EVAL: dict[type, Callable[[Any, Scope, Reporter], Value | None]] = {
    ast.Number: _number, ast.Name: _name, ast.BinOp: _binop, ast.Neg: _neg, ast.Call: _call,
    ast.Joints: _joints, ast.Vector: _vector, ast.String: _string, ast.Attr: _attr,
}
