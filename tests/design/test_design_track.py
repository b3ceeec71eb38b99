"""The design commands with external axes: `rmot reach` over a track's travel, `place` moving
the track under a robot that rides it (and `compare --place` per arm), `compare` standing each
arm on the carriage, a positioner cell mapped with its fixtures at home, a zero-length or
non-finite track range located (E601).

Witness of the swept map: for a reached point, the kept joint vector's flange pose from the
robot model's forward kinematics (pinocchio, not the IK that found it), placed on the carriage
with plain numpy (the track along world x from the cell text's numbers: the arm 250 mm up on it)
must put the flange at the point with the map's orientation for a carriage value inside the
track's range."""

from __future__ import annotations

import math

import numpy as np
import pytest
from click.testing import CliRunner

from rmot.compiler.cli import cli
from rmot.compiler.design.reach_track import swept_map, swept_slice, track_sweep
from rmot.compiler.design.study import rotation_rpy, study_for
from rmot.compiler.frontend import load_text

TRACK_CELL = """cell t {
  track rail = linear(axis x, range(0mm, 3000mm)) speed 1500 mm/s accel 2000 mm/s^2 at pose(y=100mm)
  robot r1 = kuka_kr16 on rail at pose(z=250mm)
  tool g = none tcp pose(z=100mm) on r1
}
"""


@pytest.fixture(scope="module")
def track_study():  # type: ignore[no-untyped-def]
    front = load_text(TRACK_CELL, "/tmp/design_track.rmot")
    assert front.cell is not None and not front.has_errors, [d.message for d in front.diagnostics]
    return study_for(front.cell, "r1", None)


def test_swept_map_reaches_along_the_whole_travel(track_study) -> None:  # type: ignore[no-untyped-def]
    sweep = track_sweep(track_study.cell, "r1")
    assert sweep is not None and (sweep.low, sweep.high) == (0.0, 3.0)
    np.testing.assert_allclose(sweep.low_base[:3, 3], [0.0, 0.1, 0.25])
    np.testing.assert_allclose(sweep.travel, [3.0, 0.0, 0.0])
    rot = rotation_rpy(math.pi, 0.0, 0.0)
    step = 0.1
    points = swept_slice(sweep, 1.7, step, "xy", 0.6)
    m = swept_map(track_study, sweep, points, step, rot, "r1", 0)
    far = np.linalg.norm(points[:, :2] - [3.0, 0.1], axis=1) < 0.5  # only reachable with the carriage near 3 m
    assert m.reached[far].mean() > 0.9
    assert not m.reached[points[:, 0] > 3.0 + 1.7].any()  # beyond the travel plus the arm's reach
    assert not m.reached[points[:, 0] < -1.7].any()
    for i in np.flatnonzero(m.reached)[::37]:
        flange = track_study.robot.fk(m.q[i])  # in the arm's base frame
        np.testing.assert_allclose(flange[:3, :3], rot, atol=1e-6)
        world_at_zero = np.array([0.0, 0.1, 0.25]) + flange[:3, 3]  # carriage at 0
        carriage = points[i, 0] - world_at_zero[0]
        assert -1e-6 <= carriage <= 3.0 + 1e-6
        np.testing.assert_allclose(world_at_zero[1:], points[i, 1:], atol=1e-6)
    assert m.bound == pytest.approx(track_study_bound(track_study) + 1.5)
    np.testing.assert_allclose(m.base[:3, 3], [1.5, 0.1, 0.25])  # drawn centred on the travel


def track_study_bound(study) -> float:  # type: ignore[no-untyped-def]
    from rmot.compiler.design.reach import reach_bound

    return reach_bound(study.robot, study.tcp)


def _run(tmp_path, *args: str):  # type: ignore[no-untyped-def]
    return CliRunner().invoke(cli, list(args), catch_exceptions=False)


def test_cli_reach_on_a_track_and_on_a_positioner_cell(tmp_path) -> None:  # type: ignore[no-untyped-def]
    out = tmp_path / "track.svg"
    r = _run(tmp_path, "reach", "examples/track_tending.rmot", "--orientation", "rx=180deg", "--step", "150mm", "-o", str(out))
    assert r.exit_code == 0, r.output
    assert out.stat().st_size > 0
    r = _run(tmp_path, "reach", "examples/weld_positioner.rmot", "--step", "150mm", "-o", str(tmp_path / "pos.svg"))
    assert r.exit_code == 0, r.output


PLACE_PROGRAM = """program p on r1 with rail {
  tool g
  move joint joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg)
  move joint pose(x=2000mm, y=1900mm, z=300mm, rx=180deg) frame world ext(rail=2000mm)
  move linear pose(x=2000mm, y=1900mm, z=200mm, rx=180deg) frame world speed 100 mm/s
  move joint joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg) ext(rail=500mm)
}
"""


