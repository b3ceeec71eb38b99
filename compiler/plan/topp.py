"""Time-optimal path parametrisation on a dense grid (forward/backward passes).

A path q(s), s in [0, L], is timed by x(s) = (ds/dt)^2 on a grid s_0 < ... < s_K with a
constant path acceleration u_i = (x_{i+1} - x_i) / (2 (s_{i+1} - s_i)) on each cell (what
`timing.ConstAccelTiming` evaluates). Every limit is one of two kinds:

* a velocity ceiling x_i <= xmax_i (joint speed: (v_j / |q'_j|)^2; TCP speed: (v / |p'|)^2);
* an acceleration row |a u + b x| <= c, linear in (u, x): a joint's acceleration
  q'_j u + q''_j x, the TCP's path acceleration l' u + l'' x (l = TCP arc length);
* a one-sided pair lo <= a u + b x <= hi (`Rows.lower`): a joint torque a_j u + b_j x + g_j
  within +-tau_max, i.e. lo = -tau_max - g_j, hi = tau_max - g_j (gravity g makes it lopsided).
In the solver's form every row is u + beta x in [lo, hi]; a symmetric row has lo = -hi, and
is computed exactly as before one-sided rows existed (the same floating-point operations).

Rows are held at the start of each cell (collocation, as toppra does). The passes are the
classical ones: backward, the largest x_i from which the robot can still brake to the
backward bound of s_{i+1}; forward, full acceleration up to that bound. Both are O(K) and
the result is the time-optimal timing of the discretised problem; on a grid as dense as the
path's own waypoints it is within a fraction of a percent of the continuous optimum.
Between grid points (at the end and the middle of every cell) the limits are re-checked
afterwards (`timing.path_piece`), and only where one is exceeded are that spot's limits
tightened and the passes re-run: a repair slows that spot, never the whole path.
"""

from __future__ import annotations

import math

import numpy as np

from rmot.lang.jit import Kernel

__all__ = ["CEILING", "CHECK", "CHECK_TORQUE", "PASSES", "Rows", "check", "check_torque", "solve",
           "static_ceiling"]

_TINY = 1e-12


