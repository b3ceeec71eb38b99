"""The joint bounds and speeds of the library's further ROS-I ABB and FANUC arms against the
<limit> tags of their macro files, as tests/robots/reference_arms_abb.py and
reference_arms_fanuc.py transcribe them (radians, the files' own numbers).

The library keeps a bound the file gives as a whole degree exactly, and rounds decimal radians
to the nearest 0.5 deg (speeds: 1 deg/s). A FANUC file bounds its joint_3 (J2 + J3) with the
data sheet's J3 range: the library takes it as the pendant's J3 range, as for the M-16iB/20.
"""

from __future__ import annotations

import numpy as np
import pytest

from rmot.sim.robots import load_robot
from reference_arms_abb import ABB_LIMITS
from reference_arms_fanuc import FANUC_LIMITS

LIMITS = ABB_LIMITS | FANUC_LIMITS


def _tolerance(deg: np.ndarray, rounding: float) -> np.ndarray:
    """1e-6 deg where the file's value is a whole degree, else half the library's rounding step."""
    whole = np.abs(deg - np.round(deg)) < 1e-6
    return np.where(whole, 1e-6, rounding / 2 + 1e-9)


@pytest.mark.parametrize("name", sorted(LIMITS))
def test_library_bounds_and_speeds_are_the_files_limit_tags(name):
    robot = load_robot(name)
    ref = np.degrees(np.array(LIMITS[name]))
    bounds = np.degrees(robot.joint_limits)
    speeds = np.degrees(robot.velocity_limits)
    assert np.all(np.abs(bounds - ref[:, :2]) <= _tolerance(ref[:, :2], 0.5)), (bounds, ref[:, :2])
    assert np.all(np.abs(speeds - ref[:, 2]) <= _tolerance(ref[:, 2], 1.0)), (speeds, ref[:, 2])
