"""Conservative advancement inside a contact: skipped samples keep the runs and their depth."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from rmot.sim.collide import DEPTH_TOL, _advance


def _runs(contact: np.ndarray) -> list[tuple[int, int]]:
    edges = np.flatnonzero(np.diff(np.concatenate([[0], contact.astype(np.int8), [0]])))
    return list(zip(edges[::2].tolist(), (edges[1::2] - 1).tolist(), strict=True))


def _scenario(seed: int, depth: float, wiggle: float, n: int = 600):
    """A 1-Lipschitz signed distance along the motion (slope <= 1 per metre moved), sampled
    with random motion bounds per interval: dense reference values and the motion."""
    rng = np.random.default_rng(seed)
    move = rng.uniform(0.0, 2e-3, n - 1)
    cum = np.concatenate([[0.0], np.cumsum(move)])
    mid = cum[-1] * rng.uniform(0.3, 0.7)
    # slope 0.6 from the V plus at most 0.4 from the wiggle: still 1-Lipschitz in cum
    d = 0.6 * np.abs(cum - mid) - depth + wiggle * np.sin(cum * 0.4 / max(wiggle, 1e-12))
    return d, move


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 10_000), st.floats(0.0, 0.2), st.floats(0.0, 0.02))
def test_skipping_inside_a_contact_keeps_runs_and_depth(seed: int, depth: float, wiggle: float) -> None:
    """Same contact samples and runs as the dense reference, each run's depth within DEPTH_TOL,
    and a skipped sample never reported shallower-than-contact or deeper than it is."""
    dense, move = _scenario(seed, depth, wiggle)

    def distance_at(i: int) -> float:
        return float(dense[i])

    flagged = np.arange(dense.size)
    need = np.append(move, 0.0)
    evaluated, dists, _ = _advance(flagged, need, move, 0.0, distance_at, lipschitz=True)
    assert np.all(np.diff(evaluated) > 0)
    reported = np.full(dense.size, np.inf)
    reported[evaluated] = dists
    assert np.array_equal(reported <= 0.0, dense <= 0.0)
    contact = dense <= 0.0
    assert np.all(reported[contact] >= dense[contact] - 1e-12)  # upper bounds or exact values
    for start, stop in _runs(contact):
        assert np.min(reported[start:stop + 1]) - np.min(dense[start:stop + 1]) <= DEPTH_TOL


def test_long_deep_contact_needs_few_exact_queries() -> None:
    """A long, deep contact is not measured at every sample, yet its depth is the dense one."""
    dense, move = _scenario(seed=1, depth=0.15, wiggle=0.0, n=2000)
    calls: list[int] = []

    def distance_at(i: int) -> float:
        calls.append(i)
        return float(dense[i])

    need = np.append(move, 0.0)
    evaluated, dists, _ = _advance(np.arange(dense.size), need, move, 0.0, distance_at, lipschitz=True)
    contact = dense <= 0.0
    assert contact.sum() > 200
    in_contact_calls = sum(1 for i in calls if contact[i])
    assert in_contact_calls < contact.sum() / 2
    assert abs(np.min(dists) - np.min(dense)) <= DEPTH_TOL


def test_without_lipschitz_every_contact_sample_is_exact() -> None:
    """Meshes (no signed-distance bound) still get one exact query per contact sample."""
    dense, move = _scenario(seed=2, depth=0.1, wiggle=0.0, n=800)
    evaluated, dists, _ = _advance(np.arange(dense.size), np.append(move, 0.0), move, 0.0,
                                   lambda i: float(dense[i]), lipschitz=False)
    contact = np.flatnonzero(dense <= 0.0)
    assert np.all(np.isin(contact, evaluated))
    assert np.allclose(dists[np.searchsorted(evaluated, contact)], dense[contact])


def test_contact_runs_match_a_dense_exact_reference() -> None:
    """UR5e through fixtures: every sampled contact run is one finding of its pair, with its
    start and end within a sample and its depth within DEPTH_TOL of coal at every sample."""
    from rmot.lang import ir
    from rmot.sim.robots import load_robot
    from rmot.sim.collide import Timeline, candidate_pairs, check_timeline
    from rmot.sim.exact import ExactPair
    from rmot.sim.scene import build_scene

    rng = np.random.default_rng(7)
    fixtures = []
    for k in range(8):
        angle, radius = 2 * np.pi * k / 8, (0.45, 0.6)[k % 2]
        at = (radius * np.cos(angle), radius * np.sin(angle), float(rng.uniform(0.0, 0.5)))
        fixtures.append(ir.Fixture(f"f{k}", ir.Box((0.15, 0.15, 0.4)), ir.Pose(at)))
    robot = load_robot("ur5e")
    source = ir.RobotSource(ir.RobotSourceKind.LIBRARY, "ur5e")
    cell = ir.Cell("dense", (ir.RobotInstance("r1", source, ir.Pose(), 6),), tuple(fixtures))
    scene = build_scene(cell, {}, {"r1": robot})
    n = 1500
    s = np.linspace(0.0, 1.0, n)[:, None]
    q = np.array([-2.5, -1.2, 1.0, -1.0, 0.5, 0.0]) + s * np.array([5.0, 0.8, -0.6, 1.5, -1.0, 2.0])
    t = np.arange(n) * 0.004
    timeline = Timeline(t, {"r1": q}, {"r1": np.full_like(q, 5.0)})
    pairs = [(a, b) for a, b in candidate_pairs(scene) if b.kind == "fixture" or a.kind == "fixture"]
    hits = check_timeline(scene, timeline, pairs)
    poses = scene.poses("r1", q)
    long_runs = 0
    for a, b in pairs:
        link, fixture = (a, b) if b.kind == "fixture" else (b, a)
        exact = ExactPair(link, fixture)
        dense = np.array([exact.distance(p, fixture.local, np.inf) for p in poses[link.name]])
        found = [h for h in hits if {h.a, h.b} == {a.name, b.name} and h.kind == "collision"]
        for start, stop in _runs(dense <= 0.0):
            long_runs += stop - start > 20
            mine = [h for h in found if h.t0 <= t[stop] + 0.004 and t[start] - 0.004 <= h.t1]
            assert len(mine) == 1, (a.name, b.name, t[start], t[stop], mine)
            hit = mine[0]
            assert abs(hit.t0 - t[start]) <= 0.004 + 1e-9 and abs(hit.t1 - t[stop]) <= 0.004 + 1e-9
            assert hit.distance <= np.min(dense[start:stop + 1]) + DEPTH_TOL
    assert long_runs >= 3
