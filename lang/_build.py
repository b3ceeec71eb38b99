"""The embedded lark Transformer: each grammar rule becomes one AST node with its span.

Used by `lang.parse` only. `begin(file)` sets the file whose spans are being made; the
builder also collects the few diagnostics found while building (a keyword used as a name).
"""

from __future__ import annotations

import re
from typing import Any

from lark import Token, Transformer, v_args

from rmot.lang import ast
from rmot.lang import codes
from rmot.lang.diagnostics import Diagnostic, Severity
from rmot.lang.source import Pos, SourceFile, Span

__all__ = ["AstBuilder", "KEYWORDS", "token_span"]

KEYWORDS = frozenset({
    "move", "joint", "linear", "circular", "via", "to", "speed", "accel", "zone", "fine",
    "tool", "frame", "target", "set", "wait", "until", "timeout", "pulse", "for", "in",
    "repeat", "if", "else", "proc", "return", "const", "use", "import", "cell", "program",
    "task", "sync", "native", "on", "off", "config", "at", "robot", "fixture", "io",
    "joint_speed", "joints", "time",
})
_ESCAPE = re.compile(r'\\(["\\])')


def token_span(file: SourceFile, tok: Token) -> Span:
    return Span(file, Pos(tok.line, tok.column, tok.start_pos), Pos(tok.end_line, tok.end_column, tok.end_pos))


def _unquote(tok: Token) -> str:
    return _ESCAPE.sub(r"\1", str(tok)[1:-1])


