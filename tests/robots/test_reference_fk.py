"""Every library arm against an independent reference chain (tests/robots/reference_arms.py).

The reference chain is composed here with plain numpy from the reference's own numbers
(URDF joint origins and axes, UR's calibration yaml); the pendant's joint values are mapped
to the reference's with the mapping its driver states. The library FK, from the controller
frame to the flange, must agree within 0.01 mm and 1e-6 rad at random joint values.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from rmot.sim.robots import list_robots, load_robot
from reference_arms import ARMS, BY_NAME, KUKA_INERTIALS, RefArm
from reference_arms_abb import ABB_ARMS
from reference_arms_fanuc import FANUC_ARMS
from reference_arms_motoman import MOTOMAN_ARMS
from reference_arms_staubli import STAUBLI_ARMS

EVERY_ARM = ARMS + ABB_ARMS + FANUC_ARMS + MOTOMAN_ARMS + STAUBLI_ARMS


def _rpy(r: float, p: float, y: float) -> np.ndarray:
    """URDF rpy: R = Rz(y) Ry(p) Rx(r)."""
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    rx = np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
    ry = np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
    rz = np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]])
    return rz @ ry @ rx


def _origin(xyz, rpy) -> np.ndarray:  # type: ignore[no-untyped-def]
    t = np.eye(4)
    t[:3, :3] = _rpy(*rpy)
    t[:3, 3] = xyz
    return t


def _about(axis, angle: float) -> np.ndarray:  # type: ignore[no-untyped-def]
    """Rodrigues' rotation about a unit axis."""
    k = np.asarray(axis, dtype=float)
    k = k / np.linalg.norm(k)
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    t = np.eye(4)
    t[:3, :3] = np.eye(3) + math.sin(angle) * kx + (1 - math.cos(angle)) * kx @ kx
    return t


def reference_fk(arm: RefArm, q_pendant: np.ndarray) -> np.ndarray:
    """The flange in the controller frame, composed from the reference's numbers."""
    m = arm.mapping
    q = np.asarray(m.sign) * q_pendant + np.radians(m.offset_deg)
    q[2] += m.j23 * q_pendant[1]
    t = np.eye(4)
    for xyz, rpy in arm.pre:
        t = t @ _origin(xyz, rpy)
    for (xyz, rpy, axis), qi in zip(arm.joints, q):
        t = t @ _origin(xyz, rpy) @ _about(axis, qi)
    for xyz, rpy in arm.tool:
        t = t @ _origin(xyz, rpy)
    if arm.controller is not None:
        t = np.linalg.inv(_origin(*arm.controller)) @ t
    return t


def _errors(arm: RefArm, n: int, seed: int) -> tuple[float, float]:
    """(max position error mm, max orientation error rad) over n random pendant values."""
    r = load_robot(arm.name)
    qs = np.random.default_rng(seed).uniform(r.joint_limits[:, 0], r.joint_limits[:, 1], (n, r.dof))
    pos = ang = 0.0
    for q in qs:
        a, b = r.fk(q), reference_fk(arm, q)
        pos = max(pos, float(np.linalg.norm(a[:3, 3] - b[:3, 3])) * 1000)
        rel = a[:3, :3].T @ b[:3, :3]
        skew = np.array([rel[2, 1] - rel[1, 2], rel[0, 2] - rel[2, 0], rel[1, 0] - rel[0, 1]]) / 2
        ang = max(ang, math.atan2(float(np.linalg.norm(skew)), (np.trace(rel) - 1) / 2))  # rotation angle
    return pos, ang


def test_every_library_arm_has_a_reference():
    """No library arm without an independent reference (the Puma's is Corke's DH table in
    test_library.py); no reference for an arm the library does not have."""
    assert {a.name for a in EVERY_ARM} | {"puma560"} == set(list_robots())


@pytest.mark.parametrize("arm", EVERY_ARM, ids=lambda a: a.name)
def test_library_fk_equals_the_reference_chain(arm):
    """Library FK = the reference chain, controller frame to flange, within 0.01 mm / 1e-6 rad."""
    pos, ang = _errors(arm, 60, seed=12)
    assert pos < 0.01, f"{arm.name}: {pos:.4f} mm off {arm.source}"
    assert ang < 1e-6, f"{arm.name}: {ang:.2e} rad off {arm.source}"


def _link_frames(arm: RefArm, q_pendant: np.ndarray) -> list[np.ndarray]:
    """Each moving link's URDF frame in the controller frame."""
    m = arm.mapping
    q = np.asarray(m.sign) * q_pendant + np.radians(m.offset_deg)
    q[2] += m.j23 * q_pendant[1]
    t = np.eye(4)
    for xyz, rpy in arm.pre:
        t = t @ _origin(xyz, rpy)
    c = np.eye(4) if arm.controller is None else np.linalg.inv(_origin(*arm.controller))
    out = []
    for (xyz, rpy, axis), qi in zip(arm.joints, q):
        t = t @ _origin(xyz, rpy) @ _about(axis, qi)
        out.append(c @ t)
    return out


@pytest.mark.parametrize("name", sorted(KUKA_INERTIALS))
def test_kuka_link_inertias_equal_kukas_urdf_inertials(name):
    """Each link's mass, centre of mass and inertia tensor in the base frame (library model at
    random joint values) equal the kroshu URDF's <inertial> carried through its chain."""
    import pinocchio as pin

    arm, r = BY_NAME[name], load_robot(name)
    data = r.model.createData()
    for q in np.random.default_rng(5).uniform(r.joint_limits[:, 0], r.joint_limits[:, 1], (8, r.dof)):
        pin.forwardKinematics(r.model, data, r.to_model(q))
        for j, (frame, (mass, xyz, rpy, i6)) in enumerate(zip(_link_frames(arm, q), KUKA_INERTIALS[name]), start=1):
            ref = frame @ _origin(xyz, rpy)
            xx, xy, xz, yy, yz, zz = i6
            tensor = ref[:3, :3] @ np.array([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]]) @ ref[:3, :3].T
            lib = r.model.inertias[j]
            place = data.oMi[j]
            assert lib.mass == pytest.approx(mass, rel=1e-6)  # the library keeps 6 decimals of kg
            np.testing.assert_allclose(place.act(lib.lever), ref[:3, 3], atol=1e-6)
            np.testing.assert_allclose(place.rotation @ lib.inertia @ place.rotation.T, tensor, atol=1e-6 * max(1.0, mass))
