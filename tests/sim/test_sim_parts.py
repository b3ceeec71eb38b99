"""Parts in the verification: held parts are bodies of their robot, placed parts
are fixtures, parts may rest on parts (up to 0.1 mm), the payload is checked.

Every program runs in tests/data/parts/cell.rmot: a UR10e (rated payload 12.5 kg) on a 400 mm
pedestal, 100 mm cubes on an infeed table, a 1 kg gripper whose end face is the TCP. The
expected numbers come from the cell's geometry, worked out by hand in each test.
"""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest

from rmot.compiler.frontend import load_program
from rmot.compiler.plan import plan_program
from rmot.sim.robots import load_robot
from rmot.sim.verification import verify

DATA = Path(__file__).resolve().parents[1] / "data" / "parts"


def _check(tmp_path: Path, program: str, cell_extra: str = "", name: str = "prog.rmot"):  # type: ignore[no-untyped-def]
    cell = (DATA / "cell.rmot").read_text(encoding="utf-8")
    if cell_extra:
        cell = cell.rstrip().rstrip("}") + cell_extra + "\n}\n"
    (tmp_path / "cell.rmot").write_text(cell, encoding="utf-8")
    (tmp_path / name).write_text(program, encoding="utf-8")
    result = load_program(str(tmp_path / name), require_program=True)
    assert not result.has_errors, [str(d) for d in result.diagnostics]
    plan = plan_program(result.program)
    return plan, verify(plan)


def _errors(report):  # type: ignore[no-untyped-def]
    return [d for d in report.diagnostics if d.is_error]


def _stack(gap_mm: float) -> str:
    return (DATA / "stack.rmot").read_text(encoding="utf-8").replace("const gap = 10 mm", f"const gap = {gap_mm} mm")


class TestStacking:
    def test_ten_millimetre_gap_is_clean(self, tmp_path: Path) -> None:
        _, report = _check(tmp_path, _stack(10))
        assert _errors(report) == []

    def test_zero_gap_is_clean_parts_rest_side_by_side(self, tmp_path: Path) -> None:
        """Centres 100 mm apart, cubes 100 mm: the faces touch while b2 goes down beside b1,
        the run of contact that ends where b2 is put down (resting, not colliding)."""
        _, report = _check(tmp_path, _stack(0))
        assert _errors(report) == []

    def test_overlap_beyond_the_rest_tolerance_is_a_collision(self, tmp_path: Path) -> None:
        """Centres 99.8 mm apart: b2 enters b1 by 0.2 mm, twice the 0.1 mm rest tolerance."""
        _, report = _check(tmp_path, _stack(-0.2))
        (d,) = _errors(report)
        assert d.code.id == "E300" and set(d.bodies) == {"b1", "b2"}
        assert d.span.start.line == 26  # `move linear shift(place, y=100mm + gap)`: b2 goes down beside b1
        assert d.amount is not None and d.amount.value == pytest.approx(0.2, abs=0.01)

    def test_overlap_is_a_collision_as_deep_as_the_overlap(self, tmp_path: Path) -> None:
        """Centres 90 mm apart: b2 enters b1 by 10 mm."""
        _, report = _check(tmp_path, _stack(-10))
        (d,) = _errors(report)
        assert set(d.bodies) == {"b1", "b2"}
        assert d.amount is not None and d.amount.value == pytest.approx(10.0, abs=0.05)


CARRY = """use cell "cell.rmot"
program carry on r1 {
  tool gripper
  frame world
  speed 250 mm/s
  target down = pose(rx=180deg)
  move joint joints(0, -90, 90, -90, -90, 0) deg
  move joint b1 * pose(z=150mm) * down
  move linear b1 * pose(z=50mm) * down zone fine
  attach b1
  move linear b1 * pose(z=150mm) * down zone fine
  move linear b1 * pose(y=-300mm, z=150mm) * down zone fine
  detach b1
}
"""


