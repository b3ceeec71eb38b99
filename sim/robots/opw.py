"""Closed-form IK of 6R arms with an ortho-parallel base and a spherical wrist (OPW).

The parametrisation is Brandstötter, Angerer, Hofbaur, "An analytical solution of the
inverse kinematics problem of industrial serial manipulators with an ortho-parallel basis
and a spherical wrist" (Austrian Robotics Workshop 2014), as in ROS-Industrial
opw_kinematics. In the OPW joint space (θ) the arm stands upright at θ = 0: J1 about +z
through the origin, J2 about +y at (a1, b, c1), upper arm c2 up to J3 (about +y), forearm
offset a2 (forward) and length c3 up to the wrist centre, flange c4 further along J6. At
θ = 0 the flange frame equals the base frame orientation.

Vendor joint values q relate to θ by θ = sign·(C q) + offset (C the identity except for
Fanuc's J2/J3 coupling), see `OpwJointMap`.
"""

from __future__ import annotations

import math
from dataclasses import field

import numpy as np

from rmot.sim.robots.dh import DHRow, DHTable
from rmot.lang.record import record

__all__ = ["OpwParams", "OpwJointMap", "opw_dh_table", "opw_ik", "opw_fk", "opw_shoulder_elbow"]


@record(slots=True)
class OpwParams:
    """The seven OPW lengths in metres (see the module docstring for their meaning)."""

    a1: float
    a2: float
    b: float
    c1: float
    c2: float
    c3: float
    c4: float

    @property
    def psi3(self) -> float:
        """Angle of the wrist centre seen from J3 relative to the forearm axis (rad)."""
        return math.atan2(self.a2, self.c3)

    @property
    def forearm(self) -> float:
        """Distance J3 to wrist centre (m)."""
        return math.hypot(self.a2, self.c3)


@record(slots=True)
class OpwJointMap:
    """θ = sign · (coupling @ q) + offset, per joint (rad)."""

    sign: tuple[float, ...] = (1.0,) * 6
    offset: tuple[float, ...] = (0.0,) * 6
    coupling: tuple[tuple[float, ...], ...] | None = None  # (6,6) rows; None = identity
    _c: np.ndarray = field(init=False, repr=False, compare=False)
    _cinv: np.ndarray = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        c = np.eye(6) if self.coupling is None else np.array(self.coupling, dtype=float)
        object.__setattr__(self, "_c", c)
        object.__setattr__(self, "_cinv", np.linalg.inv(c))

    def to_theta(self, q: np.ndarray) -> np.ndarray:
        """q: (..., 6) controller values -> (..., 6) OPW angles."""
        return np.asarray(self.sign) * (q @ self._c.T) + np.asarray(self.offset)

    def from_theta(self, theta: np.ndarray) -> np.ndarray:
        """theta: (..., 6) OPW angles -> (..., 6) controller values."""
        u = (theta - np.asarray(self.offset)) * np.asarray(self.sign)
        return u @ self._cinv.T


def opw_dh_table(p: OpwParams, jmap: OpwJointMap) -> DHTable:
    """A standard DH table equal to the OPW chain, in the model variables u = C q.

    Derived by placing DH frame i on joint i+1's axis: the DH θ is the OPW θ plus a fixed
    offset (-π/2 on J2, +π/2 on J3), the flange is DH frame 6.
    """
    dh_off = (0.0, -math.pi / 2, math.pi / 2, 0.0, 0.0, 0.0)
    geometry = (
        (p.c1, p.a1, -math.pi / 2), (p.b, p.c2, 0.0), (0.0, p.a2, math.pi / 2),
        (p.c3, 0.0, -math.pi / 2), (0.0, 0.0, math.pi / 2), (p.c4, 0.0, 0.0),
    )
    rows = tuple(
        DHRow(d=d, a=a, alpha=al, offset=jmap.offset[i] + dh_off[i], sign=jmap.sign[i])
        for i, (d, a, al) in enumerate(geometry)
    )
    return DHTable(rows)


def opw_fk(p: OpwParams, theta: np.ndarray) -> np.ndarray:
    """Independent closed-form FK in OPW angles; theta: (N,6) -> (N,4,4). Used by tests."""
    t = np.atleast_2d(theta)
    s, c = np.sin(t), np.cos(t)
    k, psi = p.forearm, p.psi3
    cx1 = p.c2 * s[:, 1] + k * np.sin(t[:, 1] + t[:, 2] + psi) + p.a1
    cz1 = p.c2 * c[:, 1] + k * np.cos(t[:, 1] + t[:, 2] + psi)
    centre = np.stack([cx1 * c[:, 0] - p.b * s[:, 0], cx1 * s[:, 0] + p.b * c[:, 0], cz1 + p.c1], axis=-1)
    r0c = _rz(t[:, 0]) @ _ry(t[:, 1] + t[:, 2])
    rce = _rz(t[:, 3]) @ _ry(t[:, 4]) @ _rz(t[:, 5])
    r = r0c @ rce
    out = np.zeros((len(t), 4, 4))
    out[:, :3, :3] = r
    out[:, :3, 3] = centre + p.c4 * r[:, :, 2]
    out[:, 3, 3] = 1.0
    return out


def _rz(t: np.ndarray) -> np.ndarray:
    c, s = np.cos(t), np.sin(t)
    z, o = np.zeros_like(t), np.ones_like(t)
    return np.stack([np.stack([c, -s, z], -1), np.stack([s, c, z], -1), np.stack([z, z, o], -1)], -2)


