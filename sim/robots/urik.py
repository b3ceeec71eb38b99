"""Closed-form IK of Universal Robots arms (three parallel axes J2-J4, offset wrist).

The standard DH chain of UR (d1, a2, a3, d4, d5, d6; α = π/2, 0, 0, π/2, -π/2, 0), solved as in
Hawkins, "Analytic inverse kinematics for the Universal Robots UR-5/UR-10 arms" (2013):
q1 from the wrist point p05 (two), q5 from the flange height along J2's axis (two), q6 from
the flange axes, then a planar 2R problem for q2, q3 (two) and q4 = q234 - q2 - q3.
"""

from __future__ import annotations

import numpy as np

from rmot.lang.record import record

__all__ = ["UrParams", "ur_ik", "ur_fk", "ur_branch_quantities"]


@record(slots=True)
class UrParams:
    """UR DH lengths in metres (a2, a3 negative as in UR's table)."""

    d1: float
    a2: float
    a3: float
    d4: float
    d5: float
    d6: float

    def dh(self) -> tuple[tuple[float, float, float], ...]:
        """(d, a, alpha) per joint."""
        h = np.pi / 2
        return ((self.d1, 0, h), (0, self.a2, 0), (0, self.a3, 0), (self.d4, 0, h), (self.d5, 0, -h), (self.d6, 0, 0))


def _dh_batch(theta: np.ndarray, d: float, a: float, alpha: float) -> np.ndarray:
    c, s = np.cos(theta), np.sin(theta)
    ca, sa = np.cos(alpha), np.sin(alpha)
    m = np.zeros(theta.shape + (4, 4))
    m[..., 0, :] = np.stack([c, -s * ca, s * sa, a * c], -1)
    m[..., 1, :] = np.stack([s, c * ca, -c * sa, a * s], -1)
    m[..., 2, 1], m[..., 2, 2], m[..., 2, 3] = sa, ca, d
    m[..., 3, 3] = 1.0
    return m


def ur_fk(p: UrParams, q: np.ndarray) -> np.ndarray:
    """Plain DH product; q: (N,6) -> (N,4,4). Used by tests as an independent reference."""
    q = np.atleast_2d(q)
    out = np.broadcast_to(np.eye(4), (len(q), 4, 4)).copy()
    for i, (d, a, al) in enumerate(p.dh()):
        out = out @ _dh_batch(q[:, i], d, a, al)
    return out


def _inv(t: np.ndarray) -> np.ndarray:
    out = np.zeros_like(t)
    rt = np.swapaxes(t[..., :3, :3], -1, -2)
    out[..., :3, :3] = rt
    out[..., :3, 3] = -np.einsum("...ij,...j->...i", rt, t[..., :3, 3])
    out[..., 3, 3] = 1.0
    return out


def ur_ik(p: UrParams, poses: np.ndarray) -> np.ndarray:
    """All 8 solutions; poses: (N,4,4) -> (N,8,6). Row = 4·shoulder + 2·wrist + elbow with
    shoulder 0 = front, wrist 0 = noflip (q5 > 0), elbow 0 = up (q3 > 0); NaN where none.
    The readable reference: `fastik` is the compiled one (and the one exact at q5 = 0)."""
    with np.errstate(invalid="ignore", divide="ignore"):
        return _solve(p, poses)


def _solve(p: UrParams, poses: np.ndarray) -> np.ndarray:
    n = len(poses)
    rot, pos = poses[:, :3, :3], poses[:, :3, 3]
    p05 = pos - p.d6 * rot[:, :, 2]
    psi = np.arctan2(p05[:, 1], p05[:, 0])
    r = np.hypot(p05[:, 0], p05[:, 1])
    phi = np.arccos(_clip(p.d4 / r))
    q1 = np.stack([psi + phi + np.pi / 2, psi - phi + np.pi / 2], -1)  # (N,2)
    s1, c1 = np.sin(q1), np.cos(q1)
    height = pos[:, None, 0] * s1 - pos[:, None, 1] * c1  # flange along J2's axis
    acos5 = np.arccos(_clip((height - p.d4) / p.d6))
    q5 = np.stack([acos5, -acos5], -1)  # (N,2,2)
    s5 = np.sin(q5)
    xz = rot[:, None, 0, 0] * s1 - rot[:, None, 1, 0] * c1  # z1·x6
    yz = rot[:, None, 0, 1] * s1 - rot[:, None, 1, 1] * c1  # z1·y6
    q6 = np.arctan2(-yz[..., None] / s5, xz[..., None] / s5)
    q6 = np.where(np.abs(s5) < 1e-12, 0.0, q6)  # wrist singular: q4 + q6 only matters
    q1b = np.broadcast_to(q1[..., None], q5.shape)
    t01 = _dh_batch(q1b, p.d1, 0.0, np.pi / 2)
    t45 = _dh_batch(q5, p.d5, 0.0, -np.pi / 2)
    t56 = _dh_batch(q6, p.d6, 0.0, 0.0)
    t14 = _inv(t01) @ poses[:, None, None] @ _inv(t45 @ t56)
    px, py = t14[..., 0, 3], t14[..., 1, 3]
    q234 = np.arctan2(t14[..., 1, 0], t14[..., 0, 0])
    c3 = _clip((px * px + py * py - p.a2 * p.a2 - p.a3 * p.a3) / (2 * p.a2 * p.a3))
    acos3 = np.arccos(c3)
    q3 = np.stack([acos3, -acos3], -1)  # (N,2,2,2)
    q2 = np.arctan2(py, px)[..., None] - np.arctan2(p.a3 * np.sin(q3), p.a2 + p.a3 * np.cos(q3))
    q4 = q234[..., None] - q2 - q3
    full = [np.broadcast_to(x[..., None], q3.shape) for x in (q1b, q5, q6)]
    sol = np.stack([full[0], q2, q3, q4, full[1], full[2]], -1)  # (N,2,2,2,6)
    return _wrap(sol.reshape(n, 8, 6))


def _wrap(q: np.ndarray) -> np.ndarray:
    return (q + np.pi) % (2 * np.pi) - np.pi


def _clip(x: np.ndarray) -> np.ndarray:
    return np.where(np.abs(x) <= 1 + 1e-12, np.clip(x, -1.0, 1.0), np.nan)


def ur_branch_quantities(p: UrParams, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Signed quantities whose signs name the branch of q (..., 6).

    shoulder: the wrist point p05 projected on -x1 (the direction the arm reaches at q2 = 0,
      since a2 < 0), in m: > 0 front. It is ± r·sin(φ) of the q1 solution, 0 when p05 lies
      on the cylinder of radius d4 around J1 (the shoulder singularity).
    elbow: sin(q3) (> 0 up: the forearm turned toward the front of the upper arm).
    wrist: sin(q5) (< 0 flip).
    """
    q = np.asarray(q, dtype=float)
    # p05 in frame-1 coordinates, x component: a2·c2 + a3·c23 + d5·(x component of z4 = sin q234)
    c23 = np.cos(q[..., 1] + q[..., 2])
    s234 = np.sin(q[..., 1] + q[..., 2] + q[..., 3])
    x1 = p.a2 * np.cos(q[..., 1]) + p.a3 * c23 + p.d5 * s234
    return -x1, np.sin(q[..., 2]), np.sin(q[..., 4])
