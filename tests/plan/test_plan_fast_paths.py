"""The planner's fast paths (planning speed) against independent witnesses:

* a refined timing grid (new points and cells evaluated alone and merged into the old ones in
  place) holds the same limits as the same grid evaluated whole;
* the vectorised 2 pi unwrap of a dense IK branch equals the obvious row-by-row unwrap and keeps
  every revolute step below half a turn;
* a blend's zone entry lies on its sphere and on its joint-space segment, by an FK that is not
  the one the bisection uses (the batched chain, not pinocchio).
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rmot.compiler.plan import blend, timing
from rmot.compiler.plan.dense import _Solver


def _limits(seed: int) -> timing._Limits:
    """A wavy 6-joint path with a TCP spline, a varying joint-speed share and TCP limits."""
    from scipy.interpolate import CubicSpline

    rng = np.random.default_rng(seed)
    m = 40
    ss = np.concatenate([[0.0], np.cumsum(rng.uniform(0.002, 0.03, m - 1))])
    waypoints = np.sin(ss[:, None] * rng.uniform(1, 8, 6) + rng.uniform(0, 6, 6))
    tcp = np.stack([np.cos(3 * ss), np.sin(2 * ss), 0.1 * ss], axis=1)
    f_int = rng.uniform(0.3, 1.0, m - 1)
    tcp_int = (rng.uniform(0.1, 0.5, m - 1), np.where(rng.random(m - 1) < 0.5, np.inf, 2.0))
    return timing._Limits(timing._PathSpline(ss, waypoints), CubicSpline(ss, tcp), ss,
                          np.full(6, 3.0), np.full(6, 20.0), f_int, tcp_int)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_refined_grid_holds_the_limits_of_the_same_grid_evaluated_whole(seed: int) -> None:
    limits = _limits(seed)
    grid, _ = timing._grid(limits.ss)
    arrays = timing._Arrays(limits, grid)
    rng = np.random.default_rng(seed)
    for _ in range(3):  # refine repeatedly, first and last cell included once
        bad = np.unique(np.concatenate([[0, len(arrays.h) - 1], rng.integers(0, len(arrays.h), 25)]))
        arrays = arrays.refined(bad)
    whole = timing._Arrays(limits, arrays.grid)  # the witness: every point and cell evaluated afresh
    assert np.all(np.diff(arrays.grid) > 0)
    np.testing.assert_array_equal(arrays.interval, whole.interval)
    for got, want in zip(arrays.pts, whole.pts):
        np.testing.assert_allclose(got, want, rtol=1e-9, atol=1e-12)
    for got, want in ((arrays.m1, whole.m1), (arrays.m2, whole.m2), (arrays.v_in, whole.v_in)):
        np.testing.assert_allclose(got, want, rtol=1e-9, atol=1e-12)
    # and so the same timing on it
    x, *_ = arrays.solve(arrays.xmax.copy(), 0)
    x_whole, *_ = whole.solve(whole.xmax.copy(), 0)
    np.testing.assert_allclose(x, x_whole, rtol=1e-9, atol=1e-12)


def _row_by_row(sols: np.ndarray, q_start: np.ndarray, revolute: np.ndarray) -> np.ndarray:
    """The definition: each row, shifted by whole turns on revolute joints, nearest the row before."""
    out = np.full(sols.shape, np.nan)
    prev = q_start
    for i, row in enumerate(sols):
        if np.isnan(row[0]):
            break
        turns = np.round((prev - row) / (2 * np.pi))
        out[i] = prev = np.where(revolute, row + 2 * np.pi * turns, row)
    return out


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 2**31 - 1), st.integers(1, 40), st.booleans())
def test_vectorised_unwrap_is_the_row_by_row_unwrap(seed: int, n: int, cut: bool) -> None:
    rng = np.random.default_rng(seed)
    solver = _Solver.__new__(_Solver)  # only the joint types matter here
    solver.revolute = np.array([True, True, True, True, True, False])
    # a smooth branch, wrapped into (-pi, pi] as a closed form returns it, linear axis untouched
    smooth = np.cumsum(rng.uniform(-0.4, 0.4, (n, 6)), axis=0) + rng.uniform(-9, 9, 6)
    sols = np.where(solver.revolute, np.angle(np.exp(1j * smooth)), smooth)
    if cut:
        sols[rng.integers(0, n):] = np.nan
    q_start = smooth[0] + rng.uniform(-0.3, 0.3, 6)
    got = solver._unwrap_chain(sols, q_start)
    want = _row_by_row(sols, q_start, solver.revolute)
    np.testing.assert_array_equal(np.isnan(got), np.isnan(want))
    ok = ~np.isnan(want[:, 0])
    np.testing.assert_allclose(got[ok], want[ok], rtol=0, atol=1e-9)
    # invariants: whole turns only, and the branch continues (steps below half a turn)
    turns = (got[ok] - sols[ok])[:, :5] / (2 * np.pi)
    np.testing.assert_allclose(turns, np.round(turns), atol=1e-9)
    steps = np.abs(np.diff(np.vstack([q_start, got[ok]]), axis=0))[:, :5]
    assert np.all(steps < np.pi)


def test_blend_crossing_lies_on_the_sphere_and_on_the_segment(irb120) -> None:  # type: ignore[no-untyped-def]
    robot, rng = irb120, np.random.default_rng(3)
    tool = np.eye(4)
    tool[:3, 3] = [0.0, 0.02, 0.1]
    for _ in range(20):
        qb = rng.uniform(-1.0, 1.0, 6)
        qa = qb + rng.uniform(-0.05, 0.05, 6)
        tcp = (robot.fk_batch(np.stack([qa, qb])) @ tool)[:, :3, 3]
        corner = tcp[1]
        r = 0.6 * float(np.linalg.norm(tcp[0] - corner))  # qa outside, qb (the corner) inside
        q = blend._crossing(robot, tool, qa, qb, corner, r)
        lam = (q - qa) @ (qb - qa) / ((qb - qa) @ (qb - qa))
        np.testing.assert_allclose(q, qa + lam * (qb - qa), atol=1e-12)  # on the segment
        assert 0.0 < lam <= 1.0
        p = (robot.fk_batch(q[None]) @ tool)[0, :3, 3]
        assert abs(np.linalg.norm(p - corner) - r) < 1e-7  # on the sphere (30 halvings of a short segment)
