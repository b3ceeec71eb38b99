"""Timing benchmark: random pick-and-place programs, cycle time and planning cost.

Programs: alternating `move joint pose(..)` / `move linear pose(..)` to random points of a
120 x 300 x 100 mm box in front of the robot, tool pointing down, 300 mm/s, one zone for the
whole program (fine / 2 mm / 10 mm), N moves. For each (arm, zone, N): the planned cycle time,
the planning time and the diagnostics' error codes (E228 = timing failed). With --verify the
plan is verified too (sim.verify), with --memory the peak RSS is reported.

With --reference (programs then use accel 50 m/s^2, see REFERENCE_ACCEL), also the ratio of
rmot's cycle time to an independent time-optimal timing of the same path (toppra on a dense uniform
grid, tests/plan/test_plan_optimal.reference_time).
With --memory every configuration runs in its own process (peak RSS of that process alone).

Run:
    .venv/bin/python tests/benchmarks/bench_timing.py --arms abb_irb120 ur5e --n 10 50 100 200
    .venv/bin/python tests/benchmarks/bench_timing.py --arms abb_irb120 --zones 10 --n 10 100 1000 --verify --memory
    .venv/bin/python tests/benchmarks/bench_timing.py --arms abb_irb120 ur5e --zones 0 10 --n 10 100 --reference
The machine the measured numbers came from was shared (2 cores, ~8 jobs).
"""

from __future__ import annotations

import argparse
import json
import resource
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plan"))

from plan_helpers import Prog, pose, program

from rmot.lang import ir

DOWN = dict(rx=180, ry=0, rz=180)
BOX = {  # (x, y, z) lower corner, mm: a 120 x 300 x 100 mm box in front of each arm
    "abb_irb120": (300.0, -150.0, 200.0),
    "ur5e": (350.0, -150.0, 200.0),
    "kuka_kr6_r900": (450.0, -150.0, 300.0),
}
SIZE = (120.0, 300.0, 100.0)
# with --reference the TCP acceleration limit is set out of reach (the reference, toppra with
# joint and TCP-speed limits, has none): both time the same path under the same limits
REFERENCE_ACCEL = 50.0  # m/s^2


def random_program(arm: str, n: int, zone_mm: float, seed: int = 0, speed: float = 300.0,
                   accel: float = 2.0) -> ir.Program:
    """N moves alternating joint / linear to random poses of the box (first move: joints)."""
    rng = np.random.default_rng(seed)
    lo = np.array(BOX.get(arm, (350.0, -150.0, 250.0)))
    p = Prog()
    p.joint([0, 10, 10, 0, 60, 0] if arm != "ur5e" else [0, -90, 90, -90, -90, 0])
    for k in range(n):
        x, y, z = lo + rng.random(3) * np.array(SIZE)
        target = pose(x, y, z, **DOWN)
        if k % 2 == 0:
            p.joint(target, zone=zone_mm, speed=speed, accel=accel)
        else:
            p.linear(target, zone=zone_mm, speed=speed, accel=accel)
    return program(p.task(), robots={"r1": arm})


def reference(arm: str, n: int, zone_mm: float, seed: int) -> float:
    """The independent optimum of the program's path (sum over its chains)."""
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plan"))
    from test_plan_optimal import _segments, reference_time

    from rmot.sim.robots import load_robot

    robot = load_robot(arm)
    segs = _segments(robot, random_program(arm, n, zone_mm, seed, accel=REFERENCE_ACCEL))
    chains = [segs] if zone_mm > 0 else [[s] for s in segs]
    return sum(reference_time(robot, c) for c in chains)


def run(arm: str, n: int, zone_mm: float, seed: int, verify: bool, accel: float = 2.0) -> dict:
    from rmot.compiler.plan import plan_program

    prog = random_program(arm, n, zone_mm, seed, accel=accel)
    t0 = time.perf_counter()
    plan = plan_program(prog)
    t_plan = time.perf_counter() - t0
    t_verify = 0.0
    if verify:
        from rmot.sim import verify as sim_verify

        t1 = time.perf_counter()
        sim_verify(plan)
        t_verify = time.perf_counter() - t1
    errors = sorted({d.code.id for d in plan.diagnostics if d.severity.name == "ERROR"})
    # the exact end of the last move (the sampled trajectory ends at the next 4 ms step)
    cycle = max(r.t_end for t in plan.tasks for r in t.records) if plan.tasks else float("nan")
    return dict(arm=arm, n=n, zone=zone_mm, seed=seed, cycle=cycle, plan_s=t_plan, verify_s=t_verify,
                errors=errors, rss_mb=resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024)


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--arms", nargs="+", default=["abb_irb120", "ur5e"])
    ap.add_argument("--zones", nargs="+", type=float, default=[0.0, 2.0, 10.0])
    ap.add_argument("--n", nargs="+", type=int, default=[10, 50, 100, 200])
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--verify", action="store_true")
    ap.add_argument("--memory", action="store_true")
    ap.add_argument("--reference", action="store_true")
    ap.add_argument("--single", action="store_true", help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.single:  # one configuration, as JSON (the --memory mode's worker)
        print(json.dumps(run(args.arms[0], args.n[0], args.zones[0], args.seed, args.verify)))
        return
    print("arm         zone   N     cycle_s   plan_s  verify_s  peak_MB  ref_ratio  errors", flush=True)
    for arm in args.arms:
        for n in args.n:
            for zone in args.zones:
                if args.memory:
                    cmd = [sys.executable, __file__, "--single", "--arms", arm, "--n", str(n), "--zones", str(zone),
                           "--seed", str(args.seed)] + (["--verify"] if args.verify else [])
                    r = json.loads(subprocess.run(cmd, capture_output=True, text=True, check=True).stdout)
                else:
                    r = run(arm, n, zone, args.seed, args.verify, REFERENCE_ACCEL if args.reference else 2.0)
                mem = f"{r['rss_mb']:8.0f}" if args.memory else "       -"
                ratio = f"{r['cycle'] / reference(arm, n, zone, args.seed):9.4f}" if args.reference else "        -"
                print(f"{arm:11s} {zone:4.0f}  {n:4d}  {r['cycle']:8.3f}  {r['plan_s']:7.2f}  {r['verify_s']:8.2f} {mem}  "
                      f"{ratio}  {','.join(r['errors']) or '-'}", flush=True)


if __name__ == "__main__":
    main()
