"""URScript forms of hand-written and PolyScope programs, read back: several statements on one
line, targets built by `pose_add` / `pose_trans`, variables whose value is certain (or not),
scripts whose statements follow their first def, conditions combining inputs, analog output
domains.

Witnesses: the expectations are written by hand from the URScript manual (e-Series, modules
math and interfaces: `pose_trans(A, B)` is B in A's frame, `pose_add(A, B)` adds positions and
turns A's orientation by B's; `set_analog_outputdomain(n, 0)` is a current output), and every
converted pose is compared with scipy's Rotation (rotation vectors, composition), which is not
the code under test.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from click.testing import CliRunner
from scipy.spatial.transform import Rotation

from rmot.backends.readers import read_files
from rmot.backends.readers.model import Conds, Cond, If, Move, Native, SetOut, Wait, WaitIn, walk
from rmot.compiler.cli import cli

A = [0.3, -0.2, 0.4, 0.5, -1.2, 2.0]  # p[x, y, z, rx, ry, rz]: m, rotation vector rad
B = [0.01, 0.02, -0.05, 0.3, 0.2, -0.4]


def _read(tmp_path: Path, text: str, name: str = "prog.script"):  # type: ignore[no-untyped-def]
    path = tmp_path / name
    path.write_text(text)
    doc = read_files([str(path)])
    return doc, [s for r in doc.routines for s in walk(r.body)]


def _p(v: list[float]) -> str:
    return "p[" + ", ".join(repr(x) for x in v) + "]"


def _matrix(position: tuple[float, ...], quaternion: tuple[float, ...]) -> np.ndarray:
    w, x, y, z = quaternion
    m = np.eye(4)
    m[:3, :3] = Rotation.from_quat([x, y, z, w]).as_matrix()
    m[:3, 3] = position
    return m


def _scipy(v: list[float]) -> np.ndarray:
    m = np.eye(4)
    m[:3, :3] = Rotation.from_rotvec(v[3:]).as_matrix()
    m[:3, 3] = v[:3]
    return m


def test_statements_on_one_line(tmp_path: Path) -> None:
    """`if (c): movej(q) end` and `movel(..)   sleep(0.5)` are several statements (URScript needs
    no separator); the second statement is located at its own column."""
    line = "  movel(p[0.4, 0.1, 0.3, 0, 3.14159, 0], a=1.2, v=0.25)   sleep(0.5)"
    doc, stmts = _read(tmp_path, "def prog():\n  q1 = [0, -1.5, 1.5, 0, 1.5, 0]\n"
                       f"  if (get_standard_digital_in(2) == True): movej(q1, a=1.4, v=1.05) end\n{line}\nend\n")
    branch = next(s for s in stmts if isinstance(s, If))
    assert branch.cond == Cond(2, True) and [type(s).__name__ for s in branch.then] == ["Move"]
    wait = next(s for s in stmts if isinstance(s, Wait))
    assert wait.seconds == 0.5 and (wait.where.line, wait.where.col) == (4, line.index("sleep") + 1)
    assert not any(isinstance(s, Native) for s in stmts)


def test_pose_add_and_pose_trans_targets(tmp_path: Path) -> None:
    """`global T = pose_trans(A, B)` is A * B; `pose_add(A, B)` is (pA + pB, R_B R_A): each
    target's pose equals scipy's composition of the two rotation-vector poses."""
    doc, stmts = _read(tmp_path, f"def prog():\n  global a_p = {_p(A)}\n  global t_p = pose_trans(a_p, {_p(B)})\n"
                       f"  global s_p = pose_add(a_p, {_p(B)})\n  movel(t_p, a=1.2, v=0.25)\n"
                       "  movel(s_p, a=1.2, v=0.25)\nend\n")
    targets = {t.name: t for t in doc.targets}
    trans = _scipy(A) @ _scipy(B)
    added = np.eye(4)
    added[:3, :3] = Rotation.from_rotvec(B[3:]).as_matrix() @ Rotation.from_rotvec(A[3:]).as_matrix()
    added[:3, 3] = np.add(A[:3], B[:3])
    for name, expected in (("t_p", trans), ("s_p", added)):
        pose = targets[name].pose
        assert pose is not None
        assert np.allclose(_matrix(pose.position, pose.quaternion), expected, atol=1e-12), name
    assert [m.target for m in stmts if isinstance(m, Move)] == ["t_p", "s_p"]


def test_a_variable_assigned_twice_is_not_a_target(tmp_path: Path) -> None:
    """A pose variable assigned again later (a value computed at run time) is no target: the
    move before the new value goes to the literal (its value there is certain), the move after it
    stays native; a numeric variable set again by an expression no longer gives a move's speed."""
    doc, stmts = _read(tmp_path, "def prog():\n  global w_p = p[0.4, 0.1, 0.3, 0, 3.14159, 0]\n  speed = 0.25\n"
                       "  movel(w_p, a=1.2, v=speed)\n  w_p = get_actual_tcp_pose()\n  speed = speed * 2\n"
                       "  movel(w_p, a=1.2, v=speed)\nend\n")
    assert not doc.targets
    assert [s.text for s in stmts if isinstance(s, Native) and s.text.startswith("move")] == [
        "movel(w_p, a=1.2, v=speed)"]
    first = next(s for s in stmts if isinstance(s, Move))
    assert first.target_name is None and first.speed == 250.0 and first.where.line == 4


