"""The payload: what a robot's flange carries (its tool and the parts it holds) as one point
mass, decided here for every reader: the planner's torque limits (compiler/plan/torque.py),
the verification's torque check (sim/verification.py) and the backends' payload lines
(backends/part_load.py).

The model, in the flange frame (kg, m):
- a tool's mass sits at `ir.payload_cog`, half way along the flange->TCP vector;
- a held part's mass sits at its centre, fixed at its attach (`held_loads`): its declared
  pose (the cell's `part ... at`, robot base frame; every part of a feeder is presented there)
  seen from the flange at the move before the attach, where the robot stands still (the
  planner stops before an attach). A plain part attached again (it was put down somewhere
  since) or one another task also attaches (a hand-over) is taken at the TCP, where the
  gripper holds it;
- the load a task's torques are checked with is the heaviest tool it uses plus the heaviest
  set of parts it holds at once (`task_load`).
The planner times a task before its flange poses exist, so its bound (`timing_load`) takes the
same tool and the same heaviest set of parts, each part at the TCP of the tool that attaches
it: the difference is the parts' centres' offset from the TCP.
"""

from __future__ import annotations

import numpy as np

from rmot.lang import ir, ir_tree, plan_types
from rmot.lang.record import record

__all__ = ["HeldLoad", "Load", "heaviest_tool", "held_loads", "task_load", "timing_load"]


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


def timing_load(task: ir.Task, parts: tuple[ir.Part, ...]) -> Load | None:
    """The planner's bound: the heaviest tool plus the heaviest set of parts the task holds at
    once (an attach's `held`), at the TCP of the tool of that attach."""
    tool = heaviest_tool(task.body)
    masses = {p.name: p.mass for p in parts}
    held_mass, held_at = 0.0, None
    for instr in ir_tree.walk(task.body):
        if isinstance(instr, ir.Attach):
            mass = sum(masses.get(name, 0.0) for name in instr.held)
            if mass > held_mass:
                held_mass, held_at = mass, np.asarray(instr.tool.tcp.position, dtype=float)
    if held_at is None:
        return tool
    return _with_tool(tool, held_mass, held_at)


def task_load(plan: plan_types.Plan | None, tp: plan_types.TaskPlan) -> Load | None:
    """The load the task's torques are checked with: its heaviest tool plus the heaviest set of
    parts it holds at once (after an attach or detach of the plan, `held_loads`), at their
    centres; None when it carries nothing."""
    tool = heaviest_tool(tp.task.body)
    if plan is None or not plan.program.cell.parts:
        return tool
    heaviest: Load | None = None
    for held in held_loads(plan, tp).values():
        if held.parts.mass > (heaviest.mass if heaviest else 0.0):
            heaviest = held.parts
    if heaviest is None:
        return tool
    return _with_tool(tool, heaviest.mass, heaviest.at())


def _part_centres(plan: plan_types.Plan, tp: plan_types.TaskPlan) -> dict[int, np.ndarray]:
    """Attach uid -> the part's centre in the flange frame (m), for every attach of the task.

    A part taken where it was declared has its declared centre; a feeder presents every part
    of its supply at the declared pose, so each attach of a feeder part has it too. A plain
    part attached again (it was put down somewhere since) is taken as centred on the TCP."""
    program = plan.program
    parts = {p.name: p for p in program.cell.parts}
    attached_elsewhere = {i.part for t in program.tasks if t.name != tp.task.name
                          for i in ir_tree.walk(t.body) if isinstance(i, ir.Attach)}
    base_inv = program.cell.robot(tp.robot).base.inverse()
    flange: ir.Pose | None = None
    seen: set[str] = set()
    out: dict[int, np.ndarray] = {}
    for instr in ir_tree.walk(tp.task.body):
        if isinstance(instr, ir.Move):
            rec = tp.record(instr.uid)
            if rec is not None and rec.flange_pose is not None:
                flange = rec.flange_pose
        elif isinstance(instr, ir.Attach):
            part = parts.get(instr.part)
            tcp = np.asarray(instr.tool.tcp.position, dtype=float)
            if part is None or flange is None or (instr.part in seen and not part.feeder) or instr.part in attached_elsewhere:
                out[instr.uid] = tcp
            else:
                in_base = base_inv * part.pose
                out[instr.uid] = np.asarray((flange.inverse() * in_base).position, dtype=float)
            seen.add(instr.part)
    return out


def held_loads(plan: plan_types.Plan, tp: plan_types.TaskPlan) -> dict[int, HeldLoad]:
    """Attach/detach uid -> the load after it: the held parts' mass at their centres, and the
    tool's mass (at ir.payload_cog) with them."""
    centres = _part_centres(plan, tp)
    parts = {p.name: p for p in plan.program.cell.parts}
    latest: dict[str, int] = {}
    out: dict[int, HeldLoad] = {}
    for node in ir_tree.walk(tp.task.body):
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
