"""Hand-made plans for the render tests: a small arm, a table, a tool, one move (no planner)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from rmot.lang import ir, plan_types


@dataclass(frozen=True)
class Solid:
    name: str
    joint_id: int
    geometry: ir.Geometry
    placement: ir.Pose


class Arm3:
    """A 3R arm with the robot API (ROBOT_API.md) on a hand-made pinocchio model.

    J1 about z at the base, J2 and J3 about y; capsule links along z. At q = 0 it stands
    straight up: J2 at z = 0.4, J3 at z = 0.9, flange at z = 1.3.
    """

    name = vendor = "arm3"
    dof = 3
    joint_types = ("R", "R", "R")
    joint_limits = np.tile([-np.pi, np.pi], (3, 1))
    reach = 0.9

    def __init__(self) -> None:
        self.model = pin.Model()
        parent = 0
        for i, (axis, z) in enumerate(zip("zyy", (0.0, 0.4, 0.5))):
            joint = pin.JointModelRZ() if axis == "z" else pin.JointModelRY()
            parent = self.model.addJoint(parent, joint, pin.SE3(np.eye(3), np.array([0.0, 0.0, z])), f"j{i + 1}")
        self.data = self.model.createData()
        caps = [("base", 0, 0.2, 0.08, 0.1), ("link1", 1, 0.3, 0.06, 0.2), ("link2", 2, 0.5, 0.05, 0.25),
                ("link3", 3, 0.4, 0.04, 0.2)]
        self.solids = tuple(Solid(n, j, ir.Capsule(r, length), ir.Pose((0.0, 0.0, z))) for n, j, length, r, z in caps)
        self.adjacent_pairs = ((0, 1), (1, 2), (2, 3), (0, 2))
        self._flange = pin.SE3(np.eye(3), np.array([0.0, 0.0, 0.4]))

    def fk(self, q: np.ndarray) -> np.ndarray:
        pin.forwardKinematics(self.model, self.data, np.asarray(q, float))
        return (self.data.oMi[3] * self._flange).homogeneous

    def fk_batch(self, q: np.ndarray) -> np.ndarray:
        return np.array([self.fk(row) for row in q])

    def solid_poses(self, q: np.ndarray) -> np.ndarray:
        pin.forwardKinematics(self.model, self.data, np.asarray(q, float))
        return np.array([(self.data.oMi[s.joint_id].homogeneous if s.joint_id else np.eye(4)) @ s.placement.matrix()
                         for s in self.solids])

    def solid_poses_batch(self, q: np.ndarray) -> np.ndarray:
        return np.array([self.solid_poses(row) for row in q]).reshape(len(q), len(self.solids), 4, 4)


def arm3() -> Arm3:
    return Arm3()


def cell() -> ir.Cell:
    robot = ir.RobotInstance("r1", ir.RobotSource(ir.RobotSourceKind.LIBRARY, "arm3"), ir.Pose(), 3)
    table = ir.Fixture("table", ir.Box((0.6, 0.8, 0.4)), ir.Pose((0.8, 0.0, 0.2)))
    post = ir.Fixture("post", ir.Cylinder(0.05, 1.0), ir.Pose((0.0, 0.9, 0.5)))
    tool = ir.Tool("gripper", "r1", ir.Cylinder(0.04, 0.12), ir.Pose((0.0, 0.0, 0.12)), geometry_pose=ir.Pose((0.0, 0.0, 0.06)))
    return ir.Cell("demo", (robot,), (table, post), (tool,))


def plan(duration: float = 2.0, step: float = 0.004) -> plan_types.Plan:
    """r1 swings J1 from -0.6 to 0.6 rad and J2/J3 forward, over `duration` s, with the gripper."""
    c = cell()
    motion = ir.Motion(tcp_speed=0.5, tcp_accel=2.0, joint_speed=1.0, joint_accel=1.0, zone=ir.Zone())
    move = ir.Move(uid=1, kind=ir.MotionKind.JOINT, target=ir.JointTarget((0.6, 0.9, 0.9)), motion=motion,
                   tool=ir.ToolRef("gripper", c.tools[0].tcp), frame=ir.FrameRef(None))
    task = ir.Task("main", "r1", (move,))
    program = ir.Program("demo", c, (task,))
    t = np.arange(0.0, duration + step / 2, step)
    s = (t / duration)[:, None]
    q = np.array([-0.6, 0.3, 0.6]) + s * np.array([1.2, 0.6, 0.3])
    zeros = np.zeros_like(q)
    traj = plan_types.Trajectory(t, q, zeros, zeros.copy())
    record = plan_types.InstructionRecord(1, None, 0.0, duration, q_target=q[-1])
    return plan_types.Plan(program, (plan_types.TaskPlan(task, "r1", traj, (record,)),), step)
