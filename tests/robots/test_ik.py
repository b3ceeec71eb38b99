"""IK: round trips on every library robot, branch counts, statuses, equivalent angles."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rmot.lang import ir
from rmot.sim.robots import IkStatus, list_robots, load_robot
from rmot.sim.robots.library import SPECS
from rmot.sim.robots.numeric import dls
from rmot.sim.robots.opw import opw_ik
from rmot.sim.robots.urik import ur_ik

N_POSES = 10_000


def random_q(robot, n: int, seed: int = 0) -> np.ndarray:
    return np.random.default_rng(seed).uniform(robot.joint_limits[:, 0], robot.joint_limits[:, 1], (n, robot.dof))


def errors(robot, qs: np.ndarray, targets: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Position and rotation (Frobenius/√2 ≈ angle) errors of FK(qs) against targets."""
    fk = robot.fk_batch(qs)
    dp = np.linalg.norm(fk[:, :3, 3] - targets[:, :3, 3], axis=1)
    dr = np.linalg.norm(fk[:, :3, :3] - targets[:, :3, :3], axis=(1, 2)) / math.sqrt(2)
    return dp, dr


@pytest.mark.parametrize("name", list_robots())
def test_fk_of_ik_batch_is_the_pose_on_10000_random_poses(name):
    """Every branch ik_batch returns reproduces the pose to 1e-9 and stays in the limits, and
    the branch of the joints the pose came from is among them (seeded: it comes back exactly)."""
    r = load_robot(name)
    q = random_q(r, N_POSES, seed=7)
    poses = r.fk_batch(q)
    sols = r.ik_batch(poses, seed=q)
    found = np.all(np.isfinite(sols), axis=2)
    flat = sols[found]
    dp, dr = errors(r, flat, np.repeat(poses, 8, axis=0)[found.reshape(-1)])
    assert dp.max() <= 1e-9 and dr.max() <= 1e-9
    assert np.all((flat >= r.joint_limits[:, 0]) & (flat <= r.joint_limits[:, 1]))
    assert np.all(np.any(np.all(np.abs(sols - q[:, None]) < 1e-7, axis=2), axis=1))


@pytest.mark.parametrize("name", list_robots())
def test_single_ik_agrees_with_batch_and_starts_at_the_seed(name):
    """ik(T, seed=q) lists q first; its branches are exactly the finite rows of ik_batch."""
    r = load_robot(name)
    qs = random_q(r, 30, seed=11)
    poses = r.fk_batch(qs)
    batch = r.ik_batch(poses, seed=qs)
    for q, pose, rows in zip(qs, poses, batch):
        res = r.ik(pose, seed=q)
        assert res.status is IkStatus.OK
        np.testing.assert_allclose(res.solutions[0], q, atol=1e-7)
        assert res.branches[0] == r.branch(q)
        batch_branches = {r.branch(row) for row in rows if np.all(np.isfinite(row))}
        assert set(res.branches) == batch_branches
        assert len(res.solutions) == len(res.branches)


def distinct_numeric_solutions(robot, pose: np.ndarray, seeds: int) -> list[np.ndarray]:
    """Distinct joint solutions (mod 2π, no limits) that pinocchio DLS finds from many seeds."""
    found: list[np.ndarray] = []
    for start in np.random.default_rng(5).uniform(-np.pi, np.pi, (seeds, robot.dof)):
        q, err = dls(robot, pose, start, max_iter=100)
        if err > 1e-10:
            continue
        q = np.remainder(q + np.pi, 2 * np.pi) - np.pi
        if all(np.max(np.abs(np.remainder(q - f + np.pi, 2 * np.pi) - np.pi)) > 1e-6 for f in found):
            found.append(q)
    return found


@pytest.mark.parametrize("name", ["abb_irb120", "staubli_tx2_60", "ur5e", "fanuc_lrmate200id"])
def test_closed_form_branch_count_equals_numeric_solution_count(name):
    """On generic poses the closed form has as many branches as DLS finds distinct solutions
    from 300 random seeds (limits ignored on both sides)."""
    r = load_robot(name)
    for q in random_q(r, 3, seed=21):
        pose = r.fk(q)
        closed = r.ik_closed_form(pose)[0]
        closed = closed[np.all(np.isfinite(closed), axis=1)]
        numeric = distinct_numeric_solutions(r, pose, 300)
        assert len(numeric) == len(closed)
        for n in numeric:  # and they are the same solutions
            assert min(np.max(np.abs(np.remainder(n - c + np.pi, 2 * np.pi) - np.pi)) for c in closed) < 1e-6


