"""Build a Robot from a library spec: pinocchio model, solids, adjacency, closed-form IK."""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin

from rmot.lang import ir
from rmot.sim.robots.branches import opw_branch_arrays, opw_branch_fn, ur_branch_arrays, ur_branch_fn
from rmot.sim.robots.closed_form import ClosedForm
from rmot.sim.robots.dh import build_model
from rmot.sim.robots.opw import OpwJointMap, OpwParams
from rmot.sim.robots.robot import LinkSolid, Robot
from rmot.sim.robots.spec import RobotSpec, Segment
from rmot.sim.robots.urik import UrParams

__all__ = ["build_robot"]


def build_robot(spec: RobotSpec) -> Robot:
    model, fid, _ = build_model(spec.dh, np.array(spec.flange), spec.name)
    coupling = None if spec.coupling is None else np.array(spec.coupling, dtype=float)
    solids = _solids(model, spec, coupling)
    if spec.link_mass_kg:
        _add_dynamics(model, fid, spec, coupling)
    closed_form = branch_fn = distance = rows = None
    if spec.opw is not None:
        closed_form, distance = _opw_solver(*spec.opw, np.linalg.inv(np.array(spec.flange)))
        branch_fn = opw_branch_fn(*spec.opw)
        rows = _row_branches(opw_rows=True, j5_sign=spec.opw[1].sign[4])
    elif spec.ur is not None:
        closed_form, distance = _ur_solver(spec.ur)
        branch_fn = ur_branch_fn(spec.ur)
        rows = _row_branches(opw_rows=False, j5_sign=1.0)
    return Robot(
        name=spec.name, vendor=spec.vendor, model_name=spec.model, model=model, flange_frame=fid,
        joint_limits=np.radians(spec.limits_deg), velocity_limits=np.radians(spec.speed_deg_s),
        accel_limits=np.radians(spec.accel_deg_s2), reach=spec.reach, solids=solids,
        adjacent_pairs=_adjacent(solids, spec.extra_adjacent), coupling=coupling,
        closed_form=closed_form, branch_fn=branch_fn, workspace_distance=distance,
        source=spec.source, dh_rows=spec.dh.rows, dh_modified=spec.dh.modified, batch_branches=rows,
        has_inertia=bool(spec.link_mass_kg), rated_payload_kg=spec.rated_payload_kg,
        sources=spec.sources, conventions=spec.conventions, controller=spec.vendor,
    )


def _add_dynamics(model: pin.Model, fid: int, spec: RobotSpec, coupling: np.ndarray | None) -> None:
    """Link inertias (dynamics.link_inertias) and joint torque limits (the spec's, else
    dynamics.estimate_effort) written into the model."""
    from rmot.sim.robots import dynamics  # late: loads subprocess only when this runs

    data = model.createData()
    q = np.array(spec.solid_pose, dtype=float)
    pin.forwardKinematics(model, data, q if coupling is None else coupling @ q)
    frames = [data.oMi[j].homogeneous for j in range(1, model.njoints)]
    if spec.link_inertia:
        inertias = dynamics.given_inertias(spec.link_inertia, spec.link_mass_kg, frames)
    else:
        inertias = dynamics.link_inertias(spec.segments, spec.link_mass_kg, frames)
    for j, inertia in enumerate(inertias, start=1):
        model.inertias[j] = inertia
    if spec.effort_nm:
        effort = np.array(spec.effort_nm, dtype=float)
    else:
        effort = dynamics.estimate_effort(model, coupling, np.radians(spec.limits_deg), np.radians(spec.accel_deg_s2),
                                          spec.rated_payload_kg or 0.0,
                                          model.frames[fid].placement.homogeneous)
    model.effortLimit = effort


