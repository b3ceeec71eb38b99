"""ABB RAPID backend: instruction table, rapidchecker, determinism, diagnostics."""

from __future__ import annotations


import pytest
from backend_fixtures import (
    DOWN, FRONT_UP_NOFLIP, GRIPPER, TABLE, C, J, L, Q, Row, cart, deg, emit_row, hand_plan, move, routine_lines,
    sample_program, span_at,
)

from rmot.backends import codes
from rmot.backends.rapid import RapidBackend
from rmot.lang import ir



def check_file(text: str) -> list[object]:
    """rapidchecker's errors for a module (its pyparsing deprecation noise silenced)."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        from rapidchecker.cli import check_file as rapid_check

        return rapid_check(text)  # type: ignore[no-any-return]

EXT = "[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]"


ROWS = [
    Row("moveabsj", move(1, J, ir.JointTarget(tuple(deg(0, -30, 30, 0, 60, 0)), "home")),
        ("MoveAbsJ home\\NoEOffs, vmax, fine, tool0;",),
        (f"CONST jointtarget home:=[[0.000,-30.000,30.000,0.000,60.000,0.000],{EXT}];",)),
    Row("movej_pose_confdata", move(1, J, cart(DOWN, name="p1")),
        ("MoveJ p1, vmax, fine, tool0;",),
        (f"CONST robtarget p1:=[[400.000,-100.000,300.000],[0.000000,1.000000,0.000000,0.000000],[0,-2,2,0],{EXT}];",)),
    Row("movel_table_speed_zone", move(1, L, cart(DOWN, name="p1"), speed=0.1, zone=0.01),
        ("MoveL p1, v100, z10, tool0;",)),
    Row("movel_custom_speed_zone", move(1, L, cart(DOWN, name="p1"), speed=0.1234, zone=0.0075),
        ("MoveL p1, v123_4, z7_5, tool0;",),
        ("CONST speeddata v123_4:=[123.400,500,5000,1000];",
         "CONST zonedata z7_5:=[FALSE,7.500,11.250,11.250,1.125,11.250,1.125];")),
    Row("movel_time", move(1, L, cart(DOWN, name="p1"), speed=0.1, duration=2.5),
        ("MoveL p1, v100\\T:=2.500, fine, tool0;",)),
    Row("movel_tool_wobj", move(1, L, cart(DOWN, TABLE, "p1"), tool=GRIPPER, frame=TABLE, speed=0.5),
        ("MoveL p1, v500, fine, gripper\\WObj:=table_top;",),
        ("PERS tooldata gripper:=[TRUE,[[0.000,0.000,150.000],[1.000000,0.000000,0.000000,0.000000]],"
         "[1.200,[0.000,0.000,75.000],[1,0,0,0],0,0,0]];",
         'TASK PERS wobjdata table_top:=[FALSE,TRUE,"",[[500.000,0.000,15.000],'
         "[1.000000,0.000000,0.000000,0.000000]],[[0,0,0],[1,0,0,0]]];")),
    Row("movec", move(1, C, cart(DOWN, name="p1"), via=cart(DOWN, name="m")),
        ("MoveC m, p1, v250, fine, tool0;",)),
    Row("movej_slow_joint_share", move(1, J, cart(DOWN, name="p1"), joint=0.5),
        ("MoveJ p1, vmax\\T:=1.000, fine, tool0;",), codes=("W402",)),
    Row("set_do", ir.SetDigital(uid=1, port=1, value=True, signal="gripper_close"), ("SetDO gripper_close, 1;",)),
    Row("set_do_default_name", ir.SetDigital(uid=1, port=4, value=False), ("SetDO do4, 0;",)),
    Row("set_ao", ir.SetAnalog(uid=1, port=2, value=4.5), ("SetAO ao2, 4.500;",)),
    Row("pulse", ir.Pulse(uid=1, port=3, duration=0.2), ("PulseDO\\PLength:=0.200, do3;",)),
    Row("wait_time", ir.WaitTime(uid=1, duration=0.3), ("WaitTime 0.300;",)),
    Row("wait_di", ir.WaitInput(uid=1, condition=ir.InputCondition(port=2, value=False)), ("WaitDI di2, 0;",)),
    Row("wait_di_timeout", ir.WaitInput(uid=1, condition=ir.InputCondition(port=2, value=True, signal="part"),
                                        timeout=5.0), ("WaitDI part, 1\\MaxTime:=5.000;",)),
    Row("if_else", ir.If(uid=1, condition=ir.InputCondition(port=2, value=True),
                         then=(ir.WaitTime(uid=2, duration=1.0),), otherwise=(ir.SetDigital(uid=3, port=1, value=True),)),
        ("IF DInput(di2) = 1 THEN", "WaitTime 1.000;", "ELSE", "SetDO do1, 1;", "ENDIF")),
    Row("native", ir.Native(uid=1, vendor="rapid", text='TPWrite "hi";\nStop;'), ('TPWrite "hi";', "Stop;")),
    Row("native_other_vendor", ir.Native(uid=1, vendor="krl", text="HALT"), (), codes=("W407",)),
    Row("proc_call", ir.ProcCall(uid=1, proc="pick", args=(), body=(ir.WaitTime(uid=2, duration=0.5),)), ("pick;",)),
]


def _emit(row: Row) -> tuple[str, tuple]:
    result = emit_row(RapidBackend, row)
    (text,) = result.files.values()
    return text, result.diagnostics


@pytest.mark.parametrize("row", ROWS, ids=lambda r: r.name)
def test_instruction_table(row: Row) -> None:
    """Each IR instruction prints as the RAPID lines of the table, with its data declared."""
    text, diagnostics = _emit(row)
    assert tuple(routine_lines(text, "PROC main()", "ENDPROC")) == row.lines
    declared = [ln.strip() for ln in text.splitlines()]
    for decl in row.decls:
        assert decl in declared
    found = tuple(d.code.id for d in diagnostics if d.code.id != "W408")
    assert found == row.codes


@pytest.mark.parametrize("row", ROWS, ids=lambda r: r.name)
def test_every_row_passes_rapidchecker(row: Row) -> None:
    """Every module the table produces is valid RAPID for an independent parser."""
    text, _ = _emit(row)
    assert [str(e) for e in check_file(text)] == []


class TestModule:
    def test_sample_passes_rapidchecker(self) -> None:
        """The all-instructions sample is valid RAPID (rapidchecker: syntax, indentation, whitespace)."""
        result = RapidBackend().emit(sample_program())
        assert list(result.files) == ["demo.mod"]
        assert [str(e) for e in check_file(result.files["demo.mod"])] == []

    def test_deterministic(self) -> None:
        """Two runs give byte-identical files."""
        assert RapidBackend().emit(sample_program()).files == RapidBackend().emit(sample_program()).files

    def test_source_map_comments(self) -> None:
        """Each instruction is preceded by `! file:line`; --no-source-map drops them."""
        text = RapidBackend().emit(sample_program()).files["demo.mod"]
        lines = [ln.strip() for ln in text.splitlines()]
        i = lines.index("WaitTime 0.300;")
        assert lines[i - 1] == "! demo.rmot:7"
        bare = RapidBackend().emit(sample_program(), source_map=False).files["demo.mod"]
        assert "! demo.rmot:7" not in bare and "WaitTime 0.300;" in bare

    def test_proc_becomes_proc(self) -> None:
        """A proc call is a call in main and a PROC holding the body."""
        text = RapidBackend().emit(sample_program()).files["demo.mod"]
        assert "pick;" in routine_lines(text, "PROC main()", "ENDPROC")
        assert routine_lines(text, "PROC pick()", "ENDPROC") == [
            "WaitTime 0.300;", "MoveC arc_mid, above_2, v250, z10, gripper\\WObj:=table_top;"]

    def test_findings_header(self) -> None:
        """--allow-findings puts a warning line at the top of the module."""
        text = RapidBackend(allow_findings_header=True).emit(sample_program()).files["demo.mod"]
        assert "! WARNING: verification reported errors; compiled with --allow-findings" in text.splitlines()[3]


class TestRefusals:
    def test_missing_record_is_an_error(self) -> None:
        """A move the planner did not solve is an error at the move's span (never dropped)."""
        result = RapidBackend().emit(hand_plan((move(1, L, cart(DOWN)),), {}))
        (d,) = [d for d in result.diagnostics if d.is_error]
        assert d.code is codes.MISSING_RECORD and d.span == span_at(11)

    def test_missing_branch_is_an_error(self) -> None:
        """A Cartesian target without a branch cannot get confdata."""
        result = RapidBackend().emit(hand_plan((move(1, L, cart(DOWN)),), {1: (Q, None)}))
        assert [d.code for d in result.diagnostics if d.is_error] == [codes.NO_BRANCH]

    def test_not_six_axis_is_an_error(self) -> None:
        """robtarget/jointtarget data need a 6-axis arm."""
        plan = hand_plan((move(1, L, cart(DOWN)),), {1: (deg(0, 0, 0, 0, 0, 0, 0), None)}, dof=7)
        assert [d.code for d in RapidBackend().emit(plan).diagnostics if d.is_error] == [codes.NOT_SIX_AXIS]

    def test_other_native_vendor_is_skipped_with_a_warning(self) -> None:
        """A native block for another controller is not printed, with W407 (the front end
        refuses unknown vendors with E116, so the backend never sees one from source)."""
        plan = hand_plan((ir.Native(uid=1, vendor="krl", text="x", span=span_at(3)),), {})
        assert [d.code for d in RapidBackend().emit(plan).diagnostics] == [codes.NATIVE_SKIPPED]