def test_statements_after_the_first_def_run(tmp_path: Path) -> None:
    """A script of a def and then statements: the statements run (the def is a proc they call);
    the port and the duration may be numeric variables set once."""
    doc, stmts = _read(tmp_path, "def blink():\n  set_standard_digital_out(LED, True)\n  sleep(dwell)\n"
                       "  set_standard_digital_out(LED, False)\nend\nLED = 3\ndwell = 2.5E-1\nblink()\nblink()\n")
    main = next(r for r in doc.routines if r.name == doc.main)
    assert [type(s).__name__ for s in main.body] == ["Native", "Native", "Call", "Call"]  # the assignments
    blink = next(r for r in doc.routines if r.name == "blink")
    assert [(type(s).__name__, getattr(s, "signal", None)) for s in blink.body] == [
        ("SetOut", 3), ("Wait", None), ("SetOut", 3)]
    assert next(s for s in blink.body if isinstance(s, Wait)).seconds == 0.25


def test_combined_input_conditions(tmp_path: Path) -> None:
    """`and` binds tighter than `or`, `not` tightest; `!=` negates; a wait loop on a combined
    test waits for it to fail."""
    doc, stmts = _read(tmp_path, "def prog():\n"
                       "  if get_standard_digital_in(0) == True or not get_standard_digital_in(1) and "
                       "get_configurable_digital_in(2) != False:\n    set_standard_digital_out(1, True)\n  end\n"
                       "  while (get_standard_digital_in(3) == False and get_standard_digital_in(4)):\n"
                       "    sync()\n  end\nend\n")
    branch = next(s for s in stmts if isinstance(s, If))
    assert branch.cond == Conds("or", (Cond(0, True), Conds("and", (Cond(1, False), Cond(10, True)))))
    wait = next(s for s in stmts if isinstance(s, WaitIn))
    assert wait.cond == Conds("not", (Conds("and", (Cond(3, False), Cond(4, True))),))
    doc, stmts = _read(tmp_path, "def prog():\n  if get_digital_in(7):\n    sleep(1)\n  end\n  if get_digital_in(8):\n"
                       "    sleep(1)\n  end\nend\n", "old.script")  # CB-Series name: 0..7 standard, 8..9 the tool's
    assert [s.cond for s in stmts if isinstance(s, If)] == [Cond(7, True)]


