"""Front-end speed: parse + lower a generated 10,000-line program; `rmot --help` wall time.

Run: make bench  (or .venv/bin/python -m pytest tests/benchmarks/bench_frontend.py)
Targets: >= 20,000 lines/s for parse + lower; <= 0.3 s for `rmot --help`.
`.venv/bin/python tests/benchmarks/bench_frontend.py` prints lines/s (library and CLI GC
schedules, parse alone) and where the time goes (stage_split: lex, LALR loop, AST build, passes).
"""

from __future__ import annotations

import subprocess
import sys
import time

import pytest

from rmot.compiler.frontend import load_program, load_text
from rmot.lang.parse import parse_text

LINES = 10_000


def generated_program(lines: int = LINES) -> str:
    """A realistic mix: targets, settings, moves with modifiers, I/O, waits; one statement per line."""
    out = ["program big on r1 {", "  tool gripper", "  frame table_top", "  speed 400 mm/s"]
    i = 0
    while len(out) < lines - 1:
        x, y = (i % 40) * 10, (i % 25) * 12
        out += [
            f"  target t{i} = pose(x={x}mm, y={y}mm, z=150mm, rx=180deg)",
            f"  move joint shift(t{i}, z=50mm) zone 10 mm",
            f"  move linear t{i} speed 100 mm/s zone fine",
            "  set out[1] = on",
            "  wait 200 ms",
            f"  move linear pose(x={x}mm, y={y}mm, z=200mm, rx=180deg) * pose(rz={i % 90}deg)",
            "  if in[2] == on { set out[2] = on } else { wait until in[2] == on timeout 5 s }",
            f"  move joint joints({i % 30}, -20, 30, 0, 60, 0) deg joint_speed 50 %",
        ]
        i += 1
    out = out[: lines - 1] + ["}"]
    return "\n".join(out) + "\n"


def _lines_per_second(benchmark: pytest.FixtureRequest, fn, text: str) -> None:  # type: ignore[no-untyped-def]
    benchmark(fn, text)
    median = benchmark.stats.stats.median
    benchmark.extra_info["lines_per_s"] = round(text.count("\n") / median)
    print(f"\n{fn.__name__}: {text.count(chr(10))} lines, median {median:.3f} s, {text.count(chr(10)) / median:,.0f} lines/s")


def test_parse_and_lower_10k_lines(benchmark) -> None:  # type: ignore[no-untyped-def]
    """Parse + check + lower 10,000 lines (default cell, robot library warm)."""
    text = generated_program()
    first = load_text(text, "/bench/big.rmot")
    assert not first.has_errors and first.program is not None

    def parse_and_lower(t: str) -> None:
        load_text(t, "/bench/big.rmot")

    _lines_per_second(benchmark, parse_and_lower, text)


def test_parse_only_10k_lines(benchmark) -> None:  # type: ignore[no-untyped-def]
    """The lark LALR parse + AST build alone."""
    text = generated_program()

    def parse_only(t: str) -> None:
        parse_text(t, "big.rmot")

    _lines_per_second(benchmark, parse_only, text)


def test_help_wall_time(benchmark) -> None:  # type: ignore[no-untyped-def]
    """`rmot --help` in a fresh interpreter (what a user waits for)."""

    def run() -> None:
        subprocess.run([sys.executable, "-c", "from rmot.compiler.cli import main; import sys; sys.argv=['rmot','--help']; main()"],
                       check=False, capture_output=True)

    benchmark.pedantic(run, rounds=5, iterations=1)
    print(f"\nrmot --help: median {benchmark.stats.stats.median:.3f} s")


def test_ir_of_a_small_file_wall_time(benchmark) -> None:  # type: ignore[no-untyped-def]
    """`rmot ir examples/pick_place.rmot` in a fresh interpreter, robot library included."""
    t0 = time.perf_counter()

    def run() -> None:
        subprocess.run([sys.executable, "-c", "from rmot.compiler.cli import main; import sys; "
                        "sys.argv=['rmot','ir','examples/pick_place.rmot']; main()"], check=False, capture_output=True)

    benchmark.pedantic(run, rounds=3, iterations=1)
    print(f"\nrmot ir (small file): median {benchmark.stats.stats.median:.3f} s ({time.perf_counter() - t0:.1f} s total)")


