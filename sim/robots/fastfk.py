# mypy: disable-error-code="no-untyped-call"
# (numba kernels: untyped on purpose, numba types them; they call each other by plain name)
"""FK as a screening check for the compiled IK passes (fastsolve, fastbatch): how far FK of
each of a pose's branches lies from the pose, all branches at once in loops the compiler
vectorises, with a polynomial sine and cosine.

The passes accept a branch only when this error is below HALF the tolerance (1e-9) and hand
everything between half and a clear miss to the numpy/pinocchio path, which decides with its
own FK. So this FK needs to be accurate to well under 5e-10, not to the last bit: `_sincos`
is fdlibm's kernel polynomials (k_sin.c / k_cos.c, Sun Microsystems 1993, the minimax
coefficients of sin and cos on [-π/4, π/4]) after a two-constant Cody-Waite reduction by π/2
(e_rem_pio2.c's PIO2_1 / PIO2_1T). tests/robots/test_ik_fast_path.py measures it against
math.sin / math.cos (below 4e-16 on |x| <= 40). Measured: 84 ns per configuration of a 6R
arm against 240 ns for the same products one configuration at a time with libm's sin and cos.
"""

from __future__ import annotations

import math

from rmot.lang.jit import Kernel

__all__ = ["FK_COLUMNS", "FK_ERROR_ROWS", "SINCOS"]

_TWO_OVER_PI = 6.36619772367581382433e-01
_PIO2_1 = 1.57079632673412561417e+00  # the first 33 bits of π/2: k·PIO2_1 is exact for |k| < 2^20
_PIO2_1T = 6.07710050650619224932e-11  # π/2 - PIO2_1
_S1, _S2, _S3 = -1.66666666666666324348e-01, 8.33333333332248946124e-03, -1.98412698298579493134e-04
_S4, _S5, _S6 = 2.75573137070700676789e-06, -2.50507602534068634195e-08, 1.58969099521155010221e-10
_C1, _C2, _C3 = 4.16666666666666019037e-02, -1.38888888888741095749e-03, 2.48015872894767294178e-05
_C4, _C5, _C6 = -2.75573143513906633035e-07, 2.08757232129817482790e-09, -1.13596475577881948265e-11


def _sincos(x):  # type: ignore[no-untyped-def]
    """(sin x, cos x) to ~1e-16 for |x| up to a few hundred (joint angles)."""
    k = math.floor(x * _TWO_OVER_PI + 0.5)
    r = (x - k * _PIO2_1) - k * _PIO2_1T
    z = r * r
    s = r + r * z * (_S1 + z * (_S2 + z * (_S3 + z * (_S4 + z * (_S5 + z * _S6)))))
    c = 1.0 - 0.5 * z + z * z * (_C1 + z * (_C2 + z * (_C3 + z * (_C4 + z * (_C5 + z * _C6)))))
    quadrant = int(k) & 3
    if quadrant == 0:
        return s, c
    if quadrant == 1:
        return c, -s
    if quadrant == 2:
        return -s, -c
    return -c, s


