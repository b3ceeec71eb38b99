"""Diagnostic codes of the compiler's check stage (E1xx) and the files it reads (E5xx)."""

from __future__ import annotations

from rmot.lang.diagnostics import Code

__all__ = [
    "UNKNOWN_NAME", "DUPLICATE", "WRONG_TYPE", "WRONG_DIMENSION", "MISSING_UNIT", "MIXED_UNITS",
    "ARITY", "RECURSION", "IMPORT_CYCLE", "JOINT_COUNT", "UNKNOWN_ROBOT", "TOOL_NOT_ON_ROBOT",
    "SYNC_UNMATCHED", "SYNC_ORDER", "MISPLACED", "UNKNOWN_VENDOR", "BAD_ARGUMENT",
    "OUT_OF_RANGE", "NO_PROGRAM", "NO_CELL", "TOO_LARGE_UNROLLED", "BAD_TASK",
    "CONFIG_IGNORED", "NOT_FINITE", "TOO_MUCH_WORK", "PHYSICAL_RANGE", "OUTPUT_FAILED", "UNREADABLE",
    "OUTPUT_NAME_CLASH", "FILE_NOT_FOUND", "NOT_UTF8", "FILE_TOO_LARGE", "PATH_ESCAPES", "ROBOT_LOAD",
]

UNKNOWN_NAME = Code("E101", "unknown-name", "a name is not defined in any visible scope")
DUPLICATE = Code("E102", "duplicate-definition", "a name is defined twice in one scope")
WRONG_TYPE = Code("E103", "wrong-type", "a value of the wrong kind (pose, joints, number, ...)")
WRONG_DIMENSION = Code("E104", "wrong-dimension", "a quantity of the wrong dimension (length, angle, ...)")
MISSING_UNIT = Code("E105", "missing-unit", "a bare number where a physical quantity is needed")
MIXED_UNITS = Code("E106", "mixed-units", "arithmetic on quantities of different dimensions")
ARITY = Code("E107", "wrong-argument-count", "a call with too many or too few arguments")
RECURSION = Code("E108", "recursion", "a proc calls itself, directly or through others")
IMPORT_CYCLE = Code("E109", "import-cycle", "files import each other in a cycle")
JOINT_COUNT = Code("E110", "joint-count", "joints() with a different count than the robot's axes")
UNKNOWN_ROBOT = Code("E111", "unknown-robot", "a robot name that is neither in the library nor in the cell")
TOOL_NOT_ON_ROBOT = Code("E112", "tool-not-on-robot", "a tool used by a robot it is not mounted on")
SYNC_UNMATCHED = Code("E113", "sync-unmatched", "a sync barrier that some task of a multi-task program lacks")
SYNC_ORDER = Code("E114", "sync-order", "tasks pass their sync barriers in different orders or counts")
MISPLACED = Code("E115", "misplaced-statement", "a statement where it cannot appear")
UNKNOWN_VENDOR = Code("E116", "unknown-vendor", "native text for a controller rmot does not know")
BAD_ARGUMENT = Code("E117", "bad-argument", "an unknown, missing or repeated argument")
OUT_OF_RANGE = Code("E118", "out-of-range", "a value outside what the setting allows")
NO_PROGRAM = Code("E119", "no-program", "the file holds no program (or more than one)")
NO_CELL = Code("E120", "no-cell", "no cell, or more than one, where one is needed")
TOO_LARGE_UNROLLED = Code("E121", "too-large", "loops unroll to more instructions than allowed")
BAD_TASK = Code("E122", "bad-task", "a task that names no robot of the cell, or names it twice")
CONFIG_IGNORED = Code("W123", "config-ignored", "config(...) on a joint target, which has no IK branch to choose")

FILE_NOT_FOUND = Code("E501", "file-not-found", "a file named by the program does not exist")
NOT_UTF8 = Code("E502", "not-utf8", "a source file is not UTF-8 text")
FILE_TOO_LARGE = Code("E503", "file-too-large", "a source file is larger than the limit")
PATH_ESCAPES = Code("E504", "path-escapes-project", "a path leads outside the project directory")
ROBOT_LOAD = Code("E505", "robot-load-failed", "a URDF robot could not be loaded")

