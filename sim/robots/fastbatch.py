# mypy: disable-error-code="no-untyped-call"
# (numba kernels: untyped on purpose, numba types them; they call each other by plain name)
"""`ik_batch`'s limits, seed selection and FK verification in one compiled loop (numba).

For each pose and closed-form branch: the 2π-equivalent of every joint nearest to the seed
(seeds: one row per pose, or one row for all) within the limits (as `ik._nearest_in_limits`:
k0 = round((seed - q) / 2π), then k0, k0-1, k0+1, k0-2, k0+2, the first nearest one kept,
clipped into the limits), NaN for the whole row when a joint has none; then FK of the rows
that exist (fastfk._fk_columns, in blocks of columns from several poses, vectorised; a NaN
row is not looked at) against their poses, flagging the rows beyond the tolerances it is
given (half of POS_TOL / ROT_TOL: the caller checks those again exactly as its numpy path
does, and polishes the failures with `ik._verified`).

The same arithmetic as the numpy path in `ik.solve_batch` for the chosen values (so the same
joint values come out); FK here rounds differently from numpy's matmul (another order of
sums and a polynomial sine, ~1e-16), so rows near a tolerance are decided by the caller's
numpy check.
Used above `ik._BATCH_KERNEL_POSES` poses per call (numba's load is not worth it below).
"""

from __future__ import annotations

import math

import numpy as np

from rmot.lang.jit import Kernel
from rmot.sim.robots.fastfk import FK_COLUMNS, _fk_columns

__all__ = ["NEAREST_VERIFIED"]


def _nearest_verified(  # type: ignore[no-untyped-def]
        raw, seeds, lo, hi, revolute, placements, axes, prismatic, flange, coupling, coupled,
        poses, pos_tol, rot_tol, out, bad):
    """out[n, b]: branch b of pose n at the 2π-equivalents nearest the seed within the limits
    (NaN when a joint has none); bad[n, b]: that row's FK is beyond pos_tol / rot_tol (see the
    module docstring).

    Long on purpose: one compiled loop over every pose, with the FK of the rows gathered in
    blocks of columns from several poses; split into kernels, the rows of one pose could not
    join another pose's block, and the block's scratch arrays would be passed around."""
    n_pose, n_branch, dof = raw.shape
    two_pi = 2 * math.pi
    # FK in blocks of _BLOCK columns (one per row that exists, of several poses: longer loops
    # for the compiler's vectors, no NaN rows); a block's unused columns hold earlier values
    qm = np.zeros((dof, _BLOCK))
    t = np.empty((14, _BLOCK))
    owner = np.empty(_BLOCK, dtype=np.int64)
    slot = np.empty(_BLOCK, dtype=np.int64)
    cols = 0
    for n in range(n_pose):
        sn = n if seeds.shape[0] > 1 else 0  # one seed row per pose, or one for all
        for b in range(n_branch):
            row = out[n, b]
            bad[n, b] = False
            missing = False
            for j in range(dof):
                r = raw[n, b, j]
                s = seeds[sn, j]
                k0 = np.round((s - r) / two_pi) if revolute[j] else 0.0
                cand = r + (k0 * two_pi if revolute[j] else 0.0)  # the loop's first candidate
                if (cand >= lo[j] - 1e-12 and cand <= hi[j] + 1e-12
                        and (abs(cand - s) < 3.0 or not revolute[j])):
                    # within the limits and nearer than π: every other one is farther than 3.28
                    # (or, prismatic, the same value), so the loop below would keep this one
                    row[j] = min(max(cand, lo[j]), hi[j])
                    continue
                best = np.nan
                best_d = np.inf
                for dk in (0.0, -1.0, 1.0, -2.0, 2.0):
                    cand = r + ((k0 + dk) * two_pi if revolute[j] else 0.0)
                    d = abs(cand - s)
                    if cand >= lo[j] - 1e-12 and cand <= hi[j] + 1e-12 and d < best_d:
                        best = min(max(cand, lo[j]), hi[j])
                        best_d = d
                row[j] = best
                if math.isnan(best):
                    missing = True
                    break  # the whole row becomes NaN below
            if missing:
                for j in range(dof):
                    row[j] = np.nan
                continue
            for j in range(dof):
                if coupled:
                    acc = 0.0
                    for k in range(dof):
                        acc += coupling[j, k] * row[k]
                    qm[j, cols] = acc
                else:
                    qm[j, cols] = row[j]
            owner[cols] = n
            slot[cols] = b
            cols += 1
        if cols > _BLOCK - n_branch or (n == n_pose - 1 and cols > 0):
            _fk_columns(placements, axes, prismatic, flange, qm, t)
            for c in range(cols):
                target = poses[owner[c]]
                dp = 0.0
                dr = 0.0
                for i in range(3):
                    dp += (t[4 * i + 3, c] - target[i, 3]) ** 2
                    for k in range(3):
                        dr += (t[4 * i + k, c] - target[i, k]) ** 2
                if math.sqrt(dp) > pos_tol or math.sqrt(dr) / math.sqrt(2.0) > rot_tol:
                    bad[owner[c], slot[c]] = True
            cols = 0


_BLOCK = 64  # FK columns per block (at least the branches of one pose)
NEAREST_VERIFIED = Kernel(_nearest_verified, uses=(FK_COLUMNS,))
