"""The payload: what a robot's flange carries (its tool and the parts it holds) as one point
mass, decided once per task by the planner (`decide`, carried on the plan as TaskPlan.load)
and read from there by every consumer: the planner's torque limits (compiler/plan/torque.py),
the verification's torque check and plots (sim/verification.py), the design metrics and the
backends' payload lines (backends/part_load.py). `of(plan, tp)` is that value.

The model, in the flange frame (kg, m):
- a tool's mass sits at `ir.payload_cog`, half way along the flange->TCP vector;
- a held part's mass sits at its centroid (a mesh part's from its file, which the planner
  reads: compiler/plan/load.py; a box, cylinder, sphere or capsule is centred on its pose),
  fixed at its attach: its declared pose (the cell's `part ... at`, robot base frame; every
  part of a feeder is presented there) seen from the flange at the target of the move before
  the attach, where the robot stands still (the planner stops before an attach). A plain part
  attached again (it was put down somewhere since) or one another task also attaches (a
  hand-over) is taken at the TCP, where the gripper holds it;
- after each attach or detach the flange carries the tool with the parts then held
  (`TaskLoad.held`); the load a task's torques are bounded and checked with is the heaviest
  tool it uses plus the heaviest set of parts it holds at once (`TaskLoad.peak`).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING

import numpy as np

from rmot.lang import ir, ir_tree
from rmot.lang.record import record

if TYPE_CHECKING:  # plan_types carries a TaskLoad on each TaskPlan: imported for annotations only
    from rmot.lang import plan_types

__all__ = ["HeldLoad", "Load", "TaskLoad", "decide", "heaviest_tool", "of"]


@record
class Load:
    """A point mass: `mass` kg at `cog` (x, y, z) m in the flange frame."""

    mass: float
    cog: tuple[float, float, float]

    @staticmethod
    def of(mass: float, cog: np.ndarray) -> Load:
        x, y, z = (float(v) for v in cog)
        return Load(float(mass), (x, y, z))

    def at(self) -> np.ndarray:
        """The centre of gravity as a (3,) array."""
        return np.asarray(self.cog, dtype=float)


@record
class HeldLoad:
    """After an attach or detach: the held parts alone, and the tool with them."""

    parts: Load
    total: Load


def heaviest_tool(body: tuple[ir.Instr, ...]) -> Load | None:
    """The heaviest tool the moves of `body` use (the first of equal ones), its mass at
    ir.payload_cog; None when no move uses a tool with mass."""
    best: Load | None = None
    for instr in ir_tree.walk(body):
        if isinstance(instr, ir.Move) and instr.tool.mass > (best.mass if best else 0.0):
            best = Load(instr.tool.mass, ir.payload_cog(instr.tool.tcp))
    return best


def _with_tool(tool: Load | None, held_mass: float, held_at: np.ndarray) -> Load:
    """The heaviest tool and the heaviest held parts as one point mass."""
    tool_mass = tool.mass if tool is not None else 0.0
    tool_at = tool.at() if tool is not None else np.zeros(3)
    total = tool_mass + held_mass
    return Load.of(total, (tool_mass * tool_at + held_mass * held_at) / total)


@record
class TaskLoad:
    """A task's load, decided once: `held` pairs each attach/detach uid (program order) with
    the load after it; `peak` is the heaviest tool plus the heaviest set of parts held at once
    (None: the task carries nothing)."""

    held: tuple[tuple[int, HeldLoad], ...]
    peak: Load | None

    def after(self, uid: int) -> HeldLoad:
        """The load after attach/detach `uid`."""
        return dict(self.held)[uid]


def decide(task: ir.Task, program: ir.Program | None, flanges: Mapping[int, ir.Pose],
           centroids: Mapping[str, tuple[float, float, float]]) -> TaskLoad:
    """The task's load. `flanges`: move uid -> the flange pose at its target (robot base
    frame); `centroids`: part name -> its centroid in its geometry frame (m; absent: the
    pose origin, where boxes, cylinders, spheres and capsules are centred)."""
    held = _held_loads(task, program, flanges, centroids) if program is not None and program.cell.parts else {}
    tool = heaviest_tool(task.body)
    heaviest: Load | None = None
    for h in held.values():
        if h.parts.mass > (heaviest.mass if heaviest else 0.0):
            heaviest = h.parts
    peak = tool if heaviest is None else _with_tool(tool, heaviest.mass, heaviest.at())
    return TaskLoad(tuple(held.items()), peak)


def of(plan: plan_types.Plan | None, tp: plan_types.TaskPlan) -> TaskLoad:
    """The load the plan decided for task `tp` (TaskPlan.load, set by the planner). A plan
    built without the planner (a test's) has none: it is decided here from the flange poses
    of its records, every part's centre at its pose origin."""
    if tp.load is not None:
        return tp.load
    flanges = {}
    for instr in ir_tree.walk(tp.task.body):
        rec = tp.record(instr.uid) if isinstance(instr, ir.Move) else None
        if rec is not None and rec.flange_pose is not None:
            flanges[instr.uid] = rec.flange_pose
    return decide(tp.task, plan.program if plan is not None else None, flanges, {})


def _part_centres(task: ir.Task, program: ir.Program, flanges: Mapping[int, ir.Pose],
                  centroids: Mapping[str, tuple[float, float, float]]) -> dict[int, np.ndarray]:
    """Attach uid -> the part's centroid in the flange frame (m), for every attach of the task.

    A part taken where it was declared has its declared centroid; a feeder presents every part
    of its supply at the declared pose, so each attach of a feeder part has it too. A plain
    part attached again (it was put down somewhere since) is taken as centred on the TCP."""
    parts = {p.name: p for p in program.cell.parts}
    attached_elsewhere = {i.part for t in program.tasks if t.name != task.name
                          for i in ir_tree.walk(t.body) if isinstance(i, ir.Attach)}
    base_inv = program.cell.robot(task.robot).base.inverse()
    flange: ir.Pose | None = None
    seen: set[str] = set()
    out: dict[int, np.ndarray] = {}
    for instr in ir_tree.walk(task.body):
        if isinstance(instr, ir.Move):
            flange = flanges.get(instr.uid, flange)
        elif isinstance(instr, ir.Attach):
            part = parts.get(instr.part)
            tcp = np.asarray(instr.tool.tcp.position, dtype=float)
            if part is None or flange is None or (instr.part in seen and not part.feeder) or instr.part in attached_elsewhere:
                out[instr.uid] = tcp
            else:
                out[instr.uid] = _centre_in(flange.inverse() * (base_inv * part.pose), centroids.get(part.name))
            seen.add(instr.part)
    return out


def _centre_in(part_in_flange: ir.Pose, centroid: tuple[float, float, float] | None) -> np.ndarray:
    """The part's centroid (its geometry frame) in the flange frame, given the part's pose there."""
    at = np.asarray(part_in_flange.position, dtype=float)
    if centroid is None or not any(centroid):
        return at
    centre: np.ndarray = at + part_in_flange.matrix()[:3, :3] @ np.asarray(centroid, dtype=float)
    return centre


def _held_loads(task: ir.Task, program: ir.Program, flanges: Mapping[int, ir.Pose],
                centroids: Mapping[str, tuple[float, float, float]]) -> dict[int, HeldLoad]:
    """Attach/detach uid -> the load after it: the held parts' mass at their centroids, and the
    tool's mass (at ir.payload_cog) with them."""
    centres = _part_centres(task, program, flanges, centroids)
    parts = {p.name: p for p in program.cell.parts}
    latest: dict[str, int] = {}
    out: dict[int, HeldLoad] = {}
    for node in ir_tree.walk(task.body):
        if isinstance(node, ir.Attach):
            latest[node.part] = node.uid
        if isinstance(node, (ir.Attach, ir.Detach)) and node.uid not in out:
            out[node.uid] = _held_after(node, parts, centres, latest)
    return out


def _held_after(node: ir.Attach | ir.Detach, parts: dict[str, ir.Part], centres: dict[int, np.ndarray],
                latest: dict[str, int]) -> HeldLoad:
    tcp = np.asarray(node.tool.tcp.position, dtype=float)
    mass = 0.0
    moment = np.zeros(3)
    for name in node.held:
        m = parts[name].mass if name in parts else 0.0
        mass += m
        moment += m * centres.get(latest.get(name, -1), tcp)
    cog = moment / mass if mass > 0 else tcp
    tool_cog = np.asarray(ir.payload_cog(node.tool.tcp), dtype=float)
    total = node.tool.mass + mass
    total_cog = (node.tool.mass * tool_cog + moment) / total if total > 0 else tool_cog
    return HeldLoad(Load.of(mass, cog), Load.of(total, total_cog))
