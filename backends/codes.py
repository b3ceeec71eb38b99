"""Diagnostic codes of the shared backend machinery and of RAPID, KRL and Fanuc TP.

Range E400–E449 / W400–W449 (the URScript, INFORM, VAL3 and neutral backends use
E450–E499 / W450–W499 in the section at the end of this module), with the sections of
runtime logic (E420–E439 / W420–W439: loops, runtime values, stop) and joint turns (E440–E449)
that every vendor shares.
"""

from __future__ import annotations

from rmot.lang.diagnostics import Code

__all__ = [
    "MISSING_RECORD", "UNSUPPORTED", "BAD_PORT", "SYNC_UNSUPPORTED",
    "NO_BRANCH", "NOT_SIX_AXIS", "PROGRAM_TOO_LONG", "SYNC_HANDSHAKE_MISSING",
    "NAME_CHANGED", "NAME_CLASH", "SPEED_ROUNDED", "ZONE_ROUNDED", "TIMEOUT_LOWERED",
    "PROGRAM_SPLIT", "NATIVE_SKIPPED", "ACCEL_IGNORED", "DURATION_IGNORED", "SYNC_OUTPUT_LEFT_ON",
    "TIME_ROUNDED", "MASS_RAISED", "PAYLOAD_NOT_EXPRESSED",
    # vendor programs that load on the controller: E410-E419 / W414-W419
    "RESERVED_RENAMED", "OTHER_BRAND", "STORED_DATA_WRITTEN", "LIMIT_CLAMPED", "NUMBER_OUT_OF_RANGE", "NATIVE_CLASH",
]

# errors: the program cannot be expressed faithfully for this vendor
UNSUPPORTED = Code("E400", "backend-unsupported", "an instruction has no faithful form for this vendor")
MISSING_RECORD = Code("E401", "missing-plan-record", "a move has no planned joint solution")
NO_BRANCH = Code("E402", "missing-branch", "a Cartesian target needs configuration data but its branch is unknown")
NOT_SIX_AXIS = Code("E403", "unsupported-robot", "the vendor format needs a 6-axis arm")
BAD_PORT = Code("E404", "io-port-out-of-range", "an I/O port number is outside what the vendor accepts")
SYNC_UNSUPPORTED = Code("E405", "sync-unsupported", "a multi-task barrier has no form for this vendor")
SYNC_HANDSHAKE_MISSING = Code("E409", "sync-handshake-missing",
                              "a barrier needs the robot's \"sync\" I/O handshake signals in the cell")
PROGRAM_TOO_LONG = Code("E406", "program-too-long", "a routine exceeds the controller's size limit")

# warnings: an exact or nearest-faithful lowering was applied
NAME_CHANGED = Code("W400", "name-changed", "a name was made legal for the vendor")
NAME_CLASH = Code("W401", "name-clash", "two names became equal after legalisation; one was renamed")
SPEED_ROUNDED = Code("W402", "speed-rounded", "the vendor cannot express the exact speed; the nearest was used")
ZONE_ROUNDED = Code("W403", "zone-rounded", "the vendor cannot express the exact zone; the nearest was used")
TIME_ROUNDED = Code("W412", "time-rounded",
                    "the vendor cannot express the exact time (wait, pulse, timeout); the nearest was used")
MASS_RAISED = Code("W413", "tool-mass-raised",
                   "a massless tool was declared with the vendor's smallest accepted mass")
TIMEOUT_LOWERED = Code("W405", "timeout-lowered", "a wait with timeout was lowered to a timed loop")
PROGRAM_SPLIT = Code("W406", "program-split", "a long program was split into parts called from a main")
NATIVE_SKIPPED = Code("W407", "native-other-vendor", "a native block for another vendor was not emitted")
ACCEL_IGNORED = Code("W408", "accel-not-expressed", "the vendor cannot express the programmed acceleration")
DURATION_IGNORED = Code("W409", "duration-not-expressed", "a fixed move duration is expressed as speed only")
SYNC_OUTPUT_LEFT_ON = Code("W410", "sync-output-left-on",
                           "an odd number of handshake barriers leaves the robot's sync output on")
PAYLOAD_NOT_EXPRESSED = Code("W411", "payload-not-expressed",
                             "the vendor's program cannot carry the tool's payload; set it on the controller")

# ---- programs that load on the controller (E410-E419, W414-W419)
RESERVED_RENAMED = Code("W414", "reserved-name-renamed",
                        "a name is a reserved word, instruction, function, data type or predefined "
                        "datum of the vendor's language; it was renamed")
OTHER_BRAND = Code("W415", "robot-other-brand",
                   "the program is written for a robot of another brand than the vendor's controller")
STORED_DATA_WRITTEN = Code("W416", "stored-frame-unnumbered",
                           "a tool or frame has no controller number: the program writes (or assumes) "
                           "the controller's stored tool or frame data at a number it chose")
NATIVE_CLASH = Code("E411", "native-names-backend-data",
                    "a native line names a position the backend numbers itself (it would be another point, "
                    "or none) or a register, variable, timer or tool/frame datum the backend's own lines use")
NUMBER_OUT_OF_RANGE = Code("E410", "frame-number-out-of-range",
                           "a tool or frame number is outside the numbers the vendor's controller has")
LIMIT_CLAMPED = Code("W417", "limit-clamped",
                     "a speed, acceleration or zone is beyond what the vendor accepts; clamped")

