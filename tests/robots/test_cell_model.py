"""Robots defined in a cell (`model` blocks) and URDF chains chosen with base=/tip=.

The witness for the kinematics is a plain numpy Denavit-Hartenberg product written here, from
the textbook definitions, not rmot's code:
  standard (Spong, "Robot Modeling and Control", eq. 3.10; the reference article's eq. 2-3):
      A_i = Rz(θ_i) Tz(d_i) Tx(a_i) Rx(α_i)
  modified (Craig, "Introduction to Robotics", eq. 3.6):
      A_i = Rx(α_{i-1}) Tx(a_{i-1}) Rz(θ_i) Tz(d_i)
with θ_i = q_i + theta_i (revolute) or d_i = d + q_i (prismatic).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from rmot.lang import ir
from rmot.compiler.frontend import load_text
from rmot.sim.robots import load_robot

DATA = Path(__file__).resolve().parents[1] / "data"
PANDA = Path(np.__file__).parents[1] / "cmeel.prefix/share/example-robot-data/robots/panda_description/urdf/panda.urdf"


# --------------------------------------------------------------------------- the witness

def _rx(t: float) -> np.ndarray:
    c, s = math.cos(t), math.sin(t)
    return np.array([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1.0]])


def _rz(t: float) -> np.ndarray:
    c, s = math.cos(t), math.sin(t)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])


def _tr(x: float, y: float, z: float) -> np.ndarray:
    m = np.eye(4)
    m[:3, 3] = (x, y, z)
    return m


def witness_fk(rows: list[tuple], q: np.ndarray, modified: bool, flange: np.ndarray | None = None) -> np.ndarray:
    """rows: (kind, a m, alpha rad, d m, theta rad); the chain's flange pose."""
    t = np.eye(4)
    for (kind, a, alpha, d, theta), qi in zip(rows, q):
        th, dd = (theta + qi, d) if kind == "revolute" else (theta, d + qi)
        if modified:
            t = t @ _rx(alpha) @ _tr(a, 0, 0) @ _rz(th) @ _tr(0, 0, dd)
        else:
            t = t @ _rz(th) @ _tr(0, 0, dd) @ _tr(a, 0, 0) @ _rx(alpha)
    return t if flange is None else t @ flange


def _cell(rows: list[tuple], modified: bool, name: str = "arm", extra: str = "", limit: float = 170.0) -> str:
    func = "mdh" if modified else "dh"
    lines = []
    for kind, a, alpha, d, theta in rows:
        if kind == "revolute":
            rng, spd = f"range(-{limit}deg, {limit}deg) speed 200 deg/s accel 800 deg/s^2", ""
        else:
            rng, spd = "range(0mm, 400mm) speed 500 mm/s accel 2000 mm/s^2", ""
        lines.append(f"    joint {kind} {func}(a={a * 1000!r}mm, alpha={math.degrees(alpha)!r}deg, d={d * 1000!r}mm, "
                     f"theta={math.degrees(theta)!r}deg) {rng}{spd}")
    body = "\n".join(lines)
    return f"cell c {{\n  model {name} {{\n{body}\n{extra}  }}\n  robot r1 = {name}\n}}\n"


def _robot(text: str):  # type: ignore[no-untyped-def]
    result = load_text(text, str(DATA / "model_cell.rmot"))
    assert not result.has_errors, [str(d) for d in result.diagnostics]
    inst = result.cell.robot("r1")  # type: ignore[union-attr]
    assert inst.source.kind is ir.RobotSourceKind.MODEL
    return load_robot(inst.source.load_key)


D = math.radians
# Puma 560, standard DH (Corke, Robotics Toolbox mdl_puma560: a2 431.8, a3 20.3, d3 150.05, d4 431.8 mm)
PUMA = [("revolute", 0.0, D(90), 0.0, 0.0), ("revolute", 0.4318, 0.0, 0.0, 0.0),
        ("revolute", 0.0203, D(-90), 0.15005, 0.0), ("revolute", 0.0, D(90), 0.4318, 0.0),
        ("revolute", 0.0, D(-90), 0.0, 0.0), ("revolute", 0.0, 0.0, 0.0, 0.0)]
