"""Backend benchmark: emitting a 1000-instruction hand-built plan for RAPID, KRL and Fanuc TP.

The plan is built by hand (no planner), so the numbers are the formatting cost alone:
1000 instructions = 250 cycles of linear move, set output, wait, joint move. The split
limits are at their defaults (1000 per module for KRL and TP: no split here).

Run: .venv/bin/python -m pytest tests/benchmarks/bench_backends.py --benchmark-only -q
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "backends"))

from backend_fixtures import FRONT_UP_NOFLIP, GRIPPER, TABLE, cart, deg, hand_plan, move

from rmot.backends import BACKENDS
from rmot.lang import ir, plan_types


def long_plan(cycles: int = 250) -> plan_types.Plan:
    body: list[ir.Instr] = []
    records = {}
    for k in range(cycles):
        pose = ir.Pose.from_xyz_rpy(0.1 + 0.001 * k, 0.2, 0.15, math.pi, 0, 0.01 * k)
        uid = 4 * k + 1
        body += [move(uid, ir.MotionKind.LINEAR, cart(pose, TABLE, f"p{k}"), tool=GRIPPER, frame=TABLE, zone=0.005),
                 ir.SetDigital(uid=uid + 1, port=1, value=bool(k % 2)),
                 ir.WaitTime(uid=uid + 2, duration=0.1),
                 move(uid + 3, ir.MotionKind.JOINT, ir.JointTarget(tuple(deg(0, -30, 30, 0, 60, 0)), "home"))]
        records[uid] = records[uid + 3] = (deg(10, 20, 30, -100, -50, 200), FRONT_UP_NOFLIP)
    return hand_plan(tuple(body), records)


@pytest.mark.parametrize("vendor", ["rapid", "krl", "fanuc"])
def test_emit_1000_instructions(benchmark, vendor: str) -> None:  # type: ignore[no-untyped-def]
    """Emit time of 1000 instructions (median reported by pytest-benchmark)."""
    plan = long_plan()
    result = benchmark(lambda: BACKENDS[vendor]().emit(plan))
    assert not result.has_errors
    benchmark.extra_info["lines"] = sum(text.count("\n") for text in result.files.values())
