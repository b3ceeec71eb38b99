"""Runtime expressions and conditions: ast conditions -> typed ir.RtExpr.

What the controller computes at runtime: task variables (`var`), digital and analog inputs,
arithmetic and comparisons, and/or/not. Compile-time values used in them (consts, loop
variables' bounds, `on`/`off`) become constants; a `for` variable stays a VarRef (INT) so a
backend can write the vendor loop's own counter (backends unroll with its value).

Types (REFERENCE.md §7): int, num, bool. `a op b` on numbers is int when both are int and op is
not '/', else num; comparisons and and/or/not give bool. An int may be used (and assigned)
where a num is wanted; a num never where an int is; bool only where bool is. Numbers are plain:
a unit (`4.5 V`, `10 mm`) has no meaning in a controller's variable (E159).
"""

from __future__ import annotations

from collections.abc import Callable

from rmot.lang import check_codes as codes, ir
from rmot.compiler.passes.context import Reporter, Scope
from rmot.compiler.passes.evaluate import BOOL_NAMES
from rmot.compiler.passes.values import DIMENSIONLESS, BoolV, Quantity, article, type_name
from rmot.lang import ast
from rmot.lang.lexer import IO_WORDS
from rmot.lang.source import Span

__all__ = ["TYPE_NAMES", "RtLowering", "expr_type", "fits", "reads_runtime"]

TYPE_NAMES = {"int": ir.ValueType.INT, "num": ir.ValueType.NUM, "bool": ir.ValueType.BOOL}
_CMP = {op.value: op for op in ir.CompareOp}
_ARITH = ("+", "-", "*", "/")
Port = Callable[[ast.IoRef, tuple[str, ...], str], "tuple[int, str | None] | None"]
Width = Callable[[int], "int | None"]  # a group input's port -> its width in bits (None: not given)


def expr_type(e: ir.RtExpr) -> ir.ValueType:
    if isinstance(e, (ir.Const, ir.VarRef, ir.Arith)):
        return e.type
    if isinstance(e, ir.AnalogInput):
        return ir.ValueType.NUM
    if isinstance(e, ir.GroupInput):
        return ir.ValueType.INT
    return ir.ValueType.BOOL  # Compare, Logic, Not, InputCondition


def fits(value: ir.ValueType, wanted: ir.ValueType) -> bool:
    """Can a value of type `value` be used where `wanted` is? (int widens to num)"""
    return value is wanted or (value is ir.ValueType.INT and wanted is ir.ValueType.NUM)


def reads_runtime(e: ast.Expr | None, scope: Scope) -> bool:
    """Whether `e` has a value only while the program runs: it reads a task or loop variable or
    an I/O port (`in[2] == out[3]`, `in[2] == flag`), itself or inside arithmetic."""
    if isinstance(e, (ast.IoRef, ast.Condition)):
        return True
    if isinstance(e, ast.BinOp):
        return reads_runtime(e.left, scope) or reads_runtime(e.right, scope)
    if isinstance(e, ast.Neg):
        return reads_runtime(e.operand, scope)
    if not isinstance(e, ast.Name):
        return False
    entry = scope.lookup(e.name)
    return entry is not None and entry.kind in ("rtvar", "var")


def _literal_is_int(e: ast.Number) -> bool:
    text = e.span.file.text[e.span.start.offset : e.span.end.offset] if e.span is not None else ""
    return float(e.value).is_integer() and not any(ch in text for ch in ".eE")


