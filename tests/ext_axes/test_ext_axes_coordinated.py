"""Coordinated motion: a linear or circular move while the positioner carrying its frame turns.

The witness never asks rmot where the TCP is: it composes the arm's flange from the KR 16's
reference chain (ext_axes_witness.kr16_flange, from ROS-Industrial's URDF) with the track and
the positioner built from the cell text's numbers (ext_axes_witness.py),
at every 4 ms sample of the planned joints and axis values, and reads the TCP in the part frame
`work`. That TCP must run on the programmed line / arc in `work` at no more than the programmed
speed, in step with the axes (the shared progress u). Each vendor's emitted targets, re-expanded
with the axis values written beside them, must reach the planned TCP in `work` within 0.01 mm;
the controller's reading of the move (TCP linear in the moving frame from the start target to
the end target while the axes go linearly from their start to their end values) sampled at the
plan's axis values must match the plan's TCP within the dense path tolerance (0.05 mm)."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from ext_axes_plans import planned
from ext_axes_witness import CELL_HEAD, at, kr16_flange, robot_base, work_frame
from test_ext_axes_emit import fanuc_targets, krl_targets, rapid_targets

from rmot.backends import BACKENDS
from rmot.compiler.frontend import load_text
from rmot.compiler.plan import plan_program
from rmot.lang import ir
from rmot.lang.axis_motion import axis_samples, task_axes
from rmot.lang.plan_types import Plan
from rmot.sim.verification import verify

PULSES = CELL_HEAD.replace("accel 2000 mm/s^2 at", "accel 2000 mm/s^2 inform(pulses_per_mm=100) at").replace(
    "deg/s^2,", "deg/s^2 inform(pulses_per_deg=1000),").replace("deg/s^2)\n", "deg/s^2 inform(pulses_per_deg=1000))\n")
SOURCE = PULSES + """  tool torch = none tcp pose(z=300mm) mass 1 kg on r1
}
program p on r1 with rail, pos {
  tool torch
  move joint joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg)
  move joint pose(x=100mm, z=50mm, rx=180deg) frame work ext(rail=1000mm)
  move linear pose(x=0mm, y=100mm, z=50mm, rx=180deg) frame work ext(pos=(0deg, 60deg)) speed 50 mm/s
  move circular via pose(x=-100mm, y=0mm, z=50mm, rx=180deg)
             to pose(x=0mm, y=-100mm, z=50mm, rx=180deg) frame work ext(pos=(10deg, 120deg)) speed 50 mm/s
  move linear pose(x=0mm, y=-100mm, z=150mm, rx=180deg) frame work speed 100 mm/s
}
"""
TOL_M = 1e-5  # 0.01 mm
PATH_TOL_M = 5e-5  # the dense IK's path tolerance (compiler/plan/dense.py)
TCP = at(z=0.3)


def in_work(q: np.ndarray, rail: float, tilt: float, turn: float) -> np.ndarray:
    """The TCP in the part frame `work` (rail in m, tilt and turn in rad)."""
    world = robot_base(rail * 1000) @ kr16_flange(q) @ TCP
    return np.linalg.inv(work_frame(math.degrees(tilt), math.degrees(turn))) @ world


@pytest.fixture(scope="module")
def plan() -> Plan:
    return planned(SOURCE, "/tmp/ext_axes_coordinated.rmot")


def _moves(plan: Plan) -> list[ir.Move]:
    return [m for m in plan.tasks[0].task.body if isinstance(m, ir.Move)]


def _samples(plan: Plan, move: ir.Move) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(t, axes (N, 3), TCP in work (N, 4, 4)) at the plan's samples during `move`."""
    tp = plan.tasks[0]
    rec = tp.record(move.uid)
    assert rec is not None
    values = axis_samples(tp, task_axes(tp.task, plan.program.cell.external))
    inside = (tp.trajectory.t >= rec.t_start) & (tp.trajectory.t <= rec.t_end)
    tcp = np.array([in_work(q, *e) for q, e in zip(tp.trajectory.q[inside], values[inside], strict=True)])
    return tp.trajectory.t[inside], values[inside], tcp


