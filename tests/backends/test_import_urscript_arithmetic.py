"""URScript values written as arithmetic over numbers and variables whose value is certain.

The scripts imitate a hand-written program of a new author (akingse/UR_PolyScope_test,
`URtest3`: a `SubP_initialize()` function sets `global pi=3.14159265`, speeds, blend radii and
`global point_turn=p[0.650,0.350,0.225,pi,0,0]`; moves read `a=acce`, go to
`pose_trans(point_pave1, dropz)` with `global dropz=p[0,0,0.050,0,0,0]`, and offsets are
written `p[0,-(i+1)*(width+gap),0,0,0,0]`).

Witnesses: each expression's value is computed by Python's own arithmetic on the same text's
numbers (written out by hand here), `d2r` by numpy's deg2rad (URScript manual, module urmath:
d2r "Returns the radian value of 'd' degrees"), every pose by scipy's Rotation of the rotation
vector, and `pose_trans(A, D)` of a translation D by the matrix product A · D (URScript manual,
module math: the second pose is expressed in the first's frame), none of them the code under test.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from rmot.backends.readers.model import Move, Native, Wait
from rmot.backends.readers.urscript_values import arithmetic
from tests.backends.test_import_urscript_forms import _matrix, _read, _scipy

_INIT = ("def SubP_initialize():\n\tglobal pi=3.14159265\n\tglobal width=0.300\n\tglobal gap=0.005\n"
         "\tglobal dropz=p[0,0,0.050,0,0,0]\n\tglobal acce=1.20\n\tglobal v_idle=0.35\n\tglobal t=8\n"
         "\tglobal point_turn=p[0.650,0.350,0.225,pi,0,0]\nend\n")


def _moves(stmts: list[object]) -> list[Move]:
    return [s for s in stmts if isinstance(s, Move)]


def test_a_hand_written_program_of_constants(tmp_path: Path) -> None:
    """Poses and move options over names set once (`pi`, `width`, `acce`), arithmetic inside a
    pose literal, `d2r(..)`, and a tool-axis offset by a named translation: every move is read,
    each value the one Python computes from the same numbers."""
    text = _INIT + ("def moves():\n\tmovej(point_turn,a=acce,v=v_idle)\n"
                    "\tmovel(pose_trans(point_turn,dropz),a=acce,v=0.001*100)\n"
                    "\tmovel(p[0.6,-(width+gap),0.2,0,pi/2,0],a=acce*0.5,v=v_idle)\n"
                    "\tmovel(p[0.6,0.1,0.2,d2r(180),0,0], a=acce, v=v_idle)\n"
                    "\tsleep(0.001*(10-t))\nend\nSubP_initialize()\nmoves()\n")
    doc, stmts = _read(tmp_path, text)
    assert not [s for s in stmts if isinstance(s, Native) and s.text.startswith(("move", "sleep"))]
    turn = next(t for t in doc.targets if t.name == "point_turn")
    assert turn.pose is not None
    assert np.allclose(_matrix(turn.pose.position, turn.pose.quaternion),
                       _scipy([0.650, 0.350, 0.225, 3.14159265, 0, 0]), atol=1e-12)
    joint, offset, literal, turned = _moves(stmts)
    assert (joint.kind, joint.target) == ("joint", "point_turn")
    assert offset.target == "point_turn * pose(z=50mm)" and offset.speed == pytest.approx(0.001 * 100 * 1000.0)
    pose = literal.pose
    assert pose is not None and literal.accel == pytest.approx(1.20 * 0.5 * 1000.0)
    assert np.allclose(_matrix(pose.position, pose.quaternion),
                       _scipy([0.6, -(0.300 + 0.005), 0.2, 0, 3.14159265 / 2, 0]), atol=1e-12)
    assert turned.pose is not None
    assert np.allclose(_matrix(turned.pose.position, turned.pose.quaternion),
                       _scipy([0.6, 0.1, 0.2, float(np.deg2rad(180)), 0, 0]), atol=1e-12)
    wait = next(s for s in stmts if isinstance(s, Wait))
    assert wait.seconds == pytest.approx(0.001 * (10 - 8))


def test_the_offset_is_the_tool_axis_product(tmp_path: Path) -> None:
    """The rmot form `point_turn * pose(z=50mm)` is the product A · D of the two matrices."""
    text = _INIT + "def moves():\n\tmovel(pose_trans(point_turn,dropz),a=acce,v=0.1)\nend\nSubP_initialize()\nmoves()\n"
    doc, stmts = _read(tmp_path, text)
    (move,) = _moves(stmts)
    assert move.target == "point_turn * pose(z=50mm)"
    expected = _scipy([0.650, 0.350, 0.225, 3.14159265, 0, 0]) @ _scipy([0, 0, 0.050, 0, 0, 0])
    # the tool z axis of a turn by ~pi about x points down: the offset lowers the point by 50 mm
    assert math.isclose(expected[2, 3], 0.225 - 0.050, abs_tol=1e-8)


@pytest.mark.parametrize("value", [
    "1/2",  # two integers: URScript's integer division is not rmot's
    "width/0",  # a division by zero
    "unknown_name*2",  # a name never set
    "pi",  # no builtin is assumed: a file that does not set `pi` leaves it unknown
    "twice+1",  # a name set in two branches
    "d2r(twice)",  # a function of an unknown value
    "acos(0.5)",  # a function other than d2r/r2d
    "(" * 40 + "1.0" + ")" * 40,  # nested deeper than any program writes
    "0.1 0.2",  # not one expression
])
def test_uncertain_or_unsupported_values_stay_native(tmp_path: Path, value: str) -> None:
    """A pose element or move option whose value is not certain keeps its move native."""
    text = ("def prog():\n  global width=0.3\n  if get_standard_digital_in(1):\n    twice = 1\n  else:\n"
            f"    twice = 2\n  end\n  movel(p[0.5, 0.1, {value}, 0, 3.1, 0], a=1.2, v=0.25)\n"
            f"  movel(p[0.5, 0.1, 0.3, 0, 3.1, 0], a=1.2, v={value})\nend\n")
    _, stmts = _read(tmp_path, text)
    assert not _moves(stmts)
    assert len([s for s in stmts if isinstance(s, Native) and s.text.startswith("movel")]) == 2


@pytest.mark.parametrize(("text", "expected"), [
    ("2+3*4", 2 + 3 * 4), ("-(2-5)*2", -(2 - 5) * 2), ("2*-3", 2 * -3), ("1.0/4", 1.0 / 4), ("--2", 2),
    ("a/b*2", 2.5 / 0.5 * 2), ("a-b-1", 2.5 - 0.5 - 1), ("d2r(90)/2", math.radians(90) / 2), ("r2d(a)", math.degrees(2.5)),
    ("1e-3*(10-8)", 1e-3 * (10 - 8)), (".5+a", 0.5 + 2.5),
])
def test_arithmetic_binds_as_python(text: str, expected: float) -> None:
    """The evaluator's priorities and signs are Python's (URScript manual: the operators bind as
    Python's): each value equals Python's own arithmetic on the same numbers."""
    assert arithmetic(text, {"a": 2.5, "b": 0.5}.get) == pytest.approx(expected, rel=1e-15)
