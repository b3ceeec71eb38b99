"""Linear moves while the track carrying the robot moves: in a frame fixed in the world, and in
the part frame on the positioner while the positioner turns too (the issue's own example line).

The witness never asks rmot where the TCP is: at every 4 ms sample of the planned joints and
axis values it composes the arm's flange from the KR 16's reference chain (ROS-Industrial's
URDF, ext_axes_witness.kr16_flange) on the carriage at the sampled rail value, and reads the TCP
in world (or in `work`, from the positioner built from the cell text's numbers). That TCP must
run on the programmed line at no more than the programmed speed, with the rail at the same
progress along its travel as the TCP along the line. Each vendor's emitted targets, re-expanded
with the axis values written beside them, must reach the witness's TCP at the end of each move
(the plan's final joints through the reference chain) within 0.01 mm; the controller's reading
(the TCP linear from the re-expanded start target to the re-expanded end target while the track
goes linearly from its start to its end value) sampled at the plan's rail values must match the
plan. A move where the rail binds lasts the rail's own trapezoid, computed here by hand."""

from __future__ import annotations

import math

import numpy as np
import pytest
from click.testing import CliRunner
from ext_axes_witness import CELL_HEAD, at, kr16_flange, robot_base, work_frame
from test_ext_axes_coordinated import _circle, _moves, arc_targets
from test_ext_axes_emit import fanuc_targets, krl_targets, rapid_targets
from test_ext_axes_inform import _plan

from rmot.backends import BACKENDS
from rmot.compiler.cli import cli
from rmot.compiler.frontend import load_text
from rmot.compiler.plan import plan_program
from rmot.lang import ir
from rmot.lang.axis_motion import axis_samples, task_axes
from rmot.lang.plan_types import Plan
from rmot.sim.verification import verify

SOURCE = CELL_HEAD + """  tool torch = none tcp pose(z=300mm) on r1
}
program p on r1 with rail, pos {
  tool torch
  move joint joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg)
  move joint pose(x=200mm, y=-600mm, z=900mm, ry=180deg) frame world ext(rail=0mm)
  move linear pose(x=1500mm, y=-600mm, z=900mm, ry=180deg) frame world ext(rail=1300mm) speed 1500 mm/s accel 4 m/s^2
  move linear pose(x=1700mm, y=-500mm, z=1000mm, ry=180deg) frame world ext(rail=700mm) speed 200 mm/s
  move joint pose(x=100mm, z=50mm, rx=180deg) frame work ext(rail=700mm)
  move linear pose(x=0mm, y=100mm, z=50mm, rx=180deg) frame work ext(rail=800mm, pos=(30deg, 90deg)) speed 50 mm/s
}
"""
LINE = 12  # the first line of the program's body (`tool torch`)
TOL_M = 1e-5  # 0.01 mm
PATH_TOL_M = 5e-5  # the dense IK's path tolerance (compiler/plan/dense.py)
TCP = at(z=0.3)
# the rail-bound move: 1300 mm at 1500 mm/s and 2000 mm/s^2, a trapezoid (1.5^2 / 2 = 1.125 m of
# ramps < 1.3 m): 1.3 / 1.5 + 1.5 / 2 s; the TCP alone (1500 mm/s, 4 m/s^2) would take
# 1.3 / 1.5 + 1.5 / 4 = 1.24 s: the rail's acceleration binds
RAIL_TRAPEZOID_S = 1.3 / 1.5 + 1.5 / 2.0


@pytest.fixture(scope="module")
def plan() -> Plan:
    return _plan(SOURCE)


def _world(q: np.ndarray, rail: float) -> np.ndarray:
    """The TCP in world through the witness chain (rail in m)."""
    return robot_base(rail * 1000) @ kr16_flange(q) @ TCP


def _in_work(world: np.ndarray, tilt: float, turn: float) -> np.ndarray:
    return np.linalg.inv(work_frame(math.degrees(tilt), math.degrees(turn))) @ world