def test_the_linear_seam_is_straight_in_the_turning_part_frame(plan: Plan) -> None:
    move = _moves(plan)[2]
    assert move.coordinated is not None and move.coordinated.mechanism == "pos"
    t, axes, tcp = _samples(plan, move)
    p = tcp[:, :3, 3]
    start, end = np.array([0.1, 0.0, 0.05]), np.array([0.0, 0.1, 0.05])
    d = end - start
    u = (p - start) @ d / (d @ d)
    assert np.linalg.norm(p - start - u[:, None] * d, axis=1).max() < PATH_TOL_M
    assert np.abs(p[-1] - end).max() < 1e-4 and np.abs(p[0] - start).max() < 1e-4  # the ends within a 4 ms step
    turn = (axes[:, 2] - axes[0, 2]) / (axes[-1, 2] - axes[0, 2])
    assert np.abs(turn - u).max() < 2e-3  # the axes and the TCP share one progress
    assert math.degrees(axes[-1, 2] - axes[0, 2]) == pytest.approx(60.0, abs=0.1)
    speed = np.linalg.norm(np.diff(p, axis=0), axis=1) / np.diff(t)
    assert speed.max() <= 0.05 * 1.01 and speed.max() > 0.05 * 0.99  # the programmed speed, relative to the part


def test_the_arc_is_round_in_the_part_frame_and_the_tilt_moves_with_it(plan: Plan) -> None:
    t, axes, tcp = _samples(plan, _moves(plan)[3])
    p = tcp[:, :3, 3]
    assert np.abs(np.linalg.norm(p[:, :2], axis=1) - 0.1).max() < PATH_TOL_M  # the circle through the three points
    assert np.abs(p[:, 2] - 0.05).max() < PATH_TOL_M
    assert np.abs(p[-1] - [0.0, -0.1, 0.05]).max() < 1e-4
    angle = np.unwrap(np.arctan2(p[:, 1], p[:, 0]))
    u = (angle - angle[0]) / (angle[-1] - angle[0])
    assert angle[-1] - angle[0] == pytest.approx(math.pi, abs=1e-3)  # through the via at 180 deg
    for k in (1, 2):
        progress = (axes[:, k] - axes[0, k]) / (axes[-1, k] - axes[0, k])
        assert np.abs(progress - u).max() < 2e-3
    speed = np.linalg.norm(np.diff(p, axis=0), axis=1) / np.diff(t)
    assert speed.max() <= 0.05 * 1.01


def test_the_timing_respects_every_axis_and_counts_in_the_cycle(plan: Plan) -> None:
    tp = plan.tasks[0]
    values = axis_samples(tp, task_axes(tp.task, plan.program.cell.external))
    rate = np.abs(np.diff(values, axis=0)) / np.diff(tp.trajectory.t)[:, None]
    assert np.all(rate.max(axis=0) <= np.array([1.5, math.radians(90), math.radians(180)]) * (1 + 1e-3))
    qd = np.abs(tp.trajectory.qd).max(axis=0)
    assert np.all(np.isfinite(qd))
    arc = tp.record(_moves(plan)[3].uid)
    assert arc is not None
    assert arc.t_end - arc.t_start > math.pi * 0.1 / 0.05  # 314 mm at 50 mm/s: at least 6.28 s
    assert plan.cycle_time >= arc.t_end


def _planned_in_work(plan: Plan) -> list[np.ndarray]:
    """The planned TCP at each Cartesian move's target, in `work` at that move's axis values."""
    tp = plan.tasks[0]
    out = []
    for move in _moves(plan):
        if isinstance(move.target, ir.CartesianTarget) and not move.axes_only and move.kind is not ir.MotionKind.CIRCULAR:
            rec = tp.record(move.uid)
            assert rec is not None and rec.tcp_pose is not None
            ext = dict(move.ext)
            world = robot_base(ext["rail"] * 1000) @ rec.tcp_pose.matrix()
            out.append(np.linalg.inv(work_frame(math.degrees(ext["pos.1"]), math.degrees(ext["pos.2"]))) @ world)
    return out


def _controller_matches_plan(plan: Plan, start: np.ndarray, end: np.ndarray, move: ir.Move) -> None:
    """The controller's coordinated line from the re-expanded start to end targets (in work),
    at the progress the plan's axes show, is the plan's TCP in work."""
    _, axes, tcp = _samples(plan, move)
    u = (axes[:, 2] - axes[0, 2]) / (axes[-1, 2] - axes[0, 2])
    controller = start[:3, 3] + u[:, None] * (end[:3, 3] - start[:3, 3])
    assert np.abs(controller - tcp[:, :3, 3]).max() < PATH_TOL_M + 0.05 * 0.004  # + one sample's travel


