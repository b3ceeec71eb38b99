"""URDF robots through pinocchio's parser: a serial arm, its limits and collision solids.

Meshes resolve relative to the file (and `package://` URIs against the file's folder and
its ancestors). The flange is the frame named tool0, flange or ee_link (in that order),
else the last body of the chain. Accelerations are not in URDF: 4 × the velocity limit per
second, as for the library. Reach: the largest distance of the flange from the J1 axis
over 4096 deterministic random configurations. Branch names: 6R arms with a spherical wrist
get them from their geometry (`wrist_branches`); other arms have none.
"""

from __future__ import annotations

import math
import os
from typing import Any

import numpy as np
import pinocchio as pin

from rmot.lang import ir
from rmot.sim.robots import codes
from rmot.sim.robots.errors import RobotError
from rmot.sim.robots.robot import LinkSolid, Robot

__all__ = ["robot_from_urdf", "urdf_links"]

_FLANGE_NAMES = ("tool0", "flange", "ee_link")


def robot_from_urdf(path: str, base: str | None = None, tip: str | None = None, controller: str | None = None) -> Robot:
    """base/tip: the links bounding the arm (`urdf("f.urdf", base=, tip=)`); joints outside
    the chain between them (fingers, a rail before the base) are locked at 0 (within their
    limits) and the base link's frame becomes the robot's base frame; the flange is the tip.
    controller: the maker whose pendant values the URDF joint values are, as ROS-Industrial's
    driver passes them (sim/robots/controller.py); None: undeclared."""
    if os.path.isdir(path):
        raise RobotError(f"'{path}' is a directory, not a URDF file", codes.BAD_URDF)
    if not os.path.isfile(path):
        raise RobotError(f"URDF file '{path}' does not exist", codes.BAD_URDF)
    try:
        model = pin.buildModelFromUrdf(path)
        geoms = pin.buildGeomFromUrdf(model, path, pin.GeometryType.COLLISION, package_dirs=_package_dirs(path))
    except Exception as exc:  # pinocchio raises bare RuntimeError/ValueError for any defect
        why = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
        raise RobotError(f"cannot load URDF '{path}': {why}", codes.BAD_URDF) from None
    flange_name = None
    if base is not None or tip is not None:
        from rmot.sim.robots.urdf_chain import reduce_to_chain  # late: loads subprocess only when this runs

        try:
            model, geoms = reduce_to_chain(model, geoms, base, tip)
        except ValueError as exc:
            raise RobotError(f"URDF '{path}': {exc}", codes.BAD_URDF) from None
        flange_name = tip
    if model.nq == 0:
        raise RobotError(f"URDF '{path}' has no movable joint", codes.BAD_URDF)
    try:
        robot = _robot(model, geoms, path, flange_name, controller)
    except ValueError as exc:
        raise RobotError(f"URDF '{path}' is not a usable serial arm: {exc}", codes.BAD_URDF) from None
    return robot


def _package_dirs(path: str) -> list[str]:
    folder = os.path.dirname(os.path.abspath(path))
    dirs = [folder]
    while os.path.dirname(folder) != folder:
        folder = os.path.dirname(folder)
        dirs.append(folder)
    return dirs


def _flange_frame(model: pin.Model, first: str | None = None) -> int:
    for name in ((first,) if first else _FLANGE_NAMES):
        if model.existFrame(name):
            return model.getFrameId(name)
    last_joint = model.njoints - 1
    bodies = [i for i, f in enumerate(model.frames) if f.parentJoint == last_joint and f.type == pin.FrameType.BODY]
    return bodies[-1] if bodies else model.addFrame(pin.Frame("flange", last_joint, pin.SE3.Identity(), pin.FrameType.OP_FRAME))


def _robot(model: pin.Model, geoms: pin.GeometryModel, path: str, flange_name: str | None = None,
           controller: str | None = None) -> Robot:
    from rmot.sim.robots.controller import in_joint_values  # late: loads subprocess only when this runs
    from rmot.sim.robots.kinematic_chain import chain_of  # late: loads subprocess only when this runs

    chain = chain_of(model)  # raises ValueError for branched chains and multi-dof joints
    fid = _flange_frame(model, flange_name)
    limits = np.column_stack([model.lowerPositionLimit, model.upperPositionLimit])
    if not np.all(np.isfinite(limits)) or np.any(limits[:, 0] >= limits[:, 1]):
        raise ValueError("every joint needs finite lower < upper position limits")
    velocity = np.where(model.velocityLimit > 0, model.velocityLimit, 1.0)
    solids = tuple(s for s in (_solid(g) for g in geoms.geometryObjects) if s is not None)
    name = os.path.splitext(os.path.basename(path))[0]
    coupling, conventions = _controller_coupling(controller, model.nq)
    common = dict(
        name=name, vendor="URDF", model_name=model.name or name, model=model, flange_frame=fid,
        joint_limits=limits, velocity_limits=velocity, accel_limits=4.0 * velocity, reach=0.0,
        solids=solids, adjacent_pairs=_adjacent(solids), has_inertia=any(i.mass > 0 for i in model.inertias[1:]),
        source=path, controller=controller, conventions=conventions,
    )
    closed_form, branch_fn, rows = _kinematics(Robot(**common), chain)
    # Fanuc: the URDF's joint_3 is J2 + J3; its limits stay the joint limits, as ROS-I's fanuc
    # files give the data sheet's J3 range there; the closed form and branch names read the
    # URDF joints and are turned into pendant values
    if coupling is not None and branch_fn is not None:
        closed_form, branch_fn = in_joint_values(closed_form, branch_fn, coupling)
    robot = Robot(**common, coupling=coupling, closed_form=closed_form, branch_fn=branch_fn, batch_branches=rows)
    robot.reach = _reach(robot)
    return robot