def test_part_carried_through_a_fixture_is_found_at_the_move_and_time(tmp_path: Path) -> None:
    """A 20 mm wall across the path (y -310..-290 mm, top at z = 330 mm): the carried cube
    (centre z = 350 mm, bottom 300 mm) hits it, the gripper (from z = 400 mm up) passes over.
    The cube's leading face (centre - 50 mm) reaches the wall at y = -290 mm, so contact
    starts with the TCP (over the cube's centre) at y = -240 mm."""
    wall = "\n  fixture wall = box(300mm, 20mm, 130mm) at pose(x=650mm, y=-300mm, z=265mm)"
    plan, report = _check(tmp_path, CARRY, wall)
    (d,) = _errors(report)
    assert d.code.id == "E300" and set(d.bodies) == {"b1", "wall"}
    assert d.span.start.line == 12
    tp = plan.tasks[0]
    rec = next(r for r in tp.records if r.span is not None and r.span.start.line == 12)
    assert rec.t_start <= d.time_s <= rec.t_end
    # where the TCP is at the reported start, by forward kinematics (not the collision code)
    robot = load_robot("ur10e")
    base = np.eye(4)
    base[:3, :3] = [[-1, 0, 0], [0, -1, 0], [0, 0, 1]]  # rz = 180 deg
    base[2, 3] = 0.4
    tcp = base @ np.asarray(robot.fk(tp.trajectory.at(d.time_s)))
    tcp = tcp @ np.array([0, 0, 0.1, 1.0])
    assert tcp[1] == pytest.approx(-0.240, abs=0.002)
    assert d.amount is not None and d.amount.value > 0


def test_attach_far_from_the_tool_is_an_error_with_the_distance(tmp_path: Path) -> None:
    """At home the TCP is far from b1: E330 at the attach, and the distance is the TCP's."""
    program = CARRY.replace("  move joint b1 * pose(z=150mm) * down\n  move linear b1 * pose(z=50mm) * down zone fine\n", "")
    plan, report = _check(tmp_path, program)
    e330 = [d for d in _errors(report) if d.code.id == "E330"]
    assert len(e330) == 1 and e330[0].span.start.line == 8
    # independent: distance from the TCP at home to the cube (axis-aligned box, 100 mm)
    robot = load_robot("ur10e")
    base = np.eye(4)
    base[:3, :3] = [[-1, 0, 0], [0, -1, 0], [0, 0, 1]]
    base[2, 3] = 0.4
    q = np.radians([0, -90, 90, -90, -90, 0])
    flange = base @ np.asarray(robot.fk(q))
    # points of the gripper's solid (60 x 60 x 100 mm from the flange to the TCP) every 5 mm, and the TCP
    g = np.stack(np.meshgrid(np.linspace(-0.03, 0.03, 13), np.linspace(-0.03, 0.03, 13), np.linspace(0, 0.1, 21)), -1).reshape(-1, 3)
    points = (flange @ np.c_[g, np.ones(len(g))].T).T[:, :3]
    centre = np.array([0.65, -0.15, 0.25])
    outside = np.maximum(np.abs(points - centre) - 0.05, 0.0)  # to the axis-aligned 100 mm cube
    nearest = float(np.min(np.linalg.norm(outside, axis=1))) * 1000
    assert e330[0].amount.value == pytest.approx(nearest, abs=4.0)


def test_overweight_tool_is_an_error_with_both_masses(tmp_path: Path) -> None:
    """An 80 kg tool on a UR10e (rated 12.5 kg, UR10e datasheet): E332 at the first move."""
    program = "use cell \"cell.rmot\"\nprogram heavy on r1 {\n  tool big\n  move joint joints(0, -90, 90, -90, -90, 0) deg\n}\n"
    _, report = _check(tmp_path, program, "\n  tool big = none tcp pose(z=100mm) mass 80 kg on r1")
    (d,) = [d for d in _errors(report) if d.code.id == "E332"]
    assert "80 kg" in d.message and "12.5 kg" in d.message and d.span.start.line == 4