# Puma 560, modified DH (Craig, Table 3.4: a2 431.8, a3 20.32, d3 149.09 (here 150.05), d4 433.07 mm)
PUMA_MDH = [("revolute", 0.0, 0.0, 0.0, 0.0), ("revolute", 0.0, D(-90), 0.0, 0.0),
            ("revolute", 0.4318, 0.0, 0.15005, 0.0), ("revolute", 0.0203, D(-90), 0.4331, 0.0),
            ("revolute", 0.0, D(90), 0.0, 0.0), ("revolute", 0.0, D(-90), 0.0, 0.0)]
# The example cell's arm (examples/cells/model_arm.rmot), with its theta offsets
EXAMPLE = [("revolute", 0.075, D(-90), 0.4, 0.0), ("revolute", 0.35, 0.0, 0.0, D(-90)),
           ("revolute", 0.04, D(90), 0.0, D(90)), ("revolute", 0.0, D(-90), 0.38, 0.0),
           ("revolute", 0.0, D(90), 0.0, 0.0), ("revolute", 0.0, 0.0, 0.08, 0.0)]
# Not OPW: a 6R chain with skewed axes (numeric IK)
SKEW = [("revolute", 0.1, D(70), 0.3, 0.2), ("revolute", 0.4, D(20), 0.05, -0.3),
        ("revolute", 0.05, D(-80), 0.1, 0.1), ("revolute", 0.0, D(90), 0.35, 0.0),
        ("revolute", 0.02, D(-90), 0.0, 0.0), ("revolute", 0.0, 0.0, 0.1, 0.0)]
# A SCARA-like chain with a prismatic joint
SCARA = [("revolute", 0.35, 0.0, 0.4, 0.0), ("revolute", 0.3, D(180), 0.0, 0.0),
         ("prismatic", 0.0, 0.0, 0.0, 0.0), ("revolute", 0.0, 0.0, 0.05, 0.0)]


@pytest.mark.parametrize("rows, modified, closed", [(PUMA, False, True), (PUMA_MDH, True, True), (EXAMPLE, False, True),
                                                     (SKEW, False, False), (SCARA, False, False)],
                         ids=["puma-dh", "puma-mdh", "example", "skew", "scara"])
def test_fk_equals_the_independent_dh_product(rows: list[tuple], modified: bool, closed: bool) -> None:
    robot = _robot(_cell(rows, modified))
    assert robot.has_closed_form is closed
    rng = np.random.default_rng(7)
    for _ in range(20):
        q = rng.uniform(robot.joint_limits[:, 0], robot.joint_limits[:, 1])
        np.testing.assert_allclose(robot.fk(q), witness_fk(rows, q, modified), atol=1e-12)


@pytest.mark.parametrize("rows, modified", [(PUMA, False), (PUMA_MDH, True), (EXAMPLE, False), (SKEW, False)],
                         ids=["puma-dh", "puma-mdh", "example", "skew"])
def test_ik_reproduces_the_witness_pose(rows: list[tuple], modified: bool) -> None:
    """FK_witness(IK(T)) = T for T = FK_witness(q); closed-form arms also find q itself."""
    robot = _robot(_cell(rows, modified))
    rng = np.random.default_rng(3)
    for _ in range(8):
        q = rng.uniform(robot.joint_limits[:, 0], robot.joint_limits[:, 1]) * 0.8
        target = witness_fk(rows, q, modified)
        result = robot.ik(target, seed=q)
        assert result.solutions, result.message
        for sol in result.solutions:
            np.testing.assert_allclose(witness_fk(rows, sol, modified), target, atol=1e-8)
        if robot.has_closed_form:
            assert min(float(np.abs(np.angle(np.exp(1j * (s - q)))).max()) for s in result.solutions) < 1e-7
            assert len({b for b in result.branches}) == len(result.branches) or len(result.solutions) > 8


