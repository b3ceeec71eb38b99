r"""A RAPID move's optional arguments: `\V:=` and `\Z:=` read as the TCP speed and zone they put
in place of the datum's, the others kept native with their name (rapid_data.DataFlow).

Witness: RAPID Instructions, Functions and Data types (3HAC050917-001), MoveL: "[\V] Velocity:
This argument is used to specify the velocity of the TCP in mm/s directly in the instruction. It
is then substituted for the corresponding velocity specified in the speed data"; "[\Z] Zone:
This argument is used to specify the position accuracy of the robot TCP directly in the
instruction. The length of the corner path is given in mm, which is substituted for the
corresponding zone specified in the zone data"; "[\Conc] Concurrent: Subsequent instructions are
executed while the robot is moving". VelSet scales and caps every programmed speed (VelSet,
same reference): min(v · Override / 100, Max) computed here.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from test_import_rapid_velset import _read

from rmot.backends.readers.model import Move, Native


@pytest.mark.parametrize(("move", "speed", "zone"), [
    (r"MoveL p1, v1000\V:=50, z10\Z:=3, tool0;", 50.0, 3.0),
    (r"MoveL p1, v1000\V:=75.5, z10, tool0;", 75.5, 10.0),
    (r"MoveL p1, v200, z50\Z:=12, tool0;", 200.0, 12.0),
    (r"MoveC p1, p1, v1000\V:=40, z20\Z:=1, tool0;", 40.0, 1.0),
])
def test_speed_and_zone_given_in_the_instruction_replace_the_data(tmp_path: Path, move: str, speed: float,
                                                                   zone: float) -> None:
    moves, _ = _read(tmp_path, f"    {move}\n")
    assert isinstance(moves[0], Move) and (moves[0].speed, moves[0].zone) == (speed, zone), moves


def test_a_velset_scales_a_speed_given_in_the_instruction(tmp_path: Path) -> None:
    moves, _ = _read(tmp_path, "    VelSet 50, 30;\n    MoveL p1, v1000\\V:=100, z10, tool0;\n    MoveL p1, v1000\\V:=40, z10, tool0;\n")
    assert [m.speed for m in moves if isinstance(m, Move)] == [min(100 * 50 / 100, 30), min(40 * 50 / 100, 30)]


@pytest.mark.parametrize(("move", "why"), [
    (r"MoveL p1, v1000, fine\Z:=3, tool0;", "no rmot form"),  # a stop point stays one
    (r"MoveL p1, v1000\V:=0, z10, tool0;", "no rmot form"),  # no speed
    (r"MoveL p1, v1000\V:=speedvar, z10, tool0;", "no rmot form"),  # a variable
    (r"MoveL \Conc, p1, v1000, z10, tool0;", r"its optional argument `\Conc` has no rmot form (the statements after "
                                             "the move run while the robot moves)"),
    (r"MoveL p1, v1000, z10\Inpos:=inpos50, tool0;", r"its optional argument `\Inpos` has no rmot form"),
])
def test_what_the_instruction_gives_that_rmot_cannot_read_stays_native(tmp_path: Path, move: str, why: str) -> None:
    moves, messages = _read(tmp_path, f"    {move}\n")
    assert isinstance(moves[0], Native), moves
    assert any(f"{why}; kept as `native rapid`" in m for m in messages), messages