# --- robots defined in the cell (`model` blocks, compiler/passes/lower_model.py) and URDF
# chains chosen by `urdf(..., base=, tip=)`
MODEL_JOINT_FIELD = Code("E135", "model-joint-field", "a model joint line lacks, repeats or misspells a field (dh/mdh, range, speed, accel)")
MODEL_CHAIN_LENGTH = Code("E136", "model-chain-length", "a model with no joints or more than the allowed number")
MODEL_BAD_VALUE = Code("E137", "model-bad-value", "a model number out of its domain: range lo >= hi, speed/accel <= 0, not finite")
MODEL_MIXED_DH = Code("E138", "model-mixed-dh", "a model mixing standard dh(...) and modified mdh(...) rows")
MODEL_SHADOWS_LIBRARY = Code("W135", "model-shadows-library", "a model named like a library robot: the cell's model is used")
URDF_UNKNOWN_LINK = Code("E506", "urdf-unknown-link", "urdf(base=, tip=) names a link the URDF file does not have")
URDF_BAD_CHAIN = Code("E507", "urdf-bad-chain", "the URDF links base= and tip= do not bound a serial chain of joints")

__all__ += ["MODEL_JOINT_FIELD", "MODEL_CHAIN_LENGTH", "MODEL_BAD_VALUE", "MODEL_MIXED_DH", "MODEL_SHADOWS_LIBRARY",
            "URDF_UNKNOWN_LINK", "URDF_BAD_CHAIN"]

# a model's motor ratings and link masses (the design range E809-E819 / W801-W809
# shared with rmot.compiler.design.codes)
MODEL_MASS_INCOMPLETE = Code(
    "E809",
    "model-mass-incomplete",
    "a model gives link masses on some joint lines but not on all of them",
)
MODEL_TORQUE_UNCHECKED = Code(
    "W801",
    "model-torque-unchecked",
    "a model gives torque ratings but no link masses: torques cannot be computed, "
    "the ratings are neither checked nor slow the timing",
)
__all__ += ["MODEL_MASS_INCOMPLETE", "MODEL_TORQUE_UNCHECKED"]

# parts that tools pick up and put down
UNKNOWN_PART = Code("E140", "unknown-part", "attach or detach names no part of the cell")
PART_ALREADY_HELD = Code("E141", "part-already-held", "attach of a part the task already holds")
PART_NOT_HELD = Code("E142", "part-not-held", "detach of a part the task does not hold")
PART_ARMS_DIFFER = Code("E143", "part-arms-differ", "the arms of a runtime if leave different parts held")
PART_HELD_AT_END = Code("W140", "part-held-at-end", "a task ends still holding a part")
__all__ += ["UNKNOWN_PART", "PART_ALREADY_HELD", "PART_NOT_HELD", "PART_ARMS_DIFFER", "PART_HELD_AT_END"]

# numbers, work and files a hostile or clumsy input can make absurd
NOT_FINITE = Code("E123", "not-finite", "a value overflows to infinity or is not a number")
TOO_MUCH_WORK = Code("E124", "too-much-work", "the program would make the compiler do more work than allowed")
PHYSICAL_RANGE = Code("E125", "outside-accepted-range", "a time, speed, zone, size or position outside what rmot accepts")
OUTPUT_FAILED = Code("E520", "output-failed", "an output file or directory cannot be written")
UNREADABLE = Code("E521", "unreadable", "a file or folder exists but cannot be read")
OUTPUT_NAME_CLASH = Code("E522", "output-name-clash", "two output files get the same name on a controller")
OUTPUT_IS_INPUT = Code("E564", "output-is-input",
                       "an output path is one of the command's input files (after resolving links)")
FOREIGN_OUTPUT_DIR = Code("E565", "foreign-output-dir",
                          "a vendor folder of the output directory was not created by rmot")
__all__ += ["OUTPUT_IS_INPUT", "FOREIGN_OUTPUT_DIR"]

# joint-move speeds and joint turns (E170-E179, W170-W174 are the front
# end's and the planner's; the planner's are in compiler/plan/codes.py)
TURN_BAD_JOINT = Code("E170", "turn-bad-joint",
                      "config(jN=...) names no revolute joint of the task's robot")
