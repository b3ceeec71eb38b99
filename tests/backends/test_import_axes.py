"""External axes read back: compile -> `rmot import --cell` -> compile of the track and
positioner examples means the same program (readers/axes.py).

Witnesses (none of them the readers under test): the planner's own JSON plan of the original and
of the imported program (the round-trip harness of test_import_round_trip.py: every
instruction's kind, planned joints, branch, TCP pose and timing, and the cycle time), and each
move's external-axis values in that plan (`ext`, mm or deg), which the imported program must reproduce
to 0.001 mm / 0.001 deg. URScript and VAL3 have no external axes: compiling the examples for
them is refused (E607), so there is nothing to round-trip there.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest
from click.testing import CliRunner
from test_import_round_trip import MAIN_FILE, _angle_deg, _compile, _leaves, _same_instruction

from rmot.compiler.cli import cli

ROOT = Path(__file__).resolve().parents[2]
AXES_EXAMPLES = ["track_tending", "weld_positioner"]
VENDORS = ["rapid", "krl", "fanuc", "inform"]


def _import(files: list[Path], out: Path, cell: Path | None) -> tuple[int, str]:
    args = ["import", *map(str, files), "-o", str(out)] + (["--cell", str(cell)] if cell else [])
    result = CliRunner().invoke(cli, args, catch_exceptions=False)
    return result.exit_code, result.output


def _import_on_positioner(tmp_path: Path, name: str, text: str) -> str:
    """The import's output of a hand-written file `name` on weld_positioner's cell (exit 0)."""
    (tmp_path / name).write_text(text)
    code, output = _import([tmp_path / name], tmp_path / "out.rmot", ROOT / "examples" / "weld_positioner.rmot")
    assert code == 0, output
    return output



def _same_move(a: dict, b: dict, cycle: float) -> None:
    """The round-trip harness' comparison, the TCP pose judged here (its orientation by `_angle_deg`)."""
    pa, pb = a["tcp_pose"], b["tcp_pose"]
    if pa is not None and a["kind"] != "move_joint":  # a joint move's target is its joints
        assert math.dist(pa["position_mm"], pb["position_mm"]) <= 0.001, (a["source"], pa, pb)
        turn = _angle_deg(pa["quaternion_wxyz"], pb["quaternion_wxyz"])
        assert turn <= 0.001, (a["source"], turn)
    _same_instruction({**a, "tcp_pose": None}, {**b, "tcp_pose": None}, cycle)


def _axis_values(plan: dict) -> list[dict]:
    return [i.get("ext") or {} for i in _leaves(plan)]


@pytest.mark.parametrize(("vendor", "name"), [(v, n) for v in VENDORS for n in AXES_EXAMPLES])
def test_axes_round_trip(vendor: str, name: str, tmp_path: Path) -> None:
    _round_trip(vendor, ROOT / "examples" / f"{name}.rmot", tmp_path)


# a robot on a track and a positioner driven together (`with rail, pos`: the slots in that
# order), with targets in the robot's moving base, in the world and on the positioner
BOTH = """
cell both {
  track rail = linear(axis x, range(0mm, 4000mm)) speed 1500 mm/s accel 2000 mm/s^2 inform(pulses_per_mm=200) at pose()
  robot r1 = kuka_kr16 on rail at pose(z=250mm)
  positioner pos = axes(revolute(axis y, range(-90deg, 90deg)) speed 90 deg/s accel 180 deg/s^2 inform(pulses_per_deg=1000),
                        revolute(axis z, range(-360deg, 360deg)) speed 180 deg/s accel 360 deg/s^2 inform(pulses_per_deg=1000))
                   at pose(x=1800mm, z=700mm)
  frame work = pos * pose(z=40mm)
  tool torch = none tcp pose(z=300mm) on r1
}
program both on r1 with rail, pos {
  tool torch
  target home = joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg)
  move joint home
  move joint pose(x=600mm, z=400mm, rx=180deg) ext(rail=900mm, pos=(20deg, 90deg))
  move linear pose(x=600mm, y=50mm, z=300mm, rx=180deg) speed 100 mm/s
  move linear pose(x=1500mm, y=-50mm, z=550mm, rx=180deg) frame world speed 100 mm/s
  move joint pose(z=50mm, rx=180deg) frame work ext(pos=(20deg, 100deg))
  move joint home ext(rail=0mm)
}
"""


MOVE_AXES = "  move axes pos to (0deg, 180deg)\n  move joint home ext(rail=0mm)\n"


