"""Runtime logic in the front end: parsing, typing and lowering of var, assignment,
conditions, while, wait-until timeout branches, stop, and for/repeat as ir.Loop.

The expected IR is written out by hand from the language's rules (REFERENCE.md §12), not
taken from the lowering's output.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from rmot.lang import ir, ir_tree
from rmot.compiler.frontend import load_text
from rmot.lang.ir_tree import bind_loop_variable, iteration_paths
from rmot.lang import ast
from rmot.lang.parse import parse_text

HOME = "target home = joints(0, -10, 10, 0, 90, 0) deg"


def _program(body: str, tmp_path: Path) -> tuple[ir.Program | None, list[tuple[str, str]]]:
    text = f"program p on r1 {{\n  {HOME}\n{body}\n}}\n"
    result = load_text(text, str(tmp_path / "p.rmot"))
    return result.program, [(d.code.id, d.message) for d in result.diagnostics]


def _in(port: int, value: bool, signal: str | None = None) -> ir.InputCondition:
    return ir.InputCondition(port=port, value=value, signal=signal)


def _body(body: str, tmp_path: Path) -> tuple[ir.Instr, ...]:
    prog, diags = _program(body, tmp_path)
    assert prog is not None and [c for c, _ in diags if c.startswith("E")] == [], diags
    return prog.tasks[0].body


def _stmts(text: str) -> tuple[ast.Stmt, ...]:
    result = parse_text(f"program p on r1 {{\n{text}\n}}\n")
    assert result.diagnostics == (), result.diagnostics
    assert result.module is not None
    prog = result.module.body[0]
    assert isinstance(prog, ast.ProgramDecl)
    return prog.body


class TestParse:
    def test_while_is_a_loop_not_a_call(self) -> None:
        (stmt,) = _stmts("while in[2] == off { wait 1 s }")
        assert isinstance(stmt, ast.While) and len(stmt.body) == 1

    def test_var_is_a_declaration(self) -> None:
        (stmt,) = _stmts("var count = 0")
        assert isinstance(stmt, ast.VarDecl) and stmt.name.name == "count" and stmt.type is None

    def test_and_binds_tighter_than_or_and_not_tighter_than_and(self) -> None:
        (stmt,) = _stmts("if in[1] or in[2] and not in[3] { stop }")
        assert isinstance(stmt, ast.IfStmt)
        cond = stmt.condition
        assert isinstance(cond, ast.Logic) and cond.op == "or"
        right = cond.operands[1]
        assert (
            isinstance(right, ast.Logic)
            and right.op == "and"
            and isinstance(right.operands[1], ast.NotCond)
        )

    def test_parentheses_group_conditions_and_arithmetic(self) -> None:
        (a, b) = _stmts("if (in[1] or in[2]) and in[3] { stop }\nif (n + 1) * 2 > 3 { stop }")
        assert (
            isinstance(a, ast.IfStmt)
            and isinstance(a.condition, ast.Logic)
            and a.condition.op == "and"
        )
        assert (
            isinstance(b, ast.IfStmt)
            and isinstance(b.condition, ast.Compare)
            and b.condition.op == ">"
        )
        assert isinstance(b.condition.left, ast.BinOp) and b.condition.left.op == "*"

    def test_unknown_statement_lists_the_language_words(self) -> None:
        result = parse_text("program p on r1 {\n  loop { }\n}\n")
        (d,) = result.diagnostics
        assert (
            "unknown statement 'loop'" in d.message
            and "while" in d.message
            and "repeat" in d.message
        )

    def test_var_and_let_never_suggest_via(self) -> None:
        for word in ("let x = 1", "dim x = 1", "var x = 1"):
            result = parse_text(f"program p on r1 {{\n  {word}\n}}\n")
            assert all("via" not in d.message for d in result.diagnostics), result.diagnostics
        (d,) = parse_text("program p on r1 {\n  let x = 1\n}\n").diagnostics
        assert "'var NAME" in d.message

    def test_stop_remains_usable_as_a_target_name(self) -> None:
        """weld_seam.rmot names a target `stop`: a name wherever no statement starts."""
        stmts = _stmts("target stop = pose(x=1mm)\nmove linear stop\nstop")
        assert isinstance(stmts[1], ast.Move) and isinstance(stmts[2], ast.StopStmt)


class TestLowering:
    def test_conditions_lower_to_the_ir_by_the_rules(self, tmp_path: Path) -> None:
        body = _body(
            """
  if in[1] == on and in[2] == off { stop }
  if ain[1] > 4.5 { stop }
  if in[3] == on { stop }
  if not in[4] { stop }
