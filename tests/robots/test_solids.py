"""Link solids of the library arms: placement, coverage, adjacency, self contact at home."""

from __future__ import annotations

import numpy as np
import pytest

from rmot.lang import ir
from rmot.sim.robots import list_robots, load_robot
from rmot.sim.robots.library import SPECS

HOME_DEG = {"kuka_kr6_r900": (0, -90, 90, 0, 45, 0), "kuka_kr16": (0, -90, 90, 0, 45, 0),
            "kuka_kr210": (0, -90, 90, 0, 45, 0), "ur3e": (0, -90, 90, -90, -90, 0),
            "ur5e": (0, -90, 90, -90, -90, 0), "ur10e": (0, -90, 90, -90, -90, 0),
            "puma560": (0, 90, -90, 0, 45, 0)}


def home(name: str) -> np.ndarray:
    """The vendor's home: KUKA (0, -90, 90, 0, 45, 0), UR (0, -90, 90, -90, -90, 0), else 45° on J5."""
    family = HOME_DEG["kuka_kr16"] if name.startswith("kuka_") else HOME_DEG["ur5e"] if name.startswith("ur") else None
    return np.radians(HOME_DEG.get(name, family or (0, 0, 0, 0, 45, 0)))


def segment(pose: np.ndarray, geometry: ir.Geometry) -> tuple[np.ndarray, np.ndarray, float]:
    """The core segment and radius of a capsule, or a cylinder's axis and radius."""
    half = geometry.length / 2 if isinstance(geometry, ir.Capsule) else geometry.height / 2
    axis = pose[:3, 2] * half
    return pose[:3, 3] - axis, pose[:3, 3] + axis, geometry.radius


def samples(p0: np.ndarray, p1: np.ndarray, n: int = 201) -> np.ndarray:
    return p0 + np.outer(np.linspace(0, 1, n), p1 - p0)


def segment_distance(p0, p1, q0, q1) -> float:
    """Closest distance of two segments (dense sampling: ~1e-4 m on these lengths)."""
    return float(np.linalg.norm(samples(p0, p1)[:, None] - samples(q0, q1)[None], axis=2).min())


def cylinder_distance(c0, c1, radius, points: np.ndarray) -> float:
    """Smallest distance from points (k,3) to the solid cylinder with axis c0-c1."""
    axis = c1 - c0
    length = np.linalg.norm(axis)
    u = axis / length
    t = (points - c0) @ u
    radial = np.linalg.norm(points - c0 - np.outer(t, u), axis=1)
    dr = np.maximum(radial - radius, 0.0)
    dt = np.maximum(np.maximum(-t, t - length), 0.0)
    return float(np.min(np.hypot(dr, dt)))


def gaps(name: str, q: np.ndarray, pairs=None) -> dict[tuple[int, int], float]:
    """Surface gap (m, negative = overlap) of the solid pairs (default: all) at q."""
    r = load_robot(name)
    poses = r.solid_poses(q)
    segs = [segment(p, s.geometry) for p, s in zip(poses, r.solids)]
    out = {}
    every = [(i, j) for i in range(len(segs)) for j in range(i + 1, len(segs))]
    for i, j in pairs or every:
        (a0, a1, ra), (b0, b1, rb) = segs[i], segs[j]
        if isinstance(r.solids[i].geometry, ir.Cylinder):
            out[(i, j)] = cylinder_distance(a0, a1, ra, samples(b0, b1)) - rb
        else:
            out[(i, j)] = segment_distance(a0, a1, b0, b1) - ra - rb
    return out


@pytest.mark.parametrize("name", list_robots())
def test_solids_are_capsules_on_moving_joints_and_a_base_cylinder(name):
    """One base cylinder on joint 0, capsules on every moving joint, radii well below the reach."""
    r = load_robot(name)
    assert isinstance(r.solids[0].geometry, ir.Cylinder) and r.solids[0].joint_id == 0
    assert {s.joint_id for s in r.solids} == set(range(r.dof + 1))
    assert all(isinstance(s.geometry, ir.Capsule) for s in r.solids[1:])
    assert all(0.02 <= s.geometry.radius <= 0.2 * r.reach for s in r.solids)


@pytest.mark.parametrize("name", list_robots())
def test_no_self_contact_between_non_adjacent_solids_at_home(name):
    """At the home pose of a real arm no two non-adjacent solids touch (1 mm margin)."""
    r = load_robot(name)
    adjacent = set(r.adjacent_pairs)
    touching = [(r.solids[i].name, r.solids[j].name, round(g, 4)) for (i, j), g in gaps(name, home(name)).items()
                if (i, j) not in adjacent and g < 0.001]
    assert touching == []


@pytest.mark.parametrize("name", list_robots())
def test_excluded_pairs_are_chain_neighbours_touching_at_every_configuration(name):
    """adjacent_pairs = consecutive solids plus the spec's named pairs; the consecutive ones
    touch at home and at 20 random configurations, so excluding them hides no avoidable contact."""
    r = load_robot(name)
    extra = {tuple(sorted(p)) for p in SPECS[name].extra_adjacent}
    consecutive = {(i, i + 1) for i in range(len(r.solids) - 1)}
    for i, j in r.adjacent_pairs:
        assert (i, j) in consecutive or tuple(sorted((r.solids[i].name, r.solids[j].name))) in extra
    configs = [home(name)] + list(np.random.default_rng(8).uniform(r.joint_limits[:, 0], r.joint_limits[:, 1], (20, r.dof)))
    for q in configs:
        g = gaps(name, q, sorted(consecutive))
        assert all(g[pair] <= 1e-3 for pair in consecutive), name


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
