"""`rmot import` of Fanuc TP programs with the registers and frames a controller backup saved
(NUMREG.VA, POSREG.VA, SYSFRAME.VA; readers/fanuc_va.py, lang/REFERENCE.md §14).

Witnesses: the .VA layout is the controller's ASCII variable listing as public backup tools
parse and quote it (a section `[*NUMREG*]$NUMREG  Storage: ..  : ARRAY[999] OF Numeric Reg`
with `[i] = value  'comment'`; `[*POSREG*]$POSREG .. ARRAY[g,n] OF Position Reg` with
`[g,n] = 'comment'`, `Group: 1   Config: N U T, 0, 0, 0`, `X: .. Y: .. Z: ..`, `W: .. P: ..
R: ..`, joint entries `J1 = .. deg`, `'' Uninitialized`; `[*SYSTEM*]$MNUTOOL` / `$MNUFRAME`
the same per tool and user frame), seen alike in a real backup (rickycastr0/MFI_DEMO
NUMREG.VA/POSREG.VA, measured, not copied) and in the fixtures of independent backup viewers.
The meaning is the R-30iB Operator's Manual B-83284EN: a speed may be a register (`R[i]mm/sec`),
`Offset,PR[i]` shifts the position in the user frame, a move to `PR[i]` goes to the register's
position in the active frames, a position's rotation is R = Rz(R)·Ry(P)·Rx(W). Poses are checked
against numpy matrices built here from the saved numbers, not through the reader.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
from click.testing import CliRunner
from hypothesis import given, settings
from hypothesis import strategies as st

from rmot.backends.readers import ImportError_, read_files
from rmot.compiler.cli import cli

NUMREG = """[*NUMREG*]$NUMREG  Storage: SHADOW  Access: RW  : ARRAY[200] OF Numeric Reg
  [1] = 0  ''
  [24] = 800  'fast'
  [25] = 50.500000  'slow'
[*NUMREG*]$MAXREGNUM  Storage: CMOS  Access: RW  : INTEGER = 200
"""

POSREG = """[*POSREG*]$POSREG  Storage: SHADOW  Access: RW  : ARRAY[1,100] OF Position Reg
    [1,17] =   'above'
  Group: 1   Config: N U T, 0, 0, 0
  X:     0.000   Y:   -20.000   Z:   100.000
  W:     0.000   P:     0.000   R:     0.000
    [1,18] =   'tilt'
  Group: 1   Config: N U T, 0, 0, 0
  X:     0.000   Y:     0.000   Z:   100.000
  W:     5.000   P:     0.000   R:     0.000
    [1,19] =   '' Uninitialized
    [1,30] =   'home'
  Group: 1   Config: N U T, 0, 0, 0
  X:   400.000   Y:   -50.000   Z:   600.000
  W:   170.000   P:   -10.000   R:    -.500
    [1,31] =   'park'   Group: 1
  J1 =     0.000 deg   J2 =   -30.000 deg   J3 =    10.000 deg
  J4 =     0.000 deg   J5 =   -60.000 deg   J6 =     5.000 deg
[*POSREG*]$MAXPREGNUM  Storage: CMOS  Access: RW  : INTEGER = 100
"""

SYSFRAME = """[*SYSTEM*]$MNUFRAME  Storage: SHADOW  Access: RW  : ARRAY[1,9] OF POSITION
 [1,1] =
  Group: 1   Config: N D B, 0, 0, 0
  X:  1000.000   Y:   200.000   Z:     0.000
  W:     0.000   P:     0.000   R:    90.000
[*SYSTEM*]$MNUFRAMENUM  Storage: CMOS  Access: RW  : ARRAY[1] OF BYTE
  [1] = 1
[*SYSTEM*]$MNUTOOL  Storage: SHADOW  Access: RW  : ARRAY[1,10] OF POSITION
 [1,2] =
  Group: 1   Config: N D B, 0, 0, 0
  X:     0.000   Y:    10.000   Z:   150.000
  W:     0.000   P:    90.000   R:     0.000