def _kinematics(probe: Robot, chain: Any) -> tuple[Any, Any, Any]:
    """(closed form, branch function, batch rows) of a URDF arm: the OPW closed form when its
    geometry is ortho-parallel with a spherical wrist, proven by FK at random configurations
    (model_opw, as for a cell's model), else the geometric branch names of a spherical wrist
    (wrist_branches) with the numeric IK, else none."""
    from rmot.sim.robots.model_opw import opw_solver_for  # late: loads subprocess only when this runs
    from rmot.sim.robots.wrist_branches import spherical_wrist_branch_fn  # late: loads subprocess only when this runs

    opw = opw_solver_for(probe) if probe.dof == 6 and not np.any(chain.prismatic) else None
    if opw is not None:
        return opw
    return None, spherical_wrist_branch_fn(probe.model, chain.axes, chain.prismatic, probe.joint_limits), None


def _controller_coupling(controller: str | None, dof: int) -> tuple[np.ndarray | None, tuple[tuple[str, str], ...]]:
    """The joint coupling and the conventions a URDF arm declared for `controller` has (ROS-I
    drivers pass the pendant values one to one; Fanuc's fanuc_driver J23_factor = 1)."""
    from rmot.sim.robots.controller import ANY, MAKERS, fanuc_urdf_coupling  # late: loads subprocess only when this runs

    if controller is None:
        return None, ()
    if controller == ANY:
        return None, (("controller", "any: the URDF's joint values and frames as they are (declared by the cell)"),)
    frames = (("base frame", "the URDF link at base= (ROS-Industrial `base`: the controller's base frame)"),
              ("flange frame", "the URDF link at tip= (ROS-Industrial `tool0`: the controller's flange)"))
    if MAKERS[controller] == "FANUC" and dof == 6:
        return fanuc_urdf_coupling(dof), frames + (
            ("signs", "teach pendant values; the URDF joints one to one but J3"),
            ("coupling", "URDF joint_3 = J2 + J3 (ros-industrial/fanuc fanuc_driver linkage_transform, J23_factor = 1)"))
    return None, frames + (("signs", f"{MAKERS[controller]} pendant values one to one (ROS-Industrial driver)"),)


def _solid(g: pin.GeometryObject) -> LinkSolid | None:
    import coal  # late: coal is heavy or optional, loaded only where used

    shape = g.geometry
    if isinstance(shape, coal.Box):
        geom: ir.Geometry = ir.Box(tuple(float(2 * h) for h in shape.halfSide))  # type: ignore[arg-type]
    elif isinstance(shape, coal.Capsule):
        geom = ir.Capsule(float(shape.radius), float(2 * shape.halfLength))
    elif isinstance(shape, coal.Cylinder):
        geom = ir.Cylinder(float(shape.radius), float(2 * shape.halfLength))
    elif isinstance(shape, coal.Sphere):
        geom = ir.Sphere(float(shape.radius))
    elif g.meshPath:
        geom = ir.Mesh(os.path.abspath(g.meshPath), float(g.meshScale[0]))
    else:
        return None
    return LinkSolid(g.name, int(g.parentJoint), geom, ir.Pose.from_matrix(g.placement.homogeneous))


def _adjacent(solids: tuple[LinkSolid, ...]) -> tuple[tuple[int, int], ...]:
    return tuple(
        (i, j) for i, a in enumerate(solids) for j, b in enumerate(solids) if i < j and abs(a.joint_id - b.joint_id) <= 1
    )


def _reach(robot: Robot) -> float:
    qs = np.random.default_rng(0).uniform(robot.joint_limits[:, 0], robot.joint_limits[:, 1], (4096, robot.dof))
    flange = robot.fk_batch(qs)[:, :3, 3]
    first = robot._chain.placements[0]
    axis = first[:3, :3] @ robot._chain.axes[0]
    rel = flange - first[:3, 3]
    radial = rel - np.outer(rel @ axis, axis)
    return float(math.sqrt(np.max(np.sum(radial * radial, axis=1))))


def urdf_links(path: str) -> tuple[str, ...]:
    """The link names of a URDF file, in file order (raises RobotError when it cannot load)."""
    try:
        model = pin.buildModelFromUrdf(path)
    except Exception as exc:  # pinocchio raises bare RuntimeError/ValueError for any defect
        raise RobotError(f"cannot load URDF '{path}': {type(exc).__name__}", codes.BAD_URDF) from None
    return tuple(f.name for f in model.frames if f.type == pin.FrameType.BODY)


def urdf_chain_error(path: str, base: str, tip: str) -> str | None:
    """Why base..tip is no chain of joints in the URDF (tip not below base, no joint), else None."""
    from rmot.sim.robots.urdf_chain import chain_joints  # late: loads subprocess only when this runs

    model = pin.buildModelFromUrdf(path)
    try:
        joints = chain_joints(model, base, tip)
    except ValueError as exc:
        return str(exc)
    return None if joints else f"no movable joint between links '{base}' and '{tip}'"
