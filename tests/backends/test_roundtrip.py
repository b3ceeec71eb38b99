"""Numeric round trips: read the numbers back from each emitted file, rebuild the flange pose
with that vendor's convention written independently here (scipy), and compare it with FK of
the planned joints; decode the configuration data back to the planned branch."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from rmot.backends.fanuc_tp import FanucBackend
from rmot.backends.krl import KrlBackend
from rmot.backends.rapid import RapidBackend
from rmot.lang import ir, plan_types

PROGRAM = """
program roundtrip on r1 {
  tool gripper
  frame table_top
  speed 250 mm/s
  zone 5 mm
  target home = joints(0, -20, 30, 0, 50, 0) deg
  move joint home
  move joint pose(x=-100mm, y=50mm, z=200mm, rx=180deg, rz=30deg)
  move linear pose(x=100mm, y=-50mm, z=150mm, rx=170deg, ry=10deg)
  move circular via pose(x=150mm, y=0mm, z=150mm, rx=180deg) to pose(x=100mm, y=50mm, z=150mm, rx=180deg, rz=-20deg) zone fine
  move joint pose(x=0mm, y=0mm, z=300mm, rx=180deg) config(shoulder=front, elbow=up, wrist=flip)
  move linear pose(x=-50mm, y=80mm, z=250mm, rx=160deg, ry=-15deg, rz=75deg)
}
"""
MM, DEG = 0.01, 0.001  # tolerances: mm and degrees


def homogeneous(rot: np.ndarray, xyz_mm: list[float]) -> np.ndarray:
    m = np.eye(4)
    m[:3, :3] = rot
    m[:3, 3] = np.array(xyz_mm) / 1000.0
    return m


def assert_same_pose(a: np.ndarray, b: np.ndarray) -> None:
    """Positions within 0.01 mm and rotations within 0.001 deg."""
    assert np.linalg.norm(a[:3, 3] - b[:3, 3]) * 1000.0 < MM
    angle = Rotation.from_matrix(a[:3, :3].T @ b[:3, :3]).magnitude()
    assert math.degrees(angle) < DEG


@pytest.fixture(scope="module")
def plan(plan_from_text) -> plan_types.Plan:  # type: ignore[no-untyped-def]
    return plan_from_text(PROGRAM, "roundtrip.rmot")


@pytest.fixture(scope="module")
def robot(plan: plan_types.Plan):  # type: ignore[no-untyped-def]
    from rmot.sim.robots import load_robot

    return load_robot(plan.program.cell.robot("r1").source.load_key)


def moves(plan: plan_types.Plan) -> list[tuple[ir.Move, plan_types.InstructionRecord]]:
    tp = plan.tasks[0]
    return [(m, tp.record(m.uid)) for m in tp.task.body if isinstance(m, ir.Move)]


def cartesian_records(plan: plan_types.Plan) -> list[plan_types.InstructionRecord]:
    return [r for m, r in moves(plan) if isinstance(m.target, ir.CartesianTarget)]


class TestRapid:
    def test_poses_and_confdata(self, plan: plan_types.Plan, robot) -> None:  # type: ignore[no-untyped-def]
        """robtarget (mm, quaternion w-first) in wobj with tooldata -> flange = FK(q); confdata -> branch."""
        text = RapidBackend().emit(plan).files["roundtrip.mod"]
        num = r"(-?[\d.]+)"
        tool = re.search(r"tooldata gripper:=\[TRUE,\[\[(.*?)\],\[(.*?)\]\]", text)
        wobj = re.search(r"wobjdata table_top:=\[FALSE,TRUE,\"\",\[\[(.*?)\],\[(.*?)\]\]", text)

        def pose(xyz: str, quat: str) -> np.ndarray:
            w, x, y, z = (float(v) for v in quat.split(","))
            return homogeneous(Rotation.from_quat([x, y, z, w]).as_matrix(), [float(v) for v in xyz.split(",")])

        t_tool, t_wobj = pose(*tool.groups()), pose(*wobj.groups())
        called = re.findall(r"Move[JL] (\w+),|MoveC \w+, (\w+),", text)
        names = [a or b for a, b in called]
        targets = {m[0]: m[1:] for m in re.findall(
            r"robtarget (\w+):=\[\[(.*?)\],\[(.*?)\],\[" + ",".join([num] * 4) + r"\]", text)}
        records = cartesian_records(plan)
        assert len(names) == len(records) == 5
        for name, rec in zip(names, records):
            xyz, quat, *cf = targets[name]
            flange = t_wobj @ pose(xyz, quat) @ np.linalg.inv(t_tool)
            assert_same_pose(flange, robot.fk(rec.q_target))
            q = np.degrees(rec.q_target)
            for c, i in zip(cf[:3], (0, 3, 5)):  # axis i+1 lies in quadrant cf (to rounding noise)
                assert int(c) * 90.0 - 1e-6 <= q[i] < (int(c) + 1) * 90.0 + 1e-6
            cfx = int(cf[3])
            decoded = ir.Config(ir.Shoulder.BACK if cfx & 4 else ir.Shoulder.FRONT,
                                ir.Elbow.DOWN if cfx & 2 else ir.Elbow.UP,
                                ir.Wrist.FLIP if cfx & 1 else ir.Wrist.NOFLIP)
            assert decoded == robot.branch(rec.q_target) == rec.branch

    def test_joint_target(self, plan: plan_types.Plan) -> None:
        """The jointtarget holds the joints in degrees."""
        text = RapidBackend().emit(plan).files["roundtrip.mod"]
        values = re.search(r"jointtarget home:=\[\[(.*?)\]", text).group(1)
        np.testing.assert_allclose([float(v) for v in values.split(",")], [0, -20, 30, 0, 50, 0], atol=1e-3)


class TestKrl:
    def test_poses_status_turn(self, plan: plan_types.Plan, robot) -> None:  # type: ignore[no-untyped-def]
        """E6POS (mm, A B C = Rz·Ry·Rx) in $BASE with $TOOL -> flange = FK(q); S and T -> branch and signs."""
        files = KrlBackend().emit(plan).files
        dat = files["roundtrip.dat"]

        def frame(body: str) -> tuple[np.ndarray, dict[str, float]]:
            vals = {k: float(v) for k, v in re.findall(r"([A-Z]\d?) (-?[\d.]+)", body)}
            rot = Rotation.from_euler("ZYX", [vals["A"], vals["B"], vals["C"]], degrees=True).as_matrix()
            return homogeneous(rot, [vals["X"], vals["Y"], vals["Z"]]), vals

        decl = {n: b for n, b in re.findall(r"DECL \w+ (\w+)=\{(.*)\}", dat)}
        t_tool, _ = frame(decl["gripper"])
        t_base, _ = frame(decl["table_top"])
        names = re.findall(r"^\s*(?:PTP|LIN) (\w+)|^\s*CIRC \w+,(\w+)", files["roundtrip.src"], re.M)
        cart = [a or b for a, b in names if (a or b) != "home"]
        records = cartesian_records(plan)
        assert len(cart) == len(records) == 5
        for name, rec in zip(cart, records):
            target, vals = frame(decl[name])
            assert_same_pose(t_base @ target @ np.linalg.inv(t_tool), robot.fk(rec.q_target))
            s, t = int(vals["S"]), int(vals["T"])
            decoded = ir.Config(ir.Shoulder.BACK if s & 1 else ir.Shoulder.FRONT,
                                ir.Elbow.UP if s & 2 else ir.Elbow.DOWN,
                                ir.Wrist.FLIP if s & 4 else ir.Wrist.NOFLIP)
            assert decoded == robot.branch(rec.q_target)
            # the sign the controller sees: the angle as E6AXIS prints it (4 decimals in degrees);
            # planner float noise around 0 (-1e-16 rad) is not negative
            assert [bool(t >> i & 1) for i in range(6)] == [round(math.degrees(v), 4) < 0 for v in rec.q_target]


class TestFanuc:
    def test_poses_and_config(self, plan: plan_types.Plan, robot) -> None:  # type: ignore[no-untyped-def]
        """X Y Z W P R (fixed XYZ) in UFRAME with UTOOL -> flange = FK(q); CONFIG -> branch and turns."""
        text = FanucBackend().emit(plan).files["ROUNDTRIP.ls"]

        def pr_pose(index: int) -> np.ndarray:
            vals = [float(v) for v in re.findall(rf"PR\[{index},\d\]=(-?[\d.]+)", text)]
            rot = Rotation.from_euler("xyz", vals[3:], degrees=True).as_matrix()
            return homogeneous(rot, vals[:3])

        tools = dict(re.findall(r"UTOOL\[(\d+)\]=PR\[(\d+)\]", text))
        frames = dict(re.findall(r"UFRAME\[(\d+)\]=PR\[(\d+)\]", text))
        positions = re.findall(r"P\[(\d+)[^\]]*\]\{\s*GP1:\s*UF : (\d+), UT : (\d+),\s*CONFIG : '(.*?)',"
                               r"\s*X =\s*(\S+)\s+mm,\s*Y =\s*(\S+)\s+mm,\s*Z =\s*(\S+)\s+mm,"
                               r"\s*W =\s*(\S+) deg,\s*P =\s*(\S+) deg,\s*R =\s*(\S+) deg", text)
        order = [int(n) for n in re.findall(r"[JL] P\[(\d+)\]|:  P\[(\d+)\]", text) for n in n if n]
        by_number = {int(p[0]): p for p in positions}
        cart = [by_number[n] for n in order if n in by_number]
        records = cartesian_records(plan)
        assert len(cart) == len(records) == 5
        for p, rec in zip(cart, records):
            _, uf, ut, config, *xyzwpr = p
            vals = [float(v) for v in xyzwpr]
            target = homogeneous(Rotation.from_euler("xyz", vals[3:], degrees=True).as_matrix(), vals[:3])
            flange = pr_pose(int(frames[uf])) @ target @ np.linalg.inv(pr_pose(int(tools[ut])))
            assert_same_pose(flange, robot.fk(rec.q_target))
            flags, *turns = [c.strip() for c in config.split(",")]
            f, u, t = flags.split()
            q = rec.q_target
            decoded = ir.Config(ir.Shoulder.FRONT if t == "T" else ir.Shoulder.BACK,
                                ir.Elbow.UP if u == "U" else ir.Elbow.DOWN,
                                ir.Wrist.FLIP if f == "N" else ir.Wrist.NOFLIP)  # Fanuc N: J5 < 0
            assert decoded == robot.branch(q)
            for turn, i in zip(turns, (3, 4, 5)):  # turn k covers (-180 + 360k, 180 + 360k] deg
                assert -180.0 + 360.0 * int(turn) - 1e-6 <= math.degrees(q[i]) <= 180.0 + 360.0 * int(turn) + 1e-6
