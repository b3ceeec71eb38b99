"""plan_program: IR -> Plan, task by task, then aligned at sync barriers and sampled."""

from __future__ import annotations

import numpy as np

from rmot.lang import ir, payload
from rmot.compiler.plan.load import decide_load
from rmot.lang.axis_motion import axis_findings
from rmot.compiler.plan import codes
from rmot.compiler.plan.least_time import least_duration_s
from rmot.compiler.plan.sync import align, hold_variants, sample
from rmot.compiler.plan.targets import initial_joints, unknown_starts
from rmot.compiler.plan.timeline import TaskDraft, build_task, proc_records
from rmot.compiler.plan import torque
from rmot.lang.plan_types import Plan, TaskPlan, Variant
from rmot.lang.diagnostics import Diagnostic, Severity
from rmot.compiler.plan.robot_model import RobotModel

__all__ = ["plan_program"]


def _load(key: str) -> RobotModel:
    from rmot.sim.robots import load_robot  # late: loads coal only when this runs

    return load_robot(key)


def plan_program(program: ir.Program, *, step: float = 0.004) -> Plan:
    """Plan every task of `program`; samples every `step` s (default 4 ms).

    Never raises for bad input: planning problems are diagnostics in Plan.diagnostics, each at
    the span of the instruction concerned; a task with errors still gets a trajectory.
    """
    if not step > 0:
        raise ValueError(f"step must be positive (got {step})")
    diagnostics: list[Diagnostic] = []
    drafts: dict[str, TaskDraft] = {}
    robots: dict[str, RobotModel] = {}
    starts: dict[str, np.ndarray] = {}
    loads: dict[str, payload.TaskLoad] = {}
    least = 0.0
    for task in program.tasks:
        diagnostics.extend(Diagnostic(f.code, f.severity, f.message, move.span, time_s=0.0, task=task.name)
                           for move, f in unknown_starts(task))
        robot = _robot_for(program, task, diagnostics)
        if robot is None:
            continue
        least += least_duration_s(robot.velocity_limits, task.body)
        if least / step > MAX_SAMPLES:  # refused before any move is timed
            diagnostics.append(_too_long(program, least, step, "at least "))
            diagnostics.sort(key=_diagnostic_order)
            return Plan(program, (), step, tuple(diagnostics))
        q0 = initial_joints(robot, task.body)
        robots[task.name], starts[task.name] = robot, q0
        loads[task.name] = decide_load(robot, task, program)
        drafts[task.name] = _build_task(robot, task, q0, program, loads[task.name].peak, MAX_SAMPLES * step)
        diagnostics.extend(drafts[task.name].diagnostics)
    diagnostics.extend(align(drafts))
    for draft in drafts.values():
        hold_variants(draft)
    too_long = _too_many_samples(program, drafts, step)
    if too_long:  # refused before sampling: the work is bounded before it is done
        diagnostics.extend(too_long)
        diagnostics.sort(key=_diagnostic_order)
        return Plan(program, (), step, tuple(diagnostics))
    tasks = tuple(
        _task_plan(task, drafts[task.name], robots[task.name], starts[task.name], step, loads[task.name])
        for task in program.tasks if task.name in drafts
    )
    for tp in tasks:  # external axes outside their ranges, at the move that drives them there
        diagnostics.extend(axis_findings(tp, program.cell.external))
    diagnostics.sort(key=_diagnostic_order)
    return Plan(program, tasks, step, tuple(diagnostics))


# Policy: at most 225,000 samples in all (900 s at the default 4 ms step): the trajectory
# arrays, the verifier's sweep (about 1 kB per sample for the link transforms) and the
# renderer's frames all scale with it. Measured: a 280 s program checks in 2.2 s and 0.49 GB;
# a 967 s task took 1.2 GB and 28 s on a loaded machine, and the CSV and JSON backends format
# every sample (about 0.1 ms each). 900 s covers a full pallet or a long seam (a 1000-move
# pick-and-place plans to 294 s) and keeps a compile under 2 GB (first set at 300 s,
# raised when that refused programs of realistic length).
MAX_SAMPLES = 225_000


