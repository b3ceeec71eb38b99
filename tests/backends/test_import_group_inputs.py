"""`rmot import` of KRL tests on whole numbers the program neither declares nor assigns
(`SWITCH PGNO`, `IF (nStation == 2)`): group inputs `gin[n]` with W534 at the first use
(lang/REFERENCE.md §14).

Witnesses: KSS 8.x Operating and Programming Instructions for System Integrators ("SWITCH": the
first CASE holding the value runs, else DEFAULT; "SIGNAL": a group `$IN[a] TO $IN[b]` reads as an
INT; `$config.dat` holds the globals): the CASE each program number runs is written by hand
below; the imported rmot conditions are evaluated by Python (rmot's priorities are Python's) with
gin[n] bound to each value; the import must pass `rmot check` (the compiler's own rules) and
compile back to KRL that imports to the same conditions.
"""

from __future__ import annotations

import re
from pathlib import Path

from click.testing import CliRunner

from rmot.backends.readers import read_files
from rmot.backends.readers.model import GroupIn, If, Move, Native, WaitIn, group_reads, walk
from rmot.compiler.cli import cli

SRC = """DEF cellprog( )
  INT i
  LOOP
    SWITCH PGNO
    CASE 1
      PTP {A1 0, A2 -90, A3 90, A4 0, A5 30, A6 0}
    CASE 2, 3
      PTP {A1 10, A2 -90, A3 90, A4 0, A5 30, A6 0}
      $OUT[3]=TRUE
    DEFAULT
      WAIT SEC 0.5
    ENDSWITCH
    IF (nStation == 2) AND $IN[4] THEN
      $OUT[4]=TRUE
    ENDIF
    WAIT FOR PGNO > 0
  ENDLOOP
END
"""
# PGNO -> the CASE arm that runs (KSS SWITCH rule), by the first joint of its move (None: DEFAULT)
EXPECTED_ARM = {0: None, 1: 0.0, 2: 10.0, 3: 10.0, 4: None, 255: None}


def _program(tmp_path: Path, src: str = SRC, config: str | None = None) -> tuple[str, str, str]:
    (tmp_path / "cellprog.src").write_text(src)
    if config is not None:
        (tmp_path / "$config.dat").write_text(config)
    out = tmp_path / "out.rmot"
    result = CliRunner().invoke(cli, ["import", str(tmp_path / "cellprog.src"), "-o", str(out)])
    assert result.exit_code == 0, result.output
    return out.read_text(), (tmp_path / "out_cell.rmot").read_text(), result.output


def _arm(program: str, pgno: int) -> float | None:
    """Run the imported if chain by hand: Python evaluates each condition with gin[1] = pgno."""
    lines = program.splitlines()
    for k, line in enumerate(lines):
        m = re.match(r"\s*if (.*) \{$", line)
        if m is None or "gin[1]" not in m.group(1):
            continue
        if eval(m.group(1).replace("gin[1]", str(pgno))):  # noqa: S307 - the test's own text
            move = re.search(r"joints\(([-\d.]+)", lines[k + 1])
            return float(move.group(1)) if move else None
    return None


def test_switch_on_pgno_is_an_if_chain_on_a_group_input(tmp_path: Path) -> None:
    program, cell, output = _program(tmp_path)
    assert 'io gin[1] = "pgno" on r1' in cell and 'io gin[2] = "nstation" on r1' in cell
    for pgno, arm in EXPECTED_ARM.items():
        assert _arm(program, pgno) == arm, (pgno, program)
    assert "if gin[2] == 2 and in[4] == on {" in program
    assert "wait until gin[1] > 0" in program
    # W534 once per name, at its first use: SWITCH (line 4) and the IF (line 13)
    assert re.findall(r":(\d+):\d+: warning\[W534\]: `(\w+)`", output) == [("4", "PGNO"), ("13", "nStation")]
    assert "kept native" in output and "0 kept native" in output
    check = CliRunner().invoke(cli, ["check", str(tmp_path / "out.rmot")])
    assert check.exit_code == 0, check.output


