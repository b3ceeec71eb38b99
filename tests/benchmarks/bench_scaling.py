"""Linear cost, bounded memory: `rmot check --no-cache` of a program of N
moves, N = 10 ... 2000, each run a whole `rmot` process; per run the CPU time (user + system)
and the peak RSS of that one child (os.wait4), and the wall time.

    python tests/benchmarks/bench_scaling.py                       # the curve, zone fine + 10 mm
    python tests/benchmarks/bench_scaling.py --n 10 80 400 --rounds 5 --zones fine
    python tests/benchmarks/bench_scaling.py --stages 2000         # where time and memory go
    python tests/benchmarks/bench_scaling.py --base /tmp/base      # and another tree, same rounds
    pytest tests/benchmarks/bench_scaling.py                       # a tiny curve (N = 10, 20)

BASE: another rmot tree measured in the same rounds, run by the same interpreter with this
tree's editable install taken off the import path (as in bench_startup.py), e.g. before a change:
    mkdir -p /tmp/base/rmot /tmp/old && git archive HEAD~1 | tar -x -C /tmp/old
    for d in lang compiler backends sim; do ln -s /tmp/old/$d /tmp/base/rmot/$d; done

The program: an ABB IRB 120 (library arm) over a table, a gripper; `move joint home` to a joint
target, then N moves alternating `move joint` / `move linear` to seeded random poses of a
120 x 300 x 100 mm box in front of the arm, tool pointing down, 300 mm/s, one zone for the
whole program (`zone fine`, or `zone 10 mm`: blended). Every target is reachable and nothing
collides, so the check does the whole work (IK, timing, sampled collision and limit checks)
and exits 0; a run that exits otherwise is reported as such.

Targets: time(400) <= 5 x time(80) (CPU); peak RSS at N = 2000 below 1.5 GB. Also
the slope of the log-log fit of CPU time against N over N >= 80 (1.0 = linear; the fixed
start-up cost, ~1-2 s of imports and numba kernels, flattens it), the same of the CPU time and
peak above the smallest N's (the cost of the moves themselves), and the CPU per added move
between successive N (constant when the cost is linear).

`--stages N` runs the same pipeline in this process, stage by stage (front end, planner,
verification, report text): the wall time, the RSS after each stage and its peak RSS (Linux:
VmHWM, reset before each stage); with --trace also its peak of Python and numpy allocations
(tracemalloc, ~5x slower), with --profile cProfile's top 40 functions.
"""

from __future__ import annotations

import argparse
import os
import random
import statistics
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

RMOT = [sys.executable, "-c",
        "import sys; from rmot.compiler.cli import main; sys.argv[0] = 'rmot'; main()"]


def rmot_of(tree: str | None) -> list[str]:
    """The command that runs `rmot` from `tree` (None: the installed one)."""
    if tree is None:
        return RMOT
    return [sys.executable, "-c", "import sys; sys.meta_path[:] = [f for f in sys.meta_path "
            f"if 'editable' not in repr(f).lower()]; sys.path.insert(0, {tree!r}); "
            "from rmot.compiler.cli import main; sys.argv[0] = 'rmot'; main()"]
CELL = """cell scaling {
  robot r1 = abb_irb120
  fixture table = box(600mm, 800mm, 40mm) at pose(x=450mm, z=-20mm)
  tool gripper = cylinder(r=20mm, h=60mm) at pose(z=30mm) tcp pose(z=100mm) mass 0.3 kg on r1
}
"""
# the box the targets are drawn from (mm, robot base frame): the one tests/benchmarks/
# bench_timing.py uses for the IRB 120, well inside its reach with the tool pointing down
LOWER = (300.0, -150.0, 200.0)
SIZE = (120.0, 300.0, 100.0)
DEFAULT_N = (10, 20, 40, 80, 160, 400, 1000, 2000)


def program_text(n: int, zone: str = "fine", seed: int = 0) -> str:
    """A reachable program of `n` moves (plus the first, to a joint target) in `zone`."""
    rng = random.Random(seed)
    lines = ['use cell "cell.rmot"', "", "program scaling on r1 {", "  tool gripper",
             "  speed 300 mm/s", f"  zone {zone}", "  target home = joints(0, 10, 10, 0, 60, 0) deg",
             "  move joint home"]
    for k in range(n):
        x, y, z = (lo + rng.random() * size for lo, size in zip(LOWER, SIZE))
        kind = "joint" if k % 2 == 0 else "linear"
        lines.append(f"  move {kind} pose(x={x:.1f}mm, y={y:.1f}mm, z={z:.1f}mm, "
                     "rx=180deg, rz=180deg)")
    lines.append("}")
    return "\n".join(lines) + "\n"


def write_program(folder: str, n: int, zone: str) -> str:
    """The program (and its cell beside it) in `folder`; returns the program's path."""
    Path(folder, "cell.rmot").write_text(CELL, encoding="utf-8")
    path = os.path.join(folder, f"scaling_{n}_{zone.replace(' ', '')}.rmot")
    Path(path).write_text(program_text(n, zone), encoding="utf-8")
    return path