""",
            tmp_path,
        )
        conds = [i.condition for i in body if isinstance(i, ir.If)]
        assert conds == [
            ir.Logic("and", (_in(1, True, "gripper_closed"), _in(2, False, "part_present"))),
            ir.Compare(ir.CompareOp.GT, ir.AnalogInput(1), ir.Const(4.5, ir.ValueType.NUM)),
            _in(3, True, "pallet_present"),
            _in(4, False),
        ]

    def test_arithmetic_types(self, tmp_path: Path) -> None:
        body = _body(
            """
  var a: int = 2
  var x: num = 1
  var i1 = a * a
  var n1 = a / a
  var n2 = a + x
  var b = a * 2 >= x
""",
            tmp_path,
        )
        decls = {i.name: i for i in body if isinstance(i, ir.VarDecl)}
        int_t, num_t, bool_t = ir.ValueType.INT, ir.ValueType.NUM, ir.ValueType.BOOL
        assert {n: d.type for n, d in decls.items()} == {
            "a": int_t,
            "x": num_t,
            "i1": int_t,
            "n1": num_t,
            "n2": num_t,
            "b": bool_t,
        }
        assert decls["x"].init == ir.Const(1, int_t)  # an int value widens into the num var
        assert decls["n1"].init == ir.Arith(
            "/", ir.VarRef("a", int_t), ir.VarRef("a", int_t), num_t
        )

    def test_assignment_and_while_and_stop(self, tmp_path: Path) -> None:
        body = _body(
            """
  var count = 0
  while in[2] == on and count < 3 {
    count = count + 1
  }
  stop
""",
            tmp_path,
        )
        decl, loop, stop = body
        assert isinstance(decl, ir.VarDecl) and isinstance(stop, ir.Stop)
        assert isinstance(loop, ir.While)
        int_t = ir.ValueType.INT
        assert loop.condition == ir.Logic(
            "and",
            (
                _in(2, True, "part_present"),
                ir.Compare(ir.CompareOp.LT, ir.VarRef("count", int_t), ir.Const(3, int_t)),
            ),
        )
        assert loop.body == (
            ir.Assign(
                uid=loop.uid + 1,
                name="count",
                value=ir.Arith("+", ir.VarRef("count", int_t), ir.Const(1, int_t), int_t),
            ),
        )

    def test_wait_until_timeout_branches(self, tmp_path: Path) -> None:
        body = _body(
            """
  var ok = on
  wait until in[1] == on timeout 2 s else { set out[1] = off }
  wait until in[1] == on and ok timeout 3 s else { stop }
  wait until in[2] timeout 1 s
""",
            tmp_path,
        )
        _, plain, general, bare = body
        assert isinstance(plain, ir.WaitInput) and plain.timeout == 2.0
        assert [type(i) for i in plain.on_timeout] == [ir.SetDigital]
        assert isinstance(general, ir.WaitCondition) and general.timeout == 3.0
        assert [type(i) for i in general.on_timeout] == [ir.Stop]
        assert isinstance(bare, ir.WaitInput) and bare.on_timeout == ()

    def test_nested_for_is_nested_loops_with_every_iteration(self, tmp_path: Path) -> None:
        body = _body(
            """
  move joint home
  for layer in 0 .. 2 {
    for row in 1 .. 4 {
      move joint home
    }
  }
  repeat 2 { wait 1 s }
