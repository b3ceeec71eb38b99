"""Link inertias of the library arms and estimated joint torque limits.

Link masses come from the spec: a reference's own link masses where one publishes them
(KUKA's descriptions, UR's), else the data sheet's arm mass spread over the link capsules in
proportion to their volume (`spread_mass`, an estimate, uniform density). Centre of mass and
inertia tensor of every link are an estimate: a uniform solid over the link's capsules (each
a solid cylinder of the capsule's radius, as long as the capsule's segment plus 4/3 of its
radius, the length of the cylinder of the capsule's volume).

Torque limits a vendor does not publish are estimated by `estimate_effort`: twice the
largest torque of each joint over 256 poses within the limits holding the arm against gravity
and accelerating that joint alone at its acceleration limit (gravity + M_ii · a_i), with the
rated payload 0.1 m along and 0.1 m across the flange axis.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from rmot.sim.robots.spec import Segment, capsule_volume as _volume, spread_mass

__all__ = ["EFFORT_METHOD", "INERTIA_METHOD", "SPREAD_METHOD", "estimate_effort", "given_inertias", "link_inertias",
           "spread_mass"]

SPREAD_METHOD = "estimate: the data sheet's arm mass spread over the link capsules by volume (uniform density)"
INERTIA_METHOD = "estimate: uniform solid over each link's capsules (centre of mass and inertia tensor)"
EFFORT_METHOD = ("estimate: 2 x the largest gravity + own-axis inertial torque (M_ii x accel limit) over 256 poses "
                 "within the limits, rated payload 0.1 m along and 0.1 m across the flange axis")
PAYLOAD_OFFSET = (0.1, 0.0, 0.1)  # m in the flange frame, for `estimate_effort`


def _solid(seg: Segment, mass: float) -> tuple[np.ndarray, np.ndarray]:
    """(centroid (3,), inertia (3,3) about it, base axes) of a solid cylinder for the capsule."""
    p0, p1 = np.array(seg.p0), np.array(seg.p1)
    axis = p1 - p0
    length = float(np.linalg.norm(axis))
    z = axis / length if length > 1e-12 else np.array([0.0, 0.0, 1.0])
    h, r = length + 4.0 / 3.0 * seg.radius, seg.radius
    local = np.diag([mass * (3 * r * r + h * h) / 12, mass * (3 * r * r + h * h) / 12, mass * r * r / 2])
    zz = np.outer(z, z)
    inertia = local[0, 0] * (np.eye(3) - zz) + local[2, 2] * zz  # axisymmetric about z
    return (p0 + p1) / 2, inertia


def link_inertias(segments: tuple[Segment, ...], masses: tuple[float, ...],
                  joint_frames: list[np.ndarray]) -> list[pin.Inertia]:
    """One pinocchio Inertia per moving link, in its joint's frame.

    joint_frames[j-1]: joint j's frame (4,4) in the base frame at the pose the segments are
    given in. A link without capsules gets its mass as a small sphere at its joint origin."""
    out = []
    for j, (mass, frame) in enumerate(zip(masses, joint_frames), start=1):
        segs = [s for s in segments if s.joint == j]
        if not segs:
            out.append(pin.Inertia(mass, np.zeros(3), np.eye(3) * mass * 0.05 ** 2 * 0.4))
            continue
        vols = np.array([_volume(s) for s in segs])
        parts = [_solid(s, mass * v / vols.sum()) for s, v in zip(segs, vols)]
        ms = mass * vols / vols.sum()
        com = sum(m * c for m, (c, _) in zip(ms, parts)) / mass
        inertia = np.zeros((3, 3))
        for m, (c, i) in zip(ms, parts):
            d = c - com
            inertia += i + m * (float(d @ d) * np.eye(3) - np.outer(d, d))
        rot, pos = frame[:3, :3], frame[:3, 3]
        out.append(pin.Inertia(mass, rot.T @ (com - pos), rot.T @ inertia @ rot))
    return out


def given_inertias(values: tuple[tuple[float, ...], ...], masses: tuple[float, ...],
                   joint_frames: list[np.ndarray]) -> list[pin.Inertia]:
    """Inertias given in the base frame (centre of mass, tensor Ixx Ixy Ixz Iyy Iyz Izz about it,
    at the pose `joint_frames` were taken in) moved into each joint's frame."""
    out = []
    for (x, y, z, ixx, ixy, ixz, iyy, iyz, izz), mass, frame in zip(values, masses, joint_frames):
        rot, pos = frame[:3, :3], frame[:3, 3]
        tensor = np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])
        out.append(pin.Inertia(mass, rot.T @ (np.array([x, y, z]) - pos), rot.T @ tensor @ rot))
    return out


def estimate_effort(model: pin.Model, coupling: np.ndarray | None, limits: np.ndarray, accel: np.ndarray,
                    payload_kg: float, flange_in_joint: np.ndarray) -> np.ndarray:
    """Per joint: 2 x the largest |gravity torque| + M_ii · accel_i over 256 seeded poses
    within `limits` (controller values, (dof,2) rad; accel (dof,) rad/s² of the model
    joints), the payload as a point mass at PAYLOAD_OFFSET in the flange."""
    m = pin.Model(model)
    at = (flange_in_joint @ np.array([*PAYLOAD_OFFSET, 1.0]))[:3]
    m.inertias[m.njoints - 1] = m.inertias[m.njoints - 1] + pin.Inertia(payload_kg, at, np.zeros((3, 3)))
    data = m.createData()
    qs = np.random.default_rng(12).uniform(limits[:, 0], limits[:, 1], (256, m.nq))
    worst = np.zeros(m.nq)
    for q in qs:
        qm = q if coupling is None else coupling @ q
        gravity = np.abs(pin.computeGeneralizedGravity(m, data, qm))
        inertial = np.diag(pin.crba(m, data, qm)) * accel
        worst = np.maximum(worst, gravity + inertial)
    return 2.0 * worst