@pytest.mark.parametrize("name", ["kuka_kr16", "staubli_tx2_60", "fanuc_m20ia", "ur5e", "ur10e"])
def test_numpy_reference_and_compiled_kernels_agree(name):
    """The compiled closed forms equal the numpy reference implementations (mod 2π), and
    agree on which branches exist."""
    r = load_robot(name)
    spec = SPECS[name]
    q = random_q(r, 500, seed=3)
    q[::11, 4] = 0.0  # some exactly wrist-singular
    poses = r.fk_batch(q)
    poses[::7, 0, 3] += 5.0  # some unreachable
    if spec.opw is not None:
        params, jmap = spec.opw
        ref = jmap.from_theta(opw_ik(params, poses @ np.linalg.inv(np.array(spec.flange))))
    else:
        ref = ur_ik(spec.ur, poses)
    got = r.ik_closed_form(poses)
    exists = np.all(np.isfinite(got), axis=2)
    generic = np.abs(np.sin(q[:, 4])) > 1e-6  # a singular UR pose has a continuum of solutions
    assert np.array_equal(exists[generic], np.all(np.isfinite(ref), axis=2)[generic])
    exists &= np.all(np.isfinite(ref), axis=2)
    a, b = got[exists], ref[exists]
    regular = np.abs(np.sin(a[:, 4])) > 1e-6  # at J5 = 0 only J4 ± J6 is defined
    diff = np.remainder(a[regular] - b[regular] + np.pi, 2 * np.pi) - np.pi
    assert np.abs(diff).max() < 1e-9
    target = np.repeat(poses[:, None], 8, axis=1)[exists][~regular]
    np.testing.assert_allclose(r.fk_batch(a[~regular]), target, atol=1e-7)  # the compiled one is right


def test_numeric_robot_batch_returns_one_verified_row():
    """ik_batch on a robot without closed form: row 0 is a verified solution, rows 1-7 NaN."""
    import importlib.metadata

    files = importlib.metadata.files("example-robot-data") or []
    r = load_robot(str(next(f for f in files if f.name == "ur5_robot.urdf").locate()))
    q = np.random.default_rng(2).uniform(-2.5, 2.5, (5, 6))
    out = r.ik_batch(r.fk_batch(q), seed=q)
    assert np.all(np.isnan(out[:, 1:])) and np.all(np.isfinite(out[:, 0]))
    np.testing.assert_allclose(r.fk_batch(out[:, 0]), r.fk_batch(q), atol=1e-9)


def test_joint_beyond_180_gives_every_equivalent_nearest_seed_first():
    """IRB 120 J6 spans ±400°: q6 and q6 ± 360° inside the limits are all solutions."""
    r = load_robot("abb_irb120")
    q = np.radians([10, 20, -30, 40, 50, 20])
    res = r.ik(r.fk(q), seed=np.radians([10, 20, -30, 40, 50, 370]))
    same_branch = [s for s, b in zip(res.solutions, res.branches) if b == r.branch(q)]
    j6 = sorted(round(math.degrees(s[5]), 6) for s in same_branch)
    assert j6 == [-340.0, 20.0, 380.0]
    assert math.degrees(res.solutions[0][5]) == pytest.approx(380.0)


def test_far_pose_is_unreachable_with_its_distance():
    """A pose 1 m beyond the IRB 120 reach: UNREACHABLE, distance from the wrist annulus."""
    r = load_robot("abb_irb120")
    p = SPECS["abb_irb120"].opw[0]
    pose = np.eye(4)
    pose[:3, :3] = [[0, 0, 1], [0, 1, 0], [-1, 0, 0]]  # flange axis along +x
    pose[:3, 3] = (1.5, 0.0, p.c1)
    res = r.ik(pose)
    wrist_from_j2 = 1.5 - p.c4 - p.a1
    expected = wrist_from_j2 - (p.c2 + math.hypot(p.a2, p.c3))
    assert res.status is IkStatus.UNREACHABLE and not res.solutions
    assert res.distance == pytest.approx(expected, abs=1e-12)
    assert f"{expected * 1000:.1f} mm" in res.message