TURN_NOT_WHOLE = Code("E171", "turn-not-whole",
                      "a joint turn in config(jN=...) is not a whole number")
TCP_SPEED_ON_JOINT_MOVE = Code(
    "W170", "tcp-speed-on-joint-move",
    "a TCP speed modifier on a joint move: joint moves are timed by their joint speed share")
JOINT_SPEED_ON_CARTESIAN_MOVE = Code(
    "W171", "joint-speed-on-cartesian-move",
    "a joint speed share modifier on a linear or circular move, which it does not change")
__all__ += ["TURN_BAD_JOINT", "TURN_NOT_WHOLE", "TCP_SPEED_ON_JOINT_MOVE",
            "JOINT_SPEED_ON_CARTESIAN_MOVE"]
# runtime logic: task variables, conditions, loops that stay loops, while, stop
RT_UNKNOWN_VAR = Code(
    "E150",
    "unknown-variable",
    "a runtime expression or assignment names no variable, constant or loop variable",
)
RT_WRONG_TYPE = Code(
    "E151", "runtime-wrong-type", "a runtime value of the wrong type (int, num, bool) for its use"
)
RT_ASSIGN_NOT_VAR = Code(
    "E152",
    "assign-not-variable",
    "an assignment to a target, const, loop variable or anything else that is not a var",
)
RT_REDECLARED = Code(
    "E153", "variable-redeclared", "a var whose name is already declared (var, const, target, ...)"
)
RT_IN_COMPILE_TIME = Code(
    "E154",
    "runtime-value-in-pose",
    "a runtime variable in a pose, target, speed or other value the compiler must bound",
)
FOR_WITHOUT_BOUNDS = Code(
    "E155", "for-without-bounds", "a for loop written without 'a .. b' bounds"
)
WHILE_WITHOUT_CONDITION = Code(
    "E156", "while-without-condition", "a while loop written without a condition"
)
VAR_MISPLACED = Code(
    "E157",
    "var-misplaced",
    "a var declared inside a block (loop, if arm, proc) instead of a task's body",
)
RT_BAD_TYPE_NAME = Code("E158", "unknown-variable-type", "a var type that is not int, num or bool")
RT_UNIT = Code(
    "E159",
    "runtime-unit",
    "a quantity with a unit, a pose or a string in a runtime expression (plain numbers only)",
)
WHILE_PARTS_DIFFER = Code(
    "E160", "while-parts-differ", "a while body that ends holding other parts than it started with"
)
RT_BAD_IO = Code(
    "E161",
    "runtime-bad-io",
    "a condition reads an analog output (aout[n]); conditions read in[n], out[n], ain[n] and gin[n]",
)
RT_DIVISION_BY_ZERO = Code(
    "E162", "division-by-zero", "a runtime expression divides by the constant 0"
)
UNREACHABLE_AFTER_STOP = Code(
    "W150", "unreachable-after-stop", "statements after 'stop' in the same block never run"
)
WAIT_ELSE_WITHOUT_TIMEOUT = Code(
    "W151",
    "timeout-branch-empty",
    "'timeout T else { }' with an empty branch: the same as 'timeout T'",
)

__all__ += [
    "RT_UNKNOWN_VAR",
    "RT_WRONG_TYPE",
    "RT_ASSIGN_NOT_VAR",
    "RT_REDECLARED",
    "RT_IN_COMPILE_TIME",
    "FOR_WITHOUT_BOUNDS",
    "WHILE_WITHOUT_CONDITION",
    "VAR_MISPLACED",
    "RT_BAD_TYPE_NAME",
    "RT_UNIT",
    "WHILE_PARTS_DIFFER",
    "RT_BAD_IO",
    "RT_DIVISION_BY_ZERO",
    "UNREACHABLE_AFTER_STOP",
    "WAIT_ELSE_WITHOUT_TIMEOUT",
]

