"""The load a robot carries while it holds parts, for the backends' payload lines.

`held_load(node, ctx)`: after an `attach`/`detach`, the held parts' total mass and their
centre of gravity in the flange frame, and the same for tool + parts: the payload model every
reader shares (lang/payload.of: the plan's decided TaskLoad, read once per task), as numpy arrays.
`state_at_moves(ctx)`: which attach or detach a move carries the load of.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from rmot.lang import ir, ir_tree, payload

__all__ = ["held_load", "state_at_moves"]


def _loads(ctx: Any) -> dict[int, payload.HeldLoad]:
    cache = getattr(ctx, "_held_loads", None)
    if cache is None:
        cache = dict(payload.of(ctx.plan, ctx.task_plan).held)
        object.__setattr__(ctx, "_held_loads", cache)  # a cache on the (frozen) task context
    return cache


def held_load(node: ir.Attach | ir.Detach, ctx: Any) -> tuple[float, np.ndarray, float, np.ndarray]:
    """(parts' mass kg, their centre of gravity in the flange frame m, tool + parts mass,
    tool + parts centre of gravity) after `node`."""
    held = _loads(ctx)[node.uid]
    return held.parts.mass, held.parts.at(), held.total.mass, held.total.at()


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
