"""Hand-built runtime-logic programs for the Fanuc, INFORM and VAL3 emitters: a
3 x 4 x 3 palletiser written with nested `for` loops and a machine-tending task with a
counter, a `while` on an input, a timeout branch and `stop`, lowered as the front end lowers
them (every loop iteration with its own uids, the loop variables bound into the targets) and
planned by hand (backend_fixtures.hand_plan: each move at Q, one branch)."""

from __future__ import annotations

import math
from itertools import count

import numpy as np
from backend_fixtures import (
    BRAND_ROBOT,
    FRONT_UP_NOFLIP,
    GRIPPER,
    TABLE,
    cart,
    hand_plan,
    motion,
    span_at,
)
from rmot.lang import ir, ir_tree, plan_types

J, L = ir.MotionKind.JOINT, ir.MotionKind.LINEAR
DOWN_Q = ir.Pose.from_xyz_rpy(0, 0, 0, math.pi, 0, 0).quaternion
Q = np.radians(np.array([10.0, 20.0, 30.0, -100.0, -50.0, 200.0]))
INT, BOOL = ir.ValueType.INT, ir.ValueType.BOOL
LAYERS, ROWS, COLS = 3, 4, 3


def slot(layer: int, row: int, col: int) -> ir.Pose:
    """The place pose of one box on the table: 80 mm columns, 60 mm rows, 50 mm layers."""
    return ir.Pose((0.1 + 0.08 * col, 0.05 + 0.06 * row, 0.02 + 0.05 * layer), DOWN_Q)


def _move(
    uid: int, kind: ir.MotionKind, pose: ir.Pose, name: str, line: int, speed: float = 0.25
) -> ir.Move:
    return ir.Move(
        uid=uid,
        kind=kind,
        target=cart(pose, TABLE, name),
        motion=motion(speed=speed),
        tool=GRIPPER,
        frame=TABLE,
        span=span_at(line),
    )


def pallet_program(
    vendor: str, *, branch_of: dict[tuple[int, int, int], ir.Config] | None = None
) -> tuple[plan_types.Plan, ir.Loop]:
    """home; for layer in 0..2 { for row in 0..3 { for col in 0..2 { above; place; release;
    above } } }; home. `branch_of` gives some iterations another planned IK branch."""
    uid = count(10)
    records: dict[int, tuple[np.ndarray, ir.Config | None]] = {}
    home_pose = ir.Pose((0.3, 0.2, 0.4), DOWN_Q)

    def body(a: int, b: int, c: int) -> tuple[ir.Instr, ...]:
        p = slot(a, b, c)
        above = ir.Pose((p.position[0], p.position[1], p.position[2] + 0.1), DOWN_Q)
        m1 = _move(next(uid), J, above, "above", 6)
        m2 = _move(next(uid), L, p, "place", 7, speed=0.1)
        s = ir.SetDigital(uid=next(uid), port=1, value=False, span=span_at(8))
        m3 = _move(next(uid), L, above, "above", 9)
        for m in (m1, m2, m3):
            records[m.uid] = (Q, (branch_of or {}).get((a, b, c), FRONT_UP_NOFLIP))
        return (m1, m2, s, m3)

    def nest(a: int) -> ir.Loop:
        rows = []
        for b in range(ROWS):
            inner = ir.Loop(
                uid=next(uid),
                var="col",
                first=0,
                last=COLS,
                span=span_at(5),
                iterations=tuple(
                    ir.LoopIteration(value=c, body=body(a, b, c)) for c in range(COLS)
                ),
            )
            rows.append(ir.LoopIteration(value=b, body=(inner,)))
        return ir.Loop(
            uid=next(uid),
            var="row",
            first=0,
            last=ROWS,
            span=span_at(4),
            iterations=tuple(rows),
        )

    home = _move(1, J, home_pose, "home", 2)
    records[1] = (Q, FRONT_UP_NOFLIP)
    loop_uid = next(uid)
    loop = ir.Loop(
        uid=loop_uid,
        var="layer",
        first=0,
        last=LAYERS,
        span=span_at(3),
        iterations=tuple(ir.LoopIteration(value=a, body=(nest(a),)) for a in range(LAYERS)),
    )
    back = _move(2, J, home_pose, "home", 11)
    records[2] = (Q, FRONT_UP_NOFLIP)
    return hand_plan((home, loop, back), records, robot=BRAND_ROBOT[vendor], name="pallet"), loop


