"""Diagnostic codes of the planner (E220–E299 errors, W220+ warnings).

E200–E219 are left to the kinematics library (sim/robots); the planner starts at E220.
"""

from __future__ import annotations

from rmot.lang.diagnostics import Code

__all__ = [
    "ARC_DEGENERATE", "BLEND_REDUCED", "BRANCH_CHANGE", "BRANCH_CHANGE_JOINT", "IF_ARMS_DIFFER",
    "JOINT_LIMIT_PATH", "JOINT_TARGET_LIMIT", "PATH_SINGULAR", "SLOWDOWN_SINGULAR",
    "SYNC_MISMATCH", "TARGET_LIMITS", "TARGET_UNREACHABLE", "TIME_TOO_SHORT",
    "TIMING_FAILED", "DOF_MISMATCH", "ROBOT_UNAVAILABLE", "UNKNOWN_START",
    "TIMING_EXACT_STOP",
]

TARGET_UNREACHABLE = Code("E220", "target-unreachable", "a pose target is outside the robot's workspace")
TARGET_LIMITS = Code("E221", "target-out-of-limits", "every IK solution of a target exceeds a joint limit")
BRANCH_CHANGE = Code("E222", "branch-change", "a move can only be done by changing IK branch")
JOINT_TARGET_LIMIT = Code("E223", "joint-target-out-of-limits", "a joint target exceeds a joint limit")
PATH_SINGULAR = Code("E224", "path-singular", "a linear or circular path passes through a singularity")
JOINT_LIMIT_PATH = Code("E225", "path-joint-limit", "a linear or circular path crosses a joint limit")
ARC_DEGENERATE = Code("E226", "arc-degenerate", "circular move points are collinear or coincide")
TIME_TOO_SHORT = Code("E227", "time-too-short", "a `time` modifier is shorter than the fastest feasible motion")
TIMING_FAILED = Code("E228", "timing-failed", "time parametrisation found no feasible timing")
SYNC_MISMATCH = Code("E229", "sync-mismatch", "tasks do not pass the same sync barriers in the same order")
DOF_MISMATCH = Code("E230", "joint-count-mismatch", "a joint target has the wrong number of joints")
ROBOT_UNAVAILABLE = Code("E231", "robot-unavailable", "the task's robot model cannot be loaded")

BRANCH_CHANGE_JOINT = Code("W220", "branch-change-joint-move", "a joint move changes IK branch (nearest solution)")
SLOWDOWN_SINGULAR = Code("W221", "singularity-slowdown", "the TCP slows down near a singularity")
BLEND_REDUCED = Code("W222", "blend-reduced", "a zone was reduced or dropped to keep the blend valid")
IF_ARMS_DIFFER = Code("W223", "if-arms-end-differently", "the arms of a runtime if end in different joint states")
UNKNOWN_START = Code("W224", "unknown-start", "a task's first move is not a joint move to a joint target")
TIMING_EXACT_STOP = Code("W225", "timing-exact-stop",
                         "a blended chain could not be timed as a whole; its corners became exact stops")

# joint turns fixed by config(jN=...) (E170-E179 are the front end's and
# the planner's; E170/E171 are in lang/check_codes.py)
TURN_RANGE_TOO_SMALL = Code("E172", "turn-joint-range",
                            "a turn is fixed on a joint whose range spans at most 360 deg")
TURN_OUTSIDE_LIMITS = Code("E173", "turn-outside-limits",
                           "a fixed turn lies outside the joint's limits")
TURN_NOT_REACHED = Code(
    "E174", "turn-not-reached",
    "a target has no solution on its fixed turn, or a linear or circular path ends on another")
__all__ += ["TURN_RANGE_TOO_SMALL", "TURN_OUTSIDE_LIMITS", "TURN_NOT_REACHED"]
# runtime logic
WHILE_NO_FIXED_POINT = Code(
    "E240",
    "while-no-fixed-point",
    "a while loop whose iterations do not come back to the state they started from",
)
__all__ += ["WHILE_NO_FIXED_POINT"]
# controller conventions of cell-brought arms: a branch request the arm cannot honour
CONFIG_WITHOUT_BRANCHES = Code(
    "E188", "config-without-branches",
    "config(shoulder=, elbow=, wrist=) on an arm that has no branch names (no spherical wrist)",
)
__all__ += ["CONFIG_WITHOUT_BRANCHES"]
