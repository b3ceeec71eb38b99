"""The timing's not-a-knot spline (compiler/plan/cubic.py) against three independent witnesses:
scipy's CubicSpline (the spline it replaces), the same linear system solved in exact rational
arithmetic, and the spline's defining properties (it interpolates, is C2, reproduces cubics,
and its third derivative is continuous across the second and second-to-last knot)."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.interpolate import CubicSpline as ScipySpline

from rmot.compiler.plan.cubic import THOMAS, CubicSpline


@st.composite
def knots(draw: st.DrawFn) -> tuple[np.ndarray, np.ndarray]:
    """x strictly increasing with neighbouring steps up to 1000x apart, y (n, m)."""
    n = draw(st.integers(2, 40))
    m = draw(st.integers(1, 7))
    seed = draw(st.integers(0, 2**32 - 1))
    rng = np.random.default_rng(seed)
    steps = 10 ** rng.uniform(-3, 0, n - 1) * draw(st.floats(0.01, 100))
    x = np.concatenate([[draw(st.floats(-10, 10))], steps]).cumsum()
    return x, rng.normal(scale=draw(st.floats(0.01, 100)), size=(n, m))


def _tolerance(x: np.ndarray, values: np.ndarray) -> float:
    """Both solve the same system in floating point, scipy with pivoting, this one without: they
    agree to a few ulps times its conditioning, which grows with the ratio of the steps."""
    h = np.diff(x)
    return 1e-11 * float(h.max() / h.min()) * max(1.0, float(np.abs(values).max()))


@settings(max_examples=150, deadline=None)
@given(knots(), st.integers(0, 2**32 - 1))
def test_agrees_with_scipy(data: tuple[np.ndarray, np.ndarray], seed: int) -> None:
    x, y = data
    ours, theirs = CubicSpline(x, y), ScipySpline(x, y)
    span = x[-1] - x[0]
    s = np.concatenate([x, np.random.default_rng(seed).uniform(x[0] - 0.1 * span,
                                                               x[-1] + 0.1 * span, 40)])
    for nu in (0, 1, 2):
        want = theirs(s, nu)
        assert ours(s, nu).shape == want.shape
        np.testing.assert_allclose(ours(s, nu), want, rtol=0, atol=_tolerance(x, want))
        if nu:
            np.testing.assert_allclose(ours.derivative(nu)(s), theirs.derivative(nu)(s),
                                       rtol=0, atol=_tolerance(x, want))


def test_one_column_gives_scalars_like_scipy() -> None:
    x = np.array([0.0, 0.5, 1.5, 2.0, 3.0])
    y = np.sin(x)
    ours, theirs = CubicSpline(x, y), ScipySpline(x, y)
    np.testing.assert_allclose(ours(0.7), theirs(0.7), atol=1e-14)
    assert np.shape(ours(0.7)) == np.shape(theirs(0.7)) == ()
    assert ours(np.array([[0.1, 0.2]])).shape == (1, 2)


def _exact_knot_slopes(x: np.ndarray, y: np.ndarray) -> list[Fraction]:
    """The knot derivatives of the not-a-knot spline, solved exactly (Gauss-Jordan over the
    rationals) from the conditions themselves: C2 at interior knots, the third derivative
    continuous at x1 and x(n-2) (for 3 points: one parabola)."""
    n = len(x)
    xs, ys = [Fraction(v) for v in x], [Fraction(v) for v in y]
    h = [xs[i + 1] - xs[i] for i in range(n - 1)]
    d = [(ys[i + 1] - ys[i]) / h[i] for i in range(n - 1)]
    rows = [[Fraction(0)] * (n + 1) for _ in range(n)]
    for i in range(1, n - 1):  # second derivative continuous at x_i
        rows[i][i - 1], rows[i][i], rows[i][i + 1] = 1 / h[i - 1], 2 / h[i - 1] + 2 / h[i], 1 / h[i]
        rows[i][n] = 3 * d[i - 1] / h[i - 1] + 3 * d[i] / h[i]
    for end, (a, b, c) in ((0, (0, 1, 2)), (n - 1, (n - 3, n - 2, n - 1))):
        if n == 3:  # third derivative of both pieces zero: (k_a + k_b - 2 d) / h^2 = 0
            k = 0 if end == 0 else 1
            rows[end][a + k], rows[end][b + k], rows[end][n] = Fraction(1), Fraction(1), 2 * d[k]
            continue
        # third derivative of piece [a, b] equals that of [b, c]:
        # (k_a + k_b - 2 d_ab) / h_ab^2 = (k_b + k_c - 2 d_bc) / h_bc^2
        hab, hbc = h[a], h[b]
        rows[end][a], rows[end][b], rows[end][c] = (1 / hab**2, 1 / hab**2 - 1 / hbc**2,
                                                    -1 / hbc**2)
        rows[end][n] = 2 * d[a] / hab**2 - 2 * d[b] / hbc**2
    for col in range(n):
        pivot = next(r for r in range(col, n) if rows[r][col] != 0)
        rows[col], rows[pivot] = rows[pivot], rows[col]
        for r in range(n):
            if r != col and rows[r][col] != 0:
                f = rows[r][col] / rows[col][col]
                rows[r] = [u - f * v for u, v in zip(rows[r], rows[col], strict=True)]
    return [rows[i][n] / rows[i][i] for i in range(n)]


@settings(max_examples=40, deadline=None)
@given(st.integers(3, 12), st.integers(0, 2**32 - 1))
def test_knot_derivatives_match_the_exact_solution(n: int, seed: int) -> None:
    rng = np.random.default_rng(seed)
    x = np.cumsum(rng.uniform(0.05, 1.0, n))
    y = rng.normal(size=n)
    exact = np.array([float(k) for k in _exact_knot_slopes(x, y)])
    spline = CubicSpline(x, y)
    got = np.append(spline(x[:-1], 1), spline(x[-1], 1))
    np.testing.assert_allclose(got, exact, rtol=0, atol=1e-12 * np.abs(exact).max() + 1e-300)


@settings(max_examples=60, deadline=None)
@given(knots())
def test_defining_properties(data: tuple[np.ndarray, np.ndarray]) -> None:
    x, y = data
    spline = CubicSpline(x, y)
    tol = _tolerance(x, y) * 10
    np.testing.assert_allclose(spline(x), y, rtol=0, atol=tol)  # interpolates
    if len(x) < 4:
        return
    inner = x[1:-1]
    # C2 at interior knots: the left piece evaluated at its right end equals the right piece
    c, h = spline.c, np.diff(x)[:, None]
    for nu, left in ((1, 3 * c[0] * h**2 + 2 * c[1] * h + c[2]), (2, 6 * c[0] * h + 2 * c[1])):
        right = spline(inner, nu)
        scale = max(1.0, float(np.abs(right).max()))
        np.testing.assert_allclose(left[:-1], right, rtol=0, atol=1e-6 * scale)
    # not a knot: one cubic across x1 and across x(n-2)
    third = 6 * c[0]
    scale = max(1.0, float(np.abs(third).max()))
    np.testing.assert_allclose(third[0], third[1], rtol=0, atol=1e-6 * scale)
    np.testing.assert_allclose(third[-2], third[-1], rtol=0, atol=1e-6 * scale)


@pytest.mark.parametrize("n", [2, 3, 4, 9])
def test_reproduces_polynomials_it_can_hold(n: int) -> None:
    """2 points: a line; 3 points: a parabola; 4 or more: any cubic (not-a-knot ends)."""
    x = np.array([0.0, 0.3, 1.0, 1.7, 2.0, 2.4, 3.1, 3.3, 4.0])[:n]
    degree = min(n - 1, 3)
    coef = [0.7, -1.3, 0.4, 0.25][: degree + 1]
    poly = np.polynomial.Polynomial(coef)
    spline = CubicSpline(x, poly(x))
    s = np.linspace(-0.5, x[-1] + 0.5, 37)
    for nu in (0, 1, 2):
        np.testing.assert_allclose(spline(s, nu), poly.deriv(nu)(s), rtol=0, atol=1e-12)


def test_compiled_and_interpreted_elimination_give_the_same_floats() -> None:
    rng = np.random.default_rng(7)
    n, m = 50, 6
    lower, upper = rng.uniform(0.1, 1, n), rng.uniform(0.1, 1, n)
    diag = 2 * (lower + upper) + rng.uniform(0, 1, n)
    rhs = rng.normal(size=(n, m))
    interpreted = np.asarray(THOMAS.py(lower.tolist(), diag.tolist(), upper.tolist(),
                                       rhs.tolist(), np.zeros((n, m)).tolist()))
    compiled = THOMAS.jit()(lower, diag, upper, rhs, np.zeros((n, m)))
    assert np.array_equal(interpreted, compiled)
    dense = np.diag(diag) + np.diag(lower[1:], -1) + np.diag(upper[:-1], 1)
    np.testing.assert_allclose(interpreted, np.linalg.solve(dense, rhs), rtol=0, atol=1e-12)


@pytest.mark.parametrize("x", [[0.0], [0.0, 0.0, 1.0], [0.0, 2.0, 1.0], [[0.0, 1.0]]])
def test_refuses_knots_that_make_no_spline(x: list[float]) -> None:
    with pytest.raises(ValueError):
        CubicSpline(np.array(x), np.zeros(np.shape(x)[-1]))
