"""KUKA KRL backend: instruction table, .src/.dat layout, splitting, determinism, refusals."""

from __future__ import annotations


import pytest
from backend_fixtures import (
    DOWN, GRIPPER, TABLE, C, J, L, Row, cart, deg, emit_row, hand_plan, move, routine_lines, sample_program,
    span_at,
)

from rmot.backends import codes
from rmot.backends.krl import KrlBackend
from rmot.lang import ir

NULL = ("$TOOL=$NULLFRAME", "$BASE=$NULLFRAME")
E = ",E1 0.0,E2 0.0,E3 0.0,E4 0.0,E5 0.0,E6 0.0"


ROWS = [
    Row("ptp_axis", move(1, J, ir.JointTarget(tuple(deg(0, -90, 90, 0, 45, 0)), "home"), joint=0.5),
        NULL + ("RMOT_PTP(50.000,100.000)", "PTP home"),
        (f"DECL E6AXIS home={{A1 0.0000,A2 -90.0000,A3 90.0000,A4 0.0000,A5 45.0000,A6 0.0000{E}}}",)),
    Row("ptp_pos_status_turn", move(1, J, cart(DOWN, name="p1")),
        NULL + ("RMOT_PTP(100.000,100.000)", "PTP p1"),
        (f"DECL E6POS p1={{X 400.000,Y -100.000,Z 300.000,A 0.0000,B 0.0000,C 180.0000,S 2,T 24{E}}}",)),
    Row("lin_cdis", move(1, L, cart(DOWN, name="p1"), speed=0.25, zone=0.005),
        NULL + ("$APO.CDIS=5.000", "$VEL.CP=0.2500", "$ACC.CP=2.0000", "LIN p1 C_DIS")),
    Row("lin_tool_base", move(1, L, cart(DOWN, TABLE, "p1"), tool=GRIPPER, frame=TABLE, speed=0.1),
        ("$TOOL=gripper", "$LOAD=gripper_load", "$BASE=table_top", "$VEL.CP=0.1000", "$ACC.CP=2.0000", "LIN p1"),
        ("DECL FRAME gripper={X 0.000,Y 0.000,Z 150.000,A 0.0000,B 0.0000,C 0.0000}",
         "DECL FRAME table_top={X 500.000,Y 0.000,Z 15.000,A 0.0000,B 0.0000,C 0.0000}",
         "DECL LOAD gripper_load={M 1.200,CM {X 0.000,Y 0.000,Z 75.000,A 0.0,B 0.0,C 0.0},J {X 0.0,Y 0.0,Z 0.0}}")),
    Row("circ", move(1, C, cart(DOWN, name="p1"), via=cart(DOWN, name="mid")),
        NULL + ("$VEL.CP=0.2500", "$ACC.CP=2.0000", "CIRC mid,p1")),
    Row("lin_time_warns", move(1, L, cart(DOWN, name="p1"), duration=2.0),
        NULL + ("$VEL.CP=0.2500", "$ACC.CP=2.0000", "LIN p1"), codes=("W409",)),
    Row("out", ir.SetDigital(uid=1, port=1, value=True, signal="gripper_close"), ("$OUT[1]=TRUE ; gripper_close",)),
    Row("anout", ir.SetAnalog(uid=1, port=2, value=4.5), ("$ANOUT[2]=0.4500",)),
    Row("pulse", ir.Pulse(uid=1, port=3, duration=0.2), ("PULSE($OUT[3],TRUE,0.200)",)),
    Row("wait_sec", ir.WaitTime(uid=1, duration=0.3), ("WAIT SEC 0.300",)),
    Row("wait_for", ir.WaitInput(uid=1, condition=ir.InputCondition(port=2, value=False)), ("WAIT FOR $IN[2]==FALSE",)),
    Row("wait_for_timeout", ir.WaitInput(uid=1, condition=ir.InputCondition(port=2, value=True), timeout=5.0),
        ("$TIMER_STOP[16]=TRUE", "$TIMER[16]=0", "$TIMER_STOP[16]=FALSE",
         "WAIT FOR ($IN[2]==TRUE) OR ($TIMER[16]>=5000)", "$TIMER_STOP[16]=TRUE",
         "IF NOT ($IN[2]==TRUE) THEN", "HALT ; timeout", "ENDIF"), codes=("W405",)),
    Row("if_else", ir.If(uid=1, condition=ir.InputCondition(port=2, value=True),
                         then=(ir.WaitTime(uid=2, duration=1.0),), otherwise=(ir.SetDigital(uid=3, port=1, value=False),)),
        ("IF $IN[2]==TRUE THEN", "WAIT SEC 1.000", "ELSE", "$OUT[1]=FALSE", "ENDIF")),
    Row("native", ir.Native(uid=1, vendor="krl", text="HALT\nWAIT SEC 1"), ("HALT", "WAIT SEC 1")),
    Row("native_other", ir.Native(uid=1, vendor="rapid", text="Stop;"), (), codes=("W407",)),
    Row("proc_call", ir.ProcCall(uid=1, proc="pick", args=(), body=(ir.WaitTime(uid=2, duration=0.5),)), ("pick()",)),
    Row("sync_single_task_noop", ir.Sync(uid=1, name="meet"), ()),  # two tasks: test_handshake.py
]


