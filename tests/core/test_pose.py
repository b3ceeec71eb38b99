"""ir.Pose: composition, inverse, RPY and matrix conversions against plain numpy matrices."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from rmot.lang.ir import Pose

coords = st.floats(min_value=-2.0, max_value=2.0, allow_nan=False)
angles = st.floats(min_value=-math.pi, max_value=math.pi, allow_nan=False)
poses = st.builds(Pose.from_xyz_rpy, coords, coords, coords, angles, angles, angles)


def _rx(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def _ry(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def _rz(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


@settings(max_examples=200, deadline=None)
@given(coords, coords, coords, angles, angles, angles)
def test_rpy_matches_fixed_axis_product(x: float, y: float, z: float, rx: float, ry: float, rz: float) -> None:
    """from_xyz_rpy builds R = Rz(rz)·Ry(ry)·Rx(rx), the LANGUAGE.md convention."""
    m = Pose.from_xyz_rpy(x, y, z, rx, ry, rz).matrix()
    np.testing.assert_allclose(m[:3, :3], _rz(rz) @ _ry(ry) @ _rx(rx), atol=1e-12)
    np.testing.assert_allclose(m[:3, 3], [x, y, z], atol=1e-15)


@settings(max_examples=200, deadline=None)
@given(poses, poses)
def test_compose_is_matrix_product(a: Pose, b: Pose) -> None:
    """a * b equals the product of the homogeneous matrices."""
    np.testing.assert_allclose((a * b).matrix(), a.matrix() @ b.matrix(), atol=1e-12)


@settings(max_examples=200, deadline=None)
@given(poses)
def test_inverse_and_matrix_round_trip(p: Pose) -> None:
    """inverse() is the matrix inverse, and from_matrix(matrix()) gives the same pose back."""
    np.testing.assert_allclose(p.inverse().matrix(), np.linalg.inv(p.matrix()), atol=1e-12)
    back = Pose.from_matrix(p.matrix())
    np.testing.assert_allclose(back.position, p.position, atol=1e-12)
    np.testing.assert_allclose(back.quaternion, p.quaternion, atol=1e-9)


@settings(max_examples=200, deadline=None)
@given(poses)
def test_rpy_round_trip_gives_same_rotation(p: Pose) -> None:
    """rpy() returns angles that rebuild the same rotation (angles may differ at gimbal lock)."""
    rebuilt = Pose.from_xyz_rpy(*p.position, *p.rpy())
    np.testing.assert_allclose(rebuilt.matrix(), p.matrix(), atol=1e-7)


def test_quaternion_is_canonical() -> None:
    """q and -q are one rotation; the pose always stores the spelling with w >= 0."""
    p = Pose.from_xyz_rpy(0, 0, 0, 0, 0, math.radians(350))
    assert p.quaternion[0] >= 0
    assert Pose.from_matrix(p.matrix()) == p


def test_non_unit_quaternion_is_rejected() -> None:
    """A non-unit quaternion is an invariant violation named with its value."""
    try:
        Pose((0, 0, 0), (2.0, 0, 0, 0))
    except ValueError as exc:
        assert "unit norm" in str(exc) and "2.0" in str(exc)
    else:
        raise AssertionError("a non-unit quaternion was accepted")