def test_analog_output_domain(tmp_path: Path) -> None:
    """On a voltage port (domain 1) 0.25 of the range is 2.5 V; on a current port (domain 0) the
    output stays native (rmot's analog outputs are volts)."""
    doc, stmts = _read(tmp_path, "def prog():\n  set_analog_outputdomain(0, 1)\n  set_analog_outputdomain(1, 0)\n"
                       "  set_standard_analog_out(0, 0.25)\n  set_standard_analog_out(1, 0.25)\nend\n")
    outs = [s for s in stmts if isinstance(s, SetOut)]
    assert [(s.signal, s.value, s.analog) for s in outs] == [(0, 2.5, True)]
    assert any(isinstance(s, Native) and s.text == "set_standard_analog_out(1, 0.25)" for s in stmts)


def test_urcap_installation_node_is_kept_as_a_comment(tmp_path: Path) -> None:
    """A URCap installation node is the robot's installation: its lines go to the comment block
    (W530 at its first line, naming the URCap); the program's call of its function stays
    native; a node whose blocks do not close inside it is read as program text."""
    text = ("def prog():\n  set_tcp(p[0, 0, 0.1, 0, 0, 0])\n  # begin: URCap Installation Node\n"
            "  #   Source: Robotiq_Grippers, 1.7.1.2, Robotiq Inc.\n  #   Type: Gripper\n"
            "  def rq_open():\n    sleep(0.1)\n  end\n  rq_obj = 0\n  # end: URCap Installation Node\n"
            "  $ 1 \"Robot Program\"\n  rq_open()\n  set_standard_digital_out(2, True)\nend\n")
    doc, stmts = _read(tmp_path, text)
    w530 = [d for d in doc.diagnostics if d.code.id == "W530"]
    assert [(d.span.start.line, "Robotiq_Grippers, 1.7.1.2, Robotiq Inc." in d.message) for d in w530] == [(3, True)]
    assert [k.text for k in doc.kept] == ["def rq_open():", "sleep(0.1)", "end", "rq_obj = 0"]
    assert [type(s).__name__ for s in stmts] == ["Native", "SetOut"] and stmts[0].text == "rq_open()"
    assert not any(r.name == "rq_open" for r in doc.routines)
    unclosed = text.replace("  end\n  rq_obj = 0\n", "  rq_obj = 0\n").replace("rq_open()\n  set", "rq_open()\n  end\n  set")
    doc, stmts = _read(tmp_path, unclosed, "unclosed.script")
    assert not any(d.code.id == "W530" for d in doc.diagnostics) and not doc.kept


def test_composed_poses_in_a_move(tmp_path: Path) -> None:
    """`movel(pose_trans(A, B))` with a rotating B (no `P * pose(..)` translation form) is the
    composed pose itself: its position and rotation equal scipy's A @ B; `pose_add(A, B)` with a
    rotating B likewise (positions added, R_B R_A)."""
    doc, stmts = _read(tmp_path, f"def prog():\n  global a_p = {_p(A)}\n  movel(pose_trans(a_p, {_p(B)}), a=1.2, v=0.25)\n"
                       f"  movel(pose_add({_p(A)}, {_p(B)}), a=1.2, v=0.25)\nend\n")
    moves = [s for s in stmts if isinstance(s, Move)]
    assert len(moves) == 2 and not any(isinstance(s, Native) for s in stmts)
    expected = _scipy(A) @ _scipy(B)
    pose = moves[0].pose
    assert pose is not None and np.allclose(_matrix(pose.position, pose.quaternion), expected, atol=1e-12)
    assert moves[0].target.startswith("pose(") and "x=" in moves[0].target
    rotation = Rotation.from_rotvec(B[3:]) * Rotation.from_rotvec(A[3:])
    pose = moves[1].pose
    assert pose is not None and np.allclose(pose.position, np.add(A[:3], B[:3]), atol=1e-12)
    assert np.allclose(_matrix(pose.position, pose.quaternion)[:3, :3], rotation.as_matrix(), atol=1e-12)


