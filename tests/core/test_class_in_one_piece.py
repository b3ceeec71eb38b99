"""A class is written in one piece: no module of lang, compiler, backends or sim assigns to a
class's attribute after the class (`Backend.emit = ...`, `setattr(Backend, ...)`) or keeps a
class's method aside to wrap it (`_plain = Backend.move`). "Go to definition" then lands on the
code that runs; flags, tables and methods live in the class body (sqlglot's dialect generators
are the model).

The scan reads the source with `ast` (no import): every statement at module level, including
those under a module-level `if`/`for`/`try`, whose target is `C.attr` or whose value is
`C.method`, where C names a class defined in the scanned packages (by its own module or
imported from another)."""

from __future__ import annotations

import ast
from collections.abc import Iterator
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PACKAGES = ("lang", "compiler", "backends", "sim")


def _modules() -> list[Path]:
    return sorted(p for pkg in PACKAGES for p in (ROOT / pkg).rglob("*.py"))


def class_members(sources: dict[str, str]) -> dict[str, set[str]]:
    """Class name -> the methods defined in its body, over all `sources`."""
    members: dict[str, set[str]] = {}
    for text in sources.values():
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, ast.ClassDef):
                members.setdefault(node.name, set()).update(
                    item.name for item in node.body
                    if isinstance(item, (ast.FunctionDef, ast.AsyncFunctionDef)))
    return members


def _module_level(body: list[ast.stmt]) -> Iterator[ast.stmt]:
    """Statements run at import: the module body and the blocks of its if/for/while/with/try."""
    for stmt in body:
        yield stmt
        if isinstance(stmt, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            continue
        for field in ("body", "orelse", "finalbody"):
            yield from _module_level(getattr(stmt, field, []))
        for handler in getattr(stmt, "handlers", []):
            yield from _module_level(handler.body)


def _class_attribute(node: ast.AST, classes: dict[str, set[str]]) -> str | None:
    """'C.attr' when `node` is an attribute of a known class, else None."""
    if (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name)
            and node.value.id in classes):
        return f"{node.value.id}.{node.attr}"
    return None


def class_patches(text: str, classes: dict[str, set[str]]) -> list[str]:
    """'line: what' for every patch of a class after its definition in the module `text`."""
    found: list[str] = []
    for stmt in _module_level(ast.parse(text).body):
        targets: list[ast.expr] = []
        if isinstance(stmt, ast.Assign):
            targets = list(stmt.targets)
        elif isinstance(stmt, (ast.AugAssign, ast.AnnAssign)):
            targets = [stmt.target]
        for target in targets:
            where = _class_attribute(target, classes)
            if where:
                found.append(f"{stmt.lineno}: assigns {where}")
        value = getattr(stmt, "value", None)
        kept = _class_attribute(value, classes) if value is not None else None
        if kept and isinstance(stmt, ast.Assign):
            cls, attr = kept.split(".")
            if attr in classes[cls]:
                found.append(f"{stmt.lineno}: keeps {kept} aside (a method wrapped from outside)")
        if (isinstance(stmt, ast.Expr) and isinstance(stmt.value, ast.Call)
                and isinstance(stmt.value.func, ast.Name) and stmt.value.func.id == "setattr"
                and stmt.value.args and isinstance(stmt.value.args[0], ast.Name)
                and stmt.value.args[0].id in classes):
            found.append(f"{stmt.lineno}: setattr on {stmt.value.args[0].id}")
    return found


SOURCES = {str(p.relative_to(ROOT)): p.read_text(encoding="utf-8") for p in _modules()}
CLASSES = class_members(SOURCES)


@pytest.mark.parametrize("name", sorted(SOURCES))
def test_no_class_is_patched_after_its_definition(name: str) -> None:
    found = class_patches(SOURCES[name], CLASSES)
    assert not found, f"{name}: " + "; ".join(found)


PATCHED = '''
class Backend:
    def instr(self, node): ...
    def emit(self, plan): ...

_dispatch = Backend.instr

def _instr_with_fallbacks(self, node):
    return _dispatch(self, node)

Backend.instr = _instr_with_fallbacks  # type: ignore[method-assign]
Backend.RUNTIME_CONDITIONS = False
Backend.EMIT |= {}
for _method, _fallback in (("loop", None),):
    if not hasattr(Backend, _method):
        setattr(Backend, _method, _fallback)
'''


def test_the_scan_finds_each_kind_of_patch() -> None:
    """The shapes the backends used before they were folded into their classes."""
    found = class_patches(PATCHED, class_members({"x": PATCHED}))
    assert [f.split(": ", 1)[1] for f in found] == [
        "keeps Backend.instr aside (a method wrapped from outside)",
        "assigns Backend.instr", "assigns Backend.RUNTIME_CONDITIONS", "assigns Backend.EMIT",
        "setattr on Backend",
    ]


def test_the_class_body_itself_is_not_a_patch() -> None:
    text = "class A:\n    X = 1\n    def f(self): return A.X\n\nY = A.X\nname = A.__name__\n"
    assert class_patches(text, class_members({"x": text})) == []
