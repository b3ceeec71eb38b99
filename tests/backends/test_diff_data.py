"""`rmot diff` names a touch-up of the data the moves use, not only of the moves: a re-taught
TCP or user frame moves every point the robot reaches, a payload changes its dynamics, and a
position rmot does not read is still the robot's. It also compares a vendor file with the
.rmot it came from for every vendor and for a program of several tasks.

Witness: each touch-up is an edit made in the test (a TCP moved by exactly 2 mm along z, a
work object by 1.5 mm along x, a mass from 1.5 to 2.5 kg), so the expected line comes from the
edit; the distance is recomputed here with numpy from the vendor numbers, not taken from the
reader under test.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from rmot.compiler.cli import cli

ROOT = Path(__file__).resolve().parents[2]
VENDOR = ROOT / "tests" / "data" / "vendor_programs"


def _diff(a: Path, b: Path) -> tuple[int, list[str], str]:
    result = CliRunner().invoke(cli, ["diff", str(a), str(b)], catch_exceptions=False)
    return result.exit_code, result.stdout.splitlines(), result.stderr


def _pair(tmp_path: Path, name: str, text: str, touched: str) -> tuple[Path, Path]:
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    a, b = tmp_path / "a" / name, tmp_path / "b" / name
    a.write_text(text)
    b.write_text(touched)
    return a, b


UR = """def prog():
  set_tcp(p[0.0,0.0,0.1,0.0,0.0,0.0])
  set_payload(1.5, [0.0, 0.0, 0.05])
  movel(p[0.4,0.1,0.3,3.14159,0,0], a=1.2, v=0.25)
  movel(p[0.4,0.2,0.3,3.14159,0,0], a=1.2, v=0.25)
