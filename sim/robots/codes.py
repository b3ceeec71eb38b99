"""Diagnostic codes of the kinematics stage (E201-E219; the planner uses E220 and up)."""

from __future__ import annotations

from rmot.lang.check_codes import UNKNOWN_ROBOT as UNKNOWN_ROBOT
from rmot.lang.diagnostics import Code

__all__ = ["BAD_URDF"]

# A RobotError carries one of these; the design commands (compiler/design/study.py) report BAD_URDF
# as is (`rmot reach --robot broken.urdf`: E202); the front end, planner and verifier report a
# robot that does not load under their own codes (E111, E505, E231, E320).
# An unknown robot name is the front end's E111 (UNKNOWN_ROBOT, imported above), which the
# design commands report as E804 (there is no E201: no caller would report it).
# There are no E203-E208: E203 and E208 would never be reported; E204-E207 (IkResult.code)
# would be reported only under the planner's codes for the same findings (E220 target-unreachable,
# E221 target-out-of-limits, E222 branch-change, E224/W221 singular: compiler/plan/targets.py).

BAD_URDF = Code("E202", "bad-urdf", "a URDF file cannot be loaded as a serial arm")
