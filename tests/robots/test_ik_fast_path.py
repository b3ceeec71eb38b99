"""Robot.ik's compiled single-pose pass (sim/robots/fastsolve.py) returns what the step-by-
step path (ik.solve_exact: numpy + pinocchio) returns for the same pose, seed and config: the
same joint values bit for bit, in the same order, with the same branches and status; the first
solution reaches the pose by pinocchio's FK within the tolerances; and it is one of ik_batch's
rows for the same seed (the nearest in-limit equivalent of its branch). Poses the pass hands back
(None) must be ones the exact path has a reason to treat specially, so the pass may decline but
never answer differently."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from rmot.lang import ir
from rmot.sim.robots import ik, load_robot

ROBOTS = ("abb_irb120", "ur5e", "kuka_kr6_r900", "fanuc_m20ia")  # OPW, UR, KUKA signs, Fanuc coupling
_CACHE: dict[str, object] = {}
CONFIGS = (None, ir.Config(ir.Shoulder.FRONT, None, None), ir.Config(None, ir.Elbow.DOWN, ir.Wrist.FLIP))


def robot_and_solver(name: str):  # type: ignore[no-untyped-def]
    if name not in _CACHE:
        robot = load_robot(name)
        _CACHE[name] = (robot, ik._fast_solver(robot))
    return _CACHE[name]


@settings(max_examples=60, deadline=None)
@given(name=st.sampled_from(ROBOTS), u=st.lists(st.floats(0.0, 1.0), min_size=6, max_size=6),
       offset=st.lists(st.floats(-3.0, 3.0), min_size=6, max_size=6), use_seed=st.booleans(),
       config=st.sampled_from(CONFIGS))
def test_fast_pass_equals_the_exact_path_and_the_batch(name, u, offset, use_seed, config) -> None:  # type: ignore[no-untyped-def]
    robot, solver = robot_and_solver(name)
    assert solver, f"{name} has a closed form: the compiled pass must serve it"
    lo, hi = np.maximum(robot.joint_limits[:, 0], -4.0), np.minimum(robot.joint_limits[:, 1], 4.0)
    q = lo + np.array(u) * (hi - lo)
    pose = robot.fk(q).copy()
    seed = q + np.array(offset) if use_seed else None
    fast = solver.solve(robot, pose, seed, config)
    exact = ik.solve_exact(robot, pose, seed, config)
    if fast is None:  # handed back: only for the cases the module docstring lists
        return
    assert fast.status is exact.status
    assert len(fast.solutions) == len(exact.solutions) > 0
    assert all(np.array_equal(a, b) for a, b in zip(fast.solutions, exact.solutions))
    assert fast.branches == exact.branches
    assert all(robot.branch(s) == b for s, b in zip(fast.solutions[:3], fast.branches[:3]))
    lo_all, hi_all = robot.joint_limits[:, 0], robot.joint_limits[:, 1]
    for s in fast.solutions:
        assert np.all(s >= lo_all) and np.all(s <= hi_all)
    first = fast.solutions[0]
    dp, dr = ik.pose_error(robot.fk(first), pose)  # pinocchio, not the pass's own FK
    assert dp <= ik.POS_TOL and dr <= ik.ROT_TOL
    if config is None:
        rows = robot.ik_batch(pose[None], seed=seed)[0]
        finite = rows[np.all(np.isfinite(rows), axis=1)]
        assert len(finite) and np.abs(finite - first).max(axis=1).min() <= 1e-9


def test_the_pass_is_used_and_declines_out_of_limits_and_unreachable_poses() -> None:
    robot, solver = robot_and_solver("abb_irb120")
    pose = robot.fk(np.radians([10.0, 20.0, -10.0, 30.0, 40.0, 50.0]))
    assert solver.solve(robot, pose, None, None) is not None
    far = pose.copy()
    far[:3, 3] += 5.0
    assert solver.solve(robot, far, None, None) is None
    assert robot.ik(far).status is ik.IkStatus.UNREACHABLE
    bad = pose.copy()
    bad[0, 0] = np.nan
    assert solver.solve(robot, bad, None, None) is None


def test_screening_sine_and_cosine_match_libm() -> None:
    """fastfk._sincos (fdlibm's polynomials) against math.sin / math.cos, interpreted and compiled."""
    import math

    from rmot.sim.robots.fastfk import SINCOS

    xs = np.concatenate([np.random.default_rng(3).uniform(-40.0, 40.0, 4000), np.arange(-50, 51) * np.pi / 4,
                         [0.0, -0.0, 1e-300, -1e-12, 3.0, -3.0]])
    for fn in (SINCOS.py, SINCOS.jit()):
        worst = max(max(abs(s - math.sin(x)), abs(c - math.cos(x))) for x in xs.tolist() for s, c in [fn(x)])
        assert worst <= 4e-16
