"""Readable sizes and imports where a reader looks for them: no module over 600 lines without
the reason in its docstring ("Over 600 lines: ..."), no function over 60 lines without the
reason in its docstring ("Long on purpose: ..."), and every import of an rmot module inside a
function says on its line why it is there and not at the top (`# late: <reason>`).

The witness is the source itself, read with `ast` (line counts, docstrings, where each import
statement sits)."""

from __future__ import annotations

import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PACKAGES = ("lang", "compiler", "backends", "sim")
LIMIT = 600
FUNCTION_LIMIT = 60


def _modules() -> list[Path]:
    return sorted(p for pkg in PACKAGES for p in (ROOT / pkg).rglob("*.py"))


def long_functions(paths: list[Path]) -> list[str]:
    """Functions over FUNCTION_LIMIT lines (decorators excluded) whose docstring gives no reason."""
    out = []
    for path in paths:
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                n = (node.end_lineno or node.lineno) - node.lineno + 1
                if n > FUNCTION_LIMIT and "on purpose" not in (ast.get_docstring(node) or "").lower():
                    out.append(f"{path.relative_to(ROOT)}:{node.lineno} {node.name}: {n} lines")
    return out


def _late_imports(tree: ast.Module) -> list[ast.Import | ast.ImportFrom]:
    found: list[ast.Import | ast.ImportFrom] = []
    for func in ast.walk(tree):
        if isinstance(func, (ast.FunctionDef, ast.AsyncFunctionDef)):
            found += [n for n in ast.walk(func) if isinstance(n, (ast.Import, ast.ImportFrom))]
    return list({id(n): n for n in found}.values())


def oversized(paths: list[Path]) -> list[str]:
    """Modules over LIMIT lines whose docstring gives no reason."""
    out = []
    for path in paths:
        text = path.read_text(encoding="utf-8")
        n = len(text.splitlines())
        if n > LIMIT and "over 600 lines" not in (ast.get_docstring(ast.parse(text)) or "").lower():
            out.append(f"{path.relative_to(ROOT)}: {n} lines")
    return out


def unexplained_late_imports(paths: list[Path]) -> list[str]:
    """Imports of rmot modules inside functions without `# late:` on their first line."""
    out = []
    for path in paths:
        text = path.read_text(encoding="utf-8")
        lines = text.splitlines()
        for node in _late_imports(ast.parse(text)):
            names = [a.name for a in node.names] if isinstance(node, ast.Import) else [node.module or ""]
            if any(n.split(".")[0] == "rmot" for n in names) and "# late:" not in lines[node.lineno - 1]:
                out.append(f"{path.relative_to(ROOT)}:{node.lineno}")
    return out


def test_no_module_over_600_lines_without_a_reason() -> None:
    assert oversized(_modules()) == []


def test_no_function_over_60_lines_without_a_reason() -> None:
    assert long_functions(_modules()) == []


def test_every_late_import_of_an_rmot_module_gives_its_reason() -> None:
    bad = unexplained_late_imports(_modules())
    assert bad == [], f"{len(bad)} imports inside functions without `# late: <reason>`: {bad[:20]}"


def test_the_checks_see_a_long_module_and_a_bare_late_import(tmp_path: Path) -> None:
    """Both checks fail on a module that breaks them and pass once it gives its reasons."""
    global ROOT
    saved, ROOT = ROOT, tmp_path
    try:
        body = "x = 1\n" * LIMIT
        long = tmp_path / "long.py"
        long.write_text(f'"""A module."""\n{body}', encoding="utf-8")
        assert oversized([long]) == ["long.py: 601 lines"]
        long.write_text(f'"""A module.\n\nOver 600 lines: a table."""\n{body}', encoding="utf-8")
        assert oversized([long]) == []
        body = "".join(f"    x{i} = {i}\n" for i in range(FUNCTION_LIMIT))
        func = tmp_path / "func.py"
        func.write_text(f'def f():\n    """A function."""\n{body}', encoding="utf-8")
        assert long_functions([func]) == ["func.py:1 f: 62 lines"]
        func.write_text(f'def f():\n    """Long on purpose: a table."""\n{body}', encoding="utf-8")
        assert long_functions([func]) == []
        late = tmp_path / "late.py"
        late.write_text("def f():\n    from rmot.lang import ir\n    import json\n", encoding="utf-8")
        assert unexplained_late_imports([late]) == ["late.py:2"]
        late.write_text("def f():\n    from rmot.lang import ir  # late: a cycle otherwise\n", encoding="utf-8")
        assert unexplained_late_imports([late]) == []
    finally:
        ROOT = saved