def test_closed_form_model_names_all_eight_branches() -> None:
    robot = _robot(_cell(EXAMPLE, False))
    rows = robot.batch_branches
    assert rows is not None and len(set(rows)) == 8
    q = np.radians([10, -20, 30, 40, 50, 60])
    sols = robot.ik_batch(robot.fk(q)[None])[0]
    for row, sol in zip(rows, sols):
        if not np.isnan(sol).any():
            assert robot.branch(sol) == row
            np.testing.assert_allclose(witness_fk(EXAMPLE, sol, False), robot.fk(q), atol=1e-9)


def test_flange_payload_and_prismatic_units() -> None:
    text = _cell(SCARA, False, extra="    flange pose(z=25mm)\n    payload 3 kg\n")
    robot = _robot(text)
    assert robot.rated_payload_kg == 3.0
    assert robot.joint_types == ("R", "R", "P", "R")
    np.testing.assert_allclose(robot.joint_limits[2], (0.0, 0.4))
    np.testing.assert_allclose(robot.velocity_limits, (D(200), D(200), 0.5, D(200)))
    np.testing.assert_allclose(robot.accel_limits, (D(800), D(800), 2.0, D(800)))
    q = np.array([0.3, -0.2, 0.15, 1.0])
    np.testing.assert_allclose(robot.fk(q), witness_fk(SCARA, q, False, _tr(0, 0, 0.025)), atol=1e-12)
    assert _robot(_cell(SCARA, False)).rated_payload_kg is None


def test_model_named_like_a_library_robot_shadows_it_with_a_warning() -> None:
    result = load_text(_cell(PUMA, False, name="ur5e"), str(DATA / "model_cell.rmot"))
    assert [d.code.id for d in result.diagnostics] == ["W135"]
    assert result.cell.robot("r1").source.kind is ir.RobotSourceKind.MODEL  # type: ignore[union-attr]


def test_generated_solids_follow_the_links_and_do_not_self_collide_at_zero() -> None:
    robot = _robot(_cell(EXAMPLE, False))
    assert {s.joint_id for s in robot.solids} == set(range(7))
    poses = robot.solid_poses(np.zeros(6))
    # at zero the arm stands upright (the OPW layout): the forearm solid (joint 4) is centred
    # on the d4 = 380 mm segment, x = a1 + a3 = 115 mm, z from 750 to 1130 mm
    forearm = [p for s, p in zip(robot.solids, poses) if s.joint_id == 4][0]
    np.testing.assert_allclose(forearm[:3, 3], (0.115, 0.0, 0.75 + 0.19), atol=1e-9)
    np.testing.assert_allclose(abs(forearm[2, 2]), 1.0, atol=1e-9)
    from rmot.sim.scene import build_scene  # noqa: F401  (the solids are ordinary LinkSolids)


# --------------------------------------------------------------------------- URDF chains

def _mdh(a: float, alpha: float, d: float, theta: float) -> np.ndarray:
    return _rx(alpha) @ _tr(a, 0, 0) @ _rz(theta) @ _tr(0, 0, d)


def test_panda_with_fingers_loads_as_a_seven_axis_arm_between_base_and_tip() -> None:
    """Franka's published modified DH table (frankaemika.github.io, "Robot and interface
    specifications": d1 0.333, d3 0.316, a4 0.0825, a5 -0.0825, d5 0.384, a7 0.088, flange
    d 0.107 m) against the URDF chain panda_link0 .. panda_link8 (the flange)."""
    text = f'cell c {{\n  robot r1 = urdf("{PANDA}", base="panda_link0", tip="panda_link8")\n}}\n'
    result = load_text(text, str(DATA / "model_cell.rmot"), project_root="/")
    assert not result.has_errors, [str(d) for d in result.diagnostics]
    robot = load_robot(result.cell.robot("r1").source.load_key)  # type: ignore[union-attr]
    assert robot.dof == 7
    table = [(0, 0, 0.333), (0, -np.pi / 2, 0), (0, np.pi / 2, 0.316), (0.0825, np.pi / 2, 0),
             (-0.0825, -np.pi / 2, 0.384), (0, np.pi / 2, 0), (0.088, np.pi / 2, 0)]
    rng = np.random.default_rng(1)
    for _ in range(10):
        q = rng.uniform(robot.joint_limits[:, 0], robot.joint_limits[:, 1])
        t = np.eye(4)
        for (a, alpha, d), qi in zip(table, q):
            t = t @ _mdh(a, alpha, d, qi)
        t = t @ _tr(0, 0, 0.107)
        np.testing.assert_allclose(robot.fk(q), t, atol=1e-9)