@pytest.mark.parametrize("vendor", VENDORS)
def test_track_and_positioner_round_trip(vendor: str, tmp_path: Path) -> None:
    source = tmp_path / "both.rmot"
    source.write_text(BOTH)
    _round_trip(vendor, source, tmp_path)


@pytest.mark.parametrize("vendor", VENDORS)
def test_move_axes_round_trip(vendor: str, tmp_path: Path) -> None:
    """`move axes` comes back: RAPID's `MoveExtJ jext, vmax\\T:=t, fine;` as `move axes` of the
    mechanism it moves; KRL, TP and INFORM write a joint move to the joints the arm holds with
    the new axis values (PTP to an E6AXIS, J, MOVJ with +MOVJ EC), which comes back as that joint
    move and plans the same."""
    source = tmp_path / "both.rmot"
    source.write_text(BOTH.replace("  move joint home ext(rail=0mm)\n", MOVE_AXES))
    _round_trip(vendor, source, tmp_path)


def _round_trip(vendor: str, example: Path, tmp_path: Path) -> None:
    name = example.stem
    before = _compile(example, example, vendor, tmp_path / "a")
    files = sorted((tmp_path / "a" / vendor).glob(MAIN_FILE[vendor]))
    imported = tmp_path / f"{name}_imported.rmot"
    code, output = _import(files, imported, example)
    assert code == 0, output
    assert " 0 kept native (100.0 % imported)" in output, output
    assert re.search(r"(?m)^program \w+ on r1 with \w+", imported.read_text()), imported.read_text()
    after = _compile(imported, example, vendor, tmp_path / "b")
    assert abs(after["cycle_time"] - before["cycle_time"]) <= 0.005 * before["cycle_time"]
    for a, b in zip(_leaves(before), _leaves(after), strict=True):
        _same_move(a, b, before["cycle_time"])
    for a, b in zip(_axis_values(before), _axis_values(after), strict=True):
        assert a.keys() == b.keys(), (a, b)
        for axis, value in a.items():  # the plan's mm or deg
            assert abs(value - b[axis]) <= 0.001, (axis, value, b[axis])


@pytest.mark.parametrize(("vendor", "name"), [(v, n) for v in ("urscript", "val3") for n in AXES_EXAMPLES])
def test_no_axes_vendor_refuses(vendor: str, name: str, tmp_path: Path) -> None:
    """URScript and VAL3 programs move the arm alone: compiling an example with external axes
    for them is refused (E607) and writes nothing, so there is no file to read back."""
    example = ROOT / "examples" / f"{name}.rmot"
    result = CliRunner().invoke(cli, ["compile", str(example), "--target", vendor, "-o", str(tmp_path / "out")])
    assert result.exit_code == 1, result.output
    assert re.search(rf"error\[E607\]: {vendor}: task '{name}' drives external axes", result.output), result.output
    assert not (tmp_path / "out" / vendor).exists()


def _rapid_module(tmp_path: Path, extax: str, move: str = "MoveJ p, v100, fine, tool0;") -> Path:
    path = tmp_path / "hand.mod"
    path.write_text("MODULE hand\n"
                    f"  CONST robtarget p:=[[500,0,600],[0,0,1,0],[0,0,0,0],{extax}];\n"
                    f"  CONST jointtarget j:=[[0,0,0,0,30,0],{extax}];\n"
                    "  PROC main()\n"
                    f"    {move}\n"
                    "  ENDPROC\n"
                    "ENDMODULE\n")
    return path


TRACK_CELL = ROOT / "examples" / "track_tending.rmot"


def test_rapid_extax_reads_on_the_cell_track(tmp_path: Path) -> None:
    """A hand-written RAPID move to a robtarget with eax_a = 905 mm: `ext(rail=905mm)` on the
    cell's track (its only mechanism), `with rail` on the program."""
    code, output = _import([_rapid_module(tmp_path, "[905,9E+09,9E+09,9E+09,9E+09,9E+09]")],
                           tmp_path / "out.rmot", TRACK_CELL)
    assert code == 0, output
    text = (tmp_path / "out.rmot").read_text()
    assert "program hand on r1 with rail {" in text
    assert re.search(r"move joint p ext\(rail=905mm\)", text), text


@pytest.mark.parametrize(("extax", "why"), [
    ("[905,10,9E+09,9E+09,9E+09,9E+09]", "2 external-axis slot(s) written"),  # the track has one axis
    ("[9E+09,10,9E+09,9E+09,9E+09,9E+09]", "2 external-axis slot(s) written"),  # eax_a unset
])
def test_rapid_extax_that_maps_to_no_axes_stays_native(tmp_path: Path, extax: str, why: str) -> None:
    code, output = _import([_rapid_module(tmp_path, extax)], tmp_path / "out.rmot", TRACK_CELL)
    assert code == 0, output
    assert re.search(r"hand\.mod:5:5: warning\[W523\]: external-axis values must map to the cell's axes: " + re.escape(why),
                     output), output
    text = (tmp_path / "out.rmot").read_text()
    assert 'native rapid "MoveJ p, v100, fine, tool0;"' in text and " with " not in text, text


