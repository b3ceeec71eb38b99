"""Hand-built IR programs for the planner tests (no parser needed).

`Prog` builds a task instruction by instruction; each instruction gets uid = its line number
in a synthetic source file, so a test can check that a diagnostic points at the right line.
"""

from __future__ import annotations

import math

import numpy as np

from rmot.lang import ir
from rmot.lang.source import Pos, SourceFile, Span

SOURCE = SourceFile("prog.rmot", "".join(f"instruction {i}\n" for i in range(1, 400)))


def span(line: int) -> Span:
    offset = sum(len(f"instruction {i}\n") for i in range(1, line))
    return Span(SOURCE, Pos(line, 1, offset), Pos(line, 12, offset + 11))


def pose(x: float = 0, y: float = 0, z: float = 0, rx: float = 0, ry: float = 0, rz: float = 0) -> ir.Pose:
    """Millimetres and degrees, like the language."""
    r = math.radians
    return ir.Pose.from_xyz_rpy(x / 1e3, y / 1e3, z / 1e3, r(rx), r(ry), r(rz))


def motion(speed: float = 250, zone: float = 0.0, joint_speed: float = 1.0, accel: float = 2.0,
           joint_accel: float = 1.0, duration: float | None = None) -> ir.Motion:
    """speed mm/s, zone mm, accel m/s^2."""
    return ir.Motion(speed / 1e3, accel, joint_speed, joint_accel, ir.Zone(zone / 1e3), duration)


class Counter:
    def __init__(self) -> None:
        self.n = 0

    def next(self) -> int:
        self.n += 1
        return self.n


class Prog:
    """One task's body, built in order; uids (= lines) come from a shared counter."""

    def __init__(self, counter: Counter | None = None, tool: ir.ToolRef | None = None) -> None:
        self.counter = counter or Counter()
        self.body: list[ir.Instr] = []
        self.tool = tool or ir.ToolRef(None)

    def _uid(self) -> int:
        return self.counter.next()

    def _target(self, t):  # type: ignore[no-untyped-def]
        if isinstance(t, ir.Pose):
            return ir.CartesianTarget(t, t)
        return ir.JointTarget(tuple(math.radians(v) for v in t))

    def move(self, kind: ir.MotionKind, target, via=None, config=ir.Config(), **kw) -> int:  # type: ignore[no-untyped-def]
        uid = self._uid()
        self.body.append(ir.Move(
            uid=uid, kind=kind, target=self._target(target),
            via=ir.CartesianTarget(via, via) if via is not None else None,
            motion=motion(**kw), tool=self.tool, frame=ir.FrameRef(None), config=config, span=span(uid)))
        return uid

    def joint(self, target, **kw) -> int:  # type: ignore[no-untyped-def]
        """target: a Pose or joint values in degrees."""
        return self.move(ir.MotionKind.JOINT, target, **kw)

    def linear(self, target, **kw) -> int:  # type: ignore[no-untyped-def]
        return self.move(ir.MotionKind.LINEAR, target, **kw)

    def circular(self, via: ir.Pose, target: ir.Pose, **kw) -> int:  # type: ignore[no-untyped-def]
        return self.move(ir.MotionKind.CIRCULAR, target, via=via, **kw)

    def wait(self, seconds: float) -> int:
        uid = self._uid()
        self.body.append(ir.WaitTime(uid=uid, duration=seconds, span=span(uid)))
        return uid

    def set(self, port: int, value: bool) -> int:
        uid = self._uid()
        self.body.append(ir.SetDigital(uid=uid, port=port, value=value, span=span(uid)))
        return uid

    def pulse(self, port: int, seconds: float) -> int:
        uid = self._uid()
        self.body.append(ir.Pulse(uid=uid, port=port, duration=seconds, span=span(uid)))
        return uid

    def sync(self, name: str) -> int:
        uid = self._uid()
        self.body.append(ir.Sync(uid=uid, name=name, span=span(uid)))
        return uid

    def if_(self, then: Prog, otherwise: Prog) -> int:
        uid = self._uid()
        cond = ir.InputCondition(port=1, value=True)
        self.body.append(ir.If(uid=uid, condition=cond, then=tuple(then.body),
                               otherwise=tuple(otherwise.body), span=span(uid)))
        return uid

    def task(self, name: str = "main", robot: str = "r1") -> ir.Task:
        return ir.Task(name, robot, tuple(self.body))


def program(*tasks: ir.Task, robots: dict[str, str] | None = None) -> ir.Program:
    """A cell with the named library robots (default r1 = abb_irb120)."""
    robots = robots or {"r1": "abb_irb120"}
    insts = tuple(
        ir.RobotInstance(name, ir.RobotSource(ir.RobotSourceKind.LIBRARY, key), ir.Pose(), 6)
        for name, key in robots.items()
    )
    return ir.Program("test", ir.Cell("cell", insts), tasks)


def tcp_positions(robot, q: np.ndarray, tool: ir.Pose | None = None) -> np.ndarray:  # type: ignore[no-untyped-def]
    t = tool.matrix() if tool is not None else np.eye(4)
    return (robot.fk_batch(q) @ t)[:, :3, 3]
