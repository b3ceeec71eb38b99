"""Time-optimal path parametrisation on a dense grid (forward/backward passes; numba when large).

A path q(s), s in [0, L], is timed by x(s) = (ds/dt)^2 on a grid s_0 < ... < s_K with a
constant path acceleration u_i = (x_{i+1} - x_i) / (2 (s_{i+1} - s_i)) on each cell (what
`timing.ConstAccelTiming` evaluates). Every limit is one of two kinds:

* a velocity ceiling x_i <= xmax_i (joint speed: (v_j / |q'_j|)^2; TCP speed: (v / |p'|)^2);
* an acceleration row |a u + b x| <= c, linear in (u, x): a joint's acceleration
  q'_j u + q''_j x, the TCP's path acceleration l' u + l'' x (l = TCP arc length).

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

import numpy as np

from rmot.compiler.jit import Kernel

__all__ = ["CEILING", "CHECK", "PASSES", "Rows", "check", "solve", "static_ceiling"]

_TINY = 1e-12


class Rows:
    """Acceleration rows |a u + b x| <= c at K grid points, m rows each: arrays (K, m)."""

    def __init__(self, a: np.ndarray, b: np.ndarray, c: np.ndarray) -> None:
        self.a, self.b, self.c = a, b, c

    def normalised(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(beta, gamma, ceiling): row j as u + beta_j x in [-gamma_j, gamma_j] (gamma = inf for
        rows without a u term), and the ceiling on x those rows alone impose (K,)."""
        a, b, c = self.a, self.b, self.c
        has_u = np.abs(a) > _TINY
        safe = np.where(has_u, a, 1.0)
        beta = np.where(has_u, b / safe, 0.0)
        gamma = np.where(has_u, c / np.abs(safe), np.inf)
        # rows with no u term: |b| x <= c
        pure = np.where(has_u, np.inf, c / np.maximum(np.abs(b), _TINY))
        ceiling = np.minimum(static_ceiling(beta, gamma), np.min(pure, axis=1, initial=np.inf))
        return beta, gamma, ceiling


def static_ceiling(beta: np.ndarray, gamma: np.ndarray) -> np.ndarray:
    """(K,) the largest x at which some u satisfies every row u + beta_j x in [-gamma_j,
    gamma_j]: for each pair j, k with beta_k > beta_j, x <= (gamma_j + gamma_k) / (beta_k - beta_j)."""
    beta = np.ascontiguousarray(beta, dtype=float)
    gamma = np.ascontiguousarray(gamma, dtype=float)
    out: np.ndarray = CEILING(beta.size * beta.shape[-1], beta, gamma)
    return out


# The kernels below run as plain Python on small grids and compiled by numba on large ones
# (compiler/jit.py: one function body either way). Thresholds: the work (grid points x rows,
# times rows again for the pairwise ceiling) at which the compiled form's one-time cost per
# process (~0.6 s: importing numba, loading its cache) is about what the interpreter would take.
_PY_WORK = 250_000


def _ceiling(beta, gamma):  # type: ignore[no-untyped-def]
    k, m = len(beta), len(beta[0])
    out = np.full(k, np.inf)
    for i in range(k):
        b_i, g_i = beta[i], gamma[i]  # rows: views in numba, lists in the interpreter
        best = np.inf
        for j in range(m):
            if g_i[j] == np.inf:
                continue
            for q in range(m):
                if g_i[q] == np.inf:
                    continue
                diff = b_i[q] - b_i[j]
                if diff > 1e-12:
                    lim = (g_i[j] + g_i[q]) / diff
                    if lim < best:
                        best = lim
        out[i] = best
    return out


def _passes(ss, xmax, beta, gamma):  # type: ignore[no-untyped-def]
    k = len(ss)
    m = len(beta[0])
    back = np.empty(k)
    back[k - 1] = 0.0
    for i in range(k - 2, -1, -1):
        d = 2.0 * (ss[i + 1] - ss[i])
        c = back[i + 1]
        x = xmax[i]
        b_i, g_i = beta[i], gamma[i]
        for j in range(m):
            g = g_i[j]
            if g == np.inf:
                continue
            coef = 1.0 - d * b_i[j]
            if coef > 0.0:
                lim = (c + d * g) / coef
                if lim < x:
                    x = lim
        back[i] = max(x, 0.0)
    out = np.empty(k)
    out[0] = 0.0
    for i in range(k - 1):
        d = 2.0 * (ss[i + 1] - ss[i])
        x = out[i]
        umax = np.inf
        b_i, g_i = beta[i], gamma[i]
        for j in range(m):
            g = g_i[j]
            if g == np.inf:
                continue
            u = g - b_i[j] * x
            if u < umax:
                umax = u
        nxt = back[i + 1] if umax == np.inf else min(back[i + 1], x + d * umax)
        out[i + 1] = max(nxt, 0.0)
    return out


def _check(x, h, d1, d2, m1, m2, vel_in, thetas, c):  # type: ignore[no-untyped-def]
    k, n = d1.shape[0] - 1, d1.shape[1]
    r_acc = np.zeros(k)
    r_vel = np.zeros(k)
    for i in range(k):
        u = (x[i + 1] - x[i]) / (2.0 * h[i])
        worst = 0.0
        for j in range(n):
            r = abs(d1[i + 1, j] * u + d2[i + 1, j] * x[i + 1]) / c[j]
            if r > worst:
                worst = r
        vw = 0.0
        for t in range(len(thetas)):
            xt = x[i] + thetas[t] * (x[i + 1] - x[i])
            for j in range(n):
                r = abs(m1[t, i, j] * u + m2[t, i, j] * xt) / c[j]
                if r > worst:
                    worst = r
            v = vel_in[t, i] * np.sqrt(max(xt, 0.0))
            if v > vw:
                vw = v
        r_acc[i] = worst
        r_vel[i] = vw
    return r_acc, r_vel


CEILING = Kernel(_ceiling, threshold=2 * _PY_WORK, lists=True)
PASSES = Kernel(_passes, threshold=2 * _PY_WORK, lists=True)
CHECK = Kernel(_check, threshold=_PY_WORK)


def solve(ss: np.ndarray, xmax: np.ndarray, rows: Rows | tuple[np.ndarray, np.ndarray, np.ndarray]) -> np.ndarray:
    """(K,) x = (ds/dt)^2 at the grid points, rest to rest, time-optimal for the grid.
    rows: the Rows, or their `normalised()` form (computed once for repeated solves)."""
    beta, gamma, ceiling = rows.normalised() if isinstance(rows, Rows) else rows
    top = np.minimum(xmax, ceiling)
    top = np.where(np.isfinite(top), top, 1e18)
    beta = np.ascontiguousarray(beta)
    out: np.ndarray = PASSES(beta.size * 2, np.ascontiguousarray(ss, dtype=float),
                             np.ascontiguousarray(top), beta, np.ascontiguousarray(gamma))
    return out


def check(x, h, d1, d2, m1, m2, vel_in, thetas, c):  # type: ignore[no-untyped-def]
    """Per cell: the largest joint acceleration ratio (at the cell's end and at the fractions
    `thetas` inside it, the cell's constant path acceleration) and the largest speed ratio
    inside it. m1, m2 (T, K-1, n) the path's derivatives inside the cells, vel_in (T, K-1),
    c (n,) the joint acceleration limits."""
    thetas = np.asarray(thetas, dtype=float)
    return CHECK(d1.size * (1 + len(thetas)), x, h, d1, d2, m1, m2, vel_in, thetas,
                 np.ascontiguousarray(c, dtype=float))
