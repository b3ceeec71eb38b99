"""The cell model: body names, and the bounds the no-miss guarantee rests on."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from simkit import arm3, box, cell

from rmot.lang import ir
from rmot.sim.bounds import lower_bound
from rmot.sim.exact import ExactPair
from rmot.sim.scene import _sphere_cover, build_scene


def _scene():
    tool = ir.Tool("gun", "r1", ir.Box((0.05, 0.05, 0.2)), ir.Pose((0, 0, 0.2)), geometry_pose=ir.Pose((0, 0, 0.1)))
    c = cell([("r1", (0.5, 0, 0))], fixtures=[box("table", (1, 1, 0.05), (0.5, 0, -0.03))], tools=[tool])
    return build_scene(c, {"r1": {"gun"}}, {"r1": arm3("r1")})


def test_body_names() -> None:
    """Fixtures and tools keep their names; link solids are robot/solid."""
    names = [b.name for b in _scene().bodies]
    assert names == ["table", "r1/base", "r1/link1", "r1/link2", "r1/link3", "gun"]


def test_tool_pose_is_flange_times_geometry_pose() -> None:
    """The tool body sits at base * fk(q) * geometry_pose."""
    scene = _scene()
    q = np.array([[0.3, -0.4, 0.9]])
    pose = scene.poses("r1", q)["gun"][0]
    robot = scene.robots["r1"].robot
    expected = ir.Pose((0.5, 0, 0)).matrix() @ robot.fk(q[0]) @ ir.Pose((0, 0, 0.1)).matrix()
    np.testing.assert_allclose(pose, expected, atol=1e-12)


@settings(max_examples=30, deadline=None)
@given(shape=st.sampled_from([ir.Box((0.3, 0.05, 0.1)), ir.Capsule(0.04, 0.3), ir.Cylinder(0.05, 0.2), ir.Sphere(0.1)]),
       u=st.tuples(*[st.floats(-1, 1)] * 3))
def test_sphere_cover_contains_the_shape(shape, u) -> None:
    """Every point of a solid lies inside the union of its covering spheres."""
    u = np.array(u)
    if isinstance(shape, ir.Box):
        p = u * np.array(shape.size) / 2
    elif isinstance(shape, ir.Sphere):
        p = u / max(1.0, np.linalg.norm(u)) * shape.radius
    else:
        r = shape.radius * u[:2] / max(1.0, np.linalg.norm(u[:2]))
        half = (shape.length / 2 + shape.radius) if isinstance(shape, ir.Capsule) else shape.height / 2
        p = np.array([r[0], r[1], u[2] * half])
        if isinstance(shape, ir.Capsule) and abs(p[2]) > shape.length / 2:  # inside the cap
            cap = np.array([0, 0, np.sign(p[2]) * shape.length / 2])
            p = cap + (p - cap) * min(1.0, shape.radius / max(np.linalg.norm(p - cap), 1e-12))
    spheres = _sphere_cover(shape)
    assert np.min(np.linalg.norm(spheres[:, :3] - p, axis=1) - spheres[:, 3]) <= 1e-12


@settings(max_examples=30, deadline=None)
@given(q0=st.tuples(*[st.floats(-2, 2)] * 3), dq=st.tuples(*[st.floats(-0.3, 0.3)] * 3))
def test_reach_bounds_the_motion(q0, dq) -> None:
    """No sphere centre moves more than sum |dq_j| * reach_j along the straight joint move."""
    scene = _scene()
    q0, dq = np.array(q0), np.array(dq)
    qs = q0 + np.linspace(0, 1, 50)[:, None] * dq
    poses = scene.poses("r1", qs)
    for body in scene.robot_bodies("r1"):
        centres = np.einsum("mij,kj->mki", poses[body.name][:, :3, :3], body.spheres[:, :3]) + poses[body.name][:, None, :3, 3]
        moved = np.max(np.linalg.norm(centres - centres[0], axis=-1))
        assert moved <= np.abs(dq) @ body.reach + 1e-12


@settings(max_examples=30, deadline=None)
@given(q=st.tuples(*[st.floats(-3, 3)] * 3))
def test_lower_bound_below_exact_distance(q) -> None:
    """The broad phase never reports more distance than coal's exact one."""
    scene = _scene()
    poses = scene.poses("r1", np.array([q]))
    table = scene.body("table")
    bodies = scene.robot_bodies("r1")
    for body in bodies:
        if body.moves:
            exact = ExactPair(body, table).distance(poses[body.name][0], table.local, np.inf)
            bound = lower_bound(body, table, poses[body.name], table.local[None])[0]
            assert bound <= max(exact, 0.0) + 1e-9  # (depths are not bounded, only distances)
    link1, link3 = scene.body("r1/link1"), scene.body("r1/link3")
    exact = ExactPair(link1, link3).distance(poses[link1.name][0], poses[link3.name][0], np.inf)
    assert lower_bound(link1, link3, poses[link1.name], poses[link3.name])[0] <= max(exact, 0.0) + 1e-9
