"""verify(plan) -> Report: collisions, clearance and joint limits over the whole Plan.

Every task's main timeline is checked on one shared clock (robot against robot where tasks
overlap in time); every `if` variant is checked against the fixtures, its own robot and the
other robots (on their main timelines at the same times). A robot of the cell without a task
stands still at its zero configuration (clipped to its limits). Every tool a task names is
treated as mounted for the whole task (tool changes are not modelled); the torque check's
payload is the heaviest tool with the heaviest set of parts held at once (lang/payload.py,
the one model the planner and the backends read too).

The no-miss guarantee between samples is the distance bound in collide.py: a contact
deeper than collide.CONTACT_TOL (10 µm) cannot fall between two samples unseen.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from rmot.lang import ir, ir_tree, payload, plan_types
from rmot.lang.ir_tree import describe_iteration, iteration_paths
from rmot.lang.diagnostics import Amount, Diagnostic, Severity
from rmot.lang.source import Span
from rmot.sim import codes
from rmot.sim.corners import corner_findings
from rmot.sim.collide import PairHit, Timeline, candidate_pairs, check_timeline
from rmot.sim.limits import LimitHit, check_limits
from rmot.sim.report import Report
from rmot.sim.scene import Scene, build_scene, flange_in_last_joint
from rmot.sim import axes_collide, parts

__all__ = ["verify", "verify_with"]


def verify(plan: plan_types.Plan, *, clearance: float | None = None) -> Report:
    """Check the Plan; `clearance` (m): also report every approach closer than that."""
    return verify_with(plan, clearance=clearance)


def verify_with(plan: plan_types.Plan, *, clearance: float | None = None,
                robots: Mapping[str, Any] | None = None) -> Report:
    """`verify` with the robot models given (tests) instead of loaded from the library."""
    program = plan.program
    tools_used = _tools_used(program)
    scene = build_scene(program.cell, tools_used, robots)
    findings: list[Diagnostic] = []
    tasks = [tp for tp in plan.tasks if tp.robot in scene.robots]
    if tasks:
        findings += _collisions(scene, plan, tasks, clearance or 0.0)
        if program.cell.parts:
            findings += parts.shape_diagnostics(program.cell)
            findings += _part_collisions(scene, plan, tasks, clearance or 0.0)
            findings += parts.payload_findings(scene, plan)
    findings += corner_findings(scene, tasks, {r.name for r in program.cell.robots
                                               if r.exact_ptp_approximation})
    for tp in tasks:
        findings += _limits(scene, tp, plan)
    findings.sort(key=_finding_order)
    diagnostics = tuple(plan.diagnostics) + scene.diagnostics + tuple(findings)
    cycle_times = {tp.task.name: float(tp.cycle_time) for tp in plan.tasks}
    from rmot.sim.timing_report import timing_json  # late: loads xml only when this runs

    accel = {name: dict(getattr(e.robot, "sources", ())).get("accel", "not stated") for name, e in scene.robots.items()}
    return Report(_program_file(program), cycle_times, diagnostics, tuple(timing_json(plan, accel)))


def _program_file(program: ir.Program) -> str:
    return program.span.path if program.span is not None else program.name


def _finding_order(d: Diagnostic) -> tuple[Any, ...]:
    return (d.time_s if d.time_s is not None else -1.0, d.code.id, d.bodies, d.message)


def _tools_used(program: ir.Program) -> dict[str, set[str]]:
    used: dict[str, set[str]] = {}
    for task in program.tasks:
        names = used.setdefault(task.robot, set())
        for instr in ir_tree.walk(task.body):
            if isinstance(instr, ir.Move) and instr.tool.name is not None:
                names.add(instr.tool.name)
    return used


# --------------------------------------------------------------------------- collisions


def _collisions(scene: Scene, plan: plan_types.Plan, tasks: list[plan_types.TaskPlan], clearance: float) -> list[Diagnostic]:
    main = {tp.robot: tp.trajectory for tp in tasks}
    out: list[Diagnostic] = []
    timeline = _timeline(scene, main, None)
    by_robot = {tp.robot: tp for tp in tasks}
    pairs = candidate_pairs(scene)
    external = plan.program.cell.external
    driver = axes_collide.driving_task(tasks, external)
    groups = axes_collide.body_groups(scene, external) if driver is not None else {}
    if driver is not None and external is not None:  # pairs whose relative pose the external axes change
        pairs, moved = axes_collide.axis_pairs(pairs, groups)
        hits = axes_collide.axis_collisions(scene, timeline, moved, driver, external, clearance)
        out += [_collision_diagnostic(scene, by_robot, h, clearance, 0) for h in hits]
        if moved:
            step = float(np.max(np.diff(timeline.t))) * 1000 if timeline.t.size > 1 else 0.0
            out.append(Diagnostic(codes.AXES_SAMPLED, Severity.NOTE, f"the {len(moved)} body pairs whose relative pose "
                                  f"the external axes change are checked at every sample (at most {step:.0f} ms apart), not with "
                                  "the no-miss bound: a contact shallower than their motion in one step can be missed",
                                  driver.task.span, task=driver.task.name))
        if driver.variants:
            out.append(Diagnostic(codes.AXES_PATHS_UNCHECKED, Severity.WARNING, "collisions of the bodies external axes "
                                  "carry are checked on the main path only, not on the other paths of an if or while",
                                  driver.task.span, task=driver.task.name))
    hits = check_timeline(scene, timeline, pairs, clearance)
    out += [_collision_diagnostic(scene, by_robot, h, clearance, 0) for h in hits]
    for tp in tasks:
        for variant in tp.variants:
            trajs = dict(main)
            trajs[tp.robot] = variant.trajectory
            timeline = _timeline(scene, trajs, variant.trajectory.t)
            kept = axes_collide.axis_pairs(candidate_pairs(scene, only_robot=tp.robot), groups)[0]
            hits = check_timeline(scene, timeline, kept, clearance)
            out += [_collision_diagnostic(scene, by_robot, h, clearance, variant.index, tp.robot) for h in hits
                    if h.kind != "static"]
    return out


def _part_collisions(scene: Scene, plan: plan_types.Plan, tasks: list[plan_types.TaskPlan], clearance: float) -> list[Diagnostic]:
    """The pairs with a part (sim/parts.py), phase by phase, on the main timeline and each variant."""
    main = {tp.robot: tp.trajectory for tp in tasks}
    by_robot = {tp.robot: tp for tp in tasks}
    out: list[Diagnostic] = []
    timeline = _timeline(scene, main, None)
    phase_list = parts.phases(scene, plan, None, out)
    for pscene, h in parts.part_hits(scene, timeline, phase_list, clearance):
        out.append(_collision_diagnostic(pscene, by_robot, h, clearance, 0))
    for tp in tasks:
        for variant in tp.variants:
            trajs = dict(main)
            trajs[tp.robot] = variant.trajectory
            timeline = _timeline(scene, trajs, variant.trajectory.t)
            extra: list[Diagnostic] = []
            phase_list = parts.phases(scene, plan, (tp.robot, variant), extra)
            seen = {(d.code, d.span, d.message) for d in out}
            out += [d for d in extra if (d.code, d.span, d.message) not in seen]
            for pscene, h in parts.part_hits(scene, timeline, phase_list, clearance, only_robot=tp.robot):
                if h.kind != "static":
                    out.append(_collision_diagnostic(pscene, by_robot, h, clearance, variant.index, tp.robot))
    return out


def _timeline(scene: Scene, trajs: dict[str, plan_types.Trajectory], grid: np.ndarray | None) -> Timeline:
    """Every robot on one clock: the union of the sample times (each robot's piecewise-linear
    path is unchanged by resampling at a superset of its own samples)."""
    if grid is None:
        times = np.concatenate([tr.t for tr in trajs.values() if tr.t.size] or [np.zeros(1)])
        grid = np.unique(np.round(times, 9))
    q: dict[str, np.ndarray] = {}
    accel: dict[str, np.ndarray] = {}
    for name, entry in scene.robots.items():
        traj = trajs.get(name)
        if traj is None or traj.t.size == 0:
            still = np.clip(np.zeros(entry.robot.dof), entry.robot.joint_limits[:, 0], entry.robot.joint_limits[:, 1])
            q[name] = np.tile(still, (grid.size, 1))
            accel[name] = np.zeros((grid.size, entry.robot.dof))
            continue
        q[name] = _resample(traj.t, traj.q, grid)
        accel[name] = _resample(traj.t, np.abs(traj.qdd), grid)
    return Timeline(grid, q, accel)


def _resample(t: np.ndarray, values: np.ndarray, grid: np.ndarray) -> np.ndarray:
    return np.stack([np.interp(grid, t, values[:, j]) for j in range(values.shape[1])], axis=1)


def _collision_diagnostic(scene: Scene, by_robot: dict[str, plan_types.TaskPlan], hit: PairHit, clearance: float,
                          variant: int, variant_robot: str | None = None) -> Diagnostic:
    a, b = scene.body(hit.a), scene.body(hit.b)
    if a.kind == "fixture" or (b.kind != "fixture" and not a.moves and b.moves):
        a, b = b, a  # name the moving robot body first
    robots = [body.robot for body in (a, b) if body.robot is not None and body.moves]
    robots = sorted(set(robots), key=lambda r: (r != variant_robot, robots.index(r)))
    owner = robots[0] if robots else (a.robot or b.robot)
    tp = by_robot.get(owner) if owner else None
    span = _span_at(tp, hit.t0, variant if owner == variant_robot else 0) if tp else None
    notes = []
    for other in robots[1:]:
        other_tp = by_robot.get(other)
        if other_tp is not None:
            notes.append((f"robot '{other}' is executing this move then", _span_at(other_tp, hit.t0, 0)))
    where = _variant_path(tp, variant) if variant and tp else ""
    where = _iteration_at(tp, hit.t0, variant if owner == variant_robot else 0) + where
    names = (a.name, b.name)
    if hit.kind == "clearance":
        mm = hit.distance * 1000
        message = f"'{a.name}' comes within {mm:.1f} mm of '{b.name}'; clearance must be at least {clearance * 1000:.1f} mm{where}"
        return Diagnostic(codes.CLEARANCE, Severity.WARNING, message, span, tuple(notes), hit.t0, hit.t1,
                          names, Amount(round(mm, 3), "mm"), tp.task.name if tp else None, hit.t_worst)
    depth = max(-hit.distance, 0.0) * 1000
    if hit.kind == "static":
        message = (f"'{a.name}' and '{b.name}' overlap although neither moves (penetration {depth:.1f} mm); "
                   "move one of them in the cell so they do not overlap")
        return Diagnostic(codes.STATIC_CONTACT, Severity.WARNING, message, a.span or b.span or span, (), None, None,
                          names, Amount(round(depth, 3), "mm"), None)
    code = _collision_code(a, b)
    message = f"'{a.name}' collides with '{b.name}' (penetration {depth:.1f} mm){where}"
    return Diagnostic(code, Severity.ERROR, message, span, tuple(notes), hit.t0, hit.t1, names,
                      Amount(round(depth, 3), "mm"), tp.task.name if tp else None, hit.t_worst)


def _collision_code(a: Any, b: Any) -> Any:
    if a.kind == "fixture" or b.kind == "fixture":
        return codes.COLLISION
    if a.robot == b.robot:
        return codes.SELF_COLLISION
    return codes.ROBOT_COLLISION


def _variant_path(tp: plan_types.TaskPlan, variant: int) -> str:
    """' (on the path through the 'otherwise' arm of the if at line N)': a variant covers the
    arm and everything after the if, so the finding may be in either."""
    for v in tp.variants:
        if v.index == variant:
            span = next((i.span for i in ir_tree.walk(tp.task.body) if i.uid == v.if_uid), None)
            line = span.start.line if span is not None else None
            return f" (on {plan_types.path_words(v.arm, line)})"
    return " (on another path through a runtime if)"


def _span_at(tp: plan_types.TaskPlan, t: float, variant: int) -> Span | None:
    """The span of the move the task executes at time t (else of any instruction then)."""
    record = _record_at(tp, t, variant)
    return record.span if record is not None else tp.task.span


def _iteration_at(tp: plan_types.TaskPlan | None, t: float, variant: int) -> str:
    """' (in iteration layer = 2, row = 1)' when the instruction the task executes at time t lies
    in a for/repeat loop (a finding names the iteration), else ''."""
    if tp is None:
        return ""
    record = _record_at(tp, t, variant)
    path = iteration_paths(tp.task.body).get(record.uid) if record is not None else None
    return f" (in iteration {describe_iteration(path)})" if path else ""


def _record_at(tp: plan_types.TaskPlan, t: float, variant: int) -> plan_types.InstructionRecord | None:
    """The record of the move the task executes at time t (else of any instruction then)."""
    moves = {i.uid for i in ir_tree.walk(tp.task.body) if isinstance(i, ir.Move)}
    records = [r for r in tp.records if r.variant == variant] or list(tp.records)
    for want_move in (True, False):
        chosen = None
        for r in records:
            if (r.uid in moves) != want_move and want_move:
                continue
            if r.t_start - 1e-9 <= t <= r.t_end + 1e-9:
                if chosen is None or (r.t_start <= t < r.t_end and not chosen.t_start <= t < chosen.t_end):
                    chosen = r
        if chosen is not None:
            return chosen
    if records:
        return min(records, key=lambda r: min(abs(t - r.t_start), abs(t - r.t_end)))
    return None


# --------------------------------------------------------------------------- limits


_UNITS = {  # quantity -> (revolute unit, factor, prismatic unit, factor)
    "position": ("deg", 180 / np.pi, "mm", 1000.0),
    "velocity": ("deg/s", 180 / np.pi, "mm/s", 1000.0),
    "acceleration": ("deg/s^2", 180 / np.pi, "mm/s^2", 1000.0),
    "torque": ("N·m", 1.0, "N", 1.0),
}
_LIMIT_CODES = {"position": codes.JOINT_POSITION, "velocity": codes.JOINT_VELOCITY,
                "acceleration": codes.JOINT_ACCEL, "torque": codes.JOINT_TORQUE}


def _limits(scene: Scene, tp: plan_types.TaskPlan, plan: plan_types.Plan | None = None) -> list[Diagnostic]:
    entry = scene.robots[tp.robot]
    payload, payload_at = _payload(scene, tp, plan)
    out = []
    runs = [(0, tp.trajectory)] + [(v.index, v.trajectory) for v in tp.variants]
    for variant, traj in runs:
        if traj.t.size == 0:
            continue
        for hit in check_limits(entry.robot, traj, payload, payload_at):
            out.append(_limit_diagnostic(tp, hit, variant, _estimated_torque(entry.robot)))
    return out


def _estimated_torque(robot: Any) -> bool:
    """Whether the robot's torque ratings are an estimate (its `effort` source says so,
    sim/robots/dynamics.py): an excess over them is a warning (W342), not an error."""
    source: str = dict(getattr(robot, "sources", ())).get("effort", "")
    return source.startswith("estimate")


def _payload(scene: Scene, tp: plan_types.TaskPlan, plan: plan_types.Plan | None = None) -> tuple[float, np.ndarray | None]:
    """The task's peak load as the plan decided it (lang/payload.of: its heaviest tool at
    ir.payload_cog, the point every backend writes as the tool's payload, plus the heaviest set
    of parts it holds at once, at their centroids) as a point mass in the last joint's frame."""
    load = payload.of(plan, tp).peak
    if load is None:
        return 0.0, None
    flange = flange_in_last_joint(scene.robots[tp.robot].robot)
    return load.mass, flange[:3, :3] @ load.at() + flange[:3, 3]


