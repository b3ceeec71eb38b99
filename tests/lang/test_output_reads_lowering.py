"""`out[n]` read in conditions and expressions: a bool, the state the controller holds for its
own digital output. `out[n] == on` is the read itself, `== off` / `!= on` / `not` its negation;
the cell's signal name rides along; `aout[n]` stays unreadable (E161, located)."""

from __future__ import annotations

from pathlib import Path

import pytest

from rmot.compiler.frontend import load_text
from rmot.lang import ir

CELL = """cell c {
  robot r1 = abb_irb1600 at pose(z=400mm)
  io out[1] = "clamp"
  io in[1] = "ready"
}
"""
CLAMP = ir.OutputRead(1, "clamp")
BOOL = ir.ValueType.BOOL


def _load(body: str, tmp_path: Path) -> tuple[ir.Program | None, list[tuple[str, str, int, int]]]:
    result = load_text(f"{CELL}program p on r1 {{\n{body}\n}}\n", str(tmp_path / "p.rmot"))
    diags = [(d.code.id, d.message, d.span.start.line, d.span.start.col) for d in result.diagnostics if d.span]
    return result.program, diags


@pytest.mark.parametrize(
    ("condition", "expected"),
    [("out[1]", CLAMP), ("out[1] == on", CLAMP), ("out[1] != off", CLAMP),
     ("out[1] == off", ir.Not(CLAMP)), ("out[1] != on", ir.Not(CLAMP)), ("not out[1]", ir.Not(CLAMP)),
     ("out[4] == on", ir.OutputRead(4, None)),
     ("out[1] and in[1]", ir.Logic("and", (CLAMP, ir.InputCondition(port=1, value=True, signal="ready"))))],
)
def test_an_output_read_lowers_to_its_state(condition: str, expected: ir.Condition, tmp_path: Path) -> None:
    prog, diags = _load(f"  if {condition} {{ wait 1 s }} else {{ wait 2 s }}", tmp_path)
    assert prog is not None and diags == [], diags
    branch = prog.tasks[0].body[0]
    assert isinstance(branch, ir.If) and branch.condition == expected
    assert branch.then and branch.otherwise  # both arms kept: the output's state is not known


def test_while_wait_and_var_read_an_output(tmp_path: Path) -> None:
    body = ("  var b = out[1]\n  while out[1] == off { wait 0.1 s }\n"
            "  wait until out[1] == on timeout 2 s else { set out[2] = on }")
    prog, diags = _load(body, tmp_path)
    assert prog is not None and diags == [], diags
    decl, loop, wait = prog.tasks[0].body[:3]
    assert isinstance(decl, ir.VarDecl) and decl.init == CLAMP and decl.type is BOOL
    assert isinstance(loop, ir.While) and loop.condition == ir.Not(CLAMP)
    assert isinstance(wait, ir.WaitCondition) and wait.condition == CLAMP and wait.timeout == 2.0


def test_an_output_read_is_a_bool_not_a_number(tmp_path: Path) -> None:
    _, diags = _load("  var n: int = 0\n  if out[1] > n { stop }", tmp_path)
    assert [c for c, *_ in diags] == ["E151"], diags


def test_an_analog_output_is_not_read(tmp_path: Path) -> None:
    _, diags = _load("  if aout[2] > 1 { stop }", tmp_path)
    assert diags and diags[0][0] == "E161" and "aout" in diags[0][1], diags
    assert diags[0][2:] == (7, 6)  # line 7 of the text (the cell's 5 lines, the program line), at aout