def var(name: str, vtype: ir.ValueType = INT) -> ir.VarRef:
    return ir.VarRef(name, vtype)


def const(value: int | bool) -> ir.Const:
    return ir.Const(value, BOOL if isinstance(value, bool) else INT)


def tending_program(vendor: str) -> plan_types.Plan:
    """var count = 0; var done = false
    while not done and in[2] == off {
      move joint above; wait until in[1] == on timeout 10 s else { set out[3] on; stop }
      move linear pick; set out[1] on; move linear above; count = count + 1
      if count >= 10 or in[4] == on { done = true }
      wait until in[3] == on or count > 100 timeout 5 s else { count = count - 1 }
    }
    stop"""
    above = ir.Pose((0.2, 0.1, 0.25), DOWN_Q)
    pick = ir.Pose((0.2, 0.1, 0.12), DOWN_Q)
    m1, m2, m3 = (
        _move(3, J, above, "above", 5),
        _move(6, L, pick, "pick", 7, 0.1),
        _move(8, L, above, "above", 9),
    )
    timeout = ir.WaitInput(
        uid=4,
        condition=ir.InputCondition(port=1, value=True),
        timeout=10.0,
        span=span_at(6),
        on_timeout=(
            ir.SetDigital(uid=5, port=3, value=True, span=span_at(6)),
            ir.Stop(uid=50, span=span_at(6)),
        ),
    )
    bump = ir.Assign(
        uid=9, name="count", value=ir.Arith("+", var("count"), const(1), INT), span=span_at(10)
    )
    enough = ir.If(
        uid=10,
        condition=ir.Logic(
            "or",
            (
                ir.Compare(ir.CompareOp.GE, var("count"), const(10)),
                ir.InputCondition(port=4, value=True),
            ),
        ),
        then=(ir.Assign(uid=11, name="done", value=const(True), span=span_at(11)),),
        span=span_at(11),
    )
    settle = ir.WaitCondition(
        uid=12,
        condition=ir.Logic(
            "or",
            (
                ir.InputCondition(port=3, value=True),
                ir.Compare(ir.CompareOp.GT, var("count"), const(100)),
            ),
        ),
        timeout=5.0,
        span=span_at(12),
        on_timeout=(
            ir.Assign(
                uid=13,
                name="count",
                span=span_at(12),
                value=ir.Arith("-", var("count"), const(1), INT),
            ),
        ),
    )
    loop = ir.While(
        uid=14,
        condition=ir.Logic(
            "and", (ir.Not(var("done", BOOL)), ir.InputCondition(port=2, value=False))
        ),
        body=(
            m1,
            timeout,
            m2,
            ir.SetDigital(uid=7, port=1, value=True, span=span_at(8)),
            m3,
            bump,
            enough,
            settle,
        ),
        span=span_at(4),
    )
    body = (
        ir.VarDecl(uid=1, name="count", type=INT, init=const(0), span=span_at(2)),
        ir.VarDecl(uid=2, name="done", type=BOOL, init=const(False), span=span_at(3)),
        loop,
        ir.Stop(uid=15, span=span_at(14)),
    )
    records = {m.uid: (Q, FRONT_UP_NOFLIP) for m in (m1, m2, m3)}
    return hand_plan(body, records, robot=BRAND_ROBOT[vendor], name="tending")


def iteration_poses(loop: ir.Loop, plan: plan_types.Plan) -> list[tuple[str, ir.Pose]]:
    """(target name, the planned TCP in the move's frame) of every move of every iteration,
    in execution order: what the plan verified, from its records."""
    out: list[tuple[str, ir.Pose]] = []
    tp = plan.tasks[0]
    for node in ir_tree.walk((loop,)):
        if isinstance(node, ir.Move):
            rec = tp.record(node.uid)
            assert rec is not None and rec.tcp_pose is not None
            name = node.target.name or ""
            out.append((name, node.frame.pose.inverse() * rec.tcp_pose))
    return out