def _too_many_samples(program: ir.Program, drafts: dict[str, TaskDraft], step: float) -> list[Diagnostic]:
    """E124 at the first task when all timelines together (every task, and every if-branch
    variant, which is sampled on its own) would exceed MAX_SAMPLES samples. A path is timed only
    until it passes the whole budget (build_task's budget_s): the total is then a lower bound."""
    total, parts = 0.0, 0
    for task in program.tasks:
        draft = drafts.get(task.name)
        if draft is None:
            continue
        for pieces in [draft.pieces, *(v.pieces for v in draft.variants)]:
            total += float(sum(p.duration for p in pieces))
            parts += 1
    if total / step <= MAX_SAMPLES:
        return []
    return [_too_long(program, total, step, "", f" or more over {parts} timeline{'s' * (parts != 1)}: tasks and if-branch "
                      "variants, each sampled on its own")]


def _too_long(program: ir.Program, total: float, step: float, bound: str, over: str = "") -> Diagnostic:
    """E124 at the first task: the timelines take `bound` `total` s, more than MAX_SAMPLES samples."""
    from rmot.lang import check_codes as check_codes  # late: tests replace it (monkeypatch): read at call time

    msg = (f"the timelines of a program must take at most {MAX_SAMPLES * step:g} s in all at a step of {step * 1000:g} ms "
           f"({MAX_SAMPLES} samples; got {bound}{total:.6g} s{over}): split the program or shorten its waits and slow moves")
    first = program.tasks[0]
    return Diagnostic(check_codes.TOO_MUCH_WORK, Severity.ERROR, msg, first.span, task=first.name)


def _diagnostic_order(d: Diagnostic) -> tuple:  # type: ignore[type-arg]
    span = d.span
    return (span.path, span.start.offset) if span is not None else ("", -1)


def _build_task(robot: RobotModel, task: ir.Task, q0: np.ndarray, program: ir.Program,
                load: payload.Load | None, budget_s: float) -> TaskDraft:
    """build_task under the task's joint torque limits (compiler/plan/torque.py; none where the
    robot has no torque ratings) with the task's decided peak load (compiler/plan/load.py); a
    path longer than `budget_s` is refused by _too_many_samples, so its timing stops there."""
    limits = torque.torque_limits(robot, load.mass if load else 0.0, load.at() if load else None)
    return build_task(robot, task, q0, lone=len(program.tasks) == 1, torque=limits, budget_s=budget_s)


def _robot_for(program: ir.Program, task: ir.Task, diagnostics: list[Diagnostic]) -> RobotModel | None:
    try:
        instance = program.cell.robot(task.robot)
    except KeyError:
        msg = f"task '{task.name}' must run on a robot of the cell (got '{task.robot}')"
        diagnostics.append(Diagnostic(codes.ROBOT_UNAVAILABLE, Severity.ERROR, msg, task.span, task=task.name))
        return None
    try:
        return _load(instance.source.load_key)
    except Exception as exc:  # RobotError (or anything the loader raises) becomes a diagnostic
        msg = f"robot '{instance.name}' must load ({exc})"
        diagnostics.append(Diagnostic(codes.ROBOT_UNAVAILABLE, Severity.ERROR, msg, instance.span, task=task.name))
        return None


def _task_plan(task: ir.Task, draft: TaskDraft, robot: RobotModel, q0: np.ndarray, step: float,
               load: payload.TaskLoad) -> TaskPlan:
    dof = robot.dof
    trajectory = sample(draft.pieces, step, 0.0, dof, q0)
    variants = []
    for v in draft.variants:
        start = v.pieces[0].sample(np.array([0.0]))[0][0] if v.pieces else trajectory.at(v.t0)
        variants.append(Variant(v.index, v.if_uid, v.arm, sample(v.pieces, step, v.t0, dof, start)))
    records = list(draft.records) + proc_records(task.body, list(draft.records))
    records.sort(key=lambda r: (r.variant, r.t_start, r.uid))
    return TaskPlan(task, task.robot, trajectory, tuple(records), tuple(variants), load)
