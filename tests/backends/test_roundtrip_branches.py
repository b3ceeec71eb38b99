"""Property round trip over random joint solutions of every 6R vendor arm: whatever the branch
(front/back, up/down, flip/noflip) and turns, the emitted pose rebuilt with the vendor's
convention (scipy, written here) equals FK of the joints, and the configuration data decodes
to the robot's own branch of those joints."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
from backend_fixtures import GRIPPER, TABLE, cart, hand_plan, move
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from rmot.backends.fanuc_tp import FanucBackend
from rmot.backends.krl import KrlBackend
from rmot.backends.rapid import RapidBackend
from rmot.lang import ir

fractions = st.lists(st.floats(0.02, 0.98), min_size=6, max_size=6)
FRONT, BACK = ir.Shoulder.FRONT, ir.Shoulder.BACK
UP, DOWN = ir.Elbow.UP, ir.Elbow.DOWN
FLIP, NOFLIP = ir.Wrist.FLIP, ir.Wrist.NOFLIP


def _robot(name: str):  # type: ignore[no-untyped-def]
    from rmot.sim.robots import load_robot

    return load_robot(name)


def _plan(robot, q: np.ndarray):  # type: ignore[no-untyped-def]
    """One linear move to FK(q) written in TABLE with GRIPPER; the record holds q and its branch."""
    tcp = ir.Pose.from_matrix(robot.fk(q)) * GRIPPER.tcp
    in_frame = TABLE.pose.inverse() * tcp
    node = move(1, ir.MotionKind.LINEAR, cart(in_frame, TABLE, "t"), tool=GRIPPER, frame=TABLE)
    return hand_plan((node,), {1: (q, robot.branch(q))}, robot=robot.name)


def _h(rot: np.ndarray, xyz_mm: list[float]) -> np.ndarray:
    m = np.eye(4)
    m[:3, :3], m[:3, 3] = rot, np.array(xyz_mm) / 1000.0
    return m


def _close(a: np.ndarray, b: np.ndarray, deg_tol: float = 1e-3) -> None:
    assert np.linalg.norm(a[:3, 3] - b[:3, 3]) < 1e-5  # 0.01 mm
    assert math.degrees(Rotation.from_matrix(a[:3, :3].T @ b[:3, :3]).magnitude()) < deg_tol


def _flange(target: np.ndarray) -> np.ndarray:
    """The flange in the robot base for a TCP `target` written in the table frame (z 15 mm up,
    500 mm out) with the 150 mm tool of _plan."""
    return _h(np.eye(3), [500, 0, 15]) @ target @ np.linalg.inv(_h(np.eye(3), [0, 0, 150]))


def _q(robot, f: list[float]) -> np.ndarray:  # type: ignore[no-untyped-def]
    lo, hi = robot.joint_limits[:, 0], robot.joint_limits[:, 1]
    q = lo + np.array(f) * (hi - lo)
    return q


@settings(max_examples=60, deadline=None)
@given(fractions)
def test_rapid_any_branch(f: list[float]) -> None:
    """robtarget + confdata of any IRB 120 configuration decode to FK(q) and its branch."""
    robot = _robot("abb_irb120")
    q = _q(robot, f)
    text = RapidBackend().emit(_plan(robot, q)).files["demo.mod"]
    nums = lambda s: [float(v) for v in s.split(",")]  # noqa: E731
    x, quat, conf = re.search(r"robtarget t:=\[\[(.*?)\],\[(.*?)\],\[(.*?)\]", text).groups()
    w, qx, qy, qz = nums(quat)
    _close(_flange(_h(Rotation.from_quat([qx, qy, qz, w]).as_matrix(), nums(x))), robot.fk(q))
    cf1, cf4, cf6, cfx = (int(v) for v in conf.split(","))
    for c, i in ((cf1, 0), (cf4, 3), (cf6, 5)):
        assert c * 90 - 1e-6 <= math.degrees(q[i]) < (c + 1) * 90 + 1e-6
    assert ir.Config(BACK if cfx & 4 else FRONT, DOWN if cfx & 2 else UP, FLIP if cfx & 1 else NOFLIP) == robot.branch(q)


@settings(max_examples=60, deadline=None)
@given(fractions)
def test_krl_any_branch(f: list[float]) -> None:
    """E6POS with S and T of any KR 6 R900 configuration decodes to FK(q), its branch and axis signs."""
    robot = _robot("kuka_kr6_r900")
    q = _q(robot, f)
    dat = KrlBackend().emit(_plan(robot, q)).files["demo.dat"]
    body = re.search(r"DECL E6POS t=\{(.*)\}", dat).group(1)
    v = {k: float(x) for k, x in re.findall(r"([A-Z]\d?) (-?[\d.]+)", body)}
    target = _h(Rotation.from_euler("ZYX", [v["A"], v["B"], v["C"]], degrees=True).as_matrix(), [v["X"], v["Y"], v["Z"]])
    _close(_flange(target), robot.fk(q))
    s, t = int(v["S"]), int(v["T"])
    assert ir.Config(BACK if s & 1 else FRONT, UP if s & 2 else DOWN, FLIP if s & 4 else NOFLIP) == robot.branch(q)
    assert [bool(t >> i & 1) for i in range(6)] == [x < 0 for x in q]


@settings(max_examples=60, deadline=None)
@given(fractions)
def test_fanuc_any_branch(f: list[float]) -> None:
    """X Y Z W P R with 'F U T, t4, t5, t6' of any LR Mate 200iD configuration decodes to FK(q) and its branch."""
    robot = _robot("fanuc_lrmate200id")
    q = _q(robot, f)
    text = FanucBackend().emit(_plan(robot, q)).files["DEMO.ls"]
    config = re.search(r"CONFIG : '(.*?)'", text).group(1)
    vals = [float(x) for x in re.findall(r"[XYZWPR] =\s*(-?[\d.]+)", text)]
    target = _h(Rotation.from_euler("xyz", vals[3:], degrees=True).as_matrix(), vals[:3])
    # W, P, R print with 3 decimals: each within 0.0005 deg, the rotation within their sum
    _close(_flange(target), robot.fk(q), deg_tol=1.5e-3)
    flags, *turns = [c.strip() for c in config.split(",")]
    fl, up, top = flags.split()
    decoded = ir.Config(FRONT if top == "T" else BACK, UP if up == "U" else DOWN, FLIP if fl == "N" else NOFLIP)
    assert decoded == robot.branch(q)
    for turn, i in zip(turns, (3, 4, 5)):
        assert -180 + 360 * int(turn) - 1e-6 <= math.degrees(q[i]) <= 180 + 360 * int(turn) + 1e-6


@pytest.mark.parametrize("name", ["abb_irb120", "kuka_kr6_r900", "fanuc_lrmate200id"])
def test_samples_cover_every_branch(name: str) -> None:
    """The joint box sampled above holds all 8 branches (so the properties test each of them)."""
    robot = _robot(name)
    rng = np.random.default_rng(7)
    seen = {robot.branch(_q(robot, list(rng.uniform(0.02, 0.98, 6)))) for _ in range(3000)}
    assert len(seen) == 8
