"""INFORM pulse positions read as joint targets with the arm's pulses per degree
(`rmot import --pulses-per-degree S,L,U,R,B,T`), native with the reason without them.

Witnesses: the conversion is MotoROS2's own test of it (Yaskawa-Global/motoros2
src/Tests_CtrlGroup.c, Ros_Testing_CtrlGroup_PosConverters: a 6-axis group with pulses per
radian 9, 8, 7, 6, 5, 4 turns pulses 2000..7000 into 2000/9, 3000/8, .. 7000/4 rad), its
vectors typed in here and turned into degrees with math.degrees, not with the reader's code; the
job's shape is a pendant-saved pulse job by another author (icors2's Yaskawa-Job-Helper
TCP_CHECK.JBI: `///POSTYPE PULSE`, `///PULSE`, `Cnnnnn=` counts, MOVJ and MOVL to them).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

from click.testing import CliRunner

from rmot.backends.readers import read_files
from rmot.backends.readers.model import Move, Native, walk
from rmot.compiler.cli import cli

# a job for the stub cell's arm: joint values in degrees written as pulses at scales S..T
E2E_DEGREES = ((10.0, 20.0, -15.0, 30.0, -40.0, 50.0), (-20.0, 5.0, 10.0, -30.0, 45.0, -60.0))
E2E_SCALES = (1100.5, 1300.25, 900.0, 700.0, 650.0, 400.0)

# MotoROS2's fake 6-axis group: pulses per radian of S, L, U, R, B, T, and the pulses it converts
PULSES_PER_RADIAN = (9.0, 8.0, 7.0, 6.0, 5.0, 4.0)
PULSES = (2000, 3000, 4000, 5000, 6000, 7000)
EXPECTED_RAD = (2000.0 / 9.0, 3000.0 / 8.0, 4000.0 / 7.0, 5000.0 / 6.0, 6000.0 / 5.0, 7000.0 / 4.0)

JOB = f"""/JOB
//NAME TCP_CHECK
//POS
///NPOS 2,0,0,0,0,0
///TOOL 0
///POSTYPE PULSE
///PULSE
C00000={",".join(map(str, PULSES))}
C00001=-204317,-84436,-64683,-41499,-71625,29263
//INST
///DATE 2025/06/18 13:27
///ATTR SC,RW
///GROUP1 RB1
NOP
MOVJ C00000 VJ=30.00
MOVL C00001 V=211.7
END
"""


def _scales() -> tuple[float, ...]:
    """Pulses per degree from the pulses per radian (a degree is pi/180 rad)."""
    return tuple(k * math.pi / 180.0 for k in PULSES_PER_RADIAN)


def _read(tmp_path: Path, scales: tuple[float, ...] | None) -> tuple[list[object], list[str]]:
    path = tmp_path / "TCP_CHECK.JBI"
    path.write_text(JOB)
    doc = read_files([str(path)], pulses_per_degree=scales)
    return [s for r in doc.routines for s in walk(r.body)], [d.message for d in doc.diagnostics if d.code.id == "W510"]


def test_pulse_positions_become_joint_targets_with_the_arms_scales(tmp_path: Path) -> None:
    """MOVJ to a pulse position is a joint move to its joints; MOVL to one stays native without
    the cell: its TCP pose needs the arm's forward kinematics and the tool."""
    stmts, why = _read(tmp_path, _scales())
    moves = [s for s in stmts if isinstance(s, Move)]
    assert [(m.kind, m.target, m.joint_pct) for m in moves] == [("joint", "tcp_check_c00000", 30.0)]
    assert [s.text for s in stmts if isinstance(s, Native)] == ["MOVL C00001 V=211.7"]
    assert len(why) == 1 and "C00001 is a pulse position, read as joints: a linear or circular move to it goes to its TCP pose" in why[0]
    assert moves[0].joints is not None and moves[0].pose is None
    assert all(math.isclose(got, math.degrees(rad), rel_tol=1e-12)
               for got, rad in zip(moves[0].joints, EXPECTED_RAD, strict=True))


