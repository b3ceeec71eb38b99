"""URScript pose and joint variables assigned more than once, read where their value is certain.

The scripts imitate PolyScope exports (Unitedplastic's `ExtendTest.script`: a Script node sets
`p_5 = p[..]`, then an Assignment node `global p_5=p_5`, then a MoveL to `p_5`) and hand-written
programs that reuse one pose variable for several points.

Witnesses: the expectations are written by hand from the URScript manual (e-Series, "Scoping
rules", module math: `pose_trans(A, B)` is B in A's frame), and every pose read is compared
with scipy's Rotation of the rotation vector (and its composition), not the code under test.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import rmot.backends.readers.urscript as reader
from rmot.backends.readers.model import Move, Native
from tests.backends.test_import_urscript_forms import A, B, _matrix, _p, _read, _scipy

_MOVE_OPTIONS = "a=1.2, v=0.25"


def _poses(stmts: list[object]) -> list[np.ndarray]:
    out = []
    for s in stmts:
        if isinstance(s, Move):
            assert s.pose is not None and s.target_name is None
            out.append(_matrix(s.pose.position, s.pose.quaternion))
    return out


def _native_moves(stmts: list[object]) -> list[str]:
    return [s.text for s in stmts if isinstance(s, Native) and s.text.startswith("move")]


def test_polyscope_script_node_then_assignment_node(tmp_path: Path) -> None:
    """`p_5 = p[..]` then `global p_5=p_5` (the same value) then `movel(p_5)`: the move goes
    to the literal's pose; `movej` of the other variable too."""
    doc, stmts = _read(tmp_path, f"def prog():\n  p_5 = {_p(A)}\n  p_4 = {_p(B)}\n  global p_4=p_4\n"
                       f"  global p_5=p_5\n  movej(p_4, a=1.4, v=1.05)\n  movel(p_5, {_MOVE_OPTIONS})\nend\n")
    assert not _native_moves(stmts)
    got = _poses(stmts)
    assert len(got) == 2 and not doc.targets
    assert np.allclose(got[0], _scipy(B), atol=1e-12) and np.allclose(got[1], _scipy(A), atol=1e-12)


def test_a_variable_reused_for_several_points(tmp_path: Path) -> None:
    """One variable set to a literal, moved to, set to another (a composition of known poses),
    moved to: each move reads the value set last before it."""
    text = (f"def prog():\n  pt = {_p(A)}\n  movel(pt, {_MOVE_OPTIONS})\n  pt = pose_trans({_p(A)}, {_p(B)})\n"
            f"  movel(pt, {_MOVE_OPTIONS})\n  q = pt\n  pt = {_p(B)}\n  movel(q, {_MOVE_OPTIONS})\n"
            f"  movel(pt, {_MOVE_OPTIONS})\nend\n")
    _, stmts = _read(tmp_path, text)
    expected = [_scipy(A), _scipy(A) @ _scipy(B), _scipy(A) @ _scipy(B), _scipy(B)]
    got = _poses(stmts)
    assert not _native_moves(stmts) and len(got) == 4
    assert all(np.allclose(g, e, atol=1e-12) for g, e in zip(got, expected))


def test_joint_list_variable(tmp_path: Path) -> None:
    """`q = [..]` twice (rad): each movej reads the joints set last, in degrees."""
    _, stmts = _read(tmp_path, "def prog():\n  q = [0, -1.5, 1.5, 0, 1.5, 0]\n  movej(q, a=1.4, v=1.05)\n"
                     "  q = [0.5, -1.5, 1.5, 0, 1.5, 0]\n  movej(q, a=1.4, v=1.05)\nend\n")
    moves = [s for s in stmts if isinstance(s, Move)]
    assert [m.joints[0] if m.joints else None for m in moves] == [0.0, np.degrees(0.5)]


def test_uncertain_values_stay_native(tmp_path: Path) -> None:
    """A value computed at run time, one set inside a branch, one changed element by element,
    and one read inside a function (which may run after any assignment) leave their moves
    native."""
    text = (f"def prog():\n  def go():\n    movel(c, {_MOVE_OPTIONS})\n  end\n"
            f"  a = {_p(A)}\n  a = get_actual_tcp_pose()\n  movel(a, {_MOVE_OPTIONS})\n"
            f"  b = {_p(A)}\n  if get_standard_digital_in(1):\n    b = {_p(B)}\n  end\n  movel(b, {_MOVE_OPTIONS})\n"
            f"  c = {_p(A)}\n  c = {_p(B)}\n  c[2] = 0.5\n  movel(c, {_MOVE_OPTIONS})\n  go()\nend\n")
    _, stmts = _read(tmp_path, text)
    assert _native_moves(stmts) == [f"movel(c, {_MOVE_OPTIONS})", f"movel(a, {_MOVE_OPTIONS})",
                                    f"movel(b, {_MOVE_OPTIONS})", f"movel(c, {_MOVE_OPTIONS})"]


