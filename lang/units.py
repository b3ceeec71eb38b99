"""The one table of units: the lexer, the E007 suggestions and the evaluator all read it.

`UNIT_TABLE` maps a unit as written to (factor to SI, dimension); a dimension is the
exponents of (length, angle, time, mass, percent). A compound unit is a base unit over
`s` or `s^2`; the lexer takes any `<base>/s` or `<base>/s^2` word as one unit token (so a
wrong one such as `kg/s` is reported as an unknown unit, not as a division by `s`), and
the AST builder checks it against this table.
"""

from __future__ import annotations

import difflib
import math
import re

from rmot.lang import codes
from rmot.lang.diagnostics import Diagnostic, Severity
from rmot.lang.source import Span

__all__ = ["BASE_UNITS", "COMPOUND_CUT", "COMPOUND_UNIT", "UNIT_TABLE", "UNIT_NAMES",
           "unknown_unit"]

_DEG = math.pi / 180
_L, _A, _T, _M, _P = (1, 0, 0, 0, 0), (0, 1, 0, 0, 0), (0, 0, 1, 0, 0), (0, 0, 0, 1, 0), (0, 0, 0, 0, 1)
_SPEED, _ANG_SPEED = (1, 0, -1, 0, 0), (0, 1, -1, 0, 0)
_ACCEL, _ANG_ACCEL = (1, 0, -2, 0, 0), (0, 1, -2, 0, 0)
_FORCE, _TORQUE = (1, 0, -2, 1, 0), (2, 0, -2, 1, 0)  # N, N·m: a model joint's rating

UNIT_TABLE: dict[str, tuple[float, tuple[int, int, int, int, int]]] = {
    "mm": (1e-3, _L), "cm": (1e-2, _L), "m": (1.0, _L), "in": (0.0254, _L),
    "deg": (_DEG, _A), "rad": (1.0, _A),
    "ms": (1e-3, _T), "s": (1.0, _T), "min": (60.0, _T),
    "mm/s": (1e-3, _SPEED), "m/s": (1.0, _SPEED), "cm/s": (1e-2, _SPEED), "in/s": (0.0254, _SPEED),
    "deg/s": (_DEG, _ANG_SPEED), "rad/s": (1.0, _ANG_SPEED),
    "mm/s^2": (1e-3, _ACCEL), "m/s^2": (1.0, _ACCEL), "cm/s^2": (1e-2, _ACCEL), "in/s^2": (0.0254, _ACCEL),
    "deg/s^2": (_DEG, _ANG_ACCEL), "rad/s^2": (1.0, _ANG_ACCEL),
    "g": (1e-3, _M), "kg": (1.0, _M), "%": (0.01, _P),
    "N": (1.0, _FORCE), "N*m": (1.0, _TORQUE),
}
UNIT_NAMES: tuple[str, ...] = tuple(UNIT_TABLE)
# the words that may start a unit token (longest first, so `mm` is tried before `m`)
BASE_UNITS: tuple[str, ...] = tuple(sorted((u for u in UNIT_TABLE if u.isidentifier()), key=lambda u: (-len(u), u)))
_BASES = "|".join(BASE_UNITS)
# the lexer's shape of a compound unit; whether it is a known one is the builder's question
COMPOUND_UNIT = rf"(?:(?:{_BASES})/s(?:\^2)?|N\*m)(?![A-Za-z0-9_])"
# where no unit fits, a compound unit token is cut back to its first word (`m/s` -> `m`,
# `N*m` -> `N`)
COMPOUND_CUT = re.compile(r"[/*]")


def unknown_unit(text: str, span: Span | None) -> Diagnostic:
    """E007 for a word after a number that is no unit, with the nearest known unit if any."""
    near = difflib.get_close_matches(text, UNIT_NAMES, n=1, cutoff=0.5)
    hint = f"; did you mean '{near[0]}'?" if near else ""
    msg = f"unit must be one of mm, m, deg, rad, s, mm/s, ... (got '{text}'){hint}"
    return Diagnostic(codes.UNKNOWN_UNIT, Severity.ERROR, msg, span)
