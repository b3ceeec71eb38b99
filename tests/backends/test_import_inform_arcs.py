"""INFORM arcs read back: three MOVC points make an arc (DX100 INFORM manual, MOVC; FPT marks
the end of an arc where arcs follow one another). RoboDK's Motoman post writes an arc as three
MOVC alone, the first restating where the move before ended, without FPT
(tests/data/vendor_programs/ROBODK.md); rmot's own backend ends it with FPT.

An arc is read only where its first point is where the move before it ended: otherwise the
robot first moves to that point, a motion the reading would drop. Witnesses: the positions are
compared by hand here (same coordinates, tool and user frame), and the arc's via and end points
are the job's second and third MOVC positions.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from rmot.backends.readers import read_files
from rmot.backends.readers.model import Move, Native, walk

POS = ("C00001=1007.767,-763.700,303.611,180.00,-0.00,-150.00\n"
       "C00002=1007.767,-763.700,303.611,180.00,-0.00,-150.00\n"
       "C00003=1007.767,-713.700,390.214,180.00,-0.00,-150.00\n"
       "C00004=1057.767,-663.700,319.503,180.00,-0.00,-150.00\n"
       "C00005=1000.000,-700.000,300.000,180.00,-0.00,-150.00\n")


def _read(tmp_path: Path, inst: str):  # type: ignore[no-untyped-def]
    path = tmp_path / "ARC.JBI"
    path.write_text("/JOB\n//NAME ARC\n//POS\n///NPOS 5,0,0,0,0,0\n///TOOL 1\n///POSTYPE BASE\n///RECTAN\n"
                    f"///RCONF 0,0,0,0,-1,0,0,0\n{POS}//INST\n///DATE 2026/11/29 02:22\n///ATTR SC,RW\n"
                    f"///GROUP1 RB1\nNOP\n{inst}END\n")
    doc = read_files([str(path)])
    body = [s for r in doc.routines for s in walk(r.body)]
    return [s for s in body if isinstance(s, Move)], [s.text for s in body if isinstance(s, Native)], doc


@pytest.mark.parametrize("between", ["", "DOUT OT#(1) ON\nTIMER T=1.00\n"])
def test_three_movc_alone_after_a_move_to_their_start_are_one_arc(tmp_path: Path, between: str) -> None:
    moves, natives, _ = _read(tmp_path, f"MOVL C00001 V=200.0\n{between}MOVC C00002 V=200.0\nMOVC C00003 V=200.0\n"
                                        "MOVC C00004 V=200.0\nMOVL C00005 V=50.0\n")
    assert not natives
    assert [m.kind for m in moves] == ["linear", "circular", "linear"]
    arc = moves[1]
    assert (arc.via, arc.target, arc.speed) == ("arc_c00003", "arc_c00004", 200.0)


@pytest.mark.parametrize(("inst", "why"), [
    ("MOVL C00005 V=200.0\nMOVC C00002 V=200.0\nMOVC C00003 V=200.0\nMOVC C00004 V=200.0 FPT\n", "start elsewhere, FPT"),
    ("MOVL C00005 V=200.0\nMOVC C00002 V=200.0\nMOVC C00003 V=200.0\nMOVC C00004 V=200.0\n", "start elsewhere"),
    ("MOVL C00001 V=200.0\nCALL JOB:TCP_ON\nMOVC C00002 V=200.0\nMOVC C00003 V=200.0\nMOVC C00004 V=200.0\n",
     "a call between"),
    ("MOVL C00001 V=200.0\nMOVC C00002 V=200.0\nMOVC C00003 V=200.0\nMOVC C00004 V=200.0\nMOVC C00005 V=200.0\n",
     "four MOVC, no FPT"),
])
def test_an_arc_whose_start_the_robot_may_not_stand_at_stays_native(tmp_path: Path, inst: str, why: str) -> None:
    moves, natives, doc = _read(tmp_path, inst)
    assert not any(m.kind == "circular" for m in moves), why
    assert "MOVC C00002 V=200.0" in natives
    reasons = [d.message for d in doc.diagnostics if d.code.id == "W510" and "MOVC C00002" in d.message]
    assert reasons and "its first MOVC is where the move before it ended" in reasons[0]


def test_the_fpt_form_after_a_move_to_its_start_is_still_one_arc(tmp_path: Path) -> None:
    moves, natives, _ = _read(tmp_path, "MOVL C00001 V=200.0\nMOVC C00002 V=200.0\nMOVC C00003 V=200.0\n"
                                        "MOVC C00004 V=200.0 FPT\nMOVC C00005 V=200.0\nMOVC C00003 V=200.0 FPT\n")
    assert not natives
    assert [(m.kind, m.via, m.target) for m in moves] == [
        ("linear", None, "arc_c00001"), ("circular", "arc_c00003", "arc_c00004"), ("circular", "arc_c00005", "arc_c00003")]


def _check(tmp_path: Path, name: str, text: str) -> tuple[str, str, int]:
    from click.testing import CliRunner

    from rmot.compiler.cli import cli
    path = tmp_path / name
    path.write_text(text)
    out = tmp_path / "out.rmot"
    imported = CliRunner().invoke(cli, ["import", str(path), "-o", str(out)], catch_exceptions=False)
    assert imported.exit_code == 0, imported.output
    checked = CliRunner().invoke(cli, ["check", str(out)], catch_exceptions=False)
    return out.read_text() + (tmp_path / "out_cell.rmot").read_text(), imported.output, checked.exit_code


def test_a_job_named_like_icors2s_and_a_user_frame_make_a_program_that_checks(tmp_path: Path) -> None:
    """A job named `001-R1-HOME` (icors2's DX200 backups) gave targets `001-r1-home_c00000`, read
    by `rmot check` as a subtraction (E103/E101, exit 2); a move in user frame 1 (`///USER 1`,
    POSTYPE USER) named a frame the stub did not declare (E101). Now the names are rmot names and
    the user frame is a stub entry, marked and warned (W511)."""
    text, output, code = _check(tmp_path, "001-R1-HOME.JBI", "/JOB\n//NAME 001-R1-HOME\n//POS\n///NPOS 2,0,0,0,0,0\n"
                                "///TOOL 0\n///POSTYPE ROBOT\n///RECTAN\n///RCONF 0,0,0,0,0,0,0,0\n"
                                "C00000=800.000,0.000,600.000,180.00,0.00,0.00\n///USER 1\n///POSTYPE USER\n"
                                "C00001=100.000,0.000,50.000,180.00,0.00,0.00\n//INST\n///DATE 2020/01/01 00:00\n"
                                "///ATTR SC,RW\n///GROUP1 RB1\nNOP\nMOVJ C00000 VJ=10.00\nMOVL C00001 V=50.0\nEND\n")
    assert "target n_001_r1_home_c00000 = " in text and "move joint n_001_r1_home_c00000 " in text
    assert "frame user1 = pose(x=0mm, y=0mm, z=0mm, q=(1, 0, 0, 0)) number 1  # the controller's user frame 1" in text
    assert "warning[W511]: frame `user1` is the controller's user frame 1" in output
    assert code in (0, 1)  # findings at most: the program compiles


def test_a_tp_background_copy_without_position_names_checks(tmp_path: Path) -> None:
    """`/PROG -BCKED8-` (a pendant's background-edit copy): its unnamed positions were
    `-bcked8-_p1`, not an rmot name."""
    text, _, code = _check(tmp_path, "BCK.LS", "/PROG  -BCKED8-\n/ATTR\n/MN\n   1:J P[1] 50% FINE ;\n/POS\nP[1]{\n"
                           "   GP1:\n\tUF : 0, UT : 0,\t\tCONFIG : 'N U T, 0, 0, 0',\n"
                           "\tX = 800.000 mm,\tY = 0.000 mm,\tZ = 600.000 mm,\n"
                           "\tW = 180.000 deg,\tP = 0.000 deg,\tR = 0.000 deg\n};\n/END\n")
    assert "move joint _bcked8__p1 " in text and "target _bcked8__p1 = " in text
    assert code in (0, 1)