def test_urdf_chain_ignores_fingers_and_rebases_on_the_base_link() -> None:
    plain = load_robot(str(DATA.parents[1] / "examples/urdf_cell/arm6.urdf"))
    text = 'cell c {\n  robot r1 = urdf("bad/arm6_gripper.urdf", base="base_link", tip="tool0")\n}\n'
    result = load_text(text, str(DATA / "model_cell.rmot"))
    assert not result.has_errors, [str(d) for d in result.diagnostics]
    robot = load_robot(result.cell.robot("r1").source.load_key)  # type: ignore[union-attr]
    assert robot.dof == 6
    q = np.radians([20, -30, 40, 50, -60, 70])
    np.testing.assert_allclose(robot.fk(q), plain.fk(q), atol=1e-12)
    assert robot.branch(q) == plain.branch(q) != ir.Config()


def test_urdf_unknown_link_suggests_the_nearest() -> None:
    text = 'cell c {\n  robot r1 = urdf("bad/arm6_gripper.urdf", base="base_lnk", tip="tool0")\n}\n'
    result = load_text(text, str(DATA / "model_cell.rmot"))
    [d] = result.diagnostics
    assert d.code.id == "E506" and "did you mean 'base_link'" in d.message
    assert (d.span.start.line, d.span.start.col) == (2, text.splitlines()[1].index('"base_lnk"') + 1)


def test_given_solids_replace_the_generated_ones_of_their_link() -> None:
    """`solid(GEOMETRY, at=POSE)` sits at POSE in DH frame i: its pose is the witness's frame i times POSE."""
    solid = " solid(box(100mm, 60mm, 40mm), at=pose(x=-150mm, rz=90deg)) solid(sphere(r=30mm))"
    text = _cell(PUMA, False).replace("alpha=0.0deg, d=0.0mm, theta=0.0deg)", "alpha=0.0deg, d=0.0mm, theta=0.0deg)" + solid, 1)
    assert solid in text
    robot = _robot(text)
    mine = [k for k, s in enumerate(robot.solids) if s.joint_id == 2]
    assert [type(robot.solids[k].geometry).__name__ for k in mine] == ["Box", "Sphere"]
    assert robot.solids[mine[0]].geometry == ir.Box((0.1, 0.06, 0.04))
    q = np.array([0.4, -0.7, 0.3, 0.1, 0.2, 0.3])
    frame2 = witness_fk(PUMA[:2], q[:2], False)
    at = _tr(-0.15, 0, 0) @ _rz(D(90))
    poses = robot.solid_poses(q)
    np.testing.assert_allclose(poses[mine[0]], frame2 @ at, atol=1e-12)
    np.testing.assert_allclose(poses[mine[1]], frame2, atol=1e-12)


def test_random_opw_form_tables_get_a_closed_form_that_the_witness_confirms() -> None:
    """DH tables of OPW form with random lengths, axis directions (alpha signs) and theta
    offsets: each gets the closed form, and every solution reproduces the witness's pose."""
    rng = np.random.default_rng(11)
    for trial in range(5):
        a1, a2, b = rng.uniform(0, 0.2), rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1)
        c1, c2, c3, c4 = rng.uniform(0.2, 0.5), rng.uniform(0.3, 0.6), rng.uniform(0.3, 0.6), rng.uniform(0, 0.15)
        s = rng.choice([-1.0, 1.0], 6)
        th = rng.uniform(-math.pi, math.pi, 6)
        geometry = [(a1, -s[0] * D(90), c1), (c2, 0.0, b * s[0]), (a2, s[2] * D(90), 0.0),
                    (0.0, -s[3] * D(90), c3 * s[2]), (0.0, s[4] * D(90), 0.0), (0.0, 0.0, c4 * s[4])]
        rows = [("revolute", float(a), float(al), float(d), float(t)) for (a, al, d), t in zip(geometry, th)]
        robot = _robot(_cell(rows, False, limit=179.0))
        assert robot.has_closed_form, trial
        for q in rng.uniform(-3.0, 3.0, (3, 6)):
            target = witness_fk(rows, q, False)
            result = robot.ik(target, seed=q)
            assert len(result.solutions) >= 1
            for sol in result.solutions:
                np.testing.assert_allclose(witness_fk(rows, sol, False), target, atol=1e-8)


