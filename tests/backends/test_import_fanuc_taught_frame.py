"""`rmot import` of a Fanuc TP program that moves before it selects UTOOL_NUM or UFRAME_NUM
(readers/fanuc.py, fanuc_text.caller_selection; lang/REFERENCE.md §14).

Such a program runs in the tool and user frame its caller selected. Each position records the
numbers selected when it was taught (`UF : 1, UT : 2` in /POS: B-83284EN, position data), so the
move is read in those, W545 once per program; one caller's selection holds until the program
selects, so a later move whose position records other numbers stays native, as does a move to a
position register (it records none in the program). Witnesses: the numbers written in each test's
/POS block, and SYSFRAME.VA's saved frame checked against a numpy matrix built here.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
from test_import_fanuc_saved import POSREG, SYSFRAME, _import, _pose_of, _rotation


def _program(folder: Path, body: list[str], taught: dict[int, tuple[int, int]], saved: dict[str, str] | None = None
             ) -> list[str]:
    """PICK.ls with `body` and a position P[n] taught in (UF, UT) for each entry of `taught`."""
    lines = "".join(f"{n:4d}:  {text} ;\n" for n, text in enumerate(body, 1))
    pos = "".join(f"P[{n}]{{\n   GP1:\n\tUF : {uf}, UT : {ut},\t\tCONFIG : 'N U T, 0, 0, 0',\n"
                  f"\tX =   {400 + 50 * n}.000  mm,\tY =     0.000  mm,\tZ =   300.000  mm,\n"
                  "\tW =   180.000 deg,\tP =     0.000 deg,\tR =     0.000 deg\n};\n" for n, (uf, ut) in taught.items())
    (folder / "pick.ls").write_text(f"/PROG  PICK\n/ATTR\n/MN\n{lines}/POS\n{pos}/END\n")
    paths = [str(folder / "pick.ls")]
    for name, text in (saved or {}).items():
        (folder / name).write_text(text)
        paths.append(str(folder / name))
    return paths


def test_moves_before_a_selection_are_read_in_the_numbers_their_positions_record(tmp_path: Path) -> None:
    """No UTOOL_NUM/UFRAME_NUM in the program, its positions taught in UF 1, UT 2: the moves run in
    the caller's user frame 1 and tool 2 (the frame SYSFRAME.VA saved), never the robot base and
    flange; W545 says so once, at the first move."""
    paths = _program(tmp_path, ["J P[1] 100% FINE", "L P[2] 100mm/sec FINE", "L P[1] 100mm/sec FINE"],
                     {1: (1, 2), 2: (1, 2)}, {"SYSFRAME.VA": SYSFRAME})
    program, cell, output = _import(tmp_path, paths)
    assert "native fanuc" not in program, program
    assert "  tool utool2\n  frame uframe1\n  move joint pick_p1" in program, program
    assert "frame base" not in program and "utool0" not in program, program
    warned = re.findall(r"pick\.ls:(\d+):\d+: warning\[W545\]: the program selects no UTOOL_NUM or UFRAME_NUM before "
                        r"this move: read in the numbers its position was taught in \(UT 2, UF 1\)", output)
    assert warned == ["4"], output
    position, rotation = _pose_of(next(ln for ln in cell.splitlines() if ln.strip().startswith("frame uframe1")))
    assert np.allclose(position, [1000, 200, 0]) and np.allclose(rotation, _rotation(0, 0, 90), atol=1e-9)


def test_a_later_move_taught_in_another_frame_stays_native(tmp_path: Path) -> None:
    """The first move fixes the caller's frame (UF 1); a later one whose position was taught in
    UF 2 with no UFRAME_NUM between cannot run in both: native, the reason naming both numbers.
    Once the program selects (UFRAME_NUM=2), its own number holds."""
    paths = _program(tmp_path, ["J P[1] 100% FINE", "L P[2] 100mm/sec FINE", "UFRAME_NUM=2", "L P[2] 100mm/sec FINE"],
                     {1: (1, 0), 2: (2, 0)})
    program, _, output = _import(tmp_path, paths)
    assert 'native fanuc "L P[2] 100mm/sec FINE ;"' in program, program
    assert re.search(r"pick\.ls:5:\d+: warning\[W510\]: its position was taught in UF 2, but a move before it in this "
                     r"program was taught in UF 1 with no UFRAME_NUM between", output), output
    assert program.count("move linear pick_p2") == 1 and "  frame uframe2\n  move linear pick_p2" in program, program
    assert output.count("warning[W545]") == 1, output


def test_a_position_register_before_a_selection_stays_native(tmp_path: Path) -> None:
    """A move to PR[30] (its saved value records no frame number in the program) before any
    UFRAME_NUM: which frame the caller selected is not known, so the move stays native."""
    paths = _program(tmp_path, ["L PR[30:home] 250mm/sec FINE"], {}, {"POSREG.VA": POSREG})
    program, _, output = _import(tmp_path, paths)
    assert 'native fanuc "L PR[30:home] 250mm/sec FINE ;"' in program, program
    assert "records no single UF number: the frame is the caller's, known only at run time" in output, output


def test_a_program_that_selects_first_needs_no_recorded_numbers(tmp_path: Path) -> None:
    """UFRAME_NUM and UTOOL_NUM before the first move: the program's own numbers, no W545, whatever
    the positions record (rmot's own TP output selects both before its first move)."""
    paths = _program(tmp_path, ["UFRAME_NUM=0", "UTOOL_NUM=1", "J P[1] 100% FINE"], {1: (3, 4)})
    program, _, output = _import(tmp_path, paths)
    assert "W545" not in output and "  tool utool1\n  frame base\n  move joint pick_p1" in program, (program, output)