"""

POS = """/POS
P[1]{
   GP1:
	UF : 1, UT : 2,		CONFIG : 'N U T, 0, 0, 0',
	X =   500.000  mm,	Y =     0.000  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
/END
"""

MOVES = ["UFRAME_NUM=1", "UTOOL_NUM=2", "J P[1] 100% FINE", "L P[1] R[24:fast]mm/sec CNT50 Offset,PR[17:above]",
         "L P[1] R[25:slow]mm/sec FINE", "L PR[30:home] 250mm/sec FINE", "J PR[31:park] 50% FINE",
         "L P[1] R[24:fast]mm/sec FINE"]


def _ls(name: str, body: list[str]) -> str:
    lines = "".join(f"{n:4d}:  {text} ;\n" for n, text in enumerate(body, 1))
    return f"/PROG  {name}\n/ATTR\n/MN\n{lines}{POS}"


def _files(folder: Path, programs: dict[str, list[str]], saved: dict[str, str]) -> list[str]:
    paths = []
    for name, body in programs.items():
        (folder / f"{name.lower()}.ls").write_text(_ls(name, body))
        paths.append(str(folder / f"{name.lower()}.ls"))
    for name, text in saved.items():
        (folder / name).write_text(text)
        paths.append(str(folder / name))
    return paths


def _import(folder: Path, paths: list[str], code: int = 0) -> tuple[str, str, str]:
    out = folder / "imported.rmot"
    result = CliRunner().invoke(cli, ["import", *paths, "-o", str(out)], catch_exceptions=False)
    assert result.exit_code == code, result.output
    if code:
        return "", "", result.output
    stub = folder / "imported_cell.rmot"
    return out.read_text(), stub.read_text(), result.output


def _rotation(w: float, p: float, r: float) -> np.ndarray:
    """Rz(r)·Ry(p)·Rx(w), degrees (B-83284EN: W, P, R about the fixed x, y, z axes)."""
    a, b, c = (math.radians(v) for v in (w, p, r))
    rx = np.array([[1, 0, 0], [0, math.cos(a), -math.sin(a)], [0, math.sin(a), math.cos(a)]])
    ry = np.array([[math.cos(b), 0, math.sin(b)], [0, 1, 0], [-math.sin(b), 0, math.cos(b)]])
    rz = np.array([[math.cos(c), -math.sin(c), 0], [math.sin(c), math.cos(c), 0], [0, 0, 1]])
    return rz @ ry @ rx


def _pose_of(text: str) -> tuple[np.ndarray, np.ndarray]:
    """(position mm, rotation matrix) of an rmot `pose(x=..mm, y=..mm, z=..mm, q=(w, x, y, z))`."""
    m = re.search(r"pose\(x=(\S+)mm, y=(\S+)mm, z=(\S+)mm, q=\((\S+), (\S+), (\S+), (\S+)\)\)", text)
    assert m is not None, text
    x, y, z, qw, qx, qy, qz = (float(v) for v in m.groups())
    rot = np.array([
        [1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw), 2 * (qx * qz + qy * qw)],
        [2 * (qx * qy + qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw)],
        [2 * (qx * qz - qy * qw), 2 * (qy * qz + qx * qw), 1 - 2 * (qx * qx + qy * qy)]])
    return np.array([x, y, z]), rot


def test_registers_and_frames_a_backup_saved_are_read(tmp_path: Path) -> None:
    """Register speeds, a translating offset register, moves to position registers and the tool
    and user frame the program selects are read at their saved values; W543 names each register
    once, at its first use."""
    program, cell, output = _import(tmp_path, _files(tmp_path, {"PICK": MOVES},
                                                     {"NUMREG.VA": NUMREG, "POSREG.VA": POSREG, "SYSFRAME.VA": SYSFRAME}))
    assert "native fanuc" not in program
    assert "  move linear shift(pick_p1, y=-20 mm, z=100 mm) speed 800 mm/s zone 50 mm\n" in program
    assert "  move linear pick_p1 speed 50.5 mm/s zone fine\n" in program
    assert "  move linear home speed 250 mm/s zone fine\n" in program
    assert "  move joint park speed 50 %" in program
    assert "target park = joints(0, -30, 10, 0, -60, 5) deg" in program
    position, rotation = _pose_of(next(ln for ln in program.splitlines() if "target home" in ln))
    assert np.allclose(position, [400, -50, 600], atol=1e-6)
    assert np.allclose(rotation, _rotation(170, -10, -0.5), atol=1e-9)
    tool = next(ln for ln in cell.splitlines() if ln.strip().startswith("tool utool2"))
    position, rotation = _pose_of(tool)
    assert np.allclose(position, [0, 10, 150]) and np.allclose(rotation, _rotation(0, 90, 0), atol=1e-9)
    assert "controller's" not in tool  # a value, not a placeholder
    position, rotation = _pose_of(next(ln for ln in cell.splitlines() if ln.strip().startswith("frame uframe1")))
    assert np.allclose(position, [1000, 200, 0]) and np.allclose(rotation, _rotation(0, 0, 90), atol=1e-9)
    warned = re.findall(r"pick\.ls:(\d+):\d+: warning\[W543\]: `([A-Z]+\[\d+\])` is read at ([^,]+(?:, [^,)]+)*\)?)", output)
    assert [(line, name) for line, name, _ in warned] == [
        ("7", "PR[17]"), ("7", "R[24]"), ("8", "R[25]"), ("9", "PR[30]"), ("10", "PR[31]")]
    assert "R[24]` is read at 800, the value the controller saved" in output and "NUMREG.VA:3)" in output
    result = CliRunner().invoke(cli, ["check", str(tmp_path / "imported.rmot")], catch_exceptions=False)
    assert result.exit_code in (0, 1), result.output  # reach findings on the stub's arm, never refused


def test_a_register_a_program_writes_stays_a_run_time_value(tmp_path: Path) -> None:
    """A register any program given writes (here a called one, and a FOR counter) is not read at
    its saved value: the move stays native and says which program sets it."""
    paths = _files(tmp_path, {"PICK": [*MOVES[:5], MOVES[7], "CALL SETUP"], "SETUP": ["PR[17:above]=LPOS", "R[25:slow]=10",
                                                                         "FOR R[24]=1 TO 3", "ENDFOR"]},
                   {"NUMREG.VA": NUMREG, "POSREG.VA": POSREG})
    program, _, output = _import(tmp_path, paths)
    assert 'native fanuc "L P[1] R[24:fast]mm/sec CNT50 Offset,PR[17:above] ;"' in program
    for register in ("PR[17]", "R[25]", "R[24]"):
        assert f"`{register}` is set at run time by a program given" in output
    assert "W543" not in output
    doc = read_files([paths[0], paths[2], paths[3]])  # without SETUP: both are the backup's values
    assert not [d for d in doc.diagnostics if d.code.id == "W510" and "L P[1]" in d.message]


def test_a_register_written_through_another_keeps_every_register_run_time(tmp_path: Path) -> None:
    program, _, output = _import(tmp_path, _files(tmp_path, {"PICK": [*MOVES[:5], "R[R[1]]=5"]},
                                                  {"NUMREG.VA": NUMREG, "POSREG.VA": POSREG}))
    assert program.count("native fanuc \"L P[1]") == 2 and "W543" not in output
    assert "writes a register through another (`R[R[i]]=`)" in output


def test_what_a_backup_cannot_give_stays_native_with_its_reason(tmp_path: Path) -> None:
    body = ["J P[1] 100% FINE", "L P[1] 100mm/sec FINE Offset,PR[18:tilt]", "L PR[19] 100mm/sec FINE",
            "L P[1] R[26]mm/sec FINE", "L P[1] 100mm/sec FINE Offset,PR[40]"]
    program, _, output = _import(tmp_path, _files(tmp_path, {"PICK": body}, {"NUMREG.VA": NUMREG, "POSREG.VA": POSREG}))
    assert program.count("native fanuc") == 5 and program.count('native fanuc "P[1]{ GP1:') == 1  # 4 lines, P[1]'s record
    assert "the offset PR[18] holds a saved rotation" in output
    assert "`PR[19]` is saved as Uninitialized" in output
    assert "`R[26]` is the controller's register and no file given holds its value" in output
    assert "`PR[40]` is the controller's register" in output


def test_without_a_backup_the_reason_names_the_file_that_holds_the_register(tmp_path: Path) -> None:
    program, cell, output = _import(tmp_path, _files(tmp_path, {"PICK": MOVES}, {}))
    assert program.count("native fanuc") == 6 and program.count('native fanuc "P[1]{ GP1:') == 1  # 5 lines, P[1]'s record
    assert "give the backup's NUMREG.VA too" in output and "give the backup's POSREG.VA too" in output
    assert "the controller's UTOOL[2]: not in the files" in cell  # the placeholder SYSFRAME.VA would fill


def test_a_damaged_or_foreign_va_file_is_a_located_error(tmp_path: Path) -> None:
    program = _files(tmp_path, {"PICK": MOVES}, {})
    for name, text, message, line in [
        ("NUMREG.VA", NUMREG.replace("800", "1e999"), "register R[24] must be a finite number", 3),
        ("POSREG.VA", POSREG.replace("600.000", "9e999"), "position [1,30] must hold finite numbers", 11),
        ("SYSVARS.VA", "[*SYSTEM*]$ACC_MAXLMT  Storage: CMOS  Access: RW  : INTEGER = 100\n", "saves $NUMREG", 1),
    ]:
        (tmp_path / name).write_text(text)
        _, _, output = _import(tmp_path, [*program, str(tmp_path / name)], code=2)
        assert f"{name}:{line}:1: error[E510]" in output and message in output, output
        (tmp_path / name).unlink()
    (tmp_path / "NUMREG.VA").write_text(NUMREG)
    _, _, output = _import(tmp_path, [str(tmp_path / "NUMREG.VA")], code=2)
    assert "error[E510]" in output and "give the .ls too" in output


_NUMBER = st.floats(min_value=-9999, max_value=9999, allow_nan=False).map(lambda v: round(v, 3))


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(_NUMBER, _NUMBER, _NUMBER, _NUMBER, _NUMBER, _NUMBER), min_size=1, max_size=5))
def test_saved_positions_read_back_as_written(values: list[tuple[float, ...]]) -> None:
    """Position registers written in the listing's layout (TP prints fixed 3 decimals, a value
    below 1 without its leading zero) read back to the same numbers."""
    from rmot.backends.readers.fanuc_va import empty, read_va

    def fixed(v: float) -> str:
        text = f"{v:.3f}"
        return text.replace("0.", ".", 1) if abs(v) < 1 else text

    text = "[*POSREG*]$POSREG  Storage: SHADOW  Access: RW  : ARRAY[1,100] OF Position Reg\n" + "".join(
        f"    [1,{k}] =   'p{k}'\n  Group: 1   Config: N U T, 0, 0, 0\n"
        f"  X: {fixed(x)}   Y: {fixed(y)}   Z: {fixed(z)}\n  W: {fixed(w)}   P: {fixed(p)}   R: {fixed(r)}\n"
        for k, (x, y, z, w, p, r) in enumerate(values, 1))
    data = empty()
    read_va("POSREG.VA", text, data)
    for k, v in enumerate(values, 1):
        saved = data.posreg[k]
        assert saved is not None and saved.comment == f"p{k}"
        assert saved.xyzwpr == tuple(float(f"{a:.3f}") for a in v)


def test_truncated_va_files_are_read_or_refused_never_a_traceback(tmp_path: Path) -> None:
    from rmot.backends.readers.fanuc_va import empty, read_va

    for text in (NUMREG, POSREG, SYSFRAME):
        for cut in range(0, len(text), 7):
            try:
                read_va("X.VA", text[:cut], empty())
            except ImportError_ as exc:
                assert exc.diagnostic.code.id == "E510"


def _moves(program: str) -> list[str]:
    lines = [ln.split("   #")[0].strip() for ln in program.splitlines()]
    return [ln for ln in lines if ln.startswith(("move ", 'native fanuc "L', 'native fanuc "J'))]


def test_an_offset_the_program_builds_in_straight_line_code_is_read(tmp_path: Path) -> None:
    """`PR[k]=LPOS-LPOS` (a Cartesian zero), element writes of numbers (the pendant writes
    `PR[100,3:Offset]=(-100)`), the move with `Offset,PR[k]`, then a reset: each move shifted by
    what PR[k] holds at its line (it was read unshifted, the offset lost without a word)."""
    body = ["PR[100:Offset]=LPOS-LPOS", "PR[100,3:Offset]=(-100)", "PR[100,2]=20", "J P[1] 100% FINE",
            "L P[1] 200mm/sec FINE Offset,PR[100:Offset]", "PR[100,3:Offset]=0", "L P[1] 200mm/sec FINE Offset,PR[100]"]
    program, _, output = _import(tmp_path, _files(tmp_path, {"PICK": body}, {}))
    assert _moves(program)[1:] == ["move linear shift(pick_p1, y=20 mm, z=-100 mm) speed 200 mm/s zone fine",
                                   "move linear shift(pick_p1, y=20 mm) speed 200 mm/s zone fine"]
    assert "W543" not in output  # the program's own value, not a backup's


def test_an_offset_built_where_the_import_cannot_follow_it_stays_native(tmp_path: Path) -> None:
    """A clear inside a branch, a call between the clear and the move, a turning element, and a
    value from a register: the move stays native with the reason."""
    for body, why in [
        (["IF DI[1]=ON,JMP LBL[1]", "PR[9]=LPOS-LPOS", "LBL[1]", "L P[1] 200mm/sec FINE Offset,PR[9]"],
         "the program sets PR[9] where the import does not follow its value"),
        (["PR[9]=LPOS-LPOS", "PR[9,3]=50", "CALL OTHER", "L P[1] 200mm/sec FINE Offset,PR[9]"],
         "the program sets PR[9] where the import does not follow its value"),
        (["PR[9]=LPOS-LPOS", "PR[9,6]=90", "L P[1] 200mm/sec FINE Offset,PR[9]"], "the offset PR[9] turns"),
        (["PR[9]=LPOS-LPOS", "PR[9,3]=R[4]", "L P[1] 200mm/sec FINE Offset,PR[9]"],
         "the program sets PR[9] where the import does not follow its value"),
    ]:
        program, _, output = _import(tmp_path, _files(tmp_path, {"PICK": ["J P[1] 100% FINE", *body]}, {}))
        assert _moves(program)[-1] == 'native fanuc "L P[1] 200mm/sec FINE Offset,PR[9] ;"', program
        assert why in output, output


def test_a_tool_offset_moves_along_the_tool_at_the_target(tmp_path: Path) -> None:
    """`Tool_Offset,PR[k]` shifts the position along the tool frame at the target, `Offset,PR[k]`
    along the user frame (B-83284EN, tool offset and offset instructions): the compiler's resolved
    targets (`rmot ir`) against p + R(W, P, R)·d and p + d computed here."""
    tilted = POS.replace("X =   500.000  mm,\tY =     0.000  mm,\tZ =   300.000  mm,",
                         "X =   900.000  mm,\tY =   100.000  mm,\tZ =   700.000  mm,").replace(
        "W =   180.000 deg,\tP =     0.000 deg,\tR =     0.000 deg", "W =   150.000 deg,\tP =    20.000 deg,\tR =    10.000 deg")
    assert tilted != POS
    body = ["PR[100:Offset]=LPOS-LPOS", "PR[100,3:Offset]=(-100)", "PR[100,1]=30", "J P[1] 100% FINE",
            "L P[1] 200mm/sec FINE Tool_Offset,PR[100:Offset]", "L P[1] 200mm/sec FINE Offset,PR[100:Offset]"]
    lines = "".join(f"{n:4d}:  {text} ;\n" for n, text in enumerate(body, 1))
    (tmp_path / "tofs.ls").write_text(f"/PROG  TOFS\n/ATTR\n/MN\n{lines}{tilted}")
    program, _, _ = _import(tmp_path, [str(tmp_path / "tofs.ls")])
    assert "move linear tofs_p1 * pose(x=30 mm, z=-100 mm) speed 200 mm/s" in program
    result = CliRunner().invoke(cli, ["ir", str(tmp_path / "imported.rmot")], catch_exceptions=False)
    reached = [np.array([float(v) for v in m.group(1).split()]) * 1000
               for m in re.finditer(r"move linear to \[([-\d.e ]+) \|", result.output)]
    p, d = np.array([900.0, 100.0, 700.0]), np.array([30.0, 0.0, -100.0])
    assert np.allclose(reached[0], p + _rotation(150, 20, 10) @ d, atol=1e-3)
    assert np.allclose(reached[1], p + d, atol=1e-3)


def test_values_the_program_sets_in_straight_line_code_are_read(tmp_path: Path) -> None:
    """A generated program (tab-numbered lines) that sets its speed register and all six elements
    of its offset register with numbers before its moves: both are known there, without a
    backup; after a call the speed register is the callee's to change."""
    body = ["R[10]=200", "PR[15,1]=0", "PR[15,2]=0", "PR[15,3]=-5", "PR[15,4]=0", "PR[15,5]=0", "PR[15,6]=0",
            "J P[1] 100% CNT60 Tool_Offset,PR[15]", "L P[1] R[10]mm/sec CNT60 Tool_Offset,PR[15]",
            "CALL OTHER", "L P[1] R[10]mm/sec CNT60"]
    lines = "".join(f"\t{n}:  {text} \t;\n" for n, text in enumerate(body, 1))
    (tmp_path / "gen.ls").write_text(f"/PROG GEN\n/ATTR\n/MN\n{lines}{POS}")
    program, _, output = _import(tmp_path, [str(tmp_path / "gen.ls")])
    assert _moves(program) == [
        "move joint gen_p1 * pose(z=-5 mm) config(shoulder=front, elbow=up, wrist=flip) speed 100 % zone 60 mm",
        "move linear gen_p1 * pose(z=-5 mm) speed 200 mm/s zone 60 mm",
        'native fanuc "L P[1] R[10]mm/sec CNT60 ;"']
    assert "`R[10]` is set at run time by a program given" in output


