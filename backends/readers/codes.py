"""Diagnostic codes of `rmot import` and `rmot diff` (reading vendor programs back).

Range E510–E519 / W510–W519: every message is located at the vendor file's line and column.
"""

from __future__ import annotations

from rmot.lang.diagnostics import Code

__all__ = [
    "NOT_VENDOR_LANGUAGE", "UNKNOWN_FORMAT", "IMPORT_UNREADABLE", "DIFF_VENDORS_DIFFER", "DIFF_NO_COUNTERPART",
    "KEPT_NATIVE", "DECLARATION_KEPT", "JOINT_SPEED_READ", "SIGNAL_UNKNOWN", "NAME_RENAMED",
    "JOINT_RATES_READ", "PAYLOAD_UNMATCHED", "MOTION_OPTION_KEPT", "LOOP_READ_ONCE", "PARAMETERS_NUMBER",
    "URCAP_INSTALLATION",
]
__all__ += ["FOLD_DISABLED", "NAME_READ_AS_INPUT", "MODULE_IS_PROC"]

NOT_VENDOR_LANGUAGE = Code("E510", "not-vendor-language",
                           "a file given to `rmot import` is not a program in the vendor language its name says")
UNKNOWN_FORMAT = Code("E511", "unknown-vendor-format",
                      "a file's extension names no vendor language `rmot import` reads")
IMPORT_UNREADABLE = Code("E512", "import-unreadable", "a vendor file is not UTF-8/Latin-1 text or too large")
DIFF_VENDORS_DIFFER = Code("E513", "diff-vendors-differ", "`rmot diff` was given programs of two different vendors")
DIFF_NO_COUNTERPART = Code("E514", "diff-no-counterpart",
                           "the .rmot side of `rmot diff` compiles to no file named like the vendor file (nor like the program)")

KEPT_NATIVE = Code("W510", "kept-native",
                   "a vendor instruction has no rmot form: it is kept as a `native` statement at its place")
DECLARATION_KEPT = Code("W511", "declaration-kept",
                        "a vendor declaration has no rmot form: it is kept as a comment")
JOINT_SPEED_READ = Code("W512", "joint-speed-read",
                        "a joint move's TCP speed is read as 100 % joint speed (rmot times joint moves by joint share)")
SIGNAL_UNKNOWN = Code("W513", "signal-unknown",
                      "an I/O signal name is not declared in the cell: the instruction is kept native")
NAME_RENAMED = Code("W514", "name-renamed", "a vendor name is an rmot keyword or clashes: it is renamed")
JOINT_RATES_READ = Code("W515", "joint-rates-read",
                        "a URScript movej's a=/v= (the plan's leading-axis peak rates) give no shares where its start "
                        "is unknown or it blends: read as 100 %")
PAYLOAD_UNMATCHED = Code("W516", "payload-unmatched",
                         "a payload switch matches no part of the cell, or several: it is kept native")
MOTION_OPTION_KEPT = Code("W517", "motion-option-kept",
                          "a motion option rmot's move has no form for (TP PTH, COORD, a TB/TA/DB action, Arc "
                          "Start/End, Weave; INFORM NWAIT): the move is imported and the option kept native right "
                          "after it, as a TP comment where TP cannot write it on its own line (PTH, COORD, TB/TA/DB) "
                          "(NWAIT: dropped, the next instructions run once the move ends)")
LOOP_READ_ONCE = Code("W518", "loop-read-once",
                      "a program's outermost endless loop (URScript `while True:`) is read as one cycle: "
                      "rmot's program is one cycle, which the controller repeats")
PARAMETERS_NUMBER = Code("W519", "parameters-number",
                         "a URScript function's parameters are untyped: they are declared `number` and the lines "
                         "that use them stay native")
FOLD_DISABLED = Code("W520", "fold-disabled",
                     "a KRL inline form whose statements are commented out does nothing on the controller: "
                     "it is skipped")
NAME_READ_AS_INPUT = Code("W521", "name-read-as-input",
                          "a KRL condition (or PULSE) names what the program does not declare: it is read as the "
                          "input (output) signal of that name (a SIGNAL of $config.dat, or a global BOOL another "
                          "task sets)")
MODULE_IS_PROC = Code("W522", "module-is-proc",
                      "a KRL module whose DEF takes parameters is a routine other programs call: it is written as "
                      "a proc with those parameters, and the program body is empty")

# Fanuc TP, INFORM and RAPID as pendants and RobotStudio write them
__all__ += ["ACCEL_SHARE_ON_PATH"]
ACCEL_SHARE_ON_PATH = Code("W540", "accel-share-on-path",
                           "a TP linear or circular move's ACCn, an INFORM MOVL/MOVC's equal ACC=/DEC= (the motion's "
                           "acceleration override) is read as rmot's joint acceleration share on that move: its TCP "
                           "acceleration stays the default")
