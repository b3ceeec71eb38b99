"""What the planner needs of a robot: the `RobotModel` protocol.

sim/robots/robot.Robot is the one implementation; the planner (compiler/plan) types its
robot with this protocol instead of `object`, so a missing or misspelt attribute is a type
error, and a test double (tests/plan) needs only these members.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Protocol

import numpy as np

from rmot.lang import ir

if TYPE_CHECKING:
    from rmot.sim.robots.ik import IkResult

__all__ = ["RobotModel"]


class RobotModel(Protocol):
    """A serial arm as the planner sees it. Joint values are the controller's (rad / m);
    poses are (4, 4) homogeneous matrices of the flange in the robot's base frame (m)."""

    name: str
    dof: int
    joint_types: tuple[str, ...]  # "R" revolute, "P" prismatic, one per joint
    joint_limits: np.ndarray  # (dof, 2) lower, upper
    velocity_limits: np.ndarray  # (dof,) rad/s or m/s
    accel_limits: np.ndarray  # (dof,) rad/s^2 or m/s^2
    has_closed_form: bool  # ik_batch gives one row per branch (else row 0: the numeric one)

    def fk(self, q: np.ndarray) -> np.ndarray:
        """q (dof,) -> the flange pose (4, 4)."""
        ...

    def fk_batch(self, qs: np.ndarray) -> np.ndarray:
        """qs (N, dof) -> (N, 4, 4)."""
        ...

    def jacobian(self, q: np.ndarray) -> np.ndarray:
        """q (dof,) -> the flange's geometric Jacobian (6, dof), linear rows first."""
        ...

    def manipulability(self, q: np.ndarray) -> float:
        ...

    def condition(self, q: np.ndarray) -> float:
        ...

    def branch(self, q: np.ndarray) -> ir.Config:
        """The configuration (shoulder, elbow, wrist) of q."""
        ...

    def ik(self, pose: np.ndarray, seed: np.ndarray | None = None,
           config: ir.Config | None = None) -> IkResult:
        """Every solution of the flange pose within the limits, nearest to seed first."""
        ...

    def ik_batch(self, poses: np.ndarray, seed: np.ndarray | None = None) -> np.ndarray:
        """poses (N, 4, 4) -> (N, 8, dof), NaN where a branch has no solution."""
        ...
