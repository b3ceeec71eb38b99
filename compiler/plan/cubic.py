"""The not-a-knot cubic spline through points: the path q(s) and the TCP path the timing runs on.

The same spline, and the same evaluation, as `scipy.interpolate.CubicSpline(x, y)` (default
`bc_type="not-a-knot"`, extrapolating): built here on numpy alone because importing
scipy.interpolate costs ~0.45 s of CPU, a third of a small `rmot check`; scipy stays
the independent witness in tests/plan/test_cubic.py.

The construction follows the textbook (de Boor, "A Practical Guide to Splines", ch. IV) as
scipy does: the first derivatives s_i at the knots solve a tridiagonal system, interior rows
C2 continuity, end rows the not-a-knot condition (the third derivative is continuous across the
second and the second-to-last knot); 2 points give the straight line, 3 points the parabola.
The system is solved by the Thomas algorithm (elimination without pivoting; the interior rows
are strictly diagonally dominant and eliminating the first row leaves row 2's pivot at
dx0 + dx1 > 0, so no pivot vanishes): scipy's banded LU pivots, so the two agree to rounding,
not bit for bit (the test bounds the difference). The polynomial pieces and their evaluation
(interval search closed on the left, powers accumulated left to right, derivative factors as
scipy's PPoly applies them) are scipy's, operation for operation.
"""

from __future__ import annotations

import numpy as np

from rmot.lang.jit import Kernel

__all__ = ["CubicSpline"]

# Thomas elimination in the interpreter up to this much work (knots x columns) per process,
# compiled past it: +, -, *, / only, so both forms give the same floats (lang/jit.py)
_PY_WORK = 20_000


def _thomas(lower, diag, upper, rhs, out):  # type: ignore[no-untyped-def]
    """Solve the tridiagonal system row i: lower[i] x[i-1] + diag[i] x[i] + upper[i] x[i+1] =
    rhs[i] (lower[0], upper[n-1] unused) for every column of rhs (n, m); the solution is
    written into out (n, m) and returned (rows read and written as `row = a[i]; row[j]`: views
    compiled, lists interpreted, see lang/jit.py)."""
    n = len(diag)
    m = len(rhs[0])
    cp = [0.0] * n
    pivot = diag[0]
    cp[0] = upper[0] / pivot
    row, prev = rhs[0], out[0]
    for j in range(m):
        prev[j] = row[j] / pivot
    for i in range(1, n):
        li = lower[i]
        pivot = diag[i] - li * cp[i - 1]
        cp[i] = upper[i] / pivot
        row, cur = rhs[i], out[i]
        for j in range(m):
            cur[j] = (row[j] - li * prev[j]) / pivot
        prev = cur
    for i in range(n - 2, -1, -1):
        ci, cur = cp[i], out[i]
        for j in range(m):
            cur[j] = cur[j] - ci * prev[j]
        prev = cur
    return out


THOMAS = Kernel(_thomas, threshold=_PY_WORK, lists=True)


def _knot_slopes(x: np.ndarray, y: np.ndarray, dx: np.ndarray, slope: np.ndarray) -> np.ndarray:
    """First derivatives (n, m) at the knots of the not-a-knot spline (n >= 2 points)."""
    n = len(x)
    if n == 2:  # the straight line
        return np.vstack([slope[0], slope[0]])
    dxr = dx[:, None]
    if n == 3:  # the parabola: both not-a-knot rows say the third derivative is 0
        lower = np.array([0.0, dx[1], 1.0])
        diag = np.array([1.0, 2 * (dx[0] + dx[1]), 1.0])
        upper = np.array([1.0, dx[0], 0.0])
        rhs = np.vstack([2 * slope[0], 3 * (dxr[0] * slope[1] + dxr[1] * slope[0]),
                         2 * slope[1]])
    else:
        lower, diag, upper = np.zeros(n), np.zeros(n), np.zeros(n)
        diag[1:-1] = 2 * (dx[:-1] + dx[1:])
        upper[1:-1] = dx[:-1]
        lower[1:-1] = dx[1:]
        rhs = np.empty((n, y.shape[1]))
        rhs[1:-1] = 3 * (dxr[1:] * slope[:-1] + dxr[:-1] * slope[1:])
        d = x[2] - x[0]
        diag[0], upper[0] = dx[1], d
        rhs[0] = ((dxr[0] + 2 * d) * dxr[1] * slope[0] + dxr[0] ** 2 * slope[1]) / d
        d = x[-1] - x[-3]
        diag[-1], lower[-1] = dx[-2], d
        rhs[-1] = (dxr[-1] ** 2 * slope[-2] + (2 * d + dxr[-1]) * dxr[-2] * slope[-1]) / d
    out = np.zeros((n, y.shape[1]))
    return np.asarray(THOMAS(n * y.shape[1], lower, diag, upper, rhs, out), dtype=float)


