"""The cost of parts in the collision check: configurations checked per second
without parts, and with 24 parts (one held on the flange, 23 placed around the arm), on the
same arm, fixtures and path as bench_verify.py's "clear" setting.

Run: .venv/bin/python -m pytest tests/benchmarks/bench_parts.py --benchmark-only -s -o addopts='' \
         -o python_files='bench_*.py'
(the numbers of interest are printed and stored in each benchmark's extra_info; the ratio is
measured in the same run, so a loaded machine slows both sides).
"""

from __future__ import annotations

import time

import numpy as np
import pytest

from rmot.lang import ir
from rmot.sim.robots import load_robot
from rmot.sim.collide import Timeline, candidate_pairs, check_timeline
from rmot.sim.parts import Phase, part_hits
from rmot.sim.scene import build_scene

N_SAMPLES = 20_000
N_PARTS = 24


def _cell() -> ir.Cell:
    """bench_verify's UR5e amid 20 fixtures just outside its path, plus 24 boxes: p00 held at
    the TCP, the other 23 on a ring at 0.8 m, 0.3 m below the base (a conveyor's height)."""
    rng = np.random.default_rng(7)
    fixtures = []
    for k in range(20):
        angle = 2 * np.pi * k / 20
        radius = 0.95 if k % 2 else 1.25
        at = (radius * np.cos(angle), radius * np.sin(angle), float(rng.uniform(-0.2, 0.6)))
        geometry: ir.Geometry = (ir.Box((0.12, 0.12, float(rng.uniform(0.1, 0.4)))) if k % 3
                                 else ir.Cylinder(0.05, float(rng.uniform(0.2, 0.5))))
        fixtures.append(ir.Fixture(f"f{k:02d}", geometry, ir.Pose(at)))
    parts = [ir.Part("p00", ir.Box((0.08, 0.08, 0.08)), ir.Pose(), 1.0)]
    for k in range(1, N_PARTS):
        angle = 2 * np.pi * k / (N_PARTS - 1)
        parts.append(ir.Part(f"p{k:02d}", ir.Box((0.1, 0.1, 0.1)), ir.Pose((0.8 * np.cos(angle), 0.8 * np.sin(angle), -0.3)), 1.0))
    robot = ir.RobotInstance("r1", ir.RobotSource(ir.RobotSourceKind.LIBRARY, "ur5e"), ir.Pose(), 6)
    return ir.Cell("bench", (robot,), tuple(fixtures), parts=tuple(parts))


def _joint_path(robot, n: int) -> np.ndarray:  # type: ignore[no-untyped-def]
    rng = np.random.default_rng(3)
    lo, hi = robot.joint_limits[:, 0] / 3, robot.joint_limits[:, 1] / 3
    waypoints = lo + rng.random((n // 500 + 1, robot.dof)) * (hi - lo)
    s = np.linspace(0, len(waypoints) - 1, n)
    return np.stack([np.interp(s, np.arange(len(waypoints)), waypoints[:, j]) for j in range(robot.dof)], axis=1)


@pytest.fixture(scope="module")
def setting():  # type: ignore[no-untyped-def]
    cell = _cell()
    robot = load_robot("ur5e")
    scene = build_scene(cell, {}, {"r1": robot})
    q = _joint_path(robot, N_SAMPLES)
    t = np.arange(N_SAMPLES) * 0.004
    timeline = Timeline(t, {"r1": q}, {"r1": np.full_like(q, 5.0)})
    held = np.eye(4)
    held[2, 3] = 0.12  # 120 mm beyond the flange
    phase = Phase(0.0, float(t[-1]), {p.name: p.pose.matrix() for p in cell.parts[1:]}, {"p00": ("r1", held)})
    return scene, timeline, phase


def _without(scene, timeline):  # type: ignore[no-untyped-def]
    return check_timeline(scene, timeline, candidate_pairs(scene))


def _with(scene, timeline, phase):  # type: ignore[no-untyped-def]
    return _without(scene, timeline) + part_hits(scene, timeline, [phase])


def _cpu(fn) -> float:  # type: ignore[no-untyped-def]
    t0 = time.process_time()
    fn()
    return time.process_time() - t0


def test_configurations_per_second_without_parts(benchmark, setting) -> None:  # type: ignore[no-untyped-def]
    scene, timeline, _ = setting
    benchmark.pedantic(_without, args=(scene, timeline), rounds=3, iterations=1)
    rate = N_SAMPLES / benchmark.stats.stats.median
    cpu = min(_cpu(lambda: _without(scene, timeline)) for _ in range(2))
    benchmark.extra_info.update(configs_per_s=round(rate), configs_per_cpu_s=round(N_SAMPLES / cpu))
    print(f"\nno parts: {rate:,.0f} configurations/s (wall median), {N_SAMPLES / cpu:,.0f} per CPU second")


def test_configurations_per_second_with_24_parts(benchmark, setting) -> None:  # type: ignore[no-untyped-def]
    scene, timeline, phase = setting
    hits = benchmark.pedantic(_with, args=(scene, timeline, phase), rounds=3, iterations=1)
    rate = N_SAMPLES / benchmark.stats.stats.median
    cpu_with = min(_cpu(lambda: _with(scene, timeline, phase)) for _ in range(2))
    cpu_without = min(_cpu(lambda: _without(scene, timeline)) for _ in range(2))
    benchmark.extra_info.update(configs_per_s=round(rate), configs_per_cpu_s=round(N_SAMPLES / cpu_with),
                                cpu_ratio_with_over_without=round(cpu_with / cpu_without, 2), hits=len(hits))
    print(f"\n24 parts (1 held, 23 placed): {rate:,.0f} configurations/s (wall median), "
          f"{N_SAMPLES / cpu_with:,.0f} per CPU second; CPU time x{cpu_with / cpu_without:.2f} of the check "
          f"without parts (same run); {len(hits)} contact intervals")
