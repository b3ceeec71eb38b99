"""Diagnostic codes of a cell `model`'s motor ratings and link masses (issue #16, the design
range E809-E819 / W801-W809 shared with rmot.sim.design.codes, whose E800-E808 / W800 the
design commands use). Emitted by compiler/passes/lower_model.py."""

from __future__ import annotations

from rmot.lang.diagnostics import Code

__all__ = ["MODEL_MASS_INCOMPLETE", "MODEL_TORQUE_UNCHECKED"]

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
