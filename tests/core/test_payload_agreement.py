"""Every reader of the payload gets the plan's one decided load: the planner's torque bound, the
verification's torque check and each backend's payload line agree on mass and centre of gravity
for a tool and an off-centre mesh part.

Witness, by hand (and trimesh for the mesh's centre of mass): the gripper is 1 kg with its TCP
100 mm along the flange z axis (its mass at 50 mm, half way: ir.payload_cog). The part is a
2 kg block from a mesh file spanning x -50..150, y -50..90, z -50..50 mm around its pose
origin, so its centroid is at (50, 20, 0) mm in its own frame, not at the origin. The gripper
takes it with the TCP at pose(z=50mm) * rx(180deg) in the part frame (on the top face over the
origin), so the centroid in the TCP frame is Rx(180)^T (50, 20, -50) = (50, -20, 50) mm and in
the flange frame (50, -20, 150) mm. Tool + part: 3 kg at ((0, 0, 50) + 2 (50, -20, 150)) / 3 =
(33.333, -13.333, 116.667) mm.
"""

from __future__ import annotations

import re
from typing import Any

import numpy as np
import pytest
import trimesh

from rmot.backends import BACKENDS
from rmot.compiler.frontend import load_program
from rmot.compiler.plan import plan_program

PART_IN_FLANGE = np.array([0.050, -0.020, 0.150])  # m, by hand (module doc)
TOTAL_COG = (np.array([0.0, 0.0, 0.050]) * 1.0 + PART_IN_FLANGE * 2.0) / 3.0

CELL = """cell mesh_cell {
  robot r1 = ur10e at pose(z=400mm, rz=180deg)
  fixture pedestal = cylinder(r=100mm, h=400mm) at pose(z=200mm)
  fixture infeed  = box(400mm, 600mm, 200mm) at pose(x=700mm, z=100mm)
  frame world = pose()
  tool gripper = box(60mm, 60mm, 100mm) at pose(z=50mm) tcp pose(z=100mm) mass 1 kg on r1
  part block = mesh("block.obj", unit=mm) at pose(x=650mm, y=0mm, z=250mm) mass 2 kg
}
"""
PROGRAM = """use cell "cell.rmot"
program pick on r1 {
  tool gripper
  frame world
  speed 500 mm/s
  target down = pose(rx=180deg)
  target home = joints(0, -90, 90, -90, -90, 0) deg
  move joint home
  move joint block * pose(z=150mm) * down
  move linear block * pose(z=50mm) * down zone fine
  attach block
  move linear block * pose(z=150mm) * down
  move joint home zone fine
}
"""


@pytest.fixture(scope="module")
def made(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Any]:
    """The cell, the program and its plan, with what the planner's torque bound and the
    verification's torque check were handed (recorded on the way)."""
    root = tmp_path_factory.mktemp("payload")
    block = trimesh.creation.box(extents=(200.0, 140.0, 100.0))
    block.apply_translation((50.0, 20.0, 0.0))
    np.testing.assert_allclose(block.center_mass, [50.0, 20.0, 0.0], atol=1e-9)  # the witness
    block.export(root / "block.obj")
    (root / "cell.rmot").write_text(CELL, encoding="utf-8")
    (root / "pick.rmot").write_text(PROGRAM, encoding="utf-8")
    front = load_program(str(root / "pick.rmot"))
    assert front.program is not None, [str(d) for d in front.diagnostics]
    seen: dict[str, Any] = {}
    mp = pytest.MonkeyPatch()
    from rmot.compiler.plan import torque
    from rmot.sim import verification

    def bound(robot: Any, mass: float, at: np.ndarray | None) -> Any:
        seen["planner"] = (mass, None if at is None else np.array(at))
        return real_bound(robot, mass, at)

    def check(robot: Any, traj: Any, payload: float = 0.0, payload_at: np.ndarray | None = None) -> Any:
        seen["verifier"] = (robot, payload, None if payload_at is None else np.array(payload_at))
        return real_check(robot, traj, payload, payload_at)

    real_bound, real_check = torque.torque_limits, verification.check_limits
    mp.setattr(torque, "torque_limits", bound)
    mp.setattr(verification, "check_limits", check)
    try:
        plan = plan_program(front.program)
        verification.verify(plan)
    finally:
        mp.undo()
    assert not [d for d in plan.diagnostics if d.severity.name == "ERROR"], [str(d) for d in plan.diagnostics]
    return {"plan": plan, **seen}


def test_the_planners_torque_bound_takes_the_part_at_its_centroid(made: dict[str, Any]) -> None:
    mass, at = made["planner"]
    assert mass == pytest.approx(3.0)
    np.testing.assert_allclose(at, TOTAL_COG, atol=1e-9)


