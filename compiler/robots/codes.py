"""Diagnostic codes of the kinematics stage (E201-E219; the planner uses E220 and up)."""

from __future__ import annotations

from rmot.lang.diagnostics import Code

__all__ = [
    "UNKNOWN_ROBOT", "BAD_URDF", "WRONG_JOINT_COUNT", "UNREACHABLE", "OUT_OF_LIMITS",
    "SINGULAR", "NO_SOLUTION_ON_BRANCH", "BAD_NUMBER",
]

UNKNOWN_ROBOT = Code("E201", "robot-not-in-library", "a robot name is not in the library and is not a URDF file")
BAD_URDF = Code("E202", "bad-urdf", "a URDF file cannot be loaded as a serial arm")
WRONG_JOINT_COUNT = Code("E203", "wrong-joint-count", "a joint vector has the wrong number of values")
UNREACHABLE = Code("E204", "ik-unreachable", "a pose lies outside the robot's workspace")
OUT_OF_LIMITS = Code("E205", "ik-out-of-limits", "every IK solution of a pose violates a joint limit")
SINGULAR = Code("E206", "ik-singular", "a pose lies on a kinematic singularity")
NO_SOLUTION_ON_BRANCH = Code("E207", "ik-no-solution-on-branch", "a pose has no IK solution on the requested configuration")
BAD_NUMBER = Code("E208", "bad-number", "a command-line value is not a finite number")
