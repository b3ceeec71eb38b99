"""Start-up and the plan cache: wall times of whole `rmot` processes, medians, next to the floor
(`python -c "import numpy, pinocchio"`) run in the same benchmark, interleaved round by round so
that machine load hits every command alike.

    python tests/benchmarks/bench_startup.py [ROUNDS] [BASE]   # medians (s), minus the floor
    pytest tests/benchmarks/bench_startup.py                   # the same, as a pytest run

BASE (optional): another rmot tree to measure in the same rounds, e.g. main before a change:
    mkdir -p /tmp/base/rmot /tmp/main && git archive main | tar -x -C /tmp/main
    for d in lang compiler backends sim; do ln -s /tmp/main/$d /tmp/base/rmot/$d; done
    python tests/benchmarks/bench_startup.py 5 /tmp/base
It runs through the same interpreter and site-packages, with this tree's editable install
taken off the import path; each tree has its own cache folder.

Targets: `rmot check` of a 3-move program <= floor + 0.6 s; `rmot robots ik` <=
floor + 0.3 s; `rmot compile` right after `rmot check` of the same program >= 3x faster than
`rmot compile --no-cache`. Both wall and CPU time are shown: on a loaded machine the CPU
time (user + system of the child) is the steadier.
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


def rmot_of(tree: str | None) -> list[str]:
    """The command that runs `rmot` from `tree` (None: the installed one)."""
    if tree is None:
        return RMOT
    return [PYTHON, "-c", "import sys; sys.meta_path[:] = [f for f in sys.meta_path "
            f"if 'editable' not in repr(f).lower()]; sys.path.insert(0, {tree!r}); "
            "from rmot.compiler.cli import main; sys.argv[0] = 'rmot'; main()"]


def wall(cmd: list[str], env: dict[str, str]) -> tuple[float, float]:
    """(wall s, CPU s = user + system of the child): on a loaded machine CPU time is the steadier."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False)
    elapsed = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return elapsed, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def measure(rounds: int = 5, base: str | None = None) -> dict[str, tuple[float, float]]:
    """Median (wall, CPU) seconds of each command over `rounds` interleaved rounds; with `base`,
    that tree's commands too (named "base: ...") in the same rounds."""
    with tempfile.TemporaryDirectory() as tmp:
        prog = os.path.join(tmp, "three.rmot")
        Path(prog).write_text(THREE, encoding="utf-8")
        out = os.path.join(tmp, "out")
        commands: dict[str, tuple[list[str], dict[str, str]]] = {
            "floor: import numpy, pinocchio": ([PYTHON, "-c", "import numpy, pinocchio"],
                                               dict(os.environ)),
        }
        for label, tree in [("", None)] + ([("base: ", base)] if base else []):
            env = dict(os.environ, RMOT_CACHE_DIR=os.path.join(tmp, f"cache{len(label)}"))
            rmot = rmot_of(tree)
            for name, args in _COMMANDS.items():
                argv = [prog if a == "PROG" else out if a == "OUT" else a for a in args]
                commands[label + name] = ([*rmot, *argv], env)
            # warm: numba's kernel cache, the plan cache entry
            subprocess.run([*rmot, "check", prog], env=env, capture_output=True, check=False)
        times: dict[str, list[tuple[float, float]]] = {name: [] for name in commands}
        for _ in range(rounds):
            for name, (cmd, env) in commands.items():
                times[name].append(wall(cmd, env))
    return {name: (statistics.median(t[0] for t in ts), statistics.median(t[1] for t in ts))
            for name, ts in times.items()}


_COMMANDS = {
    "rmot --help": ["--help"],
    "rmot robots ik abb_irb120": ["robots", "ik", "abb_irb120", "300", "0", "400", "180", "0", "0"],
    "rmot check 3 moves --no-cache": ["check", "--no-cache", "PROG"],
    "rmot check 3 moves (cached plan)": ["check", "PROG"],
    "rmot compile 3 moves --no-cache": ["compile", "--no-cache", "PROG", "--target", "rapid",
                                        "-o", "OUT"],
    "rmot compile 3 moves (cached plan)": ["compile", "PROG", "--target", "rapid", "-o", "OUT"],
}


def table(medians: dict[str, tuple[float, float]]) -> str:
    floor_wall, floor_cpu = medians["floor: import numpy, pinocchio"]
    lines = [f"{'command':48s} {'wall s':>8s} {'- floor':>8s} {'CPU s':>8s} {'- floor':>8s}"]
    for name, (w, c) in medians.items():
        lines.append(f"{name:48s} {w:8.3f} {w - floor_wall:8.3f} {c:8.3f} {c - floor_cpu:8.3f}")
    for label in ("", "base: "):
        if label + "rmot --help" not in medians:
            continue
        nc = medians[label + "rmot compile 3 moves --no-cache"]
        ca = medians[label + "rmot compile 3 moves (cached plan)"]
        ck = medians[label + "rmot check 3 moves (cached plan)"]
        first = medians[label + "rmot check 3 moves --no-cache"]
        ik = medians[label + "rmot robots ik abb_irb120"]
        lines.append(f"{label or 'this tree: '}check --no-cache - floor {first[0] - floor_wall:.2f} s wall, "
                     f"{first[1] - floor_cpu:.2f} s CPU (target <= 0.6); "
                     f"check (cached) - floor {ck[0] - floor_wall:.2f} s wall, "
                     f"{ck[1] - floor_cpu:.2f} s CPU (target <= 0.6); robots ik - floor "
                     f"{ik[0] - floor_wall:.2f} s wall, {ik[1] - floor_cpu:.2f} s CPU (target <= 0.3); "
                     f"compile speed-up from the cached plan {nc[0] / ca[0]:.2f}x wall, "
                     f"{nc[1] / ca[1]:.2f}x CPU (target >= 3)")
    return "\n".join(lines)


def test_startup_medians() -> None:
    medians = measure(3)
    print("\n" + table(medians))
    assert all(w > 0 and c > 0 for w, c in medians.values())


if __name__ == "__main__":
    rounds = int(sys.argv[1]) if len(sys.argv) > 1 else 5
    print(table(measure(rounds, sys.argv[2] if len(sys.argv) > 2 else None)))
    print(f"(machine load average at the end: {os.getloadavg()[0]:.1f} on {os.cpu_count()} CPUs)")
