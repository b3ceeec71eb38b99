"""Diagnostic codes of the design commands (`rmot reach`, `rmot place`, `rmot compare`): E80x.

Their values come from command-line options, so the diagnostics carry no source span; the
message names the option. An output file that cannot be written is the project's E520
(rmot.lang.check_codes.OUTPUT_FAILED), a robot file that does not load keeps the robot loader's
own code where it has one.
"""

from __future__ import annotations

from rmot.lang.diagnostics import Code

__all__ = [
    "REGION_SYNTAX", "RANGE_INVERTED", "OPTION_NUMBER", "ORIENTATION_SYNTAX", "ROBOT_UNKNOWN",
    "TOOL_UNKNOWN", "OUTPUT_FORMAT", "OPTION_MISSING", "OPTION_RANGE", "OPTION_IGNORED",
]

REGION_SYNTAX = Code("E800", "design-region-syntax",
                     "--region must list KEY=LO..HI parts (x and y required, z and rz optional), each key once")
RANGE_INVERTED = Code("E801", "design-range-inverted", "a --region range goes from high to low (LO > HI)")
OPTION_NUMBER = Code("E802", "design-option-number",
                     "a design option's value is not a finite number with a unit (--region, --orientation, --z, --step)")
ORIENTATION_SYNTAX = Code("E803", "design-orientation-syntax",
                          "--orientation is neither 'any' nor keys rx, ry, rz each given at most once")
ROBOT_UNKNOWN = Code("E804", "design-robot-unknown",
                     "--robot / --as names no robot of the cell, no library robot and no URDF file")
TOOL_UNKNOWN = Code("E805", "design-tool-unknown", "--tool names no tool of the cell mounted on the robot")
OUTPUT_FORMAT = Code("E806", "design-output-format", "the -o file of `rmot reach` does not end in .png, .svg or .html")
OPTION_MISSING = Code("E807", "design-option-missing",
                      "an option needs another one (--place needs --region; --tool needs a cell; no cell needs --robot)")
OPTION_RANGE = Code("E808", "design-option-range",
                    "a design option is outside its range (--step not positive, or so small the map exceeds its work bound)")
OPTION_IGNORED = Code("W800", "design-option-ignored", "a design option has no effect without another (--region without --place)")
