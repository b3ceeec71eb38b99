# mypy: disable-error-code="no-untyped-call"
# (numba kernels: untyped on purpose, numba types them; they call each other by plain name)
"""`Robot.ik` of closed-form arms in one compiled pass (numba), for processes that solve many
single poses (the planner, the CLI's batch commands).

The pass does what `ik.solve` does, in the same order and with the same arithmetic for every
value it returns: the closed form (fastik's kernel), FK verification of each branch, the
distinct candidates modulo 2π, each one's branch, every 2π-equivalent within the limits in
itertools.product order, the config filter, the stable sort by distance from the seed, and a
test that the first solution is not singular. The joint values and branch names are those of
`ik.solve`; so the pass only decides what is clear by a margin and hands every other pose
back to `ik.solve` whole (return -1):

- FK here sums in another order than numpy's matmul (~1e-16): a branch is accepted when its
  error is below half the tolerance, rejected when above 2e-4 (ik.solve polishes up to 1e-4),
  else the pose goes back;
- a wrist near its singularity (|sin J5| <= 2e-7; ik.solve keeps the seed's J4 below 1e-7),
  a branch quantity within 1e-10 of its boundary (the sine here may differ from numpy's in
  the last bit), no verified or no in-limit solution (the messages are ik.solve's), no branch
  left after the config filter, or a rotation near the orthonormality bound go back;
- singular: the smallest singular value of the reach-scaled Jacobian is at least
  |det J| / |J|_F^(n-1) (every singular value is at most the Frobenius norm); when that bound
  is above twice SINGULAR_SIGMA the pose is not singular, else the caller asks pinocchio and
  the SVD exactly as `ik_result.is_singular` does (flag 1).

More than _SORTED_ROWS solutions (joints beyond ±180°: a UR arm has 512 per pose): the pass
checks everything above and finds the nearest solution (the first row of the stable sort, by
a pruned walk with the same sums: `_nearest_row`), but makes and sorts the rows only when the
result is asked for more than its first one (`_expand_sorted`, through ik_rows.Lazy). The
result is then `IkResult.solutions`/`branches` as views over one array (robots/ik_rows.py).
The call passes its arrays packed into four (`solve_packed`): numba's dispatch costs ~45 ns
per argument.

The interpreted form is the same function (Kernel); `ik.solve` only calls the compiled one,
once a process has solved SOLVE_ONE.threshold poses (so `rmot robots ik` stays numba-free).
"""

from __future__ import annotations

import math

import numpy as np

from rmot.lang.jit import Kernel
from rmot.sim.robots import fastik, ik_result
from rmot.sim.robots.fastfk import FK_ERROR_ROWS, _fk_error_rows
from rmot.sim.robots.fastik import _opw_one, _ur_one

__all__ = ["SOLVE_ONE"]

_TOLS = (ik_result.POS_TOL, ik_result.ROT_TOL, ik_result.SINGULAR_SIGMA)

_TWO_PI = 2 * math.pi
_SORTED_ROWS = 48  # above: a result's rows are made and sorted only when asked for


def _branch_code(kind, bpar, crows, q):  # type: ignore[no-untyped-def]
    """4·shoulder + 2·elbow + wrist (1 = BACK / DOWN / FLIP) as branches.config_of names q,
    or -1 when a quantity lies within 1e-10 of its boundary (ik.solve decides those)."""
    if kind == 0:  # branches.opw_branch_fn
        acc2 = 0.0
        acc3 = 0.0
        for j in range(6):
            if crows[0, j] != 0.0:
                acc2 += crows[0, j] * q[j]
            if crows[1, j] != 0.0:
                acc3 += crows[1, j] * q[j]
        t2 = bpar[0] * acc2 + bpar[2]
        t3 = bpar[1] * acc3 + bpar[3]
        shoulder = bpar[4] + bpar[5] * math.sin(t2) + bpar[6] * math.sin(t2 + t3 + bpar[7])
        elbow = math.sin(t3 + bpar[7])
    else:  # urik.ur_branch_quantities
        x1 = (bpar[0] * math.cos(q[1]) + bpar[1] * math.cos(q[1] + q[2])
              + bpar[2] * math.sin(q[1] + q[2] + q[3]))
        shoulder = -x1
        elbow = math.sin(q[2])
    wrist = math.sin(q[4])
    if abs(shoulder) < 1e-10 or abs(elbow) < 1e-10 or abs(wrist) < 1e-10:
        return -1
    return (4 if shoulder < 0.0 else 0) + (2 if elbow < 0.0 else 0) + (1 if wrist < 0.0 else 0)


