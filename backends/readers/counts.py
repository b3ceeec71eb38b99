"""How many motion and I/O instructions of each file were imported and how many kept native:
the share a user of `rmot import` cares about (set-up, sockets and bookkeeping lines of a
vendor program are not motion).

A native line counts as motion or I/O when its first word (a TP `IF (..),action`: its action's)
is one of the vendor's motion or I/O instructions (RAPID Instructions reference; KSS 8.x motion and I/O statements; R-30iB
Operator's Manual motion and I/O instructions; URScript manual, modules motion and interfaces).
"""

from __future__ import annotations

import re

from rmot.backends.readers.model import Document, Move, Native, Pulse, SetOut, Wait, WaitIn, walk

__all__ = ["motion_io_counts", "MOTION_IO_WORDS"]

MOTION_IO_WORDS = {
    "rapid": {"MOVEJ", "MOVEL", "MOVEC", "MOVEABSJ", "MOVEJDO", "MOVELDO", "MOVECDO", "MOVEEXTJ", "SEARCHL",
              "TRIGGL", "TRIGGJ", "TRIGGC", "SETDO", "SETAO", "SETGO", "PULSEDO", "SET", "RESET", "WAITDI",
              "WAITDO", "WAITTIME", "WAITUNTIL"},
    "krl": {"PTP", "LIN", "CIRC", "SPTP", "SLIN", "SCIRC", "PTP_REL", "LIN_REL", "CIRC_REL", "$OUT", "$OUT_C",
            "PULSE", "WAIT", "$ANOUT"},
    "inform": {"MOVJ", "MOVL", "MOVC", "MOVS", "IMOV", "DOUT", "PULSE", "AOUT", "TIMER", "WAIT"},
    "fanuc": {"J", "L", "C", "A", "DO", "AO", "RO", "WAIT"},
    "urscript": {"MOVEJ", "MOVEL", "MOVEC", "MOVEP", "SERVOJ", "SPEEDJ", "SPEEDL", "SET_STANDARD_DIGITAL_OUT",
                 "SET_DIGITAL_OUT", "SET_CONFIGURABLE_DIGITAL_OUT", "SET_TOOL_DIGITAL_OUT",
                 "SET_STANDARD_ANALOG_OUT", "SET_ANALOG_OUT", "SLEEP"},
}


# a TP line `IF (cond),DO[n]=ON` is the I/O instruction its action is (B-83284EN, IF with an action)
_ACTION = re.compile(r"\s*(?:IF\s*\(.*\)\s*,\s*)?(\w+)")


def motion_io_counts(doc: Document) -> dict[str, tuple[int, int]]:
    """path -> (motion and I/O instructions imported, kept native). An instruction imported is
    counted once however many rmot statements it became (a move and its output, RAPID MoveLDO; an
    output set to an expression, both arms of its `if`; a loop written out per iteration)."""
    words = MOTION_IO_WORDS.get(doc.vendor, set())
    counts: dict[str, list[int]] = {c.path: [0, 0] for c in doc.counts}
    seen: set[tuple[str, int, int]] = set()
    for r in doc.routines:
        for s in walk(r.body):
            slot = counts.setdefault(s.where.path, [0, 0])
            if isinstance(s, (Move, SetOut, Pulse, Wait, WaitIn)):
                slot[0] += (s.where.path, s.where.line, s.where.col) not in seen
                seen.add((s.where.path, s.where.line, s.where.col))
            elif isinstance(s, Native):
                m = re.match(_ACTION if doc.vendor == "fanuc" else r"\s*(\$?\w+)", s.text)
                slot[1] += bool(m and m.group(1).upper() in words)
    return {path: (a, b) for path, (a, b) in counts.items()}