def test_a_functions_own_frame_variable(tmp_path: Path) -> None:
    """Two functions each assign their own `frame` (URScript scoping: a variable a function
    assigns is local to it): each move composes with its own function's frame (scipy), the
    assignments stay native (no single target), and a move to the bare name right after its
    assignment goes to the value just set (scipy)."""
    c = [0.1, 0.5, -0.2, 0.0, 0.0, 1.0]
    doc, stmts = _read(tmp_path, f"def prog():\n  def left():\n    frame = {_p(A)}\n    movel(pose_trans(frame, {_p(B)}), a=1, v=0.1)\n"
                       f"  end\n  def right():\n    frame = {_p(c)}\n    movel(pose_trans(frame, {_p(B)}), a=1, v=0.1)\n"
                       "    movel(frame, a=1, v=0.1)\n  end\n  left()\n  right()\nend\n")
    procs = {r.name: [s for s in walk(r.body) if isinstance(s, Move)] for r in doc.routines}
    for name, frame in (("left", A), ("right", c)):
        pose = procs[name][0].pose
        assert pose is not None
        assert np.allclose(_matrix(pose.position, pose.quaternion), _scipy(frame) @ _scipy(B), atol=1e-12), name
    assert not doc.targets and len(procs["right"]) == 2
    pose = procs["right"][1].pose
    assert pose is not None and np.allclose(_matrix(pose.position, pose.quaternion), _scipy(c), atol=1e-12)
    assert [s.text for s in stmts if isinstance(s, Native)] == [f"frame = {_p(A)}", f"frame = {_p(c)}"]


HELPER = "".join(f"  {line}\n" for line in (  # PolyScope's Direction helper, as PolyScope writes it
    "def calculate_point_to_move_towards(feature, direction, position_distance):",
    "  local posDir=[direction[0], direction[1], direction[2]]",
    "  if (norm(posDir) < 1e-6):",
    "    return get_target_waypoint()",
    "  end",
    "  local direction_vector_normalized=normalize(posDir)",
    "  local displacement_pose=p[direction_vector_normalized[0] * position_distance,"
    "direction_vector_normalized[1] * position_distance,direction_vector_normalized[2] * position_distance,0,0,0]",
    "  local wanted_displacement_in_base_frame=pose_sub(pose_trans(feature, displacement_pose), feature)",
    "  return pose_add(get_target_waypoint(), wanted_displacement_in_base_frame)",
    "end",
))


def _direction_node(feature: list[float], direction: str, distance: float) -> str:
    return f"""    global move_thread_flag_7=0
    thread move_thread_7():
      enter_critical
      move_thread_flag_7 = 1
      local towardsPos=calculate_point_to_move_towards({_p(feature)}, {direction}, {distance!r})
      movel(towardsPos, a=1.2, v=0.05)
      move_thread_flag_7 = 2
      exit_critical
    end
    move_thread_flag_7 = 0
    move_thread_han_7 = run move_thread_7()
    while (True):
      sleep(1.0E-10)
      if (move_thread_flag_7 > 1):
        join move_thread_han_7
        $ 9 "Until (distance)"
        break
      end
      sync()
    end
"""


