"""The load a robot carries while it holds parts, for the backends' payload lines.

`held_load(node, ctx)`: after an `attach`/`detach`, the held parts' total mass and their
centre of gravity in the flange frame, and the same for tool + parts. A part's centre is
where the plan puts it: its starting pose (the cell's `part ... at`, robot base frame) seen
from the flange at the move before its attach (the robot stands still there: the planner
stops before an attach). A part that another task moved before (a hand-over) has no such
pose in this task's plan alone; its centre is then taken at the TCP, where the gripper
holds it. The verification's torque check (sim/parts.py) uses each part's true centroid.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from rmot.compiler import ir, ir_tree

__all__ = ["held_load", "part_centres", "state_at_moves"]


def part_centres(ctx: Any) -> dict[int, np.ndarray]:
    """Attach uid -> the part's centre in the flange frame (m), for every attach of the task.

    A part taken where it was declared has its declared centre; a feeder presents every part
    of its supply at the declared pose, so each attach of a feeder part has it too. A plain
    part attached again (it was put down somewhere since) is taken as centred on the TCP."""
    cache = getattr(ctx, "_part_centres", None)
    if cache is not None:
        return cache
    program = ctx.plan.program
    cell = program.cell
    parts = {p.name: p for p in cell.parts}
    attached_elsewhere = {i.part for t in program.tasks if t.name != ctx.task.name
                          for i in ir_tree.walk(t.body) if isinstance(i, ir.Attach)}
    base_inv = ctx.robot.base.inverse()
    flange: ir.Pose | None = None
    seen: set[str] = set()
    out: dict[int, np.ndarray] = {}
    for instr in ir_tree.walk(ctx.task.body):
        if isinstance(instr, ir.Move):
            rec = ctx.record(instr)
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
    object.__setattr__(ctx, "_part_centres", out)  # a cache on the (frozen) task context
    return out


def held_load(node: ir.Attach | ir.Detach, ctx: Any) -> tuple[float, np.ndarray, float, np.ndarray]:
    """(parts' mass kg, their centre of gravity in the flange frame m, tool + parts mass,
    tool + parts centre of gravity) after `node`."""
    centres = part_centres(ctx)
    parts = {p.name: p for p in ctx.plan.program.cell.parts}
    latest: dict[str, int] = {}
    for instr in ir_tree.walk(ctx.task.body):
        if isinstance(instr, ir.Attach):
            latest[instr.part] = instr.uid
        if instr is node or instr.uid == node.uid:
            break
    mass = 0.0
    moment = np.zeros(3)
    for name in node.held:
        m = parts[name].mass if name in parts else 0.0
        mass += m
        moment += m * centres.get(latest.get(name, -1), np.asarray(node.tool.tcp.position, dtype=float))
    cog = moment / mass if mass > 0 else np.asarray(node.tool.tcp.position, dtype=float)
    tool_cog = np.asarray(ir.payload_cog(node.tool.tcp), dtype=float)
    total = node.tool.mass + mass
    total_cog = (node.tool.mass * tool_cog + moment) / total if total > 0 else tool_cog
    return mass, cog, total, total_cog


def state_at_moves(ctx: Any) -> dict[int, ir.Attach | ir.Detach | None]:
    """Move uid -> the attach or detach whose held parts the move carries (None: none yet),
    through `if` arms (each arm starts from the state before the `if`; both end alike, E143),
    proc calls and loops (ir_tree.flow), for vendors that write the load with every motion (KRL)."""
    cache = getattr(ctx, "_part_state", None)
    if cache is not None:
        return cache
    out: dict[int, ir.Attach | ir.Detach | None] = {}

    def walk(nodes: tuple[ir.Instr, ...], cur: ir.Attach | ir.Detach | None) -> ir.Attach | ir.Detach | None:
        for n in nodes:
            if isinstance(n, (ir.Attach, ir.Detach)):
                cur = n
            elif isinstance(n, ir.Move):
                out[n.uid] = cur
            else:
                runs, bodies = ir_tree.flow(n)
                if runs.sure:  # a proc body, a loop's iterations: one after another
                    for sub in bodies:
                        cur = walk(sub, cur)
                elif bodies:  # if arms, a while's body, a timeout branch: from the state before
                    ends = [walk(sub, cur) for sub in bodies]
                    # both arms of an if end alike (E143); a body that may not run leaves it
                    cur = ends[0] if runs is ir_tree.Runs.ONE_OF else cur
        return cur

    walk(ctx.task.body, None)
    object.__setattr__(ctx, "_part_state", out)
    return out
