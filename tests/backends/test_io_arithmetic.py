"""Every vendor writes an I/O read inside arithmetic (`ain[1] * 2 > 3`, `gin[1] / 2 > 1`,
`4.5 < ain[1]`) so that it means what the rmot expression means for a grid of input values, or
refuses it with a located error.

Witnesses, none of them the backends' code:
- the rmot expression's meaning: Python's own `ast` walked by the URScript import tests'
  evaluator (rmot's `+ - * /`, comparisons, and/or read as Python's: REFERENCE §12; `/` is a
  real division in both);
- RAPID and KRL: vendor_expr_witness.evaluate, from each vendor's operator priorities; KRL with
  its INT / INT division that drops the fraction, and $ANIN[n] read as volts / 10 (-1..1 for
  -10..10 V: KSS 8.x System Variables, "$ANIN");
- URScript: the same Python evaluator on the written text (URScript's operators read as
  Python's: URScript Programming Language manual, "Operators"); VAL3 likewise (its `+ - * /`
  and comparisons: VAL3 Reference Manual s7, "Simple types");
- Fanuc TP: the register lines `R[k]=a op b` and the `IF R[k] op c,JMP LBL[n]` read here by
  hand (TP register arithmetic is real: B-83284EN §4.4 "Register instructions").
"""

from __future__ import annotations

import ast
import itertools
import re
from pathlib import Path

import pytest
from backend_fixtures import BRAND_ROBOT, FRONT_UP_NOFLIP, Q, hand_plan, span_at
from test_import_urscript_runtime import _eval as python_meaning
from vendor_expr_witness import KRL_PRIORITY, RAPID_PRIORITY, evaluate

from rmot.backends import BACKENDS
from rmot.compiler.frontend import load_text
from rmot.lang import ir, ir_tree

CELL = """cell c {
  robot r1 = abb_irb1600 at pose(z=400mm)
  io gin[1] = "pgno" bits 4
  io ain[1] = "ai1"
}
"""
VOLTS = (-7.25, -1.0, 0.26, 1.49, 1.51, 2.2, 4.6, 9.9)
GROUPS = (1, 2, 3, 4, 5, 9, 15)
ANALOG = ["ain[1] * 2 > 3", "4.5 < ain[1]", "2 / ain[1] + 0.5 > 1", "1 - ain[1] / 4 >= 0.5"]
GROUP = ["gin[1] + 1 == 4", "2 * gin[1] < 8", "gin[1] / 2 > 1", "7 / gin[1] >= 2", "10 - gin[1] * 3 < 0"]
MIXED = ["ain[1] - gin[1] * 0.5 > 1 and 1 < gin[1]", "ain[1] / gin[1] < 0.5 or gin[1] == 15"]


def _condition(text: str, tmp_path: Path) -> ir.Condition:
    result = load_text(f"{CELL}program p on r1 {{\n  if {text} {{ stop }}\n}}\n", str(tmp_path / "p.rmot"))
    assert result.program is not None, result.diagnostics
    branch = result.program.tasks[0].body[0]
    assert isinstance(branch, ir.If)
    return branch.condition


def _emit(vendor: str, cond: ir.Condition):  # type: ignore[no-untyped-def]
    body = (ir.If(uid=1, condition=cond, then=(ir.WaitTime(uid=2, duration=1.0),), span=span_at(3)),)
    records = {n.uid: (Q, FRONT_UP_NOFLIP) for n in ir_tree.walk(body) if isinstance(n, ir.Move)}
    return BACKENDS[vendor]().emit(hand_plan(body, records, robot=BRAND_ROBOT[vendor]))


def _text(vendor: str, cond: ir.Condition) -> str:
    result = _emit(vendor, cond)
    assert not [d for d in result.diagnostics if d.is_error], result.diagnostics
    return "\n".join(result.files.values())


def _rmot_meaning(text: str, volts: float, group: int) -> object:
    python = text.replace("ain[1]", "A").replace("gin[1]", "G")
    return python_meaning(ast.parse(python, mode="eval"), {"A": volts, "G": group})


def _grid(text: str) -> list[tuple[float, int]]:
    volts = VOLTS if "ain" in text else (0.0,)
    groups = GROUPS if "gin" in text else (0,)
    return list(itertools.product(volts, groups))


@pytest.mark.parametrize("text", ANALOG + GROUP + MIXED)
def test_rapid_writes_the_expression_as_rmot_means_it(text: str, tmp_path: Path) -> None:
    written = re.search(r"\n\s*IF (.*) THEN", _text("rapid", _condition(text, tmp_path)))
    assert written is not None
    for volts, group in _grid(text):
        # AInput returns the signal's value in the controller's unit, GInput the group's integer
        # (RAPID Instructions, Functions and Data types, "AInput", "GInput")
        reads = {("AInput", "(", "ai1", ")"): volts, ("GInput", "(", "pgno", ")"): float(group)}

        def leaf(tokens: list[str], i: int, reads: dict[tuple[str, ...], float] = reads) -> tuple[object, int]:
            for words, value in reads.items():
                if tuple(tokens[i:i + len(words)]) == words:
                    return value, len(words)
            raise AssertionError(f"unexpected {tokens[i:]} in {written.group(1)}")

        got = evaluate(written.group(1), RAPID_PRIORITY, leaf)
        assert got == _rmot_meaning(text, volts, group), (written.group(1), volts, group)


