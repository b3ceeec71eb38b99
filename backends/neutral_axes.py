"""External axes in the neutral CSV and JSON files, named by axis and unit.

The values are `lang.axis_series` (positions from `axis_motion.axis_samples`, the series the
verifier and the renderer read; speeds their derivatives along the samples), in the units a
program writes them: mm and mm/s for a linear axis, deg and deg/s for a revolute one, as the
vendors' programs carry them (RAPID `extax`, KRL `E1..E6`; backends/ext_axes.py).

CSV: after the arm's `t,q1..qn,qd1..qdn`, per axis `NAME[UNIT]` then per axis
`NAME_d[UNIT/s]` (`rail[mm]`, `pos.1[deg]`, ..., `rail_d[mm/s]`, `pos.1_d[deg/s]`).
JSON, per task: `axes` (each axis' name, mechanism, kind, unit, range, speed and accel limits),
the trajectory's `ext` and `ext_d` (one row per sample, one value per axis in `axes` order) and
each move's `ext` (its target's values by axis name). A task without axes has none of them; an
`if` variant's trajectory has no axis rows (axes never move inside an if, E606: their values
there are the main trajectory's at the same times).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from rmot.lang import ir, plan_types
from rmot.lang.axis_motion import task_axes
from rmot.lang.axis_series import AxisSeries, axis_series, mechanism_of, move_values

__all__ = ["csv_columns", "json_axes", "json_record_ext"]


def csv_columns(tp: plan_types.TaskPlan, cell: ir.Cell) -> tuple[list[str], np.ndarray]:
    """(header names, (N, 2 * axes) values) of the task's axis columns; ([], (N, 0)) without axes."""
    series = axis_series(tp, cell.external)
    names = [f"{s.name}[{s.unit}]" for s in series] + [f"{s.name}_d[{s.unit}/s]" for s in series]
    if not series:
        return names, np.zeros((tp.trajectory.t.size, 0))
    return names, np.column_stack([s.position for s in series] + [s.speed for s in series])


def _axis_entry(s: AxisSeries, cell: ir.Cell, num: Any) -> dict[str, Any]:
    assert cell.external is not None
    low, high = s.limits
    return {"name": s.name, "mechanism": mechanism_of(s.axis, cell.external),
            "kind": "linear" if s.axis.linear else "revolute", "unit": s.unit,
            "range": [num(low), num(high)], "speed_limit": num(s.speed_limit), "speed_unit": f"{s.unit}/s",
            "accel_limit": num(s.accel_limit), "accel_unit": f"{s.unit}/s^2"}


def json_axes(tp: plan_types.TaskPlan, cell: ir.Cell, num: Any, nums: Any) -> dict[str, Any]:
    """The task's `axes` and its trajectory's `ext`/`ext_d` ({} without axes); `num`/`nums`
    round as the rest of the document does."""
    series = axis_series(tp, cell.external)
    if not series:
        return {}
    return {"axes": [_axis_entry(s, cell, num) for s in series],
            "ext": nums(np.column_stack([s.position for s in series])),
            "ext_d": nums(np.column_stack([s.speed for s in series]))}


def json_record_ext(node: ir.Instr | None, tp: plan_types.TaskPlan, cell: ir.Cell, num: Any) -> dict[str, Any]:
    """{"ext": {axis: value}} of a move with axis values (display units), else {}."""
    values = move_values(node, task_axes(tp.task, cell.external))
    return {} if values is None else {"ext": {k: num(v) for k, v in values.items()}}
