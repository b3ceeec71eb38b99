"""The planner's decision of a task's load (lang/payload.py): where each part sits on the
flange when it is attached, from the flange pose at the target of the move before the attach,
and each part's centroid (a mesh part's read from its file, sim/meshio.centroid). Decided
before the task is timed, so the torque bound of the timing is the load every later reader
takes from the plan (TaskPlan.load)."""

from __future__ import annotations

import numpy as np

from rmot.lang import ir, ir_tree, payload
from rmot.compiler.plan.robot_model import RobotModel
from rmot.compiler.plan.targets import check_joint_values, flange_target

__all__ = ["decide_load"]


def decide_load(robot: RobotModel, task: ir.Task, program: ir.Program) -> payload.TaskLoad:
    """The task's load: tool and held parts after each attach/detach, and their heaviest."""
    if not program.cell.parts:
        return payload.decide(task, program, {}, {})
    return payload.decide(task, program, _target_flanges(robot, task), part_centroids(program.cell.parts))


def _target_flanges(robot: RobotModel, task: ir.Task) -> dict[int, ir.Pose]:
    """Move uid -> the flange pose at its target (robot base frame): a pose target's
    target * inv(tool), a joint target's forward kinematics (a joint target that does not fit
    the robot has none; the planner reports it)."""
    out: dict[int, ir.Pose] = {}
    for move in ir_tree.walk(task.body):
        if not isinstance(move, ir.Move):
            continue
        if isinstance(move.target, ir.CartesianTarget):
            out[move.uid] = ir.Pose.from_matrix(flange_target(move))
        else:
            q, findings = check_joint_values(robot, move.target.values)
            if q is not None and not findings:
                out[move.uid] = ir.Pose.from_matrix(np.asarray(robot.fk(q), dtype=float))
    return out


def part_centroids(parts: tuple[ir.Part, ...]) -> dict[str, tuple[float, float, float]]:
    """Part name -> the centroid of its mesh in its geometry frame (m), for the mesh parts whose
    file loads (one that does not is reported by the verification; its mass stays at the
    part's pose origin). Boxes, cylinders, spheres and capsules are centred on their pose."""
    from rmot.sim.meshio import MeshData, centroid, load_mesh  # late: trimesh/OpenCASCADE, only for mesh parts

    out: dict[str, tuple[float, float, float]] = {}
    for part in parts:
        if isinstance(part.geometry, ir.Mesh):
            data = load_mesh(part.geometry)
            if isinstance(data, MeshData):
                out[part.name] = centroid(data)
    return out
