"""The robot library against datasheet facts and independent kinematic formulas."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rmot.lang import ir
from rmot.sim.robots import Robot, RobotError, list_robots, load_robot
from rmot.sim.robots.library import SPECS
from rmot.sim.robots.opw import opw_fk

ORIGINAL = (
    "abb_irb120", "abb_irb1600", "abb_irb4600", "kuka_kr6_r900", "kuka_kr16", "kuka_kr210",
    "fanuc_lrmate200id", "fanuc_m20ia", "yaskawa_gp8", "staubli_tx2_60", "ur3e", "ur5e", "ur10e", "puma560",
)
ADDED = (  # each with its independent reference in reference_arms.py
    "kuka_kr4_r600", "kuka_kr6_r700_2", "kuka_kr6_r900_2", "kuka_kr10_r900_2", "kuka_kr10_r1100_2",
    "kuka_kr16_r1610_2", "kuka_kr20_r1810_2", "kuka_kr30_r2100", "kuka_kr50_r2500", "kuka_kr210_r3100_2",
    "kuka_kr8_r1440_2_arc_hw", "kuka_kr150_r3100_2", "kuka_kr240_r2900_2", "kuka_kr300_r2700_2",
    "kuka_kr500_r2800_2", "ur16e", "ur3", "ur5", "ur10",
)
ROSI = (  # one arm per brand from ROS-I's support packages (sim/robots/library_rosi.py)
    "abb_irb2400", "fanuc_m16ib20", "yaskawa_mh12", "staubli_tx60l",
)
ROSI_ABB_FANUC = (  # the further ABB and FANUC arms of ROS-I's packages (library_abb.py, library_fanuc.py)
    "abb_irb120t", "abb_irb1200_5_90", "abb_irb1200_7_70", "abb_irb1600_6_12", "abb_irb2600_12_165",
    "abb_irb4600_20_250", "abb_irb4600_40_255", "abb_irb6600_225_255", "abb_irb6640_185_280",
    "abb_irb6650s_125_350", "abb_irb6650s_90_390", "abb_irb6700_200_260", "abb_irb6700_235_265",
    "abb_irb7600_150_350",
    "fanuc_cr7ia", "fanuc_cr35ia", "fanuc_lrmate200ib", "fanuc_lrmate200ic", "fanuc_lrmate200id7l", "fanuc_m6ib",
    "fanuc_m10ia", "fanuc_m10ia7l", "fanuc_m20ia10l", "fanuc_m20ib25", "fanuc_m710ic45m", "fanuc_m710ic50",
    "fanuc_m900ia260l", "fanuc_r1000ia80f", "fanuc_r2000ib210f", "fanuc_r2000ic165f", "fanuc_r2000ic210l",
    "fanuc_lrmate200i", "fanuc_lrmate200ib3l", "fanuc_lrmate200ic5l", "fanuc_lrmate200id4s", "fanuc_lrmate200id4sc",
    "fanuc_lrmate200id7lc", "fanuc_m6ib6s", "fanuc_cr7ial", "fanuc_r2000ic125l", "fanuc_r2000ic210f", "fanuc_r2000ic270f",
)
MOTOMAN_STAUBLI = (  # sim/robots/library_motoman.py, library_staubli.py
    "yaskawa_gp4", "yaskawa_gp7", "yaskawa_gp12", "yaskawa_gp25", "yaskawa_gp35l", "yaskawa_gp50", "yaskawa_gp70l",
    "yaskawa_gp88", "yaskawa_gp110", "yaskawa_gp180", "yaskawa_gp180_120", "yaskawa_mh50", "yaskawa_mh110",
    "yaskawa_ms210", "yaskawa_ar2010", "yaskawa_hc20", "yaskawa_mh5",
    "staubli_tx60", "staubli_tx2_60l", "staubli_tx90", "staubli_tx90l", "staubli_tx90xl", "staubli_tx2_90",
    "staubli_tx2_90l", "staubli_tx2_90xl", "staubli_rx160", "staubli_rx160l",
)
# Arms whose source gives no rated payload (their `sources` say "unknown"): the Stäubli
# packages give none, and the names GP180-120 and AR2010 do not say it.
PAYLOAD_UNKNOWN = frozenset(n for n in MOTOMAN_STAUBLI if n.startswith("staubli_")) | {"yaskawa_gp180_120", "yaskawa_ar2010"}
NAMES = ORIGINAL + ADDED + ROSI + ROSI_ABB_FANUC + MOTOMAN_STAUBLI


def random_q(robot: Robot, n: int, seed: int = 0) -> np.ndarray:
    return np.random.default_rng(seed).uniform(robot.joint_limits[:, 0], robot.joint_limits[:, 1], (n, robot.dof))


def rot_y(deg: float) -> np.ndarray:
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def test_library_names_are_exactly_the_contract():
    """list_robots() is the contract names (33, and the ROS-I batch), sorted."""
    assert list_robots() == tuple(sorted(NAMES))


@pytest.mark.parametrize("name", NAMES)
def test_every_robot_loads_with_consistent_attributes(name):
    """Each entry builds: 6 revolute joints, ordered limits, positive speeds and accelerations,
    a cited source, inertias, positive torque limits and a rated payload."""
    r = load_robot(name)
    assert r.name == name and r.dof == 6 and r.joint_types == ("R",) * 6
    assert np.all(r.joint_limits[:, 0] < r.joint_limits[:, 1])
    assert np.all(r.velocity_limits > 0) and np.all(r.accel_limits > 0)
    assert r.has_inertia and np.all(np.asarray(r.model.effortLimit) > 0)
    assert all(i.mass > 0 for i in r.model.inertias[1:])
    if name in PAYLOAD_UNKNOWN:
        assert r.rated_payload_kg is None and dict(r.sources)["payload"].startswith("unknown")
    else:
        assert r.rated_payload_kg is not None and r.rated_payload_kg > 0
    assert r.has_closed_form and len(r.source) > 5 and r.vendor and r.model_name
    assert load_robot(name) is r  # cached


def test_unknown_robot_suggests_the_nearest_name():
    """An unknown name raises RobotError with a did-you-mean."""
    with pytest.raises(RobotError, match="did you mean 'abb_irb120'"):
        load_robot("abb_irb12")


# The flange at a documented joint position (mm, base frame). Documented values: IRB 120
# (ABB product spec), LR Mate 200iD (pendant at all-zero joints), Puma (Corke's fkine(qz)).
# The others are sums of the dimension-drawing lengths at the vendor's zero/home pose, which
# still checks the joint zero, direction and DH build against the drawing.
FLANGE_FACTS = [
    ("abb_irb120", (0, 0, 0, 0, 0, 0), (374.0, 0.0, 630.0)),  # ABB: tool0 at calibration position
    ("abb_irb1600", (0, 0, 0, 0, 0, 0), (815.0, 0.0, 1186.5)),  # 150 + 600 + 65; 486.5 + 700
    ("abb_irb4600", (0, 0, 0, 0, 0, 0), (1270.0, 0.0, 1570.0)),  # 175 + 960 + 135; 495 + 900 + 175
    ("kuka_kr6_r900", (0, -90, 90, 0, 0, 0), (525.0, 0.0, 890.0)),  # HOME: 25 + 420 + 80; 400 + 455 + 35
    ("fanuc_lrmate200id", (0, 0, 0, 0, 0, 0), (465.0, 0.0, 365.0)),  # Fanuc world frame at J2 height
    ("puma560", (0, 0, 0, 0, 0, 0), (452.1, -150.05, 431.8)),  # Corke: fkine(qz)
    # Stäubli world frame at the J1/J2 intersection, 375 mm above the mounting face (TX2-60
    # data sheet); candle: 290 + 310 + 70 above it, 20 mm to the side.
    ("staubli_tx2_60", (0, 0, 0, 0, 0, 0), (0.0, 20.0, 670.0)),
    # KR 16-2 at HOME: A4 is 35 mm BELOW A3 (KR 16-2 spec dimension drawing): 260 + 670 + 158; 675 + 680 - 35.
    ("kuka_kr16", (0, -90, 90, 0, 0, 0), (1088.0, 0.0, 1320.0)),
    # KR 210 R2700-2 at HOME (its data sheet drawing): 330 + 1220 + 215; 645 + 1150 + 115.
    ("kuka_kr210", (0, -90, 90, 0, 0, 0), (1765.0, 0.0, 1910.0)),
    # Yaskawa GP8 robot frame at the L-axis height, 330 mm above the mounting face (Yaskawa,
    # ros-industrial/motoman issue 167): at zero 40 + 340 + 80 forward, 345 + 40 up.
    ("yaskawa_gp8", (0, 0, 0, 0, 0, 0), (460.0, 0.0, 385.0)),
]


@pytest.mark.parametrize(("name", "q_deg", "xyz_mm"), FLANGE_FACTS)
def test_flange_at_documented_pose(name, q_deg, xyz_mm):
    """FK at the documented pose puts the flange where the datasheet says (0.01 mm)."""
    t = load_robot(name).fk(np.radians(q_deg))
    np.testing.assert_allclose(t[:3, 3] * 1000, xyz_mm, atol=0.01)


@pytest.mark.parametrize("name", [n for n in ORIGINAL if not n.startswith("ur") and n != "puma560"])
def test_wrist_centre_reach_matches_datasheet(name):
    """The largest wrist-centre distance from J1 (a1 + c2 + |J3→wrist|) is the datasheet reach
    (Stäubli states it at the flange) within 0.1 % (KR 210 R2700-2: the product name's
    rounded 2700 mm against a 2705.4 mm wrist centre, 0.2 %)."""
    p = SPECS[name].opw[0]
    reach = p.a1 + p.c2 + math.hypot(p.a2, p.c3) + (p.c4 if name.startswith("staubli") else 0.0)
    assert reach == pytest.approx(SPECS[name].reach, rel=2.5e-3 if name == "kuka_kr210" else 1e-3)


@pytest.mark.parametrize("name", ["ur3e", "ur5e", "ur10e", "ur16e", "ur3", "ur5", "ur10"])
def test_ur_reach_is_near_the_stretched_arm(name):
    """UR's datasheet reach is within 7 % of the shoulder-to-flange distance of the stretched arm."""
    r = load_robot(name)
    p = SPECS[name].ur
    flange = r.fk(np.zeros(6))[:3, 3]
    stretched = np.linalg.norm(flange - [0, 0, p.d1])
    assert stretched == pytest.approx(r.reach, rel=0.07)