def _ry(t: np.ndarray) -> np.ndarray:
    c, s = np.cos(t), np.sin(t)
    z, o = np.zeros_like(t), np.ones_like(t)
    return np.stack([np.stack([c, z, s], -1), np.stack([z, o, z], -1), np.stack([-s, z, c], -1)], -2)


def opw_ik(p: OpwParams, poses: np.ndarray) -> np.ndarray:
    """All 8 OPW solutions of each flange pose; poses: (N,4,4) -> (N,8,6) OPW angles.

    Branch order: [front/back] x [elbow up/down] for wrist i (rows 0-3), then the same four
    with the flipped wrist (rows 4-7). NaN where a branch does not exist.
    """
    with np.errstate(invalid="ignore", divide="ignore"):
        arm = _arm_solutions(p, poses)  # (N,4,3)
        return _add_wrist(poses, arm)


def _arm_solutions(p: OpwParams, poses: np.ndarray) -> np.ndarray:
    rot, pos = poses[:, :3, :3], poses[:, :3, 3]
    c = pos - p.c4 * rot[:, :, 2]
    cx, cy, cz = c[:, 0], c[:, 1], c[:, 2]
    nx1 = np.sqrt(cx * cx + cy * cy - p.b * p.b) - p.a1
    tmp1 = np.arctan2(cy, cx)
    tmp2 = np.arctan2(p.b, nx1 + p.a1)
    t1_front, t1_back = tmp1 - tmp2, tmp1 + tmp2 - np.pi
    dz = cz - p.c1
    s1_2 = nx1 * nx1 + dz * dz
    s2_2 = (nx1 + 2 * p.a1) ** 2 + dz * dz
    kappa_2 = p.a2 * p.a2 + p.c3 * p.c3
    c2_2 = p.c2 * p.c2
    s1, s2 = np.sqrt(s1_2), np.sqrt(s2_2)
    tmp13 = np.arccos(_clip((s1_2 + c2_2 - kappa_2) / (2 * s1 * p.c2)))
    tmp14 = np.arctan2(nx1, dz)
    tmp15 = np.arccos(_clip((s2_2 + c2_2 - kappa_2) / (2 * s2 * p.c2)))
    tmp16 = np.arctan2(nx1 + 2 * p.a1, dz)
    tmp9 = 2 * p.c2 * math.sqrt(kappa_2)
    tmp11 = np.arccos(_clip((s1_2 - c2_2 - kappa_2) / tmp9))
    tmp12 = np.arccos(_clip((s2_2 - c2_2 - kappa_2) / tmp9))
    psi = p.psi3
    t1 = np.stack([t1_front, t1_front, t1_back, t1_back], -1)
    t2 = np.stack([-tmp13 + tmp14, tmp13 + tmp14, -tmp15 - tmp16, tmp15 - tmp16], -1)
    t3 = np.stack([tmp11 - psi, -tmp11 - psi, tmp12 - psi, -tmp12 - psi], -1)
    return np.stack([t1, t2, t3], -1)


def _clip(x: np.ndarray) -> np.ndarray:
    """Round-off just outside [-1, 1] still counts as reachable (the stretched arm)."""
    return np.where(np.abs(x) <= 1 + 1e-12, np.clip(x, -1.0, 1.0), np.nan)


def _add_wrist(poses: np.ndarray, arm: np.ndarray) -> np.ndarray:
    n = len(poses)
    t1, t23 = arm[..., 0], arm[..., 1] + arm[..., 2]
    r0c = _rz(t1.reshape(-1)) @ _ry(t23.reshape(-1))  # (4N,3,3)
    rce = np.swapaxes(r0c, -1, -2) @ np.repeat(poses[:, None, :3, :3], 4, axis=1).reshape(-1, 3, 3)
    t4 = np.arctan2(rce[:, 1, 2], rce[:, 0, 2])
    t5 = np.arctan2(np.hypot(rce[:, 0, 2], rce[:, 1, 2]), rce[:, 2, 2])
    t6 = _last_angle(rce, t4, t5)
    t4b = np.where(t4 > 0, t4 - np.pi, t4 + np.pi)
    t6b = _last_angle(rce, t4b, -t5)
    arm_flat = arm.reshape(-1, 3)
    a = np.concatenate([arm_flat, np.stack([t4, t5, t6], -1)], -1).reshape(n, 4, 6)
    b = np.concatenate([arm_flat, np.stack([t4b, -t5, t6b], -1)], -1).reshape(n, 4, 6)
    return np.concatenate([a, b], axis=1)


def _last_angle(rce: np.ndarray, t4: np.ndarray, t5: np.ndarray) -> np.ndarray:
    """θ6 from Rz(θ4)·Ry(θ5)·Rz(θ6) = rce given θ4, θ5: exact even at the wrist singularity."""
    m = np.swapaxes(_rz(t4) @ _ry(t5), -1, -2) @ rce
    return np.arctan2(m[:, 1, 0], m[:, 0, 0])


def opw_shoulder_elbow(p: OpwParams, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Signed branch quantities of OPW angles theta (..., 6).

    shoulder: the wrist centre's distance in front of the J1 axis along the arm's forward
      direction (m): > 0 front, < 0 back, 0 at the shoulder singularity.
    elbow: sin(θ3 + ψ3), > 0 when the wrist centre lies in front of the line J2-J3 (the
      lower arm), 0 when the arm is stretched or folded (the elbow singularity).
    """
    t2, t3 = theta[..., 1], theta[..., 2]
    front = p.a1 + p.c2 * np.sin(t2) + p.forearm * np.sin(t2 + t3 + p.psi3)
    return front, np.sin(t3 + p.psi3)
