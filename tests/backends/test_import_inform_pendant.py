"""INFORM jobs as a pendant saves them: position variables (`P00100=` in //POS, `MOVJ P100`
in the instructions) next to local positions, a `///USER n` frame for POSTYPE USER positions
and the line comment the pendant writes after `//`; pulse positions stay native and say why.

Witnesses: the job text follows a pendant-saved job by another author (icors2's Yaskawa-Job-
Helper fixture CUT_ONLY.JBI, written on a DX200); the expected poses are computed here with
scipy's Rotation (INFORM's Rx, Ry, Rz are fixed-axis X, then Y, then Z: `from_euler("xyz")`),
not with the reader's conversion.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from scipy.spatial.transform import Rotation

from rmot.backends.readers import read_files
from rmot.backends.readers.model import Move, Native, Pulse, Wait, walk

JOB = """/JOB
//NAME CUT_ONLY
//POS
///NPOS 0,0,0,3,0,0
///TOOL 0
///POSTYPE BASE
///RECTAN
///RCONF 1,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0
P00100=275.000,0.000,875.000,180.0000,45.0000,0.0000
///USER 1
///POSTYPE USER
P00105=216.374,-55.365,150.000,179.9941,-0.0013,-179.9943
P00106=183.974,-55.386,-103.111,179.9969,-0.0014,-179.9945
//INST
///DATE 2023/01/24 16:29
///ATTR SC,RW
///GROUP1 RB1
NOP
MOVJ P100 VJ=50.00
'CUT*****************************
MOVJ P105 VJ=25.00  //APPROCH CUT
MOVL P106 V=150.0 PL=0  //CUT PRE-SLIDE
PULSE OT#(3003) T=0.50
TIMER T=0.50
MOVJ P0100 VJ=50.00
END
"""


def _moves(tmp_path: Path, text: str) -> tuple[list[Move], list[object]]:
    path = tmp_path / "CUT_ONLY.JBI"
    path.write_text(text)
    doc = read_files([str(path)])
    stmts = [s for r in doc.routines for s in walk(r.body)]
    return [s for s in stmts if isinstance(s, Move)], stmts


def _expected(x: float, y: float, z: float, rx: float, ry: float, rz: float) -> tuple[np.ndarray, np.ndarray]:
    xyzw = Rotation.from_euler("xyz", [rx, ry, rz], degrees=True).as_quat()
    return np.array([x, y, z]) / 1000.0, np.array([xyzw[3], *xyzw[:3]])


def _same_pose(move: Move, values: tuple[float, ...]) -> bool:
    assert move.pose is not None
    position, q = _expected(*values)
    got = np.array(move.pose.quaternion)
    return bool(np.allclose(move.pose.position, position, atol=1e-9)
                and min(np.abs(got - q).max(), np.abs(got + q).max()) < 1e-9)


def test_position_variables_frames_and_line_comments(tmp_path: Path) -> None:
    moves, stmts = _moves(tmp_path, JOB)
    assert [(m.kind, m.target, m.frame, m.joint_pct, m.speed, m.zone) for m in moves] == [
        ("joint", "cut_only_p00100", "base", 50.0, None, None),
        ("joint", "cut_only_p00105", "user1", 25.0, None, None),
        ("linear", "cut_only_p00106", "user1", None, 150.0, None),  # PL=0: exact stop
        ("joint", "cut_only_p00100", "base", 50.0, None, None),  # P0100 is P100
    ]
    assert _same_pose(moves[0], (275.0, 0.0, 875.0, 180.0, 45.0, 0.0))
    assert _same_pose(moves[1], (216.374, -55.365, 150.0, 179.9941, -0.0013, -179.9943))
    assert [type(s) for s in stmts if not isinstance(s, Move)] == [Pulse, Wait]
    assert not any(isinstance(s, Native) for s in stmts)


def test_pulse_position_variable_stays_native_and_says_why(tmp_path: Path) -> None:
    text = JOB.replace("///NPOS 0,0,0,3,0,0\n", "///NPOS 0,0,0,4,0,0\n///POSTYPE PULSE\n///PULSE\n"
                       "P00001=-204317,-84436,-64683,-41499,-71625,29263\n").replace(
        "MOVJ P0100 VJ=50.00", "MOVJ P001 VJ=50.00")
    path = tmp_path / "CUT_ONLY.JBI"
    path.write_text(text)
    doc = read_files([str(path)])
    natives = [s for r in doc.routines for s in walk(r.body) if isinstance(s, Native)]
    assert [n.text for n in natives] == ["MOVJ P001 VJ=50.00"]
    why = [d.message for d in doc.diagnostics if d.code.id == "W510"]
    assert len(why) == 1 and "P00001 is a pulse position" in why[0]


def test_a_comment_inside_a_message_is_kept(tmp_path: Path) -> None:
    """`//` inside a quoted string is the string's, not a line comment."""
    moves, stmts = _moves(tmp_path, JOB.replace("TIMER T=0.50", 'MSG "see //HOME"'))
    assert [n.text for n in stmts if isinstance(n, Native)] == ['MSG "see //HOME"']


def test_positions_without_a_data_form_are_not_millimetres(tmp_path: Path) -> None:
    """A job written without `///POSTYPE`/`///RECTAN` (hehonglu123's Welding_Motoman
    blending_test/linear/linear.JBI, run on a real arm) holds pulse counts: its moves stay
    native, not read as positions 48 m away."""
    path = tmp_path / "AAA.JBI"
    path.write_text("/JOB\n//NAME AAA\n//POS\n///NPOS 2,0,0,0,0,0\nC00000=-48629,112084,69901,4161,-52375,-4796\n"
                    "C00001=-46969,105372,61036,4871,-50464,-5567\n//INST\n///DATE 2023/02/07 09:03\n"
                    "///ATTR SC,RW\n///GROUP1 RB1\nNOP\nMOVL C00000 V=10.0 PL=8\nMOVL C00001 V=10.0 PL=0\nEND\n")
    doc = read_files([str(path)])
    stmts = [s for r in doc.routines for s in walk(r.body)]
    assert not doc.targets and not any(isinstance(s, Move) for s in stmts)
    assert [s.text for s in stmts if isinstance(s, Native)] == ["MOVL C00000 V=10.0 PL=8", "MOVL C00001 V=10.0 PL=0"]


def test_acc_dec_on_a_linear_move(tmp_path: Path) -> None:
    """Equal ACC=/DEC= on MOVL (the YRC1000 tags of MOVJ, MOVL and MOVC: acceleration and
    deceleration ratios) is the joint acceleration share with W540 at its line; unequal ones
    have no rmot form."""
    text = JOB.replace("MOVL P106 V=150.0 PL=0  //CUT PRE-SLIDE", "MOVL P106 V=150.0 PL=0 ACC=50 DEC=50\n"
                       "MOVL P105 V=150.0 ACC=50 DEC=20")
    moves, stmts = _moves(tmp_path, text)
    assert [(m.kind, m.target, m.joint_accel) for m in moves if m.kind == "linear"] == [
        ("linear", "cut_only_p00106", 50.0)]
    assert [s.text for s in stmts if isinstance(s, Native)] == ["MOVL P105 V=150.0 ACC=50 DEC=20"]
    doc = read_files([str(tmp_path / "CUT_ONLY.JBI")])
    assert [(d.code.id, d.span.start.line) for d in doc.diagnostics if d.code.id == "W540"] == [("W540", 22)]