""",
            tmp_path,
        )
        _, outer, rep = body
        assert isinstance(outer, ir.Loop) and (outer.var, outer.first, outer.last) == (
            "layer",
            0,
            2,
        )
        assert [it.value for it in outer.iterations] == [0, 1]
        for it in outer.iterations:
            (inner,) = it.body
            assert isinstance(inner, ir.Loop) and [i.value for i in inner.iterations] == [1, 2, 3]
        assert isinstance(rep, ir.Loop) and rep.var is None and (rep.first, rep.last) == (0, 2)
        uids = [i.uid for i in ir_tree.walk(body)]
        assert len(uids) == len(set(uids)) == 3 + 2 * (1 + 3) + 2
        paths = iteration_paths(body)
        moves = [i for i in ir_tree.walk(outer.iterations[1].body) if isinstance(i, ir.Move)]
        assert [[(v, x) for _, v, x in paths[m.uid]] for m in moves] == [
            [("layer", 1), ("row", r)] for r in (1, 2, 3)
        ]

    def test_loop_variable_in_a_condition_is_the_vendor_counter(self, tmp_path: Path) -> None:
        body = _body(
            """
  var n = 0
  for i in 0 .. 2 {
    if n > i { stop }
  }
""",
            tmp_path,
        )
        loop = body[1]
        assert isinstance(loop, ir.Loop)
        int_t = ir.ValueType.INT
        cond = loop.iterations[1].body[0].condition  # type: ignore[union-attr]
        assert cond == ir.Compare(ir.CompareOp.GT, ir.VarRef("n", int_t), ir.VarRef("i", int_t))
        (bound,) = bind_loop_variable(loop.iterations[1].body, "i", 1)
        assert bound.condition == ir.Compare(
            ir.CompareOp.GT, ir.VarRef("n", int_t), ir.Const(1, int_t)
        )  # type: ignore[union-attr]

    def test_unreachable_after_stop_and_empty_timeout_branch_warn(self, tmp_path: Path) -> None:
        _, diags = _program(
            """
  stop
  wait 1 s
  wait until in[1] == on timeout 1 s else { }
""",
            tmp_path,
        )
        assert [c for c, _ in diags] == ["W150", "W151"]

    def test_the_unrolled_size_bound_counts_loops_in_all(self, tmp_path: Path) -> None:
        """compiler/passes/limits.py still bounds the total: 2000 x 2000 rounds is E124."""
        _, diags = _program("for i in 0 .. 2000 {\n for j in 0 .. 2000 { wait 1 ms }\n}", tmp_path)
        assert "E124" in [c for c, _ in diags]


@settings(max_examples=25, deadline=None)
@given(st.integers(-5, 5), st.integers(-5, 8))
def test_for_iterations_are_the_half_open_range(
    tmp_path_factory: pytest.TempPathFactory, first: int, last: int
) -> None:
    """Every value first, first+1, ..., last-1 in order (none when last <= first), each with
    its own uids."""
    body = _body(f"for k in {first} .. {last} {{ wait 1 ms }}", tmp_path_factory.mktemp("r"))
    (loop,) = body
    assert isinstance(loop, ir.Loop)
    assert [it.value for it in loop.iterations] == [v for v in range(-10, 10) if first <= v < last]
    uids = [i.uid for i in ir_tree.walk(body)]
    assert len(set(uids)) == len(uids)


_LEAVES = st.sampled_from([("a", False), ("x", True), ("2", False), ("1.5", True)])


def _exprs() -> st.SearchStrategy[tuple[str, bool]]:
    """(text, is num) of random arithmetic over int var a, num var x and literals; the type
    rule computed here on its own: num when any operand is num or the operator is '/'."""

    def combine(
        children: st.SearchStrategy[tuple[str, bool]],
    ) -> st.SearchStrategy[tuple[str, bool]]:
        ops = st.sampled_from(["+", "-", "*", "/"])
        return st.tuples(children, ops, children).map(
            lambda t: (f"({t[0][0]} {t[1]} {t[2][0]})", t[0][1] or t[2][1] or t[1] == "/")
        )

    return st.recursive(_LEAVES, combine, max_leaves=6)


@settings(max_examples=20, deadline=None)
@given(_exprs())
def test_arithmetic_type_follows_the_rule(
    tmp_path_factory: pytest.TempPathFactory, expr: tuple[str, bool]
) -> None:
    text, is_num = expr
    prog, diags = _program(
        f"var a: int = 1\nvar x: num = 1\nvar r = {text}", tmp_path_factory.mktemp("t")
    )
    assume("E162" not in [c for c, _ in diags])  # a constant part folded to 0 under a '/'
    assert prog is not None and [c for c, _ in diags] == []
    decl = prog.tasks[0].body[-1]
    assert isinstance(decl, ir.VarDecl)
    assert decl.type is (ir.ValueType.NUM if is_num else ir.ValueType.INT)
