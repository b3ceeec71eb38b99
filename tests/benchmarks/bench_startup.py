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


def wall(cmd: list[str], env: dict[str, str]) -> float:
    t0 = time.perf_counter()
    subprocess.run(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False)
    return time.perf_counter() - t0


def measure(rounds: int = 5) -> dict[str, float]:
    """Median wall time (s) of each command over `rounds` interleaved rounds."""
    with tempfile.TemporaryDirectory() as tmp:
        prog = os.path.join(tmp, "three.rmot")
        Path(prog).write_text(THREE, encoding="utf-8")
        env = dict(os.environ, RMOT_CACHE_DIR=os.path.join(tmp, "cache"))
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
        wall(RMOT + ["check", prog], env)  # warm: numba's kernel cache, the plan cache entry
        times: dict[str, list[float]] = {name: [] for name in commands}
        for _ in range(rounds):
            for name, cmd in commands.items():
                times[name].append(wall(cmd, env))
    return {name: statistics.median(ts) for name, ts in times.items()}


def table(medians: dict[str, float]) -> str:
    floor = medians["floor: import numpy, pinocchio"]
    lines = [f"{'command':40s} {'median s':>9s} {'- floor':>8s}"]
    for name, t in medians.items():
        lines.append(f"{name:40s} {t:9.3f} {t - floor:8.3f}")
    ratio = medians["rmot compile 3 moves --no-cache"] / medians["rmot compile 3 moves (cached plan)"]
    lines.append(f"compile speed-up from the cached plan: {ratio:.2f}x")
    return "\n".join(lines)


def test_startup_medians() -> None:
    medians = measure(3)
    print("\n" + table(medians))
    assert all(t > 0 for t in medians.values())


if __name__ == "__main__":
    print(table(measure(int(sys.argv[1]) if len(sys.argv) > 1 else 5)))
