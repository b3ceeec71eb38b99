"""Neutral trajectory files: CSV (the sampled joint trajectory) and JSON (the whole Plan).

CSV, one file per task (`<program>.csv`, `<program>_<task>.csv` with several tasks):
  header `t,q1..qn,qd1..qdn`, then one row per sample at the plan's fixed step; SI units
  (s, rad or m, rad/s or m/s); `CSV_DECIMALS` places; -0 printed as 0. A task that drives
  external axes adds their columns, named by axis and unit (`rail[mm]`, `rail_d[mm/s]`;
  backends/neutral_axes.py).

JSON, one file per program (`<program>.json`): the Plan as data —
  program, cell, step, cycle_time, and per task its robot, dof, cycle_time, instructions
  (uid, kind, source `file:line`, t_start, t_end, joint solution, branch, TCP pose in mm +
  quaternion (w, x, y, z), blend in mm, variant), the variants, and the sampled trajectory
  (t, q, qd); with external axes, the task's `axes`, the trajectory's `ext`/`ext_d` and each
  move's `ext` (backends/neutral_axes.py). Keys sorted, floats rounded to `JSON_DECIMALS` places, -0 printed as 0, so the
  same plan always gives the same bytes.
"""

from __future__ import annotations

import json
import re
from typing import Any

import numpy as np

from rmot.backends import codes
from rmot.backends.base import Backend, EmitResult, TaskContext, source_ref
from rmot.backends.neutral_axes import csv_columns, json_axes, json_record_ext
from rmot.lang import ir, ir_tree, plan_types

__all__ = ["CSV_DECIMALS", "JSON_DECIMALS", "CsvBackend", "JsonBackend", "plan_document"]

CSV_DECIMALS = 9
JSON_DECIMALS = 9


# a move's "kind" in the JSON document, one per motion kind (checked at import: a new kind
# without a label fails loudly, see lang/motion_kinds.py)
MOVE_LABELS: dict[ir.MotionKind, str] = {
    ir.MotionKind.JOINT: "move_joint", ir.MotionKind.LINEAR: "move_linear",
    ir.MotionKind.CIRCULAR: "move_circular",
}


def _num(x: float, decimals: int = JSON_DECIMALS) -> float:
    """A float rounded to fixed places, with -0.0 normalised to 0.0."""
    v = round(float(x), decimals)
    return 0.0 if v == 0.0 else v


def _nums(a: np.ndarray | tuple[float, ...], decimals: int = JSON_DECIMALS) -> list[Any]:
    """_num of every element, nested like the array. One '%.nf' format per row instead of a
    round() per number (a long trajectory has millions): the same correctly rounded decimal
    that round() takes, read back by float(); + 0.0 turns -0.0 into 0.0."""
    arr = np.asarray(a, dtype=float)
    if arr.ndim > 2:
        return [_nums(part, decimals) for part in arr]
    rows = np.atleast_2d(arr)
    if rows.shape[1] == 0:
        values: list[Any] = [[] for _ in range(rows.shape[0])]
    else:
        row_format = ",".join([f"%.{decimals}f"] * rows.shape[1])
        values = [[float(t) + 0.0 for t in (row_format % tuple(r)).split(",")]
                  for r in rows.tolist()]
    return values[0] if arr.ndim == 1 else values


class CsvBackend(Backend):
    """`t,q1..qn,qd1..qdn` per task at the plan's step."""

    name = "csv"
    file_ext = ".csv"
    EXTERNAL_AXES = True  # the axis columns (backends/neutral_axes.py)
    COMMENT = "#"

    @classmethod
    def kind_tables(cls) -> dict[str, dict[ir.MotionKind, str]]:
        """None: the sampled trajectory is the same whatever kind of move made it."""
        return {}

    def emit_task(self, ctx: TaskContext) -> dict[str, str]:
        traj = ctx.task_plan.trajectory
        if traj.t.size == 0:
            self.unsupported(codes.NEUTRAL_NO_SAMPLES, f"task '{ctx.task.name}' must have a "
                             "sampled trajectory (got 0 samples)", ctx.task.span)
            return {}
        dof = traj.q.shape[1]
        ext_names, ext_values = csv_columns(ctx.task_plan, ctx.plan.program.cell)
        header = ["t"] + [f"q{j + 1}" for j in range(dof)] + [f"qd{j + 1}" for j in range(dof)] + ext_names
        # one format per row (a long trajectory has millions of numbers); a field that prints
        # as -0.000 becomes 0.000 as conventions.fmt would write it
        row_format = ",".join([f"%.{CSV_DECIMALS}f"] * (1 + 2 * dof + len(ext_names)))
        table = np.column_stack([traj.t, traj.q, traj.qd, ext_values]).tolist()
        rows = [",".join(header)] + [row_format % tuple(r) for r in table]
        zero = f"{0.0:.{CSV_DECIMALS}f}"
        body = re.sub(rf"(^|,)-{re.escape(zero)}(?=,|$)", rf"\g<1>{zero}", "\n".join(rows), flags=re.M)
        return {f"{ctx.program_name}{self.file_ext}": body + "\n"}