def _check_vendor(plan: Plan, world_targets: list[np.ndarray], axes: list[tuple[float, float, float]]) -> None:
    want = _planned_in_work(plan)
    assert len(world_targets) == len(want) == 3
    got = [np.linalg.inv(work_frame(tilt, turn)) @ w for w, (_, tilt, turn) in zip(world_targets, axes, strict=True)]
    for g, w in zip(got, want, strict=True):
        assert np.abs(g[:3, 3] - w[:3, 3]).max() < TOL_M
        assert np.abs(g[:3, :3] - w[:3, :3]).max() < 1e-4
    _controller_matches_plan(plan, got[0], got[1], _moves(plan)[2])


def _axes_of(plan: Plan) -> list[tuple[float, float, float]]:
    out = []
    for move in _moves(plan):
        if isinstance(move.target, ir.CartesianTarget) and move.kind is not ir.MotionKind.CIRCULAR:
            ext = dict(move.ext)
            out.append((ext["rail"] * 1000, math.degrees(ext["pos.1"]), math.degrees(ext["pos.2"])))
    return out


def test_rapid_coordinated_work_object_re_expands_to_the_plan(plan: Plan) -> None:
    result = BACKENDS["rapid"]().emit(plan)
    assert not result.has_errors
    (text,) = result.files.values()
    assert 'PERS wobjdata work:=[FALSE,FALSE,"POS",' in text  # ufprog FALSE, ufmec the unit
    assert "MoveL p_3, v50, fine, torch\\WObj:=work;" in text and "MoveC " in text
    _check_vendor(plan, rapid_targets(text), _axes_of(plan))


def test_krl_coupled_base_re_expands_to_the_plan(plan: Plan) -> None:
    result = BACKENDS["krl"]().emit(plan)
    assert not result.has_errors
    src = next(t for n, t in result.files.items() if n.endswith(".src"))
    dat = next(t for n, t in result.files.items() if n.endswith(".dat"))
    assert "$BASE=EK(MACHINE_DEF[3].ROOT" in src and "CIRC " in src
    _check_vendor(plan, krl_targets(src, dat), _axes_of(plan))


def test_fanuc_coord_re_expands_to_the_plan(plan: Plan) -> None:
    result = BACKENDS["fanuc"]().emit(plan)
    assert not result.has_errors
    (text,) = result.files.values()
    assert "L P[3] 50mm/sec FINE COORD ;" in text and ":  P[5] 50mm/sec FINE COORD ;" in text
    assert "L P[6] 100mm/sec FINE ;" in text  # the positioner still: not coordinated
    assert "CD_PAIR" in text
    poses, axes = fanuc_targets(text)
    _check_vendor(plan, poses, axes)


@pytest.mark.parametrize(("program", "code", "line"), [
    # the frame rides on no mechanism: a linear move may not move the positioner
    ("  move linear pose(x=1000mm, z=800mm, ry=180deg) frame world ext(pos=(0deg, 30deg))\n", "E606", 15),
    # a fixed frame: the track may move with the line, the positioner may not
    ("  move linear pose(x=1000mm, z=800mm, ry=180deg) frame world ext(rail=500mm, pos=(0deg, 30deg))\n", "E606", 15),
    # the robot's base frame moves with the track: no controller reads a line in it
    ("  move linear pose(x=800mm, z=500mm, ry=180deg) ext(rail=500mm)\n", "E606", 15),
    # a frame on the track: the track is no part carrier
    ("  move linear pose(x=800mm, z=500mm, ry=180deg) frame carriage ext(rail=500mm)\n", "E609", 15),
])
def test_bad_coordinated_moves_are_located(program: str, code: str, line: int) -> None:
    text = PULSES + "  tool torch = none tcp pose(z=300mm) on r1\n  frame carriage = rail * pose(z=100mm)\n}\n" \
        "program p on r1 with rail, pos {\n  tool torch\n  move joint joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg)\n" + program + "}\n"
    front = load_text(text, "/tmp/ext_axes_coordinated_bad.rmot")
    errors = [d for d in front.diagnostics if d.is_error]
    assert [(d.code.id, d.span.start.line if d.span else None) for d in errors] == [(code, line)]


def test_a_frame_on_a_positioner_the_program_does_not_drive_is_located() -> None:
    text = PULSES + "  tool torch = none tcp pose(z=300mm) on r1\n}\nprogram p on r1 with rail {\n  tool torch\n" \
        "  move joint joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg)\n" \
        "  move linear pose(x=100mm, z=50mm, rx=180deg) frame work\n}\n"
    front = load_text(text, "/tmp/ext_axes_coordinated_undriven.rmot")
    errors = [d for d in front.diagnostics if d.is_error]
    assert [(d.code.id, d.span.start.line if d.span else None) for d in errors] == [("E610", 14)]
    assert "with rail, pos" in errors[0].message