@pytest.mark.parametrize("row", ROWS, ids=lambda r: r.name)
def test_instruction_table(row: Row) -> None:
    """Each IR instruction prints as the KRL lines of the table, with its data in the .dat."""
    result = emit_row(KrlBackend, row)
    files = result.files
    assert tuple(routine_lines(files["demo.src"], "DEF demo( )", "END")) == row.lines
    dat = [ln.strip() for ln in files["demo.dat"].splitlines()]
    for decl in row.decls:
        assert decl in dat
    assert tuple(d.code.id for d in result.diagnostics) == row.codes


class TestModule:
    def test_src_and_dat_pair(self) -> None:
        """One task gives NAME.src (DEF NAME) and NAME.dat (DEFDAT NAME), ending in END/ENDDAT."""
        files = KrlBackend().emit(sample_program()).files
        assert list(files) == ["demo.src", "demo.dat"]
        assert files["demo.src"].splitlines()[1] == "DEF demo( )"
        assert files["demo.dat"].splitlines()[1] == "DEFDAT demo"
        assert files["demo.dat"].rstrip().endswith("ENDDAT")

    def test_deterministic(self) -> None:
        """Two runs give byte-identical files."""
        assert KrlBackend().emit(sample_program()).files == KrlBackend().emit(sample_program()).files

    def test_proc_is_local_def(self) -> None:
        """A proc call becomes `pick()` and a local DEF with the body."""
        src = KrlBackend().emit(sample_program()).files["demo.src"]
        assert routine_lines(src, "DEF pick( )", "END")[0] == "WAIT SEC 0.300"

    def test_ptp_helper_defined_once_when_used(self) -> None:
        """RMOT_PTP is defined exactly once in a module with PTP moves."""
        src = KrlBackend().emit(sample_program()).files["demo.src"]
        assert src.count("DEF RMOT_PTP(") == 1


class TestSplit:
    def test_long_program_split_into_modules(self) -> None:
        """Past MAX_INSTRUCTIONS the body is split into part modules called in order, with W406."""

        class Small(KrlBackend):
            MAX_INSTRUCTIONS = 2

        body = tuple(ir.WaitTime(uid=i, duration=0.1 * i, span=span_at(i)) for i in range(1, 6))
        result = Small().emit(hand_plan(body, {}, robot="kuka_kr6_r900"))
        assert list(result.files) == ["demo.src", "demo.dat", "demo_part1.src", "demo_part1.dat",
                                      "demo_part2.src", "demo_part2.dat", "demo_part3.src", "demo_part3.dat"]
        assert routine_lines(result.files["demo.src"], "DEF demo( )", "END") == [
            "demo_part1()", "demo_part2()", "demo_part3()"]
        assert routine_lines(result.files["demo_part3.src"], "DEF demo_part3( )", "END") == ["WAIT SEC 0.500"]
        assert [d.code for d in result.diagnostics] == [codes.PROGRAM_SPLIT]


class TestRefusals:
    def test_missing_record(self) -> None:
        """A move without planned joints is an error at its span."""
        result = KrlBackend().emit(hand_plan((move(1, L, cart(DOWN)),), {}, robot="kuka_kr6_r900"))
        assert [(d.code, d.span) for d in result.diagnostics] == [(codes.MISSING_RECORD, span_at(11))]

    def test_analog_out_of_range(self) -> None:
        """$ANOUT covers -10..10 V; beyond is an error."""
        result = KrlBackend().emit(hand_plan((ir.SetAnalog(uid=1, port=1, value=12.0),), {}, robot="kuka_kr6_r900"))
        assert [d.code for d in result.diagnostics] == [codes.BAD_PORT]
