"""What an IK solve returns (IkStatus, IkResult, `result`) and the tolerances it decides by,
shared by `ik` (numpy and pinocchio) and its compiled pass `fastsolve` (numba), which must
accept and reject exactly the same poses. A module of their own so that `fastsolve` reads
them without importing `ik`, which loads `fastsolve` when a closed-form arm first needs it."""

from __future__ import annotations

from collections.abc import Sequence
from enum import Enum

import numpy as np

from rmot.lang import ir
from rmot.lang.record import record

__all__ = ["IkResult", "IkStatus", "POS_TOL", "ROT_TOL", "SINGULAR_SIGMA", "is_singular", "result"]

POS_TOL = 1e-9  # m
ROT_TOL = 1e-9  # rad
SINGULAR_SIGMA = 1e-6  # smallest singular value of the Jacobian (reach-scaled) at a singularity


class IkStatus(Enum):
    OK = "ok"
    UNREACHABLE = "unreachable"  # no solution at all (distance says how far outside)
    OUT_OF_LIMITS = "out-of-limits"  # solutions exist, every one violates a joint limit
    SINGULAR = "singular"  # solutions exist (in .solutions) but the pose is on a singularity


@record(slots=True)
class IkResult:
    """status; solutions (dof,) arrays nearest to seed first and `branches` parallel to them
    (immutable sequences that behave as tuples: robots/ik_rows.py; `solutions.array` is all of
    them as one (m, dof) array).
    UNREACHABLE: `distance` (m) from the workspace. OUT_OF_LIMITS: `joint` (0-based index),
    `excess` (rad or m) of the least-violating solution; `message` a sentence for users."""

    status: IkStatus
    solutions: Sequence[np.ndarray] = ()
    branches: Sequence[ir.Config] = ()
    message: str = ""
    distance: float = 0.0
    joint: int | None = None
    excess: float = 0.0

    @property
    def ok(self) -> bool:
        """True when there is at least one solution (OK or SINGULAR)."""
        return bool(self.solutions)


_NEW = object.__new__
_SETTERS = tuple(IkResult.__dict__[f].__set__ for f in
                 ("status", "solutions", "branches", "message", "distance", "joint", "excess"))


def result(status: IkStatus, solutions: Sequence[np.ndarray], branches: Sequence[ir.Config],
           message: str = "") -> IkResult:
    """IkResult(status, solutions, branches, message): the same frozen value, made through its
    slots (half the time of the dataclass's __init__, which Robot.ik pays on every call)."""
    out = _NEW(IkResult)
    s0, s1, s2, s3, s4, s5, s6 = _SETTERS
    s0(out, status)
    s1(out, solutions)
    s2(out, branches)
    s3(out, message)
    s4(out, 0.0)
    s5(out, None)
    s6(out, 0.0)
    return out


def is_singular(robot, q: np.ndarray) -> bool:  # type: ignore[no-untyped-def]
    """True when the smallest reach-scaled singular value of the Jacobian at q is below
    SINGULAR_SIGMA (the SINGULAR status)."""
    j = robot.jacobian(q).copy()
    j[3:] *= max(robot.reach, 1e-3)
    return bool(np.linalg.svd(j, compute_uv=False)[-1] < SINGULAR_SIGMA)
