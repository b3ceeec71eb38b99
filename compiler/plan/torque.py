"""Joint torque limits for the timing: a heavy payload slows the motion rather than
exceeding the motors.

Along a path q(s) timed by x = ds/dt^2 and u = d2s/dt2 the joint torques are affine in (u, x):

    tau(s) = a(s) u + b(s) x + c(s),   a = M(q) q',   b = M(q) q'' + C(q, q') q',   c = g(q),

computed by inverse dynamics (the recursive Newton-Euler algorithm on the pinocchio model,
vectorised over the points: compiler/plan/rnea.py, checked against pinocchio.rnea) at each
grid point: c = RNEA(q, 0, 0),
a = RNEA(q, 0, q') - c, b = RNEA(q, q', q'') - c. |tau_j| <= tau_max_j is then one more pair
of acceleration rows of the time-optimal parametrisation (compiler/plan/topp.py, one-sided:
gravity makes the interval lopsided) and is re-checked inside every grid cell like the
joints' acceleration limits (compiler/plan/timing.py).

Where they apply: a robot with inertia data whose model gives every joint a finite positive
torque limit (`effortLimit`) — exactly where the verification checks torque (sim/limits.py),
so a timing that respects them is one the torque check passes. Those limits are cited where a
source gives them (UR, KUKA/kroshu, Stäubli descriptions; a cell `model`'s `torque`) and
otherwise estimated (sim/robots/dynamics.EFFORT_METHOD); `rmot robots show` names which.

The payload is the task's peak load as the planner decides it before timing
(compiler/plan/load.py, lang/payload.py; carried on the plan as TaskPlan.load, which the
verification's torque check reads too): the heaviest tool the task uses, its mass at
ir.payload_cog, plus the heaviest set of parts it holds at once, each at its centroid fixed at
its attach.

A chain is first timed without torque rows; only when its torques, sampled every
`CHECK_STEP`, exceed a limit is it timed again with them (chain.py), so every program whose
motion the motors already manage plans exactly as before.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

__all__ = ["CHECK_STEP", "TorqueLimits", "exceeds", "torque_limits"]

CHECK_STEP = (
    0.002  # s: the torque of a timed chain is sampled this often to decide whether it binds
)

@dataclass(frozen=True, eq=False)
class TorqueLimits:
    """model: a pinocchio Model with the payload on its last joint (a copy, never the robot's);
    limit (dof,) N·m (N for a prismatic joint); to_model: controller -> model joint values
    (a linear map: Fanuc's J2/J3 coupling), applied to positions and their derivatives alike."""

    model: Any
    limit: np.ndarray
    to_model: Any
    dof: int

    def rows(
        self, q: np.ndarray, d1: np.ndarray, d2: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(a, b, c) each (N, dof) at path points q (N, dof) with derivatives q', q'' in s."""
        qm, v1, v2 = (
            np.asarray(self.to_model(np.asarray(v, dtype=float)), dtype=float) for v in (q, d1, d2)
        )
        dyn, dof = self.dynamics, self.dof
        zero = np.zeros_like(qm)
        c = dyn.rnea(qm, zero, zero)[:, :dof]
        return dyn.rnea(qm, zero, v1)[:, :dof] - c, dyn.rnea(qm, v1, v2)[:, :dof] - c, c

    def torques(self, q: np.ndarray, qd: np.ndarray, qdd: np.ndarray) -> np.ndarray:
        """(N, dof) joint torques along sampled motion (controller values)."""
        qm, vm, am = (
            np.asarray(self.to_model(np.asarray(v, dtype=float)), dtype=float) for v in (q, qd, qdd)
        )
        return self.dynamics.rnea(qm, vm, am)[:, : self.dof]  # type: ignore[no-any-return]

    @property
    def dynamics(self) -> Any:
        """The vectorised RNEA of the payload model (compiler/plan/rnea.py), built on first use."""
        found = self.__dict__.get("_dynamics")
        if found is None:
            from rmot.compiler.plan.rnea import Dynamics  # late: loads coal only when this runs

            found = Dynamics(self.model)
            object.__setattr__(self, "_dynamics", found)
        return found


def torque_limits(robot: Any, mass: float, at: np.ndarray | None) -> TorqueLimits | None:
    """The robot's torque limits with `mass` kg at `at` (flange frame), or None where the
    verification checks no torque either (no inertia data, or a joint without a finite positive
    limit)."""
    if not getattr(robot, "has_inertia", False):
        return None
    import pinocchio as pin  # late: pinocchio is heavy or optional, loaded only where used

    dof = int(robot.dof)
    limit = np.asarray(robot.model.effortLimit, dtype=float)[:dof]
    if limit.shape != (dof,) or not (np.all(np.isfinite(limit)) and np.all(limit > 0)):
        return None
    model = pin.Model(robot.model)
    if mass > 0:
        in_joint = flange_in_last_joint(robot) @ np.append(
            np.zeros(3) if at is None else np.asarray(at, dtype=float), 1.0
        )
        model.inertias[dof] = model.inertias[dof] + pin.Inertia(
            float(mass), in_joint[:3], np.zeros((3, 3))
        )
    return TorqueLimits(model, limit.copy(), getattr(robot, "to_model", lambda v: v), dof)


def flange_in_last_joint(robot: Any) -> np.ndarray:
    """(4,4) the flange frame in the last joint's frame (constant; taken at mid-range)."""
    import pinocchio as pin  # late: pinocchio is heavy or optional, loaded only where used

    q = np.asarray(robot.joint_limits, dtype=float).mean(axis=1)
    model = robot.model
    data = model.createData()
    pin.forwardKinematics(model, data, np.asarray(robot.to_model(q), dtype=float))
    joint = np.linalg.inv(data.oMi[int(robot.dof)].homogeneous)
    return joint @ np.asarray(robot.fk(q))  # type: ignore[no-any-return]


# samples per block of `exceeds`: the inverse dynamics of a whole blended chain at once held
# ~1 kB a sample (a 2000-move chain: 350,000 samples, 380 MB)
EXCEEDS_CHUNK = 16_384


def exceeds(limits: TorqueLimits, piece: Any) -> bool:
    """Whether the timed piece's torques, sampled every CHECK_STEP and at its end, exceed a
    limit. The samples are taken EXCEEDS_CHUNK at a time (each sample's torque is the same
    arithmetic on its own time either way), up to the first block with an excess."""
    duration = float(piece.duration)
    if duration <= 0:
        return False
    n = int(np.ceil(duration / CHECK_STEP)) + 1
    times = np.linspace(0.0, duration, n)
    for lo in range(0, n, EXCEEDS_CHUNK):
        q, qd, qdd = piece.sample(times[lo:lo + EXCEEDS_CHUNK])
        if np.any(np.abs(limits.torques(q, qd, qdd)) > limits.limit):
            return True
    return False
