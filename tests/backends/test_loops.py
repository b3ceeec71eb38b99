"""backends/loops.py: when a `for` loop's iterations can be one vendor loop."""

from __future__ import annotations

import math

import pytest
from backend_fixtures import FRONT_UP_NOFLIP
from loop_fixtures import Q0, palletiser, place

from rmot.backends import loops
from rmot.lang import ir


def analyse(plan, loop, **kw):  # type: ignore[no-untyped-def]
    tp = plan.tasks[0]
    return loops.analyse(loop, lambda n: tp.record(n.uid), **kw)


def test_grid_is_one_loop_with_the_steps_of_the_grid() -> None:
    plan, loop = palletiser(3, 4)
    t = analyse(plan, loop)
    assert isinstance(t, loops.LoopTemplate), getattr(t, "message", "")
    assert t.var.name == "layer" and (t.var.first, t.var.last) == (0, 2)
    inner = t.inner[t.body[0].uid]
    assert inner.var.name == "row" and (inner.var.first, inner.var.last) == (0, 3)
    slot = inner.body[1]
    off = t.targets[(slot.uid, "target")]
    assert [v.name for v in off.loops] == ["layer", "row"]
    assert off.step_of(t.var.uid) == pytest.approx((0.0, 0.0, 0.05))
    assert off.step_of(inner.var.uid) == pytest.approx((0.0, 0.06, 0.0))
    assert off.base.position == pytest.approx((0.1, 0.05, 0.02))
    # every iteration's pose comes back from the template
    for it in loop.iterations:
        for jt in it.body[0].iterations:
            want = jt.body[1].target.in_frame
            got = loops.offset_at(off, {t.var.uid: it.value, inner.var.uid: jt.value})
            assert got.position == pytest.approx(want.position, abs=1e-12)


def test_other_orientation_unrolls_naming_the_iteration() -> None:
    turned = ir.Pose.from_xyz_rpy(0, 0, 0, math.pi, 0, math.pi / 2).quaternion
    plan, loop = palletiser(
        2,
        3,
        pose=lambda a, b: place(
            0.1, 0.06 * b, 0.05 * a, turned if (a, b) == (1, 2) else place(0, 0, 0).quaternion
        ),
    )
    r = analyse(plan, loop)
    assert isinstance(r, loops.Unrolled)
    assert r.iteration == "layer = 1, row = 2"
    assert "orientation" in r.what


def test_non_affine_position_unrolls() -> None:
    plan, loop = palletiser(2, 3, pose=lambda a, b: place(0.1, 0.06 * b * b, 0.05 * a))
    r = analyse(plan, loop)
    assert isinstance(r, loops.Unrolled) and r.iteration == "layer = 0, row = 2", r
    assert "affine" in r.what


def test_other_branch_or_turn_unrolls() -> None:
    back = ir.Config(ir.Shoulder.FRONT, ir.Elbow.DOWN, ir.Wrist.NOFLIP)
    plan, loop = palletiser(2, 2, branch=lambda a, b: back if (a, b) == (1, 0) else FRONT_UP_NOFLIP)
    r = analyse(plan, loop)
    assert isinstance(r, loops.Unrolled) and r.iteration == "layer = 1, row = 0"
    assert "configuration" in r.what
    turned = Q0.copy()
    turned[5] -= 2 * math.pi
    plan, loop = palletiser(2, 2, q=lambda a, b: turned if (a, b) == (0, 1) else Q0)
    r = analyse(plan, loop)
    assert isinstance(r, loops.Unrolled) and r.iteration == "layer = 0, row = 1"


def test_unroll_option() -> None:
    plan, loop = palletiser(2, 2)
    r = analyse(plan, loop, unroll=True)
    assert isinstance(r, loops.Unrolled) and "--unroll" in r.what


def test_bind_loop_var() -> None:
    body = (
        ir.Assign(
            uid=1,
            name="n",
            value=ir.Arith(
                "+",
                ir.VarRef("i", ir.ValueType.INT),
                ir.Const(1, ir.ValueType.INT),
                ir.ValueType.INT,
            ),
        ),
    )
    assert loops.uses_loop_var(body, "i") and not loops.uses_loop_var(body, "j")
    bound = loops.bind_loop_var(body, "i", 3)
    assert not loops.uses_loop_var(bound, "i")  # the loop variable reads 3 now


def test_loop_plan_is_the_one_decision_of_every_vendor() -> None:
    """runtime.loop_plan: a template is one vendor loop; an analysis whose
    iterations but the last fit is that loop and then the last iteration, with W420's text at
    the differing instruction; a vendor blocker's reason writes every iteration, at the loop."""
    from rmot.backends import loops as lp
    from rmot.backends.runtime import loop_plan
    from rmot.lang import ir as _ir

    its = tuple(_ir.LoopIteration(value=v, body=()) for v in range(3))
    node = _ir.Loop(uid=1, var="i", first=0, last=3, iterations=its, span="loop")
    whole = lp.LoopTemplate(node, lp.LoopVar(1, "i", 0, 2), (), {}, {})
    plan = loop_plan(node, whole)
    assert (plan.template, plan.last, plan.why) == (whole, None, "")
    differs = lp.Unrolled(node, "i = 2", 7, "a wait where the first iteration has a move", "move")
    plan = loop_plan(node, differs)
    assert (plan.template, plan.last, plan.span) == (None, None, "move")
    assert plan.why == differs.message and "i = 2" in plan.why
    peeled = lp.Unrolled(node, "i = 2", 7, "it blends", "move", peeled=whole)
    plan = loop_plan(node, peeled)
    assert (plan.template, plan.last, plan.span) == (whole, its[-1], "move")
    assert "last iteration (i = 2)" in plan.why
    for found in (whole, peeled):
        plan = loop_plan(node, found, lambda t: "needs 12 registers")
        assert (plan.template, plan.last, plan.why, plan.span) == (
            None, None, "needs 12 registers", "loop")
