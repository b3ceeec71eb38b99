"""The external-axes tests' shared cell and their witness kinematics.

The cell: a KR 16 on a 4 m track along x (robot 250 mm up on the carriage) and a 2-axis
positioner at (1800, 0, 700) mm (tilt about y, then turn about z) carrying a jig and the frame
`work` 40 mm above its flange. The witness places things in world with plain numpy rotation
matrices built from those numbers, never through rmot.lang.ir_axes: it is what the
compiler's own composition is compared against."""

from __future__ import annotations

import math

import numpy as np

__all__ = ["CELL", "CELL_HEAD", "at", "kr16_flange", "positioner_flange", "robot_base", "rot", "work_frame"]

CELL_HEAD = """cell c {
  track rail = linear(axis x, range(0mm, 4000mm)) speed 1500 mm/s accel 2000 mm/s^2 at pose(z=0mm)
  robot r1 = kuka_kr16 on rail at pose(z=250mm)
  positioner pos = axes(revolute(axis y, range(-90deg, 90deg)) speed 90 deg/s accel 180 deg/s^2,
                        revolute(axis z, range(-360deg, 360deg)) speed 180 deg/s accel 360 deg/s^2)
                   at pose(x=1800mm, z=700mm)
  fixture jig = box(600mm, 400mm, 40mm) on pos at pose(z=20mm)
  frame work = pos * pose(z=40mm)
"""
CELL = CELL_HEAD + "  tool torch = none tcp pose(z=300mm) on r1\n}\n"


def rot(axis: str, deg: float) -> np.ndarray:
    """(4, 4) rotation by `deg` degrees about world axis x, y or z."""
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    m = {"x": [[1, 0, 0], [0, c, -s], [0, s, c]], "y": [[c, 0, s], [0, 1, 0], [-s, 0, c]],
         "z": [[c, -s, 0], [s, c, 0], [0, 0, 1]]}[axis]
    out = np.eye(4)
    out[:3, :3] = m
    return out


def at(x: float = 0.0, y: float = 0.0, z: float = 0.0) -> np.ndarray:
    """(4, 4) translation, metres."""
    out = np.eye(4)
    out[:3, 3] = (x, y, z)
    return out


def robot_base(rail_mm: float) -> np.ndarray:
    """The arm's base in world: the carriage `rail_mm` along x, the robot 250 mm up on it."""
    return at(x=rail_mm / 1000) @ at(z=0.25)


def positioner_flange(tilt_deg: float, turn_deg: float) -> np.ndarray:
    return at(1.8, 0.0, 0.7) @ rot("y", tilt_deg) @ rot("z", turn_deg)


def work_frame(tilt_deg: float, turn_deg: float) -> np.ndarray:
    return positioner_flange(tilt_deg, turn_deg) @ at(z=0.04)


# The KR 16's joint origins and axes as ROS-Industrial publishes them (kuka_experimental
# kuka_kr16_support/urdf/kr16_2_macro.xacro @ e78bbd15edb2, as in tests/robots/reference_arms.py;
# pendant joint values one to one, kuka_rsi_hw_interface).
KR16 = (((0.0, 0.0, 0.675), (0.0, 0.0, -1.0)), ((0.26, 0.0, 0.0), (0.0, 1.0, 0.0)), ((0.68, 0.0, 0.0), (0.0, 1.0, 0.0)),
        ((0.67, 0.0, -0.035), (-1.0, 0.0, 0.0)), ((0.0, 0.0, 0.0), (0.0, 1.0, 0.0)), ((0.0, 0.0, 0.0), (-1.0, 0.0, 0.0)))


def _about(axis: tuple[float, float, float], angle: float) -> np.ndarray:
    k = np.asarray(axis)
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    out = np.eye(4)
    out[:3, :3] = np.eye(3) + math.sin(angle) * kx + (1 - math.cos(angle)) * kx @ kx
    return out


def kr16_flange(q: np.ndarray) -> np.ndarray:
    """The KR 16's flange in its base frame (the URDF chain, then tool0: 0.158 m along x, ry 90 deg)."""
    out = np.eye(4)
    for (xyz, axis), value in zip(KR16, q, strict=True):
        out = out @ at(*xyz) @ _about(axis, float(value))
    return out @ at(0.158) @ rot("y", 90.0)
