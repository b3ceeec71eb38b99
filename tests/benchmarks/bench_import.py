"""`rmot import` cost against program length: a Fanuc TP program of N blocks, each a jump the
reader keeps native over an output (`IF TIMER[1]>1,JMP LBL[k]`, `DO[1]=ON`, `LBL[k]`) and a
register the program sets and tests, read in-process (read_files) for N = 100 and 800.

Run: make bench  (or .venv/bin/python -m pytest tests/benchmarks/bench_import.py)
     .venv/bin/python tests/benchmarks/bench_import.py      # medians and the ratio
Target: time(800) <= 12 x time(100) (8 x the instructions: linear is 8). Measured: 7.9
(0.022 s and 0.175 s). Keeping one jump's span per pass with a label search per jump took
minutes at 800 blocks; one label scan per pass, 44; every disjoint span per pass, 7.9. On a
4,400-line pendant backup (VASC's MAKROSTP.LS, 89 native jumps) `rmot import` took 16 s (8 s
before the register reading read it twice), now 0.7 s.
"""

from __future__ import annotations

import statistics
import sys
import tempfile
import time
from pathlib import Path

from rmot.backends.readers import ImportError_, read_files

SIZES = (100, 800)
TARGET_RATIO = 12.0


def tp_program(blocks: int) -> str:
    """A TP program of `blocks` jump spans, each with an output, a register count and a test."""
    body = ["R[1:count]=0", "R[1:count]=1"]
    for k in range(1, blocks + 1):
        body += [f"IF TIMER[1]>1,JMP LBL[{k}]", "DO[1]=ON", f"LBL[{k}]", "R[1:count]=R[1:count]+1",
                 "IF (R[1:count]>3) THEN", "DO[2]=ON", "ENDIF"]
    lines = "".join(f"{n:5d}:  {text} ;\n" for n, text in enumerate(body, 1))
    return f"/PROG  BENCH\n/ATTR\n/MN\n{lines}/POS\n/END\n"


def median_seconds(blocks: int, rounds: int = 5) -> float:
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "bench.ls"
        path.write_text(tp_program(blocks), encoding="utf-8")
        read_files([str(path)])  # warm: the readers' imports
        times = []
        for _ in range(rounds):
            t0 = time.perf_counter()
            read_files([str(path)])
            times.append(time.perf_counter() - t0)
    return statistics.median(times)


def test_import_cost_grows_linearly(benchmark) -> None:  # type: ignore[no-untyped-def]
    small, large = (median_seconds(n) for n in SIZES)
    benchmark.pedantic(lambda: None, rounds=1, iterations=1)
    print(f"\nimport: {SIZES[0]} blocks {small:.3f} s, {SIZES[1]} blocks {large:.3f} s, ratio {large / small:.1f} "
          f"(target <= {TARGET_RATIO:g})")
    assert large <= TARGET_RATIO * small


# a controller's logbook saved as .LS beside the programs (VASC's backups hold one per robot):
# no TP program, refused at its first line (E510), after the register scan every .ls gets
LOG_SIZES = (20, 160)


def logbook(entries: int) -> str:
    """A controller logbook of `entries` alarm records, each with a pendant screen image: lines
    padded with spaces as the controller writes them, runs of blank ones among them."""
    screen = "--Screen image--------------------------\n" + (" " * 60 + "\n") * 24 + "   I 718" + " " * 52 + "\n"
    record = ("========================================\nINTP-440 (FOLGE011) Stopped by TC_ONLIN\n"
              "E                                      \nSTOP.L                        00000110 \n"
              "15-JUL-24 17:27 :18\n" + screen + "SHIFT,F4( Close  ) is pressed          \n")
    return "LOGBOOK.LS     Robot Name R01 15-JUL-24 17:30:52  \n\n" + record * entries


def logbook_seconds(entries: int, rounds: int = 5) -> float:
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "LOGBOOK.LS"
        path.write_text(logbook(entries), encoding="utf-8")
        times = []
        for _ in range(rounds):
            t0 = time.perf_counter()
            try:
                read_files([str(path)])
            except ImportError_:
                pass  # E510: not a TP program, as expected
            times.append(time.perf_counter() - t0)
    return statistics.median(times)


def test_a_logbook_is_refused_in_linear_time(benchmark) -> None:  # type: ignore[no-untyped-def]
    """Measured: 20 entries 0.064 s, 160 entries 0.51 s (ratio 7.9). The register scan's patterns
    crossed lines (`\\s*`, `[^\\]]*`): 2 entries took more than a minute, VASC's 13,699-line LOGBOOK.LS more than
    ten minutes."""
    small, large = (logbook_seconds(n) for n in LOG_SIZES)
    benchmark.pedantic(lambda: None, rounds=1, iterations=1)
    print(f"\nlogbook: {LOG_SIZES[0]} entries {small:.4f} s, {LOG_SIZES[1]} entries {large:.4f} s, "
          f"ratio {large / small:.1f} (target <= {TARGET_RATIO:g})")
    assert large <= TARGET_RATIO * small


if __name__ == "__main__":
    s, b = (median_seconds(n) for n in SIZES)
    print(f"{SIZES[0]} blocks: {s:.3f} s; {SIZES[1]} blocks: {b:.3f} s; ratio {b / s:.1f} (target <= {TARGET_RATIO:g})")
    sys.exit(0 if b <= TARGET_RATIO * s else 1)