def test_without_scales_the_moves_stay_native_and_say_what_to_pass(tmp_path: Path) -> None:
    stmts, why = _read(tmp_path, None)
    assert [s.text for s in stmts if isinstance(s, Native)] == ["MOVJ C00000 VJ=30.00", "MOVL C00001 V=211.7"]
    assert len(why) == 2 and all("is a pulse position" in w and "--pulses-per-degree S,L,U,R,B,T" in w for w in why)


def test_every_axis_at_zero_pulses_is_the_zero_joint_target_without_scales(tmp_path: Path) -> None:
    """0 pulses is the axis's zero whatever its scale (MotoROS2's conversion has no offset: its
    test's vectors, divided by any scale, give 0 for 0): a generator's home `C00002=0,0,0,0,0,0`
    reads without --pulses-per-degree, the other positions still need the scales; a position
    with a value that is not a whole count stays native."""
    path = tmp_path / "HOMED.JBI"
    path.write_text(JOB.replace("///NPOS 2,", "///NPOS 4,").replace(
        "C00001=-204317", "C00002=0,0,0,0,0,0\nC00003=0,0,0,0,0.5,0\nC00001=-204317").replace(
        "MOVL C00001 V=211.7", "MOVL C00001 V=211.7\nMOVJ C00002 VJ=10.00\nMOVJ C00003 VJ=10.00"))
    doc = read_files([str(path)])
    stmts = [s for r in doc.routines for s in walk(r.body)]
    moves = [s for s in stmts if isinstance(s, Move)]
    assert [(m.kind, m.target, m.joints) for m in moves] == [("joint", "tcp_check_c00002", (0.0,) * 6)]
    assert [s.text for s in stmts if isinstance(s, Native)] == [
        "MOVJ C00000 VJ=30.00", "MOVL C00001 V=211.7", "MOVJ C00003 VJ=10.00"]
    why = [d.message for d in doc.diagnostics if d.code.id == "W510" and "C00003" in d.message]
    assert len(why) == 1 and "pass them as `rmot import --pulses-per-degree" in why[0], why


def test_scales_for_another_number_of_axes_convert_nothing(tmp_path: Path) -> None:
    """Five scales for six counts: never a guess for the sixth axis."""
    stmts, why = _read(tmp_path, _scales()[:5])
    assert not any(isinstance(s, Move) for s in stmts)
    assert len(why) == 2 and "not the 5 whole pulse counts" in why[0]


def test_the_cli_reads_pulse_jobs_and_refuses_bad_scales(tmp_path: Path) -> None:
    path = tmp_path / "TCP_CHECK.JBI"
    path.write_text(JOB)
    out = tmp_path / "tcp.rmot"
    scales = ",".join(f"{k!r}" for k in _scales())
    result = CliRunner().invoke(cli, ["import", str(path), "-o", str(out), "--pulses-per-degree", scales],
                                catch_exceptions=False)
    assert result.exit_code == 0, result.output
    text = out.read_text()
    assert "target tcp_check_c00000 = joints(" in text and "move joint tcp_check_c00000 speed 30 %" in text
    for bad, said in (("1,2,x", "numbers separated by commas"), ("100,0,100", "`0` is not a finite, non-zero"),
                      ("100,inf", "`inf` is not a finite"), ("1,2,3,4,5,6,7,8,9", "1 to 8 axes (got 9)")):
        result = CliRunner().invoke(cli, ["import", str(path), "-o", str(out), "--pulses-per-degree", bad])
        assert result.exit_code == 2 and "error[E525]" in result.output and said in result.output, result.output


def test_scales_with_task_are_refused(tmp_path: Path) -> None:
    """One arm's scales given to an import of several robots' tasks: whose they are is not said."""
    path = tmp_path / "TCP_CHECK.JBI"
    path.write_text(JOB)
    result = CliRunner().invoke(cli, ["import", "--task", f"r1={path}", "-o", str(tmp_path / "t.rmot"),
                                      "--pulses-per-degree", "100,100,100,100,100,100"])
    assert result.exit_code == 2 and "error[E525]" in result.output and "with --task" in result.output, result.output
    assert not (tmp_path / "t.rmot").exists()