def _row_branches(opw_rows: bool, j5_sign: float) -> tuple[ir.Config, ...]:
    """The branch of each closed-form row. OPW rows: 4·wrist + 2·shoulder + elbow with the
    first wrist having θ5 >= 0 (J5 = sign5·θ5); UR rows: 4·shoulder + 2·wrist + elbow. Index 0
    is FRONT, UP and θ5 >= 0."""
    out = []
    for row in range(8):
        w, s, e = (row // 4, (row // 2) % 2, row % 2) if opw_rows else ((row // 2) % 2, row // 4, row % 2)
        theta5_negative = w == 1
        flip = theta5_negative if j5_sign > 0 else not theta5_negative
        out.append(ir.Config(ir.Shoulder.BACK if s else ir.Shoulder.FRONT, ir.Elbow.DOWN if e else ir.Elbow.UP,
                             ir.Wrist.FLIP if flip else ir.Wrist.NOFLIP))
    return tuple(out)


def _solids(model: pin.Model, spec: RobotSpec, coupling: np.ndarray | None) -> tuple[LinkSolid, ...]:
    """Each segment, given in the base frame at spec.solid_pose, moved into its joint's frame."""
    data = model.createData()
    q = np.array(spec.solid_pose, dtype=float)
    pin.forwardKinematics(model, data, q if coupling is None else coupling @ q)
    return tuple(_solid(seg, data.oMi[seg.joint].homogeneous) for seg in spec.segments)


def _solid(seg: Segment, joint_frame: np.ndarray) -> LinkSolid:
    p0, p1 = np.array(seg.p0), np.array(seg.p1)
    axis = p1 - p0
    length = float(np.linalg.norm(axis))
    world = np.eye(4)
    world[:3, :3] = _frame_with_z(axis / length if length > 1e-12 else np.array([0.0, 0.0, 1.0]))
    world[:3, 3] = (p0 + p1) / 2
    local = np.linalg.inv(joint_frame) @ world
    if seg.joint == 0:  # flat bottom: the base stands on the floor or a fixture
        geometry: ir.Geometry = ir.Cylinder(radius=seg.radius, height=length)
    else:
        geometry = ir.Capsule(radius=seg.radius, length=length)
    return LinkSolid(seg.name, seg.joint, geometry, ir.Pose.from_matrix(local))


def _frame_with_z(z: np.ndarray) -> np.ndarray:
    helper = np.array([1.0, 0.0, 0.0]) if abs(z[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    x = np.cross(helper, z)
    x /= np.linalg.norm(x)
    return np.column_stack([x, np.cross(z, x), z])


def _adjacent(solids: tuple[LinkSolid, ...], extra: tuple[tuple[str, str], ...]) -> tuple[tuple[int, int], ...]:
    """Consecutive solids of the chain (listed base to flange; they share a joint and touch at
    every configuration), plus named pairs that touch by design."""
    names = {s.name: i for i, s in enumerate(solids)}
    pairs = {(i, i + 1) for i in range(len(solids) - 1)}
    pairs |= {tuple(sorted((names[a], names[b]))) for a, b in extra if a in names and b in names}  # type: ignore[misc]
    return tuple(sorted(pairs))


def _opw_solver(p: OpwParams, jmap: OpwJointMap, flange_inv: np.ndarray):  # type: ignore[no-untyped-def]
    """flange_inv: the vendor flange -> OPW flange transform (identity unless turned).
    The numba kernels load on the first IK call, not when the robot is built: `robots list`,
    `show`, `fk` and the front end never pay for numba."""
    from rmot.sim.robots import fastik  # no numba: its kernels compile on first use  # late: loads subprocess only when this runs

    turned = not np.allclose(flange_inv, np.eye(4))
    closed_form = ClosedForm("opw", fastik.opw_kernel_args(p, jmap), None, flange_inv if turned else None,
                             opw_branch_arrays(p, jmap))

    def distance(pose: np.ndarray) -> float:
        c = pose[:3, 3] - p.c4 * pose[:3, 2]  # the flange turn is about z: same axis
        rho2 = c[0] ** 2 + c[1] ** 2
        if rho2 < p.b ** 2:
            return p.b - math.sqrt(rho2)
        nx1 = math.sqrt(rho2 - p.b ** 2)
        gaps = []
        for x in (nx1 - p.a1, nx1 + p.a1):  # J2 in front of / behind the J1 axis
            s = math.hypot(x, c[2] - p.c1)
            gaps.append(max(s - (p.c2 + p.forearm), abs(p.c2 - p.forearm) - s, 0.0))
        return min(gaps)

    return closed_form, distance


def _ur_solver(p: UrParams):  # type: ignore[no-untyped-def]
    p_arr = np.array([p.d1, p.a2, p.a3, p.d4, p.d5, p.d6])
    closed_form = ClosedForm("ur", (p_arr,), branch=ur_branch_arrays(p))

    def distance(pose: np.ndarray) -> float:
        p05 = pose[:3, 3] - p.d6 * pose[:3, 2]
        r = math.hypot(p05[0], p05[1])
        if r < p.d4:
            return p.d4 - r
        reach = abs(p.a2) + abs(p.a3)
        shoulder = np.array([0.0, 0.0, p.d1])
        planar = math.sqrt(max(np.sum((p05 - shoulder) ** 2) - p.d4 ** 2, 0.0))
        return max(planar - reach - p.d5, abs(abs(p.a2) - abs(p.a3)) - planar - p.d5, 0.0)

    return closed_form, distance
