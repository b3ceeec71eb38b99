"""Vendor number and orientation conventions, as pure functions over IR values.

Units (mm from m), fixed-point text that never prints -0, and every orientation form a
controller reads: ABB quaternions (w first), KUKA/Fanuc Z-Y-X Euler angles, Stäubli moving
X-Y-Z angles, UR rotation vectors; plus the joint-value encodings of configuration data
(ABB quadrants, KUKA Turn bits). Split from backends/base.py so the Backend class stays about
formatting programs; base re-exports every name here.
"""

from __future__ import annotations

import math
from collections.abc import Iterable

import numpy as np

from rmot.lang import ir

__all__ = [
    "axis_quadrant", "euler_xyz_moving_deg", "euler_zyx_deg", "fmt", "fmt_list", "position_mm",
    "quaternion_wxyz", "rotation_vector", "tool_cog", "turn_bits",
]


# --------------------------------------------------------------------------- numbers


def fmt(value: float, decimals: int) -> str:
    """Fixed-point text with `decimals` places; -0 prints as 0 (deterministic output)."""
    text = f"{float(value):.{decimals}f}"
    if text.startswith("-") and float(text) == 0.0:
        text = text[1:]
    return text


def fmt_list(values: Iterable[float], decimals: int, sep: str = ",") -> str:
    return sep.join(fmt(v, decimals) for v in values)


def position_mm(pose: ir.Pose) -> tuple[float, float, float]:
    """Position in millimetres (the IR is in metres)."""
    x, y, z = pose.position
    return (x * 1000.0, y * 1000.0, z * 1000.0)


def quaternion_wxyz(pose: ir.Pose) -> tuple[float, float, float, float]:
    """The unit quaternion, w first, w >= 0 (ABB's q1..q4 order)."""
    return pose.quaternion


def _rot(axis: int, angle: float) -> np.ndarray:
    """The elementary rotation about x (0), y (1) or z (2)."""
    c, s = math.cos(angle), math.sin(angle)
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    m = np.eye(3)
    m[i, i], m[i, j], m[j, i], m[j, j] = c, -s, s, c
    return m


def euler_zyx_deg(pose: ir.Pose) -> tuple[float, float, float]:
    """(A, B, C) in degrees with R = Rz(A)·Ry(B)·Rx(C) (KUKA A B C; Fanuc R P W reversed).

    B in [-90, 90]. B comes from a well-conditioned atan2; C from the last row; A is then
    solved from what is left of R, so the three angles rebuild R exactly even near gimbal
    lock (B = ±90), where C is set to 0 and A carries the whole turn.
    """
    r = pose.matrix()[:3, :3]
    cb = math.hypot(r[0, 0], r[1, 0])
    b = math.atan2(-r[2, 0], cb)
    c = math.atan2(r[2, 1], r[2, 2]) if cb > 1e-12 else 0.0
    rest = r @ _rot(0, c).T @ _rot(1, b).T  # = Rz(A)
    a = math.atan2(rest[1, 0], rest[0, 0])
    return (math.degrees(a), math.degrees(b), math.degrees(c))


def euler_xyz_moving_deg(pose: ir.Pose) -> tuple[float, float, float]:
    """(rx, ry, rz) in degrees with R = Rx(rx)·Ry(ry)·Rz(rz) (Stäubli); ry in [-90, 90].

    Solved like euler_zyx_deg: ry well-conditioned, rx from the last column, rz from what is
    left, so the angles rebuild R exactly near ry = ±90 too.
    """
    r = pose.matrix()[:3, :3]
    cy = math.hypot(r[1, 2], r[2, 2])
    ry = math.atan2(r[0, 2], cy)
    rx = math.atan2(-r[1, 2], r[2, 2]) if cy > 1e-12 else 0.0
    rest = _rot(1, ry).T @ _rot(0, rx).T @ r  # = Rz(rz)
    rz = math.atan2(rest[1, 0], rest[0, 0])
    return (math.degrees(rx), math.degrees(ry), math.degrees(rz))


def rotation_vector(pose: ir.Pose) -> tuple[float, float, float]:
    """Axis * angle in radians, angle in [0, pi] (UR's rx, ry, rz)."""
    w, x, y, z = pose.quaternion  # w >= 0 by the IR's canonical form
    s = math.sqrt(x * x + y * y + z * z)
    if s < 1e-15:
        return (0.0, 0.0, 0.0)
    angle = 2.0 * math.atan2(s, w)
    return (x / s * angle, y / s * angle, z / s * angle)


def tool_cog(tool: ir.ToolRef | ir.Tool) -> tuple[float, float, float]:
    """The tool's centre of gravity in the flange frame, metres: half way along the
    flange->TCP vector (ir.payload_cog, the convention sim/verification.py's torque check
    uses too)."""
    return ir.payload_cog(tool.tcp)


def axis_quadrant(angle: float) -> int:
    """floor(angle / 90 deg): ABB cf1/cf4/cf6 (quadrant 0 is [0, 90) deg, -1 is [-90, 0))."""
    return math.floor(angle / (math.pi / 2) + 1e-12)


TURN_ZERO_RAD = 1e-6  # rad (0.00006 deg): an axis this close to 0 is at 0, whatever its float sign


def turn_bits(q: np.ndarray) -> int:
    """KUKA Turn: bit i set when axis i+1 is negative (< 0). An axis within TURN_ZERO_RAD of 0
    (float noise of the planner: -1e-12 for an axis planned at 0) counts as 0, not negative:
    its E6AXIS value prints as 0.000, and a Turn bit the angle does not show would send the
    controller to the other side of the axis' zero."""
    return sum(1 << i for i, v in enumerate(q[:6]) if v < -TURN_ZERO_RAD)
