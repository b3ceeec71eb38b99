"""INFORM coordinated motion: a line or arc relative to the turning station as SMOVL / SMOVC with
the station's `+MOVJ ECn` (no VJ), read back by a parser written here from the job data format,
never by the backend's code.

The form is the one a DX200 controller saved (rpiRobotics/dx200_motion_progam_exec,
example_inform/R1-S1-SAMPLE.JBI: `SMOVL C00003 V=11.0  +MOVJ EC00003` under `///GROUP1 RB1` /
`///GROUP2 ST1`). Each C position is X, Y, Z mm and Rx, Ry, Rz deg (R = Rz Ry Rx) in ROBOT
coordinates, the arm's base on the carriage at BC; the station's axes at EC pulses. The
witness places those with plain numpy (ext_axes_witness.py: the track along x, the robot 250 mm
up on it, the positioner at (1800, 0, 700) mm tilting about y and turning about z, `work` 40 mm
above its flange) and reads every target in the part frame `work`: it must equal the plan's
TCP there (the witness FK of the plan's joints, test_ext_axes_coordinated.py) within 0.01 mm.
The controller's reading of a coordinated arc (the circle through its three points in the part
frame, the station moving from one taught EC to the next with each segment) must give the
plan's TCP at the plan's station values, and V= the plan's TCP speed relative to the part."""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from ext_axes_witness import CELL_HEAD, at, robot_base, rot, work_frame
from test_ext_axes_coordinated import PATH_TOL_M, SOURCE, TOL_M, _circle, _moves, _planned_in_work, _samples
from test_ext_axes_inform import _plan

from rmot.backends import BACKENDS
from rmot.compiler.cli import cli
from rmot.compiler.design.machine_data import checklists
from rmot.compiler.frontend import load_text
from rmot.compiler.plan import plan_program
from rmot.lang.plan_types import Plan

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "weld_positioner.rmot"
RAIL_PER_MM, STATION_PER_DEG = 100.0, 1000.0  # SOURCE's declared scales (test_ext_axes_coordinated.PULSES)
ASSUMED_PER_DEG = 100000.0 / 360.0  # the scale written without a declared one (W610)


@dataclass(frozen=True)
class Step:
    """One move line of a job: its instruction word, the C pose (4, 4, ROBOT coordinates, m),
    the base axis (mm or pulses as written), the station (pulses), V= or VJ=, the station's VJ."""

    word: str
    pose: np.ndarray
    bc: float | None
    ec: tuple[int, ...] | None
    speed: float
    station_vj: str | None


_MOVE = re.compile(r"^(S?MOV[JLC]) (C\d{5})(?: (BC\d{5}))? (?:VJ|V)=([\d.]+)[^+]*?(?: \+MOVJ (EC\d{5})(?: VJ=([\d.]+))?)?$")


def read_job(text: str) -> list[Step]:
    """Every move line of the job, its positions looked up in the //POS section."""
    values = {k: v.split(",") for k, v in re.findall(r"^((?:B|E)?C\d{5})=(.*)$", text, re.M)}
    steps = []
    for line in text.splitlines():
        m = _MOVE.match(line)
        if not m:
            assert not re.match(r"^S?MOV", line), line
            continue
        word, c, bc, v, ec, vj = m.groups()
        x, y, z, rx, ry, rz = (float(s) for s in values[c])
        pose = at(x / 1000, y / 1000, z / 1000) @ rot("z", rz) @ rot("y", ry) @ rot("x", rx)
        steps.append(Step(word, pose, float(values[bc][0]) if bc else None,
                          tuple(int(s) for s in values[ec]) if ec else None, float(v), vj))
    return steps


def in_work(step: Step, rail_mm: float, per_deg: float) -> np.ndarray:
    """The step's TCP in the part frame `work`, with the axes it is written with."""
    assert step.ec is not None
    tilt, turn = (p / per_deg for p in step.ec)
    return np.linalg.inv(work_frame(tilt, turn)) @ robot_base(rail_mm) @ step.pose


def _emit(plan: Plan) -> tuple[str, list[str]]:
    result = BACKENDS["inform"]().emit(plan)
    assert not result.has_errors, [d.message for d in result.diagnostics if d.is_error]
    (text,) = result.files.values()
    return text, [d.code.id for d in result.diagnostics]