class TestNames:
    def test_illegal_and_clashing_names(self) -> None:
        """Signal names are made legal; clashes get a suffix and a warning."""
        body = (ir.SetDigital(uid=1, port=1, value=True, signal="grip-close"),
                ir.SetDigital(uid=2, port=2, value=True, signal="grip close"))
        result = RapidBackend().emit(hand_plan(body, {}))
        text = result.files["demo.mod"]
        assert routine_lines(text, "PROC main()", "ENDPROC") == ["SetDO grip_close, 1;", "SetDO grip_close_2, 1;"]
        assert {d.code.id for d in result.diagnostics} == {"W400", "W401"}

    def test_sync_declares_a_syncident(self) -> None:
        """sync -> WaitSyncTask with a syncident and the task list."""
        plan = hand_plan((ir.Sync(uid=1, name="meet"),), {})
        text = RapidBackend().emit(plan).files["demo.mod"]
        assert routine_lines(text, "PROC main()", "ENDPROC") == ["WaitSyncTask meet, all_tasks;"]
        assert "VAR syncident meet;" in text and 'PERS tasks all_tasks{1}:=[["T_ROB1"]];' in text


def test_zero_length_joint_move_needs_no_time() -> None:
    """A joint move the plan gives no duration (already there) is plain vmax, without \\T or warning."""
    node = move(1, J, ir.JointTarget(tuple(deg(0, -30, 30, 0, 60, 0)), "home"), joint=0.5)
    result = RapidBackend().emit(hand_plan((node,), {1: (Q, FRONT_UP_NOFLIP)}, durations={1: 0.0}))
    assert routine_lines(result.files["demo.mod"], "PROC main()", "ENDPROC") == [
        "MoveAbsJ home\\NoEOffs, vmax, fine, tool0;"]
    assert [d.code.id for d in result.diagnostics] == []  # default accel: nothing to warn
