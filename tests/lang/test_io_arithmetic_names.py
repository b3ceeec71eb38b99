"""`out`, `ain`, `gin` and `aout` are I/O reads only right before `[`: elsewhere they are
names, so a target, var, proc, param, loop variable or const called so works beside a read of
the port of the same word (`var k = gin * gin[1]`). Each program's IR is checked against the
tree written here by hand from the language's rules (REFERENCE §12); `in` is a keyword
(`for i in`), refused as a declared name (E008).
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from rmot.compiler.frontend import load_text
from rmot.lang import ir, ir_tree

CELL = """cell c {
  robot r1 = abb_irb1600 at pose(z=400mm)
  io gin[1] = "pgno" bits 4
  io ain[1] = "ai1"
  io in[2] = "ready"
  io out[3] = "lamp"
}
"""
INT, NUM = ir.ValueType.INT, ir.ValueType.NUM
AIN, GIN = ir.AnalogInput(1, "ai1"), ir.GroupInput(1, "pgno", 4)
LAMP = ir.OutputRead(port=3, signal="lamp")
READY = ir.InputCondition(port=2, value=True, signal="ready")
NAMES = ["out", "ain", "gin", "aout"]


def _body(text: str, tmp_path: Path) -> tuple[ir.Instr, ...]:
    result = load_text(CELL + text, str(tmp_path / "p.rmot"))
    assert result.program is not None and not result.diagnostics, [str(d) for d in result.diagnostics]
    return result.program.tasks[0].body


@pytest.mark.parametrize("name", NAMES)
def test_a_const_named_like_a_port_beside_a_read(name: str, tmp_path: Path) -> None:
    body = _body(f"const {name} = 3\nprogram p on r1 {{\n  var k = {name} * gin[1]\n"
                 f"  if {name} < ain [1] and out[3] {{ stop }}\n}}\n", tmp_path)
    three = ir.Const(3, INT)
    assert body[0] == ir.VarDecl(uid=1, name="k", type=INT, init=ir.Arith("*", three, GIN, INT))
    assert isinstance(body[1], ir.If)
    assert body[1].condition == ir.Logic("and", (ir.Compare(ir.CompareOp.LT, three, AIN), LAMP))


@pytest.mark.parametrize("name", NAMES)
def test_a_var_named_like_a_port_beside_a_read(name: str, tmp_path: Path) -> None:
    body = _body(f"program p on r1 {{\n  var {name}: num = 2\n  {name} = {name} + ain[1] * 2\n"
                 f"  while {name} > gin[1] or in[2] {{ {name} = {name} - 1 }}\n}}\n", tmp_path)
    mine = ir.VarRef(name, NUM)
    assert isinstance(body[1], ir.Assign)
    assert body[1].value == ir.Arith("+", mine, ir.Arith("*", AIN, ir.Const(2, INT), NUM), NUM)
    assert isinstance(body[2], ir.While)
    assert body[2].condition == ir.Logic("or", (ir.Compare(ir.CompareOp.GT, mine, GIN), READY))


@pytest.mark.parametrize("name", NAMES)
def test_a_target_named_like_a_port(name: str, tmp_path: Path) -> None:
    body = _body(f"target {name} = joints(0, 90, 0, 0, 0, 0) deg\nprogram p on r1 {{\n"
                 f"  move joint {name}\n  if gin[1] == 1 {{ move joint {name} }}\n}}\n", tmp_path)
    assert isinstance(body[0], ir.Move) and isinstance(body[0].target, ir.JointTarget)
    assert body[0].target.name == name
    assert body[0].target.values == pytest.approx((0.0, math.radians(90), 0.0, 0.0, 0.0, 0.0))
    assert isinstance(body[1], ir.If) and body[1].condition == ir.Compare(ir.CompareOp.EQ, GIN, ir.Const(1, INT))
    assert isinstance(body[1].then[0], ir.Move) and body[1].then[0].target == body[0].target


@pytest.mark.parametrize("name", NAMES)
def test_a_proc_named_like_a_port(name: str, tmp_path: Path) -> None:
    body = _body(f"program p on r1 {{\n  proc {name}() {{ wait 1 s }}\n  {name}()\n"
                 f"  if ain[1] * 2 > 3 {{ {name}() }}\n}}\n", tmp_path)
    waits = [n for n in ir_tree.walk(body) if isinstance(n, ir.WaitTime)]
    assert [w.duration for w in waits] == [1.0, 1.0]
    branch = next(n for n in body if isinstance(n, ir.If))
    assert branch.condition == ir.Compare(ir.CompareOp.GT, ir.Arith("*", AIN, ir.Const(2, INT), NUM), ir.Const(3, INT))


@pytest.mark.parametrize("text", ["var in = 1", "target in = joints(0, 0, 0, 0, 0, 0) deg"])
def test_in_stays_a_keyword(text: str, tmp_path: Path) -> None:
    result = load_text(f"{CELL}program p on r1 {{\n  {text}\n}}\n", str(tmp_path / "p.rmot"))
    assert [(d.code.id, d.span.start.line if d.span else 0) for d in result.diagnostics if d.is_error][:1] == [("E008", 9)]


@pytest.mark.parametrize(
    ("text", "tree"),
    [("in[2] == out[3]", ir.Compare(ir.CompareOp.EQ, READY, LAMP)),
     ("out[3] != in[2]", ir.Compare(ir.CompareOp.NE, READY, LAMP)),  # == and != are symmetric: the input first
     ("in[2] != (gin[1] > 3)", None)],
)
def test_an_input_compared_with_another_read_is_a_runtime_comparison(text: str, tree: ir.Condition | None,
                                                                     tmp_path: Path) -> None:
    """The level an input is compared with may itself be read while the program runs: the
    comparison is the controller's (never a value rmot computes first, E169)."""
    result = load_text(f"{CELL}program p on r1 {{\n  if {text} {{ stop }}\n}}\n", str(tmp_path / "p.rmot"))
    if tree is None:  # a condition in parentheses is no operand of `==`: a syntax error
        assert [d.code.id for d in result.diagnostics] == ["E001"]
        return
    assert result.program is not None and not result.diagnostics, [str(d) for d in result.diagnostics]
    branch = result.program.tasks[0].body[0]
    assert isinstance(branch, ir.If) and branch.condition == tree


