"""No two modules of lang, compiler, backends and sim import each other, directly or round a
longer loop, counting the imports inside functions too (a late import hides a cycle from
Python, not from a reader). Imports under `if TYPE_CHECKING:` are for annotations only and
are left out, as the layer contract (`lint-imports`, pyproject's [tool.importlinter]) does.

The graph is read from the source with `ast`; the cycles are its strongly connected
components of more than one module (Tarjan's algorithm)."""

from __future__ import annotations

import ast
from collections.abc import Iterator
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PACKAGES = ("lang", "compiler", "backends", "sim")

# Cycles that remain, each with what breaking it takes (none now). Listed so the test fails
# both on a new cycle and when one of these is broken (then delete its row).
KNOWN: set[frozenset[str]] = set()


def module_name(path: Path, root: Path = ROOT) -> str:
    parts = list(path.relative_to(root).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(["rmot", *parts])


def _statements(body: list[ast.stmt]) -> Iterator[ast.stmt]:
    """Every statement, at any depth, except those under `if TYPE_CHECKING:`."""
    for stmt in body:
        if isinstance(stmt, ast.If) and "TYPE_CHECKING" in ast.unparse(stmt.test):
            yield from _statements(stmt.orelse)
            continue
        yield stmt
        for field in ("body", "orelse", "finalbody"):
            yield from _statements(getattr(stmt, field, []))
        for handler in getattr(stmt, "handlers", []):
            yield from _statements(handler.body)


def imported(text: str, modules: set[str]) -> set[str]:
    """The modules of `modules` that the source `text` imports (the nearest enclosing module
    for `from package import name` when name is not a module)."""
    def resolve(name: str) -> str | None:
        while name and name not in modules:
            name = name.rpartition(".")[0]
        return name or None

    found: set[str] = set()
    for stmt in _statements(ast.parse(text).body):
        names: list[str] = []
        if isinstance(stmt, ast.Import):
            names = [a.name for a in stmt.names]
        elif isinstance(stmt, ast.ImportFrom) and stmt.module and stmt.level == 0:
            names = [f"{stmt.module}.{a.name}" for a in stmt.names]
        found.update(r for r in map(resolve, names) if r is not None)
    return found


def import_graph(root: Path = ROOT) -> dict[str, set[str]]:
    paths = {module_name(p, root): p for pkg in PACKAGES for p in (root / pkg).rglob("*.py")}
    modules = set(paths)
    return {m: imported(p.read_text(encoding="utf-8"), modules) - {m} for m, p in paths.items()}


def cycles(graph: dict[str, set[str]]) -> set[frozenset[str]]:
    """The strongly connected components with more than one module (iterative Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: set[frozenset[str]] = set()
    for start in sorted(graph):
        if start in index:
            continue
        work = [(start, iter(sorted(graph[start])))]
        index[start] = low[start] = len(index)
        stack.append(start)
        on_stack.add(start)
        while work:
            node, children = work[-1]
            child = next(children, None)
            if child is not None:
                if child not in index:
                    index[child] = low[child] = len(index)
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(sorted(graph.get(child, ())))))
                elif child in on_stack:
                    low[node] = min(low[node], index[child])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                component = set()
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    component.add(member)
                    if member == node:
                        break
                if len(component) > 1:
                    found.add(frozenset(component))
    return found


def test_no_import_cycle_beyond_the_known_ones() -> None:
    found = cycles(import_graph())
    assert found - KNOWN == set(), f"new import cycles: {[sorted(c) for c in found - KNOWN]}"
    assert KNOWN - found == set(), f"broken, delete from KNOWN: {[sorted(c) for c in KNOWN - found]}"


def test_the_cycle_finder_sees_late_imports_and_longer_loops() -> None:
    modules = {"rmot.a", "rmot.b", "rmot.c", "rmot.d"}
    texts = {
        "rmot.a": "from rmot import b\n",
        "rmot.b": "def f():\n    from rmot.c import x\n",
        "rmot.c": "import rmot.a\n",
        "rmot.d": "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    import rmot.a\n",
    }
    graph = {m: imported(t, modules) - {m} for m, t in texts.items()}
    assert cycles(graph) == {frozenset({"rmot.a", "rmot.b", "rmot.c"})}
    graph["rmot.a"].add("rmot.d")
    assert cycles(graph) == {frozenset({"rmot.a", "rmot.b", "rmot.c"})}  # d's import: typing only
