"""The Robot: a pinocchio model plus limits, solids, a flange frame and IK.

Built once per robot (see `load_robot`); immutable afterwards. `fk` and `jacobian` reuse
one pinocchio Data, so a Robot is not safe to share between threads.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np
import pinocchio as pin

from rmot.lang import ir
from rmot.sim.robots.kinematic_chain import Chain, chain_of
from rmot.lang.record import record
import copy

if TYPE_CHECKING:
    from rmot.sim.robots.ik import IkResult

__all__ = ["LinkSolid", "Robot"]


@record(slots=True)
class LinkSolid:
    """A collision/display solid: `geometry` placed at `placement` in joint `joint_id`'s frame
    (pinocchio joint index; 0 = fixed to the robot base)."""

    name: str
    joint_id: int
    geometry: ir.Geometry
    placement: ir.Pose


class NamedModel(pin.Model):  # type: ignore[misc]  # pinocchio has no type information
    """The pinocchio Model that prints as the vendor's model name.

    The API calls both the vendor model string and the pinocchio Model `model`: this is the
    real Model (pass it to any pinocchio function) whose str() and format() give the name."""

    def __init__(self, model: pin.Model, label: str) -> None:
        super().__init__(model)
        self._label = label

    def __str__(self) -> str:
        return self._label

    def __format__(self, spec: str) -> str:
        return format(self._label, spec)


class Robot:
    """One arm. Joint values are the controller's (rad / m); poses are (4,4) in metres.

    Attributes: name, vendor, model (the pinocchio Model, read-only; str(model) is the
    vendor's model name), model_name (that name as a plain str, e.g. "IRB 120-3/0.58"),
    dof, joint_types, joint_limits (dof,2),
    velocity_limits (dof,), accel_limits (dof,), reach (m), has_closed_form, has_inertia,
    solids, adjacent_pairs, source (where the numbers come from), batch_branches (the
    ir.Config of each of the 8 ik_batch rows, fixed per robot; None without a closed form),
    rated_payload_kg (the data sheet's rated payload, kg; None when unknown), sources
    ((quantity, source) pairs: where each number comes from), conventions ((topic, text)
    pairs: base frame, flange frame, joint zero, signs, couplings), controller (the maker
    whose pendant values the joint values are, as `controller.MAKERS` names it; "any" when the
    cell vouches for every controller; None when nothing declares it: vendor targets refuse).
    """

    rated_payload_kg: float | None = None  # the rated payload (kg), where known

    def __init__(
        self, *, name: str, vendor: str, model_name: str, model: pin.Model, flange_frame: int,
        joint_limits: np.ndarray, velocity_limits: np.ndarray, accel_limits: np.ndarray,
        reach: float, solids: tuple[LinkSolid, ...], adjacent_pairs: tuple[tuple[int, int], ...],
        coupling: np.ndarray | None = None, closed_form: Callable[[np.ndarray], np.ndarray] | None = None,
        branch_fn: Callable[[np.ndarray], ir.Config] | None = None,
        workspace_distance: Callable[[np.ndarray], float] | None = None,
        has_inertia: bool = False, source: str = "", dh_rows: tuple[Any, ...] = (), dh_modified: bool = False,
        batch_branches: tuple[ir.Config, ...] | None = None, rated_payload_kg: float | None = None,
        sources: tuple[tuple[str, str], ...] = (), conventions: tuple[tuple[str, str], ...] = (),
        controller: str | None = None,
    ) -> None:
        self.name, self.vendor, self.model_name, self.source = name, vendor, model_name, source
        self.model = model = NamedModel(model, model_name)
        self._data = model.createData()
        self._fid = flange_frame
        self._flange_joint = model.frames[flange_frame].parentJoint
        self._flange_in_joint = model.frames[flange_frame].placement.homogeneous
        self.dof = model.nq
        self.joint_types = tuple("P" if model.joints[j].shortname().startswith("JointModelP") else "R" for j in range(1, model.njoints))
        self.joint_limits = _frozen(joint_limits)
        self._revolute = np.array([t == "R" for t in self.joint_types])
        self._revolute_list = self._revolute.tolist()
        self._lo, self._hi = self.joint_limits[:, 0].tolist(), self.joint_limits[:, 1].tolist()
        self.velocity_limits = _frozen(velocity_limits)
        self.accel_limits = _frozen(accel_limits)
        self.reach = float(reach)
        self.solids = solids
        self.adjacent_pairs = adjacent_pairs
        self.has_closed_form = closed_form is not None
        self.has_inertia = has_inertia
        self.dh_rows, self.dh_modified = dh_rows, dh_modified
        self._coupling = None if coupling is None else _frozen(coupling)
        self._closed_form = closed_form
        self._branch_fn = branch_fn
        self._workspace_distance = workspace_distance
        self._chain: Chain = chain_of(model)
        self._dls_args: tuple[Any, ...] | None = None  # filled on first numeric IK
        self._restarts: np.ndarray | None = None  # numeric IK restart seeds, drawn once
        self._fast: Any = None  # ik's compiled single-pose solver (fastsolve), made on first use
        self._solid_joint = np.array([s.joint_id for s in solids], dtype=int)
        self._solid_place = np.array([s.placement.matrix() for s in solids]).reshape(-1, 4, 4)
        self._solid_se3 = [pin.SE3(m) for m in self._solid_place]
        self.batch_branches = batch_branches
        self.rated_payload_kg = None if rated_payload_kg is None else float(rated_payload_kg)
        self.sources, self.conventions = sources, conventions
        self.controller = controller

    def __repr__(self) -> str:
        return f"Robot({self.name!r}, dof={self.dof})"

    def calibrated(self, speed_share: float, accel_share: float) -> Robot:
        """This arm with its joint speed and acceleration limits scaled by the shares a cell
        gives (`robot r1 = NAME speed S % accel A %`: the user's calibration of the arm to its
        real controller, e.g. to match a measured cycle); its sources say so."""

        out = copy.copy(self)
        out.velocity_limits = _frozen(self.velocity_limits * speed_share)
        out.accel_limits = _frozen(self.accel_limits * accel_share)
        scaled = {"speed": speed_share, "accel": accel_share}
        out.sources = tuple((k, f"x {scaled[k] * 100:g} % by the cell (calibration) of: {v}"
                             if scaled.get(k, 1.0) != 1.0 else v) for k, v in self.sources)
        return out

    # ----------------------------------------------------------------- joint spaces
    def to_model(self, q: np.ndarray) -> np.ndarray:
        """Controller values (..., dof) -> pinocchio q (differs only under Fanuc's J2/J3 coupling)."""
        q = np.asarray(q, dtype=float)
        return q if self._coupling is None else q @ self._coupling.T

    def _check(self, q: np.ndarray) -> np.ndarray:
        q = np.asarray(q, dtype=float)
        if q.shape != (self.dof,):
            raise ValueError(f"{self.name}: q must have shape ({self.dof},) (got {q.shape})")
        return q if self._coupling is None else self._coupling @ q

    # ----------------------------------------------------------------- kinematics
    def fk(self, q: np.ndarray) -> np.ndarray:
        """q: (dof,) -> (4,4) the flange in the base frame (m)."""
        qm = self._check(q)
        pin.forwardKinematics(self.model, self._data, qm)
        return pin.updateFramePlacement(self.model, self._data, self._fid).homogeneous

    def fk_batch(self, qs: np.ndarray) -> np.ndarray:
        """qs: (N,dof) -> (N,4,4)."""
        frames = self._chain.joint_frames(self.to_model(np.atleast_2d(qs)))
        return frames[:, self._flange_joint - 1] @ self._flange_in_joint

    def jacobian(self, q: np.ndarray) -> np.ndarray:
        """q: (dof,) -> (6,dof) geometric Jacobian of the flange, base axes, linear rows first."""
        qm = self._check(q)
        j = pin.computeFrameJacobian(self.model, self._data, qm, self._fid, pin.LOCAL_WORLD_ALIGNED)
        return j if self._coupling is None else j @ self._coupling

    def manipulability(self, q: np.ndarray) -> float:
        """Yoshikawa's sqrt(det(J Jᵀ)) (0 at a singularity)."""
        return float(np.prod(np.linalg.svd(self.jacobian(q), compute_uv=False)))

    def condition(self, q: np.ndarray) -> float:
        """σmax/σmin of the Jacobian with its angular rows scaled by the reach (inf at a singularity)."""
        j = self.jacobian(q).copy()
        j[3:] *= max(self.reach, 1e-3)
        s = np.linalg.svd(j, compute_uv=False)
        return float(s[0] / s[-1]) if s[-1] > 0 else float("inf")

    def branch(self, q: np.ndarray) -> ir.Config:
        """The configuration of q (all fields set for closed-form 6R arms and for URDF 6R arms
        with a spherical wrist, all None otherwise). See `rmot.sim.robots.branches` and
        `rmot.sim.robots.wrist_branches` for the exact definitions."""
        if self._branch_fn is None:
            return ir.Config()
        return self._branch_fn(np.asarray(q, dtype=float))

    # ----------------------------------------------------------------- solids
    def solid_poses(self, q: np.ndarray) -> np.ndarray:
        """q: (dof,) -> (S,4,4) each solid's pose in the base frame."""
        qm = self._check(q)
        pin.forwardKinematics(self.model, self._data, qm)
        omi = self._data.oMi
        return np.array([(omi[int(j)] * p).homogeneous for j, p in zip(self._solid_joint, self._solid_se3)]).reshape(-1, 4, 4)

    def solid_poses_batch(self, qs: np.ndarray) -> np.ndarray:
        """qs: (N,dof) -> (N,S,4,4)."""
        qs = np.atleast_2d(qs)
        frames = self._chain.joint_frames(self.to_model(qs))
        base = np.broadcast_to(np.eye(4), (len(qs), 1, 4, 4))
        all_frames = np.concatenate([base, frames], axis=1)  # index = pinocchio joint id
        return all_frames[:, self._solid_joint] @ self._solid_place

    # ----------------------------------------------------------------- IK
    def ik(self, pose: np.ndarray, seed: np.ndarray | None = None,
           config: ir.Config | None = None) -> IkResult:
        """Every solution of the flange pose within limits, nearest to seed first -> IkResult."""
        solve = _IK_SOLVE[0] if _IK_SOLVE else _ik_solve()  # no import statement per call
        return solve(self, pose, seed, config)

    def ik_batch(self, poses: np.ndarray, seed: np.ndarray | None = None) -> np.ndarray:
        """poses: (N,4,4) -> (N,8,dof): one joint vector per branch (closed-form robots; row
        order as the solver's), the equivalent within limits nearest to seed (default 0);
        NaN where the branch does not exist or has no equivalent within the limits. For
        robots without a closed form, row 0 holds the numeric solution nearest to seed."""
        from rmot.sim.robots.ik import solve_batch  # late: loads subprocess only when this runs

        return solve_batch(self, poses, seed)

    def ik_closed_form(self, poses: np.ndarray) -> np.ndarray:
        """Raw closed form: (N,4,4) -> (N,8,dof) controller values, not wrapped into limits,
        not verified; NaN where a branch does not exist. Raises if there is no closed form."""
        if self._closed_form is None:
            raise ValueError(f"{self.name} has no closed-form IK")
        return self._closed_form(np.asarray(poses, dtype=float).reshape(-1, 4, 4))


_IK_SOLVE: list[Callable[..., IkResult]] = []  # ik.solve, imported on the first Robot.ik


def _ik_solve() -> Callable[..., IkResult]:
    from rmot.sim.robots.ik import solve  # late: loads subprocess only when this runs

    _IK_SOLVE.append(solve)
    return solve


def _frozen(a: np.ndarray) -> np.ndarray:
    out = np.array(a, dtype=float)
    out.setflags(write=False)
    return out
