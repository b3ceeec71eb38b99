"""RAPID data a program changes (backends/readers/rapid_data.py): a tool, work object, speed,
zone or target that a statement assigns is not its declaration at a move. Before, the reader
took every declaration for the datum's value: a tool whose `tframe` the routine set, a work
object whose `uframe` it set, a speed it set and a target it moved were verified at the values
declared, without a word.

Witnesses: RAPID's data semantics (ABB RAPID Overview, "Data types"; RAPID Instructions,
Functions and Data types: tooldata, wobjdata, speeddata, zonedata) evaluated here by hand or by
a small interpreter of straight-line code written in this file; frame arithmetic by numpy
homogeneous matrices; and the programs RoboDK's own ABB and Fanuc post-processors wrote
(tests/data/vendor_programs/ROBODK.md).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from hypothesis import given, settings
from hypothesis import strategies as st

from rmot.backends.readers import read_files
from rmot.backends.readers.model import Move, Native, WaitIn, walk
from rmot.compiler.cli import cli

VENDOR = Path(__file__).resolve().parents[1] / "data" / "vendor_programs"
P = "[[300,0,400],[0,0,1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]]"
TOOL = "[TRUE,[[0,0,0],[1,0,0,0]],[2,[0,0,15],[1,0,0,0],0,0,0.005]]"
WOBJ = "[FALSE,TRUE,\"\",[[0,0,0],[1,0,0,0]],[[100,0,0],[1,0,0,0]]]"


def _read(tmp_path: Path, body: str, data: str = "", extra: str = "", name: str = "m.mod"):  # type: ignore[no-untyped-def]
    path = tmp_path / name
    path.write_text(f"MODULE M\n  PERS tooldata t := {TOOL};\n  PERS wobjdata w := {WOBJ};\n"
                    f"  VAR speeddata s := [100,500,5000,1000];\n  VAR robtarget p := {P};\n{data}"
                    f"  PROC main()\n{body}  ENDPROC\n{extra}ENDMODULE\n")
    return read_files([str(path)])


def _moves(doc) -> list[Move]:  # type: ignore[no-untyped-def]
    return [s for r in doc.routines for s in walk(r.body) if isinstance(s, Move)]


def _natives(doc) -> list[Native]:  # type: ignore[no-untyped-def]
    return [s for r in doc.routines for s in walk(r.body) if isinstance(s, Native)]


def _matrix(xyz: tuple[float, float, float], q: tuple[float, float, float, float]) -> np.ndarray:
    """A homogeneous transform from a RAPID pose (mm, w-first unit quaternion)."""
    w, x, y, z = q
    rot = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                    [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                    [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])
    out = np.eye(4)
    out[:3, :3], out[:3, 3] = rot, np.array(xyz) / 1000.0
    return out


def test_a_tool_the_routine_sets_is_read_with_the_value_it_sets(tmp_path: Path) -> None:
    doc = _read(tmp_path, "    t.tframe := [[0,0,100],[1,0,0,0]];\n    MoveL p0, v100, fine, t;\n",
                data=f"  CONST robtarget p0 := {P};\n")
    (tool,) = doc.tools
    assert tool.tcp.position == pytest.approx((0.0, 0.0, 0.1)) and tool.mass == 2.0  # tload: the declared 2 kg
    assert [m.tool for m in _moves(doc)] == [tool.name]


def test_a_whole_tool_assigned_and_a_second_value_is_a_second_tool(tmp_path: Path) -> None:
    doc = _read(tmp_path, "    t := [TRUE,[[0,0,50],[1,0,0,0]],[3,[0,0,10],[1,0,0,0],0,0,0]];\n    MoveL p0, v100, fine, t;\n"
                          "    t.tframe.trans.z := 80;\n    MoveL p0, v100, fine, t;\n",
                data=f"  CONST robtarget p0 := {P};\n")
    tools = {t.name: t for t in doc.tools}
    assert set(tools) == {"t", "t_2"}
    assert tools["t"].tcp.position[2] == pytest.approx(0.05) and tools["t_2"].tcp.position[2] == pytest.approx(0.08)
    assert tools["t_2"].mass == 3.0
    assert [m.tool for m in _moves(doc)] == ["t", "t_2"]


def test_a_work_object_the_routine_sets_is_uframe_times_the_declared_oframe(tmp_path: Path) -> None:
    c = math.sqrt(0.5)
    doc = _read(tmp_path, f"    w.uframe := [[500,0,0],[{c},0,0,{c}]];\n    MoveL p0, v100, fine, tool0\\WObj:=w;\n",
                data=f"  CONST robtarget p0 := {P};\n")
    (frame,) = doc.frames
    expected = _matrix((500, 0, 0), (c, 0, 0, c)) @ _matrix((100, 0, 0), (1, 0, 0, 0))
    assert frame.pose.position == pytest.approx(tuple(expected[:3, 3]), abs=1e-9)  # (0.5, 0.1, 0)
    assert [m.frame for m in _moves(doc)] == [frame.name]


def test_a_speed_set_by_the_routine_and_one_written_in_place(tmp_path: Path) -> None:
    doc = _read(tmp_path, "    s := [300,500,5000,1000];\n    MoveL p0, s, z10, tool0;\n"
                          "    MoveL p0, [42,500,5000,1000], [FALSE,7,10,10,1,10,1], tool0, \\WObj:=wobj0;\n",
                data=f"  CONST robtarget p0 := {P};\n")
    assert [(m.speed, m.zone) for m in _moves(doc)] == [(300.0, 10.0), (42.0, 7.0)]  # not the declared 100 mm/s


def test_a_target_the_routine_changes_stays_native_with_where_it_is_set(tmp_path: Path, ) -> None:
    path = tmp_path / "m.mod"
    path.write_text(f"MODULE M\n  VAR robtarget p := {P};\n  PROC main()\n    p := Offs(p, 0, 0, 10);\n"
                    "    MoveL p, v100, fine, tool0;\n  ENDPROC\nENDMODULE\n")
    result = CliRunner().invoke(cli, ["import", str(path), "-o", str(tmp_path / "out.rmot")], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    assert "`p` is assigned at line 4 (`p := Offs(p, 0, 0, 10)`): its value here is known only at run time" in result.output
    assert 'native rapid "MoveL p, v100, fine, tool0;"' in (tmp_path / "out.rmot").read_text()
    assert "target p =" not in (tmp_path / "out.rmot").read_text()  # its declaration is a comment (W511)


@pytest.mark.parametrize("body", [
    "    IF DInput(di1) = 1 THEN\n      s := [300,500,5000,1000];\n    ENDIF\n    MoveL p0, s, fine, tool0;\n",
    "    s := [300,500,5000,1000];\n    WHILE DInput(di1) = 1 DO\n      MoveL p0, s, fine, tool0;\n"
    "      s := [50,500,5000,1000];\n    ENDWHILE\n",
    "    s := [300,500,5000,1000];\n    other;\n    MoveL p0, s, fine, tool0;\n",
    "    s := [300,500,5000,1000];\n  again:\n    MoveL p0, s, fine, tool0;\n",
    "    s := v300;\n    MoveL p0, s, fine, tool0;\n",
], ids=["set-in-an-if", "set-later-in-the-loop", "after-a-call", "after-a-label", "set-to-a-name"])
def test_where_the_value_may_differ_the_move_stays_native(tmp_path: Path, body: str) -> None:
    doc = _read(tmp_path, body, data=f"  CONST robtarget p0 := {P};\n",
                extra="  PROC other()\n    IF DInput(di9) = 1 THEN\n      s := [999,500,5000,1000];\n    ENDIF\n  ENDPROC\n")
    assert not _moves(doc)
    assert any(n.text.startswith("MoveL p0, s") for n in _natives(doc))
    if "v300" in body:  # an assignment not followed stays in the program, where the native move reads it
        assert "s := v300;" in [n.text for n in _natives(doc)]


def test_set_inside_the_block_before_the_move_is_known(tmp_path: Path) -> None:
    doc = _read(tmp_path, "    WHILE DInput(di1) = 1 DO\n      s := [300,500,5000,1000];\n      MoveL p0, s, fine, tool0;\n"
                          "    ENDWHILE\n", data=f"  CONST robtarget p0 := {P};\n")
    assert [m.speed for m in _moves(doc)] == [300.0]


def test_data_another_module_of_the_task_sets_is_not_constant(tmp_path: Path) -> None:
    (tmp_path / "a.mod").write_text(f"MODULE A\n  PERS tooldata gun := {TOOL};\n  CONST robtarget p0 := {P};\n"
                                    "  PROC main()\n    MoveL p0, v100, fine, gun;\n  ENDPROC\nENDMODULE\n")
    (tmp_path / "b.mod").write_text("MODULE B\n  PROC setgun()\n    gun.tframe.trans.z := 120;\n  ENDPROC\nENDMODULE\n")
    doc = read_files([str(tmp_path / "a.mod"), str(tmp_path / "b.mod")])
    assert not _moves(doc) and not doc.tools


def test_after_a_call_the_value_the_routine_leaves(tmp_path: Path) -> None:
    """A routine whose last statements set the speed leaves it known (RoboDK's `Pick;` sets
    `rdkSpeed` for the moves after the call); one that does not touch it leaves it as it was."""
    doc = _read(tmp_path, "    s := [300,500,5000,1000];\n    keep;\n    MoveL p0, s, fine, tool0;\n    slow;\n"
                          "    MoveL p0, s, fine, tool0;\n", data=f"  CONST robtarget p0 := {P};\n",
                extra="  PROC keep()\n    SetDO do1, 1;\n  ENDPROC\n  PROC slow()\n    s := [300,500,5000,1000];\n"
                      "    IF DInput(di1) = 1 THEN\n      SetDO do1, 0;\n    ENDIF\n    s := [25,500,5000,1000];\n  ENDPROC\n")
    main = next(r for r in doc.routines if r.name == "main")
    assert [s.speed for s in walk(main.body) if isinstance(s, Move)] == [300.0, 25.0]


# Straight-line code, blocks and calls, random: the speed each move reads, by an interpreter of
# the statements written here (a value set in an IF is not certain; a call of `other`, which sets
# 5 mm/s last, leaves 5; of `maybe`, which sets it in an IF, leaves it uncertain; of `keep`, which
# does not set it, leaves it as it was; else the last one set), against the import.
_STEP = st.one_of(st.tuples(st.just("set"), st.integers(1, 9)), st.tuples(st.just("if"), st.integers(1, 9)),
                  st.just(("other", 0)), st.just(("maybe", 0)), st.just(("keep", 0)), st.just(("move", 0)))


@settings(max_examples=40, deadline=None)
@given(st.lists(_STEP, min_size=1, max_size=12))
def test_the_speed_each_move_reads_is_the_last_one_set_where_certain(tmp_path_factory: pytest.TempPathFactory,
                                                                    steps: list[tuple[str, int]]) -> None:
    lines, expected, known = [], [], None
    for kind, v in steps:
        if kind == "set":
            lines.append(f"    s := [{v * 10},500,5000,1000];\n")
            known = v * 10
        elif kind == "if":
            lines.append(f"    IF DInput(di1) = 1 THEN\n      s := [{v * 10},500,5000,1000];\n    ENDIF\n")
            known = None
        elif kind in ("other", "maybe", "keep"):
            lines.append(f"    {kind};\n")
            known = 5 if kind == "other" else None if kind == "maybe" else known
        else:
            lines.append("    MoveL p0, s, fine, tool0;\n")
            expected.append(known)
    doc = _read(tmp_path_factory.mktemp("flow"), "".join(lines), data=f"  CONST robtarget p0 := {P};\n",
                extra="  PROC other()\n    s := [5,500,5000,1000];\n  ENDPROC\n  PROC maybe()\n    IF DInput(di1) = 1 "
                      "THEN\n      s := [7,500,5000,1000];\n    ENDIF\n  ENDPROC\n  PROC keep()\n    WaitTime 1;\n  ENDPROC\n")
    main = next(r for r in doc.routines if r.name == "main")
    read = [s.speed if isinstance(s, Move) else None for s in walk(main.body)
            if isinstance(s, Move) or (isinstance(s, Native) and s.text.startswith("MoveL"))]
    assert read == [float(e) if e is not None else None for e in expected]


@pytest.mark.parametrize("name", ["robodk_irc5.mod", "robodk_irc5_simplified.mod", "robodk_s4c.prg"])
def test_robodk_rapid_moves_are_read(name: str) -> None:
    """RoboDK's IRC5 post sets `rdkTool.tframe`, `rdkWObj.uframe` and `rdkSpeed` before its moves
    and writes `tool, \\WObj:=wobj` after a comma; its S4C post writes speeds in place: every move
    is read, with the tool, frame and speeds the program sets (the post's program: 200 mm/s, then
    50 mm/s; tool (62.5, -108.253, 100) mm; frame (807.767, -963.7, 41.479) mm where it sets one)."""
    doc = read_files([str(VENDOR / "rapid" / name)])
    moves = _moves(doc)
    assert [m.kind for m in moves] == ["joint", "linear", "linear", "circular", "linear", "joint"]
    assert [m.speed for m in moves if m.kind != "joint"] == [200.0, 200.0, 200.0, 50.0]
    assert moves[0].joints == pytest.approx((-46.18419, -6.77518, -20.54925, 71.38674, 49.58727, -302.54752))
    (tool,) = doc.tools
    assert tool.tcp.position == pytest.approx((0.0625, -0.108253, 0.1))
    if name == "robodk_irc5.mod":
        (frame,) = doc.frames
        assert frame.pose.position == pytest.approx((0.807767, -0.9637, 0.041479))


def test_robodk_fanuc_circular_move_with_its_second_point_on_a_line_without_colon() -> None:
    """RoboDK's R-30iA post writes `16:C P[4]` and, on the next line, `P[5] 200mm/sec FINE ;`
    without the `:` the pendant writes: one circular move (was refused whole, E510)."""
    doc = read_files([str(VENDOR / "fanuc" / "robodk_r30ia.ls")])
    moves = _moves(doc)
    arc = next(m for m in moves if m.kind == "circular")
    assert (arc.via, arc.target, arc.speed) == ("program_p4", "program_p5", 200.0)
    assert [m.kind for m in moves] == ["joint", "linear", "linear", "circular", "linear", "joint"]


def test_a_line_without_colon_elsewhere_is_still_refused(tmp_path: Path) -> None:
    path = tmp_path / "bad.ls"
    path.write_text("/PROG  BAD\n/ATTR\n/MN\n   1:L P[1] 100mm/sec FINE ;\n   P[2] 100mm/sec FINE ;\n/POS\n/END\n")
    result = CliRunner().invoke(cli, ["import", str(path), "-o", str(tmp_path / "o.rmot")], catch_exceptions=False)
    assert result.exit_code == 2 and "error[E510]: a /MN line must be `N:  instruction ;`" in result.output


def test_a_tool_and_frame_the_program_only_selects_are_marked_in_the_stub(tmp_path: Path) -> None:
    """RoboDK's TP program selects `UTOOL_NUM=1` / `UFRAME_NUM=1` and sets neither (its `! UT1:..`
    comments are no data): the stub puts them at identity and says so, W511 at the first move."""
    out = tmp_path / "p.rmot"
    result = CliRunner().invoke(cli, ["import", str(VENDOR / "fanuc" / "robodk_r30ia.ls"), "-o", str(out)],
                                catch_exceptions=False)
    assert result.exit_code == 0, result.output
    assert "robodk_r30ia.ls:30:4: warning[W511]: tool `utool1` is the controller's UTOOL[1], not set in the files " \
           "given: the cell stub puts it at the flange (give --cell with its data)" in result.output
    stub = (tmp_path / "p_cell.rmot").read_text()
    assert "tool utool1 = none tcp pose(x=0mm, y=0mm, z=0mm, q=(1, 0, 0, 0)) mass 0 kg number 1 on r1  # the controller's UTOOL[1]" \
        in stub
    assert "frame uframe1 = pose(x=0mm, y=0mm, z=0mm, q=(1, 0, 0, 0)) number 1  # the controller's UFRAME[1]" in stub


def test_robodk_main_calling_its_subprograms() -> None:
    """RoboDK's IRC5 post with a main program that sets the tool, work object and speed, then
    calls `Pick` (which sets `rdkSpeed` to 100 mm/s) and `Place`: main's moves after `Pick;` run
    at the 100 mm/s Pick leaves; the subprograms start with the values main holds at their one
    call each (Place's speed: the 100 mm/s Pick left); `WaitDI D_IN_3, 1, \\MaxTime:=2.0` (the
    optional argument after a comma) is a wait with a time-out."""
    doc = read_files([str(VENDOR / "rapid" / "robodk_irc5_calls.mod")])
    speeds = {r.name: [(m.kind, m.speed, m.tool, m.frame) for m in walk(r.body) if isinstance(m, Move)]
              for r in doc.routines}
    assert speeds == {"Main": [("joint", None, "rdkTool", "rdkWObj"), ("linear", 100.0, "rdkTool", "rdkWObj"),
                               ("joint", None, "rdkTool", "rdkWObj")],
                      "Pick": [("linear", 100.0, "rdkTool", "rdkWObj")] * 2,
                      "Place": [("linear", 100.0, "rdkTool", "rdkWObj")]}
    main = next(r for r in doc.routines if r.name == "Main")
    assert [s.timeout for s in walk(main.body) if isinstance(s, WaitIn)] == [2.0]
    (tool,) = doc.tools
    assert tool.tcp.position == pytest.approx((0.0, 0.0, 0.15))


_SUB = "  PROC sub()\n    MoveL p0, s, fine, tool0;\n  ENDPROC\n"


@pytest.mark.parametrize(("before", "body", "after"), [
    ("", "    s := [300,500,5000,1000];\n    sub;\n    s := [50,500,5000,1000];\n    sub;\n", _SUB),
    (_SUB, "    s := [300,500,5000,1000];\n    sub;\n", ""),
    ("", "    s := [300,500,5000,1000];\n    sub;\n    TPWrite \"sub\";\n", _SUB),
    ("", "    s := [300,500,5000,1000];\n    sub;\n    s := [50,500,5000,1000];\n    %\"s\" + \"ub\"%;\n", _SUB),
], ids=["two-calls-two-values", "routine-before-its-caller", "a-mention-not-read-as-a-call", "late-binding-call"])
def test_a_routine_starts_unknown_unless_every_call_gives_one_value(tmp_path: Path, before: str, body: str,
                                                                    after: str) -> None:
    path = tmp_path / "m.mod"
    path.write_text(f"MODULE M\n  VAR speeddata s := [100,500,5000,1000];\n  CONST robtarget p0 := {P};\n{before}"
                    f"  PROC main()\n{body}  ENDPROC\n{after}ENDMODULE\n")
    doc = read_files([str(path)])
    sub = next(r for r in doc.routines if r.name == "sub")
    assert not [m for m in walk(sub.body) if isinstance(m, Move)]


def test_a_routine_another_module_calls_starts_unknown(tmp_path: Path) -> None:
    (tmp_path / "a.mod").write_text(f"MODULE A\n  VAR speeddata s := [100,500,5000,1000];\n  CONST robtarget p0 := {P};\n"
                                    f"  PROC main()\n    s := [300,500,5000,1000];\n    sub;\n  ENDPROC\n{_SUB}ENDMODULE\n")
    (tmp_path / "b.mod").write_text("MODULE B\n  PROC other()\n    sub;\n  ENDPROC\nENDMODULE\n")
    alone = read_files([str(tmp_path / "a.mod")])
    assert [m.speed for r in alone.routines if r.name == "sub" for m in walk(r.body) if isinstance(m, Move)] == [300.0]
    task = read_files([str(tmp_path / "a.mod"), str(tmp_path / "b.mod")])
    assert not [m for r in task.routines if r.name == "sub" for m in walk(r.body) if isinstance(m, Move)]
