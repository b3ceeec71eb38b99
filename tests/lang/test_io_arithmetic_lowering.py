"""I/O reads are ordinary atoms of runtime expressions: `ain[n]` (num), `gin[n]` (int), `in[n]`
and `out[n]` (bool) inside arithmetic and on either side of a comparison. The IR each form
lowers to is checked against the tree written here by hand from the language's rules (REFERENCE
§12: `*` `/` before `+` `-`, int unless a num or `/` is involved), and every rule that held for
a bare read still fires at its place: E159 (a unit), E161 (aout), E167 (writing gin), E168 and
W152 (a plain `gin[n] OP constant`, either side), E169 (a read in a compile-time value)."""

from __future__ import annotations

from pathlib import Path

import pytest

from rmot.compiler.frontend import load_text
from rmot.lang import ir

CELL = """cell c {
  robot r1 = abb_irb1600 at pose(z=400mm)
  io gin[1] = "pgno" bits 4
  io ain[1] = "ai1"
  io in[2] = "ready"
}
"""
INT, NUM = ir.ValueType.INT, ir.ValueType.NUM
AIN, GIN = ir.AnalogInput(1, "ai1"), ir.GroupInput(1, "pgno", 4)
READY = ir.InputCondition(port=2, value=True, signal="ready")


def _load(body: str, tmp_path: Path) -> tuple[ir.Program | None, list[tuple[str, int, int]]]:
    text = f"{CELL}program p on r1 {{\n{body}\n}}\n"
    result = load_text(text, str(tmp_path / "p.rmot"))
    diags = [(d.code.id, d.span.start.line, d.span.start.col) for d in result.diagnostics if d.span]
    return result.program, diags


def _first(body: str, tmp_path: Path) -> ir.Instr:
    prog, diags = _load(body, tmp_path)
    assert prog is not None and diags == [], diags
    return prog.tasks[0].body[0]


def _int(v: int) -> ir.Const:
    return ir.Const(v, INT)


@pytest.mark.parametrize(
    ("text", "tree"),
    [
        ("ain[1] * 2 > 3", ir.Compare(ir.CompareOp.GT, ir.Arith("*", AIN, _int(2), NUM), _int(3))),
        ("gin[1] + 1 == 4", ir.Compare(ir.CompareOp.EQ, ir.Arith("+", GIN, _int(1), INT), _int(4))),
        ("2 * gin[1] < 8", ir.Compare(ir.CompareOp.LT, ir.Arith("*", _int(2), GIN, INT), _int(8))),
        ("4.5 < ain[1]", ir.Compare(ir.CompareOp.LT, ir.Const(4.5, NUM), AIN)),
        ("1 + ain[1] / gin[1] >= 2",
         ir.Compare(ir.CompareOp.GE, ir.Arith("+", _int(1), ir.Arith("/", AIN, GIN, NUM), NUM), _int(2))),
        ("gin[1] / 2 > 1", ir.Compare(ir.CompareOp.GT, ir.Arith("/", GIN, _int(2), NUM), _int(1))),
        ("-ain[1] > 1", ir.Compare(ir.CompareOp.GT, ir.Arith("-", _int(0), AIN, NUM), _int(1))),
        ("on == in[2]", READY),
        ("off != in[2]", READY),
        ("ain[1] > gin[1] and in[2]", ir.Logic("and", (ir.Compare(ir.CompareOp.GT, AIN, GIN), READY))),
    ],
)
def test_an_io_read_is_an_atom_of_a_condition(text: str, tree: ir.Condition, tmp_path: Path) -> None:
    branch = _first(f"  if {text} {{ stop }}", tmp_path)
    assert isinstance(branch, ir.If) and branch.condition == tree


def test_an_io_read_inside_a_var_and_a_while(tmp_path: Path) -> None:
    prog, diags = _load("  var v: num = ain[1] / 10 + 0.5\n  var k = gin[1] * 2\n"
                        "  while 2 * gin[1] < k { v = v + 1 }", tmp_path)
    assert prog is not None and diags == [], diags
    v, k, loop = prog.tasks[0].body[:3]
    assert isinstance(v, ir.VarDecl) and v.init == ir.Arith("+", ir.Arith("/", AIN, _int(10), NUM),
                                                             ir.Const(0.5, NUM), NUM)
    assert isinstance(k, ir.VarDecl) and k.init == ir.Arith("*", GIN, _int(2), INT) and k.type is INT
    assert isinstance(loop, ir.While)
    assert loop.condition == ir.Compare(ir.CompareOp.LT, ir.Arith("*", _int(2), GIN, INT), ir.VarRef("k", INT))


@pytest.mark.parametrize(
    ("body", "expected"),
    [
        ("  if ain[1] * 2 mm > 3 { stop }", [("E159", 8, 15)]),
        ("  if aout[1] + 1 > 2 { stop }", [("E161", 8, 6)]),
        ("  if 2 + aout[1] > 2 { stop }", [("E161", 8, 10)]),
        ("  set gin[1] = 3", [("E167", 8, 7)]),
        ("  if 2.5 == gin[1] { stop }", [("E168", 8, 6)]),
        ("  if 16 <= gin[1] { stop }", [("W152", 8, 6)]),
        ("  if gin[1] != -1 { stop }", [("W152", 8, 16)]),
        ("  if in[2] + 1 > 1 { stop }", [("E151", 8, 6)]),
        ("  var b: bool = ain[1] * 2", [("E151", 8, 17)]),
    ],
)
def test_every_rule_still_fires_at_its_place(body: str, expected: list[tuple[str, int, int]],
                                             tmp_path: Path) -> None:
    _, diags = _load(body, tmp_path)
    assert diags == expected


def test_gin_inside_arithmetic_is_not_range_checked(tmp_path: Path) -> None:
    """E168 and W152 are exact for a plain `gin[n] OP constant` only: `gin[1] * 2 == 2.5` or
    `gin[1] + 20 > 16` compare a computed value, which rmot does not bound."""
    _, diags = _load("  if gin[1] * 2 == 2.5 { stop }\n  if gin[1] + 20 > 16 { stop }", tmp_path)
    assert diags == []


@pytest.mark.parametrize(
    ("line", "col"),
    [("const c1 = gin[1] + 1", 1), ("speed ain[1] * 1 mm/s", 7), ("target t = joints(0, in[2], 0, 0, 0, 0) deg", 22)],
)
def test_an_io_read_in_a_compile_time_value_is_e169(line: str, col: int, tmp_path: Path) -> None:
    prefix = "" if line.startswith("const") else "  "
    text = f"{CELL}{line}\n" if line.startswith("const") else f"{CELL}program p on r1 {{\n{prefix}{line}\n}}\n"
    result = load_text(text, str(tmp_path / "p.rmot"))
    errors = [(d.code.id, d.span.start.line) for d in result.diagnostics if d.is_error and d.span]
    assert errors == [("E169", 7 if line.startswith("const") else 8)], result.diagnostics
    assert "runtime expression" in result.diagnostics[0].message
