"""`rmot compare` stands every library arm on the slot robot's pedestal: the lowest point of the
arm's base solid is the pedestal's top, whatever the height of the arm's base frame (a
Fanuc's is at J2, hundreds of mm above its mounting face).

Witness: trimesh tessellates the arm's base solid at its world pose and the cell's pedestal
fixture at its pose; their lowest and highest vertices are compared (not rmot's mounting_z)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import trimesh

from rmot.compiler.design.compare import stand_in
from rmot.compiler.frontend import load_program
from rmot.lang import ir
from rmot.sim.robots import load_robot
from rmot.sim.robots.library import SPECS

ROOT = Path(__file__).resolve().parents[2]
PICK = ROOT / "examples" / "pick_place.rmot"  # on the default cell: an IRB 1600 on a 400 mm pedestal


def _mesh(geometry: ir.Geometry, pose: np.ndarray) -> trimesh.Trimesh:
    if isinstance(geometry, ir.Cylinder):
        return trimesh.creation.cylinder(radius=geometry.radius, height=geometry.height, transform=pose, sections=64)
    if isinstance(geometry, ir.Box):
        return trimesh.creation.box(extents=geometry.size, transform=pose)
    raise AssertionError(f"no witness for {geometry}")


@pytest.fixture(scope="module")
def program() -> ir.Program:
    front = load_program(str(PICK))
    assert front.program is not None
    return front.program


def _pedestal_top(program: ir.Program) -> float:
    pedestal = next(f for f in program.cell.fixtures if f.name == "pedestal")
    return float(_mesh(pedestal.geometry, pedestal.pose.matrix()).bounds[1][2])


@pytest.mark.parametrize("name", sorted(SPECS))
def test_every_library_arm_stands_on_the_pedestal_top(program: ir.Program, name: str) -> None:
    robot = load_robot(name)
    placed = stand_in(program, "r1", name, robot)
    base = placed.cell.robot("r1").base.matrix()
    lows = [_mesh(s.geometry, base @ s.placement.matrix()).bounds[0][2] for s in robot.solids if s.joint_id == 0]
    assert lows, name
    assert min(lows) == pytest.approx(_pedestal_top(program), abs=1e-6)
    np.testing.assert_allclose(base[:3, :3], program.cell.robot("r1").base.matrix()[:3, :3], atol=1e-12)


def test_a_fanuc_base_frame_sits_at_its_j2_height_above_the_pedestal(program: ir.Program) -> None:
    """The LR Mate 200iD's controller frame is 330 mm above its mounting face (ROS-I
    fanuc_lrmate200id_support: base_link to J2 330 mm): 400 + 330 mm over the floor."""
    placed = stand_in(program, "r1", "fanuc_lrmate200id", load_robot("fanuc_lrmate200id"))
    assert placed.cell.robot("r1").base.matrix()[2, 3] == pytest.approx(0.730, abs=1e-9)


def test_the_world_targets_stay_in_the_world(program: ir.Program) -> None:
    """Lifting the base re-expresses base-frame targets: each Cartesian target's world pose is unchanged."""
    placed = stand_in(program, "r1", "fanuc_m20ia", load_robot("fanuc_m20ia"))

    def world(prog: ir.Program) -> list[np.ndarray]:
        base = prog.cell.robot("r1").base.matrix()
        return [base @ m.target.pose.matrix() for t in prog.tasks for m in _moves(t.body)
                if isinstance(m.target, ir.CartesianTarget)]

    before, after = world(program), world(placed)
    assert len(before) == len(after) > 0
    for a, b in zip(before, after):
        np.testing.assert_allclose(a, b, atol=1e-9)


def _moves(body: tuple[ir.Instr, ...]) -> list[ir.Move]:
    from rmot.lang import ir_tree

    return [i for i in ir_tree.walk(body) if isinstance(i, ir.Move)]
