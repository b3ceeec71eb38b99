# mypy: disable-error-code="no-untyped-call"
# (numba kernels: untyped on purpose, numba types them; they call each other by plain name)
"""`ik_batch`'s limits, seed selection and FK verification in one compiled loop (numba).

For each pose and closed-form branch: the 2π-equivalent of every joint nearest to the seed
within the limits (as `ik._nearest_in_limits`: k0 = round((seed - q) / 2π), then k0, k0-1,
k0+1, k0-2, k0+2, the first nearest one kept, clipped into the limits), NaN for the whole row
when a joint has none; then FK of the row over the chain arrays (fastdls's loop) against the
pose (no allocation per row), flagging rows beyond POS_TOL / ROT_TOL for the caller to polish
(`ik._verified`).

The same arithmetic as the numpy path in `ik.solve_batch` for the chosen values (so the same
joint values come out); FK here sums 4x4 products in another order than numpy's matmul, which
can only move a row whose error is within ~1e-16 of a tolerance from one side to the other.
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
    motion = np.eye(4)
    t = np.empty((4, 4))
    tmp = np.empty((4, 4))
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
            t[:, :] = 0.0
            for i in range(4):
                t[i, i] = 1.0
            for i in range(dof):
                _mul4_into(t, placements[i], tmp, t)
                x, y, z = axes[i, 0], axes[i, 1], axes[i, 2]
                if prismatic[i]:
                    for r3 in range(3):
                        for c3 in range(3):
                            motion[r3, c3] = 1.0 if r3 == c3 else 0.0
                    motion[0, 3], motion[1, 3], motion[2, 3] = x * qm[i], y * qm[i], z * qm[i]
                else:  # fastdls._rotation's formula
                    c, s = math.cos(qm[i]), math.sin(qm[i])
                    v = 1.0 - c
                    motion[0, 0] = c + x * x * v
                    motion[0, 1] = x * y * v - z * s
                    motion[0, 2] = x * z * v + y * s
                    motion[1, 0] = y * x * v + z * s
                    motion[1, 1] = c + y * y * v
                    motion[1, 2] = y * z * v - x * s
                    motion[2, 0] = z * x * v - y * s
                    motion[2, 1] = z * y * v + x * s
                    motion[2, 2] = c + z * z * v
                    motion[0, 3] = motion[1, 3] = motion[2, 3] = 0.0
                _mul4_into(t, motion, tmp, t)
            _mul4_into(t, flange, tmp, t)
            dp = 0.0
            for r3 in range(3):
                dp += (t[r3, 3] - target[r3, 3]) ** 2
            dr = 0.0
            for r3 in range(3):
                for c3 in range(3):
                    dr += (t[r3, c3] - target[r3, c3]) ** 2
            if math.sqrt(dp) > pos_tol or math.sqrt(dr) / math.sqrt(2.0) > rot_tol:
                bad[n, b] = True


def _mul4_into(a, b, tmp, out):  # type: ignore[no-untyped-def]
    """out = a @ b (4x4, fastdls._mul4's order of sums) without allocating; out may be a."""
    for i in range(4):
        for j in range(4):
            tmp[i, j] = (a[i, 0] * b[0, j] + a[i, 1] * b[1, j]
                         + a[i, 2] * b[2, j] + a[i, 3] * b[3, j])
    for i in range(4):
        for j in range(4):
            out[i, j] = tmp[i, j]


NEAREST_VERIFIED = Kernel(_nearest_verified, uses=(Kernel(_mul4_into),))
