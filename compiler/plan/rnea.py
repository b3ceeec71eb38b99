"""Inverse dynamics of a serial chain, vectorised over many samples.

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
        return _rnea(q, qd, qdd, *self._arrays)

    def _pinocchio(self, q: np.ndarray, qd: np.ndarray, qdd: np.ndarray) -> np.ndarray:
        import pinocchio as pin  # late: pinocchio is heavy or optional, loaded only where used

        data = self.model.createData()
        return np.array(
            [pin.rnea(self.model, data, a, b, c) for a, b, c in zip(q, qd, qdd)]
        ).reshape(q.shape[0], -1)


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """np.cross of (N, 3) or (3,) vectors, the same numbers at a fraction of its overhead (it was
    a third of a torque-limited timing)."""
    out = np.empty(np.broadcast_shapes(np.shape(a), np.shape(b)))
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    np.subtract(a1 * b2, a2 * b1, out=out[..., 0])
    np.subtract(a2 * b0, a0 * b2, out=out[..., 1])
    np.subtract(a0 * b1, a1 * b0, out=out[..., 2])
    return out


def _rodrigues(place: np.ndarray, axis: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(P, P K, P k k^T) for P @ R(k, q) = cos q (P - P k k^T) + sin q P K + P k k^T."""
    kx, ky, kz = axis
    skew = np.array([[0.0, -kz, ky], [kz, 0.0, -kx], [-ky, kx, 0.0]])
    return place, place @ skew, place @ np.outer(axis, axis)


def _rnea(q: np.ndarray, qd: np.ndarray, qdd: np.ndarray, revolute: np.ndarray, axes: np.ndarray,
          place_r: np.ndarray, place_p: np.ndarray, mass: np.ndarray, com: np.ndarray,
          inertia: np.ndarray, gravity: np.ndarray) -> np.ndarray:
    """The recursion over joints, each step vectorised over the N samples (numpy, no numba: a
    short check of a rated arm must not wait ~0.6 s for numba to load, and over samples numpy
    is within a few times of compiled code)."""
    count, n = q.shape
    cross = _cross
    w = np.zeros((count, 3))
    v = np.zeros((count, 3))
    dw = np.zeros((count, 3))
    dv = np.broadcast_to(-gravity, (count, 3)).copy()
    rots, poss, f_lin, f_ang = [], [], [], []
    rodrigues = [_rodrigues(place_r[i], axes[i]) for i in range(n)]
    for i in range(n):
        ax = axes[i]
        if revolute[i]:
            # place_r @ R(axis, q) by Rodrigues: cos q * P + sin q * (P K) + (1 - cos q) * P k k^T,
            # three constant matrices scaled per sample (an einsum over N 3x3 products was
            # the largest cost of a torque-limited timing)
            sn, cs = np.sin(q[:, i]), np.cos(q[:, i])
            p_cos, p_sin, p_rest = rodrigues[i]
            rot = (cs[:, None, None] * (p_cos - p_rest) + sn[:, None, None] * p_sin
                   + p_rest)
            pos = np.broadcast_to(place_p[i], (count, 3))
        else:
            rot = np.broadcast_to(place_r[i], (count, 3, 3))
            pos = place_p[i] + np.outer(q[:, i], place_r[i] @ ax)
        # the parent's motion at the child's origin, in the child's frame
        t1 = v + cross(w, pos)
        t2 = dv + cross(dw, pos)
        nw = np.einsum("nba,nb->na", rot, w)
        nv = np.einsum("nba,nb->na", rot, t1)
        ndw = np.einsum("nba,nb->na", rot, dw)
        ndv = np.einsum("nba,nb->na", rot, t2)
        t3 = np.outer(qd[:, i], ax)
        along = np.outer(qdd[:, i], ax)
        if revolute[i]:
            ndw = ndw + along + cross(nw, t3)
            ndv = ndv + cross(nv, t3)
            nw = nw + t3
        else:
            ndv = ndv + along + cross(nw, t3)
            nv = nv + t3
        w, v, dw, dv = nw, nv, ndw, ndv
        # f = I a + v x* (I v), the spatial inertia about the frame's origin
        m, c = mass[i], com[i]
        h_lin = m * (v + cross(w, c))
        a_lin = m * (dv + cross(dw, c))
        h_ang = w @ inertia[i].T + cross(c, h_lin)
        a_ang = dw @ inertia[i].T + cross(c, a_lin)
        f_lin.append(a_lin + cross(w, h_lin))
        f_ang.append(a_ang + cross(w, h_ang) + cross(v, h_lin))
        rots.append(rot)
        poss.append(pos)
    return _joint_torques(f_lin, f_ang, rots, poss, revolute, axes)


def _joint_torques(f_lin: list[np.ndarray], f_ang: list[np.ndarray], rots: list[np.ndarray],
                   poss: list[np.ndarray], revolute: np.ndarray, axes: np.ndarray) -> np.ndarray:
    """The backward pass: each link's force (in its frame) projected on its joint axis, then
    added to its parent's in the parent's frame. f_lin and f_ang are summed in place."""
    count, n = f_lin[0].shape[0], len(f_lin)
    tau = np.empty((count, n))
    for i in range(n - 1, -1, -1):
        tau[:, i] = (f_ang[i] if revolute[i] else f_lin[i]) @ axes[i]
        if i > 0:
            pl = np.einsum("nab,nb->na", rots[i], f_lin[i])
            pa = np.einsum("nab,nb->na", rots[i], f_ang[i])
            f_lin[i - 1] = f_lin[i - 1] + pl
            f_ang[i - 1] = f_ang[i - 1] + pa + _cross(poss[i], pl)
    return tau