def _fk_columns(placements, axes, prismatic, flange, qm, t):  # type: ignore[no-untyped-def]
    """FK of R configurations: qm (n, R) model values (one column each) -> t[:12] the flange
    poses' top three rows (entry 4·row + col), t (14, R). Each step is a loop over the R
    columns without branches, which the compiler vectorises (SIMD); the sine and cosine are
    `_sincos`'s with its quadrant chosen by selects.

    Long on purpose: the product of the joints' transforms written out entry by entry, one
    loop over the columns per entry, so the compiler vectorises each; calls between them
    would break those loops."""
    n, count = qm.shape
    for k in range(12):
        v = 1.0 if k == 0 or k == 5 or k == 10 else 0.0
        for r in range(count):
            t[k, r] = v
    for i in range(n + 1):
        if i < n:
            p = placements[i]
        else:
            p = flange
        p00, p01, p02, p03 = p[0, 0], p[0, 1], p[0, 2], p[0, 3]
        p10, p11, p12, p13 = p[1, 0], p[1, 1], p[1, 2], p[1, 3]
        p20, p21, p22, p23 = p[2, 0], p[2, 1], p[2, 2], p[2, 3]
        for row in range(3):  # t rows: entries 4·row .. 4·row + 3
            a, b, c, d = t[4 * row], t[4 * row + 1], t[4 * row + 2], t[4 * row + 3]
            for r in range(count):
                x0, x1, x2, x3 = a[r], b[r], c[r], d[r]
                a[r] = x0 * p00 + x1 * p10 + x2 * p20
                b[r] = x0 * p01 + x1 * p11 + x2 * p21
                c[r] = x0 * p02 + x1 * p12 + x2 * p22
                d[r] = x0 * p03 + x1 * p13 + x2 * p23 + x3
        if i == n:
            break
        x, y, z = axes[i, 0], axes[i, 1], axes[i, 2]
        q = qm[i]
        if prismatic[i]:
            for row in range(3):
                a, b, c, d = t[4 * row], t[4 * row + 1], t[4 * row + 2], t[4 * row + 3]
                for r in range(count):
                    d[r] += (a[r] * x + b[r] * y + c[r] * z) * q[r]
            continue
        sins, coss = t[12], t[13]
        for r in range(count):
            xr = q[r]
            k = math.floor(xr * _TWO_OVER_PI + 0.5)
            u = (xr - k * _PIO2_1) - k * _PIO2_1T
            w = u * u
            sp = u + u * w * (_S1 + w * (_S2 + w * (_S3 + w * (_S4 + w * (_S5 + w * _S6)))))
            cp = 1.0 - 0.5 * w + w * w * (_C1 + w * (_C2 + w * (_C3 + w * (_C4 + w * (_C5 + w * _C6)))))
            quadrant = int(k) & 3
            sv = cp if quadrant & 1 else sp
            cv = sp if quadrant & 1 else cp
            sins[r] = -sv if quadrant & 2 else sv
            coss[r] = -cv if (quadrant + 1) & 2 else cv
        if x == 0.0 and y == 0.0 and z == 1.0:  # about z: two columns turn
            for row in range(3):
                a, b = t[4 * row], t[4 * row + 1]
                for r in range(count):
                    t0, t1 = a[r], b[r]
                    a[r] = t0 * coss[r] + t1 * sins[r]
                    b[r] = t1 * coss[r] - t0 * sins[r]
            continue
        for r in range(count):
            cn, sn = coss[r], sins[r]
            v = 1.0 - cn
            r00, r01, r02 = cn + x * x * v, x * y * v - z * sn, x * z * v + y * sn
            r10, r11, r12 = y * x * v + z * sn, cn + y * y * v, y * z * v - x * sn
            r20, r21, r22 = z * x * v - y * sn, z * y * v + x * sn, cn + z * z * v
            for row in range(3):
                t0, t1, t2 = t[4 * row, r], t[4 * row + 1, r], t[4 * row + 2, r]
                t[4 * row, r] = t0 * r00 + t1 * r10 + t2 * r20
                t[4 * row + 1, r] = t0 * r01 + t1 * r11 + t2 * r21
                t[4 * row + 2, r] = t0 * r02 + t1 * r12 + t2 * r22


def _fk_error_rows(placements, axes, prismatic, flange, qm, target, t, err):  # type: ignore[no-untyped-def]
    """How far FK of R configurations lies from target: qm (n, R) model values (one column
    each), t (14, R) scratch, err (2, R) out (squared position, squared rotation errors)."""
    _fk_columns(placements, axes, prismatic, flange, qm, t)
    count = qm.shape[1]
    for r in range(count):
        dp = 0.0
        dr = 0.0
        for row in range(3):
            dp += (t[4 * row + 3, r] - target[row, 3]) ** 2
            for col in range(3):
                dr += (t[4 * row + col, r] - target[row, col]) ** 2
        err[0, r] = dp
        err[1, r] = dr


SINCOS = Kernel(_sincos)
FK_COLUMNS = Kernel(_fk_columns)
FK_ERROR_ROWS = Kernel(_fk_error_rows, uses=(FK_COLUMNS,))
