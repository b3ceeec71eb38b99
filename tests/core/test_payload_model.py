"""One payload model (lang/payload.py) for the planner, the verification and the backends.

Witness: tests/data/parts/stack.rmot's numbers by hand. The gripper is 1 kg with its TCP
100 mm out along the flange z axis (its mass at 50 mm, half way: ir.payload_cog); each cube
is 2 kg, 100 mm wide, gripped on its top face, so its centre is 50 mm beyond the TCP, at
150 mm from the flange.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from rmot.backends.part_load import held_load
from rmot.backends.rapid import RapidBackend
from rmot.lang import ir, ir_tree, payload
from rmot.compiler.frontend import load_program
from rmot.compiler.plan import plan_program

STACK = Path(__file__).resolve().parents[1] / "data" / "parts" / "stack.rmot"


@pytest.fixture(scope="module")
def planned():  # type: ignore[no-untyped-def]
    front = load_program(str(STACK))
    assert front.program is not None
    return plan_program(front.program)


def test_the_task_load_is_the_tool_and_the_heaviest_held_part_at_its_centre(planned) -> None:  # type: ignore[no-untyped-def]
    """(1 kg * 50 mm + 2 kg * 150 mm) / 3 kg = 116.67 mm along the flange z axis."""
    load = payload.of(planned, planned.tasks[0]).peak
    assert load is not None
    assert load.mass == pytest.approx(3.0)
    np.testing.assert_allclose(load.at(), [0.0, 0.0, 0.35 / 3], atol=2e-5)  # the stop is within microns of the target


def test_the_plan_carries_the_planners_decision(planned) -> None:  # type: ignore[no-untyped-def]
    """The planner decided the load before timing (from the targets) and put it on the plan:
    the same 3 kg at 116.67 mm, exactly (the targets, not the IK solutions)."""
    tp = planned.tasks[0]
    assert tp.load is not None and payload.of(planned, tp) is tp.load
    assert tp.load.peak is not None
    np.testing.assert_allclose(tp.load.peak.at(), [0.0, 0.0, 0.35 / 3], atol=1e-12)


def test_every_reader_gets_the_load_after_an_attach_from_the_model(planned) -> None:  # type: ignore[no-untyped-def]
    """The backends' load after each attach is the model's, and the verification's task load
    is the heaviest of them with the tool: one decider."""
    tp = planned.tasks[0]
    loads = dict(payload.of(planned, tp).held)
    attaches = [i for i in ir_tree.walk(tp.task.body) if isinstance(i, ir.Attach)]
    assert [a.part for a in attaches] == ["b1", "b2"]
    ctx = type("Ctx", (), {})()
    ctx.plan, ctx.task_plan = planned, tp
    for attach in attaches:
        mass, cog, total, total_cog = held_load(attach, ctx)
        assert (mass, total) == (loads[attach.uid].parts.mass, loads[attach.uid].total.mass) == (2.0, 3.0)
        np.testing.assert_allclose(cog, [0.0, 0.0, 0.15], atol=2e-5)
        np.testing.assert_allclose(total_cog, [0.0, 0.0, 0.35 / 3], atol=2e-5)
    assert payload.of(planned, tp).peak == loads[attaches[0].uid].total


def test_rapid_prints_the_models_load(planned) -> None:  # type: ignore[no-untyped-def]
    """The RAPID module's part loaddata: 2 kg at the model's 150 mm from the flange, which
    RAPID takes in the tool frame for GripLoad (ABB RAPID Instructions, Functions and Data
    types: loaddata, "cog ... in the tool coordinate system"): 150 - 100 = 50 mm."""
    result = RapidBackend().emit(planned)
    text = "\n".join(result.files.values())
    assert "PERS loaddata load_b1:=[2.000,[0.000,0.000,50.000]," in text