def lines_per_second(rounds: int = 5) -> dict[str, float]:
    """Parse + lower of the 10,000-line program, median CPU time per round, three ways: with
    Python's default collector schedule (what a library caller gets: rmot leaves it alone),
    with the schedule the `rmot` command sets (compiler/cli.tune_gc), and parse only."""
    import gc
    import statistics

    from rmot.compiler.cli import GC_THRESHOLDS

    text = generated_program()
    load_text(text, "/bench/big.rmot")
    lines = text.count("\n")
    out: dict[str, float] = {}
    old = gc.get_threshold()
    try:
        runs = (("parse + lower, default GC", old, lambda: load_text(text, "/bench/big.rmot")),
                ("parse + lower, rmot's GC schedule", GC_THRESHOLDS,
                 lambda: load_text(text, "/bench/big.rmot")),
                ("parse only, rmot's GC schedule", GC_THRESHOLDS, lambda: parse_text(text, "big.rmot")))
        for label, thresholds, fn in runs:
            gc.set_threshold(*thresholds)
            times = []
            for _ in range(rounds):
                t0 = time.process_time()
                fn()
                times.append(time.process_time() - t0)
            out[label] = lines / statistics.median(times)
    finally:
        gc.set_threshold(*old)
    return out


def stage_split(rounds: int = 7) -> list[tuple[str, float]]:
    """Where parse + lower of the 10,000-line program spends its time: median CPU seconds per
    stage, with the `rmot` command's GC schedule (the library's default schedule adds the
    collector's walks on top, mostly in the AST build). Stages: reading the file (bytes +
    UTF-8), the lexer's master regex alone, lex + the LALR loop with no-op rule callbacks,
    the AST build (full parse minus that), then each front-end pass as compiler/pipeline
    runs it (load_sources includes the parse of the program and of the default cell)."""
    import gc
    import os
    import statistics
    import tempfile

    from rmot.compiler import pipeline
    from rmot.compiler.cli import GC_THRESHOLDS
    from rmot.compiler.passes.context import Reporter, default_robot_loader
    from rmot.compiler.passes.state import FrontendState
    from rmot.lang._lalr import PostLexState
    from rmot.lang.lexer import TOKEN
    from rmot.lang.parse import _parser

    text = generated_program()
    load_text(text, "/bench/big.rmot")
    driver = _parser().driver
    real = driver.actions
    noop = [{k: v if v.__class__ is int or v[2] is None else (v[0], v[1], _first_child)
             for k, v in row.items()} for row in real]

    def lex() -> None:
        match, pos, n = TOKEN.match, 0, len(text)
        while pos < n:
            m = match(text, pos)
            if m is None:
                break
            m.group(m.lastgroup)  # type: ignore[arg-type]
            pos = m.end()

    def lalr() -> None:
        driver.actions = noop
        try:
            driver.parse(text, PostLexState())
        finally:
            driver.actions = real

    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "big.rmot")
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)

        def read() -> None:
            with open(path, "rb") as f:
                f.read().decode("utf-8")

        old = gc.get_threshold()
        gc.set_threshold(*GC_THRESHOLDS)
        try:
            def med(fn) -> float:  # type: ignore[no-untyped-def]
                times = []
                for _ in range(rounds):
                    t0 = time.process_time()
                    fn()
                    times.append(time.process_time() - t0)
                return statistics.median(times)

            out = [("read the file", med(read)), ("lex (master regex only)", med(lex))]
            out.append(("lex + LALR loop (no-op callbacks)", med(lalr)))
            out.append(("AST build (parse_text - the above)",
                        med(lambda: parse_text(text, "big.rmot")) - out[-1][1]))
            per_pass: dict[str, list[float]] = {}
            for _ in range(rounds):
                state = FrontendState(path=path, roots=(tmp,), reporter=Reporter(),
                                      robot_loader=default_robot_loader, text=None, cell_path=None)
                for p in pipeline.PASSES:
                    t0 = time.process_time()
                    state = p(state)
                    per_pass.setdefault(p.__name__, []).append(time.process_time() - t0)
                assert state.program is not None
            out += [(f"pass {k}", statistics.median(v)) for k, v in per_pass.items()]
            out.append(("load_program (all of it)", med(lambda: load_program(path))))
        finally:
            gc.set_threshold(*old)
    return out


def _first_child(c: list[object]) -> object:
    return c[0] if c else None


if __name__ == "__main__":
    import os

    for label, rate in lines_per_second().items():
        print(f"{label:36s} {rate:10,.0f} lines/s (CPU time; target >= 20,000 for parse + lower)")
    lines = generated_program().count("\n")
    print("stage split (CPU time, median; rmot's GC schedule):")
    for label, seconds in stage_split():
        print(f"  {label:38s} {seconds * 1e3:8.1f} ms {seconds / lines * 1e6:7.1f} us/line")
    print(f"(load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} CPUs)")
