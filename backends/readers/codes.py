"""Diagnostic codes of `rmot import` and `rmot diff` (reading vendor programs back).

Range E510–E519 / W510–W519: every message is located at the vendor file's line and column.
"""

from __future__ import annotations

from rmot.lang.diagnostics import Code

__all__ = [
    "NOT_VENDOR_LANGUAGE", "UNKNOWN_FORMAT", "IMPORT_UNREADABLE", "DIFF_VENDORS_DIFFER",
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
                          "after it (NWAIT: dropped, the next instructions run once the move ends)")
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
__all__ += ["NAME_READ_AS_GROUP_INPUT"]
NAME_READ_AS_GROUP_INPUT = Code("W534", "name-read-as-group-input",
                                "a KRL SWITCH or comparison tests a whole number the program neither declares nor "
                                "assigns (a SIGNAL group or an INT global of $config.dat the PLC or another task "
                                "sets, such as PGNO): read as the group input gin[n] of that name")