def test_a_config_dat_decides_which_names_are_group_inputs(tmp_path: Path) -> None:
    """With a $config.dat, only its INT globals and SIGNAL groups are group inputs: nStation,
    declared there as REAL, stays native; PGNO (an INT global) is read."""
    program, cell, _ = _program(tmp_path, config="DEFDAT $CONFIG\nDECL INT PGNO=0\nDECL REAL nStation=0.0\nENDDAT\n")
    assert 'io gin[1] = "pgno" on r1' in cell and "nstation" not in cell
    assert _arm(program, 2) == 10.0
    doc = read_files([str(tmp_path / "cellprog.src")])
    natives = [s.text for r in doc.routines for s in walk(r.body) if isinstance(s, Native)]
    assert any("nStation" in t for t in natives)


def test_a_signal_group_in_config_dat_is_a_group_input(tmp_path: Path) -> None:
    config = "DEFDAT $CONFIG\nSIGNAL PGNO $IN[33] TO $IN[40]\nSIGNAL nStation $IN[5]\nENDDAT\n"
    program, cell, _ = _program(tmp_path, config=config)
    assert 'io gin[1] = "pgno" on r1' in cell and "gin[2]" not in cell


def test_a_signal_group_of_the_program_itself_is_a_group_input(tmp_path: Path) -> None:
    """A SIGNAL group the .src declares is read as the group input even where the $config.dat
    found does not know it."""
    src = SRC.replace("  INT i\n", "  INT i\n  SIGNAL nStation $IN[17] TO $IN[20]\n")
    _, cell, _ = _program(tmp_path, src=src, config="DEFDAT $CONFIG\nDECL INT PGNO=0\nENDDAT\n")
    assert 'io gin[1] = "pgno" on r1' in cell and 'io gin[2] = "nstation" on r1' in cell


def test_what_has_no_gin_form_stays_native(tmp_path: Path) -> None:
    """A fraction never equals a whole number; arithmetic on a group input or two compared have
    no `gin[n] op value` form; a name the program declares is a variable, not an input."""
    src = ("DEF cellprog( )\n  DECL INT k\n  IF PGNO == 2.5 THEN\n    $OUT[1]=TRUE\n  ENDIF\n"
           "  IF PGNO + 1 > 3 THEN\n    $OUT[1]=TRUE\n  ENDIF\n  IF PGNO == nStation THEN\n    $OUT[1]=TRUE\n  ENDIF\n"
           "  IF k == 3 THEN\n    $OUT[1]=TRUE\n  ENDIF\nEND\n")
    (tmp_path / "cellprog.src").write_text(src)
    doc = read_files([str(tmp_path / "cellprog.src")])
    stmts = [s for r in doc.routines for s in walk(r.body)]
    assert not any(isinstance(s, If) for s in stmts)
    assert [s.where.line for s in stmts if isinstance(s, Native) and s.text.startswith("IF")] == [3, 6, 9, 12]
    assert not any(d.code.id == "W534" for d in doc.diagnostics)


def test_the_reader_reads_the_group_inputs_and_their_names(tmp_path: Path) -> None:
    (tmp_path / "cellprog.src").write_text(SRC)
    doc = read_files([str(tmp_path / "cellprog.src")])
    stmts = [s for r in doc.routines for s in walk(r.body)]
    wait = next(s for s in stmts if isinstance(s, WaitIn))
    assert group_reads(wait.cond) == [GroupIn("PGNO")]
    assert len([s for s in stmts if isinstance(s, Move)]) == 2


def test_round_trip_through_krl_keeps_the_group_inputs(tmp_path: Path) -> None:
    """The import compiled to KRL reads the group by its cell name; that KRL imports back to the
    same conditions."""
    program, _, _ = _program(tmp_path)
    out = tmp_path / "krl"
    result = CliRunner().invoke(cli, ["compile", str(tmp_path / "out.rmot"), "--target", "krl", "-o", str(out)])
    assert result.exit_code == 0, result.output
    src = next((out / "krl").glob("*.src"))
    assert "IF pgno == 1 THEN" in src.read_text()
    again = tmp_path / "again.rmot"
    assert CliRunner().invoke(cli, ["import", str(src), "-o", str(again)]).exit_code == 0
    conditions = [line.strip() for line in program.splitlines() if "gin[" in line]
    assert [line.strip() for line in again.read_text().splitlines() if "gin[" in line] == conditions


