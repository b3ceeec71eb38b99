"""One IR walker: the nesting of IR instructions is known in lang/ir_tree only.

A pass that recurses into the bodies an instruction holds asks `ir_tree.children`, `walk` or
`flow` (how those bodies run) instead of testing `isinstance(x, ir.If)` and reading `.then`;
a dispatcher that prints or plans each kind its own way is a table kind -> handler checked
against `ir_tree.KINDS`. The scan below fails on a new hand-written recursion over nested
bodies; the allow-list names the dispatchers that remain, each with its reason.
"""

from __future__ import annotations

import ast
import dataclasses
from pathlib import Path

import pytest

from rmot.lang import ir, ir_tree

ROOT = Path(__file__).resolve().parents[2]
# the IR kinds that hold bodies, and the fields those bodies live in
NESTING_KINDS = {"If", "ProcCall", "Loop", "While", "WaitInput", "WaitCondition"}
BODY_FIELDS = {"then", "otherwise", "iterations", "on_timeout"}

# (file, function) -> why it may recurse over nested bodies by kind
# (lang/ir_tree.py itself is the walker and is not scanned)
ALLOWED: dict[tuple[str, str], str] = {
    ("backends/loops.py", "analyse"): (
        "calls itself once on the loop without its last iteration (peeling), not on a body"),
    ("backends/loops.py", "_reads"): (
        "a generic dataclass scan for a loop variable's reads; a Loop of the same variable "
        "shadows it (a scoping rule, not nesting)"),
}


def _sources() -> list[Path]:
    return sorted(p for folder in ("compiler", "backends", "sim")
                  for p in (ROOT / folder).rglob("*.py") if p.name != "ir_tree.py")


def _names_nesting_kind(node: ast.AST) -> bool:
    """`ir.If`, `(ir.Loop, ir.While)`, ...: an isinstance class argument naming a nesting kind."""
    return any(isinstance(n, ast.Attribute) and n.attr in NESTING_KINDS
               and isinstance(n.value, ast.Name) and n.value.id == "ir" for n in ast.walk(node))


def _offenders(path: Path) -> list[str]:
    """Functions of `path` that call themselves and test an instruction's nesting kind or read
    the fields its bodies live in."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    rel = path.relative_to(ROOT).as_posix()
    out = []
    for fn in ast.walk(tree):
        if not isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)):
            continue
        calls = [n for n in ast.walk(fn) if isinstance(n, ast.Call)]
        recursive = any(
            (isinstance(c.func, ast.Name) and c.func.id == fn.name)
            or (isinstance(c.func, ast.Attribute) and c.func.attr == fn.name) for c in calls)
        by_kind = any(
            isinstance(c.func, ast.Name) and c.func.id == "isinstance" and len(c.args) == 2
            and _names_nesting_kind(c.args[1]) for c in calls)
        attrs = [n for n in ast.walk(fn) if isinstance(n, ast.Attribute)]
        # reads `.then`, `.iterations`, ... of IR nodes (a walk over lang's syntax tree names
        # no `ir.` at all)
        by_field = any(n.attr in BODY_FIELDS for n in attrs) and any(
            isinstance(n.value, ast.Name) and n.value.id == "ir" for n in attrs)
        if recursive and (by_kind or by_field) and (rel, fn.name) not in ALLOWED:
            out.append(f"{rel}:{fn.lineno} {fn.name}")
    return out


def test_no_hand_written_walk_over_nested_bodies() -> None:
    """Every recursion over If/ProcCall/Loop/While bodies goes through lang/ir_tree."""
    found = [o for p in _sources() for o in _offenders(p)]
    assert not found, (
        "hand-written walks over nested IR bodies (use lang/ir_tree: children, walk, flow; "
        f"or a kind -> handler table checked by ir_tree.require_kinds): {found}")


def test_the_allow_list_names_functions_that_exist_and_still_recurse() -> None:
    """A stale entry would let a new walk of that name in through the back door."""
    for (rel, name), _reason in ALLOWED.items():
        tree = ast.parse((ROOT / rel).read_text(encoding="utf-8"))
        fns = [n for n in ast.walk(tree) if isinstance(n, ast.FunctionDef) and n.name == name]
        assert fns, f"{rel}: no function {name}"


def test_the_scan_catches_a_hand_written_walk() -> None:
    """The scan is not blind: a hand-written walk of the IR nesting is reported."""
    src = ROOT / "compiler" / "_probe_walk.py"
    src.write_text(
        "from rmot.compiler import ir\n\n"
        "def syncs(body):\n"
        "    for i in body:\n"
        "        if isinstance(i, ir.If):\n"
        "            yield from syncs(i.then)\n", encoding="utf-8")
    try:
        assert _offenders(src) == ["compiler/_probe_walk.py:3 syncs"]
    finally:
        src.unlink()


def test_kinds_is_every_instruction_kind_once() -> None:
    """ir_tree.KINDS (what a dispatcher must cover) is ir.Instr, each kind a leaf or nesting."""
    import typing

    assert sorted(k.__name__ for k in ir_tree.KINDS) == sorted(
        k.__name__ for k in typing.get_args(ir.Instr))
    assert not set(ir_tree.LEAVES) & set(ir_tree.NESTING)


def _uid(body: tuple[ir.Instr, ...]) -> list[int]:
    return [i.uid for i in ir_tree.walk(body)]


def test_flow_says_how_each_body_runs() -> None:
    """Against the language's meaning (lang/REFERENCE.md: if, for/repeat, while, wait ...
    timeout ... else), not against ir_tree's own table."""
    wait = ir.WaitTime(uid=1, duration=1.0)
    cond = ir.InputCondition(port=1, value=True)
    stop = ir.Stop(uid=2)
    cases = [
        (ir.If(uid=3, condition=cond, then=(wait,), otherwise=(stop,)),
         ir_tree.Runs.ONE_OF, False),
        (ir.ProcCall(uid=4, proc="p", args=(), body=(wait,)), ir_tree.Runs.CALL, True),
        (ir.While(uid=5, condition=cond, body=(wait,)), ir_tree.Runs.REPEATED, False),
        (ir.WaitInput(uid=6, condition=cond, timeout=1.0, on_timeout=(stop,)),
         ir_tree.Runs.MAYBE, False),
        (wait, ir_tree.Runs.LEAF, False),
    ]
    for instr, runs, sure in cases:
        got, bodies = ir_tree.flow(instr)
        assert (got, got.sure) == (runs, sure), type(instr).__name__
        assert bodies == ir_tree.children(instr)


