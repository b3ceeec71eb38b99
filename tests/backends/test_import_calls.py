"""Calls in imported programs: a call of a routine none of the files given defines stays native
(W510) in every vendor's reading, so the imported program compiles and `rmot check` verifies the
rest (a call of a proc it lacks would be E101); TP's `IF (cond),CALL PROG` on a program of the job
is an rmot `if` around the call (B-83284EN, IF with a CALL action)."""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner

from rmot.compiler.cli import cli

FILES = {
    "krl": ("callk.src", "DEF callk()\n  PTP {A1 0,A2 -90,A3 90,A4 0,A5 30,A6 0}\n  Greifer_auf()\n"
                         "  PTP {A1 10,A2 -90,A3 90,A4 0,A5 30,A6 0}\nEND\n", 'native krl "Greifer_auf()"'),
    "fanuc": ("callt.ls", "/PROG  CALLT\n/ATTR\n/MN\n   1:  DO[1]=ON ;\n   2:  CALL STANCHWYTAKA ;\n"
                          "   3:  DO[2]=ON ;\n/POS\n/END\n", 'native fanuc "CALL STANCHWYTAKA ;"'),
    "inform": ("J1.JBI", "/JOB\n//NAME J1\n//POS\n///NPOS 0,0,0,0,0,0\n//INST\n///DATE 2025/01/01 00:00\n"
                         "///ATTR SC,RW\n///GROUP1 RB1\nNOP\nDOUT OT#(1) ON\nCALL JOB:PICK\nDOUT OT#(2) ON\nEND\n",
               'native inform "CALL JOB:PICK"'),
}


def _import(tmp_path: Path, files: dict[str, str]) -> tuple[str, str]:
    for name, text in files.items():
        (tmp_path / name).write_text(text)
    out = tmp_path / "imported.rmot"
    result = CliRunner().invoke(cli, ["import", *(str(tmp_path / n) for n in files), "-o", str(out)],
                                catch_exceptions=False)
    assert result.exit_code == 0, result.output
    return out.read_text(), result.output


@pytest.mark.parametrize("vendor", sorted(FILES))
def test_a_call_of_a_routine_not_given_stays_native_and_the_program_checks(tmp_path: Path, vendor: str) -> None:
    name, text, native = FILES[vendor]
    program, output = _import(tmp_path, {name: text})
    assert native in program, program
    assert "routine none of the files given defines (give its file too)" in output
    assert "1 kept native" in output.split("imported,")[1]  # the call is counted native, not imported
    result = CliRunner().invoke(cli, ["check", str(tmp_path / "imported.rmot")], catch_exceptions=False)
    assert result.exit_code == 0, result.output  # without the native line: E101 unknown proc


def test_the_same_call_is_a_proc_call_where_its_file_is_given(tmp_path: Path) -> None:
    program, output = _import(tmp_path, {
        "callt.ls": FILES["fanuc"][1],
        "stanchwytaka.ls": "/PROG  STANCHWYTAKA\n/ATTR\n/MN\n   1:  DO[7]=ON ;\n/POS\n/END\n"})
    assert "  STANCHWYTAKA()\n" in program and "native" not in program.split("program", 1)[1]
    assert "W510" not in output


def test_a_tp_conditional_call_of_a_program_of_the_job_is_an_if(tmp_path: Path) -> None:
    program, output = _import(tmp_path, {
        "ifcall.ls": "/PROG  IFCALL\n/ATTR\n/MN\n   1:  IF (DO[3]=ON),CALL SUBP ;\n   2:  IF R[2]<>1,CALL SUBP ;\n"
                     "   3:  IF (DI[1]),CALL NOTGIVEN ;\n/POS\n/END\n",
        "subp.ls": "/PROG  SUBP\n/ATTR\n/MN\n   1:  DO[5]=ON ;\n/POS\n/END\n"})
    assert "  if out[3] == on {\n    SUBP()\n  }\n  if gin[1] != 1 {\n    SUBP()\n  }\n" in program
    assert '\n  native fanuc "IF (DI[1]),CALL NOTGIVEN ;"' in program  # not a program of the job: the line whole
    assert "if in[1] == on" not in program
    result = CliRunner().invoke(cli, ["check", str(tmp_path / "imported.rmot")], catch_exceptions=False)
    assert result.exit_code == 0, result.output


def test_a_krl_call_spelt_in_another_case_calls_the_routine(tmp_path: Path) -> None:
    """KRL names are case-insensitive (KSS 8.x, "Names"): `calculatepickpos(..)` calls `DEF
    calculatePickPos(..)`. The import wrote the call as spelt and `rmot check` refused it (E101,
    exit 2) on a real milling program (HugoDanielson/KukaMiling); it is written as the DEF spells it."""
    program, _ = _import(tmp_path, {"job.src": "DEF job( )\n  calculatepickpos(2)\nEND\n"
                                               "DEF calculatePickPos(nTool :IN)\n  DECL INT nTool\n"
                                               "  PTP {A1 0,A2 -90,A3 90,A4 0,A5 30,A6 0}\nEND\n"})
    assert "calculatePickPos(2)" in program and "calculatepickpos(" not in program, program
    result = CliRunner().invoke(cli, ["check", str(tmp_path / "imported.rmot")], catch_exceptions=False)
    assert result.exit_code == 0, result.output


def test_a_call_back_to_the_main_routine_stays_native(tmp_path: Path) -> None:
    """A RAPID PROC that ends with `main;` (TheNameXDD's vision cell loops so): rmot's main routine
    is the program's body, not a proc, so the call was `main()` and `rmot check` refused it (E101)."""
    program, output = _import(tmp_path, {"cell.mod": "MODULE cell\n  PROC main()\n    put;\n  ENDPROC\n"
                                                     "  PROC put()\n    SetDO do1, 1;\n    main;\n  ENDPROC\nENDMODULE\n"})
    assert 'native rapid "main;"' in program
    assert "`main` is the routine that runs first, the program's own body in rmot" in output
    result = CliRunner().invoke(cli, ["check", str(tmp_path / "imported.rmot")], catch_exceptions=False)
    assert result.exit_code == 0, result.output