class RtLowering:
    """Lowers runtime expressions of one task; `port` resolves an I/O reference
    (TaskLowering.port)."""

    def __init__(self, scope: Scope, rep: Reporter, port: Port, width: Width = lambda port: None) -> None:
        self.scope, self.rep, self.port, self.width = scope, rep, port, width

    def _err(self, code: object, msg: str, span: Span | None) -> None:
        self.rep.error(code, msg, span)  # type: ignore[arg-type]

    # ------------------------------------------------------------------ typed entry points
    def condition(self, e: ast.RtCond, what: str) -> ir.Condition | None:
        """A BOOL expression (a condition of if/while/wait until)."""
        out = self.expr(e)
        if out is None:
            return None
        if expr_type(out) is not ir.ValueType.BOOL:
            self._err(
                codes.RT_WRONG_TYPE,
                f"{what} must be a condition (bool) (got {expr_type(out).value}: compare it, "
                f"e.g. '... > 0')",
                e.span,
            )
            return None
        return out  # type: ignore[return-value]

    def typed(self, e: ast.RtCond, wanted: ir.ValueType, what: str) -> ir.RtExpr | None:
        out = self.expr(e)
        if out is None:
            return None
        got = expr_type(out)
        if not fits(got, wanted):
            self._err(
                codes.RT_WRONG_TYPE, f"{what} must be {wanted.value} (got {got.value})", e.span
            )
            return None
        return out

    # ------------------------------------------------------------------ expressions
    def expr(self, e: ast.RtCond) -> ir.RtExpr | None:
        if isinstance(e, ast.Number):
            if e.unit is not None:
                self._err(
                    codes.RT_UNIT,
                    f"a runtime expression takes plain numbers (got {e.value:g} {e.unit}: "
                    "a controller variable has no unit)",
                    e.span,
                )
                return None
            if _literal_is_int(e):
                return ir.Const(int(e.value), ir.ValueType.INT)
            return ir.Const(float(e.value), ir.ValueType.NUM)
        if isinstance(e, ast.Name):
            return self.name(e)
        if isinstance(e, ast.BinOp):
            return self.arith(e)
        if isinstance(e, ast.Neg):
            inner = self.expr(e.operand)
            if inner is None:
                return None
            if expr_type(inner) is ir.ValueType.BOOL:
                self._err(
                    codes.RT_WRONG_TYPE,
                    "'-' must be applied to a number (got bool; use 'not')",
                    e.span,
                )
                return None
            if isinstance(inner, ir.Const):
                return ir.Const(-inner.value, inner.type)
            return ir.Arith("-", ir.Const(0, ir.ValueType.INT), inner, expr_type(inner))
        if isinstance(e, ast.IoRef):
            return self.io_read(e)
        if isinstance(e, ast.Condition):
            return self.input_condition(e)
        if isinstance(e, ast.Compare):
            return self.compare(e)
        if isinstance(e, ast.Logic):
            parts = [self.condition(x, f"each operand of '{e.op}'") for x in e.operands]
            if any(p is None for p in parts):
                return None
            return ir.Logic(e.op, tuple(parts))  # type: ignore[arg-type]
        if isinstance(e, ast.NotCond):
            inner_c = self.condition(e.operand, "the operand of 'not'")
            if isinstance(inner_c, ir.InputCondition):  # `not in[1]` is `in[1] == off`
                return ir.InputCondition(
                    port=inner_c.port, value=not inner_c.value, signal=inner_c.signal
                )
            return None if inner_c is None else ir.Not(inner_c)
        self._err(
            codes.RT_UNIT,
            f"a runtime expression takes numbers, bools, variables and inputs (got "
            f"{type(e).__name__.lower()})",
            e.span,
        )
        return None

    def name(self, e: ast.Name) -> ir.RtExpr | None:
        entry = self.scope.lookup(e.name)
        if entry is None:
            if e.name in BOOL_NAMES:
                return ir.Const(BOOL_NAMES[e.name], ir.ValueType.BOOL)
            known = [
                n
                for n in self.scope.visible()
                if (x := self.scope.lookup(n)) is not None
                and x.kind in ("rtvar", "var", "const", "param")
            ]
            port = f"a read of an I/O port is written {e.name}[n]" if e.name in IO_WORDS else ""  # `if ain > 3`
            self.rep.unknown(e.name, "variable", e.span, known, codes.RT_UNKNOWN_VAR, port)
            return None
        if entry.kind == "rtvar":
            return ir.VarRef(e.name, entry.value)
        if entry.kind == "var":  # a for loop's variable: the vendor loop's counter
            return ir.VarRef(e.name, ir.ValueType.INT)
        v = entry.value
        if isinstance(v, BoolV):
            return ir.Const(v.value, ir.ValueType.BOOL)
        if isinstance(v, Quantity) and v.dim == DIMENSIONLESS and v.unit is None:
            if float(v.value).is_integer():
                return ir.Const(int(v.value), ir.ValueType.INT)
            return ir.Const(float(v.value), ir.ValueType.NUM)
        if v is None:  # its definition failed and was reported
            return None
        got = (
            article(type_name(v))
            if not isinstance(v, Quantity)
            else f"a quantity in {v.unit or 'SI units'}"
        )
        self._err(
            codes.RT_UNIT,
            f"'{e.name}' must be a plain number or on/off to be used in a runtime expression "
            f"(got {got})",
            e.span,
        )
        return None

    def arith(self, e: ast.BinOp) -> ir.RtExpr | None:
        left, right = self.expr(e.left), self.expr(e.right)
        if left is None or right is None:
            return None
        lt, rt = expr_type(left), expr_type(right)
        if ir.ValueType.BOOL in (lt, rt):
            self._err(
                codes.RT_WRONG_TYPE,
                f"'{e.op}' must be applied to numbers (got {lt.value} {e.op} {rt.value})",
                e.span,
            )
            return None
        if e.op == "/" and isinstance(right, ir.Const) and right.value == 0:
            self._err(
                codes.RT_DIVISION_BY_ZERO, "a runtime expression must not divide by 0", e.right.span
            )
            return None
        num = e.op == "/" or ir.ValueType.NUM in (lt, rt)
        t = ir.ValueType.NUM if num else ir.ValueType.INT
        if isinstance(left, ir.Const) and isinstance(
            right, ir.Const
        ):  # folded: what a reader expects
            a, b = float(left.value), float(right.value)
            value = {"+": a + b, "-": a - b, "*": a * b, "/": a / b if b else 0.0}[e.op]
            return ir.Const(int(value) if t is ir.ValueType.INT else value, t)
        return ir.Arith(e.op, left, right, t)

    def io_read(self, io: ast.IoRef) -> ir.RtExpr | None:
        if io.kind == "aout":
            self._err(
                codes.RT_BAD_IO,
                "a condition must read in[n], out[n], ain[n] or gin[n] (got aout[...]: an analog "
                "output, which not every controller reads back)",
                io.span,
            )
            return None
        p = self.port(io, ("in", "out", "ain", "gin"), "a condition")
        if p is None:
            return None
        if io.kind == "ain":
            return ir.AnalogInput(p[0], p[1])
        if io.kind == "gin":
            return ir.GroupInput(p[0], p[1], self.width(p[0]))
        if io.kind == "out":
            return ir.OutputRead(p[0], p[1])
        return ir.InputCondition(port=p[0], value=True, signal=p[1])

    def input_condition(self, c: ast.Condition) -> ir.RtExpr | None:
        """`in[n]`, `in[n] == on|off|bool var` (`!=` negates)."""
        read = self.io_read(c.io)
        if read is None:
            return None
        if c.value is None:
            return read
        level = self.expr(c.value)
        if level is None:
            return None
        if expr_type(level) is not ir.ValueType.BOOL:
            self._err(
                codes.RT_WRONG_TYPE,
                f"the level compared with {c.io.kind}[...] must be on or off (got "
                f"{expr_type(level).value})",
                c.value.span,
            )
            return None
        if isinstance(level, ir.Const) and isinstance(read, ir.OutputRead):  # `out[n] == off` is `not out[n]`
            return read if bool(level.value) == (c.op == "==") else ir.Not(read)
        if isinstance(level, ir.Const) and isinstance(read, ir.InputCondition):
            return ir.InputCondition(
                port=read.port, value=bool(level.value) == (c.op == "=="), signal=read.signal
            )
        return ir.Compare(_CMP[c.op], read, level)

    def compare(self, e: ast.Compare) -> ir.RtExpr | None:
        left = self.io_read(e.left) if isinstance(e.left, ast.IoRef) else self.expr(e.left)
        right = self.expr(e.right)
        if left is None or right is None:
            return None
        lt, rt = expr_type(left), expr_type(right)
        op = _CMP[e.op]
        if (lt is ir.ValueType.BOOL) != (rt is ir.ValueType.BOOL):
            self._err(
                codes.RT_WRONG_TYPE,
                f"'{e.op}' must compare two numbers or two bools (got {lt.value} and {rt.value})",
                e.span,
            )
            return None
        if lt is ir.ValueType.BOOL and op not in (ir.CompareOp.EQ, ir.CompareOp.NE):
            self._err(
                codes.RT_WRONG_TYPE,
                f"'{e.op}' must compare numbers (got bools: use == or !=)",
                e.span,
            )
            return None
        if isinstance(left, ir.OutputRead) and isinstance(right, ir.Const):  # `out[n] == off`: `not out[n]`
            return left if bool(right.value) == (op is ir.CompareOp.EQ) else ir.Not(left)
        if isinstance(left, ir.GroupInput) and not self.group_value_fits(left, right, e.right):
            return None
        if isinstance(right, ir.GroupInput) and not self.group_value_fits(right, left, e.left):
            return None
        return ir.Compare(op, left, right)

    def group_value_fits(self, group: ir.GroupInput, value: ir.RtExpr, node: ast.RtCond) -> bool:
        """A constant compared with gin[n]: a whole number (E168, else the comparison means
        nothing on an integer input), and within 0..2^bits-1 when the width is known (W152)."""
        if not isinstance(value, ir.Const) or isinstance(value.value, bool):
            return True
        number = float(value.value)
        if not number.is_integer():
            self._err(codes.GROUP_INPUT_NOT_INTEGER, f"gin[{group.port}] reads a whole number: it must be "
                      f"compared with one (got {number:g})", node.span)
            return False
        top = None if group.bits is None else 2**group.bits - 1
        if number < 0 or (top is not None and number > top):
            reads = "0 or more (an unsigned integer)" if top is None else f"0..{top} ({group.bits} bits)"
            self.rep.warning(codes.GROUP_INPUT_RANGE, f"gin[{group.port}] reads {reads}: a comparison "
                             f"with {int(number)} never or always holds", node.span)
        return True