def test_a_linear_move_in_the_part_frame_with_the_axes_still_is_plain(plan: Plan) -> None:
    last = _moves(plan)[4]
    assert last.coordinated is None and last.kind is ir.MotionKind.LINEAR
    rec = plan.tasks[0].record(last.uid)
    assert rec is not None and rec.axes_path is None


def test_a_post_on_the_turning_part_is_hit_at_the_coordinated_line_and_time() -> None:
    """A 20 x 20 mm post stands on the part at (50, 50) mm in `work`, 100 mm tall: the seam line
    (100, 0) -> (0, 100) at z = 50 mm passes through it, so the torch (a 10 mm cylinder along
    its axis) meets it once the torch axis is 10 mm from the post's side: at y = 40 - 10/sqrt(2)
    mm on the line. The time is read from the plan's samples through the witness FK, not from
    the collision check: the check must report E300 at the coordinated move at that time."""
    text = PULSES + """  tool torch = cylinder(10mm, 300mm) at pose(z=150mm) tcp pose(z=300mm) on r1
  fixture post = box(20mm, 20mm, 100mm) on pos at pose(x=50mm, y=50mm, z=90mm)
}
program p on r1 with rail, pos {
  tool torch
  move joint joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg)
  move joint pose(x=100mm, z=50mm, rx=180deg) frame work ext(rail=1000mm)
  move linear pose(x=0mm, y=100mm, z=50mm, rx=180deg) frame work ext(pos=(0deg, 60deg)) speed 50 mm/s
}
"""
    front = load_text(text, "/tmp/ext_axes_coordinated_post.rmot")
    assert front.program is not None, [d.message for d in front.diagnostics]
    plan = plan_program(front.program)
    hits = [d for d in verify(plan).diagnostics if d.is_error and d.code.id == "E300" and "post" in d.bodies]
    assert hits and {h.span.start.line for h in hits if h.span is not None} == {16}
    assert set(hits[0].bodies) == {"torch", "post"}
    t, _, tcp = _samples(plan, _moves(plan)[2])
    contact = float(np.interp(0.040 - 0.010 / math.sqrt(2.0), tcp[:, 1, 3], t))
    assert hits[0].time_s == pytest.approx(contact, abs=2 * plan.step)


def test_a_short_seam_with_a_half_turn_is_timed_by_the_turntable() -> None:
    """10 mm of seam across the turntable's centre while it turns 180 deg: the turntable's own
    rest-to-rest time (180 deg at 180 deg/s and 360 deg/s^2: a trapezoid of 180/180 + 180/360 =
    1.5 s) bounds the move, not the 0.2 s the TCP speed would allow; time-optimal, it takes
    little more, and the TCP relative to the part stays below the programmed speed."""
    text = PULSES + """  tool torch = none tcp pose(z=300mm) on r1
}
program p on r1 with rail, pos {
  tool torch
  move joint joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg)
  move joint pose(x=0mm, y=-5mm, z=50mm, rx=180deg) frame work ext(rail=1000mm)
  move linear pose(x=0mm, y=5mm, z=50mm, rx=180deg) frame work ext(pos=(0deg, 180deg)) speed 50 mm/s
}
"""
    front = load_text(text, "/tmp/ext_axes_coordinated_turn.rmot")
    assert front.program is not None, [d.message for d in front.diagnostics]
    plan = plan_program(front.program)
    assert not [d for d in plan.diagnostics if d.is_error], [d.message for d in plan.diagnostics]
    slow = [d for d in plan.diagnostics if d.code.id == "W606"]
    # 180 deg over 10 mm at 50 mm/s: 900 deg/s for a turntable of 180 deg/s, so 10 mm/s at most
    assert len(slow) == 1 and slow[0].span is not None and slow[0].span.start.line == 15
    assert "must drop to 10.0 mm/s (programmed 50 mm/s): axis 'pos.2' would need 900 deg/s (max 180 deg/s)" in slow[0].message
    move = _moves(plan)[2]
    rec = plan.tasks[0].record(move.uid)
    assert rec is not None
    trapezoid = math.pi / math.pi + math.pi / (2 * math.pi)
    assert trapezoid <= rec.t_end - rec.t_start <= trapezoid * 1.03
    t, axes, tcp = _samples(plan, move)
    assert np.degrees(np.abs(np.diff(axes[:, 2])) / np.diff(t)).max() == pytest.approx(180.0, rel=0.01)  # at full speed
    assert np.abs(tcp[:, 0, 3]).max() < PATH_TOL_M and np.abs(tcp[:, 2, 3] - 0.05).max() < PATH_TOL_M