@dataclass(frozen=True)
class Run:
    cpu_s: float  # user + system of the child
    wall_s: float
    peak_mb: float  # the child's peak resident set (ru_maxrss)
    exit_code: int


def run_child(cmd: list[str], env: dict[str, str] | None = None) -> Run:
    """Run `cmd`; its own rusage (os.wait4 on its pid), not the max over all children."""
    t0 = time.perf_counter()
    proc = subprocess.Popen(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - t0
    proc.returncode = os.waitstatus_to_exitcode(status)  # reaped here: Popen must not wait again
    return Run(usage.ru_utime + usage.ru_stime, wall, usage.ru_maxrss / 1024, proc.returncode)


def measure(ns: list[int], zones: list[str], rounds: int, large: int = 400,
            large_rounds: int = 1, base: str | None = None) -> dict[tuple[str, int], Run]:
    """Median Run of `rmot check --no-cache` per (zone, N): `rounds` rounds for N < `large`,
    `large_rounds` from there on (the medians are per column: CPU, wall and peak apart). With
    `base`, that tree's runs too, interleaved, under the zone "base: <zone>"."""
    trees = [("", None)] + ([("base: ", base)] if base else [])
    out: dict[tuple[str, int], Run] = {}
    with tempfile.TemporaryDirectory() as tmp:
        env = dict(os.environ, RMOT_CACHE_DIR=os.path.join(tmp, "cache"))
        for _, tree in trees:  # warm: numba's kernel cache
            run_child([*rmot_of(tree), "check", write_program(tmp, 3, "fine")], env)
        for n in ns:
            for zone in zones:
                prog = write_program(tmp, n, zone)
                runs: dict[str, list[Run]] = {label: [] for label, _ in trees}
                for _ in range(rounds if n < large else large_rounds):
                    for label, tree in trees:
                        runs[label].append(run_child([*rmot_of(tree), "check", "--no-cache", prog], env))
                for label, got in runs.items():
                    out[(label + zone, n)] = Run(statistics.median(r.cpu_s for r in got),
                                                 statistics.median(r.wall_s for r in got),
                                                 statistics.median(r.peak_mb for r in got),
                                                 max(r.exit_code for r in got))
                    print(f"  {label}zone {zone:6s} N={n:5d}: {out[(label + zone, n)]}",
                          file=sys.stderr, flush=True)
    return out


def slope(points: list[tuple[int, float]]) -> float:
    """Least-squares slope of log(value) against log(N)."""
    import math

    xs = [math.log(n) for n, _ in points]
    ys = [math.log(v) for _, v in points]
    mx, my = statistics.fmean(xs), statistics.fmean(ys)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)


def table(results: dict[tuple[str, int], Run]) -> str:
    zones = list(dict.fromkeys(z for z, _ in results))
    ns = sorted({n for _, n in results})
    head = "     N" + "".join(f" | {'zone ' + z:>30s}" for z in zones)
    sub = "      " + "".join(f" | {'CPU s':>8s} {'wall s':>8s} {'peak MB':>8s} {'rc':>3s}"
                             for _ in zones)
    lines = [head, sub]
    for n in ns:
        row = f"{n:6d}"
        for z in zones:
            r = results.get((z, n))
            row += (f" | {r.cpu_s:8.2f} {r.wall_s:8.2f} {r.peak_mb:8.0f} {r.exit_code:3d}"
                    if r else f" | {'-':>30s}")
        lines.append(row)
    for z in zones:
        got = {n: r for (zz, n), r in results.items() if zz == z}
        facts = []
        if 80 in got and 400 in got:
            facts.append(f"CPU(400)/CPU(80) = {got[400].cpu_s / got[80].cpu_s:.2f} (target <= 5)")
        if max(got) >= 2000:
            facts.append(f"peak at N={max(got)}: {got[max(got)].peak_mb:.0f} MB (target < 1536)")
        tail = [(n, r.cpu_s) for n, r in got.items() if n >= 80]
        if len(tail) >= 2:
            facts.append(f"log-log slope of CPU over N >= 80: {slope(tail):.2f}")
        above = [(n, r.cpu_s - got[min(got)].cpu_s) for n, r in got.items()
                 if n >= 80 and r.cpu_s > got[min(got)].cpu_s]
        if len(above) >= 2:
            facts.append(f"of CPU above N={min(got)}: {slope(above):.2f}")
        steps = sorted(tail)
        if len(steps) >= 2:
            facts.append("CPU per added move (ms): " + ", ".join(
                f"{n0}->{n1} {1000 * (c1 - c0) / (n1 - n0):.1f}"
                for (n0, c0), (n1, c1) in zip(steps, steps[1:])))
        peak_tail = [(n, r.peak_mb - got[min(got)].peak_mb) for n, r in got.items()
                     if n >= 80 and r.peak_mb > got[min(got)].peak_mb]
        if len(peak_tail) >= 2:
            facts.append(f"of peak MB above N={min(got)}: {slope(peak_tail):.2f}")
        if facts:
            lines.append(f"zone {z}: " + "; ".join(facts))
    return "\n".join(lines)


