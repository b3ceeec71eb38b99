"""Torque-limited timing benchmark: what a binding joint torque limit costs the planner.

Programs on a UR5e (cited ratings 150/150/150/28/28/28 N·m): alternating joint and linear
moves between random points of a box in front of the arm, 10 mm zones, with a tool of MASS kg
at 100 mm. For each mass: the cycle time and the median planning time with the torque limits
(as rmot plans) and without them (the same planner with `torque_limits` returning None: the
floor, measured in the same run), and their ratio. At 0 kg no limit binds and the two must be
equal up to the cost of the torque check (sampled RNEA every 2 ms of each chain).

Run:
    .venv/bin/python tests/benchmarks/bench_torque.py --n 10 40 --mass 0 8 --repeat 3
The machine the numbers below came from was shared (2 cores, ~8 jobs).
Measured there (load ~12, --n 10 40 --mass 0 8 --repeat 3): no limit binds on these programs
(cycle times equal); planning with the torque check took 1.07x (10 moves) and 1.09x (40
moves) the time without it at 0 kg, within the noise of the loaded machine at 8 kg.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plan"))

from plan_helpers import Prog, pose, program
from rmot.lang import ir
from rmot.compiler.plan import plan_program
from rmot.compiler.plan import torque as torque_mod

BOX = (350.0, -150.0, 200.0)  # mm, lower corner of a 120 x 300 x 100 mm box in front of the UR5e


def make(n: int, mass: float, seed: int = 1) -> ir.Program:
    rng = np.random.default_rng(seed)
    p = Prog(tool=ir.ToolRef("t", pose(z=100), mass))
    p.joint([0, -90, 90, -90, -90, 0])
    for k in range(n):
        x, y, z = np.array(BOX) + rng.random(3) * np.array([120.0, 300.0, 100.0])
        move = p.joint if k % 2 == 0 else p.linear
        move(pose(x, y, z, 180, 0, 180), zone=10.0 if k < n - 1 else 0.0, speed=1000.0, accel=20.0)
    return program(p.task(), robots={"r1": "ur5e"})


def timed(prog: ir.Program, repeat: int) -> tuple[float, float]:
    times, cycle = [], 0.0
    for _ in range(repeat):
        t = time.perf_counter()
        cycle = plan_program(prog).tasks[0].cycle_time
        times.append(time.perf_counter() - t)
    return cycle, statistics.median(times)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, nargs="+", default=[10, 40])
    ap.add_argument("--mass", type=float, nargs="+", default=[0.0, 8.0])
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    plan_program(make(2, 0.0))  # warm up (numba kernels, robot load)
    original = torque_mod.torque_limits
    print("n  mass_kg  cycle_s(limits)  cycle_s(none)  plan_s(limits)  plan_s(none)  ratio")
    for n in args.n:
        for mass in args.mass:
            prog = make(n, mass)
            cyc, t_lim = timed(prog, args.repeat)
            torque_mod.torque_limits = lambda *a, **k: None  # type: ignore[assignment]
            try:
                cyc0, t0 = timed(prog, args.repeat)
            finally:
                torque_mod.torque_limits = original  # type: ignore[assignment]
            cols = f"{n:<3}{mass:<9g}{cyc:<17.3f}{cyc0:<15.3f}{t_lim:<16.3f}{t0:<14.3f}"
            print(f"{cols}{t_lim / t0:.2f}")


if __name__ == "__main__":
    main()