def test_part_making_the_load_too_heavy_is_found_at_the_first_move_carrying_it(tmp_path: Path) -> None:
    """1 kg tool + a 12 kg part = 13 kg > 12.5 kg: E332 at the first move after the attach,
    not before it."""
    extra = "\n  part heavy = box(100mm, 100mm, 100mm) at pose(x=650mm, y=150mm, z=250mm) mass 12 kg"
    program = CARRY.replace("b1", "heavy")
    plan, report = _check(tmp_path, program, extra)
    (d,) = [d for d in _errors(report) if d.code.id == "E332"]
    assert d.span.start.line == 11
    assert "13 kg" in d.message and "12.5 kg" in d.message and "'heavy' 12 kg" in d.message


WALL = "\n  fixture wall = box(300mm, 20mm, 130mm) at pose(x=650mm, y=-300mm, z=265mm)"


def test_runtime_if_arm_carrying_the_part_into_the_wall_is_found_on_that_path(tmp_path: Path) -> None:
    """The `then` arm carries b1 away from the wall (+y), the `otherwise` arm through it: one
    finding, on the otherwise path, naming the part and the wall."""
    program = CARRY.replace(
        "  move linear b1 * pose(y=-300mm, z=150mm) * down zone fine\n",
        "  if in[3] == on {\n    move linear b1 * pose(x=-100mm, z=150mm) * down zone fine\n  } else {\n"
        "    move linear b1 * pose(y=-300mm, z=150mm) * down zone fine\n  }\n")
    _, report = _check(tmp_path, program, WALL)
    (d,) = _errors(report)
    assert set(d.bodies) == {"b1", "wall"} and "otherwise" in d.message and d.span.start.line == 15


HANDOVER = Path(__file__).resolve().parents[2] / "examples" / "handover.rmot"


def test_handover_example_part_moves_from_r1_to_r2_and_ends_on_the_outfeed() -> None:
    """examples/handover.rmot: the block is held by r1, then by r2, and is left on r2's
    outfeed (top at z = 700 mm, 400 x 400 mm around (1450, -600) mm)."""
    from rmot.sim.parts import phases
    from rmot.sim.scene import build_scene

    front = load_program(str(HANDOVER))
    assert front.program is not None
    plan = plan_program(front.program)
    report = verify(plan)
    assert _errors(report) == []
    scene = build_scene(front.program.cell)
    found: list = []
    states = phases(scene, plan, None, found)
    assert found == []
    holders = []
    for ph in states:
        holder = ph.held["block"][0] if "block" in ph.held else None
        if not holders or holders[-1] != holder:
            holders.append(holder)
    assert holders == [None, "r1", None, "r2", None]
    final = states[-1].placed["block"][:3, 3]
    assert final[0] > 1.25 and final[0] < 1.65 and final[1] > -0.8 and final[1] < -0.4 and final[2] > 0.7


def test_attach_while_another_robot_holds_the_part_is_an_error() -> None:
    """r2 attaching before the barrier after which r1 lets go (`sync gripped`): E331 at r2's attach."""
    text = HANDOVER.read_text(encoding="utf-8")
    moved = text.replace("    sync gripped\n    sync released\n    attach block", "    attach block\n    sync gripped\n    sync released", 1)
    assert moved != text
    from rmot.compiler.frontend import load_text

    front = load_text(moved, str(HANDOVER))
    assert front.program is not None
    report = verify(plan_program(front.program))
    (d,) = [d for d in _errors(report) if d.code.id == "E331"]
    assert "'block'" in d.message and "'r1'" in d.message
    assert moved.splitlines()[d.span.start.line - 1].strip() == "attach block"


