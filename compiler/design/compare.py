"""Run one program on several arms and collect what a cell designer compares them by.

    results = compare_arms(program, ["abb_irb1600", "kuka_kr16"], slot="r1")

Each arm takes the place of the cell's robot `slot` (same base pose; with `placements`, at
its own placed pose) and goes through the same planner and verifier as `rmot check`.
"""

from __future__ import annotations

from dataclasses import dataclass

from rmot.lang import ir
from rmot.lang.diagnostics import Diagnostic, Severity
from rmot.compiler.design.metrics import TaskMetrics, program_metrics, substitute_robot
from rmot.sim.report import Report

__all__ = ["ArmResult", "compare_arms", "run_arm"]


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


def run_arm(program: ir.Program, key: str | None, slot: str, path: str) -> ArmResult:
    """Plan and verify `program` with arm `key` in `slot` (None: the cell's own robot)."""
    from rmot.compiler.plan import plan_program
    from rmot.sim.robots import RobotError, load_robot
    from rmot.sim import codes, verify

    model = ""
    if key is not None:
        try:
            robot = load_robot(key)
        except RobotError as exc:
            diag = Diagnostic(codes.ROBOT_UNAVAILABLE, Severity.ERROR, f"robot '{key}' must load ({exc.message})", None)
            return ArmResult(key, "", Report(path, {}, (diag,)), None)
        import os

        ref = os.path.abspath(key) if key.lower().endswith(".urdf") else key
        program = substitute_robot(program, slot, ref, robot.dof)
        model = robot.model_name
    plan = plan_program(program)
    report = verify(plan)
    report = Report(path, report.cycle_times, report.diagnostics)
    metrics = program_metrics(plan)
    task = next((t.name for t in program.tasks if t.robot == slot), None)
    m = metrics.get(task) if task else None
    if not model:
        from rmot.sim.robots import load_robot as _load

        model = _load(program.cell.robot(slot).source.load_key).model_name
    return ArmResult(key or program.cell.robot(slot).source.ref, model, report, m)


def compare_arms(program: ir.Program, keys: list[str], slot: str, path: str) -> list[ArmResult]:
    return [run_arm(program, key, slot, path) for key in keys]