@v_args(meta=True)
class AstBuilder(Transformer):  # type: ignore[type-arg]
    """lark rule name -> node constructor; children arrive with anonymous tokens filtered out."""

    def __init__(self) -> None:
        super().__init__(visit_tokens=False)
        self.file = SourceFile("<none>", "")
        self.diagnostics: list[Diagnostic] = []

    def begin(self, file: SourceFile) -> None:
        self.file = file
        self.diagnostics = []

    # -- helpers
    def _span(self, meta: Any) -> Span:
        f = self.file
        return Span(f, Pos(meta.line, meta.column, meta.start_pos), Pos(meta.end_line, meta.end_column, meta.end_pos))

    def _ident(self, tok: Token, what: str | None = None) -> ast.Ident:
        span = token_span(self.file, tok)
        if what is not None and str(tok) in KEYWORDS:
            msg = f"{what} name must not be a keyword (got '{tok}')"
            self.diagnostics.append(Diagnostic(codes.RESERVED_KEYWORD, Severity.ERROR, msg, span))
        return ast.Ident(str(tok), span)

    def _string(self, tok: Token) -> ast.String:
        return ast.String(_unquote(tok), token_span(self.file, tok))

    @staticmethod
    def _body(block: Any) -> tuple[Any, ...]:
        return tuple(block)

    # -- files and blocks
    def start(self, meta: Any, c: list[Any]) -> ast.Module:
        return ast.Module(self.file, tuple(c))

    def block(self, meta: Any, c: list[Any]) -> tuple[Any, ...]:
        return tuple(c)

    def use_cell(self, meta: Any, c: list[Any]) -> ast.UseCell:
        return ast.UseCell(self._string(c[0]), self._span(meta))

    def import_file(self, meta: Any, c: list[Any]) -> ast.Import:
        return ast.Import(self._string(c[0]), self._span(meta))

    def cell(self, meta: Any, c: list[Any]) -> ast.CellDecl:
        return ast.CellDecl(self._ident(c[0], "cell"), c[1], self._span(meta))

    def program(self, meta: Any, c: list[Any]) -> ast.ProgramDecl:
        robot = self._ident(c[1]) if c[1] is not None else None
        return ast.ProgramDecl(self._ident(c[0], "program"), robot, c[2], self._span(meta))

    def task(self, meta: Any, c: list[Any]) -> ast.TaskDecl:
        return ast.TaskDecl(self._ident(c[0]), c[1], self._span(meta))

    # -- cell declarations
    def robot_decl(self, meta: Any, c: list[Any]) -> ast.RobotDecl:
        library, urdf = c[1]
        return ast.RobotDecl(self._ident(c[0], "robot"), library, urdf, c[2], self._span(meta))

    def robot_library(self, meta: Any, c: list[Any]) -> tuple[ast.Ident, None]:
        return self._ident(c[0]), None

    def robot_urdf(self, meta: Any, c: list[Any]) -> tuple[None, ast.String]:
        return None, self._string(c[0])

    def fixture_decl(self, meta: Any, c: list[Any]) -> ast.FixtureDecl:
        return ast.FixtureDecl(self._ident(c[0], "fixture"), c[1], c[2], self._span(meta))

    def geometry(self, meta: Any, c: list[Any]) -> ast.Geometry:
        return ast.Geometry(self._ident(c[0]), c[1] or (), self._span(meta))

    def tool_decl(self, meta: Any, c: list[Any]) -> ast.ToolDecl:
        geometry = None if isinstance(c[1], Token) else c[1]
        opts = dict(c[2:-1])
        return ast.ToolDecl(self._ident(c[0], "tool"), geometry, opts.get("at"), opts.get("tcp"),
                            opts.get("mass"), self._ident(c[-1]), self._span(meta))

    def tool_at(self, meta: Any, c: list[Any]) -> tuple[str, Any]:
        return "at", c[0]

    def tool_tcp(self, meta: Any, c: list[Any]) -> tuple[str, Any]:
        return "tcp", c[0]

    def tool_mass(self, meta: Any, c: list[Any]) -> tuple[str, Any]:
        return "mass", c[0]

    def frame_decl(self, meta: Any, c: list[Any]) -> ast.FrameDecl:
        return ast.FrameDecl(self._ident(c[0], "frame"), c[1], self._span(meta))

    def io_decl(self, meta: Any, c: list[Any]) -> ast.IoDecl:
        robot = self._ident(c[2]) if c[2] is not None else None
        return ast.IoDecl(c[0], self._string(c[1]), robot, self._span(meta))

    # -- program declarations
    def target_decl(self, meta: Any, c: list[Any]) -> ast.TargetDecl:
        return ast.TargetDecl(self._ident(c[0], "target"), c[1], self._span(meta))

    def const_decl(self, meta: Any, c: list[Any]) -> ast.ConstDecl:
        return ast.ConstDecl(self._ident(c[0], "constant"), c[1], self._span(meta))

    def proc_decl(self, meta: Any, c: list[Any]) -> ast.ProcDecl:
        return ast.ProcDecl(self._ident(c[0], "proc"), c[1] or (), c[2], self._span(meta))

    def params(self, meta: Any, c: list[Any]) -> tuple[ast.Param, ...]:
        return tuple(c)

    def param(self, meta: Any, c: list[Any]) -> ast.Param:
        return ast.Param(self._ident(c[0], "parameter"), self._ident(c[1]), self._span(meta))

    # -- settings and modifiers
    def _setting(self, kind: str, meta: Any, value: Any) -> ast.Setting:
        if isinstance(value, Token):  # tool/frame NAME, or the FINE keyword
            value = None if value.type == "FINE" else self._ident(value)
        return ast.Setting(kind, value, self._span(meta))

    def tool_setting(self, meta: Any, c: list[Any]) -> ast.Setting:
        return self._setting("tool", meta, c[0])

    def frame_setting(self, meta: Any, c: list[Any]) -> ast.Setting:
        return self._setting("frame", meta, c[0])

    def speed_setting(self, meta: Any, c: list[Any]) -> ast.Setting:
        return self._setting("speed", meta, c[0])

    def joint_speed_setting(self, meta: Any, c: list[Any]) -> ast.Setting:
        return self._setting("joint_speed", meta, c[0])

    def accel_setting(self, meta: Any, c: list[Any]) -> ast.Setting:
        return self._setting("accel", meta, c[0])

    def zone_setting(self, meta: Any, c: list[Any]) -> ast.Setting:
        return self._setting("zone", meta, c[0])

    mod_speed = speed_setting
    mod_joint_speed = joint_speed_setting
    mod_accel = accel_setting
    mod_zone = zone_setting
    mod_tool = tool_setting
    mod_frame = frame_setting

    def mod_config(self, meta: Any, c: list[Any]) -> ast.Setting:
        return ast.Setting("config", c[0] or (), self._span(meta))

    def mod_time(self, meta: Any, c: list[Any]) -> ast.Setting:
        return self._setting("time", meta, c[0])

    # -- motion
    def move_simple(self, meta: Any, c: list[Any]) -> ast.Move:
        return ast.Move(str(c[0]), c[1], None, tuple(c[2:]), self._span(meta))

    def move_circular(self, meta: Any, c: list[Any]) -> ast.Move:
        return ast.Move("circular", c[1], c[0], tuple(c[2:]), self._span(meta))

    # -- I/O, timing, control flow
    def io_ref(self, meta: Any, c: list[Any]) -> ast.IoRef:
        return ast.IoRef(str(c[0]), c[1], self._span(meta))

    def io_kind(self, meta: Any, c: list[Any]) -> str:
        return str(c[0])

    def set_io(self, meta: Any, c: list[Any]) -> ast.SetIo:
        return ast.SetIo(c[0], c[1], self._span(meta))

    def pulse(self, meta: Any, c: list[Any]) -> ast.Pulse:
        return ast.Pulse(c[0], c[1], self._span(meta))

    def wait_time(self, meta: Any, c: list[Any]) -> ast.WaitTime:
        return ast.WaitTime(c[0], self._span(meta))

    def wait_until(self, meta: Any, c: list[Any]) -> ast.WaitUntil:
        return ast.WaitUntil(c[0], c[1], self._span(meta))

    def condition(self, meta: Any, c: list[Any]) -> ast.Condition:
        return ast.Condition(c[0], str(c[1]), c[2], self._span(meta))

    def condition_bare(self, meta: Any, c: list[Any]) -> ast.Condition:
        return ast.Condition(c[0], "==", None, self._span(meta))

    def for_loop(self, meta: Any, c: list[Any]) -> ast.For:
        return ast.For(self._ident(c[0], "loop variable"), c[1], c[2], c[3], self._span(meta))

    def repeat_loop(self, meta: Any, c: list[Any]) -> ast.Repeat:
        return ast.Repeat(c[0], c[1], self._span(meta))

    def if_stmt(self, meta: Any, c: list[Any]) -> ast.IfStmt:
        otherwise = c[2]
        if otherwise is None:
            otherwise = ()
        elif isinstance(otherwise, ast.IfStmt):  # else if: a nested branch
            otherwise = (otherwise,)
        return ast.IfStmt(c[0], c[1], otherwise, self._span(meta))

    def sync(self, meta: Any, c: list[Any]) -> ast.SyncStmt:
        return ast.SyncStmt(self._ident(c[0]), self._span(meta))

    def native(self, meta: Any, c: list[Any]) -> ast.NativeStmt:
        return ast.NativeStmt(self._ident(c[0]), self._string(c[1]), self._span(meta))

    def call(self, meta: Any, c: list[Any]) -> ast.CallStmt:
        return ast.CallStmt(self._ident(c[0]), c[1] or (), self._span(meta))

    # -- expressions
    def _binop(self, op: str, meta: Any, c: list[Any]) -> ast.BinOp:
        return ast.BinOp(op, c[0], c[1], self._span(meta))

    def add(self, meta: Any, c: list[Any]) -> ast.BinOp:
        return self._binop("+", meta, c)

    def sub(self, meta: Any, c: list[Any]) -> ast.BinOp:
        return self._binop("-", meta, c)

    def mul(self, meta: Any, c: list[Any]) -> ast.BinOp:
        return self._binop("*", meta, c)

    def div(self, meta: Any, c: list[Any]) -> ast.BinOp:
        return self._binop("/", meta, c)

    def neg(self, meta: Any, c: list[Any]) -> ast.Neg:
        return ast.Neg(c[0], self._span(meta))

    def attr(self, meta: Any, c: list[Any]) -> ast.Attr:
        return ast.Attr(c[0], self._ident(c[1]), self._span(meta))

    def number(self, meta: Any, c: list[Any]) -> ast.Number:
        unit = str(c[1]) if c[1] is not None else None
        return ast.Number(float(c[0]), unit, self._span(meta))

    def name(self, meta: Any, c: list[Any]) -> ast.Name:
        return ast.Name(str(c[0]), self._span(meta))

    def call_expr(self, meta: Any, c: list[Any]) -> ast.Call:
        return ast.Call(self._ident(c[0]), c[1] or (), self._span(meta))

    def joints(self, meta: Any, c: list[Any]) -> ast.Joints:
        unit = str(c[1]) if c[1] is not None else None
        return ast.Joints(c[0] or (), unit, self._span(meta))

    def vector(self, meta: Any, c: list[Any]) -> ast.Vector:
        first = ast.Arg(None, c[0], _expr_span(c[0]))
        return ast.Vector((first, *(c[1] or ())), self._span(meta))

    def string(self, meta: Any, c: list[Any]) -> ast.String:
        return self._string(c[0])

    def args(self, meta: Any, c: list[Any]) -> tuple[ast.Arg, ...]:
        return tuple(a if isinstance(a, ast.Arg) else ast.Arg(None, a, _expr_span(a)) for a in c)

    def kwarg(self, meta: Any, c: list[Any]) -> ast.Arg:
        return ast.Arg(self._ident(c[0]), c[1], self._span(meta))


def _expr_span(node: Any) -> Span:
    return node.span  # type: ignore[no-any-return]
