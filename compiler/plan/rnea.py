"""Inverse dynamics of a serial chain, vectorised over many samples (issue #16).

pinocchio's `rnea` takes one configuration per call; the torque limits of the timing need it
at every grid point (three calls each) and the decision whether they bind at every 2 ms of a
chain, tens of thousands of calls whose Python overhead dominates. This is the same recursive
Newton-Euler algorithm (Featherstone, "Rigid Body Dynamics Algorithms", 2008, §5.3) written
once over arrays of N samples: a forward pass of spatial velocities and accelerations from the
base (gravity as a base acceleration), a backward pass of spatial forces to the base. It reads
the pinocchio Model's joint placements, joint axes, inertias and gravity, so it computes the
same torques as pinocchio.rnea (tests/plan/test_plan_torque.py compares them); a model it
cannot follow (a branching tree, a joint type other than revolute/prismatic about one axis)
is left to pinocchio, one call per sample (`Dynamics.supported`).

Conventions: per joint frame i, a motion vector is (w, v) (angular, linear velocity of the
frame's origin, both in frame i), a force (n, f) (moment about the origin, force). Frame i's
pose in its parent's frame is placement_i * joint motion (a rotation about the axis, or a
translation along it).
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["Dynamics"]

_AXES = {"X": (1.0, 0.0, 0.0), "Y": (0.0, 1.0, 0.0), "Z": (0.0, 0.0, 1.0)}


def _joint_axis(joint: Any) -> tuple[str, np.ndarray] | None:
    """('R' | 'P', unit axis in the joint frame) or None for a joint type not handled here."""
    name = joint.shortname()
    for kind, prefix in (("R", "JointModelR"), ("P", "JointModelP")):
        if name.startswith(prefix) and name[len(prefix) :] in _AXES:
            return kind, np.array(_AXES[name[len(prefix) :]])
    if name in ("JointModelRevoluteUnaligned", "JointModelPrismaticUnaligned"):
        axis = np.asarray(joint.extract().axis, dtype=float)
        if (
            abs(float(np.linalg.norm(axis)) - 1.0) > 1e-12
        ):  # pinocchio takes it as given: left to it
            return None
        return ("R" if "Revolute" in name else "P"), axis
    return None


class Dynamics:
    """Joint torques tau = RNEA(q, qd, qdd) of a pinocchio model, for (N, nq) arrays at once."""

    def __init__(self, model: Any) -> None:
        self.model = model
        self.n = int(model.njoints) - 1
        joints = [_joint_axis(model.joints[i]) for i in range(1, model.njoints)]
        serial = all(int(model.parents[i]) == i - 1 for i in range(1, model.njoints))
        self.supported = (
            serial and all(j is not None for j in joints) and model.nq == model.nv == self.n
        )
        if not self.supported:
            return
        self.kinds = [j[0] for j in joints]  # type: ignore[index]
        self.axes = [j[1] for j in joints]  # type: ignore[index]
        self.place_r = [
            np.asarray(model.jointPlacements[i].rotation) for i in range(1, model.njoints)
        ]
        self.place_p = [
            np.asarray(model.jointPlacements[i].translation) for i in range(1, model.njoints)
        ]
        self.mass = [float(model.inertias[i].mass) for i in range(1, model.njoints)]
        self.com = [np.asarray(model.inertias[i].lever) for i in range(1, model.njoints)]
        self.inertia = [
            np.asarray(model.inertias[i].inertia) for i in range(1, model.njoints)
        ]  # about the com
        self.gravity = np.asarray(model.gravity.linear, dtype=float)

    def rnea(self, q: np.ndarray, qd: np.ndarray, qdd: np.ndarray) -> np.ndarray:
        """(N, nq) torques (N·m; N for prismatic joints) at (N, nq) positions, speeds and
        accelerations."""
        q, qd, qdd = (
            np.ascontiguousarray(np.atleast_2d(np.asarray(v, dtype=float))) for v in (q, qd, qdd)
        )
        if not self.supported:
            return self._pinocchio(q, qd, qdd)
        global _KERNEL
        if _KERNEL is None:
            _KERNEL = _numba_rnea()
        if not hasattr(self, "_arrays"):
            self._arrays = (
                np.array([k == "R" for k in self.kinds]),
                np.array(self.axes),
                np.array(self.place_r),
                np.array(self.place_p),
                np.array(self.mass),
                np.array(self.com),
                np.array(self.inertia),
                self.gravity.copy(),
            )
        return np.asarray(_KERNEL(q, qd, qdd, *self._arrays))

    def _pinocchio(self, q: np.ndarray, qd: np.ndarray, qdd: np.ndarray) -> np.ndarray:
        import pinocchio as pin

        data = self.model.createData()
        return np.array(
            [pin.rnea(self.model, data, a, b, c) for a, b, c in zip(q, qd, qdd)]
        ).reshape(q.shape[0], -1)


_KERNEL = None


def _numba_rnea() -> Any:
    import numba

    @numba.njit(cache=True)
    def rnea(q, qd, qdd, revolute, axes, place_r, place_p,  # type: ignore[no-untyped-def]
             mass, com, inertia, gravity):
        # (an inner function, not a jitted one from outside: numba then caches the kernel)
        def cross(a, b, out):  # type: ignore[no-untyped-def]
            out[0] = a[1] * b[2] - a[2] * b[1]
            out[1] = a[2] * b[0] - a[0] * b[2]
            out[2] = a[0] * b[1] - a[1] * b[0]

        count, n = q.shape
        tau = np.empty((count, n))
        rot = np.empty((n, 3, 3))
        pos = np.empty((n, 3))
        f_ang = np.empty((n, 3))
        f_lin = np.empty((n, 3))
        w, v, dw, dv = np.empty(3), np.empty(3), np.empty(3), np.empty(3)
        t1, t2, t3, t4 = np.empty(3), np.empty(3), np.empty(3), np.empty(3)
        rj = np.empty((3, 3))
        nw, nv, ndw, ndv = np.empty(3), np.empty(3), np.empty(3), np.empty(3)
        h_ang, a_ang, pl, pa = np.empty(3), np.empty(3), np.empty(3), np.empty(3)
        for s in range(count):
            for k in range(3):
                w[k] = v[k] = dw[k] = 0.0
                dv[k] = -gravity[k]
            for i in range(n):
                ax = axes[i]
                # the joint's own motion: a rotation about ax by q (Rodrigues) or a translation
                if revolute[i]:
                    th = q[s, i]
                    sn, cs = np.sin(th), np.cos(th)
                    kx, ky, kz = ax[0], ax[1], ax[2]
                    c1 = 1.0 - cs
                    rj[0, 0] = cs + kx * kx * c1
                    rj[0, 1] = kx * ky * c1 - kz * sn
                    rj[0, 2] = kx * kz * c1 + ky * sn
                    rj[1, 0] = ky * kx * c1 + kz * sn
                    rj[1, 1] = cs + ky * ky * c1
                    rj[1, 2] = ky * kz * c1 - kx * sn
                    rj[2, 0] = kz * kx * c1 - ky * sn
                    rj[2, 1] = kz * ky * c1 + kx * sn
                    rj[2, 2] = cs + kz * kz * c1
                    for a in range(3):
                        pos[i, a] = place_p[i, a]
                        for b in range(3):
                            acc = 0.0
                            for c in range(3):
                                acc += place_r[i, a, c] * rj[c, b]
                            rot[i, a, b] = acc
                else:
                    for a in range(3):
                        acc = place_p[i, a]
                        for c in range(3):
                            acc += place_r[i, a, c] * ax[c] * q[s, i]
                        pos[i, a] = acc
                        for b in range(3):
                            rot[i, a, b] = place_r[i, a, b]
                # the parent's motion at the child's origin, in the child's frame
                cross(w, pos[i], t1)
                cross(dw, pos[i], t2)
                for k in range(3):
                    t1[k] += v[k]
                    t2[k] += dv[k]
                for a in range(3):
                    nw[a] = nv[a] = ndw[a] = ndv[a] = 0.0
                for a in range(3):
                    for b in range(3):
                        r = rot[i, b, a]
                        nw[a] += r * w[b]
                        nv[a] += r * t1[b]
                        ndw[a] += r * dw[b]
                        ndv[a] += r * t2[b]
                sq, sqq = qd[s, i], qdd[s, i]
                for k in range(3):
                    t3[k] = ax[k] * sq
                if revolute[i]:
                    cross(nw, t3, t1)
                    cross(nv, t3, t2)
                    for k in range(3):
                        ndw[k] += ax[k] * sqq + t1[k]
                        ndv[k] += t2[k]
                        nw[k] += t3[k]
                else:
                    cross(nw, t3, t1)
                    for k in range(3):
                        ndv[k] += ax[k] * sqq + t1[k]
                        nv[k] += t3[k]
                for k in range(3):
                    w[k], v[k], dw[k], dv[k] = nw[k], nv[k], ndw[k], ndv[k]
                # f = I a + v x* (I v), the spatial inertia about the frame's origin
                m, c = mass[i], com[i]
                cross(w, c, t1)
                for k in range(3):
                    t1[k] = m * (v[k] + t1[k])  # h_lin
                cross(dw, c, t2)
                for k in range(3):
                    t2[k] = m * (dv[k] + t2[k])  # a_lin
                for a in range(3):
                    h_ang[a] = a_ang[a] = 0.0
                    for b in range(3):
                        h_ang[a] += inertia[i, a, b] * w[b]
                        a_ang[a] += inertia[i, a, b] * dw[b]
                cross(c, t1, t3)
                cross(c, t2, t4)
                for k in range(3):
                    h_ang[k] += t3[k]
                    a_ang[k] += t4[k]
                cross(w, t1, t3)
                for k in range(3):
                    f_lin[i, k] = t2[k] + t3[k]
                cross(w, h_ang, t3)
                cross(v, t1, t4)
                for k in range(3):
                    f_ang[i, k] = a_ang[k] + t3[k] + t4[k]
            for i in range(n - 1, -1, -1):
                acc = 0.0
                for k in range(3):
                    acc += (f_ang[i, k] if revolute[i] else f_lin[i, k]) * axes[i, k]
                tau[s, i] = acc
                if i > 0:  # the force on the parent, in the parent's frame
                    for a in range(3):
                        pl[a] = pa[a] = 0.0
                        for b in range(3):
                            pl[a] += rot[i, a, b] * f_lin[i, b]
                            pa[a] += rot[i, a, b] * f_ang[i, b]
                    cross(pos[i], pl, t1)
                    for k in range(3):
                        f_lin[i - 1, k] += pl[k]
                        f_ang[i - 1, k] += pa[k] + t1[k]
        return tau

    return rnea
