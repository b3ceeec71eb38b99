"""Write a robot's new base pose into the cell's text: only the `at POSE` of its declaration
changes (lang/REFERENCE.md §4: `robot NAME = MODEL [at POSE]`); every other byte is kept."""

from __future__ import annotations

import math
import re

import numpy as np

from rmot.lang import ir

__all__ = ["pose_text", "with_robot_at"]


def _num(v: float) -> str:
    text = f"{v:.3f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def pose_text(base: np.ndarray) -> str:
    """pose(x=..mm, y=..mm, z=..mm[, rx=..deg, ry=..deg][, rz=..deg]) of a (4,4) world pose."""
    rx, ry, rz = ir.Pose.from_matrix(np.asarray(base, dtype=float)).rpy()
    x, y, z = (float(v) * 1000 for v in base[:3, 3])
    parts = [f"x={_num(x)}mm", f"y={_num(y)}mm", f"z={_num(z)}mm"]
    for key, angle in (("rx", rx), ("ry", ry), ("rz", rz)):
        deg = math.degrees(angle)
        if abs(deg) > 5e-4:
            parts.append(f"{key}={_num(deg)}deg")
    return f"pose({', '.join(parts)})"


def with_robot_at(text: str, start: int, end: int, base: np.ndarray) -> str:
    """`text` with the robot declaration at [start, end) (offsets of its span) placed at `base`."""
    decl = text[start:end]
    match = re.search(r"\bat\b", decl)
    new = (decl[: match.start()] if match else decl.rstrip() + " ") + "at " + pose_text(base)
    return text[:start] + new + text[end:]
