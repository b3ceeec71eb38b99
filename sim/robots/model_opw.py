"""OPW parameters from a chain's geometry: the closed-form IK for 6R cell models.

A 6R chain is ortho-parallel with a spherical wrist when some fixed base frame B and flange
transform F make its FK  T(q) = B · T_opw(θ(q)) · F  with θ = sign·q + offset (the OPW
chain of `opw.py`). The parameters are read off the joint axes at q = 0 (in B):

  B        origin on the J1 axis (the foot of the model's base origin), z along ±J1, y along
           ±J2 (so at q = 0 the arm lies in B's x-z plane and θ1 = 0);
  a1, c1   the J2 axis' x and z; c2 and θ2(0) the J3 axis' distance and direction from J2;
  θ2+θ3(0) the direction of the J4 axis (±), a2 and c3 the wrist centre from J3 in that
           rotated frame, b the wrist centre's y;
  θ4(0), θ5(0) from the J5 and J6 axis directions, c4 the flange origin along J6 from the
           wrist centre; θ6(0) = 0 and F = T_opw(θ(0))⁻¹ B⁻¹ T(0).

Each of the eight sign choices (±J1, ±J2, ±J4) is tried; a candidate is accepted only when,
at 24 random configurations within the limits, the closed form reproduces the model's FK
(1e-9 m, 1e-9 rad) and one of its rows is the configuration itself (mod 2π). Anything else
(not OPW, or a geometry this derivation does not cover) returns None: the caller falls back
to the numeric IK.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np

from rmot.lang import ir
from rmot.sim.robots.opw import OpwJointMap, OpwParams

if TYPE_CHECKING:
    from rmot.sim.robots.robot import Robot

_Opw = tuple[OpwParams, OpwJointMap, np.ndarray, np.ndarray]  # params, joint map, base, flange

__all__ = ["derive_opw", "opw_solver_for"]

_CHECKS = 24
_TOL = 1e-9


def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.linalg.norm(v)


def _ry(t: float) -> np.ndarray:
    c, s = math.cos(t), math.sin(t)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def _rz(t: float) -> np.ndarray:
    c, s = math.cos(t), math.sin(t)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _axes(robot) -> tuple[np.ndarray, np.ndarray, np.ndarray]:  # type: ignore[no-untyped-def]
    """At q = 0: joint axis points (6,3), directions (6,3), the flange (4,4), in the model base."""
    frames = robot._chain.joint_frames(np.zeros((1, 6)))[0]
    pts = frames[:, :3, 3]
    dirs = np.einsum("nij,nj->ni", frames[:, :3, :3], robot._chain.axes)
    return pts, dirs, robot.fk(np.zeros(6))


def derive_opw(robot, geometric_branch=None) -> tuple[OpwParams, OpwJointMap, np.ndarray, np.ndarray] | None:  # type: ignore[no-untyped-def]
    """(params, joint map, B, F) verified on the robot's FK, or None.

    geometric_branch: the arm's branch function from its geometry (wrist_branches); among the
    verified sign choices the first whose OPW branch names agree with it at the check
    configurations wins (so the names do not depend on how the DH frames were drawn), else
    the first verified one."""
    from rmot.sim.robots.wrist_branches import wrist_centre  # late: loads subprocess only when this runs

    if robot.dof != 6 or any(t != "R" for t in robot.joint_types) or robot._coupling is not None:
        return None
    pts, dirs, flange0 = _axes(robot)
    centre = wrist_centre(robot.model, robot._chain.axes, np.zeros(6))
    if centre is None or abs(dirs[0] @ dirs[1]) > 1e-9 or np.linalg.norm(np.cross(dirs[1], dirs[2])) > 1e-9:
        return None
    verified = []
    for z_sign in (1.0, -1.0):
        for y_sign in (1.0, -1.0):
            for u_sign in (1.0, -1.0):
                found = _candidate(robot, pts, dirs, flange0, centre, z_sign, y_sign, u_sign)
                if found is not None and _verified(robot, *found):
                    if geometric_branch is None or _names_agree(robot, found, geometric_branch):
                        return found
                    verified.append(found)
    return verified[0] if verified else None


def _names_agree(robot, found, geometric_branch) -> bool:  # type: ignore[no-untyped-def]
    from rmot.sim.robots.branches import opw_branch_fn  # late: loads subprocess only when this runs

    branch = opw_branch_fn(found[0], found[1])
    rng = np.random.default_rng(5)
    qs = rng.uniform(robot.joint_limits[:, 0], robot.joint_limits[:, 1], (_CHECKS, 6))
    return all(branch(q) == geometric_branch(q) for q in qs)


def _candidate(robot: Robot, pts: np.ndarray, dirs: np.ndarray, flange0: np.ndarray, centre: np.ndarray,
               z_sign: float, y_sign: float, u_sign: float) -> _Opw | None:
    z = z_sign * dirs[0]
    y = y_sign * dirs[1]
    x = np.cross(y, z)
    origin = pts[0] + ((-pts[0]) @ dirs[0]) * dirs[0]  # foot of the model base origin on J1
    b_mat = np.eye(4)
    b_mat[:3, :3] = np.column_stack([x, y, z])
    b_mat[:3, 3] = origin
    rot = b_mat[:3, :3].T

    def local(p: np.ndarray) -> np.ndarray:
        return rot @ (p - origin)

    j2, j3, c = local(pts[1]), local(pts[2]), local(centre)
    a1, c1 = float(j2[0]), float(j2[2])
    dx, dz = float(j3[0] - a1), float(j3[2] - c1)
    c2 = math.hypot(dx, dz)
    if c2 < 1e-6:
        return None
    theta2 = math.atan2(dx, dz)
    u4 = rot @ (u_sign * dirs[3])
    if abs(u4[1]) > 1e-9:
        return None
    theta23 = math.atan2(u4[0], u4[2])
    vx, vz = float(c[0] - j3[0]), float(c[2] - j3[2])
    a2 = vx * math.cos(theta23) - vz * math.sin(theta23)
    c3 = vx * math.sin(theta23) + vz * math.cos(theta23)
    b = float(c[1])
    r0c = _ry(theta23)
    w5 = rot @ dirs[4]
    f = r0c.T @ w5
    theta4 = math.atan2(-f[0], f[1])
    flange_local = local(flange0[:3, 3])
    w6 = rot @ dirs[5]
    c4 = float((flange_local - c) @ w6)
    if c4 < -1e-12:
        w6, c4 = -w6, -c4
    g = _rz(theta4).T @ r0c.T @ w6
    theta5 = math.atan2(g[0], g[2])
    # the model's positive rotation about each axis against the OPW one's
    signs = (z_sign, y_sign, y_sign * float(np.sign(dirs[2] @ dirs[1])), u_sign, 1.0, float(np.sign((rot @ dirs[5]) @ w6)))
    # θ = sign·q + offset; at q = 0: θ = offset
    offsets = (0.0, theta2, theta23 - theta2, theta4, theta5, 0.0)
    params = OpwParams(a1=a1, a2=a2, b=b, c1=c1, c2=c2, c3=c3, c4=c4)
    jmap = OpwJointMap(sign=signs, offset=offsets)
    from rmot.sim.robots.opw import opw_fk  # late: loads subprocess only when this runs

    t_opw0 = opw_fk(params, np.array([offsets]))[0]
    f_mat = np.linalg.inv(t_opw0) @ np.linalg.inv(b_mat) @ flange0
    return params, jmap, b_mat, f_mat


def _verified(robot, params: OpwParams, jmap: OpwJointMap, b_mat: np.ndarray, f_mat: np.ndarray) -> bool:  # type: ignore[no-untyped-def]
    from rmot.sim.robots import fastik  # late: loads subprocess only when this runs

    rng = np.random.default_rng(12)
    lo, hi = robot.joint_limits[:, 0], robot.joint_limits[:, 1]
    qs = rng.uniform(np.maximum(lo, -math.pi), np.minimum(hi, math.pi), (_CHECKS, 6))
    poses = robot.fk_batch(qs)
    args = fastik.opw_kernel_args(params, jmap)
    local = np.linalg.inv(b_mat) @ poses @ np.linalg.inv(f_mat)
    with np.errstate(invalid="ignore"):
        rows = fastik.opw_solve(args, local)  # (N,8,6)
    for q, pose, sol in zip(qs, poses, rows):
        ok = ~np.isnan(sol).any(axis=1)
        if not ok.any():
            return False
        back = robot.fk_batch(sol[ok])
        err = np.abs(back - pose).max(axis=(1, 2))
        if err.max() > _TOL:
            return False
        wrapped = np.angle(np.exp(1j * (sol[ok] - q)))
        if np.abs(wrapped).max(axis=1).min() > 1e-7:
            return False
    return True


def opw_solver_for(robot: Robot) -> tuple[Callable[[np.ndarray], np.ndarray], Callable[[np.ndarray], ir.Config],
                                          tuple[ir.Config, ...]] | None:
    """(closed_form, branch_fn, batch rows) for a verified OPW chain, else None."""
    from rmot.sim.robots.branches import opw_branch_fn  # late: loads subprocess only when this runs
    from rmot.sim.robots.build import _row_branches  # late: loads subprocess only when this runs

    from rmot.sim.robots.wrist_branches import spherical_wrist_branch_fn  # late: loads subprocess only when this runs

    geometric = spherical_wrist_branch_fn(robot.model, robot._chain.axes, robot._chain.prismatic, robot.joint_limits)
    found = derive_opw(robot, geometric)
    if found is None:
        return None
    params, jmap, b_mat, f_mat = found
    from rmot.sim.robots import fastik  # late: loads subprocess only when this runs

    from rmot.sim.robots.branches import opw_branch_arrays  # late: loads subprocess only when this runs
    from rmot.sim.robots.closed_form import ClosedForm  # late: loads subprocess only when this runs

    closed_form = ClosedForm("opw", fastik.opw_kernel_args(params, jmap), np.linalg.inv(b_mat),
                             np.linalg.inv(f_mat), opw_branch_arrays(params, jmap))
    branch_fn: Callable[[np.ndarray], ir.Config] = opw_branch_fn(params, jmap)
    return closed_form, branch_fn, _row_branches(opw_rows=True, j5_sign=jmap.sign[4])
