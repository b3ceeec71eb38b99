"""`config(jN=n)`: the turn of joint N fixed at a move's target.

Turn n of a revolute joint means its value q lies in [n*360 - 180, n*360 + 180) deg
(ir.turn_of; lang/REFERENCE.md section 6). The front end checks what it can know without the
robot's limits: N names a revolute joint of the task's robot (E170) and n is a whole number
(E171). Whether the joint's range exceeds 360 deg, whether turn n lies inside it and whether
the target can be reached on it are the planner's checks (compiler/plan/targets.py,
E172-E174), where the limits are known.
"""

from __future__ import annotations

import math
import re

from rmot.lang import check_codes as codes
from rmot.compiler.passes.context import Reporter, RobotInfo, Scope
from rmot.compiler.passes.evaluate import eval_expr
from rmot.compiler.passes.values import DIMENSIONLESS, Quantity, article, fmt_quantity, type_name
from rmot.lang import ast

__all__ = ["TURN_KEY", "turn_arg"]

TURN_KEY = re.compile(r"j([0-9]+)")
_MAX_TURN = 1000  # far beyond any joint's range; keeps the number an int the planner can use


def turn_arg(
    arg: ast.Arg, scope: Scope, info: RobotInfo, robot: str, rep: Reporter
) -> tuple[int, int] | None:
    """(joint index from 0, turn) of a `jN=n` argument of config(...), or None (reported)."""
    key = arg.name.name if arg.name is not None else ""
    m = TURN_KEY.fullmatch(key)
    assert m is not None, key
    number = int(m.group(1))
    if not 1 <= number <= info.dof:
        rep.error(
            codes.TURN_BAD_JOINT,
            f"config {key} must name a joint of robot '{robot}', j1 to j{info.dof} (got {key})",
            arg.span,
        )
        return None
    if info.joint_types[number - 1] != "R":
        rep.error(
            codes.TURN_BAD_JOINT,
            f"config {key} must name a revolute joint (joint {number} of robot "
            f"'{robot}' is prismatic: it has no turns)",
            arg.span,
        )
        return None
    value = eval_expr(arg.value, scope, rep)
    if value is None:
        return None
    if not isinstance(value, Quantity) or value.dim != DIMENSIONLESS or value.unit is not None:
        got = fmt_quantity(value) if isinstance(value, Quantity) else article(type_name(value))
        rep.error(
            codes.TURN_NOT_WHOLE,
            f"config {key} must be a whole turn number such as -1, 0 or 1 "
            f"(turn n = joint {number} in [n*360 - 180, n*360 + 180) deg; got {got})",
            arg.value.span,
        )
        return None
    x = value.value
    if not math.isfinite(x) or abs(x) > _MAX_TURN or x != int(x):
        rep.error(
            codes.TURN_NOT_WHOLE,
            f"config {key} must be a whole turn number such as -1, 0 or 1 (got {x:g})",
            arg.value.span,
        )
        return None
    return number - 1, int(x)