URCAP_INSTALLATION = Code("W530", "urcap-installation-kept",
                          "a PolyScope URCap installation node (a gripper's or device's functions, threads and "
                          "start-up) belongs to the robot's installation: it is kept as a comment")

# runtime variables read back (RAPID, KRL)
__all__ += ["PERSISTENT_VARIABLE"]
PERSISTENT_VARIABLE = Code("W541", "persistent-variable",
                           "a persistent variable (a KRL .dat variable, a RAPID PERS) the main routine does not set "
                           "first thing is read as a task variable starting at the value the file stores; on the "
                           "controller it starts where the previous run left it")

# several robots' programs read into one program with a task per robot (tasks.py)
__all__ += ["TASK_SPEC_INVALID", "BARRIER_TASK_UNKNOWN", "BARRIER_ONE_SIDED", "BARRIER_NAMES_DIFFER",
            "HANDSHAKE_KEPT_IO"]
TASK_SPEC_INVALID = Code("E523", "task-spec-invalid",
                         "a `--task ROBOT=FILE` of `rmot import` names no robot of the cell, gives a file twice, or "
                         "is given without --cell or with plain FILE arguments; or plain FILE arguments are several "
                         "tasks' RAPID programs (two define PROC main)")
BARRIER_TASK_UNKNOWN = Code("E524", "barrier-task-unknown",
                            "a RAPID WaitSyncTask's task list names a task that is not imported (the k-th robot of "
                            "--task is task T_ROBk, or the name --task ROBOT:NAME=FILE gives), or leaves out the "
                            "task that waits")
BARRIER_ONE_SIDED = Code("W531", "barrier-one-sided",
                         "a barrier one task passes and a peer it waits for lacks (or passes a different number "
                         "of handshakes): it is not read as `sync` but kept as it is written")
BARRIER_NAMES_DIFFER = Code("W532", "barrier-names-differ",
                            "the tasks' files name the k-th handshake barrier differently: the first task's name "
                            "is used")
HANDSHAKE_KEPT_IO = Code("W533", "handshake-kept-io",
                         "a task's use of its \"sync\" signals is not the handshake rmot's backends write (set the "
                         "own output, then wait for the peer's input at the same level, on at odd rounds, off at "
                         "even ones): its sync I/O is kept as plain I/O, not read as barriers")
# external axes read back (readers/axes.py)
__all__ += ["AXES_KEPT"]
AXES_KEPT = Code("W523", "axes-kept",
                 "a move's external-axis values (RAPID extax, KRL E1..E6, TP E1/GP2, INFORM BC/EC) map to no "
                 "axes of the cell (no --cell, no mechanism choice fills the slots, or more than one): it is "
                 "kept native")
__all__ += ["NAME_READ_AS_GROUP_INPUT"]
NAME_READ_AS_GROUP_INPUT = Code("W534", "name-read-as-group-input",
                                "a KRL SWITCH or comparison tests a whole number the program neither declares nor "
                                "assigns (a SIGNAL group or an INT global of $config.dat the PLC or another task "
                                "sets, such as PGNO): read as the group input gin[n] of that name")

# KRL motion settings after a routine the import does not read
__all__ += ["SETTINGS_AFTER_CALL"]
SETTINGS_AFTER_CALL = Code("W527", "settings-after-call",
                           "a KRL motion after a call of a routine the import does not read (kept native) is read "
                           "with the speed, approximation, tool and base set before the call; the routine may "
                           "change them ($VEL, $APO, $TOOL, $BASE are global)")

# KRL FOR loops over array elements (readers/krl_unroll.py)
__all__ += ["LOOP_NOT_UNROLLED", "LOOP_UNROLLED"]
LOOP_NOT_UNROLLED = Code("W537", "krl-loop-not-written-out",
                         "a KRL FOR moves to array elements its counter selects over more iterations (or lines) than "
                         "the import writes out: it stays a loop, its moves native")
LOOP_UNROLLED = Code("W538", "krl-loop-written-out",
                     "a KRL FOR moves to known array elements its counter selects, which an rmot target cannot: "
                     "written out as its iterations")

# KRL globals and controller flags read as task variables (krl_vars.py)
__all__ += ["GLOBAL_READ_AS_VARIABLE"]
GLOBAL_READ_AS_VARIABLE = Code("W542", "global-read-as-variable",
                               "a KRL global (of $config.dat, or $FLAG[n]) that the main routine sets is read as a "
                               "task variable: on the controller it starts where the last run or another program "
                               "left it, and another program writing it while this one runs is not seen")

