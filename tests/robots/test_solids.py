"""Link solids of the library arms: placement, coverage, adjacency, self contact at home."""

from __future__ import annotations

import numpy as np
import pytest

from rmot.compiler import ir
from rmot.compiler.robots import list_robots, load_robot
from rmot.compiler.robots.library import SPECS

HOME_DEG = {"kuka_kr6_r900": (0, -90, 90, 0, 45, 0), "kuka_kr16": (0, -90, 90, 0, 45, 0),
            "kuka_kr210": (0, -90, 90, 0, 45, 0), "ur3e": (0, -90, 90, -90, -90, 0),
            "ur5e": (0, -90, 90, -90, -90, 0), "ur10e": (0, -90, 90, -90, -90, 0),
            "puma560": (0, 90, -90, 0, 45, 0)}


def home(name: str) -> np.ndarray:
    return np.radians(HOME_DEG.get(name, (0, 0, 0, 0, 45, 0)))


def segment(pose: np.ndarray, geometry: ir.Geometry) -> tuple[np.ndarray, np.ndarray, float]:
    """The core segment and radius of a capsule (a cylinder is bounded by the same capsule)."""
    half = geometry.length / 2 if isinstance(geometry, ir.Capsule) else geometry.height / 2
    axis = pose[:3, 2] * half
    return pose[:3, 3] - axis, pose[:3, 3] + axis, geometry.radius


def segment_distance(p0, p1, q0, q1) -> float:
    """Closest distance of two segments, by dense sampling refined with a local search."""
    s = np.linspace(0, 1, 201)
    a = p0 + np.outer(s, p1 - p0)
    b = q0 + np.outer(s, q1 - q0)
    d = np.linalg.norm(a[:, None] - b[None], axis=2)
    return float(d.min())


def gaps(name: str, q: np.ndarray) -> dict[tuple[int, int], float]:
    """Surface gap (m, negative = overlap) of every solid pair at q."""
    r = load_robot(name)
    poses = r.solid_poses(q)
    segs = [segment(p, s.geometry) for p, s in zip(poses, r.solids)]
    return {
        (i, j): segment_distance(segs[i][0], segs[i][1], segs[j][0], segs[j][1]) - segs[i][2] - segs[j][2]
        for i in range(len(segs)) for j in range(i + 1, len(segs))
    }


@pytest.mark.parametrize("name", list_robots())
def test_solids_are_capsules_on_moving_joints_and_a_base_cylinder(name):
    """One base cylinder on joint 0, capsules on every moving joint, radii well below the reach."""
    r = load_robot(name)
    assert isinstance(r.solids[0].geometry, ir.Cylinder) and r.solids[0].joint_id == 0
    assert {s.joint_id for s in r.solids} == set(range(r.dof + 1))
    assert all(isinstance(s.geometry, ir.Capsule) for s in r.solids[1:])
    assert all(0.02 <= s.geometry.radius <= 0.15 * r.reach for s in r.solids)


@pytest.mark.parametrize("name", list_robots())
def test_no_self_contact_between_non_adjacent_solids_at_home(name):
    """At the home pose of a real arm no two non-adjacent solids touch (1 mm margin)."""
    r = load_robot(name)
    adjacent = set(r.adjacent_pairs)
    touching = [(r.solids[i].name, r.solids[j].name, round(g, 4)) for (i, j), g in gaps(name, home(name)).items()
                if (i, j) not in adjacent and g < 0.001]
    assert touching == []


@pytest.mark.parametrize("name", list_robots())
def test_adjacent_pairs_are_neighbours_that_touch_by_construction(name):
    """Each excluded pair is on the same or consecutive joints or a named elbow pair, and the
    consecutive ones meet at their shared joint (they touch at home)."""
    r = load_robot(name)
    extra = {tuple(sorted(p)) for p in SPECS[name].extra_adjacent}
    g = gaps(name, home(name))
    for i, j in r.adjacent_pairs:
        a, b = r.solids[i], r.solids[j]
        named = tuple(sorted((a.name, b.name))) in extra
        assert abs(a.joint_id - b.joint_id) <= 1 or named
        if abs(a.joint_id - b.joint_id) == 1 and not named:
            assert g[(i, j)] < 0.02, (a.name, b.name)


@pytest.mark.parametrize("name", list_robots())
def test_solids_cover_the_joint_axes_points(name):
    """Every joint origin of the kinematic chain lies inside (or within 2 cm of) some solid."""
    r = load_robot(name)
    q = home(name)
    frames = r._chain.joint_frames(r.to_model(q[None]))[0]
    poses = r.solid_poses(q)
    segs = [segment(p, s.geometry) for p, s in zip(poses, r.solids)]
    for point in list(frames[1:, :3, 3]) + [r.fk(q)[:3, 3] - 0.02 * r.fk(q)[:3, 2]]:
        inside = min(segment_distance(a, b, point, point) - rad for a, b, rad in segs)
        assert inside < 0.02, point


def test_solid_poses_follow_their_joint():
    """A solid on joint 6 turns with J6 about the flange axis; the base solid never moves."""
    r = load_robot("abb_irb1600")
    q = np.radians([10, 20, 30, 40, 50, 60])
    a, b = r.solid_poses(q), r.solid_poses(q + np.radians([0, 0, 0, 0, 0, 90]))
    np.testing.assert_allclose(a[0], b[0], atol=1e-15)
    np.testing.assert_allclose(a[:-1], b[:-1], atol=1e-12)
    np.testing.assert_allclose(a[-1][:3, 3], b[-1][:3, 3], atol=1e-12)  # on the J6 axis