def _samples(plan: Plan, move: ir.Move, part: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(t, axes (N, 3), TCP (N, 4, 4) in world, or in `work` when `part`) during `move`."""
    tp = plan.tasks[0]
    rec = tp.record(move.uid)
    assert rec is not None
    values = axis_samples(tp, task_axes(tp.task, plan.program.cell.external))
    inside = (tp.trajectory.t >= rec.t_start) & (tp.trajectory.t <= rec.t_end)
    worlds = [_world(q, e[0]) for q, e in zip(tp.trajectory.q[inside], values[inside], strict=True)]
    tcp = np.array([_in_work(w, e[1], e[2]) if part else w for w, e in zip(worlds, values[inside], strict=True)])
    return tp.trajectory.t[inside], values[inside], tcp


def _on_the_line(plan: Plan, index: int, start: list[float], end: list[float], speed: float, part: bool) -> None:
    """The witness's TCP on the line start -> end (m), the rail at the same progress, at most
    `speed` (m/s), reaching the end."""
    move = _moves(plan)[index]
    assert move.coordinated is not None and move.kind is ir.MotionKind.LINEAR
    t, axes, tcp = _samples(plan, move, part)
    p = tcp[:, :3, 3]
    a, b = np.array(start), np.array(end)
    d = b - a
    u = (p - a) @ d / (d @ d)
    assert np.linalg.norm(p - a - u[:, None] * d, axis=1).max() < PATH_TOL_M
    assert np.abs(p[0] - a).max() < 1e-4 and np.abs(p[-1] - b).max() < 1e-4
    rail = (axes[:, 0] - axes[0, 0]) / (axes[-1, 0] - axes[0, 0])
    assert np.abs(rail - u).max() < 2e-3  # the track and the TCP share one progress
    moved = np.linalg.norm(np.diff(p, axis=0), axis=1) / np.diff(t)
    assert moved.max() <= speed * 1.01


def test_the_tcp_runs_straight_in_world_while_the_track_carries_the_arm(plan: Plan) -> None:
    _on_the_line(plan, 2, [0.2, -0.6, 0.9], [1.5, -0.6, 0.9], 1.5, part=False)
    _on_the_line(plan, 3, [1.5, -0.6, 0.9], [1.7, -0.5, 1.0], 0.2, part=False)
    # on the second line the arm moves on its carriage as well (800 mm back relative to it)
    tp = plan.tasks[0]
    start, end = (tp.record(m.uid) for m in _moves(plan)[2:4])
    assert start is not None and end is not None and start.q_target is not None and end.q_target is not None
    assert np.abs(end.q_target - start.q_target).max() > math.radians(10)


def test_the_issue_line_is_straight_in_the_turning_part_while_the_track_moves(plan: Plan) -> None:
    _on_the_line(plan, 5, [0.1, 0.0, 0.05], [0.0, 0.1, 0.05], 0.05, part=True)
    _, axes, _ = _samples(plan, _moves(plan)[5], part=True)
    assert axes[-1] == pytest.approx([0.8, math.radians(30), math.radians(90)], abs=1e-4)  # the last 4 ms sample
    turn = (axes[:, 2] - axes[0, 2]) / (axes[-1, 2] - axes[0, 2])
    rail = (axes[:, 0] - axes[0, 0]) / (axes[-1, 0] - axes[0, 0])
    assert np.abs(turn - rail).max() < 1e-6  # every axis on the same progress


def test_the_rail_bound_line_lasts_the_rails_trapezoid_and_counts_in_the_cycle(plan: Plan) -> None:
    tp = plan.tasks[0]
    rec = tp.record(_moves(plan)[2].uid)
    assert rec is not None
    assert RAIL_TRAPEZOID_S <= rec.t_end - rec.t_start <= RAIL_TRAPEZOID_S * 1.01
    values = axis_samples(tp, task_axes(tp.task, plan.program.cell.external))
    rate = np.abs(np.diff(values, axis=0)) / np.diff(tp.trajectory.t)[:, None]
    assert np.all(rate.max(axis=0) <= np.array([1.5, math.radians(90), math.radians(180)]) * (1 + 1e-3))
    assert rate[:, 0].max() == pytest.approx(1.5, rel=0.01)  # the rail at its full speed
    assert plan.cycle_time >= rec.t_end


def _witness_targets(plan: Plan) -> list[tuple[np.ndarray, tuple[float, float, float]]]:
    """(the witness's TCP in world at the end of each Cartesian move, its axes (mm, deg, deg))."""
    tp = plan.tasks[0]
    out = []
    for move in _moves(plan):
        if isinstance(move.target, ir.CartesianTarget):
            rec = tp.record(move.uid)
            assert rec is not None and rec.q_target is not None
            ext = dict(move.ext)
            axes = (ext["rail"] * 1000, math.degrees(ext["pos.1"]), math.degrees(ext["pos.2"]))
            out.append((_world(rec.q_target, ext["rail"]), axes))
    return out


def _check_vendor(plan: Plan, world: list[np.ndarray], axes: list[tuple[float, float, float]]) -> None:
    want = _witness_targets(plan)
    assert len(world) == len(want) == 5
    for g, (w, wax), ax in zip(world, want, axes, strict=True):
        assert ax == pytest.approx(wax, abs=1e-3)
        assert np.abs(g[:3, 3] - w[:3, 3]).max() < TOL_M
        assert np.abs(g[:3, :3] - w[:3, :3]).max() < 1e-4
    # the controller's lines: from each re-expanded start to its end, at the plan's rail progress
    for index, (k0, k1), part in ((2, (0, 1), False), (3, (1, 2), False), (5, (3, 4), True)):
        a, b = world[k0], world[k1]
        if part:
            a, b = (_in_work(w, math.radians(x[1]), math.radians(x[2])) for w, x in ((a, axes[k0]), (b, axes[k1])))
        _, values, tcp = _samples(plan, _moves(plan)[index], part)
        u = (values[:, 0] - values[0, 0]) / (values[-1, 0] - values[0, 0])
        controller = a[:3, 3] + u[:, None] * (b[:3, 3] - a[:3, 3])
        assert np.abs(controller - tcp[:, :3, 3]).max() < PATH_TOL_M


def _axes_of(world_axes: list[float]) -> tuple[float, float, float]:
    rail, tilt, turn = world_axes[:3]
    return rail, tilt, turn


def test_rapid_re_expands_to_the_witness(plan: Plan) -> None:
    result = BACKENDS["rapid"]().emit(plan)
    assert not result.has_errors, [d.message for d in result.diagnostics]
    (text,) = result.files.values()
    assert "MoveL p_3, v1500, fine, torch\\WObj:=world;" in text and "MoveL p_6, v50, fine, torch\\WObj:=work;" in text
    assert 'unit "RAIL": MOC type TRACK' in text
    extax = [line.split("[")[-1] for line in text.splitlines() if "CONST robtarget" in line]
    axes = [_axes_of([float(v) for v in e.rstrip("];").split(",")[:3]]) for e in extax]
    _check_vendor(plan, rapid_targets(text), axes)


def test_krl_re_expands_to_the_witness(plan: Plan) -> None:
    result = BACKENDS["krl"]().emit(plan)
    assert not result.has_errors, [d.message for d in result.diagnostics]
    src = next(t for n, t in result.files.items() if n.endswith(".src"))
    dat = next(t for n, t in result.files.items() if n.endswith(".dat"))
    assert "LIN p_3" in src and "LIN p_4" in src and "LIN p_6" in src and "ROBROOT" in src
    world = krl_targets(src, dat)
    axes = []
    for line in dat.splitlines():
        if line.strip().startswith("DECL E6POS"):
            v = dict(item.split(" ") for item in line.split("{")[1].rstrip("}").split(","))
            axes.append((float(v["E1"]), float(v["E2"]), float(v["E3"])))
    _check_vendor(plan, world, axes)


def test_fanuc_re_expands_to_the_witness(plan: Plan) -> None:
    result = BACKENDS["fanuc"]().emit(plan)
    assert not result.has_errors, [d.message for d in result.diagnostics if d.is_error]
    (text,) = result.files.values()
    assert "L P[3] 1500mm/sec FINE ;" in text and "L P[4] 200mm/sec FINE ;" in text  # the rail with the line: plain L
    assert "L P[6] 50mm/sec FINE COORD ;" in text  # the positioner turns: COORD
    world, axes = fanuc_targets(text)
    _check_vendor(plan, world, axes)


def test_inform_refuses_the_line_with_the_track_at_its_line() -> None:
    pulses = SOURCE.replace("accel 2000 mm/s^2 at", "accel 2000 mm/s^2 inform(pulses_per_mm=100) at").replace(
        "deg/s^2,", "deg/s^2 inform(pulses_per_deg=1000),").replace("deg/s^2)\n", "deg/s^2 inform(pulses_per_deg=1000))\n")
    front = load_text(pulses, "/tmp/ext_axes_track_line_inform.rmot")
    assert front.program is not None
    errors = [d for d in BACKENDS["inform"]().emit(plan_program(front.program)).diagnostics if d.is_error]
    assert [d.code.id for d in errors] == ["E607"]
    assert errors[0].span is not None and errors[0].span.start.line == LINE + 3
    assert "while the track carrying the robot moves" in errors[0].message


def test_the_command_line_checks_clean_and_compiles(tmp_path: object) -> None:
    path = f"{tmp_path}/track_line.rmot"
    with open(path, "w", encoding="utf-8") as f:
        f.write(SOURCE)
    runner = CliRunner()
    checked = runner.invoke(cli, ["check", path])
    assert checked.exit_code == 0, checked.output
    assert "error[" not in checked.output and "warning[" not in checked.output, checked.output
    compiled = runner.invoke(cli, ["compile", path, "--target", "rapid", "--target", "krl", "--target", "fanuc",
                                   "-o", f"{tmp_path}/out"])
    assert compiled.exit_code == 0, compiled.output
    assert "error[" not in compiled.output


@pytest.mark.parametrize(("program", "code"), [
    # the robot's base frame moves with the track
    ("  move linear pose(x=800mm, z=500mm, ry=180deg) ext(rail=500mm)\n", "E606"),
    # a fixed frame: the positioner may not turn during the line
    ("  move linear pose(x=1000mm, y=-600mm, z=900mm, ry=180deg) frame world ext(rail=500mm, pos=(0deg, 30deg))\n", "E606"),
])
def test_what_still_cannot_be_planned_is_located(program: str, code: str) -> None:
    body = SOURCE[:SOURCE.index("  move joint pose(x=200mm")] + program + "}\n"
    front = load_text(body, "/tmp/ext_axes_track_line_bad.rmot")
    errors = [d for d in front.diagnostics if d.is_error]
    assert [(d.code.id, d.span.start.line if d.span else None) for d in errors] == [(code, LINE + 2)]


ARC = CELL_HEAD + """  tool torch = none tcp pose(z=300mm) on r1
}
program p on r1 with rail, pos {
  tool torch
  move joint joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg)
  move joint pose(x=500mm, y=-600mm, z=900mm, ry=180deg) frame world ext(rail=300mm)
  move circular via pose(x=700mm, y=-800mm, z=900mm, ry=180deg)
             to pose(x=900mm, y=-600mm, z=900mm, ry=180deg) frame world ext(rail=700mm) speed 200 mm/s
}
"""


@pytest.fixture(scope="module")
def arc_plan() -> Plan:
    return _plan(ARC)


@pytest.mark.parametrize("vendor", ["rapid", "krl", "fanuc"])
def test_an_arc_in_world_while_the_track_moves(arc_plan: Plan, vendor: str) -> None:
    """The half circle about (700, -600, 900) mm of radius 200 mm through the via, in world,
    while the rail goes 300 -> 700 mm: the witness's TCP on it with the rail at the arc's
    angular progress; each vendor's start, via and end re-expanded (rail from the text), and
    the controller's circle through them at the plan's rail progress, match the plan."""
    move = _moves(arc_plan)[2]
    assert move.coordinated is not None and not move.coordinated.relative()
    _, axes, tcp = _samples(arc_plan, move, part=False)
    p = tcp[:, :3, 3]
    centre = np.array([0.7, -0.6, 0.9])
    assert np.abs(np.linalg.norm(p - centre, axis=1) - 0.2).max() < PATH_TOL_M
    angle = np.unwrap(np.arctan2(p[:, 1] - centre[1], p[:, 0] - centre[0]))
    u = (angle - angle[0]) / (angle[-1] - angle[0])
    rail = (axes[:, 0] - axes[0, 0]) / (axes[-1, 0] - axes[0, 0])
    assert abs(angle[-1] - angle[0]) == pytest.approx(math.pi, abs=1e-3) and np.abs(rail - u).max() < 2e-3
    files = BACKENDS[vendor]().emit(arc_plan).files
    text = "".join(files.values())
    written = {"rapid": "MoveC via, p_3, v200, fine, torch\\WObj:=world;", "krl": "CIRC via,p_3", "fanuc": "C P[3]"}[vendor]
    assert written in text and " COORD" not in text  # the frame stays put: a plain circular move
    start, via, end = arc_targets(files, vendor)
    rec = arc_plan.tasks[0].record(move.uid)
    assert rec is not None and rec.q_target is not None
    assert np.abs(via[:3, 3] - [0.7, -0.8, 0.9]).max() < TOL_M
    assert np.abs(end[:3, 3] - _world(rec.q_target, 0.7)[:3, 3]).max() < TOL_M
    controller = _circle(start[:3, 3], via[:3, 3], end[:3, 3], rail)
    assert np.abs(controller - p).max() < PATH_TOL_M


def test_a_line_in_the_still_part_frame_while_only_the_track_moves() -> None:
    """In `work` with the positioner still, only the rail moves (700 -> 900 mm): the line is
    straight in `work` (and so in world), not relative to a moving part: a plain Fanuc L."""
    source = SOURCE[:SOURCE.index("  move joint pose(x=200mm")] + (
        "  move joint pose(x=100mm, z=50mm, rx=180deg) frame work ext(rail=700mm, pos=(30deg, 90deg))\n"
        "  move linear pose(x=0mm, y=100mm, z=50mm, rx=180deg) frame work ext(rail=900mm) speed 50 mm/s\n}\n")
    plan = _plan(source)
    move = _moves(plan)[2]
    assert move.coordinated is not None and not move.coordinated.relative()
    _on_the_line(plan, 2, [0.1, 0.0, 0.05], [0.0, 0.1, 0.05], 0.05, part=True)
    (text,) = BACKENDS["fanuc"]().emit(plan).files.values()
    assert "L P[3] 50mm/sec FINE ;" in text and " COORD" not in text
    world, axes = fanuc_targets(text)
    for g, (w, wax), ax in zip(world, _witness_targets(plan), axes, strict=True):
        assert ax == pytest.approx(wax, abs=1e-3) and np.abs(g[:3, 3] - w[:3, 3]).max() < TOL_M


def test_a_post_in_the_way_of_the_carried_torch_is_hit_at_the_line_and_time() -> None:
    """A 20 x 20 mm post fixed in world at x = 1000 mm on the rail-bound line (y = -600 mm,
    z 1000 .. 1100 mm, across the torch's 300 mm between TCP and flange): the torch (a 10 mm
    cylinder along its axis) meets it once its axis is at x = 1000 - 10 - 10 mm. The time comes
    from the witness's TCP on the plan's samples, not from the collision check, which must
    report E300 at the line at that time: the arm is checked where the carriage carries it."""
    source = SOURCE.replace("  tool torch = none tcp pose(z=300mm) on r1\n", "  tool torch = cylinder(10mm, 300mm) at pose(z=150mm) "
                            "tcp pose(z=300mm) on r1\n  fixture post = box(20mm, 20mm, 100mm) at pose(x=1000mm, y=-600mm, z=1050mm)\n")
    plan = _plan(source)
    hits = [d for d in verify(plan).diagnostics if d.is_error and d.code.id == "E300" and "post" in d.bodies]
    assert hits and {h.span.start.line for h in hits if h.span is not None} == {LINE + 4}  # the rail-bound line
    assert set(hits[0].bodies) == {"torch", "post"}
    t, _, tcp = _samples(plan, _moves(plan)[2], part=False)
    contact = float(np.interp(0.980, tcp[:, 0, 3], t))
    assert hits[0].time_s == pytest.approx(contact, abs=2 * plan.step)
