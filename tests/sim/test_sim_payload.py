"""The torque check's payload sits where every backend writes it: half way to the TCP."""

from __future__ import annotations

import numpy as np
from simkit import arm3, cell

from rmot.lang import ir, plan_types
from rmot.sim.scene import build_scene, flange_in_last_joint
from rmot.sim.verification import _payload


def test_payload_at_half_the_tcp_offset() -> None:
    """A 2 kg tool with its TCP at (0.02, -0.04, 0.2) m loads the arm at (0.01, -0.02, 0.1) m."""
    tcp = ir.Pose((0.02, -0.04, 0.2))
    tool = ir.Tool("gun", "r1", None, tcp, mass=2.0)
    scene = build_scene(cell([("r1", (0, 0, 0))], tools=[tool]), {"r1": {"gun"}}, {"r1": arm3("r1")})
    motion = ir.Motion(tcp_speed=0.25, tcp_accel=2.0, joint_speed=1.0, joint_accel=1.0, zone=ir.Zone(0.0))
    move = ir.Move(uid=1, kind=ir.MotionKind.JOINT, target=ir.JointTarget((0.0, 0.0, 0.0)), via=None,
                   motion=motion, tool=ir.ToolRef("gun", tcp, 2.0), frame=ir.FrameRef(None))
    task = ir.Task("main", "r1", (move,))
    traj = plan_types.Trajectory(np.array([0.0, 1.0]), np.zeros((2, 3)), np.zeros((2, 3)), np.zeros((2, 3)))
    mass, at = _payload(scene, plan_types.TaskPlan(task, "r1", traj, ()))
    flange = flange_in_last_joint(scene.robots["r1"].robot)
    assert mass == 2.0
    assert at is not None
    np.testing.assert_allclose(at, flange[:3, :3] @ np.array([0.01, -0.02, 0.1]) + flange[:3, 3], atol=1e-12)
