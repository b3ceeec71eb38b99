# mypy: disable-error-code="no-untyped-call"
# (numba kernels: untyped on purpose, numba types them; they call each other by plain name)
"""A compiled damped-least-squares loop over a serial chain (the arrays of `chain.Chain`).

The same iteration as `numeric.dls` (which calls pinocchio per step); compiled, one step
costs well under a microsecond instead of ~10 µs of Python overhead. The chain arrays come
from the pinocchio model, and every solution is still verified with pinocchio's FK.
World-frame error: position difference and the rotation vector of R*·Rᵀ; geometric
Jacobian from the joint axes and origins.
"""

from __future__ import annotations

import math

import numpy as np

from rmot.lang.jit import Kernel

__all__ = ["DLS_CHAIN", "JOINT_FRAMES", "dls_chain", "joint_frames_batch"]


def _rotation(axis, angle):  # type: ignore[no-untyped-def]
    c, s = math.cos(angle), math.sin(angle)
    x, y, z = axis[0], axis[1], axis[2]
    v = 1.0 - c
    m = np.empty((3, 3))
    m[0, 0], m[0, 1], m[0, 2] = c + x * x * v, x * y * v - z * s, x * z * v + y * s
    m[1, 0], m[1, 1], m[1, 2] = y * x * v + z * s, c + y * y * v, y * z * v - x * s
    m[2, 0], m[2, 1], m[2, 2] = z * x * v - y * s, z * y * v + x * s, c + z * z * v
    return m


def _rot_log(r):  # type: ignore[no-untyped-def]
    """The rotation vector of r (axis · angle)."""
    out = np.empty(3)
    cos = min(1.0, max(-1.0, (r[0, 0] + r[1, 1] + r[2, 2] - 1.0) / 2.0))
    angle = math.acos(cos)
    vx, vy, vz = r[2, 1] - r[1, 2], r[0, 2] - r[2, 0], r[1, 0] - r[0, 1]
    if angle < 1e-6:
        out[0], out[1], out[2] = 0.5 * vx, 0.5 * vy, 0.5 * vz
        return out
    if angle < math.pi - 1e-6:
        k = angle / (2.0 * math.sin(angle))
        out[0], out[1], out[2] = k * vx, k * vy, k * vz
        return out
    # near π: the axis is the largest column of (r + I) / 2
    i = 0
    for j in range(1, 3):
        if r[j, j] > r[i, i]:
            i = j
    axis = np.empty(3)
    for j in range(3):
        axis[j] = (r[j, i] + (1.0 if j == i else 0.0)) / 2.0
    n = math.sqrt(axis[0] ** 2 + axis[1] ** 2 + axis[2] ** 2)
    sign = 1.0 if (vx * axis[0] + vy * axis[1] + vz * axis[2]) >= 0 else -1.0
    for j in range(3):
        out[j] = sign * angle * axis[j] / n
    return out


def _mul4(a, b):  # type: ignore[no-untyped-def]
    out = np.empty((4, 4))
    for i in range(4):
        for j in range(4):
            out[i, j] = a[i, 0] * b[0, j] + a[i, 1] * b[1, j] + a[i, 2] * b[2, j] + a[i, 3] * b[3, j]
    return out


def _fk_jac(placements, axes, prismatic, flange, qm, jac):  # type: ignore[no-untyped-def]
    """Flange pose (4,4) of model values qm; fills the world-frame geometric Jacobian."""
    n = qm.shape[0]
    t = np.eye(4)
    origins = np.empty((n, 3))
    waxes = np.empty((n, 3))
    motion = np.eye(4)
    for i in range(n):
        t = _mul4(t, placements[i])
        ax = axes[i]
        if prismatic[i]:
            motion[:3, :3] = np.eye(3)
            motion[0, 3], motion[1, 3], motion[2, 3] = ax[0] * qm[i], ax[1] * qm[i], ax[2] * qm[i]
        else:
            motion[:3, :3] = _rotation(ax, qm[i])
            motion[0, 3] = motion[1, 3] = motion[2, 3] = 0.0
        for r in range(3):
            waxes[i, r] = t[r, 0] * ax[0] + t[r, 1] * ax[1] + t[r, 2] * ax[2]
        t = _mul4(t, motion)
        origins[i, 0], origins[i, 1], origins[i, 2] = t[0, 3], t[1, 3], t[2, 3]
    tf = _mul4(t, flange)
    for i in range(n):
        a = waxes[i]
        if prismatic[i]:
            jac[0, i], jac[1, i], jac[2, i] = a[0], a[1], a[2]
            jac[3, i] = jac[4, i] = jac[5, i] = 0.0
        else:
            d = tf[:3, 3] - origins[i]
            jac[0, i] = a[1] * d[2] - a[2] * d[1]
            jac[1, i] = a[2] * d[0] - a[0] * d[2]
            jac[2, i] = a[0] * d[1] - a[1] * d[0]
            jac[3, i], jac[4, i], jac[5, i] = a[0], a[1], a[2]
    return tf


