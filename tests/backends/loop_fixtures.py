"""Hand-built loop programs for the loop analysis and the vendor loop tests.

A palletiser nest `for layer in 0 .. L-1 { for row in 0 .. R-1 { ... } }` lowered as the front
end lowers it: every iteration's body with its own uids and the loop variables bound into the
targets (the place pose = base + layer * dz + row * dy), and a record per move.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from itertools import count

import numpy as np
from backend_fixtures import (
    BASE,
    FRONT_UP_NOFLIP,
    GRIPPER,
    TABLE,
    cart,
    deg,
    hand_plan,
    motion,
    span_at,
)

from rmot.lang import ir, plan_types

L_KIND, J_KIND = ir.MotionKind.LINEAR, ir.MotionKind.JOINT
DOWN_Q = ir.Pose.from_xyz_rpy(0, 0, 0, math.pi, 0, 0).quaternion
Q0 = deg(10, 20, 30, -100, -50, 200)


def place(
    x: float, y: float, z: float, quaternion: tuple[float, float, float, float] = DOWN_Q
) -> ir.Pose:
    return ir.Pose((x, y, z), quaternion)


def palletiser(
    layers: int,
    rows: int,
    *,
    pose: Callable[[int, int], ir.Pose] | None = None,
    branch: Callable[[int, int], ir.Config] | None = None,
    q: Callable[[int, int], np.ndarray] | None = None,
    frame: ir.FrameRef = TABLE,
) -> tuple[plan_types.Plan, ir.Loop]:
    """A two-level loop nest: per (layer, row) an approach move, a place move and a gripper
    set. `pose(layer, row)` gives the place pose in `frame` (default: base + row*60 mm in y +
    layer*50 mm in z); `branch`/`q` the planned branch and joints of each move."""
    uid = count(100)
    pose = pose or (lambda a, b: place(0.1, 0.05 + 0.06 * b, 0.02 + 0.05 * a))
    branch = branch or (lambda a, b: FRONT_UP_NOFLIP)
    q = q or (lambda a, b: Q0)
    records: dict[int, tuple[np.ndarray, ir.Config | None]] = {}

    def iteration_body(a: int, b: int) -> tuple[ir.Instr, ...]:
        p = pose(a, b)
        above = ir.Pose((p.position[0], p.position[1], p.position[2] + 0.1), p.quaternion)
        m1 = ir.Move(
            uid=next(uid),
            kind=J_KIND,
            target=cart(above, frame, "above"),
            motion=motion(),
            tool=GRIPPER,
            frame=frame,
            span=span_at(20),
        )
        m2 = ir.Move(
            uid=next(uid),
            kind=L_KIND,
            target=cart(p, frame, "slot"),
            motion=motion(speed=0.1),
            tool=GRIPPER,
            frame=frame,
            span=span_at(21),
        )
        s = ir.SetDigital(uid=next(uid), port=1, value=False, span=span_at(22))
        for m in (m1, m2):
            records[m.uid] = (q(a, b), branch(a, b))
        return (m1, m2, s)

    outer_uid = next(uid)
    iterations = []
    for a in range(layers):
        inner_uid = next(uid)
        inner = ir.Loop(
            uid=inner_uid,
            var="row",
            first=0,
            last=rows,
            span=span_at(19),
            iterations=tuple(
                ir.LoopIteration(value=b, body=iteration_body(a, b)) for b in range(rows)
            ),
        )
        iterations.append(ir.LoopIteration(value=a, body=(inner,)))
    loop = ir.Loop(
        uid=outer_uid,
        var="layer",
        first=0,
        last=layers,
        iterations=tuple(iterations),
        span=span_at(18),
    )
    home = ir.Move(
        uid=1,
        kind=J_KIND,
        target=ir.JointTarget(tuple(deg(0, -30, 30, 0, 60, 0)), "home"),
        motion=motion(),
        tool=GRIPPER,
        frame=BASE,
        span=span_at(17),
    )
    records[1] = (deg(0, -30, 30, 0, 60, 0), FRONT_UP_NOFLIP)
    plan = hand_plan((home, loop), records)
    return plan, loop
