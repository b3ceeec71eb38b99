"""Plain helpers for the backend tests: import with `from backend_fixtures import ...`
(pytest puts this folder on sys.path). See conftest.py for the fixtures."""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from rmot.compiler import ir, planned
from rmot.lang.source import Pos, SourceFile, Span

DEMO_FILE = SourceFile("demo.rmot", "\n" * 200)


def span_at(line: int) -> Span:
    """A one-character span at column 3 of `line` in demo.rmot."""
    return Span(DEMO_FILE, Pos(line, 3, 0), Pos(line, 4, 0))


FRONT_UP_NOFLIP = ir.Config(ir.Shoulder.FRONT, ir.Elbow.UP, ir.Wrist.NOFLIP)


def motion(speed: float = 0.25, joint: float = 1.0, zone: float = 0.0,
           duration: float | None = None) -> ir.Motion:
    """A Motion in SI units (speed m/s, zone radius m)."""
    return ir.Motion(tcp_speed=speed, tcp_accel=2.0, joint_speed=joint, joint_accel=1.0,
                     zone=ir.Zone(zone), duration=duration)


def cell(robot: str = "abb_irb120", dof: int = 6) -> ir.Cell:
    r1 = ir.RobotInstance("r1", ir.RobotSource(ir.RobotSourceKind.LIBRARY, robot), ir.Pose(), dof)
    return ir.Cell("democell", (r1,))


def hand_plan(body: tuple[ir.Instr, ...], records: dict[int, tuple[np.ndarray, ir.Config | None]],
              *, robot: str = "abb_irb120", dof: int = 6, name: str = "demo",
              durations: dict[int, float] | None = None) -> planned.Plan:
    """A Plan built by hand: `records` maps a move's uid to (q_target (dof,), branch).

    Moves of If arms and proc bodies are looked up the same way. Each record lasts 1 s unless
    `durations` says otherwise; the trajectory is two samples (backends do not read it).
    """
    durations = durations or {}
    recs = []
    t = 0.0
    for node in ir.walk(body):
        if node.uid in records:
            q, branch = records[node.uid]
            d = durations.get(node.uid, 1.0)
            tcp = node.target.pose if isinstance(node, ir.Move) and isinstance(node.target, ir.CartesianTarget) else None
            recs.append(planned.InstructionRecord(uid=node.uid, span=node.span, t_start=t, t_end=t + d,
                                                  q_target=np.asarray(q, float), branch=branch, tcp_pose=tcp,
                                                  q_via=np.asarray(q, float) if getattr(node, "via", None) else None))
            t += d
    traj = planned.Trajectory(np.array([0.0, max(t, 0.004)]), np.zeros((2, dof)), np.zeros((2, dof)),
                              np.zeros((2, dof)))
    task = ir.Task("main", "r1", body, span=span_at(1))
    program = ir.Program(name, cell(robot, dof), (task,), span=span_at(1))
    return planned.Plan(program, (planned.TaskPlan(task, "r1", traj, tuple(recs)),))


def deg(*values: float) -> np.ndarray:
    return np.radians(np.array(values, float))