class JsonBackend(Backend):
    """The whole Plan as one deterministic JSON document."""

    name = "json"
    file_ext = ".json"
    EXTERNAL_AXES = True  # the axes, their samples and each move's values (backends/neutral_axes.py)

    @classmethod
    def kind_tables(cls) -> dict[str, dict[ir.MotionKind, str]]:
        """A move's label in the document (MOVE_LABELS)."""
        return {"MOVE_LABELS": MOVE_LABELS}

    def emit(self, plan: plan_types.Plan, *, source_map: bool = True) -> EmitResult:
        result = super().emit(plan, source_map=source_map)
        doc = plan_document(plan)
        text = json.dumps(doc, sort_keys=True, separators=(",", ":"), ensure_ascii=True) + "\n"
        return EmitResult({f"{plan.program.name}{self.file_ext}": text}, result.diagnostics)

    def emit_task(self, ctx: TaskContext) -> dict[str, str]:
        if ctx.task_plan.trajectory.t.size == 0:
            self.unsupported(codes.NEUTRAL_NO_SAMPLES, f"task '{ctx.task.name}' must have a "
                             "sampled trajectory (got 0 samples)", ctx.task.span)
        return {}


def plan_document(plan: plan_types.Plan) -> dict[str, Any]:
    """The Plan as JSON-ready data (see the module docstring for the layout)."""
    return {
        "program": plan.program.name,
        "cell": plan.program.cell.name,
        "step": _num(plan.step),
        "cycle_time": _num(plan.cycle_time),
        "tasks": [_task(tp, plan.program.cell) for tp in plan.tasks],
    }


def _task(tp: plan_types.TaskPlan, cell: ir.Cell) -> dict[str, Any]:
    nodes = {n.uid: n for n in ir_tree.walk(tp.task.body)}
    traj = tp.trajectory
    axes = json_axes(tp, cell, _num, _nums)  # external axes: {} without (backends/neutral_axes.py)
    trajectory = _trajectory(traj)
    if axes:
        trajectory.update(ext=axes.pop("ext"), ext_d=axes.pop("ext_d"))
    return axes | {
        "name": tp.task.name,
        "robot": tp.robot,
        "dof": int(traj.q.shape[1]),
        "cycle_time": _num(tp.cycle_time),
        "instructions": [_record(r, nodes.get(r.uid)) | json_record_ext(nodes.get(r.uid), tp, cell, _num) for r in tp.records],
        "variants": [{"index": v.index, "if_uid": v.if_uid, "arm": v.arm,
                      "trajectory": _trajectory(v.trajectory)} for v in tp.variants],
        "trajectory": trajectory,
    }


def _trajectory(traj: plan_types.Trajectory) -> dict[str, Any]:
    return {"t": _nums(traj.t), "q": _nums(traj.q), "qd": _nums(traj.qd)}


# the JSON document's word for each instruction kind (a move: its motion kind's MOVE_LABELS)
_KIND_LABELS: dict[type, str] = {
    ir.Move: "move", ir.SetDigital: "set_digital", ir.SetAnalog: "set_analog", ir.Pulse: "pulse",
    ir.WaitTime: "wait_time", ir.WaitInput: "wait_input", ir.If: "if", ir.Sync: "sync",
    ir.Native: "native", ir.ProcCall: "proc_call", ir.Attach: "attach", ir.Detach: "detach",
    ir.VarDecl: "var", ir.Assign: "assign", ir.Loop: "loop", ir.While: "while",
    ir.WaitCondition: "wait_condition", ir.Stop: "stop",
}
ir_tree.require_kinds("backends/neutral._KIND_LABELS", _KIND_LABELS)


def _kind(node: ir.Instr | None) -> str:
    if node is None:
        return "unknown"
    if isinstance(node, ir.Move):
        return MOVE_LABELS[node.kind]
    return _KIND_LABELS[type(node)]


def _pose(pose: ir.Pose | None) -> dict[str, Any] | None:
    if pose is None:
        return None
    return {"position_mm": [_num(c * 1000.0) for c in pose.position],
            "quaternion_wxyz": [_num(c) for c in pose.quaternion]}


def _branch(branch: ir.Config | None) -> dict[str, Any] | None:
    if branch is None:
        return None
    return {"shoulder": branch.shoulder.value if branch.shoulder else None,
            "elbow": branch.elbow.value if branch.elbow else None,
            "wrist": branch.wrist.value if branch.wrist else None}


def _record(rec: plan_types.InstructionRecord, node: ir.Instr | None) -> dict[str, Any]:
    return {
        "uid": rec.uid,
        "kind": _kind(node),
        "source": source_ref(rec.span),
        "t_start": _num(rec.t_start),
        "t_end": _num(rec.t_end),
        "q_target": None if rec.q_target is None else _nums(rec.q_target),
        "q_via": None if rec.q_via is None else _nums(rec.q_via),
        "branch": _branch(rec.branch),
        "tcp_pose": _pose(rec.tcp_pose),
        "flange_pose": _pose(rec.flange_pose),
        "blend_mm": _num(rec.blend_radius * 1000.0),
        "variant": rec.variant,
    }