def test_torque_check_payload_is_tool_plus_held_part_at_their_centres() -> None:
    """stack.rmot: 1 kg gripper at 50 mm (half its 100 mm TCP offset) plus the 2 kg cube whose
    centre is 150 mm from the flange (held by its top face, 50 mm beyond the TCP): 3 kg at
    (1 * 50 + 2 * 150) / 3 = 116.67 mm along the flange z axis."""
    from rmot.sim.scene import build_scene, flange_in_last_joint
    from rmot.sim.verification import _payload

    front = load_program(str(DATA / "stack.rmot"))
    assert front.program is not None
    plan = plan_program(front.program)
    scene = build_scene(front.program.cell)
    mass, at = _payload(scene, plan.tasks[0], plan)
    assert mass == pytest.approx(3.0)
    flange = flange_in_last_joint(scene.robots["r1"].robot)
    expected = flange[:3, :3] @ np.array([0.0, 0.0, 0.35 / 3]) + flange[:3, 3]
    np.testing.assert_allclose(at, expected, atol=2e-5)  # the planned stop is within microns of the target


def test_mesh_part_overlapping_a_fixture_where_it_starts_is_w300(tmp_path: Path) -> None:
    """A mesh part (the 300 x 200 x 80 mm jig of examples/urdf_cell) declared 40 mm into a
    table: the overlap is reported once, as for two fixtures (W300), naming the part."""
    shutil.copy(Path(__file__).resolve().parents[2] / "examples" / "urdf_cell" / "meshes" / "jig.stl", tmp_path / "jig.stl")
    program = "use cell \"cell.rmot\"\nprogram p on r1 {\n  move joint joints(0, -90, 90, -90, -90, 0) deg\n}\n"
    extra = ('\n  fixture slab = box(400mm, 400mm, 100mm) at pose(x=-600mm, z=50mm)'
             '\n  part jig = mesh("jig.stl", unit=mm) at pose(x=-600mm, z=60mm)')
    _, report = _check(tmp_path, program, extra)
    w300 = [d for d in report.diagnostics if d.code.id == "W300"]
    assert [set(d.bodies) for d in w300] == [{"jig", "slab"}]
    assert _errors(report) == []


def test_overweight_only_on_an_if_arm_is_found_on_that_path(tmp_path: Path) -> None:
    """The `otherwise` arm lifts a 12 kg part (1 kg tool + 12 kg > 12.5 kg): E332 at that arm's
    first move carrying it, said to be on the otherwise path; the `then` arm only waits."""
    program = """use cell "cell.rmot"
program p on r1 {
  tool gripper
  frame world
  target down = pose(rx=180deg)
  move joint joints(0, -90, 90, -90, -90, 0) deg
  move joint heavy * pose(z=150mm) * down
  move linear heavy * pose(z=50mm) * down zone fine
  if in[3] == on {
    wait 1 s
  } else {
    attach heavy
    move linear heavy * pose(z=80mm) * down zone fine
    move linear heavy * pose(z=50mm) * down zone fine
    detach heavy
  }
  move linear heavy * pose(z=150mm) * down
}
"""
    extra = "\n  part heavy = box(100mm, 100mm, 100mm) at pose(x=650mm, y=300mm, z=250mm) mass 12 kg"
    _, report = _check(tmp_path, program, extra)
    (d,) = [d for d in _errors(report) if d.code.id == "E332"]
    assert d.span.start.line == 13 and "otherwise" in d.message and "13 kg" in d.message


def test_clearance_reports_part_gaps_but_not_the_pick_and_place_themselves(tmp_path: Path) -> None:
    """With 10 mm between the cubes: a 5 mm clearance gives nothing (the gripper on its cube
    and a cube on its table are the pick and place, not approaches); 20 mm names the cubes."""
    from rmot.sim.verification import verify as verify_

    plan, _ = _check(tmp_path, _stack(10))
    assert [d for d in verify_(plan, clearance=0.005).diagnostics if d.code.id == "W301"] == []
    near = [d for d in verify_(plan, clearance=0.020).diagnostics if d.code.id == "W301"]
    assert near and all(set(d.bodies) == {"b1", "b2"} for d in near)
    assert near[0].amount.value == pytest.approx(10.0, abs=0.05)
