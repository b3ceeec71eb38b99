"""Start-up and the plan cache: wall times of whole `rmot` processes, medians, next to the floor
(`python -c "import numpy, pinocchio"`) run in the same benchmark, interleaved round by round so
that machine load hits every command alike.

    python tests/benchmarks/bench_startup.py [ROUNDS]    # a table of medians (s) and floor ratios
    pytest tests/benchmarks/bench_startup.py             # the same, as a pytest run

Targets (issue 18): `rmot check` of a 3-move program <= floor + 0.6 s; `rmot robots ik` <=
floor + 0.3 s; `rmot compile` right after `rmot check` of the same program >= 3x faster than
`rmot compile --no-cache`.
"""

from __future__ import annotations

import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PYTHON = sys.executable
THREE = """program three on r1 {
  tool gripper
  speed 400 mm/s
  target home = joints(0, -10, 10, 0, 90, 0) deg
  target a = pose(x=-100mm, y=0mm, z=100mm, rx=180deg)
  move joint home
  frame table_top
  move linear a
  move joint home zone fine
}
"""
RMOT = [PYTHON, "-c", "import sys; from rmot.compiler.cli import main; sys.argv[0] = 'rmot'; main()"]


def wall(cmd: list[str], env: dict[str, str]) -> tuple[float, float]:
    """(wall s, CPU s = user + system of the child): on a loaded machine CPU time is the steadier."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False)
    elapsed = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return elapsed, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def measure(rounds: int = 5, pythonpath: str | None = None) -> dict[str, tuple[float, float]]:
    """Median (wall, CPU) seconds of each command over `rounds` interleaved rounds; `pythonpath`
    runs another rmot tree (e.g. an older commit's) through the same interpreter."""
    with tempfile.TemporaryDirectory() as tmp:
        prog = os.path.join(tmp, "three.rmot")
        Path(prog).write_text(THREE, encoding="utf-8")
        env = dict(os.environ, RMOT_CACHE_DIR=os.path.join(tmp, "cache"))
        if pythonpath:
            env["PYTHONPATH"] = pythonpath
        out = os.path.join(tmp, "out")
        commands = {
            "floor: import numpy, pinocchio": [PYTHON, "-c", "import numpy, pinocchio"],
            "rmot --help": RMOT + ["--help"],
            "rmot robots ik abb_irb120": RMOT + ["robots", "ik", "abb_irb120", "300", "0", "400", "180", "0", "0"],
            "rmot check 3 moves --no-cache": RMOT + ["check", "--no-cache", prog],
            "rmot check 3 moves (cached plan)": RMOT + ["check", prog],
            "rmot compile 3 moves --no-cache": RMOT + ["compile", "--no-cache", prog, "--target", "rapid", "-o", out],
            "rmot compile 3 moves (cached plan)": RMOT + ["compile", prog, "--target", "rapid", "-o", out],
        }
        if pythonpath:  # an older tree has no --no-cache: it always plans
            commands = {name: [a for a in cmd if a != "--no-cache"] for name, cmd in commands.items()}
        wall(RMOT + ["check", prog], env)  # warm: numba's kernel cache, the plan cache entry
        times: dict[str, list[tuple[float, float]]] = {name: [] for name in commands}
        for _ in range(rounds):
            for name, cmd in commands.items():
                times[name].append(wall(cmd, env))
    return {name: (statistics.median(t[0] for t in ts), statistics.median(t[1] for t in ts))
            for name, ts in times.items()}


def table(medians: dict[str, tuple[float, float]]) -> str:
    floor_wall, floor_cpu = medians["floor: import numpy, pinocchio"]
    lines = [f"{'command':40s} {'wall s':>8s} {'- floor':>8s} {'CPU s':>8s} {'- floor':>8s}"]
    for name, (w, c) in medians.items():
        lines.append(f"{name:40s} {w:8.3f} {w - floor_wall:8.3f} {c:8.3f} {c - floor_cpu:8.3f}")
    nc, ca = medians["rmot compile 3 moves --no-cache"], medians["rmot compile 3 moves (cached plan)"]
    lines.append(f"compile speed-up from the cached plan: {nc[0] / ca[0]:.2f}x wall, {nc[1] / ca[1]:.2f}x CPU")
    return "\n".join(lines)


def test_startup_medians() -> None:
    medians = measure(3)
    print("\n" + table(medians))
    assert all(w > 0 and c > 0 for w, c in medians.values())


if __name__ == "__main__":
    rounds = int(sys.argv[1]) if len(sys.argv) > 1 else 5
    print(table(measure(rounds, sys.argv[2] if len(sys.argv) > 2 else None)))