def test_a_functions_variable_set_then_moved_to(tmp_path: Path) -> None:
    """A hand-written function sets one variable to a point, moves to it, sets it to the next
    point, moves again (akingse/UR_PolyScope_test `URtest2`: `global point_scan=p[..]`,
    `movej(point_scan, ..)`, `point_scan=p[..]`, `movej(point_scan, ..)`), a speed variable
    likewise: each move reads the value set right before it (scipy)."""
    text = (f"def scan():\n  global pt = {_p(A)}\n  speed = 0.1\n  movej(pt, a=1.4, v=1.05)\n"
            f"  pt = {_p(B)}\n  speed = speed * 2\n  movel(pt, a=1.2, v=speed)\nend\nscan()\n")
    _, stmts = _read(tmp_path, text)
    assert not _native_moves(stmts)
    got = _poses(stmts)
    assert len(got) == 2 and np.allclose(got[0], _scipy(A), atol=1e-12) and np.allclose(got[1], _scipy(B), atol=1e-12)
    assert [s.speed for s in stmts if isinstance(s, Move)][1] == 0.1 * 2 * 1000.0


@pytest.mark.parametrize("between", [
    "  other()\n",  # a call: the function may set any global
    "  SubP_initialize()\n",  # a function another file of the program defines (akingse's files)
    "  x = rq_current_pos()\n",  # a URCap's function, in an assignment
    "  th = run other_thread()\n",  # a thread started
    "  if get_standard_digital_in(1):\n    sleep(0.1)\n  end\n",  # a block
    "  pt[2] = 0.5\n",  # an element changed
])
def test_a_value_is_forgotten_where_something_may_change_it(tmp_path: Path, between: str) -> None:
    text = (f"def other():\n  sleep(0.1)\nend\nthread other_thread():\n  sleep(0.1)\nend\n"
            f"def scan():\n  pt = {_p(A)}\n  pt = {_p(B)}\n{between}  movel(pt, {_MOVE_OPTIONS})\nend\nscan()\n")
    _, stmts = _read(tmp_path, text)
    assert _native_moves(stmts) == [f"movel(pt, {_MOVE_OPTIONS})"]


def test_a_name_a_thread_sets_is_never_certain(tmp_path: Path) -> None:
    """A thread may set the name between any two statements: even right after the function
    assigns it, the move stays native; a read inside a block stays native too."""
    text = (f"thread watch():\n  pt = get_actual_tcp_pose()\nend\n"
            f"def scan():\n  pt = {_p(A)}\n  pt = {_p(B)}\n  movel(pt, {_MOVE_OPTIONS})\n  q = {_p(A)}\n  q = {_p(B)}\n"
            f"  while get_standard_digital_in(1):\n    movel(q, {_MOVE_OPTIONS})\n  end\nend\nscan()\n")
    _, stmts = _read(tmp_path, text)
    assert _native_moves(stmts) == [f"movel(pt, {_MOVE_OPTIONS})", f"movel(q, {_MOVE_OPTIONS})"]


def test_a_native_move_says_which_value_is_not_known(tmp_path: Path) -> None:
    """W510 of a move kept native names its unknown value: read at run time, a function of the
    file, a parameter, a name the file never sets (akingse's `URtest2` reads speeds its other
    file sets), one set in two branches."""
    text = ("def shift(q):\n  return q\nend\ndef go(x):\n  movel(p[x, 0.1, 0.2, 0, 3.1, 0], a=1.2, v=0.25)\nend\n"
            "def prog():\n  movel(get_actual_tcp_pose(), a=1.2, v=0.25)\n  movel(shift(p[0.5, 0.1, 0.2, 0, 3.1, 0]), a=1.2, v=0.25)\n"
            f"  movel({_p(A)}, a=acce, v=0.25)\n  if get_standard_digital_in(1):\n    b = {_p(A)}\n  else:\n"
            f"    b = {_p(B)}\n  end\n  movel(b, a=1.2, v=0.25)\n  go(0.3)\nend\nprog()\n")
    doc, _ = _read(tmp_path, text)
    why = {d.span.start.line: d.message for d in doc.diagnostics if d.code.id == "W510"}
    assert why[5].startswith("`x` is a parameter of the function")
    assert why[8].startswith("`get_actual_tcp_pose(..)` is computed at run time")
    assert why[9].startswith("`shift(..)` is computed at run time")
    assert why[10].startswith("`acce` is not set in this file")
    assert why[16].startswith("`b`'s value here is not known for certain (the file sets it at 2 places)")


def test_straight_line_code_does_not_look_for_block_ends(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Finding a block's end scans to it: done for loops only, so a long straight-line program
    (here 400 statements) is read in time proportional to its length, not its square."""
    calls: list[int] = []
    real = reader.block_end
    monkeypatch.setattr(reader, "block_end", lambda heads, i: calls.append(i) or real(heads, i))
    body = "".join(f"  pt = p[0.{k % 90 + 10}, 0.1, 0.2, 0, 3.1, 0]\n  movel(pt, {_MOVE_OPTIONS})\n" for k in range(200))
    _, stmts = _read(tmp_path, f"def prog():\n{body}end\n")
    assert len(_poses(stmts)) == 200 and len(calls) <= 2
