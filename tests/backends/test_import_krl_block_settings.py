"""KRL motion settings a block changes, or a line sets to a value the import does not read.

`$VEL.CP`, `$APO.CDIS`, `BAS(#TOOL, n)`, `$TOOL = ..` are modal: every later motion reads them.
Set inside an `IF` arm, the value after the `IF` is the arm's only where the arm ran; set by a
line the import keeps native (`$TOOL = tool_var`), the later motions run with that value. The
reader took the last value in the text for every later motion: `IF $IN[3] THEN $VEL.CP = 0.05
ENDIF` made every motion after it 50 mm/s whatever the input, without a word. Witness: the
semantics above (KSS 8.x System Integrators: the motion system variables keep their value
until the next assignment), applied here by hand; `$TOOL = TOOL_DATA[n]` is what `BAS(#TOOL, n)`
does (KSS BAS.SRC).
"""

from __future__ import annotations

from pathlib import Path

from rmot.backends.readers import read_files
from rmot.backends.readers.model import Move, Native, walk

LIN = "  LIN {X 500, Y 0, Z 600, A 0, B 90, C 0}\n"


def _read(tmp_path: Path, body: str) -> tuple[list[object], list[str]]:
    path = tmp_path / "t.src"
    path.write_text("DEF t()\n" + body + "END\n")
    doc = read_files([str(path)])
    return [s for r in doc.routines for s in walk(r.body) if isinstance(s, Move) or
            (isinstance(s, Native) and s.text.startswith("LIN"))], \
        [d.message for d in doc.diagnostics]


def test_a_speed_set_in_an_if_arm_leaves_the_motions_after_it_native(tmp_path: Path) -> None:
    moves, messages = _read(tmp_path, f"  $VEL.CP = 0.2\n{LIN}  IF $IN[3] == TRUE THEN\n    $VEL.CP = 0.05\n{LIN}"
                                      f"  ENDIF\n{LIN}  $VEL.CP = 0.1\n{LIN}")
    assert [type(m).__name__ for m in moves] == ["Move", "Move", "Native", "Move"]
    assert [m.speed for m in moves if isinstance(m, Move)] == [200, 50, 100]  # the arm's own motion reads its value
    assert any("its $VEL.CP is set in the block at line 4, which may not run" in m for m in messages)


def test_a_tool_chosen_in_a_branch_or_by_a_value_not_read(tmp_path: Path) -> None:
    moves, messages = _read(tmp_path, f"  $TOOL = TOOL_DATA[1]\n{LIN}  IF $IN[2] == TRUE THEN\n    BAS(#TOOL, 3)\n"
                                      f"  ENDIF\n{LIN}  $TOOL = TOOL_DATA[2]\n{LIN}  $TOOL = my_tool\n{LIN}")
    assert [type(m).__name__ for m in moves] == ["Move", "Native", "Move", "Native"]
    assert [m.tool for m in moves if isinstance(m, Move)] == ["tool1", "tool2"]
    assert any("its $TOOL is set at line 10 to a value the import does not read" in m for m in messages)


def test_a_setting_a_block_sets_back_to_the_same_value_changes_nothing(tmp_path: Path) -> None:
    moves, _ = _read(tmp_path, f"  $VEL.CP = 0.2\n  IF $IN[1] == TRUE THEN\n    $VEL.CP = 0.2\n  ENDIF\n{LIN}")
    assert isinstance(moves[0], Move) and moves[0].speed == 200


def test_a_line_after_the_block_that_sets_the_setting_again_makes_it_known(tmp_path: Path) -> None:
    """Set again after the block, even to the value the arm gave it, the setting is known."""
    moves, _ = _read(tmp_path, f"  $VEL.CP = 0.2\n  IF $IN[1] == TRUE THEN\n    $VEL.CP = 0.05\n  ENDIF\n  $VEL.CP = 0.05\n{LIN}")
    assert isinstance(moves[0], Move) and moves[0].speed == 50