def _as_moves(text: str, vendor: str) -> str:
    """The circular move's via and end as two plain motions, so the readers of
    test_ext_axes_emit.py (J/L, PTP/LIN, MoveJ/MoveL) re-expand them in order."""
    if vendor == "rapid":
        return re.sub(r"MoveC (\w+), (\w+), ([^;]*);", r"MoveL \1, \3;\n    MoveL \2, \3;", text)
    if vendor == "krl":
        return re.sub(r"CIRC (\w+),(\w+)", r"LIN \1\n  LIN \2", text)
    return re.sub(r"^(\s*\d+:\s*)C (P\[\d+\])\n\s*:\s*(P\[\d+\])", r"\1L \2 ;\n\1L \3", text, flags=re.M)


def arc_targets(files: dict[str, str], vendor: str) -> list[np.ndarray]:
    """World TCP of every Cartesian target of a vendor's program (a circular move's via and end
    as two), in program order, re-expanded by test_ext_axes_emit.py's readers."""
    if vendor == "rapid":
        (text,) = files.values()
        return rapid_targets(_as_moves(text, vendor))
    if vendor == "krl":
        src = next(t for n, t in files.items() if n.endswith(".src"))
        return krl_targets(_as_moves(src, vendor), next(t for n, t in files.items() if n.endswith(".dat")))
    (text,) = files.values()
    return fanuc_targets(_as_moves(text, vendor))[0]


@pytest.mark.parametrize("vendor", ["rapid", "krl", "fanuc"])
def test_the_circular_via_and_end_re_expand_in_the_part_frame(plan: Plan, vendor: str) -> None:
    """The coordinated arc's via and end as each vendor writes them, placed in `work` with the
    axis values written beside them (the end's: the via is a point of the part), equal the via
    as programmed and the planned end within 0.01 mm."""
    world = arc_targets(BACKENDS[vendor]().emit(plan).files, vendor)
    arc = _moves(plan)[3]
    rec = plan.tasks[0].record(arc.uid)
    assert rec is not None and rec.tcp_pose is not None and arc.via is not None
    ext = dict(arc.ext)
    part = work_frame(math.degrees(ext["pos.1"]), math.degrees(ext["pos.2"]))
    planned_end = np.linalg.inv(part) @ robot_base(ext["rail"] * 1000) @ rec.tcp_pose.matrix()
    via, end = (np.linalg.inv(part) @ w for w in world[2:4])  # after the joint move and the coordinated line
    assert np.abs(via[:3, 3] - np.asarray(arc.via.in_frame.position)).max() < TOL_M
    assert np.abs(end[:3, 3] - planned_end[:3, 3]).max() < TOL_M
    assert np.abs(end[:3, :3] - planned_end[:3, :3]).max() < 1e-4
    # the controller's arc: the circle through the line's end (the arc's start), via and end, in
    # `work`, at the progress the plan's axes show (both axes move: tilt 0 -> 10, turn 60 -> 120)
    line_ext = dict(_moves(plan)[2].ext)
    start = np.linalg.inv(work_frame(math.degrees(line_ext["pos.1"]), math.degrees(line_ext["pos.2"]))) @ world[1]
    _, axes, tcp = _samples(plan, arc)
    u = (axes[:, 2] - axes[0, 2]) / (axes[-1, 2] - axes[0, 2])
    controller = _circle(start[:3, 3], via[:3, 3], end[:3, 3], u)
    assert np.abs(controller - tcp[:, :3, 3]).max() < PATH_TOL_M + 0.05 * 0.004


def _circle(p0: np.ndarray, p1: np.ndarray, p2: np.ndarray, u: np.ndarray) -> np.ndarray:
    """Points at fractions u (N,) of the arc from p0 through p1 to p2 (by angle): the centre as
    the point of the three points' plane equidistant from them (a 3 x 3 linear system)."""
    normal = np.cross(p1 - p0, p2 - p0)
    rows = np.array([2 * (p1 - p0), 2 * (p2 - p0), normal])
    centre = np.linalg.solve(rows, [p1 @ p1 - p0 @ p0, p2 @ p2 - p0 @ p0, normal @ p0])
    e1 = (p0 - centre) / np.linalg.norm(p0 - centre)
    e2 = np.cross(normal / np.linalg.norm(normal), e1)
    sweep = math.atan2((p2 - centre) @ e2, (p2 - centre) @ e1) % (2 * math.pi)
    radius = float(np.linalg.norm(p0 - centre))
    return centre + radius * (np.cos(u * sweep)[:, None] * e1 + np.sin(u * sweep)[:, None] * e2)
