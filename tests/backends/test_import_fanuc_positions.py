"""A TP program's /POS blocks read one by one, each ending at its own `};`
(fanuc_text.position_blocks).

A damaged file whose block lacks its `};` must not lend it the next block's values: the old lazy
match ran from one header to the next block's end, so P[1] took P[2]'s coordinates and P[2]
vanished. Witness: the numbers typed in each block here, and the line each header is on.
"""

from __future__ import annotations

from pathlib import Path

from rmot.backends.readers import read_files
from rmot.backends.readers.fanuc_text import position_blocks
from rmot.backends.readers.model import Move, Native, walk


def _block(n: int, x: float, end: bool = True) -> str:
    return (f"P[{n}]{{\n   GP1:\n\tUF : 0, UT : 1,\t\tCONFIG : 'N U T, 0, 0, 0',\n"
            f"\tX =   {x:.3f}  mm,\tY =     0.000  mm,\tZ =   300.000  mm,\n"
            "\tW =   180.000 deg,\tP =     0.000 deg,\tR =     0.000 deg\n" + ("};\n" if end else ""))


def test_a_block_without_its_end_is_left_out_not_merged(tmp_path: Path) -> None:
    text = ("/PROG  PICK\n/ATTR\n/MN\n   1:  UTOOL_NUM=1 ;\n   2:  UFRAME_NUM=0 ;\n   3:  L P[1] 100mm/sec FINE ;\n"
            "   4:  L P[2] 100mm/sec FINE ;\n/POS\n" + _block(1, 400.0, end=False) + _block(2, 555.0) + "/END\n")
    (tmp_path / "pick.ls").write_text(text)
    doc = read_files([str(tmp_path / "pick.ls")])
    moves = [s for s in walk(doc.routines[0].body) if isinstance(s, (Move, Native))]
    assert isinstance(moves[0], Native), moves  # P[1] has no values the file vouches for
    assert isinstance(moves[1], Move) and moves[1].pose is not None, moves
    assert abs(moves[1].pose.position[0] - 0.555) < 1e-12, moves[1].pose  # P[2]'s own X, in metres


def test_each_block_keeps_its_header_line() -> None:
    text = "/PROG  PICK\n/MN\n/POS\n" + _block(3, 1.0) + _block(7, 2.0) + "/END\n"
    found = position_blocks(text)
    lines = text.split("\n")
    assert [(n, line) for n, _, _, line in found] == [(3, 4), (7, 10)]
    assert all(lines[line - 1].startswith(f"P[{n}]") for n, _, _, line in found)
    assert "1.000" in found[0][2] and "2.000" in found[1][2]
