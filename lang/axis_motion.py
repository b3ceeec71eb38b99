"""Where the external axes are over a planned task, and where they go out of range.

The plan decides each move's start and end time (InstructionRecord) with the axes' shortest
time as a floor (ir.Motion.min_duration); the IR decides each move's axis values (ir.Move.ext).
An axis that changes during a move follows the time-synchronous trapezoid of
`ir_axes.synced_position` over the move's whole duration, so it starts and stops with the arm;
during a coordinated move (ir.Move.coordinated) it follows the values the planner sampled from
the move's one timing (InstructionRecord.axes_path).
The verifier, the renderer and the backends read axis positions from `axis_samples` only.
"""

from __future__ import annotations

import numpy as np

from rmot.lang import codes_axes, ir, ir_tree
from rmot.lang.ir_axes import ExtAxis, ExternalAxes, synced_position
from rmot.lang.plan_types import InstructionRecord, TaskPlan
from rmot.lang.diagnostics import Diagnostic, Severity

__all__ = ["axis_findings", "axis_samples", "task_axes"]


def task_axes(task: ir.Task, external: ExternalAxes | None) -> tuple[ExtAxis, ...]:
    """The axes `task` drives, in the order of its moves' `ext` values (none without axes)."""
    if external is None:
        return ()
    first = next((i for i in ir_tree.walk(task.body) if isinstance(i, ir.Move) and i.ext), None)
    if first is None:
        return ()
    by_name = {a.name: a for m in external.mechanisms for a in m.axes}
    return tuple(by_name[name] for name, _ in first.ext)


def _moves(tp: TaskPlan) -> list[tuple[float, float, dict[str, float], InstructionRecord]]:
    """(t_start, t_end, axis values at the target, record) of every move with axis values, in time order."""
    moves = {i.uid: i for i in ir_tree.walk(tp.task.body) if isinstance(i, ir.Move) and i.ext}
    out = [(r.t_start, r.t_end, dict(moves[r.uid].ext), r) for r in tp.records if r.variant == 0 and r.uid in moves]
    return sorted(out, key=lambda m: (m[0], m[1]))


def axis_samples(tp: TaskPlan, axes: tuple[ExtAxis, ...], t: np.ndarray | None = None) -> np.ndarray:
    """Axis values (SI) at times `t` (default: the task's trajectory samples): shape (N, len(axes))."""
    times = tp.trajectory.t if t is None else np.asarray(t, dtype=float)
    out = np.empty((times.shape[0], len(axes)))
    moves = _moves(tp)
    for k, axis in enumerate(axes):
        value = np.full(times.shape, axis.home)
        now = axis.home
        for t0, t1, values, rec in moves:
            end = values.get(axis.name, now)
            if end != now:
                inside = (times >= t0) & (times <= t1)
                if rec.axes_path is not None:  # coordinated: the axes as the move's own timing drives them
                    column = list(values).index(axis.name)
                    value[inside] = np.interp(times[inside], rec.axes_path[0], rec.axes_path[1][:, column])
                else:
                    value[inside] = synced_position(now, end, t1 - t0, axis.accel, times[inside] - t0)
            value[times > t1] = end
            now = end
        out[:, k] = value
    return out


def axis_findings(tp: TaskPlan, external: ExternalAxes | None) -> list[Diagnostic]:
    """E605 at each move that drives an axis outside its range, naming the axis, from the instant
    it leaves the range to the move's end (a later move that leaves it there is not reported
    again: the finding is the move that took it out)."""
    axes = {a.name: a for a in task_axes(tp.task, external)}
    found: list[Diagnostic] = []
    for instr in ir_tree.walk(tp.task.body):
        if not isinstance(instr, ir.Move):
            continue
        rec = tp.record(instr.uid)
        for name, value in instr.ext:
            axis = axes[name]
            if axis.low - 1e-12 <= value <= axis.high + 1e-12 or (
                    rec is not None and rec.variant == 0  # on the main timeline: where the move starts is known
                    and abs(float(axis_samples(tp, (axis,), np.array([rec.t_start]))[0, 0]) - value) <= 1e-12):
                continue
            found.append(Diagnostic(
                codes_axes.EXT_AXIS_LIMIT, Severity.ERROR,
                f"axis '{name}' must stay within [{axis.shown(axis.low)}, {axis.shown(axis.high)}] (got {axis.shown(value)})",
                instr.span, time_s=None if rec is None else _leaves_range(tp, axis, rec),
                end_time_s=None if rec is None else rec.t_end, task=tp.task.name))
    return found


def _leaves_range(tp: TaskPlan, axis: ExtAxis, rec: InstructionRecord) -> float:
    """The first sample of `rec`'s move at which `axis` is outside its range (its end if none)."""
    t = tp.trajectory.t
    times = t[(t >= rec.t_start) & (t <= rec.t_end)]
    if times.size == 0:
        return rec.t_end
    values = axis_samples(tp, (axis,), times)[:, 0]
    outside = np.flatnonzero((values < axis.low - 1e-12) | (values > axis.high + 1e-12))
    return float(times[outside[0]]) if outside.size else rec.t_end