def _jacobian_into(placements, axes, prismatic, flange, qm, jac, frames):  # type: ignore[no-untyped-def]
    """jac (6,n): the world-frame geometric Jacobian of the flange (fastdls._fk_jac's columns:
    linear rows first); frames (n,6) scratch: each joint's world axis and origin."""
    n = qm.shape[0]
    t00, t01, t02, t03 = 1.0, 0.0, 0.0, 0.0
    t10, t11, t12, t13 = 0.0, 1.0, 0.0, 0.0
    t20, t21, t22, t23 = 0.0, 0.0, 1.0, 0.0
    for i in range(n + 1):
        p = flange if i == n else placements[i]
        p00, p01, p02, p03 = p[0, 0], p[0, 1], p[0, 2], p[0, 3]
        p10, p11, p12, p13 = p[1, 0], p[1, 1], p[1, 2], p[1, 3]
        p20, p21, p22, p23 = p[2, 0], p[2, 1], p[2, 2], p[2, 3]
        t00, t01, t02, t03 = (t00 * p00 + t01 * p10 + t02 * p20, t00 * p01 + t01 * p11 + t02 * p21,
                              t00 * p02 + t01 * p12 + t02 * p22, t00 * p03 + t01 * p13 + t02 * p23 + t03)
        t10, t11, t12, t13 = (t10 * p00 + t11 * p10 + t12 * p20, t10 * p01 + t11 * p11 + t12 * p21,
                              t10 * p02 + t11 * p12 + t12 * p22, t10 * p03 + t11 * p13 + t12 * p23 + t13)
        t20, t21, t22, t23 = (t20 * p00 + t21 * p10 + t22 * p20, t20 * p01 + t21 * p11 + t22 * p21,
                              t20 * p02 + t21 * p12 + t22 * p22, t20 * p03 + t21 * p13 + t22 * p23 + t23)
        if i == n:
            break
        x, y, z = axes[i, 0], axes[i, 1], axes[i, 2]
        frames[i, 0] = t00 * x + t01 * y + t02 * z
        frames[i, 1] = t10 * x + t11 * y + t12 * z
        frames[i, 2] = t20 * x + t21 * y + t22 * z
        if prismatic[i]:
            d = qm[i]
            t03 += frames[i, 0] * d
            t13 += frames[i, 1] * d
            t23 += frames[i, 2] * d
        else:
            c, s = math.cos(qm[i]), math.sin(qm[i])
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
        frames[i, 3], frames[i, 4], frames[i, 5] = t03, t13, t23
    for i in range(n):
        ax, ay, az = frames[i, 0], frames[i, 1], frames[i, 2]
        if prismatic[i]:
            jac[0, i], jac[1, i], jac[2, i] = ax, ay, az
            jac[3, i] = jac[4, i] = jac[5, i] = 0.0
        else:
            dx, dy, dz = t03 - frames[i, 3], t13 - frames[i, 4], t23 - frames[i, 5]
            jac[0, i] = ay * dz - az * dy
            jac[1, i] = az * dx - ax * dz
            jac[2, i] = ax * dy - ay * dx
            jac[3, i], jac[4, i], jac[5, i] = ax, ay, az


def _not_singular(placements, axes, prismatic, flange, coupling, coupled, qm, reach, sigma,  # type: ignore[no-untyped-def]
                  jac, a, frames):
    """True when the smallest singular value of the reach-scaled Jacobian is surely >= sigma
    (by |det J| / |J|_F^(n-1) > 2 sigma); False = ask the SVD. jac, a (6,6), frames (6,6):
    scratch."""
    n = qm.shape[0]
    if n != 6:
        return False
    _jacobian_into(placements, axes, prismatic, flange, qm, jac, frames)
    scale = max(reach, 1e-3)
    frob = 0.0
    for r in range(6):
        for c in range(6):
            v = jac[r, c]
            if coupled:
                v = 0.0
                for k in range(6):
                    v += jac[r, k] * coupling[k, c]
            if r >= 3:
                v *= scale
            a[r, c] = v
            frob += v * v
    det = 1.0
    for c in range(6):  # Gaussian elimination with partial pivoting
        piv = c
        for r in range(c + 1, 6):
            if abs(a[r, c]) > abs(a[piv, c]):
                piv = r
        if a[piv, c] == 0.0:
            return False
        if piv != c:
            det = -det
            for k in range(6):
                a[c, k], a[piv, k] = a[piv, k], a[c, k]
        det *= a[c, c]
        for r in range(c + 1, 6):
            f = a[r, c] / a[c, c]
            for k in range(c, 6):
                a[r, k] -= f * a[c, k]
    return abs(det) > 2.0 * sigma * math.sqrt(frob) ** (n - 1)


