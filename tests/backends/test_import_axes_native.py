"""Moves with external-axis values the cell cannot place: kept native whole, counted as the
motion they are, and RAPID's zeros on a cell without axes read as the controller reads them
(readers/axes.py).

Witnesses (none of them the readers under test): the vendor file's own lines, joined in the test
(what a native move must carry to run on the controller); the program `rmot compile` writes back
from the imported .rmot (a KRL line starting `;` is a comment the controller skips); motion lines
counted in the test by each vendor's line form; ABB's rule for an axis not connected ("If the
position is defined in the position data, although the axis is not connected, the value will be
ignored", RAPID reference, extjoint), so a `[0,9E9,..]` move compiles back to the same arm move.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from click.testing import CliRunner

from rmot.compiler.cli import cli



def _import(files: list[Path], out: Path, cell: Path | None = None) -> str:
    args = ["import", *map(str, files), "-o", str(out)] + (["--cell", str(cell)] if cell else [])
    result = CliRunner().invoke(cli, args, catch_exceptions=False)
    assert result.exit_code == 0, result.output
    return result.output


def _compile(program: Path, target: str, out: Path) -> str:
    result = CliRunner().invoke(cli, ["compile", str(program), "--target", target, "-o", str(out)], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    main = next(p for p in (out / target).iterdir() if p.suffix in (".mod", ".src", ".ls", ".JBI"))
    return main.read_text()


def _motion_summary(output: str, name: str) -> tuple[int, int]:
    m = re.search(rf"{re.escape(name)}: .*motion and I/O: (\d+) imported, (\d+) kept native", output)
    assert m is not None, output
    return int(m.group(1)), int(m.group(2))


RAPID_OVER_LINES = """MODULE hand
  CONST robtarget p1 := [[500,0,800],[0,0,1,0],[0,0,0,0],[1000,9E9,9E9,9E9,9E9,9E9]];
  PROC main()
    MoveL [[500,0,700],[0,0,1,0],[0,0,0,0],
           [1200,9E9,9E9,9E9,9E9,9E9]], v100, z10, tool0;
    MoveL Offs(p1, 0, 0, 10),
      v100, fine, tool0;
  ENDPROC
