"""Time-optimal path parametrisation on a dense grid (forward/backward passes, numba).

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

from typing import Any

import numpy as np

__all__ = ["Rows", "solve", "static_ceiling"]

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
    global _CEILING
    if _CEILING is None:
        _CEILING = _numba_ceiling()
    return _CEILING(np.ascontiguousarray(beta, dtype=float), np.ascontiguousarray(gamma, dtype=float))


def _numba_ceiling() -> Any:  # a numba dispatcher (numba is untyped)
    import numba

    @numba.njit(cache=True)
    def ceiling(beta, gamma):  # type: ignore[no-untyped-def]
        k, m = beta.shape
        out = np.full(k, np.inf)
        for i in range(k):
            best = np.inf
            for j in range(m):
                if gamma[i, j] == np.inf:
                    continue
                for q in range(m):
                    if gamma[i, q] == np.inf:
                        continue
                    diff = beta[i, q] - beta[i, j]
                    if diff > 1e-12:
                        lim = (gamma[i, j] + gamma[i, q]) / diff
                        if lim < best:
                            best = lim
            out[i] = best
        return out

    return ceiling


_CEILING = None


def _numba() -> Any:  # a numba dispatcher (numba is untyped)
    import numba

    @numba.njit(cache=True)
    def passes(ss, xmax, beta, gamma):  # type: ignore[no-untyped-def]
        k = len(ss)
        m = beta.shape[1]
        back = np.empty(k)
        back[k - 1] = 0.0
        for i in range(k - 2, -1, -1):
            d = 2.0 * (ss[i + 1] - ss[i])
            c = back[i + 1]
            x = xmax[i]
            for j in range(m):
                g = gamma[i, j]
                if g == np.inf:
                    continue
                coef = 1.0 - d * beta[i, j]
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
            for j in range(m):
                g = gamma[i, j]
                if g == np.inf:
                    continue
                u = g - beta[i, j] * x
                if u < umax:
                    umax = u
            nxt = back[i + 1] if umax == np.inf else min(back[i + 1], x + d * umax)
            out[i + 1] = max(nxt, 0.0)
        return out

    return passes


_PASSES = None


def solve(ss: np.ndarray, xmax: np.ndarray, rows: Rows | tuple[np.ndarray, np.ndarray, np.ndarray]) -> np.ndarray:
    """(K,) x = (ds/dt)^2 at the grid points, rest to rest, time-optimal for the grid.
    rows: the Rows, or their `normalised()` form (computed once for repeated solves)."""
    global _PASSES
    if _PASSES is None:
        _PASSES = _numba()
    beta, gamma, ceiling = rows.normalised() if isinstance(rows, Rows) else rows
    top = np.minimum(xmax, ceiling)
    top = np.where(np.isfinite(top), top, 1e18)
    return _PASSES(np.ascontiguousarray(ss, dtype=float), np.ascontiguousarray(top),
                   np.ascontiguousarray(beta), np.ascontiguousarray(gamma))


def _numba_check() -> Any:  # a numba dispatcher (numba is untyped)
    import numba

    @numba.njit(cache=True)
    def check(x, h, d1, d2, m1, m2, vel_in, thetas, c):  # type: ignore[no-untyped-def]
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

    return check


_CHECK = None


def check(x: np.ndarray, h: np.ndarray, d1: np.ndarray, d2: np.ndarray, m1: np.ndarray, m2: np.ndarray,
          vel_in: np.ndarray, thetas: tuple[float, ...], c: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per cell: the largest joint acceleration ratio (at the cell's end and at the fractions
    `thetas` inside it, the cell's constant path acceleration) and the largest speed ratio
    inside it. m1, m2 (T, K-1, n) the path's derivatives inside the cells, vel_in (T, K-1),
    c (n,) the joint acceleration limits."""
    global _CHECK
    if _CHECK is None:
        _CHECK = _numba_check()
    return _CHECK(x, h, d1, d2, m1, m2, vel_in, np.asarray(thetas, dtype=float), np.ascontiguousarray(c, dtype=float))
