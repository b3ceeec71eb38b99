"""RAPID, KRL and URScript write the runtime-logic instructions: expressions with
each vendor's operators and priorities, analog inputs in each vendor's unit and range (E420),
waits on a condition, stop inside a routine (KRL W421), repeat loops."""

from __future__ import annotations

import pytest
from backend_fixtures import (
    BRAND_ROBOT,
    FRONT_UP_NOFLIP,
    Q,
    DOWN,
    L,
    cart,
    hand_plan,
    move,
    span_at,
)

from rmot.backends import BACKENDS
from rmot.lang import ir, ir_tree

INT, NUM, BOOL = ir.ValueType.INT, ir.ValueType.NUM, ir.ValueType.BOOL
COUNT = ir.VarRef("count", INT)


def emit(vendor: str, body: tuple[ir.Instr, ...]):  # type: ignore[no-untyped-def]
    records = {n.uid: (Q, FRONT_UP_NOFLIP) for n in ir_tree.walk(body) if isinstance(n, ir.Move)}
    return BACKENDS[vendor]().emit(hand_plan(body, records, robot=BRAND_ROBOT[vendor]))


def text(result) -> str:  # type: ignore[no-untyped-def]
    return "\n".join(result.files.values())


def codes(result) -> list[str]:  # type: ignore[no-untyped-def]
    return [d.code.id for d in result.diagnostics]


DECL = ir.VarDecl(uid=1, name="count", type=INT, init=ir.Const(0, INT), span=span_at(2))
HALF = ir.Assign(
    uid=2, name="level", value=ir.Arith("/", COUNT, ir.Const(2, INT), NUM), span=span_at(3)
)
LEVEL = ir.VarDecl(uid=3, name="level", type=NUM, init=ir.Const(0.5, NUM), span=span_at(4))
COND = ir.Logic(
    "and",
    (
        ir.InputCondition(port=1, value=True),
        ir.Not(ir.Compare(ir.CompareOp.GT, ir.AnalogInput(port=1), ir.Const(4.5, NUM))),
    ),
)


@pytest.mark.parametrize(
    ("vendor", "want"),
    [
        (
            "rapid",
            [
                "count := 0;",
                "level := count / 2;",
                "IF DInput(di1) = 1 AND (NOT (AInput(ai1) > 4.5)) THEN",
                "WaitUntil count >= 3;",
            ],
        ),
        (
            "krl",
            [
                "count=0",
                "level=(count*1.0)/2",
                "IF ($IN[1]==TRUE) AND (NOT ($ANIN[1]*10 > 4.5)) THEN",
                "WAIT FOR count >= 3",
            ],
        ),
        (
            "urscript",
            [
                "count = 0",
                "level = (count * 1.0) / 2",
                "if (get_standard_digital_in(1) == True) and "
                "(not (get_standard_analog_in(1) > 4.5)):",
                "while not (count >= 3):",
            ],
        ),
    ],
)
def test_expressions_in_each_vendors_syntax(vendor: str, want: list[str]) -> None:
    """Integer division is a real division everywhere (KRL and URScript divide INTs as
    integers, so the left operand is made real); KRL compares with the lowest priority, so its
    comparisons are parenthesised; the analog input reads volts (KRL $ANIN is +-1.0 for
    +-10 V)."""
    body = (
        DECL,
        LEVEL,
        HALF,
        ir.If(uid=5, condition=COND, then=(ir.WaitTime(uid=6, duration=1.0),), span=span_at(5)),
        ir.WaitCondition(
            uid=7, condition=ir.Compare(ir.CompareOp.GE, COUNT, ir.Const(3, INT)), span=span_at(6)
        ),
    )
    result = emit(vendor, body)
    assert not result.has_errors, [d.message for d in result.diagnostics]
    lines = [ln.strip() for ln in text(result).splitlines()]
    for line in want:
        assert line in lines, (line, lines)


@pytest.mark.parametrize(
    ("vendor", "port", "bad"),
    [("krl", 33, True), ("krl", 32, False), ("urscript", 2, True), ("urscript", 1, False)],
)
def test_analog_input_port_range(vendor: str, port: int, bad: bool) -> None:
    """E420 outside KRL's $ANIN[1..32] and URScript's standard analog inputs 0..1."""
    cond = ir.Compare(ir.CompareOp.GT, ir.AnalogInput(port=port), ir.Const(1.0, NUM))
    result = emit(
        vendor,
        (ir.If(uid=1, condition=cond, then=(ir.WaitTime(uid=2, duration=1.0),), span=span_at(3)),),
    )
    assert ("E420" in codes(result)) is bad


