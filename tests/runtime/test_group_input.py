"""Group inputs `gin[n]`: an unsigned integer the controller reads from several digital inputs
(a program number a PLC sends). The cell names it (`io gin[n] = "name" bits B`); conditions and
assignments read it as an int; writing it (E167), a width outside 1..32 or on another kind of
signal (E166), a comparison with a fraction (E168) are located errors; a comparison with a value
outside 0..2^B-1 is W152, located at the value."""

from __future__ import annotations

from pathlib import Path

import pytest

from rmot.compiler.frontend import load_text
from rmot.lang import ir

CELL = """cell c {
  robot r1 = abb_irb1600 at pose(z=400mm)
  io gin[1] = "pgno" bits 8
  io gin[2] = "station"
  io in[1] = "ready"
}
"""


def _load(body: str, tmp_path: Path, cell: str = CELL) -> tuple[ir.Program | None, list[tuple[str, str, int, int]]]:
    text = f"{cell}program p on r1 {{\n{body}\n}}\n"
    result = load_text(text, str(tmp_path / "p.rmot"))
    diags = [(d.code.id, d.message, d.span.start.line, d.span.start.col) for d in result.diagnostics if d.span]
    return result.program, diags


def _codes(diags: list[tuple[str, str, int, int]]) -> list[str]:
    return [c for c, *_ in diags]


def test_a_group_input_reads_as_an_int_with_its_name_and_width(tmp_path: Path) -> None:
    prog, diags = _load("  var n: int = gin[1]\n  if gin[2] >= 4 and in[1] { stop }", tmp_path)
    assert prog is not None and _codes(diags) == [], diags
    decl, branch = prog.tasks[0].body[:2]
    assert isinstance(decl, ir.VarDecl) and decl.init == ir.GroupInput(1, "pgno", 8)
    assert isinstance(branch, ir.If)
    assert branch.condition == ir.Logic("and", (
        ir.Compare(ir.CompareOp.GE, ir.GroupInput(2, "station", None), ir.Const(4, ir.ValueType.INT)),
        ir.InputCondition(port=1, value=True, signal="ready"),
    ))
    signals = {s.port: s for s in prog.cell.io if s.direction is ir.IoDirection.GROUP_IN}
    assert (signals[1].name, signals[1].bits, signals[2].bits) == ("pgno", 8, None)


def test_a_group_input_is_an_int_not_a_num(tmp_path: Path) -> None:
    """An int reads into a num (widening) but gin[n] is never a bool."""
    _, diags = _load("  var x: num = gin[1]\n  var b: bool = gin[1]", tmp_path)
    assert [(c, line) for c, _, line, _ in diags] == [("E151", 9)], diags
    assert "must be bool (got int)" in diags[0][1]


@pytest.mark.parametrize(
    ("value", "warned"),
    [("255", False), ("0", False), ("256", True), ("-1", True), ("300", True)],
)
def test_a_value_outside_the_width_is_a_warning_at_the_value(tmp_path: Path, value: str, warned: bool) -> None:
    """8 bits read 0..255 (2^8 - 1): any other value never equals the input."""
    _, diags = _load(f"  if gin[1] == {value} {{ stop }}", tmp_path)
    found = [d for d in diags if d[0] == "W152"]
    assert bool(found) is warned, diags
    if warned:
        assert found[0][2:] == (8, 16) and "0..255 (8 bits)" in found[0][1]


def test_a_group_input_without_a_width_warns_only_below_zero(tmp_path: Path) -> None:
    _, diags = _load("  if gin[2] == 100000 { stop }\n  if gin[2] > -3 { stop }", tmp_path)
    assert [(c, line) for c, _, line, _ in diags] == [("W152", 9)], diags


def test_a_fraction_compared_with_a_group_input_is_an_error(tmp_path: Path) -> None:
    _, diags = _load("  if gin[1] == 2.5 { stop }", tmp_path)
    assert [(c, line, col) for c, _, line, col in diags] == [("E168", 8, 16)], diags


@pytest.mark.parametrize("stmt", ["set gin[1] = 3", "pulse gin[1] for 0.1s"])
def test_a_group_input_is_never_written(tmp_path: Path, stmt: str) -> None:
    _, diags = _load(f"  {stmt}", tmp_path)
    assert [(c, line, col) for c, _, line, col in diags] == [("E167", 8, len(stmt.split("gin")[0]) + 3)], diags
    assert "a group input is read" in diags[0][1]


@pytest.mark.parametrize(
    ("line", "message"),
    [('io gin[3] = "x" bits 0', "1..32 bits (got 0)"), ('io gin[3] = "x" bits 33', "1..32 bits (got 33)"),
     ('io in[3] = "x" bits 8', "gin[n] only (got it on in[...])")],
)
def test_a_width_must_be_1_to_32_on_a_group_input(tmp_path: Path, line: str, message: str) -> None:
    cell = CELL.replace('  io in[1] = "ready"\n', f'  io in[1] = "ready"\n  {line}\n')
    _, diags = _load("  stop", tmp_path, cell)
    assert [(c, ln) for c, _, ln, _ in diags] == [("E166", 6)], diags
    assert message in diags[0][1]
