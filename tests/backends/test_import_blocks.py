"""Blocks and conditions a reader must not flatten. Fanuc TP structured blocks (B-83284EN, "IF ... THEN / ELSE / ENDIF" and "FOR / ENDFOR"):
an I/O condition is read as an rmot `if`; a block on a register or a FOR loop is kept native
whole, because reading its body as straight-line code would plan and verify one run of it as if
it always happened (found in a pendant backup, kamilkozdro/FanucProgramAnalyze `gratowanie.ls`:
`IF (R[1]=1) THEN` around a move and an output)."""

from __future__ import annotations

from pathlib import Path

from click.testing import CliRunner

from rmot.compiler.cli import cli

POS = """/POS
P[1]{
   GP1:
	UF : 0, UT : 1,		CONFIG : 'N U T, 0, 0, 0',
	X =   500.000  mm,	Y =     0.000  mm,	Z =   500.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[2]{
   GP1:
	UF : 0, UT : 1,		CONFIG : 'N U T, 0, 0, 0',
	X =   500.000  mm,	Y =   100.000  mm,	Z =   400.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
/END
"""


def _import(tmp_path: Path, body: list[str]) -> tuple[str, str]:
    lines = "".join(f"{n:4d}:  {text} ;\n" for n, text in enumerate(body, 1))
    path = tmp_path / "blk.ls"
    path.write_text(f"/PROG  BLK\n/ATTR\n/MN\n{lines}{POS}")
    out = tmp_path / "blk.rmot"
    result = CliRunner().invoke(cli, ["import", str(path), "-o", str(out)], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    program = out.read_text()
    return program[program.index("program"):], result.output


def test_a_block_on_a_register_is_kept_native_whole(tmp_path: Path) -> None:
    program, output = _import(tmp_path, ["J P[1] 100% FINE", "IF (R[1]=1) THEN", "L P[2] 100mm/sec FINE",
                                         "DO[108]=ON", "ENDIF", "J P[1] 100% FINE"])
    assert "move linear" not in program and "set out[108]" not in program
    assert 'native fanuc "L P[2] 100mm/sec FINE ;"' in program and 'native fanuc "ENDIF ;"' in program
    assert program.count("move joint") == 2
    assert "motion and I/O: 2 imported, 2 kept native" in output
    assert "inside `IF (R[1]=1) THEN` at line 5" in output


def test_an_input_block_is_an_if_with_its_else(tmp_path: Path) -> None:
    program, output = _import(tmp_path, ["J P[1] 100% FINE", "IF (DI[3]=ON AND !DI[4]) THEN",
                                         "L P[2] 100mm/sec FINE", "DO[108]=ON", "ELSE", "DO[2]=ON", "ENDIF"])
    assert "W510" not in output
    assert ("  if in[3] == on and in[4] == off {\n    move linear blk_p2 speed 100 mm/s zone fine\n"
            "    set out[108] = on\n  } else {\n    set out[2] = on\n  }\n") in program


def test_a_for_loop_and_the_blocks_inside_it_are_kept_native_whole(tmp_path: Path) -> None:
    program, _ = _import(tmp_path, ["FOR R[1]=1 TO 3", "IF (DI[1]=ON) THEN", "DO[1]=ON", "ENDIF", "ENDFOR",
                                    "DO[2]=ON"])
    lines = [ln.strip() for ln in program.splitlines() if ln.startswith("  native") or "set out" in ln]
    assert lines == [
        'native fanuc "FOR R[1]=1 TO 3 ;"   # ' + str(tmp_path / "blk.ls") + ":4:4",
        'native fanuc "IF (DI[1]=ON) THEN ;"   # ' + str(tmp_path / "blk.ls") + ":5:4",
        'native fanuc "DO[1]=ON ;"   # ' + str(tmp_path / "blk.ls") + ":6:4",
        'native fanuc "ENDIF ;"   # ' + str(tmp_path / "blk.ls") + ":7:4",
        'native fanuc "ENDFOR ;"   # ' + str(tmp_path / "blk.ls") + ":8:4",
        "set out[2] = on"]


def test_a_block_not_closed_is_read_line_by_line(tmp_path: Path) -> None:
    program, output = _import(tmp_path, ["IF (R[1]=1) THEN", "DO[1]=ON"])
    assert "set out[1] = on" in program and "IF (R[1]=1) THEN" in output


def test_a_rapid_if_on_a_declared_num_is_not_read_as_an_input(tmp_path: Path) -> None:
    """RAPID's `IF sig = 1 THEN` tests a digital input signal, but `IF reg1 = 1 THEN` on a `PERS num
    reg1` the module declares is a test of that data: it must not become `if in[1] == on` with a
    signal named reg1 in the stub cell."""
    path = tmp_path / "m.mod"
    path.write_text("MODULE M\n  CONST robtarget p1:=[[500,0,500],[0,1,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];\n"
                    "  PERS num reg1:=0;\n  PROC main()\n    IF reg1 = 1 THEN\n      MoveL p1, v100, fine, tool0;\n"
                    "    ENDIF\n    IF di1 = 1 THEN\n      MoveL p1, v100, fine, tool0;\n    ENDIF\n  ENDPROC\nENDMODULE\n")
    out = tmp_path / "m.rmot"
    result = CliRunner().invoke(cli, ["import", str(path), "-o", str(out)], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    program, cell = out.read_text(), (tmp_path / "m_cell.rmot").read_text()
    assert "if reg1 == 1 {" in program and "if in[1] == on {" in program
    assert 'io in[1] = "di1"' in cell and '"reg1"' not in cell
