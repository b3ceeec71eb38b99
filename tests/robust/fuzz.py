"""`make fuzz`: N generated projects (tests/robust/gen.py, by seed) through the whole pipeline
(front end, planner, verifier, every backend, the compile writer), each in a worker process
under a 2 GB address-space cap (resource.setrlimit) with a 30 s limit per input. The limit is
on the worker's CPU time for the input (read from /proc), so a loaded machine (the test suite
running beside the fuzzer) cannot turn a slow input into a false hang; a worker that answers
nothing for four times the limit in wall time is a hang too (blocked, not computing).

    .venv/bin/python -m tests.robust.fuzz [--n 100000] [--start 0] [--jobs 1] [--timeout 30]
                                         [--memory-gb 2] [--report fuzz-report.json]

With FUZZ_MIX=1 (`make fuzz FUZZ_MIX=1`), the seeds mix the strategies that found what the
generator's well-formed programs did not: seed % 4 == 0 a generated project, 1 an example
program mutated by `mutated_example(seed)`, 2 and 3 a hostile file (a damaged mesh or URDF, a
damaged cache entry, an attacked report for merge-reports: tests/robust/hostile.py, where a
cache verdict that differs from --no-cache's is a failure too).

Counted per input: ok (diagnostics or files, exit 0/1/2), traceback (an exception escaped a
stage), hang (more CPU than the timeout, or no answer for 4x it: the worker is killed and replaced), memory
(MemoryError under the cap) and crash (the worker died: a signal such as SIGSEGV). Every
failure is listed with its seed: `random_project(seed)` rebuilds the input.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import select
import signal
import shutil
import subprocess
import sys
import tempfile
import time
import traceback
from rmot.backends import targets
from collections import Counter

TARGETS = targets()
_TICKS = os.sysconf("SC_CLK_TCK")
_WALL_FACTOR = 4  # no answer for this many timeouts of wall time: blocked, a hang
_SLOWEST = 20  # the slowest inputs (CPU seconds) listed in the report


_EXTREMES = ("nan", "1e308", "-1e308", "0", "-0", "999999999999", "1e-320", "-5", "inf")


def mutated_example(seed: int) -> dict[str, str]:
    """An example program (examples/*.rmot, with a cell file of its own folder) mutated by seed:
    lines deleted, duplicated or swapped, numbers replaced by extremes (nan, 1e308, 0, negative),
    a brace removed. The strategy that found what the generator's well-formed programs did not."""
    import random
    import re

    rng = random.Random(seed)
    folder = os.path.join(os.path.dirname(__file__), "..", "..", "examples")
    names = sorted(n for n in os.listdir(folder) if n.endswith(".rmot"))
    lines = open(os.path.join(folder, rng.choice(names)), encoding="utf-8").read().splitlines()
    for _ in range(rng.randint(1, 4)):
        i = rng.randrange(len(lines))
        kind = rng.randrange(5)
        if kind == 0:
            del lines[i]
        elif kind == 1:
            lines.insert(i, lines[i])
        elif kind == 2:
            j = rng.randrange(len(lines))
            lines[i], lines[j] = lines[j], lines[i]
        elif kind == 3:
            lines[i] = re.sub(r"\d+(\.\d+)?", lambda _: rng.choice(_EXTREMES), lines[i], count=1)
        else:
            lines[i] = lines[i].replace("}", "", 1)
        if not lines:
            lines = ["program p on r1 {", "}"]
    return {"main.rmot": "\n".join(lines) + "\n"}


def run_one(seed: int, workdir: str) -> str:
    """One input through the pipeline; 'ok' or 'traceback: ...'."""
    from rmot.compiler.cli.compile_cmd import compile_program, write_all
    from rmot.lang.diagnostics import render
    from tests.robust.gen import random_project

    proj = os.path.join(workdir, f"p{seed}")
    os.makedirs(proj)
    try:
        if os.environ.get("FUZZ_MIX") and seed % 4 >= 2:
            from tests.robust.hostile import run_hostile

            try:
                return run_hostile(seed, proj, os.path.join(workdir, "caches"))
            except MemoryError:
                return "memory"
        project = mutated_example(seed) if os.environ.get("FUZZ_MIX") and seed % 4 == 1 else random_project(seed)
        for name, text in project.items():
            with open(os.path.join(proj, name), "w", encoding="utf-8", newline="") as f:
                f.write(text)
        try:
            outcome = compile_program(os.path.join(proj, "main.rmot"), TARGETS, allow_findings=seed % 2 == 0)
            for d in outcome.diagnostics:
                render(d)
            if outcome.files:
                write_all(os.path.join(proj, "out"), outcome.files)
        except MemoryError:
            return "memory"
        except Exception as exc:  # the finding this tool exists for
            tb = traceback.extract_tb(exc.__traceback__)[-1]
            return f"traceback: {exc.__class__.__name__}: {str(exc)[:200]} at {os.path.basename(tb.filename)}:{tb.lineno}"
        return f"ok exit={outcome.exit_code} files={len(outcome.files)}"
    finally:
        shutil.rmtree(proj, ignore_errors=True)


def _warm_up() -> None:
    """Imports and numba's compilation (or loading of its cache) before the first timed input:
    a worker's first program past a kernel's threshold (lang/jit.py; the IK pass after 200
    poses) would otherwise count a one-time compile of 10-30 s against that input."""
    from rmot.compiler.cli.compile_cmd import compile_program

    example = os.path.join(os.path.dirname(__file__), "..", "..", "examples", "palletizing.rmot")
    compile_program(example, ("rapid",), allow_findings=True, use_cache=False)


def worker(memory_gb: float) -> None:
    cap = int(memory_gb * (1 << 30))
    resource.setrlimit(resource.RLIMIT_AS, (cap, cap))
    workdir = tempfile.mkdtemp(prefix="rmot-fuzz-")
    _warm_up()
    sys.stdout.write("ready\n")
    sys.stdout.flush()
    for line in sys.stdin:
        seed = int(line)
        started = time.process_time()
        result = run_one(seed, workdir)
        sys.stdout.write(json.dumps([seed, result, round(time.process_time() - started, 3)]) + "\n")
        sys.stdout.flush()


class Worker:
    def __init__(self, memory_gb: float) -> None:
        self.proc = subprocess.Popen([sys.executable, "-m", "tests.robust.fuzz", "--worker", "--memory-gb", str(memory_gb)],
                                     stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True, bufsize=1)
        assert self.proc.stdout is not None
        self.proc.stdout.readline()  # "ready" (imports are not part of any input's time)
        self.seed: int | None = None
        self.started = self.cpu_started = 0.0

    def cpu_seconds(self) -> float:
        """The worker's user + system CPU time so far (/proc/PID/stat fields 14 and 15)."""
        try:
            with open(f"/proc/{self.proc.pid}/stat", encoding="ascii") as f:
                fields = f.read().rsplit(")", 1)[1].split()
        except OSError:
            return 0.0
        return (int(fields[11]) + int(fields[12])) / _TICKS

    def send(self, seed: int) -> None:
        assert self.proc.stdin is not None
        self.seed, self.started, self.cpu_started = seed, time.monotonic(), self.cpu_seconds()
        self.proc.stdin.write(f"{seed}\n")
        self.proc.stdin.flush()

    def kill(self) -> None:
        self.proc.kill()
        self.proc.wait()


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=int(os.environ.get("FUZZ_N", 100_000)))
    ap.add_argument("--start", type=int, default=int(os.environ.get("FUZZ_START", 0)))
    ap.add_argument("--jobs", type=int, default=int(os.environ.get("FUZZ_JOBS", 1)))
    ap.add_argument("--timeout", type=float, default=30.0)
    ap.add_argument("--memory-gb", type=float, default=2.0)
    ap.add_argument("--report", default=os.environ.get("FUZZ_REPORT", "fuzz-report.json"))
    ap.add_argument("--worker", action="store_true")
    args = ap.parse_args()
    if args.worker:
        worker(args.memory_gb)
        return
    seeds = iter(range(args.start, args.start + args.n))
    counts: Counter[str] = Counter()
    exits: Counter[str] = Counter()  # among ok inputs: how far they got (exit 0 / 1 / 2)
    written = [0]  # inputs for which vendor files were written
    failures: list[tuple[int, str]] = []
    slowest: list[tuple[float, int]] = []
    workers = [Worker(args.memory_gb) for _ in range(args.jobs)]
    t0, done = time.monotonic(), 0

    def feed(w: Worker) -> None:
        seed = next(seeds, None)
        if seed is None:
            w.seed = None
        else:
            w.send(seed)

    def record(seed: int, result: str, cpu: float | None = None) -> None:
        nonlocal done
        if cpu is not None:
            slowest.append((cpu, seed))
            slowest.sort(reverse=True)
            del slowest[_SLOWEST:]
        kind = result.split(":", 1)[0].split(" ", 1)[0]
        counts[kind] += 1
        if kind == "ok":
            exits[result.split(" ")[1]] += 1
            written[0] += "files=0" not in result
        done += 1
        if kind != "ok":
            failures.append((seed, result))
            print(f"seed {seed}: {result}", flush=True)
        if done % 1000 == 0:
            print(f"{done} inputs, {time.monotonic() - t0:.0f} s: {dict(counts)}", flush=True)

    def stop(signum: int, frame: object) -> None:
        raise KeyboardInterrupt

    signal.signal(signal.SIGTERM, stop)  # stopped early: the counts so far are still written
    interrupted = False
    try:
        for w in workers:
            feed(w)
        _loop(workers, feed, record, args)
    except KeyboardInterrupt:
        interrupted = True
    for w in workers:
        w.kill()
    summary = {"inputs": done, "seconds": round(time.monotonic() - t0, 1), "start": args.start, "interrupted": interrupted,
               "ok": counts["ok"], "traceback": counts["traceback"], "hang": counts["hang"],
               "memory": counts["memory"], "crash": counts["crash"], "ok_exit_codes": dict(exits),
               "inputs_with_files_written": written[0], "hang_limit": f"{args.timeout:g} s CPU or "
               f"{_WALL_FACTOR * args.timeout:g} s without an answer",
               "slowest_cpu_seconds": [[seed, cpu] for cpu, seed in slowest], "failures": failures}
    with open(args.report, "w", encoding="utf-8") as f:
        json.dump(summary, f, indent=1)
    print(json.dumps({k: v for k, v in summary.items() if k not in ("failures", "slowest_cpu_seconds")}))
    sys.exit(1 if failures else 0)


def _loop(workers: list[Worker], feed, record, args) -> None:  # type: ignore[no-untyped-def]
    while any(w.seed is not None for w in workers):
        busy = [w for w in workers if w.seed is not None]
        ready, _, _ = select.select([w.proc.stdout for w in busy], [], [], 0.5)
        for w in busy:
            if w.proc.stdout in ready:
                line = w.proc.stdout.readline()  # type: ignore[union-attr]
                if line:
                    seed, result, cpu = json.loads(line)
                    record(seed, result, cpu)
                    feed(w)
                    continue
                code = w.proc.wait()  # died: a crash (signal) or an out-of-memory kill
                record(w.seed, f"crash: worker exited with {code}" if code != -9 else "memory: killed")  # type: ignore[arg-type]
                workers[workers.index(w)] = nw = Worker(args.memory_gb)
                feed(nw)
            elif (w.cpu_seconds() - w.cpu_started > args.timeout
                  or time.monotonic() - w.started > _WALL_FACTOR * args.timeout):
                cpu, wall = w.cpu_seconds() - w.cpu_started, time.monotonic() - w.started
                w.kill()
                record(w.seed, f"hang: no answer after {cpu:.1f} s CPU, {wall:.1f} s wall")  # type: ignore[arg-type]
                workers[workers.index(w)] = nw = Worker(args.memory_gb)
                feed(nw)


if __name__ == "__main__":
    main()