# INFORM pulse positions read with the arm's scales (readers/inform.py)
__all__ += ["PULSE_SCALES_INVALID"]
PULSE_SCALES_INVALID = Code("E525", "pulse-scales-invalid",
                            "`rmot import --pulses-per-degree` is not one finite, non-zero number of encoder pulses "
                            "per degree for each axis (1 to 8, separated by commas), or is given with --task")

# URScript waits read back
__all__ += ["POLLED_WAIT"]
POLLED_WAIT = Code("W528", "polled-wait",
                   "a URScript loop that sleeps T s between tests of digital inputs is read as `wait until`: the "
                   "controller goes on up to T s after the condition holds, rmot's wait as soon as it holds")

# URScript get_inverse_kin(P, qnear=Q) (urscript_qnear.py)
__all__ += ["QNEAR_NOT_READ"]
QNEAR_NOT_READ = Code("W529", "qnear-not-read",
                      "a URScript joint move to `get_inverse_kin(P, qnear=Q)` goes on the controller to the solution of "
                      "P nearest Q; where the import cannot read that branch (no --cell, Q or the tool not known) "
                      "rmot's move takes the solution nearest the current joints, which may differ")

# Fanuc TP registers read as state set elsewhere or as task variables (fanuc_regs.py)
__all__ += ["REGISTER_READ_AS_GROUP_INPUT", "REGISTER_READ_AS_VARIABLE"]
REGISTER_READ_AS_GROUP_INPUT = Code("W535", "register-read-as-group-input",
                                    "a Fanuc TP program tests a numeric register it never sets (a called program, "
                                    "another task or the PLC sets it): read as the group input gin[n] named after "
                                    "the register, so every arm of a branch on it is planned and verified")
REGISTER_READ_AS_VARIABLE = Code("W536", "register-read-as-variable",
                                 "a Fanuc TP register or flag the running program sets before it reads it is read "
                                 "as a task variable: on the controller it keeps its value between runs and another "
                                 "program writing it while this one runs is not seen")

__all__ += ["BIT_READ_AS_INPUT"]
BIT_READ_AS_INPUT = Code("W549", "bit-read-as-input",
                         "a program tests a flag it never sets (a Fanuc TP flag or marker, a KRL $FLAG or BOOL "
                         "global): another program, the background logic or the PLC sets it; it is read as the "
                         "digital input named after it, so every arm of a branch on it is planned and verified")

__all__ += ["GERMAN_EXPORT_READ"]
GERMAN_EXPORT_READ = Code("W551", "german-export-read",
                          "a Fanuc TP program a German-language pendant exported is read in the English words of the "
                          "same program's English export (fanuc_german.py); its lines show, and its native lines "
                          "are kept, in those words")

# Fanuc registers read at the value a controller backup saved (fanuc_va.py)
__all__ += ["CONTROLLER_VALUE_READ"]
CONTROLLER_VALUE_READ = Code("W543", "controller-value-read",
                             "a Fanuc TP register no program given writes is read at the value the backup's "
                             "NUMREG.VA or POSREG.VA saved: another program or the PLC may change it before "
                             "this one runs")

# RAPID external-axis values the controller ignores on a cell without the axes (axes.py)
__all__ += ["AXES_NOT_CONNECTED"]
AXES_NOT_CONNECTED = Code("W544", "axes-not-connected",
                          "every external-axis value of a RAPID file is 0 and the cell declares no track or "
                          "positioner: the controller ignores the value of an axis not connected, so the moves are "
                          "read without them")

# Fanuc TP moves in a program that selects no tool or frame: read in the numbers the positions record
__all__ += ["CALLERS_SELECTION_READ"]
CALLERS_SELECTION_READ = Code("W545", "callers-selection-read",
                              "a Fanuc TP program moves before it selects UTOOL_NUM or UFRAME_NUM: its moves are read "
                              "in the tool and user frame their positions were taught in, which its caller must select")

# KRL and URScript moves before the program sets its tool or base (start_state.py)
__all__ += ["START_TOOL_UNKNOWN"]
START_TOOL_UNKNOWN = Code("W546", "start-tool-unknown",
                          "a KRL or URScript program moves (Cartesian) before it sets its tool or base: the move is "
                          "read with the bare flange and the robot base, while the controller runs it with the ones "
                          "set before the program")

# what an unconditional jump skips every time, read into a proc nothing calls (jump_spans.py)
__all__ += ["UNREACHED_READ_AS_PROC"]
UNREACHED_READ_AS_PROC = Code("W552", "unreached-read-as-proc",
                              "an unconditional forward jump skips lines every time and no line names a label "
                              "among them: they never run, and are read into a proc nothing calls (their moves "
                              "and targets kept, not planned, verified or compiled)")