end
"""


def test_a_retaught_urscript_tcp_and_payload_are_named(tmp_path: Path) -> None:
    touched = UR.replace("p[0.0,0.0,0.1,", "p[0.0,0.0,0.102,").replace("set_payload(1.5,", "set_payload(2.5,")
    a, b = _pair(tmp_path, "x.script", UR, touched)
    code, lines, _ = _diff(a, b)
    moved = 1000 * np.linalg.norm(np.array([0.0, 0.0, 0.102]) - np.array([0.0, 0.0, 0.1]))
    assert code == 1, lines
    assert f"{a}:2:3 -> {b}:2:3: tool tcp_1 moved {moved:.3f} mm, turned 0.000 deg" in lines
    assert f"{a}:2:3 -> {b}:2:3: tool tcp_1 mass 1.5 kg -> 2.5 kg" in lines
    assert lines[-1] == "2 differences"


RAPID = """MODULE M
  PERS tooldata tGun:=[TRUE,[[0,0,100],[1,0,0,0]],[1.5,[0,0,50],[1,0,0,0],0,0,0]];
  PERS wobjdata wTable:=[FALSE,TRUE,"",[[500,0,200],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];
  PERS loaddata piece:=[2.0,[0,0,80],[1,0,0,0],0,0,0];
  CONST robtarget p10:=[[100,0,50],[0,0,1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
  PROC main()
    MoveL p10,v100,z10,tGun\\WObj:=wTable;
    GripLoad piece;
  ENDPROC
ENDMODULE
"""


def test_rapid_tool_work_object_and_load_data_touch_ups_are_named(tmp_path: Path) -> None:
    touched = (RAPID.replace("[[0,0,100],", "[[0,0,102],").replace("[1.5,[0,0,50]", "[2.5,[0,0,50]")
               .replace("[[500,0,200],", "[[501.5,0,200],").replace("[2.0,[0,0,80]", "[2.4,[0,0,80]"))
    a, b = _pair(tmp_path, "M.mod", RAPID, touched)
    code, lines, _ = _diff(a, b)
    assert code == 1, lines
    assert lines[:-1] == [
        f"{a}:2:3 -> {b}:2:3: tool tGun moved 2.000 mm, turned 0.000 deg",
        f"{a}:2:3 -> {b}:2:3: tool tGun mass 1.5 kg -> 2.5 kg",
        f"{a}:3:3 -> {b}:3:3: frame wTable moved 1.500 mm, turned 0.000 deg",
        f"{a}:4:3 -> {b}:4:3: kept line changed (piece:=[2.0,[0,0,80],[1,0,0,0],0,0,0]; -> "
        "piece:=[2.4,[0,0,80],[1,0,0,0],0,0,0];): PERS loaddata piece:=[2.4,[0,0,80],[1,0,0,0],0,0,0];",
    ], lines
    assert _diff(a, a)[:2] == (0, ["0 differences"])


KRL_SRC = """DEF k()
  $TOOL = {X 0, Y 0, Z 150, A 0, B 0, C 0}
  $BASE = {X 800, Y 0, Z 0, A 0, B 0, C 0}
  PTP XP1
  $LOAD = BOX
  LIN XP2
END
"""
KRL_DAT = """DEFDAT k
  DECL E6POS XP1={X 0.0,Y 0.0,Z 600.0,A 0.0,B 90.0,C 0.0,S 6,T 50,E1 0.0,E2 0.0,E3 0.0,E4 0.0,E5 0.0,E6 0.0}
  DECL E6POS XP2={X 0.0,Y 100.0,Z 600.0,A 0.0,B 90.0,C 0.0,S 6,T 50,E1 0.0,E2 0.0,E3 0.0,E4 0.0,E5 0.0,E6 0.0}
  DECL LOAD BOX={M 2.0,CM {X 0.0,Y 0.0,Z 80.0,A 0.0,B 0.0,C 0.0},J {X 0.0,Y 0.0,Z 0.0}}
ENDDAT
"""


def test_krl_inline_tool_base_and_load_touch_ups_are_named(tmp_path: Path) -> None:
    a, b = _pair(tmp_path, "k.src", KRL_SRC, KRL_SRC.replace("Z 150", "Z 152").replace("X 800", "X 801"))
    (tmp_path / "a" / "k.dat").write_text(KRL_DAT)
    (tmp_path / "b" / "k.dat").write_text(KRL_DAT.replace("M 2.0", "M 2.5").replace("Z 80.0", "Z 83.0"))
    code, lines, _ = _diff(a, b)
    da, db = a.with_suffix(".dat"), b.with_suffix(".dat")
    assert (code, lines) == (1, [
        f"{a}:2:3 -> {b}:2:3: tool tool_1 moved 2.000 mm, turned 0.000 deg",
        f"{a}:3:3 -> {b}:3:3: frame base_1 moved 1.000 mm, turned 0.000 deg",
        f"{da}:4:3 -> {db}:4:3: load BOX mass 2 kg -> 2.5 kg",
        f"{da}:4:3 -> {db}:4:3: load BOX centre of mass moved 3.000 mm",
        "4 differences"])


def test_a_touched_up_position_rmot_does_not_read_is_named(tmp_path: Path) -> None:
    """A pulse position (INFORM, read only with --pulses-per-degree) and a TP position in a
    coordinate form rmot does not read (`RX =`): their moves stay native, and a touch-up of
    their data, which no instruction line shows, is still a difference."""
    jbi = (VENDOR / "inform" / "yis_TEST1.JBI").read_text()
    old = "C00000=390876,202089,35618,0,-117424,182917"
    a, b = _pair(tmp_path, "TEST1.JBI", jbi, jbi.replace(old, old.replace("390876", "391076")))
    code, lines, _ = _diff(a, b)
    line = jbi[:jbi.index(old)].count("\n") + 1
    assert (code, lines[-1]) == (1, "1 difference"), lines
    assert lines[0].startswith(f"{a}:{line}:1 -> {b}:{line}:1: kept line changed (C00000=390876,"), lines

    ls = """/PROG  R
/ATTR
DEFAULT_GROUP	= 1,*,*,*,*;
/MN
   1:  UFRAME_NUM=1 ;
   2:  UTOOL_NUM=4 ;
   3:J P[1] 100% FINE ;
/POS
P[1]{
   GP1:
	UF : 1, UT : 4,		CONFIG : 'N U T, 0, 0, 0',
	RX =   341.681  mm,	RY =  -170.477  mm,	RZ =  -671.251  mm,
	RW =    29.745 deg,	RP =   -14.702 deg,	RR =    72.713 deg
};
/END
"""
    (tmp_path / "tp").mkdir()
    a, b = _pair(tmp_path / "tp", "R.ls", ls, ls.replace("341.681", "343.681"))
    code, lines, _ = _diff(a, b)
    assert (code, lines[-1]) == (1, "1 difference"), lines
    assert lines[0].startswith(f"{a}:9:1 -> {b}:9:1: kept line changed (341.681 -> 343.681): P[1]{{GP1:"), lines


TP_TOOL = """/PROG  T
/ATTR
DEFAULT_GROUP	= 1,*,*,*,*;
/MN
   1:  !UTOOL[1] = gun ;
   2:  PR[91]=LPOS ;
   3:  PR[91,1]=0.0000 ;
   4:  PR[91,2]=0.0000 ;
   5:  PR[91,3]=150.0000 ;
   6:  PR[91,4]=0.0000 ;
   7:  PR[91,5]=0.0000 ;
   8:  PR[91,6]=0.0000 ;
   9:  UTOOL[1]=PR[91] ;
  10:  UFRAME_NUM=0 ;
  11:  UTOOL_NUM=1 ;
  12:J P[1] 50% FINE ;
/POS
P[1]{
   GP1:
	UF : 0, UT : 1,		CONFIG : 'N U T, 0, 0, 0',
	X =   500.000  mm,	Y =     0.000  mm,	Z =   600.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
/END
"""


def test_a_tool_the_file_no_longer_sets_is_named(tmp_path: Path) -> None:
    """The TP program sets UTOOL[1] through PR[91] (as rmot's backend writes it); the touched
    copy drops those lines, so the move runs with whatever UTOOL[1] the controller holds."""
    kept = "\n".join(ln for ln in TP_TOOL.splitlines() if "PR[91" not in ln and "UTOOL[1]=" not in ln) + "\n"
    a, b = _pair(tmp_path, "T.ls", TP_TOOL, kept)
    code, lines, _ = _diff(a, b)
    assert (code, lines) == (1, [f"{a}:13:4 -> {b}:8:3: tool gun set in the file -> the controller's UTOOL[1]",
                                 "1 difference"])


@pytest.fixture(scope="module")
def handover(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("handover")
    result = CliRunner().invoke(cli, ["compile", str(ROOT / "examples" / "handover.rmot"), "--target", "rapid",
                                      "--target", "inform", "--target", "fanuc", "-o", str(out)], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    return out


@pytest.mark.parametrize("vendor, name", [("rapid", "handover_r2.mod"), ("inform", "HANDOVER_R1.JBI"),
                                          ("fanuc", "HANDOVER_R2.ls")])
def test_a_task_of_several_against_the_rmot_is_that_task(handover: Path, vendor: str, name: str) -> None:
    """Each robot's file of a two-task program against the .rmot: the same-named file the
    .rmot compiles to is compared (not both tasks' files as one), and the other task's file is
    named as left out."""
    code, lines, err = _diff(handover / vendor / name, ROOT / "examples" / "handover.rmot")
    assert (code, lines) == (0, ["0 differences"])
    assert f"note: the .rmot compiles to 1 more {vendor} file" in err


def test_a_job_file_against_the_rmot_says_what_it_leaves_out(tmp_path: Path) -> None:
    """A TP job compiles to the main program and one program per routine: `MAIN.ls` against the
    .rmot compares MAIN.ls (not the routines' programs, which it does not hold), and the note says how
    many files it did not compare."""
    result = CliRunner().invoke(cli, ["compile", str(ROOT / "examples" / "pick_place.rmot"), "--target", "fanuc",
                                      "-o", str(tmp_path)], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    files = sorted((tmp_path / "fanuc").iterdir())
    code, lines, err = _diff(tmp_path / "fanuc" / "PICK_PLACE.ls", ROOT / "examples" / "pick_place.rmot")
    assert (code, lines) == (0, ["0 differences"])
    assert f"note: the .rmot compiles to {len(files) - 1} more fanuc files" in err


def test_a_file_named_like_no_task_is_a_located_error(handover: Path, tmp_path: Path) -> None:
    """A program of two tasks compiles to `handover_r1.mod` and `handover_r2.mod`: a file named
    like neither (nor like the program) cannot say which task it is."""
    other = tmp_path / "other.mod"
    other.write_text((handover / "rapid" / "handover_r1.mod").read_text())
    result = CliRunner().invoke(cli, ["diff", str(other), str(ROOT / "examples" / "handover.rmot")])
    assert result.exit_code == 2, result.output
    assert f"{other}:1:1: error[E514]" in result.stderr
    assert "compiles for rapid to handover_r1.mod, handover_r2.mod: none is named like other.mod" in result.stderr


def test_a_renamed_vendor_file_is_compared_with_the_program_it_came_from(tmp_path: Path) -> None:
    """A backup copy under another name (`INSPECT_BACKUP.JBI`) against the .rmot: the program's
    own file is compared."""
    result = CliRunner().invoke(cli, ["compile", str(ROOT / "examples" / "inspect.rmot"), "--target", "inform",
                                      "-o", str(tmp_path)], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    renamed = tmp_path / "INSPECT_BACKUP.JBI"
    renamed.write_text((tmp_path / "inform" / "INSPECT.JBI").read_text())
    assert _diff(renamed, ROOT / "examples" / "inspect.rmot")[:2] == (0, ["0 differences"])