def test_the_verifications_torque_check_takes_the_same_load(made: dict[str, Any]) -> None:
    """The check puts the point mass on the last joint: the hand value mapped into that joint's
    frame by pinocchio's own kinematics (flange = last joint * constant offset)."""
    import pinocchio as pin

    robot, mass, at = made["verifier"]
    assert mass == pytest.approx(3.0)
    q = np.zeros(robot.dof)
    data = robot.model.createData()
    pin.forwardKinematics(robot.model, data, np.asarray(robot.to_model(q), dtype=float))
    flange_in_joint = np.linalg.inv(data.oMi[robot.dof].homogeneous) @ np.asarray(robot.fk(q))
    np.testing.assert_allclose(at, (flange_in_joint @ np.append(TOTAL_COG, 1.0))[:3], atol=1e-9)


def _emit(made: dict[str, Any], vendor: str) -> Any:
    return BACKENDS[vendor]().emit(made["plan"])


def test_rapid_grip_load_is_the_part_in_the_tool_frame(made: dict[str, Any]) -> None:
    """GripLoad's loaddata is the held part alone, cog in the tool (TCP) frame: (50, -20, 50) mm."""
    text = "\n".join(_emit(made, "rapid").files.values())
    decl = re.search(r"PERS loaddata load_block:=\[([^,]+),\[([^\]]+)\]", text)
    assert decl is not None, text
    assert float(decl.group(1)) == pytest.approx(2.0)
    assert [float(x) for x in decl.group(2).split(",")] == pytest.approx([50.0, -20.0, 50.0], abs=1e-3)


def test_krl_load_data_is_tool_and_part_in_the_flange_frame(made: dict[str, Any]) -> None:
    dat = next(t for n, t in _emit(made, "krl").files.items() if n.endswith(".dat"))
    m = re.search(r"DECL LOAD \w*block\w*=\{M ([\d.]+),CM \{X ([-\d.]+),Y ([-\d.]+),Z ([-\d.]+)", dat)
    assert m is not None, dat
    assert float(m.group(1)) == pytest.approx(3.0)
    assert [float(m.group(k)) for k in (2, 3, 4)] == pytest.approx(TOTAL_COG * 1000, abs=1e-3)


def test_urscript_set_payload_is_tool_and_part_in_the_flange_frame(made: dict[str, Any]) -> None:
    (text,) = _emit(made, "urscript").files.values()
    calls = re.findall(r"set_payload\(([\d.]+), \[([^\]]+)\]\)", text)
    held = [(float(m), [float(c) for c in cog.split(",")]) for m, cog in calls if float(m) == pytest.approx(3.0)]
    assert held, text
    assert held[0][1] == pytest.approx(TOTAL_COG, abs=1e-6)


@pytest.mark.parametrize("vendor", ["fanuc", "inform", "val3"])
def test_the_payload_to_enter_on_the_controller_is_the_same(made: dict[str, Any], vendor: str) -> None:
    """Fanuc's payload schedule (PAYLOAD[i]), INFORM's and VAL3's controller setting: W460 names
    3 kg at the same centre of gravity (mm, one decimal)."""
    messages = [d.message for d in _emit(made, vendor).diagnostics if d.code.id == "W460"]
    cog = "[" + ",".join(f"{v:.1f}" for v in TOTAL_COG * 1000) + "] mm"
    assert any("3.000 kg" in m and cog in m for m in messages), (cog, messages)


def test_a_mesh_centroid_is_the_solids_centre_of_mass() -> None:
    """sim/meshio.centroid against trimesh's center_mass on an irregular closed solid (the
    convex hull of scattered points, far from its origin), and on an open surface (one face of
    a cube removed: trimesh's surface centroid, area-weighted, is the witness)."""
    from rmot.sim.meshio import MeshData, centroid

    rng = np.random.default_rng(7)
    hull = trimesh.convex.convex_hull(rng.normal(size=(40, 3)) * [0.3, 0.1, 0.05] + [0.4, -0.2, 0.1])
    assert hull.is_volume
    got = centroid(MeshData(np.array(hull.vertices, dtype=float), np.array(hull.faces, dtype=np.int64)))
    np.testing.assert_allclose(got, hull.center_mass, atol=1e-12)
    box = trimesh.creation.box(extents=(0.2, 0.1, 0.1))
    box.apply_translation((0.3, 0.0, 0.0))
    up = box.face_normals[:, 2] > 0.5
    open_box = trimesh.Trimesh(box.vertices, box.faces[~up], process=False)
    got = centroid(MeshData(np.array(open_box.vertices, dtype=float), np.array(open_box.faces, dtype=np.int64)))
    np.testing.assert_allclose(got, open_box.triangles_center.T @ open_box.area_faces / open_box.area, atol=1e-12)