def test_cell_constants_are_usable_in_a_model() -> None:
    text = _cell(PUMA, False, extra="    payload rated\n").replace("cell c {\n", "cell c {\n  const upper = 431.8 mm\n  const rated = 2.5 kg\n")
    text = text.replace("a=431.8mm", "a=upper")
    assert "a=upper" in text
    robot = _robot(text)
    assert robot.rated_payload_kg == 2.5
    q = np.array([0.1, 0.2, 0.3, 0.4, 0.5, 0.6])
    np.testing.assert_allclose(robot.fk(q), witness_fk(PUMA, q, False), atol=1e-12)


def test_spherical_wrist_without_opw_base_gets_numeric_ik_and_branch_names() -> None:
    """J1 tilted 60 deg against J2 (not ortho-parallel) but a spherical wrist: numeric IK, and
    branch names from the geometry, so vendors needing configuration data accept it."""
    rows = [("revolute", 0.05, D(60), 0.4, 0.0)] + PUMA[1:]
    robot = _robot(_cell(rows, False))
    assert not robot.has_closed_form
    q = np.array([0.2, -0.4, 0.3, 0.5, 0.6, 0.7])
    assert all(f is not None for f in (robot.branch(q).shoulder, robot.branch(q).elbow, robot.branch(q).wrist))
    result = robot.ik(witness_fk(rows, q, False), seed=q)
    assert result.solutions
    np.testing.assert_allclose(witness_fk(rows, result.solutions[0], False), witness_fk(rows, q, False), atol=1e-8)
    assert robot.branch(result.solutions[0]) == result.branches[0]


# Yaskawa MH5 (Yaskawa-Global/motoman_ros2_support_packages mh5_macro.xacro: 88/310/40/305/80 mm),
# standard DH with frame 0 at the L-axis height: the robot frame `controller yaskawa` declares.
MH5_AT_SHOULDER = [("revolute", 0.088, D(-90), 0.0, 0.0), ("revolute", 0.31, 0.0, 0.0, D(-90)),
                   ("revolute", 0.04, D(-90), 0.0, 0.0), ("revolute", 0.0, D(90), 0.305, 0.0),
                   ("revolute", 0.0, D(-90), 0.0, 0.0), ("revolute", 0.0, 0.0, 0.08, 0.0)]


def test_generated_base_hangs_below_a_shoulder_height_frame_0_clear_of_the_upper_arm() -> None:
    """With DH frame 0 at the shoulder (the MH5's robot frame), the upper arm swings about J2
    through the whole L range without touching the base cylinder (a standing cylinder filled
    the shoulder: E301 at L = -60 deg); where frame 0 is on the floor the base still stands."""
    from test_solids import cylinder_distance, samples, segment

    robot = _robot(_cell(MH5_AT_SHOULDER, False))
    names = [s.name for s in robot.solids]
    base, upper = names.index("base"), names.index("link_2")
    for lean in np.linspace(D(-90), D(150), 49):
        q = np.array([0.0, lean, 0.0, 0.0, 0.0, 0.0])
        poses = robot.solid_poses(q)
        b0, b1, rb = segment(poses[base], robot.solids[base].geometry)
        u0, u1, ru = segment(poses[upper], robot.solids[upper].geometry)
        assert max(b0[2], b1[2]) < 0.0  # below the shoulder
        assert cylinder_distance(b0, b1, rb, samples(u0, u1)) - ru > 0.0, np.degrees(lean)
    standing = _robot(_cell(EXAMPLE, False))
    s0, s1, _ = segment(standing.solid_poses(np.zeros(6))[0], standing.solids[0].geometry)
    assert min(s0[2], s1[2]) == pytest.approx(0.0, abs=1e-12) and max(s0[2], s1[2]) > 0.0