def test_vendor_flange_orientations_at_zero():
    """ABB tool0 / KUKA $FLANGE at home: z forward, x down (B = 90°); Fanuc faceplate at zero:
    W P R = (180, -90, 0), i.e. z forward, x up."""
    down_x = rot_y(90)
    np.testing.assert_allclose(load_robot("abb_irb120").fk(np.zeros(6))[:3, :3], down_x, atol=1e-12)
    np.testing.assert_allclose(load_robot("kuka_kr6_r900").fk(np.radians([0, -90, 90, 0, 0, 0]))[:3, :3], down_x, atol=1e-12)
    wpr = ir.Pose.from_xyz_rpy(0, 0, 0, math.pi, -math.pi / 2, 0).matrix()[:3, :3]
    np.testing.assert_allclose(load_robot("fanuc_lrmate200id").fk(np.zeros(6))[:3, :3], wpr, atol=1e-12)


def test_kuka_a1_positive_turns_clockwise_from_above():
    """KUKA A1 > 0 turns the arm clockwise seen from above (flange to negative y)."""
    t = load_robot("kuka_kr6_r900").fk(np.radians([30, -90, 90, 0, 0, 0]))
    assert t[1, 3] < -0.2


def test_fanuc_j3_is_the_forearm_angle_to_the_horizontal():
    """Fanuc J2/J3 interaction: moving J2 with J3 fixed keeps the forearm (and flange) orientation."""
    r = load_robot("fanuc_lrmate200id")
    a = r.fk(np.radians([0, 0, 20, 0, -30, 0]))
    b = r.fk(np.radians([0, 40, 20, 0, -30, 0]))
    np.testing.assert_allclose(a[:3, :3], b[:3, :3], atol=1e-12)
    assert b[0, 3] > a[0, 3] + 0.1  # J2 > 0 tilts the upper arm forward


