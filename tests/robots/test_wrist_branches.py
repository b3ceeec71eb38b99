"""Branch names of URDF arms with a spherical wrist, from their joint axes and frames."""

from __future__ import annotations

import importlib.metadata
import math
from pathlib import Path

import numpy as np
import pytest

from rmot.lang import ir
from rmot.sim.robots import load_robot
from rmot.sim.robots.wrist_branches import spherical_wrist_branch_fn, wrist_centre

ARM6 = str(Path(__file__).resolve().parents[2] / "examples" / "urdf_cell" / "arm6.urdf")
N = 2000
MARGIN = 1e-6  # closer than this to a branch boundary a name may round either way


def _ur5_urdf() -> str:
    files = importlib.metadata.files("example-robot-data") or []
    return str(next(f for f in files if f.name == "ur5_robot.urdf").locate())


def _arm6_quantities(q: np.ndarray) -> tuple[float, float, float]:
    """arm6 by hand from its file: J2/J3 about +y (positive tips forward), a1 = 0.05 m,
    lower arm 0.40 m up at zero, J3 to wrist centre 0.38 m along the upper arm, horizontal
    at zero (as on an ABB arm). The wrist centre's side of the lower arm is then
    0.38·cos(q3): stretched or folded at q3 = ±90°."""
    front = 0.05 + 0.40 * math.sin(q[1]) + 0.38 * math.cos(q[1] + q[2])
    return front, math.cos(q[2]), math.sin(q[4])


def _name(front: float, elbow: float, j5: float) -> ir.Config:
    return ir.Config(ir.Shoulder.FRONT if front >= 0 else ir.Shoulder.BACK,
                     ir.Elbow.UP if elbow >= 0 else ir.Elbow.DOWN,
                     ir.Wrist.FLIP if j5 < 0 else ir.Wrist.NOFLIP)


class TestArm6:
    def test_branches_match_the_hand_formula_on_random_configurations(self) -> None:
        """arm6.urdf's branch equals the hand-derived OPW quantities on 2,000 random q."""
        arm = load_robot(ARM6)
        rng = np.random.default_rng(7)
        checked = 0
        for q in rng.uniform(arm.joint_limits[:, 0], arm.joint_limits[:, 1], (N, 6)):
            quantities = _arm6_quantities(q)
            if min(abs(v) for v in quantities) < MARGIN:
                continue
            assert arm.branch(q) == _name(*quantities), q
            checked += 1
        assert checked > 0.99 * N

    def test_all_eight_names_occur_and_zero_is_front_up_noflip(self) -> None:
        """The home pose is FRONT/UP/NOFLIP and random configurations reach every name."""
        arm = load_robot(ARM6)
        assert arm.branch(np.zeros(6)) == ir.Config(ir.Shoulder.FRONT, ir.Elbow.UP, ir.Wrist.NOFLIP)
        qs = np.random.default_rng(3).uniform(arm.joint_limits[:, 0], arm.joint_limits[:, 1], (N, 6))
        assert len({arm.branch(q) for q in qs}) == 8

    def test_wrist_centre_is_the_documented_point(self) -> None:
        """At q = 0 the wrist centre is 0.05 + 0.18 + 0.20 m forward, 0.2 + 0.2 + 0.4 m up."""
        arm = load_robot(ARM6)
        np.testing.assert_allclose(wrist_centre(arm.model, arm._chain.axes, np.zeros(6)), [0.43, 0.0, 0.8], atol=1e-12)


@pytest.mark.parametrize("name", ["abb_irb120", "kuka_kr6_r900", "fanuc_lrmate200id", "staubli_tx2_60", "puma560", "yaskawa_gp8"])
def test_generic_path_agrees_with_closed_form_branches(name: str) -> None:
    """A library arm's branch through the geometric path equals its closed-form branch() on
    2,000 random configurations (none of which lands on a singular boundary)."""
    arm = load_robot(name)
    fn = spherical_wrist_branch_fn(arm.model, arm._chain.axes, arm._chain.prismatic, arm.joint_limits)
    assert fn is not None
    qs = np.random.default_rng(11).uniform(arm.joint_limits[:, 0], arm.joint_limits[:, 1], (N, 6))
    mismatches = [q for q in qs if fn(arm.to_model(q)) != arm.branch(q)]
    assert mismatches == []


def test_offset_wrist_urdf_keeps_no_branch() -> None:
    """The UR5 URDF (offset wrist: J4–J6 axes do not meet) has all-None branch names."""
    ur5 = load_robot(_ur5_urdf())
    assert spherical_wrist_branch_fn(ur5.model, ur5._chain.axes, ur5._chain.prismatic, ur5.joint_limits) is None
    assert ur5.branch(np.array([0.3, -1.2, 1.4, -0.9, 1.1, 0.4])) == ir.Config()
    assert wrist_centre(ur5.model, ur5._chain.axes, np.zeros(6)) is None
