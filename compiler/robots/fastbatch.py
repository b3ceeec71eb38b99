# mypy: disable-error-code="no-untyped-call"
# (numba kernels: untyped on purpose, numba types them; they call each other by plain name)
"""`ik_batch`'s limits, seed selection and FK verification in one compiled loop (numba).

For each pose and closed-form branch: the 2π-equivalent of every joint nearest to the seed
within the limits (as `ik._nearest_in_limits`: k0 = round((seed - q) / 2π), then k0, k0-1,
k0+1, k0-2, k0+2, the first nearest one kept, clipped into the limits), NaN for the whole row
when a joint has none; then FK of the row over the chain arrays (fastdls's loop) against the
pose (3x4 affine products, rotations as 3x3, no allocation per row), flagging the rows beyond
the tolerances it is given (half of POS_TOL / ROT_TOL: the caller checks those again exactly as
its numpy path does, and polishes the failures with `ik._verified`).

The same arithmetic as the numpy path in `ik.solve_batch` for the chosen values (so the same
joint values come out); FK here rounds differently from numpy's matmul (another order of
sums, ~1e-16), so rows near a tolerance are decided by the caller's numpy check.
Used above `ik._BATCH_KERNEL_POSES` poses per call (numba's load is not worth it below).
"""

from __future__ import annotations

import math

import numpy as np

from rmot.compiler.jit import Kernel

__all__ = ["NEAREST_VERIFIED"]


def _nearest_verified(  # type: ignore[no-untyped-def]
        raw, seeds, lo, hi, revolute, placements, axes, prismatic, flange, coupling, coupled,
        poses, pos_tol, rot_tol, out, bad):
    n_pose, n_branch, dof = raw.shape
    two_pi = 2 * math.pi
    qm = np.empty(dof)
    rot = np.empty((3, 3))
    t = np.empty((3, 4))
    tmp = np.empty(4)
    for n in range(n_pose):
        target = poses[n]
        for b in range(n_branch):
            row = out[n, b]
            bad[n, b] = False
            missing = False
            for j in range(dof):
                r = raw[n, b, j]
                s = seeds[n, j]
                k0 = np.round((s - r) / two_pi) if revolute[j] else 0.0
                best = np.nan
                best_d = np.inf
                for dk in (0.0, -1.0, 1.0, -2.0, 2.0):
                    cand = r + ((k0 + dk) * two_pi if revolute[j] else 0.0)
                    d = abs(cand - s)
                    if cand >= lo[j] - 1e-12 and cand <= hi[j] + 1e-12 and d < best_d:
                        best = min(max(cand, lo[j]), hi[j])
                        best_d = d
                if math.isnan(best):
                    missing = True
                row[j] = best
            if missing:
                for j in range(dof):
                    row[j] = np.nan
                continue
            for j in range(dof):
                if coupled:
                    acc = 0.0
                    for k in range(dof):
                        acc += coupling[j, k] * row[k]
                    qm[j] = acc
                else:
                    qm[j] = row[j]
            # FK as 3x4 affine products (the bottom row is always 0 0 0 1)
            for r3 in range(3):
                for c3 in range(4):
                    t[r3, c3] = 1.0 if r3 == c3 else 0.0
            for i in range(dof):
                _affine_into(t, placements[i], tmp)
                x, y, z = axes[i, 0], axes[i, 1], axes[i, 2]
                if prismatic[i]:  # a translation along the axis, in the joint frame
                    for r3 in range(3):
                        t[r3, 3] += (t[r3, 0] * x + t[r3, 1] * y + t[r3, 2] * z) * qm[i]
                else:  # fastdls._rotation's formula; the translation is unchanged
                    c, s = math.cos(qm[i]), math.sin(qm[i])
                    v = 1.0 - c
                    rot[0, 0] = c + x * x * v
                    rot[0, 1] = x * y * v - z * s
                    rot[0, 2] = x * z * v + y * s
                    rot[1, 0] = y * x * v + z * s
                    rot[1, 1] = c + y * y * v
                    rot[1, 2] = y * z * v - x * s
                    rot[2, 0] = z * x * v - y * s
                    rot[2, 1] = z * y * v + x * s
                    rot[2, 2] = c + z * z * v
                    for r3 in range(3):
                        t0, t1, t2 = t[r3, 0], t[r3, 1], t[r3, 2]
                        for c3 in range(3):
                            t[r3, c3] = t0 * rot[0, c3] + t1 * rot[1, c3] + t2 * rot[2, c3]
            _affine_into(t, flange, tmp)
            dp = 0.0
            for r3 in range(3):
                dp += (t[r3, 3] - target[r3, 3]) ** 2
            dr = 0.0
            for r3 in range(3):
                for c3 in range(3):
                    dr += (t[r3, c3] - target[r3, c3]) ** 2
            if math.sqrt(dp) > pos_tol or math.sqrt(dr) / math.sqrt(2.0) > rot_tol:
                bad[n, b] = True


def _affine_into(t, b, row):  # type: ignore[no-untyped-def]
    """t = t @ b for a 3x4 affine t and a 4x4 rigid b, in place (row: a 4-float buffer)."""
    for r3 in range(3):
        for c3 in range(4):
            row[c3] = t[r3, 0] * b[0, c3] + t[r3, 1] * b[1, c3] + t[r3, 2] * b[2, c3]
        row[3] += t[r3, 3]
        for c3 in range(4):
            t[r3, c3] = row[c3]


NEAREST_VERIFIED = Kernel(_nearest_verified, uses=(Kernel(_affine_into),))
