"""The AST builder's vocabulary apart from the AstBuilder class: keywords and reserved
words, and the fast constructors of its nodes, positions and token spans."""

from __future__ import annotations

import re
from dataclasses import MISSING, fields
from collections.abc import Callable
from typing import Any, TypeVar

from lark import Token

from rmot.lang import ast
from rmot.lang import codes
from rmot.lang.diagnostics import Diagnostic, Severity
from rmot.lang.source import Pos, SourceFile, Span


__all__ = ["KEYWORDS", "RESERVED", "T", "reserved_statement", "token_span"]


KEYWORDS = frozenset({
    "move", "joint", "linear", "circular", "via", "to", "speed", "accel", "zone", "fine",
    "tool", "frame", "target", "set", "wait", "until", "timeout", "pulse", "for", "in",
    "repeat", "if", "else", "proc", "return", "const", "use", "import", "cell", "program",
    "task", "sync", "native", "on", "off", "config", "at", "robot", "fixture", "io",
    "joint_speed", "joints", "time",
    "var", "while", "and", "or", "not",  # runtime logic (`stop` stays a name: weld_seam's target)
})


# keywords that start no statement yet, kept for the language's future (see reserved_statement)
RESERVED = {"return": "procs end at their closing brace"}


_ESCAPE = re.compile(r'\\(["\\])')


T = TypeVar("T")


def _fast_constructor(cls: type, names: tuple[str, str, str]) -> Any:
    """`cls(x, y, z)` for a frozen slots dataclass, setting the slots directly (half the time).

    The builder makes ~25 Pos and Span per line. Other fields get their plain defaults; a
    class with a __post_init__, a default_factory or a field without default beyond `names`
    gets its ordinary constructor instead, so a change to source.py stays correct.
    """
    extras = [f for f in fields(cls) if f.name not in names]
    if hasattr(cls, "__post_init__") or any(f.default is MISSING or not f.init for f in extras):
        return cls
    set_x, set_y, set_z = (cls.__dict__[n].__set__ for n in names)
    defaults = tuple((cls.__dict__[f.name].__set__, f.default) for f in extras)
    new = object.__new__

    if len(defaults) == 1:  # Span: its `parent`
        (set_w, w), = defaults

        def make_one_default(x: Any, y: Any, z: Any) -> Any:
            obj: Any = new(cls)
            set_x(obj, x)
            set_y(obj, y)
            set_z(obj, z)
            set_w(obj, w)
            return obj

        return make_one_default

    def make(x: Any, y: Any, z: Any) -> Any:
        obj: Any = new(cls)
        set_x(obj, x)
        set_y(obj, y)
        set_z(obj, z)
        for set_default, default in defaults:
            set_default(obj, default)
        return obj

    return make


def _fast_node(cls: Callable[..., T]) -> Callable[..., T]:
    """`cls(*every field)` for a frozen slots dataclass (an AST node), setting the slots directly.

    The builder makes ~11 nodes per line; a frozen dataclass's __init__ goes through
    `object.__setattr__` per field, this through the slot descriptors (about half the time).
    The same object results (same class, same field values). Only for classes whose fields
    are all set from positional arguments; any other class keeps its own constructor.
    """
    assert isinstance(cls, type)
    names = [f.name for f in fields(cls)]
    if hasattr(cls, "__post_init__") or not all(f.init for f in fields(cls)) or not 2 <= len(names) <= 5:
        return cls
    s = [cls.__dict__[n].__set__ for n in names]
    new = object.__new__
    if len(s) == 2:
        s0, s1 = s

        def make2(a: Any, b: Any) -> Any:
            obj: Any = new(cls)
            s0(obj, a)
            s1(obj, b)
            return obj

        return make2
    if len(s) == 3:
        s0, s1, s2 = s

        def make3(a: Any, b: Any, c: Any) -> Any:
            obj: Any = new(cls)
            s0(obj, a)
            s1(obj, b)
            s2(obj, c)
            return obj

        return make3
    if len(s) == 4:
        s0, s1, s2, s3 = s

        def make4(a: Any, b: Any, c: Any, d: Any) -> Any:
            obj: Any = new(cls)
            s0(obj, a)
            s1(obj, b)
            s2(obj, c)
            s3(obj, d)
            return obj

        return make4
    s0, s1, s2, s3, s4 = s

    def make5(a: Any, b: Any, c: Any, d: Any, e: Any) -> Any:
        obj: Any = new(cls)
        s0(obj, a)
        s1(obj, b)
        s2(obj, c)
        s3(obj, d)
        s4(obj, e)
        return obj

    return make5


