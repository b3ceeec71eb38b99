# mypy: disable-error-code="no-untyped-call"
# (numba kernels: untyped on purpose, numba types them; they call each other by plain name)
"""Closed-form IK kernels: the same algebra as `opw.opw_ik` and `urik.ur_ik`, one pose at a
time in a loop, writing controller joint values directly.

The numpy versions stay as the readable reference and are tested against these. Each kernel
is one function body that runs as plain Python for a few poses (no numba import: `rmot robots
ik` answers in the interpreter's time) and compiled by numba for many, or once a process has
solved enough poses to pay for it (lang/jit.py; cache=True keeps the compiled code across
processes). Both forms agree to the last bit of the transcendental functions (1 ulp).
"""

from __future__ import annotations

import math

import numpy as np

from rmot.lang.jit import Kernel
from rmot.sim.robots.opw import OpwJointMap, OpwParams
from rmot.sim.robots.urik import UrParams

__all__ = ["opw_batch", "ur_batch", "opw_kernel_args", "opw_solve", "ur_solve"]


def _acos(x: float) -> float:
    if x > 1.0:
        return 0.0 if x <= 1.0 + 1e-12 else math.nan
    if x < -1.0:
        return math.pi if x >= -1.0 - 1e-12 else math.nan
    return math.acos(x)


