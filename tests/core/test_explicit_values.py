"""Values reach the code that reads them through its signature: no module of lang, compiler,
backends or sim imports `contextvars` (the task's torque limits, for one, are an argument of
the timeline builder and of move_chain.time_chain, not a ContextVar set around the call)."""

from __future__ import annotations

import ast
import inspect
from pathlib import Path

import pytest

from rmot.compiler.plan import move_chain, timeline

ROOT = Path(__file__).resolve().parents[2]
MODULES = sorted(p for pkg in ("lang", "compiler", "backends", "sim") for p in (ROOT / pkg).rglob("*.py"))


def _imports_contextvars(text: str) -> bool:
    for node in ast.walk(ast.parse(text)):
        if isinstance(node, ast.Import) and any(a.name == "contextvars" for a in node.names):
            return True
        if isinstance(node, ast.ImportFrom) and node.module == "contextvars":
            return True
    return False


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(ROOT)))
def test_no_value_is_handed_through_a_context_variable(path: Path) -> None:
    assert not _imports_contextvars(path.read_text(encoding="utf-8"))


def test_the_scan_sees_both_import_forms() -> None:
    assert _imports_contextvars("import contextvars\n")
    assert _imports_contextvars("from contextvars import ContextVar\n")
    assert not _imports_contextvars("import context\n")


def test_torque_limits_are_a_parameter_of_the_timing() -> None:
    assert "torque" in inspect.signature(timeline.build_task).parameters
    assert "torque" in inspect.signature(move_chain.time_chain).parameters
