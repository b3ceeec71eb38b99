# mypy: disable-error-code="no-untyped-call"
# (numba kernels: untyped on purpose, numba types them; they call each other by plain name)
"""FK as a screening check for the compiled IK passes (fastsolve, fastbatch): how far FK(q)
lies from a target, in registers, with a polynomial sine and cosine.

The passes accept a branch only when this error is below HALF the tolerance (1e-9) and hand
everything between half and a clear miss to the numpy/pinocchio path, which decides with its
own FK. So this FK needs to be accurate to well under 5e-10, not to the last bit: `_sincos`
is fdlibm's kernel polynomials (k_sin.c / k_cos.c, Sun Microsystems 1993, the minimax
coefficients of sin and cos on [-π/4, π/4]) after a two-constant Cody-Waite reduction by π/2
(e_rem_pio2.c's PIO2_1 / PIO2_1T). tests/robots/test_ik_fast_path.py measures it against
math.sin / math.cos (below 4e-16 on |x| <= 40); it costs about a third of libm's pair.
"""

from __future__ import annotations

import math

from rmot.compiler.jit import Kernel

__all__ = ["FK_ERROR", "SINCOS"]

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


def _fk_error(placements, axes, prismatic, flange, qm, target):  # type: ignore[no-untyped-def]
    """(squared position error, squared rotation-matrix error) of FK(qm) against target:
    3x4 affine products in local scalars, no allocation; sines and cosines by `_sincos`."""
    t00, t01, t02, t03 = 1.0, 0.0, 0.0, 0.0
    t10, t11, t12, t13 = 0.0, 1.0, 0.0, 0.0
    t20, t21, t22, t23 = 0.0, 0.0, 1.0, 0.0
    n = qm.shape[0]
    for i in range(n + 1):
        k = i if i < n else 0
        if i < n:
            p00, p01, p02, p03 = placements[k, 0, 0], placements[k, 0, 1], placements[k, 0, 2], placements[k, 0, 3]
            p10, p11, p12, p13 = placements[k, 1, 0], placements[k, 1, 1], placements[k, 1, 2], placements[k, 1, 3]
            p20, p21, p22, p23 = placements[k, 2, 0], placements[k, 2, 1], placements[k, 2, 2], placements[k, 2, 3]
        else:
            p00, p01, p02, p03 = flange[0, 0], flange[0, 1], flange[0, 2], flange[0, 3]
            p10, p11, p12, p13 = flange[1, 0], flange[1, 1], flange[1, 2], flange[1, 3]
            p20, p21, p22, p23 = flange[2, 0], flange[2, 1], flange[2, 2], flange[2, 3]
        t00, t01, t02, t03 = (t00 * p00 + t01 * p10 + t02 * p20, t00 * p01 + t01 * p11 + t02 * p21,
                              t00 * p02 + t01 * p12 + t02 * p22, t00 * p03 + t01 * p13 + t02 * p23 + t03)
        t10, t11, t12, t13 = (t10 * p00 + t11 * p10 + t12 * p20, t10 * p01 + t11 * p11 + t12 * p21,
                              t10 * p02 + t11 * p12 + t12 * p22, t10 * p03 + t11 * p13 + t12 * p23 + t13)
        t20, t21, t22, t23 = (t20 * p00 + t21 * p10 + t22 * p20, t20 * p01 + t21 * p11 + t22 * p21,
                              t20 * p02 + t21 * p12 + t22 * p22, t20 * p03 + t21 * p13 + t22 * p23 + t23)
        if i == n:
            break
        x, y, z = axes[i, 0], axes[i, 1], axes[i, 2]
        if prismatic[i]:
            d = qm[i]
            t03 += (t00 * x + t01 * y + t02 * z) * d
            t13 += (t10 * x + t11 * y + t12 * z) * d
            t23 += (t20 * x + t21 * y + t22 * z) * d
        elif x == 0.0 and y == 0.0 and z == 1.0:  # about z: two columns turn
            s, c = _sincos(qm[i])
            t00, t01 = t00 * c + t01 * s, t01 * c - t00 * s
            t10, t11 = t10 * c + t11 * s, t11 * c - t10 * s
            t20, t21 = t20 * c + t21 * s, t21 * c - t20 * s
        else:  # fastdls._rotation's matrix
            s, c = _sincos(qm[i])
            v = 1.0 - c
            r00, r01, r02 = c + x * x * v, x * y * v - z * s, x * z * v + y * s
            r10, r11, r12 = y * x * v + z * s, c + y * y * v, y * z * v - x * s
            r20, r21, r22 = z * x * v - y * s, z * y * v + x * s, c + z * z * v
            t00, t01, t02 = (t00 * r00 + t01 * r10 + t02 * r20, t00 * r01 + t01 * r11 + t02 * r21,
                             t00 * r02 + t01 * r12 + t02 * r22)
            t10, t11, t12 = (t10 * r00 + t11 * r10 + t12 * r20, t10 * r01 + t11 * r11 + t12 * r21,
                             t10 * r02 + t11 * r12 + t12 * r22)
            t20, t21, t22 = (t20 * r00 + t21 * r10 + t22 * r20, t20 * r01 + t21 * r11 + t22 * r21,
                             t20 * r02 + t21 * r12 + t22 * r22)
    dp = ((t03 - target[0, 3]) ** 2 + (t13 - target[1, 3]) ** 2 + (t23 - target[2, 3]) ** 2)
    dr = ((t00 - target[0, 0]) ** 2 + (t01 - target[0, 1]) ** 2 + (t02 - target[0, 2]) ** 2
          + (t10 - target[1, 0]) ** 2 + (t11 - target[1, 1]) ** 2 + (t12 - target[1, 2]) ** 2
          + (t20 - target[2, 0]) ** 2 + (t21 - target[2, 1]) ** 2 + (t22 - target[2, 2]) ** 2)
    return dp, dr


SINCOS = Kernel(_sincos)
FK_ERROR = Kernel(_fk_error, uses=(SINCOS,))
