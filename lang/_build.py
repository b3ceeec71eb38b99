"""The embedded lark Transformer: each grammar rule becomes one AST node with its span.

Used by `lang.parse` only, as lark's embedded transformer (no parse tree is built: the
fast path). Embedded callbacks get no positions, so the rules whose first or last symbol is
a keyword or a bracket are `!rules` in the grammar: their children keep every token, at
fixed indexes (optional parts give None placeholders), and a node's span runs from its
first child to its last. `begin(file)` sets the file whose spans are being made; the
builder also collects the few diagnostics found while building (a keyword used as a name).
"""

from __future__ import annotations

from typing import Any

from lark import Token, Transformer

from rmot.lang import ast
from rmot.lang import codes
from rmot.lang.diagnostics import Diagnostic, Severity
from rmot.lang.source import SourceFile, Span
from rmot.lang.units import UNIT_TABLE, unknown_unit
from rmot.lang._build_nodes import (
    KEYWORDS,
    RESERVED,
    _make_pos,
    _make_span,
    _tokens_span,
    _Number,
    _Arg,
    _Ident,
    _Name,
    _Setting,
    _Call,
    _Move,
    _IoRef,
    _SetIo,
    _Condition,
    _TargetDecl,
    _WaitTime,
    _BinOp,
    _IfStmt,
    _WaitUntil,
    _Joints,
    _Neg,
    _Vector,
    _String,
    _Attr,
    _Compare,
    _Logic,
    _NotCond,
    _Pulse,
    _For,
    _Repeat,
    _CallStmt,
    _AssignStmt,
    _VarDecl,
    _While,
    _ConstDecl,
    reserved_statement,
    _unquote,
)

__all__ = ["AstBuilder"]


def _bare_input(node: Any) -> bool:
    """A bare `in[n]` read (the atom, not yet compared with a level)."""
    return isinstance(node, ast.Condition) and node.value is None


class Block(tuple):  # type: ignore[type-arg]
    """A block's statements plus the span of its braces (nodes store a plain tuple)."""

    span: Span