def dls_chain(placements, axes, prismatic, flange, coupling, target, q0, tol, max_iter, damping2, max_step):  # type: ignore[no-untyped-def]
    """DLS from q0 (controller values) -> (q, final error norm)."""
    n = q0.shape[0]
    q = q0.copy()
    jac = np.empty((6, n))
    err = np.empty(6)
    rerr = np.empty((3, 3))
    a = np.empty((6, 6))
    norm = np.inf
    coupled = not np.array_equal(coupling, np.eye(n))
    for _ in range(max_iter):
        qm = coupling @ q if coupled else q
        tf = _fk_jac(placements, axes, prismatic, flange, qm, jac)
        for r in range(3):
            err[r] = target[r, 3] - tf[r, 3]
            for c in range(3):
                rerr[r, c] = target[r, 0] * tf[c, 0] + target[r, 1] * tf[c, 1] + target[r, 2] * tf[c, 2]
        err[3:] = _rot_log(rerr)
        norm = math.sqrt(np.sum(err * err))
        if norm < tol:
            break
        j = np.ascontiguousarray(jac @ coupling) if coupled else jac
        for r in range(6):
            for c in range(r, 6):
                acc = 0.0
                for k in range(n):
                    acc += j[r, k] * j[c, k]
                a[r, c] = a[c, r] = acc
            a[r, r] += damping2
        y = np.linalg.solve(a, err)
        step = np.zeros(n)
        for k in range(n):
            for r in range(6):
                step[k] += j[r, k] * y[r]
        biggest = np.max(np.abs(step))
        if biggest > max_step:
            step *= max_step / biggest
        q += step
    return q, norm


def joint_frames_batch(placements, axes, prismatic, qm, out):  # type: ignore[no-untyped-def]
    """out[k, i] = joint i's frame (after its motion) in the base, for model values qm[k]."""
    n = placements.shape[0]
    motion = np.eye(4)
    for k in range(qm.shape[0]):
        t = np.eye(4)
        for i in range(n):
            t = _mul4(t, placements[i])
            ax = axes[i]
            if prismatic[i]:
                motion[:3, :3] = np.eye(3)
                motion[0, 3], motion[1, 3], motion[2, 3] = ax[0] * qm[k, i], ax[1] * qm[k, i], ax[2] * qm[k, i]
            else:
                motion[:3, :3] = _rotation(ax, qm[k, i])
                motion[0, 3] = motion[1, 3] = motion[2, 3] = 0.0
            t = _mul4(t, motion)
            out[k, i] = t


# Compiled once a process has done this much work in the interpreter (lang/jit.py): a
# numeric IK run costs ~50 iterations, a configuration of FK one pass over the joints.
_ROTATION, _MUL4 = Kernel(_rotation), Kernel(_mul4)
_FK_JAC = Kernel(_fk_jac, uses=(_MUL4, _ROTATION))
DLS_CHAIN = Kernel(dls_chain, uses=(_FK_JAC, Kernel(_rot_log)), threshold=0)
# configurations (chain.joint_frames runs them in numpy until then: ~6 µs each, ~0.15 s)
JOINT_FRAMES = Kernel(joint_frames_batch, uses=(_MUL4, _ROTATION), threshold=25_000)