def test_rapid_extax_without_cell_stays_native(tmp_path: Path) -> None:
    """The stub cell declares the arm, tools, frames and I/O, never a track or positioner (their
    geometry is not in the file): a move with axis values stays native."""
    code, output = _import([_rapid_module(tmp_path, "[905,9E+09,9E+09,9E+09,9E+09,9E+09]")], tmp_path / "out.rmot", None)
    assert code == 0, output
    assert "warning[W523]" in output and "the cell declares no track or positioner" in output, output
    assert "0 imported, 1 kept native" in output.replace("motion and I/O: ", ""), output


def test_rapid_move_ext_j_stays_native(tmp_path: Path) -> None:
    """MoveExtJ (the units alone, ABB RAPID reference) written by hand: kept native, W510."""
    path = _rapid_module(tmp_path, "[905,9E+09,9E+09,9E+09,9E+09,9E+09]", "MoveExtJ j, v1000, fine;")
    code, output = _import([path], tmp_path / "out.rmot", TRACK_CELL)
    assert code == 0, output
    assert re.search(r"hand\.mod:5:5: warning\[W510\].*MoveExtJ \(the external axes alone\) is read only as rmot writes", output), output
    assert 'native rapid "MoveExtJ j, v1000, fine;"' in (tmp_path / "out.rmot").read_text()


def _import_krl(tmp_path: Path, position: str) -> tuple[str, str]:
    """(the import's output, the program) of a hand-written `PTP position` on the track cell."""
    src = tmp_path / "hand.src"
    src.write_text(f"DEF hand( )\n  PTP {position}\nEND\n")
    code, output = _import([src], tmp_path / "out.rmot", TRACK_CELL)
    assert code == 0, output
    return output, (tmp_path / "out.rmot").read_text()


def test_krl_inline_e6pos_e1_reads(tmp_path: Path) -> None:
    """A PTP to an inline E6POS with E1 (KRL's first external axis) on a track cell."""
    _, text = _import_krl(tmp_path, "{X 500,Y 0,Z 600,A 0,B 90,C 0,S 2,T 35,E1 905,E2 0,E3 0,E4 0,E5 0,E6 0}")
    assert re.search(r"move joint pose\([^)]*\)\) ext\(rail=905mm\)", text), text


def test_tp_second_group_of_unknown_axis_count_stays_native(tmp_path: Path) -> None:
    """A TP position with a GP2 block of three axes where the cell's positioner has two: the
    slots fill no choice of the cell's mechanisms, so the move stays native (W523)."""
    output = _import_on_positioner(tmp_path, "HAND.ls", "/PROG  HAND\n/ATTR\nDEFAULT_GROUP\t= 1,1,*,*,*;\n/MN\n   1:  J P[1] 100% FINE ;\n/POS\n"
                  "P[1]{\n   GP1:\n\tUF : 0, UT : 0,\t\tCONFIG : 'N U T, 0, 0, 0',\n"
                  "\tX =   500.000  mm,\tY =     0.000  mm,\tZ =   600.000  mm,\n"
                  "\tW =   180.000 deg,\tP =     0.000 deg,\tR =     0.000 deg\n"
                  "   GP2:\n\tUF : 0, UT : 0,\t\n\tJ1=     0.000  deg,\tJ2=    90.000  deg,\tJ3=    10.000  deg\n};\n/END\n")
    assert re.search(r"HAND\.ls:5:\d+: warning\[W523\]: .*3 external-axis slot\(s\) written", output), output