@pytest.fixture(scope="module")
def plan() -> Plan:
    return _plan(SOURCE)


@pytest.fixture(scope="module")
def job(plan: Plan) -> str:
    return _emit(plan)[0]


def test_the_seam_is_written_coordinated_under_the_robot_and_station_groups(job: str) -> None:
    steps = read_job(job)
    # the joint moves and the line in the still part frame keep the station's own VJ; the line
    # and the arc while the positioner turns are the slave's SMOVL / SMOVC, the station's
    # +MOVJ without a speed (it follows the robot's V=, relative to the part)
    assert [s.word for s in steps] == ["MOVJ", "MOVJ", "SMOVL", "SMOVC", "SMOVC", "SMOVC", "MOVL"]
    assert [s.station_vj is None for s in steps] == [False, False, True, True, True, True, False]
    assert [s.speed for s in steps[2:]] == [50.0, 50.0, 50.0, 50.0, 100.0]
    assert "\n///GROUP1 RB1,BS1\n///GROUP2 ST1\nNOP\n" in job
    assert re.search(r"^SMOVC C\d{5} BC\d{5} V=50\.0 PL=0 FPT \+MOVJ EC\d{5}$", job, re.M)  # the arc's end
    counts = [len(re.findall(rf"^{kind}\d{{5}}=", job, re.M)) for kind in ("C", "BC", "EC")]
    assert f"///NPOS {counts[0]},{counts[1]},{counts[2]},0,0,0" in job and counts == [7, 7, 7]
    # the robot-station calibration the controller coordinates through: the positioner's axes
    # meet at (1800, 0, 700) mm in world, the robot's base 250 mm up on the carriage at 0 mm
    assert "X 1800.000, Y 0.000, Z 450.000 mm" in "".join(line[1:] for line in job.splitlines() if line.startswith("'"))


def test_no_station_speed_warning_when_the_station_moves_only_coordinated(plan: Plan) -> None:
    """W604 (the station at its own VJ) is for a station moving without the robot's path: here
    it turns only during the coordinated line and arc, which follow the robot's V=."""
    assert "W604" not in _emit(plan)[1]


def test_the_report_checklist_names_the_calibration_too(plan: Plan) -> None:
    (inform,) = [lines for title, lines in checklists(plan) if "INFORM" in title]
    assert any("robot-station calibration" in line and "X 1800.000, Y 0.000, Z 450.000 mm, their frame at "
               "Rx 0.0000, Ry 0.0000, Rz 0.0000 deg" in line for line in inform)


def test_the_calibration_line_carries_the_station_turned_in_the_cell() -> None:
    """The positioner turned 30 deg about z in the cell, the robot 1 m along the track's y: in
    the robot's frame (the carriage at 0) the station's base is 1800 mm along x, -1000 mm along y
    and 450 mm up, its frame turned 30 deg about z."""
    source = SOURCE.replace("at pose(x=1800mm, z=700mm)", "at pose(x=1800mm, z=700mm, rz=30deg)").replace(
        "on rail at pose(z=250mm)", "on rail at pose(y=1000mm, z=250mm)")
    (inform,) = [lines for title, lines in checklists(_plan(source)) if "INFORM" in title]
    assert any("X 1800.000, Y -1000.000, Z 450.000 mm, their frame at Rx 0.0000, Ry 0.0000, Rz 30.0000 deg" in line
               for line in inform), inform


def test_every_target_re_expands_to_the_plan_in_the_part_frame(plan: Plan, job: str) -> None:
    steps = read_job(job)
    rails = [s.bc / RAIL_PER_MM for s in steps if s.bc is not None]
    got = [in_work(s, r, STATION_PER_DEG) for s, r in zip(steps, rails, strict=True)]
    # the joint move's pose target, the coordinated line's end and the last line (the non-circular ones)
    for g, want in zip((got[1], got[2], got[6]), _planned_in_work(plan), strict=True):
        assert np.abs(g[:3, 3] - want[:3, 3]).max() < TOL_M
        assert np.abs(g[:3, :3] - want[:3, :3]).max() < 1e-4
    arc = _moves(plan)[3]
    rec = plan.tasks[0].record(arc.uid)
    assert rec is not None and rec.tcp_pose is not None and arc.via is not None
    ext = dict(arc.ext)
    end = np.linalg.inv(work_frame(math.degrees(ext["pos.1"]), math.degrees(ext["pos.2"]))) \
        @ robot_base(ext["rail"] * 1000) @ rec.tcp_pose.matrix()
    assert np.abs(got[5][:3, 3] - end[:3, 3]).max() < TOL_M and np.abs(got[5][:3, :3] - end[:3, :3]).max() < 1e-4
    assert np.abs(got[3] - got[2]).max() < TOL_M  # the arc starts where the line ended, in the part
    assert np.abs(got[4][:3, 3] - np.asarray(arc.via.in_frame.position)).max() < TOL_M  # the via as programmed