def _opw_one(p, sign, offset, cinv, t, out):  # type: ignore[no-untyped-def]
    a1, a2, b, c1, c2, c3, c4 = p[0], p[1], p[2], p[3], p[4], p[5], p[6]
    diagonal = True
    for j in range(6):
        for k in range(6):
            if j != k and cinv[j, k] != 0.0:
                diagonal = False
    cx, cy, cz = t[0, 3] - c4 * t[0, 2], t[1, 3] - c4 * t[1, 2], t[2, 3] - c4 * t[2, 2]
    rho2 = cx * cx + cy * cy - b * b
    nx1 = math.sqrt(rho2) - a1 if rho2 >= 0 else math.nan
    tmp1, tmp2 = math.atan2(cy, cx), math.atan2(b, nx1 + a1)
    dz = cz - c1
    s1_2 = nx1 * nx1 + dz * dz
    s2_2 = (nx1 + 2 * a1) ** 2 + dz * dz
    kappa_2 = a2 * a2 + c3 * c3
    c2_2 = c2 * c2
    tmp13 = _acos((s1_2 + c2_2 - kappa_2) / (2 * math.sqrt(s1_2) * c2))
    tmp14 = math.atan2(nx1, dz)
    tmp15 = _acos((s2_2 + c2_2 - kappa_2) / (2 * math.sqrt(s2_2) * c2))
    tmp16 = math.atan2(nx1 + 2 * a1, dz)
    tmp9 = 2 * c2 * math.sqrt(kappa_2)
    tmp11 = _acos((s1_2 - c2_2 - kappa_2) / tmp9)
    tmp12 = _acos((s2_2 - c2_2 - kappa_2) / tmp9)
    psi = math.atan2(a2, c3)
    th1 = (tmp1 - tmp2, tmp1 - tmp2, tmp1 + tmp2 - math.pi, tmp1 + tmp2 - math.pi)
    th2 = (-tmp13 + tmp14, tmp13 + tmp14, -tmp15 - tmp16, tmp15 - tmp16)
    th3 = (tmp11 - psi, -tmp11 - psi, tmp12 - psi, -tmp12 - psi)
    sin1 = (math.sin(th1[0]), math.sin(th1[2]))
    cos1 = (math.cos(th1[0]), math.cos(th1[2]))
    for i in range(4):
        s1, k1 = sin1[i // 2], cos1[i // 2]
        s23, k23 = math.sin(th2[i] + th3[i]), math.cos(th2[i] + th3[i])
        # rce = (Rz(θ1)·Ry(θ2+θ3))ᵀ · R: the columns 0 and 2 are all the wrist needs
        r00 = k1 * k23 * t[0, 0] + s1 * k23 * t[1, 0] - s23 * t[2, 0]
        r10 = -s1 * t[0, 0] + k1 * t[1, 0]
        r20 = k1 * s23 * t[0, 0] + s1 * s23 * t[1, 0] + k23 * t[2, 0]
        r02 = k1 * k23 * t[0, 2] + s1 * k23 * t[1, 2] - s23 * t[2, 2]
        r12 = -s1 * t[0, 2] + k1 * t[1, 2]
        r22 = k1 * s23 * t[0, 2] + s1 * s23 * t[1, 2] + k23 * t[2, 2]
        hyp = math.sqrt(r02 * r02 + r12 * r12)
        t4 = math.atan2(r12, r02) if hyp > 0 else 0.0
        t5 = math.atan2(hyp, r22)
        # sines and cosines from the same numbers, not from the angles (fewer transcendentals)
        s4, k4 = (r12 / hyp, r02 / hyp) if hyp > 0 else (0.0, 1.0)
        rho = math.sqrt(hyp * hyp + r22 * r22)
        s5, k5 = hyp / rho, r22 / rho
        for w in range(2):
            if w == 1:  # the flipped wrist: θ4 ± π, -θ5 (so sin θ4, cos θ4, sin θ5 change sign)
                t4 = t4 - math.pi if t4 > 0 else t4 + math.pi
                t5, s4, k4, s5 = -t5, -s4, -k4, -s5
            a00 = k4 * r00 + s4 * r10
            a10 = -s4 * r00 + k4 * r10
            t6 = math.atan2(a10, k5 * a00 - s5 * r20)
            _store(out[4 * w + i], (th1[i], th2[i], th3[i], t4, t5, t6), sign, offset, cinv, diagonal)


def _store(row, theta, sign, offset, cinv, diagonal):  # type: ignore[no-untyped-def]
    """row = cinv @ ((theta - offset) * sign): OPW angles to controller values (all NaN when
    the branch does not exist). diagonal: cinv has no off-diagonal entry (then the one term
    of each sum directly: the same operations, 0.0 + c·(θ - offset)·sign, without the scan)."""
    for k in range(6):
        if math.isnan(theta[k]):
            for j in range(6):
                row[j] = math.nan
            return
    if diagonal:
        for j in range(6):
            row[j] = 0.0 + cinv[j, j] * (theta[j] - offset[j]) * sign[j]
        return
    for j in range(6):
        acc = 0.0
        for k in range(6):
            c = cinv[j, k]
            if c != 0.0:
                acc += c * (theta[k] - offset[k]) * sign[k]
        row[j] = acc


def _opw_many(p, sign, offset, cinv, poses, out):  # type: ignore[no-untyped-def]
    for n in range(poses.shape[0]):
        _opw_one(p, sign, offset, cinv, poses[n], out[n])


# poses solved in the interpreter before the compiled form is worth its load (~0.6 s once)
_PY_POSES = 500
_ACOS = Kernel(_acos)
_OPW_ONE = Kernel(_opw_one, uses=(_ACOS, Kernel(_store)))
OPW_MANY = Kernel(_opw_many, uses=(_OPW_ONE,), threshold=_PY_POSES)


def opw_kernel_args(p: OpwParams, jmap: OpwJointMap) -> tuple[np.ndarray, ...]:
    return (
        np.array([p.a1, p.a2, p.b, p.c1, p.c2, p.c3, p.c4]), np.array(jmap.sign, dtype=float),
        np.array(jmap.offset, dtype=float), np.ascontiguousarray(jmap._cinv),
    )


def opw_solve(args: tuple[np.ndarray, ...], poses: np.ndarray) -> np.ndarray:
    """poses (N,4,4) -> (N,8,6) controller values (branch rows as in `opw.opw_ik`)."""
    poses = np.ascontiguousarray(poses, dtype=float)
    out = np.empty((len(poses), 8, 6))
    OPW_MANY(len(poses), *args, poses, out)
    return out


def opw_batch(p: OpwParams, poses: np.ndarray) -> np.ndarray:
    """OPW angles (identity joint map), for comparing with the numpy reference."""
    return opw_solve(opw_kernel_args(p, OpwJointMap()), poses)


def _wrap(x):  # type: ignore[no-untyped-def]
    """(x + π) % 2π - π; the modulo only outside [0, 2π), where it is not the identity (the
    usual case, an atan2 angle, skips the fmod: the same float either way)."""
    y = x + math.pi
    if 0.0 <= y < 2 * math.pi:
        return y - math.pi
    return y % (2 * math.pi) - math.pi


def _ur_one(p, t, out):  # type: ignore[no-untyped-def]
    """Frame-1 algebra (no 4x4 products): R16 = Rz(q234)·Ry(-q5)·Rz(q6), so the J6 axis in
    frame 1 is (-s5·cos q234, -s5·sin q234, c5), and the frame-4 origin is the flange minus
    d6 along J6 and d5 along z4 = (sin q234, -cos q234, 0)."""
    d1, a2, a3, d4, d5, d6 = p[0], p[1], p[2], p[3], p[4], p[5]
    h = math.pi / 2
    px5, py5 = t[0, 3] - d6 * t[0, 2], t[1, 3] - d6 * t[1, 2]
    psi, r = math.atan2(py5, px5), math.sqrt(px5 * px5 + py5 * py5)
    phi = _acos(d4 / r) if r > 0 else math.nan
    for si in range(2):
        q1 = psi + phi + h if si == 0 else psi - phi + h
        s1, c1 = math.sin(q1), math.cos(q1)
        p16x, p16y = c1 * t[0, 3] + s1 * t[1, 3], t[2, 3] - d1
        a5 = _acos((s1 * t[0, 3] - c1 * t[1, 3] - d4) / d6)
        zx, zy = c1 * t[0, 2] + s1 * t[1, 2], t[2, 2]
        xx, xy, xz = c1 * t[0, 0] + s1 * t[1, 0], t[2, 0], s1 * t[0, 0] - c1 * t[1, 0]
        yx, yy, yz = c1 * t[0, 1] + s1 * t[1, 1], t[2, 1], s1 * t[0, 1] - c1 * t[1, 1]
        for wi in range(2):
            q5 = a5 if wi == 0 else -a5
            s5 = math.sin(q5)
            if abs(s5) < 1e-12:  # wrist singular: only q234 + q6 matters
                q6 = 0.0
            else:
                q6 = math.atan2(-yz, xz) if s5 > 0 else math.atan2(yz, -xz)
            # first column of Rz(q234) = R16·Rz(-q6)·Ry(q5): exact given q5, q6 (no division)
            c5, s6, c6 = math.cos(q5), math.sin(q6), math.cos(q6)
            colx = c6 * c5 * xx - s6 * c5 * yx - s5 * zx
            coly = c6 * c5 * xy - s6 * c5 * yy - s5 * zy
            q234 = math.atan2(coly, colx)
            ox = p16x - d6 * zx - d5 * math.sin(q234)
            oy = p16y - d6 * zy + d5 * math.cos(q234)
            a3c = _acos((ox * ox + oy * oy - a2 * a2 - a3 * a3) / (2 * a2 * a3))
            for ei in range(2):
                q3 = a3c if ei == 0 else -a3c
                q2 = math.atan2(oy, ox) - math.atan2(a3 * math.sin(q3), a2 + a3 * math.cos(q3))
                row = 4 * si + 2 * wi + ei
                if math.isnan(q1 + q2 + q3 + q5 + q6 + q234):
                    for j in range(6):
                        out[row, j] = math.nan
                    continue
                out[row, 0], out[row, 1], out[row, 2] = _wrap(q1), _wrap(q2), _wrap(q3)
                out[row, 3], out[row, 4], out[row, 5] = _wrap(q234 - q2 - q3), _wrap(q5), _wrap(q6)


def _ur_many(p, poses, out):  # type: ignore[no-untyped-def]
    for n in range(poses.shape[0]):
        _ur_one(p, poses[n], out[n])


_UR_ONE = Kernel(_ur_one, uses=(_ACOS, Kernel(_wrap)))
UR_MANY = Kernel(_ur_many, uses=(_UR_ONE,), threshold=_PY_POSES)


def ur_solve(p_arr: np.ndarray, poses: np.ndarray) -> np.ndarray:
    poses = np.ascontiguousarray(poses, dtype=float)
    out = np.empty((len(poses), 8, 6))
    UR_MANY(len(poses), p_arr, poses, out)
    return out


def ur_batch(p: UrParams, poses: np.ndarray) -> np.ndarray:
    return ur_solve(np.array([p.d1, p.a2, p.a3, p.d4, p.d5, p.d6]), poses)
