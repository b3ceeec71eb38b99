"""Diagnostic codes of the kinematics stage (E201-E219; the planner uses E220 and up)."""

from __future__ import annotations

from rmot.lang.diagnostics import Code

__all__ = ["UNKNOWN_ROBOT", "BAD_URDF"]

# A RobotError carries one of these; the design commands (sim/design/study.py) report it as
# is (`rmot reach --robot nosuch`: E201); the front end, planner and verifier report a robot
# that does not load under their own codes (E111, E505, E231, E320).
# Issue #19 removed E203-E208: E203 and E208 were never reported; E204-E207 (IkResult.code)
# were reported only under the planner's codes for the same findings (E220 target-unreachable,
# E221 target-out-of-limits, E222 branch-change, E224/W221 singular: compiler/plan/targets.py).

UNKNOWN_ROBOT = Code("E201", "robot-not-in-library", "a robot name is not in the library and is not a URDF file")
BAD_URDF = Code("E202", "bad-urdf", "a URDF file cannot be loaded as a serial arm")