def test_a_frame_a_register_selects_keeps_the_moves_after_it_native(tmp_path: Path) -> None:
    """`UFRAME_NUM=R[5]` (a frame chosen at run time): the moves after it were read in the frame
    selected before (the robot base), without a word; now they stay native until a number
    selects the frame again."""
    body = ["UFRAME_NUM=R[5:frame]", "UTOOL_NUM=1", "J P[1] 100% FINE", "UFRAME_NUM=1", "L P[1] 100mm/sec FINE"]
    program, _, output = _import(tmp_path, _files(tmp_path, {"PICK": body}, {}))
    assert _moves(program) == ['native fanuc "J P[1] 100% FINE ;"', "move linear pick_p1 speed 100 mm/s zone fine"]
    assert "the frame or tool here depends on `UFRAME_NUM=R[5:frame]`: which one is known only at run time" in output
    assert "\n  frame uframe1\n" in program


def test_a_tool_a_branch_selects_keeps_the_moves_after_it_native(tmp_path: Path) -> None:
    """`IF (DI[1]=ON) THEN UTOOL_NUM=2 ENDIF`: after the IF the tool is 2 only where the arm ran
    (it was read as 2 for every later move); a number selecting it again makes it known."""
    body = ["UTOOL_NUM=1", "J P[1] 100% FINE", "IF (DI[1]=ON) THEN", "UTOOL_NUM=2", "ENDIF", "L P[1] 100mm/sec FINE",
            "UTOOL_NUM=2", "L P[1] 100mm/sec FINE"]
    program, _, output = _import(tmp_path, _files(tmp_path, {"PICK": body}, {}))
    assert _moves(program) == ["move joint pick_p1 config(shoulder=front, elbow=up, wrist=flip) speed 100 % zone fine",
                               'native fanuc "L P[1] 100mm/sec FINE ;"', "move linear pick_p1 speed 100 mm/s zone fine"]
    assert "the frame or tool here depends on `IF (DI[1]=ON) THEN`" in output