@pytest.mark.parametrize("name", [n for n in NAMES if SPECS[n].opw is not None])
def test_pinocchio_model_equals_the_opw_formula(name):
    """The DH table built into pinocchio equals the closed OPW FK formula (independent algebra)."""
    r = load_robot(name)
    params, jmap = SPECS[name].opw
    q = random_q(r, 200, seed=1)
    flange_turn = np.array(SPECS[name].flange)
    np.testing.assert_allclose(r.fk_batch(q), opw_fk(params, jmap.to_theta(q)) @ flange_turn, atol=1e-12)


def dh_standard(q: np.ndarray, table: list[tuple[float, float, float]]) -> np.ndarray:
    """A plain standard-DH product, written out for the test."""
    t = np.eye(4)
    for theta, (d, a, alpha) in zip(q, table):
        ct, st, ca, sa = math.cos(theta), math.sin(theta), math.cos(alpha), math.sin(alpha)
        t = t @ np.array([[ct, -st * ca, st * sa, a * ct], [st, ct * ca, -ct * sa, a * st], [0, sa, ca, d], [0, 0, 0, 1]])
    return t


def test_puma560_equals_corkes_dh_table():
    """Puma 560 FK equals Corke's standard DH table on random joint values."""
    h = math.pi / 2
    table = [(0, 0, h), (0, 0.4318, 0), (0.15005, 0.0203, -h), (0.4318, 0, h), (0, 0, -h), (0, 0, 0)]
    r = load_robot("puma560")
    for q in random_q(r, 50, seed=2):
        np.testing.assert_allclose(r.fk(q), dh_standard(q, table), atol=1e-12)


