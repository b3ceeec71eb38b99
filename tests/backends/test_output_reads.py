"""Each vendor writes the read of its own digital output `out[n]` in IF/WHILE/WAIT, and the
written condition means what the IR means for every state of the outputs and the input.

Witnesses, none of them the backends' code:
- RAPID and KRL: vendor_expr_witness.evaluate, written from each vendor's operator priorities,
  with DOutput(sig) read as 0/1 (RAPID Instructions, Functions and Data types, "DOutput") and
  $OUT[n] as a BOOL (KSS 8.x, "System variables");
- URScript: Python's own `ast` walked by the URScript import tests' evaluator (URScript's
  not/and/or and comparisons read as Python's: URScript Programming Language manual,
  "Operators"), with get_standard_digital_out(n) bound to the output's state;
- Fanuc TP and INFORM: the `IF DO[n]=ON/OFF,JMP LBL[k]` / `JUMP *L IF OT#(n)=ON/OFF` line read
  here by hand: the jump skips the `then` arm exactly when the IR's condition is false.
"""

from __future__ import annotations

import ast
import itertools
import re

import pytest
from backend_fixtures import BRAND_ROBOT, FRONT_UP_NOFLIP, Q, hand_plan, span_at
from test_import_urscript_runtime import _eval as python_meaning
from vendor_expr_witness import KRL_PRIORITY, RAPID_PRIORITY, evaluate

from rmot.backends import BACKENDS
from rmot.lang import ir, ir_tree

OUT2, OUT3 = ir.OutputRead(port=2, signal="do_two"), ir.OutputRead(port=3)
IN1 = ir.InputCondition(port=1, value=True)
# (not out[2] and in[1]) or out[3]
COND = ir.Logic("or", (ir.Logic("and", (ir.Not(OUT2), IN1)), OUT3))


def _python(out2: bool, out3: bool, in1: bool) -> bool:
    return (not out2 and in1) or out3


STATES = list(itertools.product((False, True), repeat=3))


def _emit(vendor: str, cond: ir.Condition = COND):  # type: ignore[no-untyped-def]
    body = (ir.If(uid=1, condition=cond, then=(ir.WaitTime(uid=2, duration=1.0),), span=span_at(3)),)
    records = {n.uid: (Q, FRONT_UP_NOFLIP) for n in ir_tree.walk(body) if isinstance(n, ir.Move)}
    return BACKENDS[vendor]().emit(hand_plan(body, records, robot=BRAND_ROBOT[vendor]))


def _text(vendor: str, cond: ir.Condition = COND) -> str:
    result = _emit(vendor, cond)
    assert not [d for d in result.diagnostics if d.is_error], result.diagnostics
    return "\n".join(result.files.values())


def _condition(vendor: str, pattern: str) -> str:
    found = re.search(pattern, _text(vendor))
    assert found is not None, _text(vendor)
    return found.group(1)


@pytest.mark.parametrize(
    ("vendor", "priority", "reads"),
    [("rapid", RAPID_PRIORITY, {"DOutput ( do_two )": "out2", "DOutput ( do3 )": "out3", "DInput ( di1 )": "in1"}),
     ("krl", KRL_PRIORITY, {"OUT 2": "out2", "OUT 3": "out3", "$IN[1]": "in1"})],
)
def test_rapid_and_krl_read_the_output_as_the_ir_means(vendor: str, priority: dict[str, int],
                                                       reads: dict[str, str]) -> None:
    text = _condition(vendor, r"IF (.*) THEN")
    numeric = vendor == "rapid"  # DOutput and DInput return 0/1 (a num), KRL's reads a BOOL
    for out2, out3, in1 in STATES:
        state = {"out2": out2, "out3": out3, "in1": in1}

        def leaf(tokens: list[str], i: int, state: dict[str, bool] = state) -> tuple[object, int]:
            for written, name in reads.items():
                words = written.split()
                if tokens[i:i + len(words)] == words:
                    return (float(state[name]) if numeric else state[name]), len(words)
            raise AssertionError(f"unexpected {tokens[i:]} in {text}")

        assert evaluate(text, priority, leaf) == _python(out2, out3, in1), (text, state)


def test_urscript_reads_get_standard_digital_out() -> None:
    text = _condition("urscript", r"\n\s*if (.*):")
    assert "get_standard_digital_out(2)" in text and "get_standard_digital_out(3)" in text
    for out2, out3, in1 in STATES:
        reads = {"get_standard_digital_out(2)": out2, "get_standard_digital_out(3)": out3,
                 "get_standard_digital_in(1)": in1}
        assert python_meaning(ast.parse(text, mode="eval"), dict(reads)) == _python(out2, out3, in1), (text, reads)


@pytest.mark.parametrize(
    ("vendor", "pattern", "on"),
    [("fanuc", r"IF DO\[3\]=(ON|OFF),JMP LBL\[\d+\]", "ON"),
     ("inform", r"JUMP \*L\d+ IF OT#\(3\)=(ON|OFF)", "ON")],
)
@pytest.mark.parametrize("negated", [False, True])
def test_fanuc_and_inform_skip_the_arm_when_the_output_test_fails(vendor: str, pattern: str, on: str,
                                                                  negated: bool) -> None:
    """`if out[3]` / `if not out[3]`: the jump past the `then` arm is taken in exactly the
    output states where the IR's condition is false."""
    cond: ir.Condition = ir.Not(OUT3) if negated else OUT3
    m = re.search(pattern, _text(vendor, cond))
    assert m is not None, _text(vendor, cond)
    for out3 in (False, True):
        jumps_past = (m.group(1) == on) == out3
        holds = (not out3) if negated else out3
        assert jumps_past == (not holds), (m.group(0), out3)


def test_val3_reads_the_output_dio() -> None:
    """VAL3 reads an output's dio like an input's (`dOut[n] == true`), the dio it sets."""
    text = _text("val3", OUT3)
    assert re.search(r"\n\s*if dOut\[3\] == true\n", text), text


def test_a_port_the_vendor_has_no_output_for_is_refused() -> None:
    """URScript has digital outputs 0..7 standard and 0..7 configurable (8..15 here): a larger
    port is refused with a located error, never written as another signal."""
    result = _emit("urscript", ir.OutputRead(port=99))
    errors = [d for d in result.diagnostics if d.is_error]
    assert errors and errors[0].span is not None and errors[0].span.start.line == 3, result.diagnostics