class AstBuilder(Transformer):  # type: ignore[type-arg]
    """lark rule name -> node constructor; `c` is the rule's children list."""

    def __init__(self) -> None:
        super().__init__(visit_tokens=False)
        self.file = SourceFile("<none>", "")
        self.diagnostics: list[Diagnostic] = []

    def begin(self, file: SourceFile) -> None:
        self.file = file
        self.diagnostics = []

    def _token_span(self, tok: Token) -> Span:
        return _tokens_span(self.file, tok, tok)

    def _span(self, c: list[Any]) -> Span:
        """From the start of the first child to the end of the last (tokens or nodes)."""
        first = c[0]
        if first is None:
            first = next(x for x in c if x is not None)
        last = c[-1]
        if last is None:
            last = next(x for x in reversed(c) if x is not None)
        start = _make_pos(first.line, first.column, first.start_pos) if first.__class__ is Token else first.span.start
        end = _make_pos(last.end_line, last.end_column, last.end_pos) if last.__class__ is Token else last.span.end
        return _make_span(self.file, start, end)

    def _ident(self, tok: Token, what: str | None = None) -> ast.Ident:
        span = self._token_span(tok)
        if what is not None and str(tok) in KEYWORDS:
            msg = f"{what} name must not be a keyword (got '{tok}')"
            self.diagnostics.append(Diagnostic(codes.RESERVED_KEYWORD, Severity.ERROR, msg, span))
        return _Ident(str(tok), span)

    def _unit(self, tok: Token) -> str:
        """The unit text; an E007 when the lexer's compound shape (`kg/s`) is no known unit."""
        text = str(tok)
        if text not in UNIT_TABLE:
            self.diagnostics.append(unknown_unit(text, self._token_span(tok)))
        return text

    def _string(self, tok: Token) -> ast.String:
        return _String(_unquote(tok), self._token_span(tok))

    # -- files and blocks
    def start(self, c: list[Any]) -> ast.Module:
        return ast.Module(self.file, tuple(x for x in c if not isinstance(x, Token)))

    def block(self, c: list[Any]) -> Block:
        out = Block(x for x in c[1:-1] if not isinstance(x, Token))
        out.span = self._span(c)
        return out

    def use_cell(self, c: list[Any]) -> ast.UseCell:
        return ast.UseCell(self._string(c[2]), self._span(c))

    def import_file(self, c: list[Any]) -> ast.Import:
        return ast.Import(self._string(c[1]), self._span(c))

    def cell(self, c: list[Any]) -> ast.CellDecl:
        return ast.CellDecl(self._ident(c[1], "cell"), tuple(c[2]), self._span(c))

    def program(self, c: list[Any]) -> ast.ProgramDecl:
        robot = self._ident(c[3]) if c[3] is not None else None
        axes = tuple(self._ident(t) for t in c[5]) if c[5] is not None else ()
        return ast.ProgramDecl(self._ident(c[1], "program"), robot, tuple(c[6]), self._span(c), axes)

    def names(self, c: list[Any]) -> list[Token]:
        return c

    def task(self, c: list[Any]) -> ast.TaskDecl:
        return ast.TaskDecl(self._ident(c[1]), tuple(c[2]), self._span(c))

    # -- cell declarations
    def robot_decl(self, c: list[Any]) -> ast.RobotDecl:
        library, urdf, *urdf_args = c[3]
        shares = tuple(x for x in c[4:6] if x is not None)
        span = self._span([*c[:3], library or urdf, *c[4:6], *(c[6] or ()), *c[7:]])
        return ast.RobotDecl(self._ident(c[1], "robot"), library, urdf, c[-1], span,
                             urdf_args=urdf_args[0] if urdf_args else (), shares=shares,
                             software=c[6], on=self._ident(c[8]) if c[8] is not None else None)

    def robot_speed(self, c: list[Any]) -> ast.Setting:
        return _Setting(ast.SettingKind.SPEED, c[1], self._span(c))

    def robot_accel(self, c: list[Any]) -> ast.Setting:
        return _Setting(ast.SettingKind.ACCEL, c[1], self._span(c))

    def robot_software(self, c: list[Any]) -> tuple[ast.Ident, ast.Expr]:
        return (self._ident(c[1]), c[2])

    def urdf_args(self, c: list[Any]) -> tuple[ast.Arg, ...]:
        return self.args(c)

    def urdf_packages(self, c: list[Any]) -> ast.Arg:
        """`packages={a: "dir", ...}`: an Arg whose value is a Vector of named String items."""
        items = tuple(c[1] or ())
        return _Arg(self._ident(c[0]), _Vector(items, None, self._span([c[0], *items]) if items else self._span([c[0]])),
                    self._span([c[0], *items]))

    def package_items(self, c: list[Any]) -> tuple[ast.Arg, ...]:
        return tuple(c)

    def package_item(self, c: list[Any]) -> ast.Arg:
        return _Arg(self._ident(c[0]), self._string(c[1]), self._span(c))

    def robot_library(self, c: list[Any]) -> tuple[ast.Ident, None]:
        return self._ident(c[0]), None

    def robot_urdf(self, c: list[Any]) -> tuple[None, ast.String]:
        return None, self._string(c[0])

    def robot_urdf_chain(self, c: list[Any]) -> tuple[None, ast.String, tuple[ast.Arg, ...]]:
        return None, self._string(c[0]), c[1]

    def fixture_decl(self, c: list[Any]) -> ast.FixtureDecl:
        on = self._ident(c[5]) if c[5] is not None else None
        return ast.FixtureDecl(self._ident(c[1], "fixture"), c[3], c[7], self._span(c), on)

    def geometry(self, c: list[Any]) -> ast.Geometry:
        return ast.Geometry(self._ident(c[0]), c[2] or (), self._span(c))

    def tool_decl(self, c: list[Any]) -> ast.ToolDecl:
        geometry = None if isinstance(c[3], Token) else c[3]
        opts = dict(c[4:-2])
        return ast.ToolDecl(self._ident(c[1], "tool"), geometry, opts.get("at"), opts.get("tcp"),
                            opts.get("mass"), self._ident(c[-1]), self._span(c), opts.get("number"))

    def tool_at(self, c: list[Any]) -> tuple[str, Any]:
        return "at", c[0]

    def tool_tcp(self, c: list[Any]) -> tuple[str, Any]:
        return "tcp", c[0]

    def tool_mass(self, c: list[Any]) -> tuple[str, Any]:
        return "mass", c[0]

    def tool_number(self, c: list[Any]) -> tuple[str, Any]:
        return "number", c[0]

    def frame_decl(self, c: list[Any]) -> ast.FrameDecl:
        number = c[5] if len(c) > 5 else None
        return ast.FrameDecl(self._ident(c[1], "frame"), c[3], self._span(c), number)

    def io_decl(self, c: list[Any]) -> ast.IoDecl:
        robot = self._ident(c[7]) if c[7] is not None else None
        return ast.IoDecl(c[1], self._string(c[3]), robot, self._span(c), c[5])

    # -- program declarations
    def target_decl(self, c: list[Any]) -> ast.TargetDecl:
        return _TargetDecl(self._ident(c[1], "target"), c[3], self._span(c))

    def const_decl(self, c: list[Any]) -> ast.ConstDecl:
        return _ConstDecl(self._ident(c[1], "constant"), c[3], self._span(c))

    def proc_decl(self, c: list[Any]) -> ast.ProcDecl:
        return ast.ProcDecl(self._ident(c[1], "proc"), c[3] or (), tuple(c[5]), self._span(c))

    def params(self, c: list[Any]) -> tuple[ast.Param, ...]:
        return tuple(c)

    def param(self, c: list[Any]) -> ast.Param:
        return ast.Param(self._ident(c[0], "parameter"), self._ident(c[1]), self._span(c))

    # -- settings and modifiers: [KEYWORD, value]
    def _setting(self, kind: str, c: list[Any]) -> ast.Setting:
        value = c[1]
        if isinstance(value, Token):  # tool/frame NAME, or the FINE keyword
            value = None if value.type == "FINE" else self._ident(value)
        return _Setting(ast.SettingKind(kind), value, self._span(c))

    def tool_setting(self, c: list[Any]) -> ast.Setting:
        return self._setting("tool", c)

    def frame_setting(self, c: list[Any]) -> ast.Setting:
        return self._setting("frame", c)

    def speed_setting(self, c: list[Any]) -> ast.Setting:
        return self._setting("speed", c)

    def joint_speed_setting(self, c: list[Any]) -> ast.Setting:
        return self._setting("joint_speed", c)

    def accel_setting(self, c: list[Any]) -> ast.Setting:
        return self._setting("accel", c)

    def zone_setting(self, c: list[Any]) -> ast.Setting:
        return self._setting("zone", c)

    mod_speed = speed_setting
    mod_joint_speed = joint_speed_setting
    mod_accel = accel_setting
    mod_zone = zone_setting
    mod_tool = tool_setting
    mod_frame = frame_setting

    def mod_config(self, c: list[Any]) -> ast.Setting:
        return _Setting(ast.SettingKind.CONFIG, c[2] or (), self._span(c))

    def mod_time(self, c: list[Any]) -> ast.Setting:
        return self._setting("time", c)

    def mod_ext(self, c: list[Any]) -> ast.Setting:
        return _Setting(ast.SettingKind.EXT, c[2] or (), self._span(c))

    # -- motion
    def move_simple(self, c: list[Any]) -> ast.Move:
        return _Move(str(c[1]), c[2], None, tuple(c[3:]), self._span(c))

    def move_circular(self, c: list[Any]) -> ast.Move:
        return _Move("circular", c[5], c[3], tuple(c[6:]), self._span(c))

    def move_free(self, c: list[Any]) -> ast.Move:
        return _Move("free", c[2], None, tuple(c[3:]), self._span(c))

    def free_clearance(self, c: list[Any]) -> ast.Setting:
        return self._setting(ast.SettingKind.CLEARANCE, c)

    def free_samples(self, c: list[Any]) -> ast.Setting:
        return self._setting(ast.SettingKind.SAMPLES, c)

    def free_budget(self, c: list[Any]) -> ast.Setting:
        return self._setting(ast.SettingKind.BUDGET, c)

    # -- I/O, timing, control flow
    def io_ref(self, c: list[Any]) -> ast.IoRef:
        return _IoRef(str(c[0]), c[2], self._span(c))

    def set_io(self, c: list[Any]) -> ast.SetIo:
        return _SetIo(c[1], c[3], self._span(c))

    def pulse(self, c: list[Any]) -> ast.Pulse:
        return _Pulse(c[1], c[3], self._span(c))

    def wait_time(self, c: list[Any]) -> ast.WaitTime:
        return _WaitTime(c[1], self._span(c))

    def wait_until(self, c: list[Any]) -> ast.WaitUntil:
        otherwise = tuple(c[6]) if len(c) > 6 and c[6] is not None else None
        return _WaitUntil(c[2], c[4], self._span(c), otherwise)

    def for_loop(self, c: list[Any]) -> ast.For:
        return _For(self._ident(c[1], "loop variable"), c[3], c[5], tuple(c[6]), self._span(c))

    def repeat_loop(self, c: list[Any]) -> ast.Repeat:
        return _Repeat(c[1], tuple(c[2]), self._span(c))

    def if_stmt(self, c: list[Any]) -> ast.IfStmt:
        otherwise = c[3]
        if otherwise is None:
            otherwise = ()
        elif isinstance(otherwise, ast.IfStmt):  # else if: a nested branch
            otherwise = (otherwise,)
        return _IfStmt(c[1], tuple(c[2]), tuple(otherwise), self._span(c))

    def else_part(self, c: list[Any]) -> Any:
        return c[0]

    def sync(self, c: list[Any]) -> ast.SyncStmt:
        return ast.SyncStmt(self._ident(c[1]), self._span(c))

    def native(self, c: list[Any]) -> ast.NativeStmt:
        return ast.NativeStmt(self._ident(c[1]), self._string(c[2]), self._span(c))

    def call(self, c: list[Any]) -> ast.CallStmt:
        if str(c[0]) in RESERVED:  # `return()`: the word is reserved, not an unknown proc
            self.diagnostics.append(reserved_statement(str(c[0]), self._token_span(c[0])))
        return _CallStmt(self._ident(c[0]), c[2] or (), self._span(c))

    # -- expressions
    def _binop(self, op: str, c: list[Any]) -> ast.BinOp:
        return _BinOp(op, c[0], c[1], self._span(c))

    def add(self, c: list[Any]) -> ast.BinOp:
        return self._binop("+", c)

    def sub(self, c: list[Any]) -> ast.BinOp:
        return self._binop("-", c)

    def mul(self, c: list[Any]) -> ast.BinOp:
        return self._binop("*", c)

    def div(self, c: list[Any]) -> ast.BinOp:
        return self._binop("/", c)

    def neg(self, c: list[Any]) -> ast.Neg:
        return _Neg(c[1], self._span(c))

    def unary(self, c: list[Any]) -> Any:  # `+x`
        return c[1]

    def atom(self, c: list[Any]) -> Any:  # `(x)`
        return c[1]

    def attr(self, c: list[Any]) -> ast.Attr:
        return _Attr(c[0], self._ident(c[1]), self._span(c))

    def number(self, c: list[Any]) -> ast.Number:
        num, unit = c
        last = num if unit is None else unit
        span = _tokens_span(self.file, num, last)
        value = float(num)
        if value == float("inf"):  # `1e999`: refused where written; 0.0 keeps the tree well-typed
            self.diagnostics.append(Diagnostic(codes.NOT_FINITE_LITERAL, Severity.ERROR, "number must fit a 64-bit "
                                               f"float, at most about 1.8e308 (got {str(num)[:40]})", span))
            value = 0.0
        return _Number(value, None if unit is None else self._unit(unit), span)

    def name(self, c: list[Any]) -> ast.Name:
        return _Name(str(c[0]), self._token_span(c[0]))

    def call_expr(self, c: list[Any]) -> ast.Call:
        return _Call(self._ident(c[0]), c[2] or (), self._span(c))

    def joints(self, c: list[Any]) -> ast.Joints:
        unit = self._unit(c[4]) if c[4] is not None else None
        return _Joints(c[2] or (), unit, self._span(c))

    def vector(self, c: list[Any]) -> ast.Vector:
        first = _Arg(None, c[1], c[1].span)
        unit = self._unit(c[5]) if c[5] is not None else None
        return _Vector((first, *(c[3] or ())), unit, self._span(c))

    def string(self, c: list[Any]) -> ast.String:
        return self._string(c[0])

    def args(self, c: list[Any]) -> tuple[ast.Arg, ...]:
        return tuple([a if a.__class__ is ast.Arg else _Arg(None, a, a.span) for a in c])

    def kwarg(self, c: list[Any]) -> ast.Arg:
        return _Arg(self._ident(c[0]), c[1], self._span(c))

    # -- robot models (appended; lowered by compiler/passes/lower_model.py)
    def model_decl(self, c: list[Any]) -> ast.ModelDecl:
        items = tuple(x for x in c[3:-1] if x is not None and not isinstance(x, Token))
        return ast.ModelDecl(self._ident(c[1], "model"), items, self._span(c))

    def model_joint(self, c: list[Any]) -> ast.ModelJoint:
        if str(c[0]) != "joint":  # `linear ...`: the word shares the move-kind token
            msg = f"a model line must start with 'joint', 'flange', 'payload' or 'controller' (got '{c[0]}')"
            self.diagnostics.append(Diagnostic(codes.SYNTAX, Severity.ERROR, msg, self._token_span(c[0])))
        return ast.ModelJoint(self._ident(c[1]), tuple(c[2:]), self._span(c))

    def model_call(self, c: list[Any]) -> ast.Call:
        return _Call(self._ident(c[0]), c[2] or (), self._span(c))

    def model_speed(self, c: list[Any]) -> ast.Setting:
        return _Setting(ast.SettingKind.SPEED, c[1], self._span(c))

    def model_accel(self, c: list[Any]) -> ast.Setting:
        return _Setting(ast.SettingKind.ACCEL, c[1], self._span(c))

    def model_torque(self, c: list[Any]) -> ast.Setting:
        return _Setting(ast.SettingKind.TORQUE, c[1], self._span(c))

    def model_mass(self, c: list[Any]) -> ast.Setting:
        return _Setting(ast.SettingKind.MASS, c[1], self._span(c))

    def model_flange(self, c: list[Any]) -> ast.Setting:
        return _Setting(ast.SettingKind.FLANGE, c[1], self._span(c))

    def model_payload(self, c: list[Any]) -> ast.Setting:
        return _Setting(ast.SettingKind.PAYLOAD, c[1], self._span(c))

    def model_controller(self, c: list[Any]) -> ast.Setting:
        return _Setting(ast.SettingKind.CONTROLLER, self._ident(c[1]), self._span(c))

    # -- parts
    def part_decl(self, c: list[Any]) -> ast.PartDecl:
        opts = dict(c[4:])
        span = self._span([*c[:4], *(value for _, value in c[4:])])
        return ast.PartDecl(self._ident(c[1], "part"), c[3], opts.get("at"), opts.get("mass"), span)

    def feeder_decl(self, c: list[Any]) -> ast.FeederDecl:
        opts = dict(c[4:])
        span = self._span([*c[:4], *(value for _, value in c[4:])])
        return ast.FeederDecl(self._ident(c[1], "feeder"), c[3], opts.get("at"), opts.get("mass"), opts.get("count"),
                              span)

    def feeder_count(self, c: list[Any]) -> tuple[str, Any]:
        return "count", c[0]

    def part_at(self, c: list[Any]) -> tuple[str, Any]:
        return "at", c[0]

    def part_mass(self, c: list[Any]) -> tuple[str, Any]:
        return "mass", c[0]

    def attach(self, c: list[Any]) -> ast.AttachStmt:
        return ast.AttachStmt(self._ident(c[1]), True, self._span(c))

    def detach(self, c: list[Any]) -> ast.AttachStmt:
        return ast.AttachStmt(self._ident(c[1]), False, self._span(c))

    # -- runtime logic
    def var_decl(self, c: list[Any]) -> ast.VarDecl:
        type_ = self._ident(c[3]) if c[3] is not None else None
        return _VarDecl(self._ident(c[1], "variable"), type_, c[5], self._span(c))

    def assign(self, c: list[Any]) -> ast.AssignStmt:
        return _AssignStmt(self._ident(c[0]), c[2], self._span(c))

    def stop_stmt(self, c: list[Any]) -> ast.StopStmt:
        return ast.StopStmt(self._span(c))

    def while_loop(self, c: list[Any]) -> ast.While:
        return _While(c[1], tuple(c[2]), self._span(c))

    def while_bare(self, c: list[Any]) -> ast.While:
        return _While(None, tuple(c[1]), self._span(c))

    def for_unbounded(self, c: list[Any]) -> ast.For:
        return _For(self._ident(c[1], "loop variable"), c[3], None, tuple(c[4]), self._span(c))

    def _logic(self, op: str, c: list[Any]) -> ast.Logic:
        items: list[Any] = []
        for x in c:
            items += x.operands if isinstance(x, ast.Logic) and x.op == op else [x]
        return _Logic(op, tuple(items), self._span(c))

    def logic_or(self, c: list[Any]) -> ast.Logic:
        return self._logic("or", c)

    def logic_and(self, c: list[Any]) -> ast.Logic:
        return self._logic("and", c)

    def logic_not(self, c: list[Any]) -> ast.NotCond:
        return _NotCond(c[1], self._span(c))

    def compare(self, c: list[Any]) -> Any:
        op, left, right = str(c[1]), c[0], c[2]
        if op in ("==", "!="):  # `in[n] == on` (either side): the level test every backend writes
            if _bare_input(left):
                return _Condition(left.io, op, right, self._span(c))
            if _bare_input(right):
                return _Condition(right.io, op, left, self._span(c))
        return _Compare(op, left, right, self._span(c))

    def io_read(self, c: list[Any]) -> Any:
        """An I/O read as an expression atom: `in[n]` is the condition `in[n] == on`; the other
        kinds stay a reference the compiler types (ain num, gin int, out bool)."""
        io = c[0]
        return _Condition(io, "==", None, io.span) if io.kind == "in" else io

    def r_cmp(self, c: list[Any]) -> Any:  # `( cond )`
        return c[1]

    # -- external axes (tracks and positioners)
    def track_decl(self, c: list[Any]) -> ast.MechanismDecl:
        return ast.MechanismDecl("track", self._ident(c[1], "track"), (c[3],), c[7], self._span(c),
                                 self._ident(c[5]) if c[5] is not None else None)

    def positioner_decl(self, c: list[Any]) -> ast.MechanismDecl:
        return ast.MechanismDecl("positioner", self._ident(c[1], "positioner"), tuple(c[5]), c[10], self._span(c),
                                 self._ident(c[8]) if c[8] is not None else None)

    def ext_axes(self, c: list[Any]) -> list[ast.ExtAxisDecl]:
        return c

    def ext_axis(self, c: list[Any]) -> ast.ExtAxisDecl:
        options = dict(c[7:])
        return ast.ExtAxisDecl(self._ident(c[0]), self._ident(c[3]), c[5], options.get("speed"),
                               options.get("accel"), self._span([*c[:7], *(value for _, value in c[7:])]),
                               options.get("inform"), tuple(v for k, v in c[7:] if k == "solid"), options.get("mass"))

    def ext_solid(self, c: list[Any]) -> tuple[str, Any]:
        return "solid", ast.Call(self._ident(c[0]), c[2], self._span(c))

    def ext_mass(self, c: list[Any]) -> tuple[str, Any]:
        return "mass", c[1]

    def ext_speed(self, c: list[Any]) -> tuple[str, Any]:
        return "speed", c[1]

    def ext_accel(self, c: list[Any]) -> tuple[str, Any]:
        return "accel", c[1]

    def ext_inform(self, c: list[Any]) -> tuple[str, Any]:
        return "inform", ast.Call(self._ident(c[0]), c[2], self._span(c))

    def move_axes(self, c: list[Any]) -> ast.MoveAxes:
        return ast.MoveAxes(self._ident(c[2]), c[4], tuple(c[5:]), self._span(c))