def _expand(groups, n_groups, seed, out, codes, dist, digits):  # type: ignore[no-untyped-def]
    """Every row of the first n_groups groups (solve_one's layout: code, row count, then per
    joint its count of equivalents and their values) in ik._equivalents' order (itertools.product
    over the joints, last fastest; groups in branch order), with its branch code and its distance
    from the seed (the sum of squares in joint order, then the square root). digits: (dof,)
    scratch. Returns the row count."""
    dof = seed.shape[0]
    per = (groups.shape[1] - 2 - dof) // dof
    m = 0
    for gi in range(n_groups):
        g = groups[gi]
        code = int(g[0])
        for j in range(dof):
            digits[j] = 0
        for _idx in range(int(g[1])):
            acc = 0.0
            for j in range(dof):
                v = g[2 + dof + j * per + digits[j]]
                out[m, j] = v
                d = v - seed[j]
                acc += d * d
            dist[m] = math.sqrt(acc)
            codes[m] = code
            m += 1
            j = dof - 1
            while j >= 0:
                digits[j] += 1
                if digits[j] < g[2 + j]:
                    break
                digits[j] = 0
                j -= 1
    return m


def _nearest_row(groups, n_groups, seed, row, digits, partial):  # type: ignore[no-untyped-def]
    """The index (in `_expand`'s order) of the first row at the least distance from the seed
    (the first row of a stable sort by `_expand`'s distances, with the same arithmetic), and
    that row into row, without making the others.

    A depth-first walk over each group's joints in `_expand`'s order: a row's sum of squares
    is the sums over its first joints (partial: (dof,) scratch) plus the rest, the same sums
    in the same order as `_expand`'s. A float sum of non-negative terms never decreases, so
    once a prefix sum exceeds T = U·(1 + 1e-13), where U is the sum of some row (each group's
    nearest option per joint), every row below it has a distance above √U's rounding, which
    is at least the least distance: it can be neither the nearest nor tie with it, and the
    walk skips it. digits: (dof,) scratch.
    Long on purpose: the walk keeps its prefix sums, bound and position in a few scalars and
    one scratch row; a recursive or split version would pass them at every step of the walk.
    """
    dof = seed.shape[0]
    per = (groups.shape[1] - 2 - dof) // dof
    bound = math.inf
    for gi in range(n_groups):  # U: a row of each group, its nearest option per joint
        g = groups[gi]
        acc = 0.0
        for j in range(dof):
            best_d = math.inf
            for k in range(int(g[2 + j])):
                d = abs(g[2 + dof + j * per + k] - seed[j])
                if d < best_d:
                    best_d = d
            acc += best_d * best_d
        if acc < bound:
            bound = acc
    limit = bound * (1.0 + 1e-13)
    best = math.inf
    first = -1
    base = 0
    for gi in range(n_groups):
        g = groups[gi]
        j = 0
        digits[0] = 0
        while True:
            d = g[2 + dof + j * per + digits[j]] - seed[j]
            acc = (0.0 if j == 0 else partial[j - 1]) + d * d
            partial[j] = acc
            if acc <= limit:
                if j < dof - 1:
                    j += 1
                    digits[j] = 0
                    continue
                dist = math.sqrt(acc)
                if dist < best:
                    best = dist
                    index = 0
                    for i in range(dof):
                        row[i] = g[2 + dof + i * per + digits[i]]
                        index = index * int(g[2 + i]) + digits[i]
                    first = base + index
            digits[j] += 1  # the next option of this joint, or back up
            while digits[j] >= g[2 + j]:
                j -= 1
                if j < 0:
                    break
                digits[j] += 1
            if j < 0:
                break
        base += int(g[1])
    return first