def test_with_a_cell_that_does_not_declare_the_group_it_stays_native(tmp_path: Path) -> None:
    (tmp_path / "cellprog.src").write_text(SRC)
    cell = tmp_path / "cell.rmot"
    cell.write_text('cell c {\n  robot r1 = kuka_kr6_r900\n  io gin[4] = "nstation"\n}\n')
    out = tmp_path / "out.rmot"
    result = CliRunner().invoke(cli, ["import", str(tmp_path / "cellprog.src"), "-o", str(out), "--cell", str(cell)])
    assert result.exit_code == 0, result.output
    assert "W513" in result.output and "signal `PGNO` must be declared in the cell" in result.output
    assert "if gin[4] == 2 and in[4] == on {" in out.read_text()


RMOT = """cell c {
  robot r1 = abb_irb1600 at pose(z=400mm)
  io gin[1] = "pgno" bits 8
}
program p on r1 {
  var n: int = gin[1]
  if gin[1] == 3 and in[2] {
    move joint joints(0deg, 0deg, 0deg, 0deg, 30deg, 0deg)
  }
  while gin[1] < 2 { wait 0.1s }
}
"""


def test_rapid_ginput_round_trip(tmp_path: Path) -> None:
    """rmot's gin[1] is written `GInput(pgno)` (function GInput on the GI signal the cell names)
    and read back as the group input of that name, in the same conditions."""
    (tmp_path / "p.rmot").write_text(RMOT)
    result = CliRunner().invoke(cli, ["compile", str(tmp_path / "p.rmot"), "--target", "rapid", "-o", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    module = tmp_path / "out" / "rapid" / "p.mod"
    assert "IF GInput(pgno) = 3 AND DInput(di2) = 1 THEN" in module.read_text()
    back = tmp_path / "back.rmot"
    result = CliRunner().invoke(cli, ["import", str(module), "-o", str(back)])
    assert result.exit_code == 0, result.output
    text = back.read_text()
    assert "n = gin[1]" in text and "if gin[1] == 3 and in[2] == on {" in text and "while gin[1] < 2 {" in text
    assert 'io gin[1] = "pgno" on r1' in (tmp_path / "back_cell.rmot").read_text()
    check = CliRunner().invoke(cli, ["check", str(back)])
    assert check.exit_code == 0, check.output


FANUC = """cell c {
  robot r1 = fanuc_m10ia
  io gin[1] = "pgno" bits 8
}
program p on r1 {
  if gin[1] == 3 {
    move joint joints(0deg, 0deg, 0deg, 0deg, 30deg, 0deg)
  } else {
    move joint joints(10deg, 0deg, 0deg, 0deg, 30deg, 0deg)
  }
  if gin[1] >= 5 { wait 1s }
  wait until gin[1] > 0
}
"""


def test_fanuc_gi_round_trip(tmp_path: Path) -> None:
    """`IF GI[1:pgno]<>3,JMP LBL[a]` skips the then arm when the test holds: read back as the
    negated test, `gin[1] == 3`; `WAIT GI[1:pgno]>0` as a wait on it."""
    (tmp_path / "p.rmot").write_text(FANUC)
    result = CliRunner().invoke(cli, ["compile", str(tmp_path / "p.rmot"), "--target", "fanuc", "-o", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    tp = tmp_path / "out" / "fanuc" / "P.ls"
    assert "IF GI[1:pgno]<>3,JMP LBL[1]" in tp.read_text() and "IF GI[1:pgno]<5,JMP LBL[3]" in tp.read_text()
    back = tmp_path / "back.rmot"
    result = CliRunner().invoke(cli, ["import", str(tp), "-o", str(back)])
    assert result.exit_code == 0, result.output
    conditions = [line.strip() for line in back.read_text().splitlines() if "gin[" in line]
    assert conditions == ["if gin[1] == 3 {", "if gin[1] >= 5 {", "wait until gin[1] > 0"]
    assert "0 kept native" in result.output
    check = CliRunner().invoke(cli, ["check", str(back)])
    assert check.exit_code == 0, check.output