def test_the_via_carries_the_station_where_the_plan_passes_it(plan: Plan, job: str) -> None:
    """The via's EC is the station where the plan's TCP passes the via (read from the witness
    FK of the plan's samples), so the station, moving from one taught EC to the next, keeps
    the plan's pace: the via is half-way round the half circle, the station half-way between
    (0, 60) and (10, 120) deg."""
    steps = read_job(job)
    assert steps[4].ec is not None
    via_deg = np.array(steps[4].ec) / STATION_PER_DEG
    assert via_deg == pytest.approx([5.0, 90.0], abs=1.0 / STATION_PER_DEG)
    _, axes, tcp = _samples(plan, _moves(plan)[3])
    nearest = int(np.argmin(np.linalg.norm(tcp[:, :3, 3] - [-0.1, 0.0, 0.05], axis=1)))
    step = np.degrees(np.abs(np.diff(axes[:, 1:], axis=0)).max(axis=0))  # one sample's travel
    assert np.all(np.abs(np.degrees(axes[nearest, 1:]) - via_deg) <= step + 1.0 / STATION_PER_DEG)


def test_the_controller_arc_through_the_written_points_is_the_plan(plan: Plan, job: str) -> None:
    """The controller's coordinated arc: the circle through start, via and end as written, in the
    part frame; in each segment the robot goes from one point to the next while the station goes
    from one taught EC to the next. At the station's values of each plan sample, that arc's
    point equals the plan's TCP in `work`."""
    steps = read_job(job)
    start, via, end = (in_work(s, s.bc / RAIL_PER_MM, STATION_PER_DEG)[:3, 3] for s in steps[3:6] if s.bc is not None)
    turns = [s.ec[1] / STATION_PER_DEG for s in steps[3:6] if s.ec is not None]
    fine = np.linspace(0.0, 1.0, 20001)
    f_via = float(fine[np.argmin(np.linalg.norm(_circle(start, via, end, fine) - via, axis=1))])  # the via's share of the sweep
    _, axes, tcp = _samples(plan, _moves(plan)[3])
    turn = np.degrees(axes[:, 2])
    first = turn <= turns[1]
    share = np.where(first, f_via * (turn - turns[0]) / (turns[1] - turns[0]),
                     f_via + (1 - f_via) * (turn - turns[1]) / (turns[2] - turns[1]))
    controller = _circle(start, via, end, np.clip(share, 0.0, 1.0))
    assert np.abs(controller - tcp[:, :3, 3]).max() < PATH_TOL_M + 0.05 * 0.004  # + one sample's travel


def test_v_is_the_tcp_speed_relative_to_the_part(plan: Plan, job: str) -> None:
    """SMOVL's V= is the plan's TCP speed in the turning part frame (witness FK), not in world."""
    steps = read_job(job)
    t, _, tcp = _samples(plan, _moves(plan)[2])
    relative = np.linalg.norm(np.diff(tcp[:, :3, 3], axis=0), axis=1) / np.diff(t)
    assert steps[2].speed / 1000 == pytest.approx(relative.max(), rel=0.01)


def test_a_line_while_the_track_moves_stays_refused_at_its_line() -> None:
    source = SOURCE.replace("frame work ext(pos=(0deg, 60deg)) speed 50 mm/s",
                            "frame work ext(rail=1100mm, pos=(0deg, 60deg)) speed 50 mm/s")
    front = load_text(source, "/tmp/ext_axes_inform_track_line.rmot")
    assert front.program is not None
    result = BACKENDS["inform"]().emit(plan_program(front.program))
    errors = [d for d in result.diagnostics if d.is_error]
    assert [(d.code.id, d.span.start.line if d.span else None) for d in errors] == [("E607", 15)]
    assert "'rail', the base axis BC" in errors[0].message and "keep it still during it" in errors[0].message


