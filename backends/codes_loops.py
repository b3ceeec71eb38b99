"""Diagnostic codes of the runtime logic in the backends (issue #15): loops written as vendor
loops or unrolled, runtime expressions, waits with a timeout branch, stop.

Range E420–E429 / W420–W429.
"""

from __future__ import annotations

from rmot.lang.diagnostics import Code

__all__ = ["ANALOG_IN_PORT", "LOOP_UNROLLED", "STOP_IN_ROUTINE"]

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