def _status_mb(field: str) -> float:
    """VmRSS / VmHWM of this process (Linux /proc), MB."""
    with open("/proc/self/status", encoding="ascii") as f:
        for line in f:
            if line.startswith(field + ":"):
                return int(line.split()[1]) / 1024
    return float("nan")


def _reset_peak() -> None:
    """Start a new VmHWM (peak RSS) window: Linux's clear_refs value 5."""
    try:
        with open("/proc/self/clear_refs", "w", encoding="ascii") as f:
            f.write("5")
    except OSError:
        pass


def stages(n: int, zone: str = "fine", profile: bool = False, trace: bool = False) -> str:
    """The check's stages in this process: wall time, RSS after and peak RSS of each (and the
    peak of Python/numpy allocations with `trace`, which slows the planner ~5x)."""
    import cProfile
    import io
    import pstats
    import tracemalloc
    from collections.abc import Callable
    from typing import Any

    from rmot.compiler import frontend, plan_cache
    from rmot.compiler.cli.verify_cache import cached_verify
    from rmot.sim.report import Report, format_text

    pad = " " * (len(f"N={n} zone {zone}: "))
    lines = [f"N={n} zone {zone}: {'stage':14s} {'wall s':>8s} {'RSS after MB':>13s} "
             f"{'peak MB':>8s}" + (f" {'traced peak MB':>15s}" if trace else ""),
             f"{pad}{'(imports)':14s} {'':8s} {_status_mb('VmRSS'):13.0f}"]
    prof = cProfile.Profile() if profile else None

    def stage(name: str, fn: Callable[..., Any], *args: Any, **kwargs: Any) -> Any:
        _reset_peak()
        if trace:
            tracemalloc.start()
        t0 = time.perf_counter()
        if prof:
            prof.enable()
        value = fn(*args, **kwargs)
        if prof:
            prof.disable()
        wall = time.perf_counter() - t0
        line = f"{pad}{name:14s} {wall:8.2f} {_status_mb('VmRSS'):13.0f} {_status_mb('VmHWM'):8.0f}"
        if trace:
            line += f" {tracemalloc.get_traced_memory()[1] / 2**20:15.0f}"
            tracemalloc.stop()
        lines.append(line)
        return value

    with tempfile.TemporaryDirectory() as tmp:
        path = write_program(tmp, n, zone)
        front = stage("front end", frontend.load_program, path)
        planned = stage("planner", plan_cache.cached_plan, front.program, use_cache=False)
        report = stage("verification", cached_verify, planned, use_cache=False)
        full = Report(path, report.cycle_times, tuple(front.diagnostics) + report.diagnostics,
                      report.tasks)
        stage("report text", format_text, [full])
    if prof:
        buf = io.StringIO()
        pstats.Stats(prof, stream=buf).sort_stats("cumulative").print_stats(40)
        lines.append(buf.getvalue())
    return "\n".join(lines)


def test_scaling_small() -> None:
    """The tiny curve: every run is a clean check (exit 0), CPU and peak are measured."""
    results = measure([10, 20], ["fine", "10 mm"], rounds=1)
    print("\n" + table(results))
    assert all(r.exit_code == 0 and r.cpu_s > 0 and r.peak_mb > 0 for r in results.values())


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--n", nargs="+", type=int, default=list(DEFAULT_N))
    ap.add_argument("--zones", nargs="+", default=["fine", "10mm"],
                    help="zones as written after `zone` (fine, 10mm, ...)")
    ap.add_argument("--rounds", type=int, default=3, help="rounds per N below --large")
    ap.add_argument("--large", type=int, default=400, help="from this N on, --large-rounds")
    ap.add_argument("--large-rounds", type=int, default=1)
    ap.add_argument("--base", default=None, help="another rmot tree to measure in the same rounds")
    ap.add_argument("--stages", type=int, default=None, metavar="N",
                    help="only the per-stage split of one program of N moves, in this process")
    ap.add_argument("--profile", action="store_true", help="with --stages: cProfile's top 40")
    ap.add_argument("--trace", action="store_true",
                    help="with --stages: tracemalloc's peak per stage (slow)")
    args = ap.parse_args(argv)
    if args.stages is not None:
        print(stages(args.stages, args.zones[0], args.profile, args.trace))
        return
    results = measure(args.n, args.zones, args.rounds, args.large, args.large_rounds, args.base)
    print(table(results))
    print(f"(machine load average at the end: {os.getloadavg()[0]:.1f} on {os.cpu_count()} CPUs)")


if __name__ == "__main__":
    main()
