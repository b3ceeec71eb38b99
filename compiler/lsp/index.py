"""The names of parsed .rmot files: where each is declared and where it is used.

Built from the front end's AST (lang/ast.py) of every file a document reads (itself, its
imports, its cell), so go-to-definition and find-references work across `import` and
`use cell`. A use resolves to the declaration of the same name in the innermost enclosing
block (proc, loop, program, task) that declares it, else to a top-level declaration in any
of the files; the front end has already reported names that are not visible.
"""

from __future__ import annotations

import os
from dataclasses import fields, is_dataclass
from typing import Any

from rmot.lang import ast
from rmot.lang.record import record
from rmot.lang.source import Span

__all__ = ["Symbol", "SymbolIndex", "build_index", "contains", "field_names"]

# declaration class -> kind shown to users (its `name` field is the declared name)
DECLARATIONS: dict[type, str] = {
    ast.TargetDecl: "target", ast.ConstDecl: "const", ast.ProcDecl: "proc", ast.ToolDecl: "tool",
    ast.FrameDecl: "frame", ast.FixtureDecl: "fixture", ast.PartDecl: "part", ast.RobotDecl: "robot",
    ast.ProgramDecl: "program", ast.CellDecl: "cell", ast.Param: "param", ast.VarDecl: "var",
    ast.ModelDecl: "model",
}
# blocks whose declarations are local to them
_BLOCKS = (ast.ProgramDecl, ast.TaskDecl, ast.ProcDecl, ast.For, ast.Repeat, ast.IfStmt, ast.While)
# Ident fields that are neither a declaration nor a use of a declared name: keyword
# arguments, attributes, geometry and type words, library names, vendors, sync barriers
_NOT_NAMES = {
    (ast.Arg, "name"), (ast.Attr, "name"), (ast.Geometry, "kind"), (ast.Call, "func"),
    (ast.Param, "type"), (ast.NativeStmt, "vendor"), (ast.SyncStmt, "name"),
    (ast.RobotDecl, "library"), (ast.VarDecl, "type"), (ast.ModelJoint, "kind"),
}


@record(slots=True)
class Symbol:
    """One occurrence of a name: a declaration (`kind` set) or a use (`kind` is "")."""

    name: str
    span: Span
    kind: str = ""
    scope: Span | None = None  # the enclosing block (None: top level of its file)
    node: Any = None  # the declaration node (declarations only)

    @property
    def path(self) -> str:
        return os.path.abspath(self.span.path)


def contains(span: Span, line: int, col: int) -> bool:
    """Whether 1-based (line, col) lies in span, its end included (a cursor after a word)."""
    start, end = span.start, span.end
    if (line, col) < (start.line, start.col):
        return False
    return (line, col) <= (end.line, end.col)


class SymbolIndex:
    """Declarations and uses of every file of an analysis."""

    def __init__(self, symbols: list[Symbol]) -> None:
        self.symbols = symbols
        self.declarations = [s for s in symbols if s.kind]
        self._declared: dict[str, list[Symbol]] = {}
        for d in self.declarations:
            self._declared.setdefault(d.name, []).append(d)

    def at(self, path: str, line: int, col: int) -> Symbol | None:
        """The occurrence under the 1-based (line, col) of `path`, if any."""
        path = os.path.abspath(path)
        for s in self.symbols:
            if s.path == path and contains(s.span, line, col):
                return s
        return None

    def definition(self, symbol: Symbol) -> Symbol | None:
        """The declaration `symbol` names (itself when it is one)."""
        if symbol.kind:
            return symbol
        same = self._declared.get(symbol.name, [])
        local = [d for d in same if d.scope is not None and d.path == symbol.path
                 and _within(symbol.span, d.scope)]
        if local:  # innermost block first
            return max(local, key=lambda d: (d.scope.start.offset if d.scope else -1))
        top = [d for d in same if d.scope is None]
        here = [d for d in top if d.path == symbol.path]
        candidates = here or top
        return candidates[0] if candidates else None

    def references(self, declaration: Symbol) -> list[Symbol]:
        """Every occurrence that resolves to `declaration`, the declaration included."""
        return [s for s in self.symbols if s.name == declaration.name and self.definition(s) == declaration]

    def visible(self, path: str, line: int, col: int, kinds: frozenset[str] | None = None) -> list[Symbol]:
        """Declarations visible at a position: its blocks' and every file's top level."""
        path = os.path.abspath(path)
        out: dict[str, Symbol] = {}
        for d in self.declarations:
            if kinds is not None and d.kind not in kinds:
                continue
            if d.scope is None or (d.path == path and contains(d.scope, line, col)):
                out.setdefault(d.name, d)
        return sorted(out.values(), key=lambda d: d.name)


def _within(inner: Span, outer: Span) -> bool:
    return outer.start.offset <= inner.start.offset and inner.end.offset <= outer.end.offset


def build_index(modules: list[ast.Module]) -> SymbolIndex:
    symbols: list[Symbol] = []
    for module in modules:
        for stmt in module.body:
            _walk(stmt, None, symbols)
    return SymbolIndex(symbols)


_FIELD_NAMES: dict[type, tuple[str, ...]] = {}


def field_names(cls: type) -> tuple[str, ...]:
    """The fields of an AST class, looked up once per class (dataclasses.fields is slow)."""
    names = _FIELD_NAMES.get(cls)
    if names is None:
        names = _FIELD_NAMES[cls] = tuple(f.name for f in fields(cls))
    return names


def _walk(node: Any, scope: Span | None, out: list[Symbol]) -> None:
    kind = DECLARATIONS.get(type(node))
    if kind is not None and isinstance(getattr(node, "name", None), ast.Ident):
        out.append(Symbol(node.name.name, node.name.span, kind, scope, node))
    if isinstance(node, ast.For):
        out.append(Symbol(node.var.name, node.var.span, "var", node.span, node))
    if isinstance(node, ast.IoDecl):
        key = io_key(node.io)
        if key is not None:
            out.append(Symbol(key, node.io.span, "io", None, node))
    inner = node.span if isinstance(node, _BLOCKS) else scope
    for name in field_names(type(node)):
        value = getattr(node, name)
        if kind is not None and name == "name":
            continue
        if isinstance(node, ast.For) and name == "var":
            continue
        if (type(node), name) in _NOT_NAMES:
            if isinstance(value, tuple):
                _walk_items(value, inner, out)
            continue
        _walk_value(node, value, inner, out)


def _walk_value(parent: Any, value: Any, scope: Span | None, out: list[Symbol]) -> None:
    if isinstance(value, (ast.Ident, ast.Name)):
        out.append(Symbol(value.name, value.span))
    elif isinstance(value, ast.IoRef) and not isinstance(parent, ast.IoDecl):
        key = io_key(value)
        if key is not None:
            out.append(Symbol(key, value.span))
        _walk(value, scope, out)
    elif isinstance(value, tuple):
        _walk_items(value, scope, out)
    elif is_dataclass(value) and hasattr(value, "span"):
        _walk(value, scope, out)


def _walk_items(items: tuple[Any, ...], scope: Span | None, out: list[Symbol]) -> None:
    for item in items:
        _walk_value(None, item, scope, out)


def io_key(io: ast.IoRef) -> str | None:
    """`out[1]`: the name an I/O port is declared and used by (a literal port number only)."""
    if isinstance(io.index, ast.Number) and io.index.unit is None and float(io.index.value).is_integer():
        return f"{io.kind}[{int(io.index.value)}]"
    return None