def test_krl_stop_inside_a_routine_returns_through_a_flag() -> None:
    """KRL cannot end the program from a routine: RMOT_STOP and RETURN there, and the call
    returns in turn (W421); in the main program RETURN ends it."""
    call = ir.ProcCall(
        uid=1,
        proc="check",
        args=(),
        span=span_at(3),
        body=(
            ir.If(
                uid=2,
                condition=ir.InputCondition(port=1, value=False),
                span=span_at(4),
                then=(ir.Stop(uid=3, span=span_at(5)),),
            ),
        ),
    )
    result = emit("krl", (call, ir.Stop(uid=4, span=span_at(6))))
    src = next(t for n, t in result.files.items() if n.endswith(".src"))
    dat = next(t for n, t in result.files.items() if n.endswith(".dat"))
    assert "W421" in codes(result)
    assert "DECL BOOL RMOT_STOP=FALSE" in dat
    lines = [ln.strip() for ln in src.splitlines()]
    k = lines.index("check()")
    assert lines[k + 1 : k + 4] == ["IF RMOT_STOP THEN", "RETURN ; stop: ends the program", "ENDIF"]
    assert "RMOT_STOP=TRUE" in lines and lines.count("RETURN ; stop: ends the program") == 2


@pytest.mark.parametrize(
    ("vendor", "word"),
    [("rapid", "EXIT;"), ("krl", "RETURN ; stop: ends the program"), ("urscript", "halt")],
)
def test_stop_ends_the_program(vendor: str, word: str) -> None:
    result = emit(vendor, (ir.Stop(uid=1, span=span_at(3)),))
    assert word in [ln.strip() for ln in text(result).splitlines()]


@pytest.mark.parametrize(
    ("vendor", "head"),
    [
        ("rapid", "FOR rmot_rep1 FROM 0 TO 2 DO"),
        ("krl", "FOR rmot_rep1=0 TO 2"),
        ("urscript", "while rmot_rep1 <= 2:"),
    ],
)
def test_repeat_loop_has_its_own_counter(vendor: str, head: str) -> None:
    """`repeat 3` (no loop variable): a counter of its own, the same body three times."""
    its = tuple(
        ir.LoopIteration(value=k, body=(move(10 + k, L, cart(DOWN, name="p1")),)) for k in range(3)
    )
    result = emit(
        vendor, (ir.Loop(uid=1, var=None, first=0, last=3, iterations=its, span=span_at(3)),)
    )
    assert not result.has_errors and "W420" not in codes(result)
    assert head in [ln.strip() for ln in text(result).splitlines()]


@pytest.mark.parametrize("vendor", ["rapid", "krl", "urscript"])
def test_timeout_branch(vendor: str) -> None:
    """`wait until in[1] == on timeout 2 s else { set out[2] = on }`: the branch runs when the
    time runs out (no stop of the program)."""
    wait = ir.WaitInput(
        uid=1,
        condition=ir.InputCondition(port=1, value=True),
        timeout=2.0,
        span=span_at(3),
        on_timeout=(ir.SetDigital(uid=2, port=2, value=True, span=span_at(4)),),
    )
    out = text(emit(vendor, (wait,)))
    want = {
        "rapid": [
            "WaitDI di1, 1\\MaxTime:=2.000\\TimeFlag:=rmot_timeout;",
            "IF rmot_timeout THEN",
            "SetDO do2, 1;",
        ],
        "krl": [
            "WAIT FOR ($IN[1]==TRUE) OR ($TIMER[16]>=2000)",
            "IF NOT ($IN[1]==TRUE) THEN",
            "$OUT[2]=TRUE",
        ],
        "urscript": [
            "if not (get_standard_digital_in(1) == True):",
            "set_standard_digital_out(2, True)",
        ],
    }
    lines = [ln.strip() for ln in out.splitlines()]
    for line in want[vendor]:
        assert line in lines, (line, lines)
    assert "halt" not in lines and "HALT ; timeout" not in lines
