"""UTOOL_NUM and UFRAME_NUM select the controller's tool and user frame: a program's selection
holds after it returns to its caller (B-83284EN, UTOOL_NUM / UFRAME_NUM). `rmot import` reads a
caller's move after `CALL SUB`, where SUB (or a program it calls) of the job's files selects one,
as known only at run time: it stays native, its reason naming the call, until the caller selects
again. Witness: the expected reading is worked out by hand from that rule for each program.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from rmot.backends.readers import read_files
from rmot.backends.readers.model import Move, Native, walk

MAIN = """/PROG  MAIN
/ATTR
DEFAULT_GROUP	= 1,*,*,*,*;
/MN
   1:  !UTOOL[1] = gripper ;
   2:  !UTOOL[2] = probe ;
   3:  UFRAME_NUM=0 ;
   4:  UTOOL_NUM=1 ;
   5:J P[1] 50% FINE ;
   6:  CALL SUB ;
   7:J P[2] 50% FINE ;
/POS
P[1]{
   GP1:
	UF : 0, UT : 1,		CONFIG : 'N U T, 0, 0, 0',
	X =   500.000  mm,	Y =     0.000  mm,	Z =   600.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[2]{
   GP1:
	UF : 0, UT : 1,		CONFIG : 'N U T, 0, 0, 0',
	X =   500.000  mm,	Y =   100.000  mm,	Z =   600.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
/END
"""
SUB = """/PROG  SUB
/ATTR
DEFAULT_GROUP	= 1,*,*,*,*;
/MN
   1:  UTOOL_NUM=2 ;
   2:J P[1] 50% FINE ;
/POS
P[1]{
   GP1:
	UF : 0, UT : 2,		CONFIG : 'N U T, 0, 0, 0',
	X =   500.000  mm,	Y =    50.000  mm,	Z =   600.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
/END
"""


def _main_body(tmp_path: Path, main: str, sub: str) -> list[object]:
    (tmp_path / "MAIN.ls").write_text(main)
    (tmp_path / "SUB.ls").write_text(sub)
    doc = read_files([str(tmp_path / "MAIN.ls"), str(tmp_path / "SUB.ls")])
    return list(next(r for r in doc.routines if r.name == "MAIN").body)


def test_a_move_after_a_call_that_selects_a_tool_is_the_run_times(tmp_path: Path) -> None:
    body = _main_body(tmp_path, MAIN, SUB)
    last = body[-1]
    assert isinstance(last, Native) and last.text.startswith("J P[2]"), body
    doc = read_files([str(tmp_path / "MAIN.ls"), str(tmp_path / "SUB.ls")])
    assert any("depends on `CALL SUB`" in d.message and d.span is not None and d.span.start.line == 11
               for d in doc.diagnostics)


@pytest.mark.parametrize("main, sub, tool", [
    (MAIN.replace("   7:J P[2] 50% FINE ;", "   7:  UTOOL_NUM=1 ;\n   8:J P[2] 50% FINE ;"), SUB, "gripper"),
    (MAIN, SUB.replace("   1:  UTOOL_NUM=2 ;\n", ""), "gripper"),
])
def test_a_move_after_a_call_is_read_where_the_selection_is_known(tmp_path: Path, main: str, sub: str,
                                                                  tool: str) -> None:
    """The caller selects again after the call, or the called program selects nothing."""
    last = _main_body(tmp_path, main, sub)[-1]
    assert isinstance(last, Move) and last.tool == tool and last.target_name == "main_p2"


def test_a_call_in_an_if_action_leaves_the_selection_to_the_run_time(tmp_path: Path) -> None:
    main = MAIN.replace("   6:  CALL SUB ;", "   6:  IF (DI[1]),CALL SUB ;")
    last = _main_body(tmp_path, main, SUB)[-1]
    assert isinstance(last, Native) and last.text.startswith("J P[2]")


def test_a_program_inlined_at_the_call_starts_with_the_callers_selection(tmp_path: Path) -> None:
    """A program that moves by a loop's offset is read inlined at its call. The caller selects
    UFRAME 2 and UTOOL 1 right before `CALL PALLETIZING_DOWN_TO_2_L1`, whose first move selects
    nothing of its own: it runs with that selection, so it is read. The selection the called
    program makes holds only from the line after the call."""
    from click.testing import CliRunner  # late: only this test compiles

    from rmot.compiler.cli import cli

    root = Path(__file__).resolve().parents[2]
    result = CliRunner().invoke(cli, ["compile", str(root / "examples" / "palletizing.rmot"), "--target", "fanuc",
                                      "-o", str(tmp_path)], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    folder = tmp_path / "fanuc"
    callee = folder / "PALLETIZING_DOWN_TO_2_L1.ls"
    text = callee.read_text()
    assert "   8:  UFRAME_NUM=2 ;\n   9:  UTOOL_NUM=1 ;\n" in text
    callee.write_text(text.replace("   8:  UFRAME_NUM=2 ;\n   9:  UTOOL_NUM=1 ;\n", "", 1))
    main = folder / "PALLETIZING.ls"
    call = "  74:  CALL PALLETIZING_DOWN_TO_2_L1 ;"
    assert call in main.read_text()
    main.write_text(main.read_text().replace(call, "  74:  UFRAME_NUM=2 ;\n  74:  UTOOL_NUM=1 ;\n" + call, 1))
    files = [main] + sorted(p for p in folder.glob("*.ls") if p != main)
    doc = read_files([str(p) for p in files])
    moves = [s for r in doc.routines for s in walk(r.body) if isinstance(s, Move)]
    assert any(m.target.startswith("shift(palletizing_down_to_2_l1_p1") for m in moves), moves