# runtime logic: what the base class reports for the nodes a vendor does not write itself
RUNTIME_UNSUPPORTED = Code(
    "E165",
    "runtime-logic-unsupported",
    "a var, assignment, while, stop or general condition the vendor's backend cannot write yet",
)
__all__ += ["RUNTIME_UNSUPPORTED"]


# ------------------------------------------------------------------ URScript, INFORM,
# VAL3 and the neutral (CSV/JSON) backends: E450-E499 / W450-W499 (the generic codes above -
# speed or zone rounded, program split, native skipped, name changed - are theirs too)

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

# parts held by the tool
PART_PAYLOAD_NOT_EXPRESSED = Code("W460", "part-payload-not-expressed",
                                  "the payload of held parts cannot be set by this vendor's program: "
                                  "enter the numbers given on the controller")

__all__ += [
    "ANALOG_UNSUPPORTED",
    "CIRCULAR_VIA_MISSING",
    "NEUTRAL_NO_SAMPLES",
    "JOINT_AS_CARTESIAN",
    "PULSE_INLINE",
    "SPEED_TABLE_UNKNOWN",
    "WAIT_END_MOVE",
    "ANALOG_LINK",
    "PART_PAYLOAD_NOT_EXPRESSED",
]


# ------------------------------------------------------------------ runtime logic
# Loops written as vendor loops or unrolled, runtime values, waits with a timeout branch,
# stop (E420-E429 / W420-W429; E165 above is the fallback of a vendor that writes none of
# it), and the emitters of Fanuc TP, Yaskawa INFORM and Staubli VAL3 (E430-E439 / W430-W439).
ANALOG_IN_PORT = Code(
    "E420",
    "analog-input-out-of-range",
    "an analog input's port is outside what the vendor's controller has",
)
LOOP_UNROLLED = Code(
    "W420",
    "loop-unrolled",
    "a for loop was written iteration by iteration: its iterations differ in more "
    "than target positions on a constant step (the warning names the iteration, "
    "the instruction and the difference)",
)
STOP_IN_ROUTINE = Code(
    "W421",
    "stop-flag",
    "a stop inside a routine ends the program through a flag tested after each "
    "call (the vendor has no instruction that ends the program from a routine)",
)
LOGIC_UNSUPPORTED = Code(
    "E430",
    "runtime-value-unsupported",
    "a runtime value or condition has no form in this vendor's language",
)
REGISTERS_EXHAUSTED = Code(
    "E431",
    "registers-exhausted",
    "the program needs more controller variables or registers than the block rmot writes them to",
)
WAIT_POLLED = Code(
    "W431",
    "wait-polled",
    "a wait on a condition the vendor's wait instruction cannot test is written as a "
    "polling loop (its timeout counted by a timer)",
)
STOP_AS_PAUSE = Code(
    "W432",
    "stop-as-pause",
    "`stop` inside a called job is written as a pause: the vendor cannot end the "
    "calling job from a called one",
)

# ------------------------------------------------------------------ joint turns
# in the vendors' configuration data, E440-E449 / W440-W444 (the front end's
# turn codes are in lang/check_codes.py)
TURN_NOT_EXPRESSIBLE = Code(
    "E440", "turn-not-expressible",
    "a planned joint value's turn cannot be told apart by the vendor's configuration data")

__all__ += [
    "ANALOG_IN_PORT", "LOOP_UNROLLED", "STOP_IN_ROUTINE",
    "LOGIC_UNSUPPORTED", "REGISTERS_EXHAUSTED", "WAIT_POLLED", "STOP_AS_PAUSE",
    "TURN_NOT_EXPRESSIBLE",
]

# --- controller conventions a vendor target needs (sim/robots/controller.py)
CONTROLLER_UNDECLARED = Code(
    "E480", "controller-undeclared",
    "a cell model or URDF robot declares no controller conventions: the vendor cannot vouch for its joint values",
)
CONTROLLER_MISMATCH = Code(
    "E481", "controller-mismatch",
    "a cell model or URDF robot declares another maker's controller than the target's",
)

__all__ += ["CONTROLLER_UNDECLARED", "CONTROLLER_MISMATCH"]

# ------------------------------------------------------------------ motion fidelity
# what the controller runs is what was verified: E470-E474 / W470-W474
ANALOG_RAW_COUNTS = Code(
    "E470", "analog-raw-counts",
    "a Fanuc AI[n] holds the raw A/D count, not volts: a comparison in volts has no TP form")
__all__ += ["ANALOG_RAW_COUNTS"]

# ------------------------------------------------------------------ external axes
EXT_AXES_UNSUPPORTED = Code(
    "E607", "ext-axes-unsupported",
    "a program that drives external axes, for a vendor rmot cannot write them for")
__all__ += ["EXT_AXES_UNSUPPORTED"]
INFORM_STATION_SPEED = Code(
    "W604", "inform-station-speed",
    "an INFORM station group moves at its own VJ: it may not end with the arm as the plan has it")
__all__ += ["INFORM_STATION_SPEED"]
PULSE_ROUNDING = Code(
    "W605", "pulse-rounding",
    "INFORM base/station positions in whole encoder pulses move a target by more than 0.01 mm")
__all__ += ["PULSE_ROUNDING"]
INFORM_ASSUMED_SCALE = Code(
    "W610", "inform-assumed-scale",
    "INFORM station positions written at an assumed pulse scale (none declared): confirm it on the controller")
__all__ += ["INFORM_ASSUMED_SCALE"]