def _imported_plan(tmp_path: Path, name: str, degrees: tuple[tuple[float, ...], ...], moves: str,
                   cell: Path | None = None) -> tuple[str, list[dict]]:
    """A pulse job `name` (counts = degrees x E2E_SCALES, rounded to whole pulses as a job holds
    them) with the instructions `moves`, imported with those scales (on `cell`, else the stub),
    then planned: (the .rmot written, the plan's move instructions)."""
    lines = [f"C{n:05d}=" + ",".join(str(round(d * k)) for d, k in zip(q, E2E_SCALES, strict=True))
             for n, q in enumerate(degrees)]
    job = tmp_path / f"{name}.JBI"
    job.write_text(f"/JOB\n//NAME {name}\n//POS\n///NPOS {len(lines)},0,0,0,0,0\n///TOOL 0\n///POSTYPE PULSE\n"
                   "///PULSE\n" + "\n".join(lines) + "\n//INST\n///DATE 2025/06/18 13:27\n///ATTR SC,RW\n"
                   f"///GROUP1 RB1\nNOP\n{moves}END\n")
    out = tmp_path / f"{name.lower()}.rmot"
    on_cell = ["--cell", str(cell)] if cell else []
    result = CliRunner().invoke(cli, ["import", str(job), "-o", str(out), *on_cell, "--pulses-per-degree",
                                      ",".join(map(str, E2E_SCALES))], catch_exceptions=False)
    assert result.exit_code == 0 and "0 kept native" in result.output, result.output
    result = CliRunner().invoke(cli, ["compile", str(out), *on_cell, "--target", "json", "-o", str(tmp_path / "plan"),
                                      "--allow-findings"], catch_exceptions=False)
    assert result.exit_code in (0, 1), result.output
    plan = json.loads(next((tmp_path / "plan" / "json").glob("*.json")).read_text())
    return out.read_text(), [i for i in plan["tasks"][0]["instructions"] if "q_target" in i]


def _within_half_a_pulse(q: list[float], degrees: tuple[float, ...], slack: float) -> bool:
    return all(abs(math.degrees(got) - want) <= 0.5 / k + slack for got, want, k in zip(q, degrees, E2E_SCALES, strict=True))


def test_an_imported_pulse_job_plans_to_its_joints(tmp_path: Path) -> None:
    """End to end: a pulse job imported with its scales plans, on the stub cell's Yaskawa arm, to
    its joints within half a pulse; the witness is the planner's own JSON plan (q_target, rad)."""
    _, planned = _imported_plan(tmp_path, "E2E", E2E_DEGREES, "MOVJ C00000 VJ=30.00\nMOVJ C00001 VJ=50.00\n")
    assert [i["kind"] for i in planned] == ["move_joint", "move_joint"]
    assert all(_within_half_a_pulse(i["q_target"], q, 1e-6) for i, q in zip(planned, E2E_DEGREES, strict=True))


def test_a_linear_move_to_a_pulse_position_goes_to_its_tcp_pose_in_the_cell(tmp_path: Path) -> None:
    """With --cell (the arm and the tool the job names), MOVL to a pulse position goes to its TCP
    pose: the arm's forward kinematics times the tool's TCP. Witness: the planner's own IK ends
    the imported linear move at the joints the pulses give (q_target, to 0.001 deg)."""
    degrees = ((10.0, 20.0, -15.0, 30.0, -40.0, 50.0), (15.0, 25.0, -10.0, 25.0, -45.0, 55.0))
    cell = tmp_path / "cell.rmot"
    cell.write_text("cell fk_cell {\n  robot r1 = yaskawa_gp8\n  tool torch = none tcp pose(x=0mm, y=0mm, z=150mm, "
                    "q=(1, 0, 0, 0)) mass 1 kg on r1\n}\n")
    text, planned = _imported_plan(tmp_path, "FK", degrees, "'TOOL 0 = torch\nMOVJ C00000 VJ=30.00\n"
                                   "MOVL C00001 V=100.0\n", cell)
    assert "move linear fk_c00001_tcp speed 100 mm/s" in text
    assert [i["kind"] for i in planned] == ["move_joint", "move_linear"]
    assert _within_half_a_pulse(planned[1]["q_target"], degrees[1], 1e-3), (planned[1]["q_target"], degrees[1])