@pytest.mark.parametrize(("vendor", "old", "new", "slot"), [
    ("rapid", "[2000.000,9E+09", "[2005.000,9E+09", "eax_a 2000 -> 2005"),
    ("krl", ",E1 2000.0000,", ",E1 2005.0000,", "E1 2000 -> 2005"),
])
def test_diff_names_a_touched_up_axis_value(vendor: str, old: str, new: str, slot: str, tmp_path: Path) -> None:
    """A touch-up moving the track 5 mm at the buffer table (rmot's own file, edited as a pendant
    would): `rmot diff` names each target and its slot, with the vendor file's line."""
    _compile(TRACK_CELL, TRACK_CELL, vendor, tmp_path / "a")
    folder = tmp_path / "a" / vendor
    data = next(folder.glob("*.mod" if vendor == "rapid" else "*.dat"))
    touched = tmp_path / "b"
    touched.mkdir()
    for f in folder.iterdir():
        (touched / f.name).write_text(f.read_text().replace(old, new) if f == data else f.read_text())
    main = MAIN_FILE[vendor]
    result = CliRunner().invoke(cli, ["diff", str(next(folder.glob(main))), str(next(touched.glob(main)))])
    assert result.exit_code == 1, result.output
    lines = [ln for ln in result.output.splitlines() if "external axes changed" in ln]
    edited = [n + 1 for n, ln in enumerate(data.read_text().splitlines()) if old in ln]
    assert len(lines) == len(edited) == 2, result.output  # put and its approach (the retreat's target)
    for line, n in zip(lines, edited):
        assert re.search(rf"{data.name}:{n}:\d+ -> \S+{data.name}:{n}:\d+: target \w+ external axes changed: {slot}$",
                         line), line


@pytest.mark.parametrize(("operand", "why"), [
    ("+MOVJ EC00000 VJ=50.00", "the station moves at its own VJ=50.00 %"),
    ("+MOVJ EC00007 VJ=100.00", "its base (BC) or station (EC) position is not declared"),
])
def test_inform_station_line_not_read_stays_native(operand: str, why: str, tmp_path: Path) -> None:
    """A hand-written job line moving the station in a way rmot has no form for stays native
    with W510 naming why; the line beside it (the station at VJ=100) is read."""
    output = _import_on_positioner(tmp_path, "HAND.JBI", "/JOB\n//NAME HAND\n//POS\n///NPOS 1,0,1,0,0,0\n///TOOL 0\n///POSTYPE ROBOT\n///RECTAN\n"
                   "///RCONF 0,0,0,0,0,0,0,0\nC00000=1000.000,0.000,630.000,135.0000,0.0000,90.0000\n"
                   "///POSTYPE PULSE\n///PULSE\nEC00000=0,90000\n//INST\n///DATE 2000/01/01 00:00\n"
                   "///ATTR SC,RW\n///GROUP1 RB1\n///GROUP2 ST1\nNOP\n"
                   f"MOVJ C00000 VJ=100.00 PL=0 {operand}\nMOVJ C00000 VJ=100.00 PL=0 +MOVJ EC00000 VJ=100.00\nEND\n")
    assert re.search(rf"HAND\.JBI:19:1: warning\[W510\]: .*{re.escape(why)}", output), output
    assert "ext(pos=(0deg, 90deg))" in (tmp_path / "out.rmot").read_text()


@pytest.mark.parametrize("value", ["1E+300", "1" * 400])
def test_absurd_axis_value_stays_native(value: str, tmp_path: Path) -> None:
    """An axis value no machine has (1e300 mm, or 400 digits: infinite as a float) is no data:
    the move stays native (W523), never an `ext(...)` the compiler would choke on."""
    output, text = _import_krl(tmp_path, f"{{X 500,Y 0,Z 600,A 0,B 90,C 0,S 2,T 35,E1 {value},E2 0,E3 0,E4 0,E5 0,E6 0}}")
    assert re.search(r"hand\.src:2:3: warning\[W523\]: .*a value must be a finite number within", output), output
    assert "ext(" not in text


@pytest.mark.parametrize("vendor", ["rapid", "krl"])
def test_slot_order_from_the_header(vendor: str, tmp_path: Path) -> None:
    """`with pos, rail`: eax_a/E1, eax_b/E2 are the positioner's, eax_c/E3 the track's (the
    backends' slot rule); the file's header states it, and the import follows it."""
    source = tmp_path / "both.rmot"
    source.write_text(BOTH.replace("with rail, pos", "with pos, rail"))
    _round_trip(vendor, source, tmp_path)
    assert "program both on r1 with pos, rail {" in (tmp_path / "both_imported.rmot").read_text()


def test_slot_order_unstated_stays_native(tmp_path: Path) -> None:
    """The same RAPID module without its header: which mechanism takes eax_a is machine data the
    file does not hold, so every move with axis values stays native (W523), none guessed."""
    source = tmp_path / "both.rmot"
    source.write_text(BOTH)
    _compile(source, source, "rapid", tmp_path / "a")
    module = next((tmp_path / "a" / "rapid").glob("*.mod"))
    bare = tmp_path / "bare.mod"
    bare.write_text("\n".join(ln for ln in module.read_text().splitlines() if not ln.lstrip().startswith("!")) + "\n")
    code, output = _import([bare], tmp_path / "out.rmot", source)
    assert code == 0, output
    assert output.count("warning[W523]") == 6 and "an order the controller's machine data sets" in output, output
    assert "move " not in (tmp_path / "out.rmot").read_text()


