"""Diagnostic codes of external axes: tracks and positioners (E601–E606, E608–E611, W601, W606–W608;
compiler/passes/lower_axes.py, lang/axis_motion.py). E607, a vendor that cannot write them,
is the backends' (backends/codes.py)."""

from __future__ import annotations

from rmot.lang.diagnostics import Code

__all__ = ["EXT_AXES_MODIFIER", "EXT_FRAME_NUMBER", "EXT_VALUE_AT_HOME",
           "EXT_AXIS_DEFINITION", "EXT_AXIS_LIMIT", "EXT_COORDINATED", "EXT_FRAME_UNDRIVEN", "EXT_INFORM_BINDING", "EXT_MOTION",
           "EXT_MOUNT", "EXT_PROGRAM_AXES", "EXT_SLOWDOWN", "EXT_STOPS", "EXT_VALUES"]


EXT_AXIS_DEFINITION = Code("E601", "ext-axis-definition", "an external axis that is not linear or revolute about x, y "
                           "or z with a finite range(low, high), low < high, and positive speed and accel")
EXT_MOUNT = Code("E602", "ext-mount", "`on NAME` that names no track or positioner, or a robot on a positioner")
EXT_PROGRAM_AXES = Code("E603", "ext-program-axes", "`with` naming what is not a mechanism, or a robot on a track its program does not drive")
EXT_VALUES = Code("E604", "ext-values", "ext(...) or `move axes` values that name no axis of the program, or of the wrong "
                 "count or unit, or a mechanism set twice")
EXT_AXIS_LIMIT = Code("E605", "ext-axis-limit", "an external axis driven outside its range")
EXT_MOTION = Code("E606", "ext-motion", "external axes moved where rmot cannot plan it: during a linear or circular move in the "
                   "robot's base frame, a positioner during one in a frame it does not carry, or inside an if or while "
                   "that leaves them at different values")
EXT_COORDINATED = Code("E609", "ext-coordinated", "a coordinated move (a linear or circular move while axes move) in a frame "
                       "riding on a track, or that changes axes other than those of the positioner its frame rides on and "
                       "the robot's track")
EXT_FRAME_UNDRIVEN = Code("E610", "ext-frame-undriven", "a move in a frame riding on a mechanism the program does not drive")
EXT_SLOWDOWN = Code("W606", "ext-slowdown", "a coordinated move whose TCP must go slower than programmed, relative to the "
                    "part, because an arm joint or an external axis cannot keep up")
EXT_STOPS = Code("W601", "ext-stops", "a zone ignored: a move that moves external axes, and the move before it, stop exactly")
EXT_INFORM_BINDING = Code("E608", "ext-inform-binding", "an axis' inform(...) binding that is not pulses_per_mm (linear) "
                          "or pulses_per_deg (revolute) = one finite number > 0")
EXT_AXES_MODIFIER = Code("E611", "ext-axes-modifier", "a `move axes` modifier other than `time` (speed, zone, tool, frame, "
                         "config, ext: its axes move at their own speed and acceleration, the arm holds its joints)")
EXT_VALUE_AT_HOME = Code("W607", "ext-value-at-home", "a target built from a frame riding on a mechanism the program "
                         "moves (or the mechanism) as a pose: its place with the axes at home, which does not follow them")
EXT_FRAME_NUMBER = Code("W608", "ext-frame-number", "a `number` on a frame riding on a mechanism: not used, the programs "
                        "write that frame through the mechanism")
