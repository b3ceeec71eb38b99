"""URScript movej re-timed from its own `a` and `v` equals the verified duration.

Witness: the documented movej semantics (Universal Robots, The URScript Programming Language,
e-Series, movej: "a: joint acceleration of leading axis [rad/s^2], v: joint speed of leading
axis [rad/s]"): every axis arrives together, the leading axis (the one that moves farthest,
by d) on a trapezoid: T = d / v + v / a when d >= v^2 / a, else 2 sqrt(d / a). Computed here
from the emitted text alone and compared with each rest-to-rest move's planned duration.
"""

from __future__ import annotations

import math
import re

import pytest

from rmot.backends import BACKENDS
from rmot.compiler.cli import stages

CELL = """cell ur_cell {
  robot r1 = ur5e at pose()
  tool load = sphere(r=20mm) at pose(z=60mm) tcp pose(z=100mm) mass 1 kg on r1
}
"""
PROGRAM = """program swing on r1 {
  tool load
  move joint joints(0, -90, 90, -90, -90, 0) deg zone fine
  move joint joints(60, -60, 60, -90, -90, 0) deg zone fine
  move joint joints(60, -100, 100, -60, -90, 90) deg zone fine speed 50 % accel 70 %
  move joint joints(-30, -90, 90, -90, -60, 0) deg zone fine
  move joint joints(-28, -88, 90, -90, -60, 0) deg zone fine
}
"""
MOVEJ = re.compile(r"movej\(\[([^\]]*)\], a=([\d.]+), v=([\d.]+), r=0(?:\.0+)?\)")


def _trapezoid(d: float, v: float, a: float) -> float:
    return d / v + v / a if d >= v * v / a else 2.0 * math.sqrt(d / a)


def test_rest_to_rest_movej_retimes_to_the_verified_duration(tmp_path) -> None:  # type: ignore[no-untyped-def]
    path = tmp_path / "swing.rmot"
    path.write_text(CELL + PROGRAM)
    front = stages.load(str(path), use_cache=False)
    assert front.program is not None
    plan = stages.plan(front.program, use_cache=False)
    (text,) = BACKENDS["urscript"]().emit(plan, source_map=False).files.values()
    moves = [([float(x) for x in q.split(",")], float(a), float(v)) for q, a, v in MOVEJ.findall(text)]
    records = sorted((r for r in plan.tasks[0].records if r.q_target is not None), key=lambda r: r.t_start)
    assert len(moves) == len(records) == 5
    for k in range(1, len(moves)):
        (q0, _, _), (q1, a, v) = moves[k - 1], moves[k]
        lead = max(abs(x1 - x0) for x0, x1 in zip(q0, q1))
        verified = records[k].t_end - records[k].t_start
        assert _trapezoid(lead, v, a) == pytest.approx(verified, rel=0.03), k