class CubicSpline:
    """y(x) through points x (n,) strictly increasing, y (n,) or (n, m); `spline(s, nu)` the
    value (nu = 0) or the nu-th derivative at s (..., ), shaped (..., m) or (...), extrapolated
    by the end pieces; `derivative(nu)` the derivative as a spline of its own."""

    def __init__(self, x: np.ndarray, y: np.ndarray) -> None:
        x = np.asarray(x, dtype=float)
        y = np.asarray(y, dtype=float)
        if x.ndim != 1 or len(x) < 2 or len(y) != len(x) or y.ndim not in (1, 2):
            raise ValueError("a spline needs x (n,) and y (n, ...) with n >= 2")
        dx = np.diff(x)
        if not np.all(dx > 0):
            raise ValueError("x must be strictly increasing")
        self._vector = y.ndim == 2
        y2 = y if self._vector else y[:, None]
        dxr = dx[:, None]
        slope = np.diff(y2, axis=0) / dxr
        knot = _knot_slopes(x, y2, dx, slope)
        t = (knot[:-1] + knot[1:] - 2 * slope) / dxr
        c = np.empty((4, len(x) - 1, y2.shape[1]))
        c[0] = t / dxr
        c[1] = (slope - knot[:-1]) / dxr - t
        c[2] = knot[:-1]
        c[3] = y2[:-1]
        self.x, self.c = x, c

    @classmethod
    def _of(cls, x: np.ndarray, c: np.ndarray, vector: bool) -> CubicSpline:
        spline = cls.__new__(cls)
        spline.x, spline.c, spline._vector = x, c, vector
        return spline

    def derivative(self, nu: int = 1) -> CubicSpline:
        """The nu-th derivative as a piecewise polynomial of its own (scipy's PPoly.derivative:
        the top nu rows dropped, row k times the falling factorial of its power)."""
        if nu < 1 or nu >= len(self.c):
            raise ValueError(f"derivative order must be 1..{len(self.c) - 1} (got {nu})")
        c = self.c[:-nu].copy()
        powers = np.arange(len(c), 0, -1) + (nu - 1)  # the power each remaining row had
        factor = np.ones(len(c))
        for k in range(nu):
            factor = factor * (powers - k)
        c *= factor[:, None, None]
        return CubicSpline._of(self.x, c, self._vector)

    def __call__(self, s: np.ndarray | float, nu: int = 0) -> np.ndarray:
        s_arr = np.asarray(s, dtype=float)
        flat = s_arr.reshape(-1)
        x, c = self.x, self.c
        i = np.clip(np.searchsorted(x, flat, side="right") - 1, 0, len(x) - 2)
        t = (flat - x[i])[:, None]
        res = np.zeros((len(flat), c.shape[2]))
        z = np.ones_like(t)
        top = len(c) - 1
        for kp in range(len(c)):  # ascending powers, as scipy's evaluate_poly1
            if kp < nu:
                continue
            prefactor = 1.0
            for k in range(kp, kp - nu, -1):
                prefactor *= k
            term = c[top - kp][i] * z
            res = res + (term if nu == 0 else term * prefactor)
            if kp < top:
                z = z * t
        shape = s_arr.shape + ((c.shape[2],) if self._vector else ())
        return res.reshape(shape)
