"""RAPID `VelSet Override, Max` read into the speeds of the moves after it, and a program
displacement (`PDispSet`, `PDispOn`) keeping the moves it moves native (rapid_data.DataFlow).

`VelSet 100, 200;` at the top of `main` is how many real programs cap their speed (found in
public modules: `VelSet 100, 200; AccSet 50, 50;` before the moves, `VelSet 100, 750;`,
`VelSet 100, 800;`). The reader kept the line native and read every later `MoveL .., v1000, ..`
at 1000 mm/s: the plan and its cycle time were the programmed speed's, not the controller's,
and the only word was "no rmot form" at the VelSet line.

Witness: RAPID Instructions, Functions and Data types (3HAC050917-001), VelSet: "Override:
desired velocity as a percentage of programmed velocity", "Max: maximum TCP velocity in mm/s";
the values are reset to 100, 5000 when the program starts from the beginning. The effective
TCP speed min(v · Override / 100, Max) is computed here from the numbers of each case.
PDispOn / PDispSet / PDispAdd (same reference): "all subsequent robtargets are displaced" by the
displacement frame until PDispOff; a jointtarget is not.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from rmot.backends.readers import read_files
from rmot.backends.readers.model import Move, Native, walk

P = "[[500,0,400],[0,0,1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]]"


def _read(tmp_path: Path, main: str, procs: str = "") -> tuple[list[object], list[str]]:
    path = tmp_path / "m.mod"
    path.write_text(f"MODULE M\n  CONST robtarget p1 := {P};\n  VAR num ov := 40;\n  PROC main()\n{main}  ENDPROC\n"
                    f"{procs}ENDMODULE\n")
    doc = read_files([str(path)])
    moves = [s for r in doc.routines for s in walk(r.body) if isinstance(s, (Move, Native))]
    return moves, [d.message for d in doc.diagnostics]


def _speed(v: float, override: float, most: float) -> float:
    return min(v * override / 100.0, most)


@pytest.mark.parametrize(("velset", "v", "override", "most"), [
    ("VelSet 50, 800;", 1000, 50, 800), ("VelSet 100, 200;", 1000, 100, 200), ("VelSet 100, 200;", 150, 100, 200),
    ("VelSet 25, 5000;", 400, 25, 5000), ("VelSet 120, 5000;", 100, 120, 5000),
])
def test_a_velset_scales_and_caps_the_linear_moves_after_it(tmp_path: Path, velset: str, v: float, override: float,
                                                             most: float) -> None:
    moves, _ = _read(tmp_path, f"    MoveL p1, v{v:g}, fine, tool0;\n    {velset}\n    MoveL p1, v{v:g}, z10, tool0;\n"
                               f"    MoveC p1, p1, v{v:g}, fine, tool0;\n")
    assert all(isinstance(m, Move) for m in moves)
    assert [m.speed for m in moves] == [v, _speed(v, override, most), _speed(v, override, most)]  # type: ignore[union-attr]


def test_a_joint_move_takes_the_override_as_its_share(tmp_path: Path) -> None:
    moves, messages = _read(tmp_path, "    VelSet 50, 300;\n    MoveJ p1, v1000, fine, tool0;\n")
    assert isinstance(moves[0], Move) and moves[0].joint_pct == 50
    assert any("read as 50 % (the VelSet override)" in m for m in messages)


def test_a_routine_takes_the_velset_of_every_call(tmp_path: Path) -> None:
    """main sets the speed cap once and calls its routines (the common form): their moves run
    under it; a routine called under two different VelSets stays native with the reason."""
    procs = "  PROC pick()\n    MoveL p1, v1000, fine, tool0;\n  ENDPROC\n  PROC place()\n    MoveL p1, v1000, fine, tool0;\n  ENDPROC\n"
    moves, _ = _read(tmp_path, "    VelSet 100, 250;\n    pick;\n    place;\n    VelSet 100, 500;\n    place;\n", procs)
    by_line = {m.where.line: m for m in moves}
    assert isinstance(by_line[12], Move) and by_line[12].speed == 250  # pick, called once under 100, 250
    assert isinstance(by_line[15], Native)  # place: 250 at one call, 500 at the other


def test_a_velset_the_import_cannot_follow_keeps_the_moves_native(tmp_path: Path) -> None:
    for main, line in [("    VelSet ov, 800;\n    MoveL p1, v1000, fine, tool0;\n", 6),
                       ("    IF ov > 3 THEN\n      VelSet 50, 800;\n    ENDIF\n    MoveL p1, v1000, fine, tool0;\n", 8),
                       ("    VelSet 50, 800;\n    MoveL p1, v1000\\T:=2, fine, tool0;\n", 6)]:
        moves, messages = _read(tmp_path, main)
        assert isinstance(moves[-1], Native) and moves[-1].where.line == line, (main, moves)
    _, messages = _read(tmp_path, "    IF ov > 3 THEN\n      VelSet 50, 800;\n    ENDIF\n    MoveL p1, v1000, fine, tool0;\n")
    assert any("its speed follows `VelSet` (line 6: `VelSet 50, 800`)" in m for m in messages), messages


def test_without_velset_the_speeds_are_the_programmed_ones(tmp_path: Path) -> None:
    moves, _ = _read(tmp_path, "    MoveL p1, v1000, fine, tool0;\n    MoveL p1, vmax, fine, tool0;\n")
    assert [m.speed for m in moves] == [1000, 5000]  # type: ignore[union-attr]


def test_moves_under_a_program_displacement_stay_native(tmp_path: Path) -> None:
    """Between `PDispSet` and `PDispOff` the controller moves every robtarget by a frame: those
    moves were read at their robtargets without a word. Now they stay native with the reason; a
    MoveAbsJ (a jointtarget, not displaced) and the moves after PDispOff are read."""
    main = ("    MoveL p1, v100, fine, tool0;\n    PDispSet [[0,0,50],[1,0,0,0]];\n    MoveL p1, v100, fine, tool0;\n"
            "    MoveAbsJ [[0,0,0,0,90,0],[9E9,9E9,9E9,9E9,9E9,9E9]], v100, fine, tool0;\n    PDispOff;\n"
            "    MoveL p1, v100, fine, tool0;\n")
    moves, messages = _read(tmp_path, main)
    assert [type(m).__name__ for m in moves] == ["Move", "Native", "Native", "Move", "Native", "Move"]
    assert [m.text for m in moves if isinstance(m, Native)] == [
        "PDispSet [[0,0,50],[1,0,0,0]];", "MoveL p1, v100, fine, tool0;", "PDispOff;"]
    assert any("a program displacement may be on here (`PDispSet [[0,0,50],[1,0,0,0]]` at line 6)" in m for m in messages)


def test_a_displacement_a_routine_switches_on_reaches_the_moves_after_its_call(tmp_path: Path) -> None:
    procs = "  PROC shiftit()\n    PDispOn \\ExeP:=p1, p1, tool0;\n  ENDPROC\n"
    moves, _ = _read(tmp_path, "    MoveL p1, v100, fine, tool0;\n    shiftit;\n    MoveL p1, v100, fine, tool0;\n", procs)
    assert [type(m).__name__ for m in moves if m.where.line in (5, 7)] == ["Move", "Native"]