def test_out_of_limits_names_the_joint_and_the_excess():
    """A KR 210 pose reached only with A2 beyond -5°: OUT_OF_LIMITS on joint index 1 (A2)."""
    r = load_robot("kuka_kr210")
    q = np.radians([0, 5, 90, 0, 45, 0])  # A2 = +5° is 10° beyond its -5° limit
    res = r.ik(r.fk(q))
    assert res.status is IkStatus.OUT_OF_LIMITS
    assert res.joint == 1 and math.degrees(res.excess) == pytest.approx(10.0, abs=1e-6)
    assert res.message.startswith("joint 2 exceeds its limit by 10.0 deg")


def test_wrist_singular_pose_reports_singular_and_keeps_the_seed_j4():
    """J5 = 0 aligns J4 and J6: SINGULAR, with solutions, J4 taken from the seed."""
    r = load_robot("abb_irb120")
    pose = r.fk(np.radians([0, 10, 10, 30, 0, -10]))
    res = r.ik(pose, seed=np.radians([0, 10, 10, 25, 0, 0]))
    assert res.status is IkStatus.SINGULAR
    np.testing.assert_allclose(np.degrees(res.solutions[0]), [0, 10, 10, 25, 0, -5], atol=1e-6)


def test_config_filter_keeps_only_that_branch():
    """config=... keeps matching branches; an impossible one says which branches exist."""
    r = load_robot("staubli_tx2_60")
    pose = r.fk(np.radians([10, 30, 60, 20, 40, 10]))
    down = r.ik(pose, config=ir.Config(elbow=ir.Elbow.DOWN))
    assert down.solutions and all(b.elbow is ir.Elbow.DOWN for b in down.branches)
    every = {b for b in r.ik(pose).branches}
    missing = [ir.Config(s, e, w) for s in ir.Shoulder for e in ir.Elbow for w in ir.Wrist if ir.Config(s, e, w) not in every]
    if missing:
        res = r.ik(pose, config=missing[0])
        assert res.status is IkStatus.UNREACHABLE and "no IK solution with" in res.message


def test_bad_pose_raises_value_error():
    """A non-rigid or wrongly shaped pose is a programming error: ValueError."""
    r = load_robot("ur5e")
    with pytest.raises(ValueError, match="orthonormal"):
        r.ik(np.diag([2.0, 1.0, 1.0, 1.0]))
    with pytest.raises(ValueError, match="shape"):
        r.ik(np.eye(3))


@pytest.mark.parametrize("name", list_robots())
def test_batch_rows_are_fixed_branches(name):
    """Row k of ik_batch is the same branch (robot.batch_branches[k]) for every pose, and the
    eight rows are the eight different branches."""
    r = load_robot(name)
    assert len(set(r.batch_branches)) == 8
    qs = random_q(r, 300, seed=12)
    raw = r.ik_closed_form(r.fk_batch(qs))
    for rows in raw:
        for k, row in enumerate(rows):
            if np.all(np.isfinite(row)) and abs(math.sin(row[4])) > 1e-6:
                assert r.branch(row) == r.batch_branches[k]


def test_equivalents_are_every_in_limit_shift_in_product_order_and_reproduce_the_pose():
    """UR5 URDF (±2π limits): the equivalents of a solution are exactly the in-limit q + 2πk,
    in itertools.product order, and each reproduces the solution's FK to 1e-9 (the invariance
    that lets `ik` verify only the distinct solutions)."""
    import importlib.metadata
    import itertools

    from rmot.sim.robots.ik import _equivalents

    files = importlib.metadata.files("example-robot-data") or []
    r = load_robot(str(next(f for f in files if f.name == "ur5_robot.urdf").locate()))
    lo, hi = r.joint_limits[:, 0], r.joint_limits[:, 1]
    for q in np.random.default_rng(3).uniform(lo, hi, (50, r.dof)):
        options = [[v + k * 2 * math.pi for k in range(-3, 4) if lo[j] - 1e-12 <= v + k * 2 * math.pi <= hi[j] + 1e-12]
                   for j, v in enumerate(q)]
        expected = np.array(list(itertools.product(*options)))
        got = _equivalents(r, q)
        assert got.shape == expected.shape
        np.testing.assert_allclose(got, expected, atol=1e-12)
        fk = r.fk_batch(got)
        np.testing.assert_allclose(fk, np.broadcast_to(r.fk(q), fk.shape), atol=1e-9)
