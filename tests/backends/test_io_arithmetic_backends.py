"""I/O reads inside arithmetic, as each vendor writes them: the written condition has the IR's
value for a grid of analog volts and group values, or the vendor refuses it with a located E430.

Witnesses, none of them the backends' code: vendor_expr_witness.evaluate (each vendor's operator
priorities) for RAPID (`AInput(sig)` the signal's logical value in volts, `GInput(sig)` the
group's number: RAPID Instructions, Functions and Data types) and KRL (`$ANIN[n]` is ±1.0 for
±10 V: KSS 8.x System Variables; a SIGNAL group read by its name); the values the IR means are
computed here with Python's arithmetic from the rmot text's own numbers.
"""

from __future__ import annotations

import itertools
import re
from pathlib import Path

import pytest
from test_output_reads import _emit, _text
from vendor_expr_witness import KRL_PRIORITY, RAPID_PRIORITY, evaluate

from rmot.compiler.frontend import load_text
from rmot.lang import ir

CELL = """cell c {
  robot r1 = abb_irb1600 at pose(z=400mm)
  io gin[1] = "pgno" bits 4
  io ain[1] = "ai1"
}
"""
# `ain[1] * 2 > 3 or 4 == gin[1] + 1`: the analog input above 1.5 V, or the group at 3
SOURCE = "program p on r1 {\n  if ain[1] * 2 > 3 or 4 == gin[1] + 1 {\n    wait 1 s\n  }\n}\n"
GRID = list(itertools.product((-2.0, 0.0, 1.4, 1.5, 1.6, 9.5), range(6)))


def _condition(tmp_path: Path) -> ir.Condition:
    result = load_text(CELL + SOURCE, str(tmp_path / "p.rmot"))
    assert result.program is not None, result.diagnostics
    first = result.program.tasks[0].body[0]
    assert isinstance(first, ir.If)
    return first.condition


@pytest.mark.parametrize(
    ("vendor", "priority", "reads"),
    [("rapid", RAPID_PRIORITY, {"AInput ( ai1 )": lambda v, g: v, "GInput ( pgno )": lambda v, g: float(g)}),
     ("krl", KRL_PRIORITY, {"ANIN 1": lambda v, g: v / 10.0, "pgno": lambda v, g: float(g)})],
)
def test_arithmetic_on_reads_means_what_the_ir_means(vendor: str, priority: dict[str, int], reads: dict,  # type: ignore[type-arg]
                                                     tmp_path: Path) -> None:
    written = re.search(r"IF (.*) THEN", _text(vendor, _condition(tmp_path)))
    assert written is not None
    text = written.group(1)
    for volts, group in GRID:
        def leaf(tokens: list[str], i: int, volts: float = volts, group: int = group) -> tuple[object, int]:
            for form, value in reads.items():
                words = form.split()
                if tokens[i:i + len(words)] == words:
                    return value(volts, group), len(words)
            raise AssertionError(f"unexpected {tokens[i:]} in {text}")

        expected = volts * 2 > 3 or 4 == group + 1
        assert evaluate(text, priority, leaf) == expected, (text, volts, group)


@pytest.mark.parametrize("vendor", ["inform", "val3", "urscript"])
def test_a_vendor_that_cannot_compute_with_a_group_refuses_it_located(vendor: str, tmp_path: Path) -> None:
    errors = [d for d in _emit(vendor, _condition(tmp_path)).diagnostics if d.is_error]
    assert errors and {d.code.id for d in errors} <= {"E430"}, errors
    assert all(d.span is not None for d in errors)
