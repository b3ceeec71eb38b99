"""Each vendor writes a group input `gin[n]` its own way or refuses it (E430).

Witnesses: RAPID's GInput(signal) (RAPID Instructions, Functions and Data types, "GInput") and
KRL's SIGNAL name read as an INT (KSS 8.x "SIGNAL") evaluated by vendor_expr_witness.py, a small
evaluator written from each vendor's operator priorities, not by the backends' code, with the
group bound to every value 0..8 against Python's evaluation of the same IR; Fanuc's `IF GI[n]...
,JMP LBL` line is run by hand here (FANUC B-83284EN: the jump is taken when the comparison holds).
"""

from __future__ import annotations

import re

import pytest
from backend_fixtures import BRAND_ROBOT, FRONT_UP_NOFLIP, Q, hand_plan, span_at
from vendor_expr_witness import KRL_PRIORITY, RAPID_PRIORITY, evaluate

from rmot.backends import BACKENDS
from rmot.lang import ir, ir_tree

INT = ir.ValueType.INT
PGNO = ir.GroupInput(port=1, signal="pgno", bits=8)
# gin[1] >= 2 and (gin[1] < 5 or in[1] == on), and gin[1] != 3
COND = ir.Logic("and", (
    ir.Compare(ir.CompareOp.GE, PGNO, ir.Const(2, INT)),
    ir.Logic("or", (ir.Compare(ir.CompareOp.LT, PGNO, ir.Const(5, INT)), ir.InputCondition(port=1, value=True))),
    ir.Compare(ir.CompareOp.NE, PGNO, ir.Const(3, INT)),
))


def _python(pgno: int, di1: bool) -> bool:
    return pgno >= 2 and (pgno < 5 or di1) and pgno != 3


def _emit(vendor: str, cond: ir.Condition = COND):  # type: ignore[no-untyped-def]
    body = (ir.If(uid=1, condition=cond, then=(ir.WaitTime(uid=2, duration=1.0),), span=span_at(3)),)
    records = {n.uid: (Q, FRONT_UP_NOFLIP) for n in ir_tree.walk(body) if isinstance(n, ir.Move)}
    return BACKENDS[vendor]().emit(hand_plan(body, records, robot=BRAND_ROBOT[vendor]))


def _if_text(vendor: str, pattern: str) -> str:
    result = _emit(vendor)
    assert not [d for d in result.diagnostics if d.is_error], result.diagnostics
    text = "\n".join(result.files.values())
    found = re.search(pattern, text)
    assert found is not None, text
    return found.group(1)


@pytest.mark.parametrize(
    ("vendor", "pattern", "priority", "group", "digital"),
    [("rapid", r"IF (.*) THEN", RAPID_PRIORITY, "GInput ( pgno )", "DInput ( di1 ) = 1"),
     ("krl", r"IF (.*) THEN", KRL_PRIORITY, "pgno", "$IN[1] == TRUE")],
)
def test_the_group_reads_as_the_ir_means(vendor: str, pattern: str, priority: dict[str, int], group: str,
                                         digital: str) -> None:
    text = _if_text(vendor, pattern)
    group_tokens, digital_tokens = group.split(), digital.split()
    for pgno in range(9):
        for di1 in (False, True):
            def leaf(tokens: list[str], i: int, pgno: int = pgno, di1: bool = di1) -> tuple[object, int]:
                if tokens[i:i + len(digital_tokens)] == digital_tokens:
                    return di1, len(digital_tokens)
                if tokens[i:i + len(group_tokens)] == group_tokens:
                    return float(pgno), len(group_tokens)
                raise AssertionError(f"unexpected {tokens[i:]} in {text}")
            assert evaluate(text, priority, leaf) == _python(pgno, di1), (text, pgno, di1)


def test_fanuc_compares_gi_with_the_signal_comment() -> None:
    """`IF GI[1:pgno]<>3,JMP LBL[k]` jumps past the `then` arm when the test fails: for each
    value, the arm runs exactly when the IR's comparison holds."""
    cond = ir.Compare(ir.CompareOp.EQ, PGNO, ir.Const(3, INT))
    result = _emit("fanuc", cond)
    text = "\n".join(result.files.values())
    m = re.search(r"IF GI\[1:pgno\](<>|=|<|>|<=|>=)(\d+),JMP LBL", text)
    assert m is not None, text
    tp = {"<>": lambda a, b: a != b, "=": lambda a, b: a == b, "<": lambda a, b: a < b,
          ">": lambda a, b: a > b, "<=": lambda a, b: a <= b, ">=": lambda a, b: a >= b}[m.group(1)]
    for pgno in range(9):
        jumps_past = tp(pgno, int(m.group(2)))
        assert (not jumps_past) == (pgno == 3)


@pytest.mark.parametrize("vendor", ["urscript", "val3"])
def test_vendors_without_a_group_input_refuse_it(vendor: str) -> None:
    result = _emit(vendor)
    errors = [d for d in result.diagnostics if d.is_error]
    assert [d.code.id for d in errors][:1] == ["E430"] and "gin[1]" in errors[0].message
    assert errors[0].span.start.line == 3


def test_krl_refuses_an_unnamed_group() -> None:
    """KRL reads a group by a SIGNAL name only the cell's io line gives."""
    cond = ir.Compare(ir.CompareOp.EQ, ir.GroupInput(port=2), ir.Const(3, INT))
    errors = [d for d in _emit("krl", cond).diagnostics if d.is_error]
    assert [d.code.id for d in errors] == ["E430"] and "must be named by the cell" in errors[0].message


def test_rapid_names_an_unnamed_group_gi_n() -> None:
    cond = ir.Compare(ir.CompareOp.EQ, ir.GroupInput(port=2), ir.Const(3, INT))
    text = "\n".join(_emit("rapid", cond).files.values())
    assert "IF GInput(gi2) = 3 THEN" in text


@pytest.mark.parametrize(("bits", "refused"), [(23, False), (24, True), (None, False)])
def test_rapid_refuses_a_group_wider_than_ginput_reads(bits: int | None, refused: bool) -> None:
    """GInput reads up to 23 bits into a num (RAPID Instructions, Functions and Data types,
    "GInput"; GInputDnum beyond, which rmot does not write)."""
    cond = ir.Compare(ir.CompareOp.EQ, ir.GroupInput(port=1, signal="pgno", bits=bits), ir.Const(3, INT))
    errors = [d for d in _emit("rapid", cond).diagnostics if d.is_error]
    assert bool(errors) is refused and all(d.code.id == "E430" and "23 bits" in d.message for d in errors)