def test_coordinated_without_station_position_stays_native(tmp_path: Path) -> None:
    """A hand-written SMOVL naming no station position: the robot's path relative to a station
    whose values the job does not give is kept native (W523), never read as a plain line."""
    output = _import_on_positioner(tmp_path, "HAND.JBI", "/JOB\n//NAME HAND\n//POS\n///NPOS 1,0,0,0,0,0\n///TOOL 0\n///POSTYPE ROBOT\n///RECTAN\n"
                   "///RCONF 0,0,0,0,0,0,0,0\nC00000=1000.000,0.000,630.000,135.0000,0.0000,90.0000\n"
                   "//INST\n///DATE 2000/01/01 00:00\n///ATTR SC,RW\n///GROUP1 RB1\nNOP\n"
                   "SMOVL C00000 V=12.0\nEND\n")
    assert re.search(r"HAND\.JBI:15:1: warning\[W523\]: .*a coordinated move must give the positioner's position", output), output
    assert "@" not in (tmp_path / "out.rmot").read_text()


def test_rapid_move_ext_j_of_two_mechanisms_stays_native(tmp_path: Path) -> None:
    """A MoveExtJ whose jointtarget changes the track and the positioner at once has no `move
    axes` form (one mechanism): it stays native (W523), and the program still checks."""
    source = tmp_path / "both.rmot"
    source.write_text(BOTH.replace("  move joint home ext(rail=0mm)\n", MOVE_AXES))
    _compile(source, source, "rapid", tmp_path / "a")
    module = next((tmp_path / "a" / "rapid").glob("*.mod"))
    text = module.read_text()
    both = re.sub(r"(jointtarget jext:=\[\[[^\]]*\],\[)900\.000", r"\g<1>950.000", text)
    assert both != text
    module.write_text(both)
    code, output = _import([module], tmp_path / "out.rmot", source)
    assert code == 0, output
    assert re.search(r"warning\[W523\]: MoveExtJ must move one mechanism .*it moves 2 mechanisms", output), output
    assert "9000000000" not in (tmp_path / "out.rmot").read_text()
    result = CliRunner().invoke(cli, ["check", str(tmp_path / "out.rmot"), "--cell", str(source)])
    assert result.exit_code == 0, result.output


def test_krl_track_at_zero_throughout(tmp_path: Path) -> None:
    """KRL writes 0 in an unused E slot and for a track standing at 0: on a cell whose robot rides
    a track (which its program must drive), E1 0 is the track at 0 mm."""
    _, text = _import_krl(tmp_path, "{A1 0,A2 -90,A3 90,A4 0,A5 45,A6 0,E1 0,E2 0,E3 0,E4 0,E5 0,E6 0}")
    assert "program hand on r1 with rail {" in text and "ext(rail=0mm)" in text, text
    result = CliRunner().invoke(cli, ["check", str(tmp_path / "out.rmot"), "--cell", str(TRACK_CELL)])
    assert result.exit_code == 0, result.output


def test_rapid_move_axes_with_time_round_trip(tmp_path: Path) -> None:
    """`move axes .. time 3 s` (longer than the axes need): MoveExtJ's \\T:=3.000 comes back as
    that time; without `time` (test_move_axes_round_trip) \\T is the axes' own shortest time and
    comes back as none."""
    source = tmp_path / "both.rmot"
    source.write_text(BOTH.replace("  move joint home ext(rail=0mm)\n", MOVE_AXES.replace("180deg)", "180deg) time 3 s")))
    _round_trip("rapid", source, tmp_path)
    assert re.search(r"(?m)^  move axes pos to \(0deg, 180deg\) time 3 s$", (tmp_path / "both_imported.rmot").read_text())


@pytest.mark.parametrize("vendor", ["fanuc", "inform"])
def test_positioner_declared_before_the_track(vendor: str, tmp_path: Path) -> None:
    """TP and INFORM write the track with the arm's group (E1, BC) and the positioner in its own
    (GP2, EC) whatever the cell's order: a cell declaring the positioner first reads the same."""
    lines = BOTH.splitlines(keepends=True)
    track = next(k for k, ln in enumerate(lines) if ln.lstrip().startswith("track rail"))
    robot = lines[track + 1]
    positioner = lines[track + 2:track + 5]
    source = tmp_path / "both.rmot"
    source.write_text("".join(lines[:track] + positioner + [lines[track], robot] + lines[track + 5:]))
    _round_trip(vendor, source, tmp_path)