def test_polyscope_direction_until_distance(tmp_path: Path) -> None:
    """PolyScope's Direction node ("Until (distance)") right after a move to a taught waypoint
    is a linear move to the waypoint shifted by the distance along the direction turned by the
    feature's rotation (scipy), orientation kept, at the node's speed; after a statement that
    may move the robot (a native line) it stays native."""
    feature = [0.1, 0.2, 0.0, 0.3, -0.2, 1.1]
    waypoint = [0.4, -0.1, 0.3, 0.0, 3.14159, 0.0]
    node = _direction_node(feature, "[1.0,2.0,-2.0]", 0.06)
    text = (f"def prog():\n{HELPER}  global Waypoint_1_p={_p(waypoint)}\n  while (True):\n"
            f"    movel(Waypoint_1_p, a=1.2, v=0.25)\n{node}    textmsg(\"x\")\n{node}  end\nend\n")
    doc, stmts = _read(tmp_path, text)
    line = text.split("\n").index("      movel(towardsPos, a=1.2, v=0.05)") + 1
    main = next(r for r in doc.routines if r.name == doc.main)
    moves = [s for s in main.body if isinstance(s, Move)]
    assert len(moves) == 2 and moves[1].target.startswith("shift(Waypoint_1_p, ")
    offset = Rotation.from_rotvec(feature[3:]).apply(np.array([1.0, 2.0, -2.0]) / 3.0 * 0.06)
    pose = moves[1].pose
    assert pose is not None and np.allclose(pose.position, np.add(waypoint[:3], offset), atol=1e-12)
    assert np.allclose(_matrix(pose.position, pose.quaternion)[:3, :3], _scipy(waypoint)[:3, :3], atol=1e-12)
    assert moves[1].speed == 50.0 and moves[1].where.line == line
    natives = [s.text for s in main.body if isinstance(s, Native)]
    assert 'textmsg("x")' in natives and "movel(towardsPos, a=1.2, v=0.05)" in natives


def test_counted_loop_with_a_variable_bound(tmp_path: Path) -> None:
    """`i = 0`, `while i < n:` with n set once to 3 is `for i in 0 .. 3`; a loop that breaks out
    or sets its counter in its body is no counted loop (it stays native, read once: one W510 per
    line, no duplicate)."""
    doc, stmts = _read(tmp_path, "def prog():\n  n = 3\n  i = 0\n  while i < n:\n    sleep(0.1)\n    i = i + 1\n  end\n"
                       "  k = 0\n  while k < 4:\n    if get_standard_digital_in(1):\n      break\n    end\n    k = k + 1\n  end\nend\n")
    loops = [s for s in stmts if type(s).__name__ == "For"]
    assert [(f.var, f.first, f.stop) for f in loops] == [("i", 0, 3)]  # type: ignore[attr-defined]
    lines = [d.span.start.line for d in doc.diagnostics if d.code.id == "W510"]
    assert lines == sorted(set(lines)) and 9 in lines and 11 in lines


def test_an_installation_node_assignment_counts(tmp_path: Path) -> None:
    """A variable a URCap installation node assigns too is assigned twice: no target."""
    doc, _ = _read(tmp_path, "def prog():\n  # begin: URCap Installation Node\n  #   Source: X, 1.0, Y\n"
                   "  home_p = get_actual_tcp_pose()\n  # end: URCap Installation Node\n"
                   "  global home_p = p[0.4, 0.1, 0.3, 0, 3.14159, 0]\n  movel(home_p, a=1.2, v=0.25)\nend\n")
    assert not doc.targets


def test_a_function_local_to_another_with_a_name_taken_is_renamed(tmp_path: Path) -> None:
    """URScript scoping: `def calc(x)` inside `def homing()` is homing's own; a `def calc(x)` of
    the program is another function. rmot's procs share one scope: both were `proc calc` and
    `rmot check` refused the import (E102, exit 2; Unitedplastic's PolyScope programs). The inner
    one is `homing_calc`, and so are the calls inside `homing`."""
    path = tmp_path / "prog.script"
    path.write_text("def prog():\n  def homing():\n    def calc(x):\n      set_standard_digital_out(1, True)\n    end\n"
                    "    calc(1)\n  end\n  def calc(x):\n    set_standard_digital_out(2, True)\n  end\n"
                    "  homing()\n  calc(2)\nend\n")
    out = tmp_path / "prog.rmot"
    result = CliRunner().invoke(cli, ["import", str(path), "-o", str(out)], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    text = out.read_text()
    assert "proc homing_calc(x: number) {\n    set out[1] = on" in text and "proc calc(x: number) {\n    set out[2] = on" in text
    assert "homing_calc(1)" in text and "\n  calc(2)" in text
    checked = CliRunner().invoke(cli, ["check", str(out)], catch_exceptions=False)
    assert checked.exit_code == 0, checked.output