def test_place_moves_the_track_under_the_arm(tmp_path) -> None:  # type: ignore[no-untyped-def]
    """The seam 1.9 m to the side is out of reach from the track at y = 100 mm (1.8 m from the
    rail's line, the KR 16 reaches 1.6 m): `rmot place` moves the track's `at` into the region,
    the written cell checks clean, and the planned flange, placed on the carriage with numpy
    from the written numbers (track at (x, y), rail value along x, arm 250 mm up), is at the
    world target."""
    import re

    from rmot.compiler.plan import plan_program
    from rmot.lang import ir, ir_tree

    program = tmp_path / "p.rmot"
    program.write_text(TRACK_CELL + PLACE_PROGRAM)
    r = _run(tmp_path, "check", str(program))
    assert r.exit_code == 1, r.output  # unreachable where the track is
    out = tmp_path / "placed.rmot"
    r = _run(tmp_path, "place", str(program), "--region", "x=-200mm..200mm, y=500mm..1200mm", "--samples", "16", "-o", str(out))
    assert r.exit_code == 0, r.output
    assert "placing the track" in r.output
    text = out.read_text()
    assert "robot r1 = kuka_kr16 on rail at pose(z=250mm)" in text  # the arm stays on its carriage
    at = re.search(r"track rail = .* at pose\(x=(-?[0-9.]+)mm, y=(-?[0-9.]+)mm, z=(-?[0-9.]+)mm\)", text)
    assert at is not None, text
    x, y, z = (float(v) / 1000 for v in at.groups())
    assert -0.2 <= x <= 0.2 and 0.5 <= y <= 1.2 and z == 0.0
    r = _run(tmp_path, "check", str(out))
    assert r.exit_code == 0, r.output
    front = load_text(text, str(out))
    assert front.program is not None
    plan = plan_program(front.program)
    tp = plan.tasks[0]
    from rmot.sim.robots import load_robot

    arm = load_robot("kuka_kr16")
    moves = [m for m in ir_tree.walk(tp.task.body) if isinstance(m, ir.Move)]
    for m, rail, target in ((moves[1], 2.0, (2.0, 1.9, 0.3)), (moves[2], 2.0, (2.0, 1.9, 0.2))):
        rec = tp.record(m.uid)
        assert rec is not None and rec.q_target is not None
        base = np.eye(4)
        base[:3, 3] = (x + rail, y, z + 0.25)
        tcp = base @ arm.fk(rec.q_target) @ np.array([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0.1], [0, 0, 0, 1.0]])
        np.testing.assert_allclose(tcp[:3, 3], target, atol=1e-5)
        np.testing.assert_allclose(tcp[:3, 2], (0, 0, -1), atol=1e-6)


def test_compare_place_places_the_track_for_each_arm(tmp_path) -> None:  # type: ignore[no-untyped-def]
    program = tmp_path / "p.rmot"
    program.write_text(TRACK_CELL + PLACE_PROGRAM)
    r = _run(tmp_path, "compare", str(program), "--robot", "kuka_kr16", "--place", "--region", "x=-200mm..200mm, y=500mm..1200mm")
    assert r.exit_code == 0, r.output
    assert "track 'rail' placed at x=" in r.output


def test_zero_length_track_is_located(tmp_path) -> None:  # type: ignore[no-untyped-def]
    cell = tmp_path / "z.rmot"
    cell.write_text(TRACK_CELL.replace("range(0mm, 3000mm)", "range(0mm, 0mm)"))
    r = _run(tmp_path, "reach", str(cell), "-o", str(tmp_path / "z.png"))
    assert r.exit_code == 2
    assert f"{cell}:2:" in r.output and "error[E601]" in r.output
    cell.write_text(TRACK_CELL.replace("range(0mm, 3000mm)", "range(0mm, 1e999mm)"))
    r = _run(tmp_path, "reach", str(cell), "-o", str(tmp_path / "z.png"))
    assert r.exit_code == 2 and f"{cell}:2:" in r.output


def test_compare_stands_each_arm_on_the_carriage(tmp_path) -> None:  # type: ignore[no-untyped-def]
    """A target 2.9 m along the track is out of a KR 16's reach (1.6 m) from the track's start:
    the program verifies with a substituted arm only if that arm rides the carriage there."""
    program = tmp_path / "p.rmot"
    program.write_text(TRACK_CELL + """program p on r1 with rail {
  tool g
  move joint joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg)
  move joint pose(x=2900mm, y=700mm, z=500mm, rx=180deg) frame world ext(rail=2600mm)
}
""")
    r = _run(tmp_path, "compare", str(program), "--robot", "kuka_kr16", "--format", "json")
    assert r.exit_code == 0, r.output
    assert '"verified": true' in r.output


POSITIONER_PROGRAM = """cell pc {
  robot r1 = kuka_kr16 at pose()
  positioner pos = axes(revolute(axis z, range(-360deg, 360deg)) speed 180 deg/s accel 360 deg/s^2) at pose(x=1100mm, z=500mm)
  fixture plate = cylinder(r=200mm, h=20mm) on pos at pose(z=10mm)
  frame work = pos * pose(z=20mm)
  tool g = none tcp pose(z=100mm) on r1
}
program p on r1 with pos {
  tool g
  move joint joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg)
  move joint pose(x=-150mm, z=100mm, rx=180deg) frame work
  move axes pos to (90deg)
  move joint pose(x=-150mm, z=100mm, rx=180deg) frame work
}
"""


def test_place_with_a_positioner_keeps_the_targets_on_it(tmp_path) -> None:  # type: ignore[no-untyped-def]
    """A robot on the floor beside a turntable: `rmot place` moves the robot (the positioner
    stays), the targets in the frame on the turntable stay on it, and the written cell checks clean."""
    program = tmp_path / "p.rmot"
    program.write_text(POSITIONER_PROGRAM)
    out = tmp_path / "placed.rmot"
    r = _run(tmp_path, "place", str(program), "--region", "x=-300mm..100mm, y=-200mm..200mm", "--samples", "8", "-o", str(out))
    assert r.exit_code == 0, r.output
    text = out.read_text()
    assert "at pose(x=1100mm, z=500mm)" in text and "robot r1 = kuka_kr16 at pose(x=" in text
    r = _run(tmp_path, "check", str(out))
    assert r.exit_code == 0, r.output