ENDMODULE
"""


def test_rapid_move_over_lines_kept_native_whole(tmp_path: Path) -> None:
    """A RAPID move written over two lines to a track position, imported without a cell: the
    native statement is the whole move (its first line alone is not RAPID), and the compiled
    module carries it whole."""
    src = tmp_path / "hand.mod"
    src.write_text(RAPID_OVER_LINES)
    output = _import([src], tmp_path / "out.rmot")
    assert _motion_summary(output, "hand.mod") == (0, 2), output
    lines = RAPID_OVER_LINES.splitlines()
    statements = [" ".join(" ".join(lines[a:b]).split()) for a, b in ((3, 5), (5, 7))]  # as written, spaces aside
    written = " ".join(_compile(tmp_path / "out.rmot", "rapid", tmp_path / "c").split())
    for statement in statements:
        assert statement.endswith("tool0;") and statement in written, (statement, written)


KRL_SRC = """DEF hand( )
;FOLD PTP P1 Vel=100 % PDAT1 Tool[1] Base[0];%{PE}%R 8.3.38,%MKUKATPBASIS,%CMOVE,%VPTP,%P 1:PTP, 2:P1, 3:, 5:100, 7:PDAT1
$BWDSTART=FALSE
PDAT_ACT=PPDAT1
FDAT_ACT=FP1
BAS(#PTP_PARAMS,100)
PTP XP1
;ENDFOLD
LIN {X 500, Y 0, Z 800, A 0, B 90, C 0, E1 300}
END
"""
KRL_DAT = """DEFDAT hand
DECL E6POS XP1={X 600.0,Y 0.0,Z 900.0,A 0.0,B 90.0,C 0.0,S 2,T 35,E1 250.0,E2 0.0,E3 0.0,E4 0.0,E5 0.0,E6 0.0}
DECL FDAT FP1={TOOL_NO 1,BASE_NO 0,IPO_FRAME #BASE}
DECL PDAT PPDAT1={VEL 100.0,ACC 100.0,APO_DIST 100.0}
ENDDAT
"""


def test_krl_inline_form_kept_native_is_a_motion_not_a_comment(tmp_path: Path) -> None:
    """A KRL inline form to a point with E1 250, imported without a cell: kept native as the
    motion its header names, as the reader keeps a form it cannot read, never as the `;FOLD`
    comment line (the controller would skip it: the move would vanish from the compiled program)."""
    (tmp_path / "hand.src").write_text(KRL_SRC)
    (tmp_path / "hand.dat").write_text(KRL_DAT)
    output = _import([tmp_path / "hand.src"], tmp_path / "out.rmot")
    assert _motion_summary(output, "hand.src") == (0, 2), output
    code = [ln.strip() for ln in _compile(tmp_path / "out.rmot", "krl", tmp_path / "c").splitlines()]
    assert "PTP P1 Vel=100 % PDAT1 Tool[1] Base[0]" in code, code  # a statement, not after `;`
    assert not any(ln.startswith(";FOLD PTP P1") for ln in code), code


TP_GP2 = ("/PROG  HAND\n/ATTR\nDEFAULT_GROUP\t= 1,1,*,*,*;\n/MN\n"
          "   1:  J P[1] 100% FINE ;\n   2:  L P[2] 250mm/sec CNT50 ;\n   3:  L P[1] 250mm/sec FINE ;\n/POS\n"
          + "".join(f"P[{n}]{{\n   GP1:\n\tUF : 0, UT : 0,\t\tCONFIG : 'N U T, 0, 0, 0',\n"
                    f"\tX =   {400 + 100 * n}.000  mm,\tY =     0.000  mm,\tZ =   600.000  mm,\n"
                    "\tW =   180.000 deg,\tP =     0.000 deg,\tR =     0.000 deg\n"
                    f"   GP2:\n\tUF : 0, UT : 0,\t\n\tJ1=     {10 * n}.000 deg\n}};\n" for n in (1, 2))
          + "/END\n")


def test_tp_second_group_without_cell_counts_every_motion(tmp_path: Path) -> None:
    """A TP program whose positions carry a second group (GP2, a positioner the file proves the
    controller has), imported without a cell: every move stays native, counted as motion kept
    native, its text without the pendant's line number (as the reader keeps a line)."""
    (tmp_path / "HAND.ls").write_text(TP_GP2)
    output = _import([tmp_path / "HAND.ls"], tmp_path / "out.rmot")
    moves = [ln for ln in TP_GP2.splitlines() if re.match(r"\s*\d+:\s*[JLC]\s", ln)]
    assert output.count("warning[W523]") == len(moves) == 3, output
    assert _motion_summary(output, "HAND.ls") == (0, len(moves)), output
    text = (tmp_path / "out.rmot").read_text()
    assert 'native fanuc "L P[2] 250mm/sec CNT50 ;"' in text and 'native fanuc "2:' not in text, text


INFORM_ARC = ("/JOB\n//NAME HAND\n//POS\n///NPOS 3,0,1,0,0,0\n///TOOL 0\n///POSTYPE ROBOT\n///RECTAN\n"
              "///RCONF 0,0,0,0,0,0,0,0\nC00000=1000.000,0.000,630.000,135.0000,0.0000,90.0000\n"
              "C00001=1000.000,50.000,680.000,135.0000,0.0000,90.0000\n"
              "C00002=1000.000,100.000,630.000,135.0000,0.0000,90.0000\n"
              "///POSTYPE PULSE\n///PULSE\nEC00000=0,90000\n//INST\n///DATE 2000/01/01 00:00\n"
              "///ATTR SC,RW\n///GROUP1 RB1\n///GROUP2 ST1\nNOP\n"
              "MOVJ C00000 VJ=100.00 +MOVJ EC00000 VJ=100.00\n"
              "MOVC C00000 V=100.0 +MOVJ EC00000 VJ=100.00\nMOVC C00001 V=100.0 +MOVJ EC00000 VJ=100.00\n"
              "MOVC C00002 V=100.0 +MOVJ EC00000 VJ=100.00\nEND\n")


def test_inform_arc_kept_native_keeps_its_three_lines(tmp_path: Path) -> None:
    """An INFORM arc (three MOVC lines) beside a station, imported without a cell: the native arc
    is all three lines (one MOVC alone is no arc on the controller)."""
    (tmp_path / "HAND.JBI").write_text(INFORM_ARC)
    _import([tmp_path / "HAND.JBI"], tmp_path / "out.rmot")
    natives = re.findall(r'native inform "([^"]*)"', (tmp_path / "out.rmot").read_text())
    arcs = [ln for ln in INFORM_ARC.splitlines() if ln.startswith("MOVC")]
    assert [n for n in natives if n.startswith("MOVC")] == arcs, natives


def _rapid_zeros(tmp_path: Path, second: str) -> Path:
    path = tmp_path / "gen.mod"
    path.write_text("MODULE gen\n  PROC main()\n"
                    "    MoveJ [[500,0,700],[0,0,1,0],[0,-1,0,0],[0,9E9,9E9,9E9,9E9,9E9]], v100, z10, tool0;\n"
                    f"    MoveL [[500,100,700],[0,0,1,0],[0,-1,0,0],{second}], v100, fine, tool0;\n"
                    "  ENDPROC\nENDMODULE\n")
    return path


@pytest.mark.parametrize("given", [False, True])
def test_rapid_zero_extax_on_a_cell_without_axes_reads(tmp_path: Path, given: bool) -> None:
    """A generator's `[0,9E9,..]` on every move, on the stub cell or given a cell without track or
    positioner (`--cell`): the controller ignores a value of an axis not connected, so the moves are read
    (W544 once for the file, at its first move), and compile back to the same arm moves with
    eax_a unset (9E+09), which that controller runs the same."""
    cell = tmp_path / "stub_cell.rmot" if given else None  # the cell a first import writes: the arm alone
    if cell is not None:
        _import([_rapid_zeros(tmp_path, "[9E9,9E9,9E9,9E9,9E9,9E9]")], tmp_path / "stub.rmot")
    output = _import([_rapid_zeros(tmp_path, "[9E9,9E9,9E9,9E9,9E9,9E9]")], tmp_path / "out.rmot", cell)
    assert output.count("warning[W544]") == 1 and "W523" not in output, output
    assert re.search(r"gen\.mod:3:5: warning\[W544\]: every external-axis value the moves give is 0 \(eax_a\)", output), output
    assert _motion_summary(output, "gen.mod") == (2, 0), output
    written = _compile(tmp_path / "out.rmot", "rapid", tmp_path / "c")
    extax = re.findall(r"\],\s*\[([^\[\]]*)\]\s*\]", written)
    assert extax and all(set(v.strip() for v in e.split(",")) == {"9E+09"} for e in extax), written


@pytest.mark.parametrize("second", ["[5,9E9,9E9,9E9,9E9,9E9]", "[0,0,9E9,9E9,9E9,9E9]"])
def test_rapid_extax_other_than_zero_stays_native(tmp_path: Path, second: str) -> None:
    """A move that places an axis (5 mm; or a second slot, however small the value) beside the
    zeros: the axis is real, the cell lacks it, and the moves with values stay native (W523)."""
    output = _import([_rapid_zeros(tmp_path, second)], tmp_path / "out.rmot")
    if second.startswith("[5"):
        assert output.count("warning[W523]") == 2 and "W544" not in output, output
        assert _motion_summary(output, "gen.mod") == (0, 2), output
    else:
        assert output.count("warning[W544]") == 1, output  # zeros in eax_a and eax_b: still no axis placed
        assert "(eax_a, eax_b)" in output, output


def test_corpus_share_counts_what_the_command_keeps(tmp_path: Path) -> None:
    """The corpus measurement reads a file as `rmot import FILE` does: a move its stub cell keeps
    native (W523) counts native there too."""
    from test_import_corpus_rates import _shares  # late: the measurement under test

    (tmp_path / "rapid").mkdir()
    (tmp_path / "rapid" / "gen.mod").write_text(_rapid_zeros(tmp_path, "[5,9E9,9E9,9E9,9E9,9E9]").read_text())
    assert _shares(tmp_path) == {"rapid": (0, 2)}


def _tp_coord(positions: list[tuple[float, float]]) -> str:
    """A TP program in user frame 1 moving linearly, COORD, to P[1..n], the positioner (GP2, two
    axes as weld_positioner's) at the given values."""
    moves = "".join(f"{4 + n:4d}:  L P[{n}] 100mm/sec FINE COORD ;\n" for n in range(1, len(positions) + 1))
    pos = "".join(f"P[{n}]{{\n   GP1:\n\tUF : 1, UT : 1,\t\tCONFIG : 'N U T, 0, 0, 0',\n"
                  f"\tX =   {100 + 10 * n}.000  mm,\tY =     0.000  mm,\tZ =   200.000  mm,\n"
                  "\tW =   180.000 deg,\tP =     0.000 deg,\tR =     0.000 deg\n"
                  f"   GP2:\n\tUF : 1, UT : 1,\t\n\tJ1=     {a:.3f} deg,\tJ2=    {b:.3f} deg\n}};\n"
                  for n, (a, b) in enumerate(positions, 1))
    return f"/PROG  HAND\n/ATTR\nDEFAULT_GROUP\t= 1,1,*,*,*;\n/MN\n   1:  UFRAME_NUM=1 ;\n   2:  UTOOL_NUM=1 ;\n" \
           f"   3:  WAIT   0.10(sec) ;\n   4:  WAIT   0.10(sec) ;\n{moves}/POS\n{pos}/END\n"


def test_tp_coord_in_a_user_frame_reads_only_where_the_positioner_stands_still(tmp_path: Path) -> None:
    """COORD (the path relative to the part the positioner carries) in user frame 1 on the weld
    positioner's cell: a move whose positioner values are the move's before it follows the same
    path as a plain move (the part stands still), read as one; the first move (where it starts is
    not in the program) and a move that turns the positioner stay native whole (W523), never a
    plain move with a `COORD` line after it."""
    (tmp_path / "HAND.ls").write_text(_tp_coord([(0, 0), (0, 0), (0, 90)]))
    cell = tmp_path / "cell.rmot"
    cell.write_text((Path(__file__).resolve().parents[2] / "examples" / "weld_positioner.rmot").read_text())
    output = _import([tmp_path / "HAND.ls"], tmp_path / "out.rmot", cell)
    text = (tmp_path / "out.rmot").read_text()
    assert re.findall(r"HAND\.ls:(\d+):\d+: warning\[W523\]: .*a coordinated move \(COORD\) in a user frame", output) == \
        ["9", "11"], output  # the file lines of TP lines 5 and 7
    assert 'native fanuc "L P[1] 100mm/sec FINE COORD ;"' in text and 'native fanuc "L P[3] 100mm/sec FINE COORD ;"' in text
    assert re.search(r"move linear hand_p2 ext\(pos=\(0deg, 0deg\)\) speed 100 mm/s zone fine", text), text
    assert 'native fanuc "!COORD ;"' not in text and "`COORD` is kept after the move" not in output, (text, output)
    assert _motion_summary(output, "HAND.ls") == (3, 2), output  # the two WAITs and P[2]
