"""What a reported cycle time assumes, and where the time goes.

`ASSUMPTIONS` is the model behind every cycle time rmot prints (lang/REFERENCE.md section 6);
`ASSUMPTIONS_LINE` is its one-line form for text reports. `timing_json(plan)` gives per task
the time spent moving, waiting and synchronising, and per instruction its start and end.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from rmot.lang import ir, ir_tree, plan_types

__all__ = ["ASSUMPTIONS", "ASSUMPTIONS_LINE", "timing_json"]

ASSUMPTIONS: dict[str, str] = {
    "motion_model": "acceleration-limited, no jerk limit; every chain of blended moves timed "
                    "time-optimally along its planned path",
    "limits": "joint velocity and acceleration; on linear and circular moves (and the blends "
              "touching them) TCP path speed <= speed and TCP path acceleration <= accel",
    "accelerations": "robot library values: estimates (vmax reached in 0.25 s) unless the robot's data "
                     "cites a source; ABB IRB 120 estimated from ABB's published standard cycle (0.58 s); "
                     "each task's `accelerations` gives its robot's source",
    "payload": "the payload (heaviest tool and held parts) slows the motion only where a joint "
               "torque would exceed its rating (robots with inertia data and torque ratings); "
               "servo lag does not change the timing",
    "wait_until": "an awaited input arrives at once (timeouts are not simulated)",
    "first_move": "the motion to a task's first target is not timed (the robot starts there)",
}

ASSUMPTIONS_LINE = ("timing: acceleration-limited, time-optimal on the planned path (no jerk limit); "
                    "library accelerations are estimates; payload slows the robot only where "
                    "torque ratings bind; awaited inputs arrive at once; the motion to the first "
                    "target is not counted")


def _round(x: float) -> float:
    return round(float(x), 6)


def _instructions(body: tuple[ir.Instr, ...]) -> dict[int, ir.Instr]:
    return {instr.uid: instr for instr in ir_tree.walk(body)}  # every nested body (loop iterations too)


def _union(intervals: list[tuple[float, float]]) -> float:
    total, end = 0.0, float("-inf")
    for a, b in sorted(intervals):
        if b <= end:
            continue
        total += b - max(a, end)
        end = b
    return total


_KIND = {ir.Move: "move", ir.SetDigital: "set", ir.SetAnalog: "set", ir.Pulse: "pulse",
         ir.WaitTime: "wait", ir.WaitInput: "wait_until", ir.If: "if", ir.Sync: "sync",
         ir.Native: "native", ir.ProcCall: "call",
         ir.VarDecl: "var", ir.Assign: "assign", ir.Loop: "loop", ir.While: "while",
         ir.WaitCondition: "wait_until", ir.Stop: "stop"}


def timing_json(plan: plan_types.Plan, accel_sources: Mapping[str, str] | None = None) -> list[dict[str, Any]]:
    """Per task (main timeline): cycle time, time moving / waiting / synchronising (they add up
    to the cycle time: waiting is every other instant the robot stands still), and every
    instruction's start and end (s). Records of `if` variants carry their variant number.
    `accel_sources` (robot name -> where its joint accelerations come from, "estimate: ..." for
    an estimate) adds the task robot's as `accelerations`: the cycle time rests on them."""
    tasks = []
    for tp in plan.tasks:
        by_uid = _instructions(tp.task.body)
        main = [r for r in tp.records if r.variant == 0]
        kind = {r.uid: _KIND.get(type(by_uid.get(r.uid)), "other") for r in tp.records}
        moving = _union([(r.t_start, r.t_end) for r in main if kind[r.uid] == "move"])
        syncing = _union([(r.t_start, r.t_end) for r in main if kind[r.uid] == "sync"])
        cycle = float(tp.cycle_time)
        tasks.append({
            "task": tp.task.name,
            "robot": tp.robot,
            "cycle_time_s": _round(cycle),
            "moving_s": _round(moving),
            "waiting_s": _round(max(cycle - moving - syncing, 0.0)),
            "sync_s": _round(syncing),
            "instructions": [_instruction(r, kind[r.uid])
                             for r in sorted(tp.records, key=lambda r: (r.variant, r.t_start, r.uid))],
        })
        if accel_sources and tp.robot in accel_sources:
            tasks[-1]["accelerations"] = accel_sources[tp.robot]
    return tasks


def _instruction(r: plan_types.InstructionRecord, kind: str) -> dict[str, Any]:
    """One instruction's times; a move also its verified blend radius (mm, 0 = exact stop), the
    radius every backend prints as the move's zone."""
    out: dict[str, Any] = {"uid": r.uid, "kind": kind, "line": r.span.start.line if r.span else None,
                           "start_s": _round(r.t_start), "end_s": _round(r.t_end), "variant": r.variant}
    if kind == "move":
        out["blend_radius_mm"] = _round(r.blend_radius * 1000.0)
    return out
