"""A small serial arm with the robot API (ROBOT_API.md) built on a hand-made pinocchio model,
so the simulator's tests do not depend on the robot library.

`arm3()`: J1 about z at the base, J2 and J3 about y; links are capsules along their joint's z.
At q = 0 the arm stands straight up: J2 at z=0.4, J3 at z=0.9, flange at z=1.3.
`arm6()`: a 6R arm of the same style for the benchmark.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from rmot.lang import ir


@dataclass(frozen=True)
class LinkSolid:
    name: str
    joint_id: int
    geometry: ir.Geometry
    placement: ir.Pose


class FakeRobot:
    """Joint values are pinocchio's q; the flange is at `flange` in the last joint's frame."""

    def __init__(self, name: str, axes: list[str], offsets: list[tuple[float, float, float]],
                 flange: tuple[float, float, float], solids: list[LinkSolid],
                 adjacent: tuple[tuple[int, int], ...], vmax: float = 3.0, amax: float = 10.0,
                 effort: float = 1e6) -> None:
        self.name = name
        self.model = pin.Model()
        parent = 0
        for i, (axis, off) in enumerate(zip(axes, offsets, strict=True)):
            jm = {"z": pin.JointModelRZ(), "y": pin.JointModelRY(), "x": pin.JointModelRX()}[axis]
            parent = self.model.addJoint(parent, jm, pin.SE3(np.eye(3), np.array(off)), f"j{i + 1}")
            inertia = pin.Inertia.FromCylinder(2.0, 0.05, 0.3)
            self.model.appendBodyToJoint(parent, inertia, pin.SE3(np.eye(3), np.array([0, 0, 0.15])))
        self.model.effortLimit[:] = effort
        self.data = self.model.createData()
        self.dof = len(axes)
        self.joint_types = ("R",) * self.dof
        self.joint_limits = np.tile([-np.pi, np.pi], (self.dof, 1))
        self.velocity_limits = np.full(self.dof, vmax)
        self.accel_limits = np.full(self.dof, amax)
        self.reach = float(sum(np.linalg.norm(o) for o in offsets[1:]) + np.linalg.norm(flange))
        self.has_inertia = True
        self.solids = tuple(solids)
        self.adjacent_pairs = adjacent
        self._flange = pin.SE3(np.eye(3), np.array(flange))

    def _fk(self, q: np.ndarray) -> None:
        pin.forwardKinematics(self.model, self.data, np.asarray(q, dtype=float))

    def fk(self, q: np.ndarray) -> np.ndarray:
        self._fk(q)
        return (self.data.oMi[self.dof] * self._flange).homogeneous

    def fk_batch(self, Q: np.ndarray) -> np.ndarray:
        return np.array([self.fk(q) for q in Q])

    def solid_poses(self, q: np.ndarray) -> np.ndarray:
        self._fk(q)
        return np.array([(self.data.oMi[s.joint_id] if s.joint_id else pin.SE3.Identity()).homogeneous
                         @ s.placement.matrix() for s in self.solids])

    def solid_poses_batch(self, Q: np.ndarray) -> np.ndarray:
        return np.array([self.solid_poses(q) for q in Q]).reshape(len(Q), len(self.solids), 4, 4)


def _capsule(name: str, joint: int, length: float, radius: float, z: float) -> LinkSolid:
    return LinkSolid(name, joint, ir.Capsule(radius, length), ir.Pose((0.0, 0.0, z)))


def arm3(name: str = "arm3", vmax: float = 3.0, amax: float = 10.0, effort: float = 1e6) -> FakeRobot:
    solids = [
        _capsule("base", 0, 0.2, 0.08, 0.1),
        _capsule("link1", 1, 0.3, 0.06, 0.2),
        _capsule("link2", 2, 0.5, 0.05, 0.25),
        _capsule("link3", 3, 0.4, 0.04, 0.2),
    ]
    return FakeRobot(name, ["z", "y", "y"], [(0, 0, 0), (0, 0, 0.4), (0, 0, 0.5)], (0, 0, 0.4),
                     solids, ((0, 1), (1, 2), (2, 3), (0, 2)), vmax, amax, effort)


def arm6(name: str = "arm6") -> FakeRobot:
    solids = [
        _capsule("base", 0, 0.2, 0.08, 0.1),
        _capsule("link1", 1, 0.3, 0.06, 0.2),
        _capsule("link2", 2, 0.45, 0.05, 0.225),
        _capsule("link3", 3, 0.3, 0.045, 0.15),
        _capsule("link4", 4, 0.1, 0.04, 0.05),
        _capsule("link5", 5, 0.1, 0.04, 0.05),
        _capsule("link6", 6, 0.05, 0.035, 0.025),
    ]
    adjacent = tuple((i, i + 1) for i in range(6)) + ((3, 5), (4, 6), (3, 6), (0, 2))
    return FakeRobot(name, ["z", "y", "y", "z", "y", "z"],
                     [(0, 0, 0), (0, 0, 0.4), (0, 0, 0.45), (0, 0, 0.3), (0, 0, 0.1), (0, 0, 0.1)],
                     (0, 0, 0.06), solids, adjacent)


# --------------------------------------------------------------------------- hand-made plans

from rmot.lang import plan_types  # noqa: E402
from rmot.lang.source import Pos, SourceFile, Span  # noqa: E402

PROGRAM_PATH = "prog.rmot"


def source(lines: int = 40) -> SourceFile:
    """A fake program file: line k reads `  move joint p{k}`."""
    text = "program p on r1 {\n" + "".join(f"  move joint p{k}\n" for k in range(2, lines + 1)) + "}\n"
    return SourceFile(PROGRAM_PATH, text)


def line_span(file: SourceFile, line: int) -> Span:
    text = file.line_text(line)
    start = len(text) - len(text.lstrip()) + 1
    return Span(file, Pos(line, start, 0), Pos(line, len(text) + 1, 0))


def quintic(q0: np.ndarray, q1: np.ndarray, t: np.ndarray, duration: float) -> tuple[np.ndarray, ...]:
    """Rest-to-rest straight joint move with a quintic time law; t in [0, duration]."""
    tau = np.clip(t / duration, 0, 1)[:, None]
    s = 10 * tau**3 - 15 * tau**4 + 6 * tau**5
    sd = (30 * tau**2 - 60 * tau**3 + 30 * tau**4) / duration
    sdd = (60 * tau - 180 * tau**2 + 120 * tau**3) / duration**2
    dq = (q1 - q0)[None]
    return q0 + s * dq, sd * dq, sdd * dq


def task_plan(task_name: str, robot: str, waypoints: list, durations: list[float], file: SourceFile,
              first_line: int = 2, t0: float = 0.0, step: float = 0.004, first_uid: int = 1,
              tool: ir.ToolRef | None = None) -> plan_types.TaskPlan:
    """Moves from waypoints[k] to waypoints[k+1] in durations[k] s; move k is on line first_line+k.
    A duration of a move between equal waypoints is a wait (still a Move record)."""
    tool = tool or ir.ToolRef(None)
    motion = ir.Motion(0.5, 2.0, 1.0, 1.0, ir.Zone(0.0))
    moves, records, ts, qs, qds, qdds = [], [], [], [], [], []
    t_start = t0
    for k, dur in enumerate(durations):
        q0, q1 = np.asarray(waypoints[k], float), np.asarray(waypoints[k + 1], float)
        span = line_span(file, first_line + k)
        uid = first_uid + k
        moves.append(ir.Move(uid=uid, kind=ir.MotionKind.JOINT, target=ir.JointTarget(tuple(q1)),
                             motion=motion, tool=tool, frame=ir.FrameRef(None), span=span))
        n = max(1, round(dur / step))
        local = np.arange(n + (k == len(durations) - 1)) * step
        q, qd, qdd = quintic(q0, q1, local, dur)
        ts.append(t_start + local)
        qs.append(q)
        qds.append(qd)
        qdds.append(qdd)
        records.append(plan_types.InstructionRecord(uid, span, t_start, t_start + n * step, q_target=q1))
        t_start += n * step
    traj = plan_types.Trajectory(np.concatenate(ts), np.concatenate(qs), np.concatenate(qds), np.concatenate(qdds))
    task = ir.Task(task_name, robot, tuple(moves))
    return plan_types.TaskPlan(task, robot, traj, tuple(records))


def make_plan(cell: ir.Cell, tasks: list[plan_types.TaskPlan], file: SourceFile) -> plan_types.Plan:
    program = ir.Program("p", cell, tuple(tp.task for tp in tasks), span=line_span(file, 1))
    return plan_types.Plan(program, tuple(tasks))


def cell(robots: list[tuple[str, tuple[float, float, float]]], fixtures=(), tools=(), allowed=()) -> ir.Cell:
    inst = tuple(ir.RobotInstance(name, ir.RobotSource(ir.RobotSourceKind.LIBRARY, "fake"), ir.Pose(pos), 3)
                 for name, pos in robots)
    return ir.Cell("c", inst, tuple(fixtures), tuple(tools), allowed_contacts=tuple(allowed))


def box(name: str, size, at, rpy=(0.0, 0.0, 0.0)) -> ir.Fixture:
    return ir.Fixture(name, ir.Box(tuple(size)), ir.Pose.from_xyz_rpy(*at, *rpy))