def _group_of(groups, n_groups, index):  # type: ignore[no-untyped-def]
    """The group of row `index` in `_expand`'s order."""
    for gi in range(n_groups):
        index -= int(groups[gi, 1])
        if index < 0:
            return gi
    return -1


def solve_one(a0, a1, a2, a3, bpar, crows, local, target, seed, consts,  # type: ignore[no-untyped-def]
              placements, axes, prismatic, flange, coupling, want, fwork, groups, iwork, dist,
              branch_work, out, codes, saved):
    """One pose -> (m, flag, first, n_groups, code): out[:m] the solutions sorted as ik.solve
    sorts them, codes[:m] their branch codes, when first = -1; when m > _SORTED_ROWS (many
    2π-equivalents) saved = the seed, the nearest row, then groups (as `_expand` makes the rows
    of groups[:n_groups]), first the nearest row's index in that order and code its branch code
    (the caller makes and sorts the rows only if asked: ik_rows.Lazy); flag 1 = the caller must
    run the exact singularity test on the nearest row.
    m = -1: hand the pose to ik.solve (see the module docstring). consts: lo, hi, revolute
    (1.0 / 0.0) per joint, then reach, POS_TOL, ROT_TOL, SINGULAR_SIGMA, coupled, kind
    (0 OPW, 1 UR). Scratch: fwork (35 + rows, dof): raw (8,dof), 19 rows, the 8 rows mod 2π, then
    out's rows reordered; groups (8, 2 + dof + dof·K): `_expand`'s; iwork: (dof, unused),
    three flag rows (3x8),
    the order and the codes of out's rows; dist with out's rows; branch_work (dof + 16, 8):
    the branches' FK (fastfk._fk_error_rows).
    Long on purpose: one compiled kernel per pose, called in a loop over the poses; its
    stages (closed form, limits, sort, verification) share the scratch arrays above, and a
    call per stage would pass all of them.
    """
    dof = seed.shape[0]
    rows = out.shape[0]
    lo, hi, revolute = consts[0:dof], consts[dof:2 * dof], consts[2 * dof:3 * dof]
    reach, pos_tol, rot_tol, sigma = consts[3 * dof], consts[3 * dof + 1], consts[3 * dof + 2], consts[3 * dof + 3]
    coupled = consts[3 * dof + 4] != 0.0
    kind = int(consts[3 * dof + 5])
    raw, scratch, wrapped, ordered = fwork[0:8], fwork[8:27], fwork[27:35], fwork[35:35 + rows]
    flags = iwork[dof:dof + 24].reshape((3, 8))
    order, ordered_codes = iwork[dof + 24:dof + 24 + rows], iwork[dof + 24 + rows:dof + 24 + 2 * rows]
    # the pose: finite, rotation orthonormal (ik._check_pose raises otherwise)
    for r in range(4):
        for c in range(4):
            if not math.isfinite(target[r, c]):
                return -1, 0, -1, 0, 0
    for r in range(3):
        for c in range(3):
            dot = target[r, 0] * target[c, 0] + target[r, 1] * target[c, 1] + target[r, 2] * target[c, 2]
            if abs(dot - (1.0 if r == c else 0.0)) > 0.5e-6:
                return -1, 0, -1, 0, 0
    if kind == 0:
        _opw_one(a0, a1, a2, a3, local, raw)
    else:
        _ur_one(a0, local, raw)
    qm = scratch[0]
    keep = flags[0]
    verified = flags[1]
    for b in range(8):
        keep[b] = 0
    n_keep = 0
    columns, t, err = branch_work[0:dof], branch_work[dof:dof + 14], branch_work[dof + 14:dof + 16]
    finite = flags[2]
    for b in range(8):
        finite[b] = 1
        for j in range(dof):
            if not math.isfinite(raw[b, j]):
                finite[b] = 0
        for j in range(dof):
            if not finite[b]:
                columns[j, b] = 0.0  # FK'd with the others, not looked at
            elif coupled:
                acc = 0.0
                for k in range(dof):
                    acc += coupling[j, k] * raw[b, k]
                columns[j, b] = acc
            else:
                columns[j, b] = raw[b, j]
    _fk_error_rows(placements, axes, prismatic, flange, columns, target, t, err)
    for b in range(8):
        if not finite[b]:
            continue
        dp2, dr2 = err[0, b], err[1, b]
        dp, dr = math.sqrt(dp2), math.sqrt(dr2 / 2.0)
        if dp <= pos_tol / 2 and dr <= rot_tol / 2:
            if dof == 6 and abs(math.sin(raw[b, 4])) <= 2e-7:
                return -1, 0, -1, 0, 0  # the wrist singularity: ik.solve keeps the seed's J4
            keep[b] = 1
            n_keep += 1
        elif dp < 2e-4 and dr < 2e-4:
            return -1, 0, -1, 0, 0  # a near miss: ik.solve polishes it
    if n_keep == 0:
        return -1, 0, -1, 0, 0
    # distinct modulo 2π (ik._distinct: np.remainder, then the wrapped gap; a candidate is
    # dropped when it equals any earlier verified one, dropped or not)
    for b in range(8):
        verified[b] = keep[b]
        if keep[b]:
            for j in range(dof):
                w = np.fmod(raw[b, j], _TWO_PI)
                wrapped[b, j] = w + _TWO_PI if w < 0.0 else w
    for b in range(8):
        if not verified[b]:
            continue
        for e in range(b):
            if not verified[e]:
                continue
            worst = 0.0
            for j in range(dof):
                gap = abs(wrapped[e, j] - wrapped[b, j])
                d = min(gap, _TWO_PI - gap)
                if d > worst:
                    worst = d
            if worst <= 1e-9:
                keep[b] = 0
                break
    m = 0
    n_groups = 0
    n_kept = 0
    per = (groups.shape[1] - 2 - dof) // dof  # room for equivalents per joint
    for b in range(8):
        if not keep[b]:
            continue
        # ik._equivalents: every q + 2πk within the limits, itertools.product order
        g = groups[n_kept]
        empty = False
        total = 1
        for j in range(dof):
            v = raw[b, j]
            start = v
            if revolute[j] != 0.0:
                start = v + math.ceil((lo[j] - 1e-12 - v) / _TWO_PI) * _TWO_PI
            if not (lo[j] - 1e-12 <= start and start <= hi[j] + 1e-12):
                empty = True
                break
            value = min(max(start, lo[j]), hi[j])
            g[2 + dof + j * per] = value
            k = 1
            while revolute[j] != 0.0 and value + _TWO_PI <= hi[j] + 1e-12:
                value = min(value + _TWO_PI, hi[j])
                g[2 + dof + j * per + k] = value
                k += 1
            g[2 + j] = k
            total *= k
        if empty:
            continue
        code = _branch_code(kind, bpar, crows, raw[b])
        if code < 0:
            return -1, 0, -1, 0, 0
        n_groups += 1
        if ((want[0] >= 0 and want[0] != code // 4) or (want[1] >= 0 and want[1] != (code // 2) % 2)
                or (want[2] >= 0 and want[2] != code % 2)):
            continue
        g[0] = code
        g[1] = total
        n_kept += 1
        m += total
    if n_groups == 0 or m == 0:
        return -1, 0, -1, 0, 0  # out of limits, or no branch as configured: ik.solve's messages
    if m > _SORTED_ROWS:  # many 2π-equivalents: made and sorted if asked for (ik_rows.Lazy)
        for j in range(dof):
            saved[j] = seed[j]
        nearest = saved[dof:2 * dof]
        first = _nearest_row(groups, n_kept, seed, nearest, flags[2, :dof], wrapped[0])
        code0 = int(groups[_group_of(groups, n_kept, first), 0])
    else:  # all rows, then an insertion sort of the indices: stable, no allocation
        first = -1
        _expand(groups, n_kept, seed, out, codes, dist, flags[2, :dof])
        for i in range(m):
            k = i
            while k > 0 and dist[order[k - 1]] > dist[i]:
                order[k] = order[k - 1]
                k -= 1
            order[k] = i
        for i in range(m):
            k = order[i]
            for j in range(dof):
                ordered[i, j] = out[k, j]
            ordered_codes[i] = codes[k]
        for i in range(m):
            for j in range(dof):
                out[i, j] = ordered[i, j]
            codes[i] = ordered_codes[i]
        nearest = out[0]
        code0 = codes[0]
    for j in range(dof):
        if coupled:
            acc = 0.0
            for k in range(dof):
                acc += coupling[j, k] * nearest[k]
            qm[j] = acc
        else:
            qm[j] = nearest[j]
    flag = 0 if _not_singular(placements, axes, prismatic, flange, coupling, coupled, qm, reach, sigma,
                              scratch[1:7], scratch[7:13], scratch[13:19]) else 1
    return m, flag, first, n_kept, code0


def solve_packed(fc, ic, local, target, seed, want, fs, iscr):  # type: ignore[no-untyped-def]
    """solve_one with its arrays packed into four (FastSolver's layout): a call with fewer
    arguments costs less to dispatch (~45 ns each). fc: the robot's constants; ic: dof, the
    length of the closed form's first array and of the branch parameters, the scratch rows,
    the columns of a group; fs / iscr: float / int scratch."""
    dof, n0, nb, rows, gcols = ic[0], ic[1], ic[2], ic[3], ic[4]
    a0 = fc[0:n0]
    o = n0
    a1, a2 = fc[o:o + 6], fc[o + 6:o + 12]
    a3 = fc[o + 12:o + 48].reshape((6, 6))
    o += 48
    bpar = fc[o:o + nb]
    o += nb
    crows = fc[o:o + 2 * dof].reshape((2, dof))
    o += 2 * dof
    consts = fc[o:o + 3 * dof + 6]
    o += 3 * dof + 6
    placements = fc[o:o + 16 * dof].reshape((dof, 4, 4))
    o += 16 * dof
    axes = fc[o:o + 3 * dof].reshape((dof, 3))
    o += 3 * dof
    prismatic = fc[o:o + dof]
    o += dof
    flange = fc[o:o + 16].reshape((4, 4))
    coupling = fc[o + 16:o + 16 + dof * dof].reshape((dof, dof))
    saved = fs[0:2 * dof + 8 * gcols]  # seed, nearest row, groups: what a lazy result keeps
    groups = saved[2 * dof:].reshape((8, gcols))
    o = 2 * dof + 8 * gcols
    fwork = fs[o:o + (35 + rows) * dof].reshape((35 + rows, dof))
    o += (35 + rows) * dof
    dist = fs[o:o + rows]
    o += rows
    branch_work = fs[o:o + (dof + 16) * 8].reshape((dof + 16, 8))
    o += (dof + 16) * 8
    out = fs[o:o + rows * dof].reshape((rows, dof))
    iwork = iscr[0:dof + 24 + 2 * rows]
    codes = iscr[dof + 24 + 2 * rows:dof + 24 + 3 * rows]
    return solve_one(a0, a1, a2, a3, bpar, crows, local, target, seed, consts, placements, axes,
                     prismatic, flange, coupling, want, fwork, groups, iwork, dist, branch_work,
                     out, codes, saved)


EXPAND = Kernel(_expand)
_SOLVE_ONE = Kernel(solve_one, uses=(fastik._OPW_ONE, fastik._UR_ONE, FK_ERROR_ROWS,
                                     Kernel(_branch_code), EXPAND, Kernel(_nearest_row),
                                     Kernel(_group_of),
                                     Kernel(_not_singular, uses=(Kernel(_jacobian_into),))))
SOLVE_ONE = Kernel(solve_packed, uses=(_SOLVE_ONE,), threshold=200)


def _expand_sorted(groups, seed, rows, codes):  # type: ignore[no-untyped-def]
    """`_expand` of every group, then the rows and codes in the order of a stable sort by the
    distances (numba's mergesort: stable, as ik.solve_exact's np.argsort(kind="stable"))."""
    m, dof = rows.shape
    made, made_codes, dist = np.empty((m, dof)), np.empty(m, dtype=np.int64), np.empty(m)
    _expand(groups, groups.shape[0], seed, made, made_codes, dist, np.empty(dof, dtype=np.int64))
    order = np.argsort(dist, kind="mergesort")
    for i in range(m):
        k = order[i]
        for j in range(dof):
            rows[i, j] = made[k, j]
        codes[i] = made_codes[k]


EXPAND_SORTED = Kernel(_expand_sorted, uses=(EXPAND,))
