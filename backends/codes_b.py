"""Diagnostic codes of the URScript, INFORM, VAL3 and neutral (CSV/JSON) backends.

Range E450–E499 / W450–W499 (the shared machinery, RAPID, KRL and Fanuc TP use
E400–E449 / W400–W449 in `codes.py`; the generic ones there — speed rounded, zone rounded,
program split, native skipped, name changed — are reused here rather than duplicated).
"""

from __future__ import annotations

from rmot.lang.diagnostics import Code

__all__ = [
    "ANALOG_UNSUPPORTED", "CIRCULAR_VIA_MISSING", "JOINT_AS_CARTESIAN", "PULSE_INLINE",
    "SPEED_TABLE_UNKNOWN", "TOO_MANY_POSITIONS", "WAIT_END_MOVE", "NEUTRAL_NO_SAMPLES",
    "TURN_AMBIGUOUS",
]

# errors
ANALOG_UNSUPPORTED = Code("E450", "analog-out-unsupported",
                          "the vendor backend has no faithful analog output instruction")
CIRCULAR_VIA_MISSING = Code("E451", "circular-via-missing",
                            "a circular move must carry its via point and its planned via joints")
TOO_MANY_POSITIONS = Code("E452", "too-many-positions",
                          "one instruction needs more position variables than a job may hold")
NEUTRAL_NO_SAMPLES = Code("E453", "trajectory-empty",
                          "a task's trajectory has no samples to write")

# warnings
JOINT_AS_CARTESIAN = Code("W450", "joint-target-as-cartesian",
                          "a joint target was written as a Cartesian position with full "
                          "configuration data (an exact lowering)")
PULSE_INLINE = Code("W451", "pulse-blocking",
                    "a pulse was lowered to set, delay, reset (the program waits for it)")
SPEED_TABLE_UNKNOWN = Code("W452", "speed-table-unknown",
                           "the robot model has no entry in the vendor's speed table; the "
                           "vendor default maximum was assumed")
WAIT_END_MOVE = Code("W453", "wait-end-move",
                     "the vendor executes I/O asynchronously to motion; a waitEndMove() was "
                     "inserted, so the preceding move stops exactly instead of blending")
TURN_AMBIGUOUS = Code("W454", "turn-flag-ambiguous",
                      "a joint lies at exactly +-180 deg, where the vendor's turn flag "
                      "changes; the controller may pick the other turn")
