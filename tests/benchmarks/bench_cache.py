"""One plan (and one verification) per program: `rmot compile` right after `rmot check` of the
same program against `rmot compile --no-cache`, whole processes, medians of interleaved rounds.

    python tests/benchmarks/bench_cache.py [ROUNDS] [BASE]     # medians (s) and the ratios
    pytest tests/benchmarks/bench_cache.py                     # the same, as a pytest run

Programs: a 3-move program (bench_startup.THREE), examples/pick_place.rmot and
examples/palletizing.rmot (96 moves).
BASE (optional): another rmot tree measured in the same rounds (see bench_startup.py for how
to lay one out), e.g. the commit before the verification cache, for a before/after in one run.
Each tree has its own cache folder, filled by one `rmot check` of each program before the
rounds. Target: the cached compile at least 3x faster than --no-cache. Wall and
CPU time (user + system of the child) are both shown: on a loaded machine CPU is the steadier.
"""

from __future__ import annotations

import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_startup import THREE, rmot_of, wall  # a sibling script, not a package

ROOT = Path(__file__).resolve().parents[2]


def measure(rounds: int = 5, base: str | None = None) -> dict[str, tuple[float, float]]:
    """Median (wall, CPU) seconds of every (tree, program, cached|--no-cache) compile."""
    with tempfile.TemporaryDirectory() as tmp:
        three = os.path.join(tmp, "three.rmot")
        Path(three).write_text(THREE, encoding="utf-8")
        past = time.time() - 60  # saved before the run: files modified within 2 s get no
        os.utime(three, (past, past))  # front-end cache entry (compiler/cli/load_cache.py)
        programs = {"3 moves": three, "pick_place": str(ROOT / "examples" / "pick_place.rmot"),
                    "palletizing": str(ROOT / "examples" / "palletizing.rmot")}
        commands: dict[str, tuple[list[str], dict[str, str]]] = {}
        for label, tree in [("", None)] + ([("base: ", base)] if base else []):
            env = dict(os.environ, RMOT_CACHE_DIR=os.path.join(tmp, f"cache{len(label)}"))
            rmot = rmot_of(tree)
            for name, prog in programs.items():
                subprocess.run([*rmot, "check", prog], env=env, capture_output=True, check=False)
                out = os.path.join(tmp, f"out{len(label)}")
                compile_ = [*rmot, "compile", prog, "--target", "rapid", "-o", out]
                commands[f"{label}{name}: compile after check"] = (compile_, env)
                commands[f"{label}{name}: compile --no-cache"] = ([*compile_, "--no-cache"], env)
        times: dict[str, list[tuple[float, float]]] = {name: [] for name in commands}
        for _ in range(rounds):
            for name, (cmd, env) in commands.items():
                times[name].append(wall(cmd, env))
    return {name: (statistics.median(t[0] for t in ts), statistics.median(t[1] for t in ts))
            for name, ts in times.items()}


def table(medians: dict[str, tuple[float, float]]) -> str:
    lines = [f"{'command':48s} {'wall s':>8s} {'CPU s':>8s}"]
    lines += [f"{name:48s} {w:8.3f} {c:8.3f}" for name, (w, c) in medians.items()]
    for name in medians:
        if name.endswith(": compile after check"):
            stem = name[: -len(": compile after check")]
            warm, cold = medians[name], medians[f"{stem}: compile --no-cache"]
            lines.append(f"{stem}: --no-cache / after check = {cold[0] / warm[0]:.2f}x wall, "
                         f"{cold[1] / warm[1]:.2f}x CPU (target >= 3)")
    return "\n".join(lines)


def test_cache_medians() -> None:
    medians = measure(3)
    print("\n" + table(medians))
    assert all(w > 0 and c > 0 for w, c in medians.values())


if __name__ == "__main__":
    rounds = int(sys.argv[1]) if len(sys.argv) > 1 else 5
    print(table(measure(rounds, sys.argv[2] if len(sys.argv) > 2 else None)))
    print(f"(machine load average at the end: {os.getloadavg()[0]:.1f} on {os.cpu_count()} CPUs; "
          f"PYTHONDONTWRITEBYTECODE={os.environ.get('PYTHONDONTWRITEBYTECODE', '')!r}: when set, "
          "every process compiles rmot's modules from source, the same cost on both sides)")