def _limit_diagnostic(tp: plan_types.TaskPlan, hit: LimitHit, variant: int, estimated: bool = False) -> Diagnostic:
    unit, factor, p_unit, p_factor = _UNITS[hit.quantity]
    if hit.prismatic:
        unit, factor = p_unit, p_factor
    value, limit = hit.value * factor, hit.limit * factor
    if hit.quantity == "position":
        excess = abs(value - limit)
        side = "upper" if value > limit else "lower"
        message = (f"joint {hit.joint} position {value:.1f} {unit} must stay within its {side} limit "
                   f"{limit:.1f} {unit} (exceeds it by {excess:.2f} {unit})")
        amount = Amount(round(excess, 4), unit)
    else:
        ratio = (abs(value) / abs(limit) - 1) * 100 if limit else float("inf")
        message = f"joint {hit.joint} {hit.quantity} {abs(value):.1f} {unit} exceeds its limit {abs(limit):.1f} {unit} by {ratio:.0f}%"
        amount = Amount(round(abs(value) - abs(limit), 4), unit)
    message += _iteration_at(tp, hit.t0, variant)
    if variant:
        message += _variant_path(tp, variant)
    span = _span_at(tp, hit.t0, variant)
    code, severity = _LIMIT_CODES[hit.quantity], Severity.ERROR
    if hit.quantity == "torque" and estimated:
        code, severity = codes.JOINT_TORQUE_ESTIMATE, Severity.WARNING
        message = message.replace("exceeds its limit", "exceeds its estimated limit")
        message += f" (robot '{tp.robot}': the vendor publishes no torque rating; `rmot robots show` gives the estimate)"
    return Diagnostic(code, severity, message, span, (), hit.t0, hit.t1,
                      (f"{tp.robot}/joint{hit.joint}",), amount, tp.task.name)
