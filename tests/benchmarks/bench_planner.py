"""Planner benchmark: a 100-instruction pick-and-place on the ABB IRB 120.

Reports (pytest-benchmark medians) the planner's time and, in the same run, a plain baseline
that does what a naive planner would: dense numeric IK (damped Newton from the previous point,
1 mm steps) along every Cartesian move and uniform timing (every step at the speed of its
slowest joint or the programmed TCP speed, no acceleration phases, no blends). `extra_info` holds instructions, trajectory
seconds and the planner/baseline ratio.

Run: .venv/bin/python -m pytest tests/benchmarks/bench_planner.py --benchmark-only -q
     (or directly: .venv/bin/python tests/benchmarks/bench_planner.py)
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plan"))

from plan_helpers import Prog, pose, program

from rmot.lang import ir, ir_tree
from rmot.compiler.plan import plan_program
from rmot.compiler.plan.dense import newton_ik

DOWN = dict(rx=180, ry=0, rz=180)


def pick_and_place(n_instructions: int = 100) -> ir.Program:
    """Cycles of: joint above pick, linear down, grip, wait, linear up, joint above place,
    linear down, release, wait, linear up (zones 10 mm on the approach moves)."""
    p = Prog()
    p.joint([0, 0, 0, 0, 30, 0])
    k = 0
    while len(p.body) < n_instructions:
        px, py = 300 + 20 * (k % 3), -150 + 25 * (k % 4)
        qx, qy = 250 + 30 * (k % 2), 150 + 20 * (k % 3)
        p.joint(pose(px, py, 250, **DOWN), zone=10, joint_speed=0.8)
        p.linear(pose(px, py, 150, **DOWN), speed=200)
        p.set(1, True)
        p.wait(0.1)
        p.linear(pose(px, py, 250, **DOWN), speed=500, zone=10)
        p.joint(pose(qx, qy, 250, **DOWN), zone=10, joint_speed=0.8)
        p.linear(pose(qx, qy, 180, **DOWN), speed=200)
        p.set(1, False)
        p.wait(0.1)
        p.linear(pose(qx, qy, 250, **DOWN), speed=500, zone=10)
        k += 1
    return program(p.task())


def baseline(prog: ir.Program, step: float = 0.004) -> float:
    """Dense numeric IK + uniform timing (each step at the speed of its slowest joint or the
    programmed TCP speed, no acceleration phases); returns the trajectory duration (s)."""
    from rmot.sim.robots import load_robot

    robot = load_robot(prog.cell.robots[0].source.load_key)
    q = np.zeros(robot.dof)
    total, path = 0.0, [q]
    for instr in ir_tree.walk(prog.tasks[0].body):
        if isinstance(instr, ir.WaitTime):
            total += instr.duration
        if not isinstance(instr, ir.Move):
            continue
        if isinstance(instr.target, ir.JointTarget):
            goal = np.array(instr.target.values)
            qs = q + np.linspace(0, 1, 50)[:, None] * (goal - q)
        else:
            start, end = robot.fk(q), instr.target.pose.matrix()
            n = max(2, int(np.linalg.norm(end[:3, 3] - start[:3, 3]) / 1e-3) + 1)
            qs = [q]
            for u in np.linspace(0, 1, n)[1:]:
                t = end.copy()
                t[:3, 3] = start[:3, 3] + u * (end[:3, 3] - start[:3, 3])
                qs.append(newton_ik(robot, t, qs[-1], iters=20) if instr.kind is not ir.MotionKind.JOINT else qs[-1])
                if qs[-1] is None:
                    qs[-1] = qs[-2]
            qs = np.array(qs)
        vmax = robot.velocity_limits * (instr.motion.joint_speed if instr.kind is ir.MotionKind.JOINT else 1.0)
        dt = np.max(np.abs(np.diff(qs, axis=0)) / vmax, axis=1)
        if instr.kind is not ir.MotionKind.JOINT:  # and no faster than the programmed TCP speed
            tcp = robot.fk_batch(qs)[:, :3, 3]
            dt = np.maximum(dt, np.linalg.norm(np.diff(tcp, axis=0), axis=1) / instr.motion.tcp_speed)
        total += float(np.sum(dt))
        path.append(qs[-1])
        q = qs[-1]
    return total


def test_plan_pick_and_place(benchmark) -> None:  # type: ignore[no-untyped-def]
    """Plan the 100-instruction program; compare with the plain baseline run in the same test."""
    prog = pick_and_place()
    plan_program(prog)  # warm up: imports, robot cache
    plan = benchmark(plan_program, prog)
    assert not [d for d in plan.diagnostics if d.is_error]
    t0 = time.perf_counter()
    baseline_traj = baseline(prog)
    baseline_s = time.perf_counter() - t0
    n = sum(1 for _ in ir_tree.walk(prog.tasks[0].body))
    benchmark.extra_info.update(
        instructions=n, trajectory_s=round(plan.cycle_time, 3), baseline_s=round(baseline_s, 4),
        baseline_trajectory_s=round(baseline_traj, 3),
        ratio_planner_over_baseline=round(benchmark.stats.stats.median / baseline_s, 3),
    )


if __name__ == "__main__":
    prog = pick_and_place()
    plan_program(prog)
    times = []
    for _ in range(5):
        t0 = time.perf_counter()
        plan = plan_program(prog)
        times.append(time.perf_counter() - t0)
    t0 = time.perf_counter()
    traj = baseline(prog)
    base = time.perf_counter() - t0
    n = sum(1 for _ in ir_tree.walk(prog.tasks[0].body))
    print(f"instructions {n}, trajectory {plan.cycle_time:.3f} s, planning median "
          f"{np.median(times) * 1e3:.0f} ms; baseline {base * 1e3:.0f} ms (trajectory {traj:.3f} s); "
          f"ratio {np.median(times) / base:.2f}; errors {[d.code.id for d in plan.diagnostics]}")
