"""Diagnostic codes of the URScript, INFORM, VAL3 and neutral (CSV/JSON) backends.

Range E450–E499 / W450–W499 (the shared machinery, RAPID, KRL and Fanuc TP use
E400–E449 / W400–W449 in `codes.py`; the generic ones there — speed rounded, zone rounded,
program split, native skipped, name changed — are reused here rather than duplicated).
"""

from __future__ import annotations

from rmot.lang.diagnostics import Code

__all__ = [
    "ANALOG_UNSUPPORTED", "CIRCULAR_VIA_MISSING", "JOINT_AS_CARTESIAN", "PULSE_INLINE",
    "SPEED_TABLE_UNKNOWN", "WAIT_END_MOVE", "NEUTRAL_NO_SAMPLES",
    "ANALOG_LINK",
]

# errors
ANALOG_UNSUPPORTED = Code("E450", "analog-out-unsupported",
                          "an analog output's port or value has no faithful form for this vendor")
CIRCULAR_VIA_MISSING = Code("E451", "circular-via-missing",
                            "a circular move must carry its via point and its planned via joints")
NEUTRAL_NO_SAMPLES = Code("E452", "trajectory-empty",
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
ANALOG_LINK = Code("W455", "analog-link-needed",
                   "an analog output variable is declared unlinked: link it to the controller's "
                   "physical output before running")

# parts held by the tool (issue #14)
PART_PAYLOAD_NOT_EXPRESSED = Code("W460", "part-payload-not-expressed",
                                  "the payload of held parts cannot be set by this vendor's program: "
                                  "enter the numbers given on the controller")
__all__ += ["PART_PAYLOAD_NOT_EXPRESSED"]