@pytest.mark.parametrize("text", ANALOG + GROUP + MIXED)
def test_krl_writes_the_expression_as_rmot_means_it(text: str, tmp_path: Path) -> None:
    written = re.search(r"\n\s*IF (.*) THEN", _text("krl", _condition(text, tmp_path)))
    assert written is not None
    for volts, group in _grid(text):

        def leaf(tokens: list[str], i: int, volts: float = volts, group: int = group) -> tuple[object, int]:
            if tokens[i] == "ANIN" and tokens[i + 1] == "1":  # `$ANIN[1]`: -1..1 for -10..10 V
                return volts / 10, 2
            if tokens[i].upper() == "PGNO":  # the SIGNAL's INT
                return group, 1
            raise AssertionError(f"unexpected {tokens[i:]} in {written.group(1)}")

        got = evaluate(written.group(1), KRL_PRIORITY, leaf, int_division=True)
        assert got == _rmot_meaning(text, volts, group), (written.group(1), volts, group)


@pytest.mark.parametrize("text", ANALOG)
def test_urscript_writes_the_expression_as_rmot_means_it(text: str, tmp_path: Path) -> None:
    written = re.search(r"\n\s*if (.*):", _text("urscript", _condition(text, tmp_path)))
    assert written is not None
    for volts, group in _grid(text):
        reads: dict[str, object] = {"get_standard_analog_in(1)": volts}
        got = python_meaning(ast.parse(written.group(1), mode="eval"), reads)
        assert got == _rmot_meaning(text, volts, group), (written.group(1), volts)


@pytest.mark.parametrize("text", ANALOG)
def test_val3_writes_the_expression_as_rmot_means_it(text: str, tmp_path: Path) -> None:
    """VAL3's `aioGet(aIn[n])` is the input's value (VAL3 Reference Manual, "aio"); its
    operators `+ - * /` and comparisons read as Python's (manual s7, "Simple types": num)."""
    written = re.search(r"\n\s*if (.*)\n", _text("val3", _condition(text, tmp_path)))
    assert written is not None
    python = written.group(1).replace("aioGet(aIn[1])", "A")
    for volts, group in _grid(text):
        got = python_meaning(ast.parse(python, mode="eval"), {"A": volts})
        assert got == _rmot_meaning(text, volts, group), (written.group(1), volts)


def _fanuc_runs_the_arm(program: str, group: int) -> bool:
    """Runs the register lines before the IF, then the IF: the arm runs when it does not jump."""
    registers: dict[str, float] = {}

    def value(text: str) -> float:
        text = re.sub(r"GI\[1(:[^\]]*)?\]", str(group), text)
        text = re.sub(r"R\[(\d+)(:[^\]]*)?\]", lambda m: repr(registers[m.group(1)]), text)
        return float(python_meaning(ast.parse(text, mode="eval"), {}))  # type: ignore[arg-type]

    for line in program.splitlines():
        assign = re.match(r"\s*\d+:\s*R\[(\d+)(?::[^\]]*)?\]=(.*) ;$", line)
        if assign:
            registers[assign.group(1)] = value(assign.group(2))
            continue
        test = re.match(r"\s*\d+:\s*IF (.*?)(<>|<=|>=|<|>|=)(.*),JMP LBL\[\d+\] ;$", line)
        if test:
            op = {"=": "==", "<>": "!="}.get(test.group(2), test.group(2))
            jumps = python_meaning(ast.parse(f"{value(test.group(1))} {op} {value(test.group(3))}", mode="eval"), {})
            return not jumps
    raise AssertionError(program)


@pytest.mark.parametrize("text", GROUP)
def test_fanuc_computes_group_arithmetic_in_registers(text: str, tmp_path: Path) -> None:
    program = _text("fanuc", _condition(text, tmp_path))
    assert "GI[1" in program, program
    for group in GROUPS:
        assert _fanuc_runs_the_arm(program, group) == _rmot_meaning(text, 0.0, group), (program, group)


@pytest.mark.parametrize(
    ("vendor", "text", "code"),
    [("urscript", "gin[1] + 1 == 4", "E430"), ("inform", "ain[1] * 2 > 3", "E430"),
     ("inform", "gin[1] + 1 == 4", "E430"), ("val3", "2 * gin[1] < 8", "E430"),
     ("fanuc", "ain[1] * 2 > 3", "E470")],
)
def test_a_vendor_that_cannot_write_the_read_refuses_at_the_statement(vendor: str, text: str, code: str,
                                                                     tmp_path: Path) -> None:
    result = _emit(vendor, _condition(text, tmp_path))
    errors = [(d.code.id, d.span.start.line) for d in result.diagnostics if d.is_error and d.span]
    assert errors and all(e == (code, 3) for e in errors), result.diagnostics