def test_an_input_compared_with_a_number_read_is_e151(tmp_path: Path) -> None:
    result = load_text(f"{CELL}program p on r1 {{\n  if in[2] == ain[1] + 1 {{ stop }}\n}}\n", str(tmp_path / "p.rmot"))
    assert [(d.code.id, d.span.start.line, d.span.start.col) for d in result.diagnostics if d.span] == [("E151", 9, 15)]


def test_a_param_and_a_loop_variable_named_like_ports(tmp_path: Path) -> None:
    """A proc's parameters `gin` and `out` (a number, a target) and a loop variable `ain`,
    each read beside the port of the same word."""
    body = _body("target home = joints(0, 90, 0, 0, 0, 0) deg\nprogram p on r1 {\n"
                 "  proc f(gin: number, out: target) {\n    move joint out\n    if gin[1] > gin { stop }\n  }\n"
                 "  f(2, home)\n  for ain in 1..2 { if ain[1] > ain { stop } }\n}\n", tmp_path)
    conditions = [n.condition for n in ir_tree.walk(body) if isinstance(n, ir.If)]
    assert conditions[0] == ir.Compare(ir.CompareOp.GT, GIN, ir.Const(2, INT))
    counter = ir.VarRef("ain", INT)
    assert {c for c in conditions[1:]} == {ir.Compare(ir.CompareOp.GT, AIN, counter)}, conditions
    moves = [n for n in ir_tree.walk(body) if isinstance(n, ir.Move)]
    assert len(moves) == 1 and isinstance(moves[0].target, ir.JointTarget) and moves[0].target.name == "home"


def test_a_port_word_without_its_index_says_how_a_read_is_written(tmp_path: Path) -> None:
    """`if ain > 3` with no var `ain`: `ain` away from `[` is a name, unknown here, and the
    message shows the read's form."""
    result = load_text(f"{CELL}program p on r1 {{\n  if ain > 3 {{ stop }}\n}}\n", str(tmp_path / "p.rmot"))
    found = [(d.code.id, d.span.start.line, d.span.start.col, d.message) for d in result.diagnostics if d.span]
    assert found == [("E150", 9, 6, "unknown variable 'ain'; a read of an I/O port is written ain[n]")]