def test_the_issue_cell_without_pulse_scales_re_expands_in_the_part_frame() -> None:
    """The issue's cell as written (no pulse scales): the track's BC in mm, the station at the
    assumed 100000 pulses per turn (W610); the coordinated line and arc still re-expand to the
    plan in `work` within 0.01 mm."""
    plan = _plan(SOURCE.replace(SOURCE[:SOURCE.index("  tool torch")], CELL_HEAD))
    job, found = _emit(plan)
    assert "W610" in found and "W605" not in found
    steps = read_job(job)
    assert [s.word for s in steps][2:6] == ["SMOVL", "SMOVC", "SMOVC", "SMOVC"]
    got = [in_work(s, s.bc, ASSUMED_PER_DEG) for s in steps if s.bc is not None]
    for g, want in zip((got[1], got[2], got[6]), _planned_in_work(plan), strict=True):
        assert np.abs(g[:3, 3] - want[:3, 3]).max() < TOL_M


def test_weld_positioner_compiles_for_inform_with_its_seam_on_the_fillet(tmp_path: Path) -> None:
    """examples/weld_positioner.rmot through the command line: exit 0, its four quarter arcs as
    SMOVC, and every arc point, placed with the station's EC (1000 pulses/deg) on the example's
    positioner (1100 mm out, 600 mm up, tilt about y, turn about z, `work` 30 mm above the
    flange; the robot at the world origin), on the fillet circle: radius 100 mm, z 0 in `work`."""
    out = CliRunner().invoke(cli, ["compile", str(EXAMPLE), "--target", "inform", "-o", str(tmp_path)])
    assert out.exit_code == 0, out.stderr
    # the turntable's return from 360 to 0 deg with the arm's joint move home is the station alone
    assert re.findall(r"weld_positioner.rmot:(\d+):\d+: warning\[W604\]", out.stderr) == ["76"]
    (path,) = (tmp_path / "inform").glob("*.JBI")
    steps = read_job(path.read_text(encoding="utf-8"))
    arc = [s for s in steps if s.word == "SMOVC"]
    assert len(arc) == 9 and {s.speed for s in arc} == {12.0}  # the start, then via and end of each quarter
    for s in arc:
        assert s.ec is not None
        tilt, turn = (p / STATION_PER_DEG for p in s.ec)
        part = at(1.1, 0.0, 0.6) @ rot("y", tilt) @ rot("z", turn) @ at(z=0.03)
        p = (np.linalg.inv(part) @ s.pose)[:3, 3]
        assert abs(math.hypot(p[0], p[1]) - 0.1) < TOL_M and abs(p[2]) < TOL_M
    # each via half-way through its quarter: the turntable at 45 + 90 k deg
    assert [s.ec[1] for s in arc[1::2] if s.ec is not None] == [45000, 135000, 225000, 315000]


def test_a_coordinated_arc_after_a_plain_arc_restates_its_start() -> None:
    """A plain arc in the still part frame, then a coordinated one continuing from its end: the
    SMOVC run starts on its own SMOVC line at the plain arc's end (the same point of the part),
    so each circle's three points are lines of one kind."""
    source = SOURCE.replace("  move circular via", """  move circular via pose(x=-70.711mm, y=70.711mm, z=50mm, rx=180deg)
             to pose(x=-100mm, y=0mm, z=50mm, rx=180deg) frame work speed 50 mm/s
  move circular via""").replace("via pose(x=-100mm, y=0mm, z=50mm, rx=180deg)\n             to pose(x=0mm, y=-100mm",
                                "via pose(x=-70.711mm, y=-70.711mm, z=50mm, rx=180deg)\n             to pose(x=0mm, y=-100mm")
    steps = read_job(_emit(_plan(source))[0])
    assert [s.word for s in steps][2:10] == ["SMOVL", "MOVC", "MOVC", "MOVC", "SMOVC", "SMOVC", "SMOVC", "MOVL"]
    rails = [s.bc / RAIL_PER_MM for s in steps if s.bc is not None]
    plain_end, coordinated_start = (in_work(steps[k], rails[k], STATION_PER_DEG) for k in (5, 6))
    assert np.abs(plain_end - coordinated_start).max() < TOL_M
    assert np.abs(plain_end[:3, 3] - [-0.1, 0.0, 0.05]).max() < TOL_M