# --- controller conventions of cell-defined robots (sim/robots/controller.py)
MODEL_PENDANT = Code(
    "E185", "model-pendant", "a model joint's pendant(sign=, zero=, coupled_to=) is not a valid mapping"
)
UNKNOWN_CONTROLLER = Code(
    "E186", "unknown-controller", "a `controller` line or urdf(controller=) names no known robot maker"
)
URDF_CONTROLLER_FRAMES = Code(
    "E187", "urdf-controller-frames",
    "urdf(controller=) on a file without the controller's `base` and `tool0` links (and no base=/tip=)",
)

__all__ += ["MODEL_PENDANT", "UNKNOWN_CONTROLLER", "URDF_CONTROLLER_FRAMES"]

# --- robot descriptions as xacro / with packages (compiler/passes/xacro_files.py)
XACRO_FAILED = Code("E540", "xacro-failed", "a xacro file does not expand to a URDF (xacro's message)")
XACRO_REFUSED = Code(
    "E541", "xacro-refused",
    "a xacro file uses what is not data: $(env)/$(optenv)/$(eval), entities, files outside the project, "
    "expressions beyond arithmetic",
)
UNKNOWN_PACKAGE = Code("E542", "unknown-package", "$(find PKG) or package://PKG names a package urdf(packages=) does not give")

__all__ += ["XACRO_FAILED", "XACRO_REFUSED", "UNKNOWN_PACKAGE"]
STEP_UNIT = Code("E543", "step-unit", "mesh(\"f.step\", unit=/scale=): a STEP file states its own length unit")
__all__ += ["STEP_UNIT"]

# `move free` (E180-E184 are its front end's; its search reports E250-E259, sim/codes.py)
FREE_TIMED = Code("E180", "free-move-timed", "a 'move free' with a 'time' modifier (its path is found at plan time)")
__all__ += ["FREE_TIMED"]

# --- `rmot robots add`: a DH table turned into a library definition (sim/robots/add_robot.py)
ADD_UNREADABLE = Code("E547", "robot-table-unreadable", "a `rmot robots add` DH table is not readable YAML/JSON")
ADD_BAD_FIELD = Code("E548", "robot-table-field", "a `rmot robots add` DH table lacks a field or has a bad value")
ADD_NOT_OPW = Code(
    "E549", "robot-table-not-opw",
    "a `rmot robots add` DH table is not a 6R spherical-wrist arm a library definition (OPW form) can hold",
)
ADD_NO_SOURCE = Code("W547", "robot-table-no-source", "a `rmot robots add` DH table names no source for its numbers")
ADD_ACCEL_ESTIMATED = Code(
    "W548", "robot-table-accel-estimated", "a `rmot robots add` definition's accelerations are the library's estimate"
)

__all__ += ["ADD_ACCEL_ESTIMATED", "ADD_BAD_FIELD", "ADD_NOT_OPW", "ADD_NO_SOURCE", "ADD_UNREADABLE"]

# Group inputs: `gin[n]`, several digital inputs read as one unsigned integer.
GROUP_INPUT_WIDTH = Code(
    "E166", "group-input-width", "'bits B' on an io line: B must be an integer 1..32, on gin[n] only"
)
GROUP_INPUT_WRITTEN = Code(
    "E167", "group-input-written", "set or pulse of gin[n]: a group input is read, never written"
)
GROUP_INPUT_NOT_INTEGER = Code(
    "E168", "group-input-not-integer", "gin[n] compared with a number that is not a whole number"
)
GROUP_INPUT_RANGE = Code(
    "W152", "group-input-range",
    "gin[n] compared with a value outside 0..2^bits-1: the comparison never or always holds",
)

__all__ += ["GROUP_INPUT_WIDTH", "GROUP_INPUT_WRITTEN", "GROUP_INPUT_NOT_INTEGER", "GROUP_INPUT_RANGE"]

# I/O reads are runtime values: the controller reads them while the program runs.
IO_READ_NOT_CONSTANT = Code(
    "E169", "io-read-not-constant",
    "in[n], out[n], ain[n] or gin[n] in a compile-time expression (a const, a target, a speed, ...)",
)

__all__ += ["IO_READ_NOT_CONSTANT"]

PROC_NEVER_CALLED = Code(
    "W153", "proc-never-called",
    "a proc no task calls: checked for names, but not planned, verified or written to the controller files",
)

__all__ += ["PROC_NEVER_CALLED"]
