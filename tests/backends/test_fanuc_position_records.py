"""A TP line `rmot import` keeps native that moves to a position of its program compiles back
for Fanuc with that position's record (readers/position_records.py, backends/fanuc_records.py,
lang/REFERENCE.md §5 `native`, §14).

Witness: the compiled .ls is read here with plain regular expressions, and the flange pose each
native move asks for is computed with numpy from the numbers of the files alone, in the source
program and in the compiled one: UFRAME[uf] · P · UTOOL[ut]⁻¹, with the frame and tool the lines
before the move select and the values the programs write into them (`PR[i,j]=v`, then
`UFRAME[n]=PR[i]`), each pose's rotation Rz(R)·Ry(P)·Rx(W) (B-83284EN, position data). The
controller runs a move only in the frame and tool its position records (INTP-250/252), so the
two programs move the robot alike exactly when those flange poses agree and the record's UF/UT
are the numbers selected at the line.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
from click.testing import CliRunner

from rmot.compiler.cli import cli

FRAME = [1000.0, 200.0, 0.0, 0.0, 0.0, 90.0]  # UFRAME[1], x y z mm, w p r deg
TOOL = [0.0, 10.0, 150.0, 0.0, 90.0, 0.0]  # UTOOL[2]
POINTS = {1: [500.0, 0.0, 300.0, 180.0, 0.0, 0.0], 2: [450.5, -20.25, 310.0, 179.5, 1.5, -30.0],
          3: [420.0, 35.0, 280.0, -178.0, 2.0, 45.0]}
TAUGHT_IN = {1: 1, 2: 1, 3: 0}  # the UFRAME each position records (UT 2 all)


def _setup(kind: str, n: int, pr: int, values: list[float]) -> list[str]:
    return [f"PR[{pr}]=LPOS"] + [f"PR[{pr},{i}]={v}" for i, v in enumerate(values, 1)] + [f"{kind}[{n}]=PR[{pr}]"]


def _pos(points: dict[int, list[float]], labels: dict[int, str] | None = None) -> str:
    out = ["/POS"]
    for n, (x, y, z, w, p, r) in points.items():
        label = f':"{labels[n]}"' if labels and n in labels else ""
        out += [f"P[{n}{label}]{{", "   GP1:", f"\tUF : {TAUGHT_IN.get(n, 1)}, UT : 2,\t\tCONFIG : 'N U T, 0, 0, 0',",
                f"\tX = {x:9.3f}  mm,\tY = {y:9.3f}  mm,\tZ = {z:9.3f}  mm,",
                f"\tW = {w:9.3f} deg,\tP = {p:9.3f} deg,\tR = {r:9.3f} deg", "};"]
    return "\n".join(out + ["/END", ""])


def _ls(name: str, body: list[str], points: dict[int, list[float]], labels: dict[int, str] | None = None) -> str:
    lines = "".join(f"{n:4d}:  {text} ;\n" for n, text in enumerate(body, 1))
    return f"/PROG  {name}\n/ATTR\n/MN\n{lines}{_pos(points, labels)}"


MAIN = [*_setup("UFRAME", 1, 90, FRAME), *_setup("UTOOL", 2, 91, TOOL), "UFRAME_NUM=1", "UTOOL_NUM=2",
        "J P[1] 100% FINE", "L P[2] 100mm/sec FINE Offset,PR[40]", "UFRAME_NUM=0", "L P[3] R[26]mm/sec CNT50", "UFRAME_NUM=1",
        "L P[1] 200mm/sec FINE"]


def _round_trip(tmp_path: Path, files: dict[str, str]) -> tuple[str, dict[str, str]]:
    """The imported program's text and the compiled .ls files by name."""
    paths = []
    for name, text in files.items():
        (tmp_path / name).write_text(text)
        paths.append(str(tmp_path / name))
    result = CliRunner().invoke(cli, ["import", *paths, "-o", str(tmp_path / "p.rmot")], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    result = CliRunner().invoke(cli, ["compile", str(tmp_path / "p.rmot"), "--target", "fanuc", "-o", str(tmp_path / "out"),
                                      "--allow-findings", "--no-cache"], catch_exceptions=False)
    assert result.exit_code in (0, 1) and "error[E4" not in result.output, result.output
    compiled = {p.name: p.read_text() for p in (tmp_path / "out" / "fanuc").glob("*.ls")}
    return (tmp_path / "p.rmot").read_text(), compiled


def _matrix(xyzwpr: list[float]) -> np.ndarray:
    """The pose of X, Y, Z (mm), W, P, R (deg): rotation Rz(R)·Ry(P)·Rx(W)."""
    a, b, c = (math.radians(v) for v in xyzwpr[3:])
    rx = np.array([[1, 0, 0], [0, math.cos(a), -math.sin(a)], [0, math.sin(a), math.cos(a)]])
    ry = np.array([[math.cos(b), 0, math.sin(b)], [0, 1, 0], [-math.sin(b), 0, math.cos(b)]])
    rz = np.array([[math.cos(c), -math.sin(c), 0], [math.sin(c), math.cos(c), 0], [0, 0, 1]])
    out = np.eye(4)
    out[:3, :3], out[:3, 3] = rz @ ry @ rx, xyzwpr[:3]
    return out


def _instructions(ls: str) -> list[str]:
    return [m.group(1).strip() for m in re.finditer(r"(?m)^\s*\d+:\s*(.*?)\s*;\s*$", ls.split("/POS")[0])]


def _written(ls: str, kind: str) -> dict[int, list[float]]:
    """The tool or frame data the program writes: `PR[i,j]=v` lines, then `KIND[n]=PR[i]`."""
    registers: dict[int, list[float]] = {}
    out = {}
    for line in _instructions(ls):
        if m := re.fullmatch(r"PR\[(\d+)\]=LPOS", line):
            registers[int(m.group(1))] = [0.0] * 6
        elif m := re.fullmatch(r"PR\[(\d+),(\d)\]=(\S+)", line):
            registers[int(m.group(1))][int(m.group(2)) - 1] = float(m.group(3))
        elif m := re.fullmatch(rf"{kind}\[(\d+)\]=PR\[(\d+)\]", line):
            out[int(m.group(1))] = registers[int(m.group(2))]
    return out


def _records(ls: str) -> dict[int, tuple[str, int, int, list[float]]]:
    """/POS records: number -> (label, UF, UT, X..R)."""
    out = {}
    for m in re.finditer(r"P\[(\d+)((?::\"[^\"]*\")?)\]\{\s*GP1:\s*UF : (\d+), UT : (\d+),[^\n]*\n(.*?)\};", ls, re.S):
        values = [float(v) for v in re.findall(r"[XYZWPR] =\s*(\S+)\s+(?:mm|deg)", m.group(5))]
        out[int(m.group(1))] = (m.group(2), int(m.group(3)), int(m.group(4)), values)
    return out


def _native_moves(ls: str) -> list[tuple[str, int, int, int]]:
    """Each move to a position with the position and the UFRAME_NUM, UTOOL_NUM in force there."""
    selected, out = {"UFRAME": -1, "UTOOL": -1}, []
    for line in _instructions(ls):
        if m := re.fullmatch(r"(UFRAME|UTOOL)_NUM=(\d+)", line):
            selected[m.group(1)] = int(m.group(2))
        elif m := re.match(r"[JL] P\[(\d+)", line):
            out.append((line, int(m.group(1)), selected["UFRAME"], selected["UTOOL"]))
    return out


def test_a_native_move_goes_to_its_position_in_its_frame_with_its_tool(tmp_path: Path) -> None:
    program, compiled = _round_trip(tmp_path, {"main.ls": _ls("PICK", MAIN, POINTS)})
    assert program.count('native fanuc "L P[') == 2 and program.count('native fanuc "P[') == 2  # P[2], P[3] records
    ls = compiled["PICK.ls"]
    frames, tools, records = _written(ls, "UFRAME"), _written(ls, "UTOOL"), _records(ls)
    moves = _native_moves(ls)
    assert len(moves) == 4 and len(records) == 4  # two of rmot's own moves (to P[1]), two native ones
    natives = [m for m in moves if "Offset,PR[40]" in m[0] or "R[26]" in m[0]]
    for (line, k, uf, ut), source in zip(natives, (2, 3)):
        label, rec_uf, rec_ut, values = records[k]
        assert (rec_uf, rec_ut) == (uf, ut), line  # the controller's frame check passes
        frame = _matrix(FRAME) if TAUGHT_IN[source] else np.eye(4)  # UFRAME 0: the robot's world
        want = frame @ _matrix(POINTS[source]) @ np.linalg.inv(_matrix(TOOL))
        got = (_matrix(frames[uf]) if uf else np.eye(4)) @ _matrix(values) @ np.linalg.inv(_matrix(tools[ut]))
        assert np.allclose(got, want, atol=1e-6), line
    assert [n for _, n, _, _ in moves].count(natives[0][1]) == 1  # the record's number is the native line's alone


def test_each_program_moves_to_its_own_records_and_labels_are_kept(tmp_path: Path) -> None:
    """MAIN and SUB both name P[2]; each compiled program's native line goes to its own data."""
    sub_points = {2: [300.0, -100.0, 250.0, 180.0, 0.0, 10.0]}
    files = {"main.ls": _ls("PICK", [*MAIN[:-4], "CALL SUB"], POINTS, {2: "above"}),
             "sub.ls": _ls("SUB", ["L P[2] 50mm/sec FINE Offset,PR[41]"], sub_points)}
    _, compiled = _round_trip(tmp_path, files)
    sub_name = next(name for name in compiled if name != "PICK.ls")
    for name, points in (("PICK.ls", POINTS), (sub_name, sub_points)):
        ls = compiled[name]
        records = _records(ls)
        line, k, _, _ = next(m for m in _native_moves(ls) if "Offset" in m[0])
        assert records[k][3] == points[2], (name, line)
        assert records[k][0] == (':"above"' if name == "PICK.ls" else "")


def _compile_edited(tmp_path: Path, old: str, new: str) -> str:
    (tmp_path / "main.ls").write_text(_ls("PICK", MAIN, POINTS))
    result = CliRunner().invoke(cli, ["import", str(tmp_path / "main.ls"), "-o", str(tmp_path / "p.rmot")])
    assert result.exit_code == 0, result.output
    text = (tmp_path / "p.rmot").read_text()
    assert old in text
    (tmp_path / "p.rmot").write_text(text.replace(old, new, 1))
    result = CliRunner().invoke(cli, ["compile", str(tmp_path / "p.rmot"), "--target", "fanuc", "-o", str(tmp_path / "out"),
                                      "--allow-findings", "--no-cache"])
    assert result.exit_code != 0 and not (tmp_path / "out" / "fanuc").exists(), result.output
    assert "Traceback" not in result.output
    return result.output


def test_a_record_rmot_cannot_vouch_for_is_refused_at_the_line(tmp_path: Path) -> None:
    unwritable = "native line names P[2], whose record cannot be written: "
    cases = [
        ("UF : uframe1", "UF : nowhere", unwritable + "its UF `nowhere` names no frame of the cell"),
        ("UT : utool2", "UT : hammer", unwritable + "its UT `hammer` names no tool of robot 'r1'"),
        ("X = 450.500 mm", "X = abc mm", unwritable + "`X = abc mm` is not a `KEY : value` or `KEY = number mm|deg` item"),
        ("X = 450.500 mm", "X = 1e999 mm", unwritable + "`X = 1e999 mm` is not a"),
        ("R = -30.000 deg }", "R = -30.000 deg GP2: UF : 0, UT : 1, J1= 5.000 deg }", unwritable + "it moves motion group 2"),
        ("R = -30.000 deg }", "R = -30.000 deg, E1= 100.000 mm }", unwritable + "it gives an extended axis of the arm's group"),
        ("X = 450.500 mm, Y", "Y", unwritable + "it must give UF, UT and X..R or J1..J6 once each"),
        ('native fanuc "P[2]{', 'native fanuc "P[9]{', "native line names P[2], a position of the program it came from "
                                                       "with no native position record `P[2]{GP1: ..}` in this program"),
    ]
    for k, (old, new, message) in enumerate(cases):
        folder = tmp_path / str(k)
        folder.mkdir()
        output = _compile_edited(folder, old, new)
        assert re.search(r"p\.rmot:\d+:\d+: error\[E411\]: fanuc: " + re.escape(message), output), (k, output)


def test_two_records_of_one_position_that_differ_are_refused(tmp_path: Path) -> None:
    (tmp_path / "main.ls").write_text(_ls("PICK", MAIN, POINTS))
    CliRunner().invoke(cli, ["import", str(tmp_path / "main.ls"), "-o", str(tmp_path / "p.rmot")])
    text = (tmp_path / "p.rmot").read_text()
    record = next(line for line in text.splitlines() if 'native fanuc "P[2]{' in line)
    text = text.replace(record, record + "\n" + record.replace("X = 450.500 mm", "X = 451.500 mm"))
    (tmp_path / "p.rmot").write_text(text)
    result = CliRunner().invoke(cli, ["compile", str(tmp_path / "p.rmot"), "--target", "fanuc", "-o", str(tmp_path / "out")])
    assert "error[E411]: fanuc: native line names P[2], whose record cannot be written: two records give P[2] different data" \
        in result.output


def test_positions_taught_in_different_frames_on_one_line_are_refused(tmp_path: Path) -> None:
    """A circular move kept native names two positions; their records select one frame and tool."""
    body = [*MAIN[:-6], "C P[2] : P[3] 100mm/sec FINE Offset,PR[40]"]  # P[3] taught in UFRAME 0, P[2] in 1
    (tmp_path / "main.ls").write_text(_ls("PICK", body, POINTS))
    result = CliRunner().invoke(cli, ["import", str(tmp_path / "main.ls"), "-o", str(tmp_path / "p.rmot")])
    assert result.exit_code == 0, result.output
    result = CliRunner().invoke(cli, ["compile", str(tmp_path / "p.rmot"), "--target", "fanuc", "-o", str(tmp_path / "out")])
    assert "native line names positions taught in different frames or tools (P[2], P[3])" in result.output, result.output


def test_a_native_line_of_a_program_inlined_at_its_call_is_refused(tmp_path: Path) -> None:
    """The palletizing example's callee moves by the loop's offset, so the import reads it
    inlined in its caller. A line of it kept native names the callee's P[2], which is not the
    caller's P[2]: the caller's records cannot serve it, so it is refused, never pointed at
    the caller's data."""
    root = Path(__file__).resolve().parents[2]
    result = CliRunner().invoke(cli, ["compile", str(root / "examples" / "palletizing.rmot"), "--target", "fanuc",
                                      "-o", str(tmp_path / "built")], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    folder = tmp_path / "built" / "fanuc"
    callee = folder / "PALLETIZING_DOWN_TO_2_L1.ls"
    line = "  14:  L P[2] 150mm/sec FINE Offset,PR[61] ;"
    assert line in callee.read_text()
    callee.write_text(callee.read_text().replace(line, "  14:  L P[2] R[26]mm/sec FINE Offset,PR[61] ;"))
    main = folder / "PALLETIZING.ls"
    files = [str(main)] + sorted(str(p) for p in folder.glob("*.ls") if p != main)
    result = CliRunner().invoke(cli, ["import", *files, "-o", str(tmp_path / "p.rmot")], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    program = (tmp_path / "p.rmot").read_text()
    assert 'native fanuc "L P[2] R[26]mm/sec FINE Offset,PR[61] ;"' in program and 'native fanuc "P[' not in program
    result = CliRunner().invoke(cli, ["compile", str(tmp_path / "p.rmot"), "--target", "fanuc", "-o", str(tmp_path / "out")])
    assert "error[E411]: fanuc: native line names P[2], a position of the program it came from with no native position " \
           "record" in result.output, result.output


def test_with_a_cell_the_record_takes_the_cells_numbers(tmp_path: Path) -> None:
    """--cell numbers the tool and frame as the controller does (`number n`): the compiled
    record and the selection before its line are the source's own numbers."""
    (tmp_path / "cell.rmot").write_text(
        "cell c {\n  robot r1 = fanuc_m20ia\n"
        "  tool utool2 = none tcp pose(x=0mm, y=10mm, z=150mm, ry=90deg) number 2 on r1\n"
        "  frame uframe1 = pose(x=1000mm, y=200mm, rz=90deg) number 1\n}\n")
    (tmp_path / "main.ls").write_text(_ls("PICK", MAIN[16:], POINTS))
    result = CliRunner().invoke(cli, ["import", str(tmp_path / "main.ls"), "--cell", str(tmp_path / "cell.rmot"),
                                      "-o", str(tmp_path / "p.rmot")], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    result = CliRunner().invoke(cli, ["compile", str(tmp_path / "p.rmot"), "--target", "fanuc", "-o", str(tmp_path / "out"),
                                      "--allow-findings", "--no-cache"], catch_exceptions=False)
    assert "error[E4" not in result.output, result.output
    ls = (tmp_path / "out" / "fanuc" / "PICK.ls").read_text()
    records = _records(ls)
    natives = [m for m in _native_moves(ls) if "Offset,PR[40]" in m[0] or "R[26]" in m[0]]
    assert [(records[k][1:], uf, ut) for _, k, uf, ut in natives] == [((1, 2, POINTS[2]), 1, 2), ((0, 2, POINTS[3]), 0, 2)]


def test_compiled_back_the_controllers_tools_and_frames_keep_their_numbers(tmp_path: Path) -> None:
    """A program that selects UFRAME 1 and UTOOL 2 and sets neither: the stub gives them their
    numbers (`number 1`, `number 2`), so the program compiled back selects the slots the source
    selected and writes none of them. Without the numbers it selected the first free slots and
    wrote the stub's placeholders into them (W416), over the controller's own data. The witness
    is the source file's own selections."""
    source = _ls("PICK", MAIN[16:], POINTS)
    _, compiled = _round_trip(tmp_path, {"main.ls": source})
    stub = (tmp_path / "p_cell.rmot").read_text()
    assert " number 2 on r1  # the controller's UTOOL[2]" in stub and " number 1  # the controller's UFRAME[1]" in stub
    ls = compiled["PICK.ls"]
    selections = r"\b(UTOOL_NUM|UFRAME_NUM)=(\d+)"
    assert set(re.findall(selections, ls)) == set(re.findall(selections, source)) == {
        ("UFRAME_NUM", "1"), ("UFRAME_NUM", "0"), ("UTOOL_NUM", "2")}
    assert not [line for line in _instructions(ls) if re.match(r"(UTOOL|UFRAME)\[\d+\]\s*=", line)]  # comments aside
