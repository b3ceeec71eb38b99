"""Fanuc TP backend: instruction table, LS layout, line numbers, splitting, determinism, refusals."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
from backend_fixtures import (
    DOWN, GRIPPER, TABLE, C, J, L, Row, cart, deg, emit_row, hand_plan, move, sample_program, span_at,
)

from rmot.backends import codes
from rmot.backends.fanuc_tp import FanucBackend
from rmot.backends.fanuc_tp_text import config_string, turn_number
from rmot.lang import ir

FRAMES = ("UFRAME_NUM=0", "UTOOL_NUM=1")


ROWS = [
    Row("j_joint", move(1, J, ir.JointTarget(tuple(deg(0, 0, 0, 0, -90, 0)), "home"), joint=0.5),
        FRAMES + ("J P[1] 50% FINE",), codes=("W416",)),
    Row("j_pose", move(1, J, cart(DOWN, name="p1"), zone=0.01), FRAMES + ("J P[1] 100% CNT10",), codes=("W403", "W416")),
    Row("j_rounded", move(1, J, cart(DOWN, name="p1"), joint=0.333), FRAMES + ("J P[1] 33% FINE",), codes=("W402", "W416")),
    Row("l_speed", move(1, L, cart(DOWN, name="p1"), speed=0.5), FRAMES + ("L P[1] 500mm/sec FINE",), codes=("W416",)),
    Row("l_time", move(1, L, cart(DOWN, name="p1"), duration=2.5), FRAMES + ("L P[1] 2.50sec FINE",), codes=("W416",)),
    Row("l_frames", move(1, L, cart(DOWN, TABLE), tool=GRIPPER, frame=TABLE, speed=0.1),
        ("UFRAME_NUM=1", "UTOOL_NUM=1", "L P[1] 100mm/sec FINE"), codes=("W411", "W416", "W416")),
    Row("c_move", move(1, C, cart(DOWN, name="p1"), via=cart(DOWN, name="mid")),
        FRAMES + ("C P[1]", ":  P[2] 250mm/sec FINE"), codes=("W416",)),
    Row("do", ir.SetDigital(uid=1, port=1, value=True, signal="gripper_close"), ("DO[1:gripper_close]=ON",)),
    Row("ao", ir.SetAnalog(uid=1, port=2, value=4.5), ("AO[2]=4.500",)),
    Row("pulse", ir.Pulse(uid=1, port=3, duration=0.2), ("DO[3]=PULSE,0.2sec",)),
    Row("wait", ir.WaitTime(uid=1, duration=0.3), ("WAIT 0.30(sec)",)),
    Row("wait_di", ir.WaitInput(uid=1, condition=ir.InputCondition(port=2, value=False)), ("WAIT DI[2]=OFF",)),
    Row("wait_di_timeout", ir.WaitInput(uid=1, condition=ir.InputCondition(port=2, value=True), timeout=5.0),
        ("$WAITTMOUT=500", "WAIT DI[2]=ON TIMEOUT,LBL[1]", "JMP LBL[2]", "LBL[1]", "!wait timed out", "ABORT",
         "LBL[2]")),
    Row("if_else", ir.If(uid=1, condition=ir.InputCondition(port=2, value=True),
                         then=(ir.WaitTime(uid=2, duration=1.0),), otherwise=(ir.SetDigital(uid=3, port=1, value=False),)),
        ("IF DI[2]<>ON,JMP LBL[1]", "WAIT 1.00(sec)", "JMP LBL[2]", "LBL[1]", "DO[1]=OFF", "LBL[2]")),
    Row("native", ir.Native(uid=1, vendor="fanuc", text="MESSAGE[done] ;\nPAUSE"), ("MESSAGE[done]", "PAUSE")),
    Row("proc_call", ir.ProcCall(uid=1, proc="pick", args=(), body=(ir.WaitTime(uid=2, duration=0.5),)), ("CALL DEMO_PICK",)),
    Row("sync_single_task_noop", ir.Sync(uid=1, name="meet"), ("!sync meet: no-op (single task)",)),
]


def _mn(text: str) -> list[str]:
    """The /MN body without line numbers, comments and the frame set-up."""
    body = text.split("/MN\n")[1].split("/POS")[0].splitlines()
    out = [re.sub(r"^\s*\d+:\s\s|^\s{4}", "", ln).removesuffix(" ;") for ln in body]
    out = [ln for ln in out if not re.match(r"PR\[\d+|UTOOL\[|UFRAME\[|!UTOOL|!UFRAME|!generated|!target|![a-z.]*rmot", ln)]
    return [ln for ln in out if not ln.startswith("!'") and not ln.startswith("!do") and not ln.startswith("!hand")]


@pytest.mark.parametrize("row", ROWS, ids=lambda r: r.name)
def test_instruction_table(row: Row) -> None:
    """Each IR instruction prints as the numbered TP lines of the table."""
    result = emit_row(FanucBackend, row)
    assert tuple(ln for ln in _mn(result.files["DEMO.ls"]) if not ln.startswith("!native")) == row.lines
    assert tuple(d.code.id for d in result.diagnostics) == row.codes


class TestPositions:
    def test_cartesian_position_record(self) -> None:
        """A Cartesian P[] has UF/UT, the CONFIG string and X Y Z W P R."""
        files = emit_row(FanucBackend, Row("x", move(1, L, cart(DOWN, name="p1")), ())).files
        pos = files["DEMO.ls"].split("/POS\n")[1]
        assert pos.startswith('P[1:"p1"]{\n   GP1:\n\tUF : 0, UT : 1,\t\tCONFIG : \'F U T, 0, 0, 1\',\n')
        assert "\tX =   400.000  mm,\tY =  -100.000  mm,\tZ =   300.000  mm,\n" in pos
        assert "\tW =   180.000 deg,\tP =     0.000 deg,\tR =     0.000 deg\n};" in pos

    def test_joint_position_record(self) -> None:
        """A joint target uses the joint representation."""
        files = emit_row(FanucBackend, Row("x", move(1, J, ir.JointTarget(tuple(deg(1, 2, 3, 4, -90, 6)))), ())).files
        assert "\tJ4=     4.000 deg,\tJ5=   -90.000 deg,\tJ6=     6.000 deg\n" in files["DEMO.ls"]

    @pytest.mark.parametrize(("deg_value", "turn"), [(0, 0), (180, 0), (181, 1), (540, 1), (-179, 0), (-180, -1),
                                                      (-181, -1), (-539, -1), (-540, -2)])
    def test_turn_number(self, deg_value: float, turn: int) -> None:
        """Turn k covers (-180 + 360k, 180 + 360k] deg."""
        assert turn_number(math.radians(deg_value)) == turn

    @pytest.mark.parametrize(("branch", "flags"), [
        (ir.Config(ir.Shoulder.FRONT, ir.Elbow.UP, ir.Wrist.FLIP), "N U T"),
        (ir.Config(ir.Shoulder.BACK, ir.Elbow.DOWN, ir.Wrist.NOFLIP), "F D B"),
    ])
    def test_config_flags(self, branch: ir.Config, flags: str) -> None:
        """rmot FLIP (J5 < 0) is Fanuc N; elbow up U; shoulder front T."""
        assert config_string(branch, np.zeros(6)) == f"{flags}, 0, 0, 0"


class TestProgram:
    def test_layout_and_line_numbers(self) -> None:
        """/PROG, /ATTR, /MN, /POS, /END in order; /MN lines numbered 1..n; LINE_COUNT = n."""
        text = FanucBackend().emit(sample_program()).files["DEMO.ls"]
        heads = [ln for ln in text.splitlines() if ln.startswith("/")]
        assert heads == ["/PROG  DEMO", "/ATTR", "/MN", "/POS", "/END"]
        numbers = [int(m) for m in re.findall(r"^\s*(\d+):  ", text, re.M)]
        assert numbers == list(range(1, len(numbers) + 1))
        assert f"LINE_COUNT\t= {len(numbers)};" in text

    def test_procs_are_separate_programs(self) -> None:
        """A proc is its own .ls file, called with CALL."""
        files = FanucBackend().emit(sample_program()).files
        assert list(files) == ["DEMO.ls", "DEMO_PICK.ls"]
        assert "CALL DEMO_PICK ;" in files["DEMO.ls"] and files["DEMO_PICK.ls"].startswith("/PROG  DEMO_PICK\n")

    def test_comments_fit_the_pendant(self) -> None:
        """Every comment line is at most 32 characters after the '!'."""
        text = FanucBackend().emit(sample_program()).files["DEMO.ls"]
        comments = re.findall(r"^\s*\d+:  !(.*) ;$", text, re.M)
        assert comments and max(len(c) for c in comments) <= 32

    def test_deterministic(self) -> None:
        """Two runs give byte-identical files."""
        assert FanucBackend().emit(sample_program()).files == FanucBackend().emit(sample_program()).files

    def test_split(self) -> None:
        """Past MAX_INSTRUCTIONS the program is split into called parts, with W406."""

        class Small(FanucBackend):
            MAX_INSTRUCTIONS = 2

        body = tuple(ir.WaitTime(uid=i, duration=0.1 * i, span=span_at(i)) for i in range(1, 6))
        result = Small().emit(hand_plan(body, {}, robot="fanuc_lrmate200id"))
        assert list(result.files) == ["DEMO.ls", "DEMO_PART1.ls", "DEMO_PART2.ls", "DEMO_PART3.ls"]
        assert _mn(result.files["DEMO.ls"]) == ["CALL DEMO_PART1", "CALL DEMO_PART2", "CALL DEMO_PART3"]
        assert [d.code for d in result.diagnostics] == [codes.PROGRAM_SPLIT]


class TestResolution:
    @pytest.mark.parametrize(("instr", "line", "code"), [
        (ir.WaitTime(uid=1, duration=0.255), "WAIT 0.26(sec)", "W412"),
        (ir.WaitTime(uid=1, duration=0.25), "WAIT 0.25(sec)", None),
        (ir.Pulse(uid=1, port=1, duration=0.25), "DO[1]=PULSE,0.2sec", "W412"),
        (move(1, L, cart(DOWN), speed=3.0), "L P[1] 2000mm/sec FINE", "W417"),
    ])
    def test_rounded_values_warn(self, instr: ir.Instr, line: str, code: str | None) -> None:
        """Values finer than TP's resolution (or beyond its limit) are rounded with a warning."""
        result = emit_row(FanucBackend, Row("x", instr, ()))
        assert line in _mn(result.files["DEMO.ls"])
        # the frame setup's W416 (the flange tool has no controller number) is not the point here
        assert [d.code.id for d in result.diagnostics if d.code.id != "W416"] == ([code] if code else [])
