"""Which controllers a blended-corner finding concerns (sim/corners.py), without the
verification's numeric libraries: the command line filters the findings of a cached report
for its targets with this module alone.
"""

from __future__ import annotations

from collections.abc import Iterable

from rmot.lang.diagnostics import Diagnostic
from rmot.sim import codes

__all__ = ["BOUND_VENDORS", "SPHERE_VENDORS", "for_targets"]

# vendor -> how its corner is written (the words the messages use)
SPHERE_VENDORS = "RAPID zone, KRL C_DIS, URScript r, VAL3 blend, INFORM PL"
BOUND_VENDORS = {"fanuc": "Fanuc CNT", "krl": "KRL C_PTP"}  # KRL only for a PTP (joint) move


def for_targets(diagnostics: Iterable[Diagnostic], targets: Iterable[str]) -> tuple[Diagnostic, ...]:
    """The diagnostics without the W341 findings that concern none of `targets` (a compile for
    RAPID is not told about Fanuc's CNT bound; `rmot check`, with no target, reports the zone
    sphere alone)."""
    wanted = {BOUND_VENDORS[t] for t in targets if t in BOUND_VENDORS}
    return tuple(d for d in diagnostics
                 if d.code != codes.CORNER_BOUND or any(words in d.message for words in wanted))