class Rows:
    """Acceleration rows at K grid points, m rows each: arrays (K, m). Symmetric rows
    |a u + b x| <= c, or, with `lower`, lower <= a u + b x <= c (c is then the upper bound)."""

    def __init__(self, a: np.ndarray, b: np.ndarray, c: np.ndarray,
                 lower: np.ndarray | None = None) -> None:
        self.a, self.b, self.c, self.lower = a, b, c, lower

    def normalised(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """(beta, lo, hi, ceiling): row j as u + beta_j x in [lo_j, hi_j] (lo = -inf, hi = inf for
        rows without a u term), and the ceiling on x those rows alone impose (K,)."""
        beta, lo, hi, pure = self.parts()
        ceiling = np.minimum(static_ceiling(beta, lo, hi), np.min(pure, axis=1, initial=np.inf))
        return beta, lo, hi, ceiling

    def parts(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """(beta, lo, hi, pure): the solver's form and, per row, the ceiling on x of a row with no
        u term (inf for the others); the static ceiling over pairs of rows is not included."""
        a, b, c = self.a, self.b, self.c
        has_u = np.abs(a) > _TINY
        safe = np.where(has_u, a, 1.0)
        beta = np.where(has_u, b / safe, 0.0)
        if self.lower is None:
            gamma = np.where(has_u, c / np.abs(safe), np.inf)
            # rows with no u term: |b| x <= c
            pure = np.where(has_u, np.inf, c / np.maximum(np.abs(b), _TINY))
            return beta, -gamma, gamma, pure
        lower = self.lower
        up, down = c / safe, lower / safe  # divided by a < 0 the bounds swap
        lo = np.where(has_u, np.where(a > 0, down, up), -np.inf)
        hi = np.where(has_u, np.where(a > 0, up, down), np.inf)
        # rows with no u term: lower <= b x <= c (a speed floor, lower > 0 with b > 0, is not
        # representable and is left out; lower > 0 with b ~ 0 cannot hold at all: ceiling 0)
        with np.errstate(divide="ignore", invalid="ignore"):
            bound = np.where(b > _TINY, c / np.where(b > _TINY, b, 1.0),
                             np.where(b < -_TINY, lower / np.where(b < -_TINY, b, -1.0),
                                      np.where((lower <= 0) & (c >= 0), np.inf, 0.0)))
        pure = np.where(has_u, np.inf, np.maximum(bound, 0.0))
        return beta, lo, hi, pure


def static_ceiling(beta: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """(K,) the largest x at which some u satisfies every row u + beta_j x in [lo_j, hi_j]:
    for each pair j, k with beta_k > beta_j, x <= (hi_k - lo_j) / (beta_k - beta_j); 0 where a
    row's own interval is empty (lo_j > hi_j: gravity alone exceeds a torque limit)."""
    beta = np.ascontiguousarray(beta, dtype=float)
    out: np.ndarray = CEILING(beta.size * beta.shape[-1], beta, np.ascontiguousarray(lo, dtype=float),
                              np.ascontiguousarray(hi, dtype=float))
    return out


# The kernels below run as plain Python on small grids and compiled by numba on large ones
# (lang/jit.py: one function body either way). Thresholds: the work (grid points x rows,
# times rows again for the pairwise ceiling) at which the compiled form's one-time cost per
# process (~0.6 s: importing numba, loading its cache) is about what the interpreter would take.
# A symmetric row (lo = -hi) goes through the same floating-point operations as before
# one-sided rows existed: c - d*lo == c + d*gamma, hi_q - lo_j == gamma_q + gamma_j.
_PY_WORK = 250_000


def _ceiling(beta, lo, hi):  # type: ignore[no-untyped-def]
    k, m = len(beta), len(beta[0])
    out = np.full(k, np.inf)
    for i in range(k):
        b_i, l_i, h_i = beta[i], lo[i], hi[i]  # rows: views in numba, lists in the interpreter
        best = np.inf
        for j in range(m):
            if h_i[j] == np.inf:
                continue
            if l_i[j] > h_i[j]:
                best = 0.0
            for q in range(m):
                if h_i[q] == np.inf:
                    continue
                diff = b_i[q] - b_i[j]
                if diff > 1e-12:
                    lim = (h_i[q] - l_i[j]) / diff
                    if lim < best:
                        best = lim
        out[i] = best
    return out


def _passes(ss, xmax, beta, lo, hi):  # type: ignore[no-untyped-def]
    k = len(ss)
    m = len(beta[0])
    back = np.empty(k)
    back[k - 1] = 0.0
    for i in range(k - 2, -1, -1):
        d = 2.0 * (ss[i + 1] - ss[i])
        c = back[i + 1]
        x = xmax[i]
        b_i, l_i, h_i = beta[i], lo[i], hi[i]
        for j in range(m):
            if h_i[j] == np.inf:
                continue
            coef = 1.0 - d * b_i[j]
            if coef > 0.0:
                lim = (c - d * l_i[j]) / coef
                if lim < x:
                    x = lim
        back[i] = max(x, 0.0)
    out = np.empty(k)
    out[0] = 0.0
    for i in range(k - 1):
        d = 2.0 * (ss[i + 1] - ss[i])
        x = out[i]
        umax = np.inf
        b_i, h_i = beta[i], hi[i]
        for j in range(m):
            g = h_i[j]
            if g == np.inf:
                continue
            u = g - b_i[j] * x
            if u < umax:
                umax = u
        nxt = back[i + 1] if umax == np.inf else min(back[i + 1], x + d * umax)
        out[i + 1] = max(nxt, 0.0)
    return out


def _check(x, h, d1, d2, m1, m2, vel_in, thetas, c):  # type: ignore[no-untyped-def]
    k, n = len(d1) - 1, len(d1[0])
    r_acc = np.zeros(k)
    r_vel = np.zeros(k)
    for i in range(k):
        x0, x1 = x[i], x[i + 1]
        u = (x1 - x0) / (2.0 * h[i])
        worst = 0.0
        d1_end, d2_end = d1[i + 1], d2[i + 1]
        for j in range(n):
            r = abs(d1_end[j] * u + d2_end[j] * x1) / c[j]
            if r > worst:
                worst = r
        vw = 0.0
        for t in range(len(thetas)):
            xt = x0 + thetas[t] * (x1 - x0)
            m1_in, m2_in = m1[t][i], m2[t][i]
            for j in range(n):
                r = abs(m1_in[j] * u + m2_in[j] * xt) / c[j]
                if r > worst:
                    worst = r
            v = vel_in[t][i] * math.sqrt(max(xt, 0.0))
            if v > vw:
                vw = v
        r_acc[i] = worst
        r_vel[i] = vw
    return r_acc, r_vel


def _check_torque(x, h, ta, tb, tc, thetas, limit):  # type: ignore[no-untyped-def]
    k, n = len(h), ta.shape[2]
    out = np.zeros(k)
    for i in range(k):
        u = (x[i + 1] - x[i]) / (2.0 * h[i])
        worst = 0.0
        for t in range(len(thetas)):
            xt = x[i] + thetas[t] * (x[i + 1] - x[i])
            for j in range(n):
                dyn = ta[t, i, j] * u + tb[t, i, j] * xt
                tau = dyn + tc[t, i, j]
                if abs(tau) <= limit[j]:
                    w = abs(tau) / limit[j]
                else:
                    room = (limit[j] if tau > 0 else -limit[j]) - tc[t, i, j]
                    w = dyn / room if dyn * room > 0.0 else np.inf
                worst = max(worst, w)
        out[i] = worst
    return out


CEILING = Kernel(_ceiling, threshold=2 * _PY_WORK, lists=True)
PASSES = Kernel(_passes, threshold=2 * _PY_WORK, lists=True)
CHECK = Kernel(_check, threshold=_PY_WORK, lists=True)
CHECK_TORQUE = Kernel(_check_torque, threshold=_PY_WORK)


def solve(ss: np.ndarray, xmax: np.ndarray,
          rows: Rows | tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]) -> np.ndarray:
    """(K,) x = (ds/dt)^2 at the grid points, rest to rest, time-optimal for the grid.
    rows: the Rows, or their `normalised()` form (computed once for repeated solves)."""
    beta, lo, hi, ceiling = rows.normalised() if isinstance(rows, Rows) else rows
    top = np.minimum(xmax, ceiling)
    top = np.where(np.isfinite(top), top, 1e18)
    beta = np.ascontiguousarray(beta)
    out: np.ndarray = PASSES(beta.size * 2, np.ascontiguousarray(ss, dtype=float),
                             np.ascontiguousarray(top), beta, np.ascontiguousarray(lo),
                             np.ascontiguousarray(hi))
    return out


def check(x: np.ndarray, h: np.ndarray, d1: np.ndarray, d2: np.ndarray, m1: np.ndarray, m2: np.ndarray,
          vel_in: np.ndarray, thetas: tuple[float, ...], c: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per cell: the largest joint acceleration ratio (at the cell's end and at the fractions
    `thetas` inside it, the cell's constant path acceleration) and the largest speed ratio
    inside it. m1, m2 (T, K-1, n) the path's derivatives inside the cells, vel_in (T, K-1),
    c (n,) the joint acceleration limits."""
    fractions = np.asarray(thetas, dtype=float)
    return CHECK(d1.size * (1 + len(fractions)), x, h, d1, d2, m1, m2, vel_in, fractions,
                 np.ascontiguousarray(c, dtype=float))


def check_torque(x: np.ndarray, h: np.ndarray, ta: np.ndarray, tb: np.ndarray, tc: np.ndarray,
                 thetas: tuple[float, ...], limit: np.ndarray) -> np.ndarray:
    """Per cell (K-1,): the joint torques a u + b x + c (ta, tb, tc: (T, K-1, n) at the fractions
    `thetas` of each cell, u the cell's constant path acceleration) against `limit` (n,): where
    every |tau| is within its limit, the largest |tau| / limit (<= 1); where one is not, the
    factor w > 1 that u and x must shrink by (a local time stretch by sqrt(w)) for it to hold
    (inf where gravity alone exceeds the limit)."""
    ta = np.ascontiguousarray(ta)
    arrays = (np.ascontiguousarray(x, dtype=float), np.ascontiguousarray(h, dtype=float),
              ta, np.ascontiguousarray(tb), np.ascontiguousarray(tc),
              np.asarray(thetas, dtype=float), np.ascontiguousarray(limit, dtype=float))
    return np.asarray(CHECK_TORQUE(ta.size, *arrays))