_make_pos = _fast_constructor(Pos, ("line", "col", "offset"))


_make_span = _fast_constructor(Span, ("file", "start", "end"))


def _fast_token_span() -> Any:
    """`Span(file, Pos(a.line, a.column, a.start_pos), Pos(b.end_line, b.end_column, b.end_pos))`
    for tokens `a` .. `b` in one call (the builder makes one per name, number and string).

    The same three objects as through _make_pos / _make_span, without two of the calls; if
    either class stops fitting that shape it is built the ordinary way."""
    if _make_pos is Pos or _make_span is Span or [f.name for f in fields(Span)] != [
            "file", "start", "end", "parent"]:
        return lambda file, a, b: Span(file, Pos(a.line, a.column, a.start_pos),
                                       Pos(b.end_line, b.end_column, b.end_pos))
    line, col, offset = (Pos.__dict__[n].__set__ for n in ("line", "col", "offset"))
    set_file, set_start, set_end, set_parent = (
        Span.__dict__[n].__set__ for n in ("file", "start", "end", "parent"))
    new = object.__new__

    def token_span(file: SourceFile, a: Token, b: Token) -> Span:
        start: Any = new(Pos)
        line(start, a.line)
        col(start, a.column)
        offset(start, a.start_pos)
        end: Any = new(Pos)
        line(end, b.end_line)
        col(end, b.end_column)
        offset(end, b.end_pos)
        span: Any = new(Span)
        set_file(span, file)
        set_start(span, start)
        set_end(span, end)
        set_parent(span, None)
        return span

    return token_span


_tokens_span = _fast_token_span()


# The AST nodes the builder makes most, built through their slots (see _fast_node).
_Number = _fast_node(ast.Number)


_Arg = _fast_node(ast.Arg)


_Ident = _fast_node(ast.Ident)


_Name = _fast_node(ast.Name)


_Setting = _fast_node(ast.Setting)


_Call = _fast_node(ast.Call)


_Move = _fast_node(ast.Move)


_IoRef = _fast_node(ast.IoRef)


_SetIo = _fast_node(ast.SetIo)


_Condition = _fast_node(ast.Condition)


_TargetDecl = _fast_node(ast.TargetDecl)


_WaitTime = _fast_node(ast.WaitTime)


_BinOp = _fast_node(ast.BinOp)


_IfStmt = _fast_node(ast.IfStmt)


_WaitUntil = _fast_node(ast.WaitUntil)


_Joints = _fast_node(ast.Joints)


_Neg = _fast_node(ast.Neg)


_Vector = _fast_node(ast.Vector)


_String = _fast_node(ast.String)


_Attr = _fast_node(ast.Attr)


_Compare = _fast_node(ast.Compare)


_Logic = _fast_node(ast.Logic)


_NotCond = _fast_node(ast.NotCond)


_Pulse = _fast_node(ast.Pulse)


_For = _fast_node(ast.For)


_Repeat = _fast_node(ast.Repeat)


_CallStmt = _fast_node(ast.CallStmt)


_AssignStmt = _fast_node(ast.AssignStmt)


_VarDecl = _fast_node(ast.VarDecl)


_While = _fast_node(ast.While)


_ConstDecl = _fast_node(ast.ConstDecl)


def reserved_statement(word: str, span: Span) -> Diagnostic:
    """E008 for a reserved word written as a statement (`return`)."""
    msg = f"'{word}' is reserved for future use: {RESERVED[word]} (got '{word}' as a statement)"
    return Diagnostic(codes.RESERVED_KEYWORD, Severity.ERROR, msg, span)


def token_span(file: SourceFile, tok: Token) -> Span:
    # lark types a token's position as int | None; tokens of a parse always carry one (no
    # cast: this runs once per token)
    return Span(file, Pos(tok.line, tok.column, tok.start_pos),  # type: ignore[arg-type]
                Pos(tok.end_line, tok.end_column, tok.end_pos))  # type: ignore[arg-type]


def _unquote(tok: Token) -> str:
    return _ESCAPE.sub(r"\1", str(tok)[1:-1])
