"""Diagnostic codes of joint turns in the vendors' configuration data (issue #15, item 4).

Range E440-E449 / W440-W444 (assigned to issue #15's turns within the backends' E4xx).
"""

from __future__ import annotations

from rmot.lang.diagnostics import Code

__all__ = ["TURN_NOT_EXPRESSIBLE"]

TURN_NOT_EXPRESSIBLE = Code(
    "E440", "turn-not-expressible",
    "a planned joint value's turn cannot be told apart by the vendor's configuration data")
