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
