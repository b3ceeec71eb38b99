"""The verification's chunked computations (bounded memory) give the same floats as
one computation over every sample: Scene.poses (POSE_CHUNK samples at a time) and the broad
phase's lower_bound (BOUND_CHUNK), each on a case of several chunks with a short last one,
and a whole verification report, byte for byte, with tiny chunks against the defaults."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from simkit import box, cell

from rmot.lang import ir
from rmot.sim.robots import load_robot
from rmot.sim.robots.fastdls import JOINT_FRAMES
from rmot.sim import bounds, scene as scene_mod
from rmot.sim.bounds import LazyCentres, lower_bound
from rmot.sim.scene import Body, Scene, build_scene

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.fixture
def one_fk_form(monkeypatch: pytest.MonkeyPatch) -> None:
    """FK in one form for the whole test, the compiled one: numba's and the interpreter's sine
    may differ in the last bit, and which runs depends on the work done so far (lang/jit.py).
    Its threshold set low, so that Scene.poses' chunk is POSE_CHUNK, as patched by the test."""
    JOINT_FRAMES.jit()  # from now on this process runs the compiled form (loaded from numba's cache)
    monkeypatch.setattr(JOINT_FRAMES, "threshold", 1)


def _scene() -> Scene:
    tool = ir.Tool("gripper", "r1", ir.Cylinder(0.02, 0.06), ir.Pose((0, 0, 0.1)),
                   geometry_pose=ir.Pose((0, 0, 0.03)))
    c = cell([("r1", (0.1, -0.2, 0.3))], fixtures=[box("table", (0.6, 0.8, 0.04), (0.45, 0, -0.02))],
             tools=[tool])
    return build_scene(c, {"r1": {"gripper"}}, {"r1": load_robot("abb_irb120")})


def _samples(n: int, seed: int = 0) -> np.ndarray:
    robot = load_robot("abb_irb120")
    lo, hi = robot.joint_limits[:, 0], robot.joint_limits[:, 1]
    return lo + np.random.default_rng(seed).random((n, robot.dof)) * (hi - lo)


def test_scene_poses_in_chunks_equal_one_pass(monkeypatch: pytest.MonkeyPatch, one_fk_form: None) -> None:
    """2,500 samples in chunks of 1,000 (the last one 500) == all at once, bit for bit."""
    scene, q = _scene(), _samples(2500)
    monkeypatch.setattr(scene_mod, "POSE_CHUNK", 10**9)
    whole = scene.poses("r1", q)
    monkeypatch.setattr(scene_mod, "POSE_CHUNK", 1000)
    chunked = scene.poses("r1", q)
    assert list(chunked) == list(whole) == [b.name for b in scene.robot_bodies("r1")]
    for name, poses in whole.items():
        assert poses.shape == (2500, 4, 4)
        assert np.array_equal(chunked[name], poses), name
    # and each pose is the robot's own FK of its sample (not a shifted or repeated chunk)
    flange = scene.robots["r1"].base @ scene.robots["r1"].robot.fk(q[2101])
    tool = scene.body("gripper")
    np.testing.assert_allclose(chunked["gripper"][2101], flange @ tool.local, atol=1e-12)


def test_lower_bound_in_chunks_equals_one_pass(monkeypatch: pytest.MonkeyPatch, one_fk_form: None) -> None:
    """A fixture pair and a sphere-cover pair, at chosen samples and at all, with and without
    cached centres: chunks of 7 samples (several, the last short) == one pass, bit for bit."""
    scene, q = _scene(), _samples(300, seed=1)
    poses = scene.poses("r1", q)
    poses["table"] = scene.body("table").local[None]
    pairs = [(scene.body("table"), scene.body("r1/forearm")), (scene.body("r1/upper_arm"), scene.body("gripper")),
             (scene.body("gripper"), scene.body("table"))]
    idx = np.sort(np.random.default_rng(2).choice(300, size=52, replace=False))
    for a, b in pairs:
        for rows in (idx, None):
            for cached in (False, True):
                def bound(a: Body = a, b: Body = b, rows: np.ndarray | None = rows,
                          cached: bool = cached) -> np.ndarray:
                    centres = LazyCentres(scene, poses) if cached else None
                    return lower_bound(a, b, poses[a.name], poses[b.name], centres, rows)

                monkeypatch.setattr(bounds, "BOUND_CHUNK", 10**9)
                whole = bound()
                monkeypatch.setattr(bounds, "BOUND_CHUNK", 7)
                chunked = bound()
                assert whole.shape == ((52,) if rows is not None else (300,))
                assert np.array_equal(chunked, whole), (a.name, b.name, rows is None, cached)


def test_verification_report_unchanged_by_chunk_sizes(monkeypatch: pytest.MonkeyPatch, one_fk_form: None) -> None:
    """examples/collision.rmot (a collision finding: exact distances, bisection, runs) verified
    with chunks of 64 poses and 5 bound samples gives the same JSON report, byte for byte."""
    from rmot.compiler import frontend, plan_cache
    from rmot.sim import verify
    from rmot.sim.report import format_json

    front = frontend.load_program(str(EXAMPLES / "collision.rmot"), require_program=True)
    assert front.program is not None
    plan = plan_cache.cached_plan(front.program)
    samples = plan.tasks[0].trajectory.t.size
    default = format_json([verify(plan)])
    monkeypatch.setattr(scene_mod, "POSE_CHUNK", 64)
    monkeypatch.setattr(bounds, "BOUND_CHUNK", 5)
    small = format_json([verify(plan)])
    assert samples > 10 * 64 and '"E300"' in default
    assert small == default


def test_pose_chunks_never_below_the_fk_threshold(monkeypatch: pytest.MonkeyPatch) -> None:
    """A chunk is at least JOINT_FRAMES's threshold: the first chunk of a long sweep then takes
    the form (compiled or not) one call for every sample would take."""
    scene, q = _scene(), _samples(2500)
    robot = scene.robots["r1"].robot
    sizes: list[int] = []
    batch = robot.solid_poses_batch

    def spy(qs: np.ndarray) -> np.ndarray:
        sizes.append(len(qs))
        return np.asarray(batch(qs))

    monkeypatch.setattr(robot, "solid_poses_batch", spy)
    monkeypatch.setattr(scene_mod, "POSE_CHUNK", 1000)
    monkeypatch.setattr(JOINT_FRAMES, "threshold", 1200)
    scene.poses("r1", q)
    assert sizes == [1200, 1200, 100]
    sizes.clear()
    monkeypatch.setattr(JOINT_FRAMES, "threshold", 1)
    scene.poses("r1", q)
    assert sizes == [1000, 1000, 500]
