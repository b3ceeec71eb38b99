"""Run one program on several arms and collect what a cell designer compares them by.

    results = compare_arms(program, ["abb_irb1600", "kuka_kr16"], slot="r1")

Each arm takes the place of the cell's robot `slot` (`stand_in`: its mounting face where the
slot robot's is, so an arm whose base frame is not at its mounting face -- a Fanuc's, at the
J2 height -- still stands on the same pedestal; with `placements`, at its own placed pose) and
goes through the same planner and verifier as `rmot check`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from rmot.lang import ir
from rmot.lang.diagnostics import Diagnostic, Severity
from rmot.compiler.design.metrics import TaskMetrics, program_metrics, substitute_robot
from rmot.compiler.design.place import rebase
from rmot.sim.robots import load_robot
from rmot.sim.report import Report
import os

__all__ = ["ArmResult", "compare_arms", "mounting_z", "run_arm", "stand_in"]


@dataclass(frozen=True, eq=False)
class ArmResult:
    key: str  # library name or URDF path, as given
    model: str  # the vendor's model name ('' when the robot did not load)
    report: Report
    metrics: TaskMetrics | None  # of the slot's task; None when nothing was planned
    note: str = ""

    @property
    def verified(self) -> bool:
        return not self.report.has_errors

    def first_findings(self, n: int = 3) -> tuple[Diagnostic, ...]:
        return self.report.errors[:n]


def slot_of(program: ir.Program, slot: str | None) -> str:
    """The cell robot the arms stand in for: `slot`, else the robot of the program's first task."""
    if slot is not None:
        program.cell.robot(slot)  # KeyError if absent
        return slot
    return program.tasks[0].robot


def mounting_z(robot: Any) -> float:
    """The z (m) of the lowest point of the robot's base solids (those fixed to its base, joint
    0) in its base frame: the face it stands on. 0 for a robot without base solids."""
    lows = [float(s.placement.matrix()[2, 3]) - _half_height(s.geometry, s.placement.matrix())
            for s in robot.solids if s.joint_id == 0]
    return min(lows, default=0.0)


def _half_height(geometry: ir.Geometry, placement: np.ndarray) -> float:
    """How far a solid reaches below its placement's origin along the base z (m)."""
    axis = np.abs(placement[2, :3])  # the base z in the solid's frame, by component
    if isinstance(geometry, ir.Box):
        return float(axis @ np.asarray(geometry.size, dtype=float)) / 2
    if isinstance(geometry, ir.Sphere):
        return float(geometry.radius)
    if isinstance(geometry, (ir.Cylinder, ir.Capsule)):
        length = geometry.height if isinstance(geometry, ir.Cylinder) else geometry.length
        sideways = float(np.sqrt(max(0.0, 1.0 - axis[2] ** 2)))
        caps = geometry.radius if isinstance(geometry, ir.Capsule) else geometry.radius * sideways
        return float(axis[2] * length / 2 + caps)
    return 0.0  # a mesh base: the base frame is taken as the mounting face


def stand_in(program: ir.Program, slot: str, key: str, robot: Any) -> ir.Program:
    """The program with the loaded `robot` (library name or absolute URDF path `key`) in the
    cell's robot `slot`, its mounting face (mounting_z) where the slot robot's is: the base frame
    moves along its own z by the difference; world-fixed targets stay where they are in the world."""
    old = program.cell.robot(slot)
    rise = mounting_z(load_robot(old.source.load_key)) - mounting_z(robot)
    swapped = substitute_robot(program, slot, key, robot.dof)
    if abs(rise) < 1e-12:
        return swapped
    return rebase(swapped, slot, old.base.matrix() @ _lift(rise))


def _lift(z: float) -> np.ndarray:
    out = np.eye(4)
    out[2, 3] = z
    return out


def run_arm(program: ir.Program, key: str | None, slot: str, path: str) -> ArmResult:
    """Plan and verify `program` with arm `key` in `slot` (None: the cell's own robot)."""
    from rmot.compiler.plan import plan_program  # late: tests replace it (monkeypatch): read at call time
    from rmot.sim.robots import RobotError, load_robot  # late: loads subprocess only when this runs
    from rmot.sim import codes, verify  # late: tests replace it (monkeypatch): read at call time

    model = ""
    if key is not None:
        try:
            robot = load_robot(key)
        except RobotError as exc:
            diag = Diagnostic(codes.ROBOT_UNAVAILABLE, Severity.ERROR, f"robot '{key}' must load ({exc.message})", None)
            return ArmResult(key, "", Report(path, {}, (diag,)), None)

        ref = os.path.abspath(key) if key.lower().endswith(".urdf") else key
        program = stand_in(program, slot, ref, robot)
        model = robot.model_name
    plan = plan_program(program)
    report = verify(plan)
    report = Report(path, report.cycle_times, report.diagnostics)
    metrics = program_metrics(plan)
    task = next((t.name for t in program.tasks if t.robot == slot), None)
    m = metrics.get(task) if task else None
    if not model:
        from rmot.sim.robots import load_robot as _load  # late: loads subprocess only when this runs

        model = _load(program.cell.robot(slot).source.load_key).model_name
    return ArmResult(key or program.cell.robot(slot).source.ref, model, report, m)


def compare_arms(program: ir.Program, keys: list[str], slot: str, path: str) -> list[ArmResult]:
    return [run_arm(program, key, slot, path) for key in keys]
