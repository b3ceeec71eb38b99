"""Whether a vendor's configuration data can select a planned joint value.

KRL's Turn holds only the sign of each axis (KSS 8.x System Integrators manual, "Status and
Turn") and INFORM's RCONF only whether R, T and S lie outside -180 < a <= 180 deg (DX100
156191-1CD section 4.1): both tell a joint's 360-degree equivalents apart only within +-360
deg. A planned value of 360 deg or more in magnitude has an equivalent 360 deg nearer zero with
the same sign and the same flag (390 and 30 deg for KRL; 390 and -330 deg for INFORM), which a
joint range wide enough for the first holds as well: the controller could take either, so the
backend refuses (E440) a joint move to such a position instead of writing one that may not
be the verified one (a linear or circular move runs on from the current joints). A
backend sees no joint limits (it never imports the robot library), so this is the bound it can
check; every KUKA and Yaskawa arm of the library lies within it (A4/A6 <= +-350, T +-360 deg).
"""

from __future__ import annotations

import math
from collections.abc import Iterable

import numpy as np

__all__ = ["beyond_one_turn", "message"]

_FULL = 2 * math.pi - 1e-9


def beyond_one_turn(q: np.ndarray, axes: Iterable[int]) -> list[int]:
    """The axes (0-based, among `axes`) whose planned value is 360 deg or more in magnitude."""
    return [j for j in axes if abs(float(q[j])) >= _FULL]


def message(q: np.ndarray, axes: list[int], what: str) -> str:
    """The E440 message for `axes` of `q` (what: the vendor's configuration data)."""
    shown = ", ".join(f"joint {j + 1} at {math.degrees(float(q[j])):.1f} deg" for j in axes)
    return (f"{what} must select the planned joints (got {shown}: the same data fits the value "
            "360 deg nearer zero); fix a turn within +-360 deg with config(jN=n), or move there "
            "with a joint target")