def test_walk_is_source_order_at_every_depth() -> None:
    cond = ir.InputCondition(port=1, value=True)
    leaf = [ir.WaitTime(uid=u, duration=1.0) for u in range(10, 14)]
    inner = ir.ProcCall(uid=2, proc="p", args=(), body=(leaf[1],))
    body = (ir.If(uid=1, condition=cond, then=(inner,), otherwise=(leaf[2],)), leaf[3])
    assert _uid((leaf[0],) + body) == [10, 1, 2, 11, 12, 13]
    assert _uid((leaf[0],) + body) == [i.uid for i in ir_tree.walk((leaf[0],) + body)]


def test_require_kinds_names_the_missing_kind() -> None:
    table = {k: None for k in ir_tree.KINDS if k is not ir.While}
    with pytest.raises(TypeError, match=r"owner: no handler for instruction kind While"):
        ir_tree.require_kinds("owner", table)
    ir_tree.require_kinds("owner", {**table, ir.While: None})


def test_a_kind_unknown_to_ir_tree_raises() -> None:
    @dataclasses.dataclass(frozen=True)
    class Spline:
        uid: int

    with pytest.raises(TypeError, match="Spline"):
        ir_tree.flow(Spline(1))  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="Spline"):
        list(ir_tree.walk((Spline(1),)))  # type: ignore[arg-type]


def test_every_dispatcher_covers_every_kind() -> None:
    """The per-kind tables (planner, IR dump, every vendor's printer) cover ir_tree.KINDS."""
    from rmot.backends import BACKENDS
    from rmot.compiler import ir_dump
    from rmot.compiler.plan import timeline

    from rmot.backends import neutral

    tables = {"timeline": timeline._PLAN, "ir_dump heads": ir_dump._HEADS,
              "ir_dump labels": ir_dump._LABELS, "JSON kinds": neutral._KIND_LABELS}
    tables.update({f"{name} EMIT": cls.EMIT for name, cls in BACKENDS.items()})
    for owner, table in tables.items():
        ir_tree.require_kinds(owner, table)  # type: ignore[arg-type]