QUANTITIES = ("geometry", "limits", "speed", "accel", "reach", "mass", "inertia", "effort", "payload")
TOPICS = ("base frame", "flange frame", "joint zero", "signs", "coupling")


@pytest.mark.parametrize("name", NAMES)
def test_every_number_names_its_source_and_every_arm_its_conventions(name):
    """Each quantity of each arm has a source text (a document, a reference file, or
    "estimate: how"); each arm states base frame, flange frame, joint zero, signs, coupling."""
    r = load_robot(name)
    sources = dict(r.sources)
    assert tuple(sources) == QUANTITIES
    assert all(len(text) > 10 for text in sources.values())
    assert tuple(dict(r.conventions)) == TOPICS


def test_kuka_accelerations_are_marked_estimates_not_the_ros_planning_limits():
    """KR 6 R900 sixx: KUKA's ROS description gives A2 394.7 deg/s^2 (kroshu/kuka_robot_descriptions
    kuka_agilus_support/config/kr6_r900_sixx_joint_limits.yaml, 6.889457 rad/s^2, transcribed
    here), a planning limit, not the controller's: the library uses the estimate every other
    vendor's arm has (4 x the axis speed per second, the speeds typed from KUKA spec PF0030) and
    says so, with KUKA's numbers kept in the source text."""
    speeds = np.radians((360, 300, 360, 381, 388, 615))
    robot = load_robot("kuka_kr6_r900")
    np.testing.assert_allclose(robot.accel_limits, 4 * speeds, rtol=1e-9)
    assert not np.isclose(robot.accel_limits[1], 6.889457, rtol=1e-3)
    for name in ("kuka_kr6_r900", "kuka_kr210", "kuka_kr10_r1100_2"):
        source = dict(load_robot(name).sources)["accel"]
        assert source.startswith("estimate") and "kroshu" in source, name
