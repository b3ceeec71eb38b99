"""Diagnostic codes of the runtime-logic emitters (issue #15) of Fanuc TP, Yaskawa INFORM and
Stäubli VAL3: range E430–E439 / W430–W439."""

from __future__ import annotations

from rmot.lang.diagnostics import Code

__all__ = [
    "LOGIC_UNSUPPORTED",
    "REGISTERS_EXHAUSTED",
    "WAIT_POLLED",
    "STOP_AS_PAUSE",
]

# errors
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

# warnings
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
