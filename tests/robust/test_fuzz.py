"""Grammar-generated whole projects (tests/robust/gen.py) through the whole pipeline: no input
may raise. A small Hypothesis budget here (well under a minute); `make fuzz` runs the same
generator for 100,000 inputs under a memory cap and a per-input timeout."""

from __future__ import annotations

import os
import tempfile

from hypothesis import HealthCheck, given, settings

from rmot.compiler.cli.compile_cmd import compile_program, write_all
from rmot.compiler.frontend import load_program
from rmot.lang.diagnostics import render
from rmot.backends import targets
from tests.robust.gen import hypothesis_project, random_project

TARGETS = targets()
_FEW = settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
_MORE = settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])


def _write(folder: str, files: dict[str, str]) -> str:
    for name, text in files.items():
        with open(os.path.join(folder, name), "w", encoding="utf-8", newline="") as f:
            f.write(text)
    return os.path.join(folder, "main.rmot")


def _check_spans(diagnostics: tuple) -> None:  # type: ignore[type-arg]
    for d in diagnostics:
        render(d)
        if d.span is not None:
            assert 0 <= d.span.start.offset <= d.span.end.offset <= len(d.span.file.text), d


@_MORE
@given(hypothesis_project())
def test_generated_projects_front_end_never_raises(files: dict[str, str]) -> None:
    """Parse, check and lower: diagnostics, never an exception; spans inside their files."""
    with tempfile.TemporaryDirectory() as d:
        result = load_program(_write(d, files), require_program=True)
        _check_spans(result.diagnostics)
        assert (result.program is None) == result.has_errors


@_FEW
@given(hypothesis_project())
def test_generated_projects_compile_for_every_vendor_without_raising(files: dict[str, str]) -> None:
    """Front end, planner, verifier, every backend and the writer: exit 0, 1 or 2, never a
    traceback; whatever is written is text with \\n line ends only."""
    with tempfile.TemporaryDirectory() as d:
        outcome = compile_program(_write(d, files), TARGETS, allow_findings=True)
        assert outcome.exit_code in (0, 1, 2)
        _check_spans(outcome.diagnostics)
        if outcome.files:
            for path in write_all(os.path.join(d, "out"), outcome.files):
                with open(path, "rb") as f:
                    data = f.read()
                assert b"\r" not in data and b"\x00" not in data, path


def test_the_generator_reaches_the_backends() -> None:
    """The generator is not a syntax-error machine: of 60 seeded projects, at least a third
    pass the front end (so the planner, verifier and backends are exercised)."""
    clean = 0
    for seed in range(60):
        with tempfile.TemporaryDirectory() as d:
            clean += not load_program(_write(d, random_project(seed)), require_program=True).has_errors
    assert clean >= 20, clean


def test_inputs_make_fuzz_found_stay_fixed(tmp_path) -> None:  # type: ignore[no-untyped-def]
    """Seeds `make fuzz` reported: tracebacks (a second robot without a task near a fixture:
    KeyError in the collision bisection) and memory over 2 GB (a capsule of 1 nm radius, now
    E125) end in diagnostics."""
    from tests.robust.fuzz import run_one

    for seed in (11011, 16503, 13338, 15919):
        assert run_one(seed, str(tmp_path)).startswith("ok"), seed


def test_the_mutation_strategy_changes_an_example_and_is_reproducible() -> None:
    """`make fuzz FUZZ_MIX=1`'s second strategy: the same seed gives the same text, and the
    text is no example verbatim (a strategy that mutates nothing would test nothing new)."""
    from pathlib import Path

    from tests.robust.fuzz import mutated_example

    examples = {p.read_text(encoding="utf-8") for p in (Path(__file__).resolve().parents[2] / "examples").glob("*.rmot")}
    texts = [mutated_example(seed)["main.rmot"] for seed in range(1, 40, 2)]
    assert texts == [mutated_example(seed)["main.rmot"] for seed in range(1, 40, 2)]
    assert sum(t not in examples for t in texts) >= 35 * len(texts) // 40


def test_the_hostile_strategies_are_reproducible_and_each_runs_clean(tmp_path) -> None:  # type: ignore[no-untyped-def]
    """`make fuzz FUZZ_MIX=1`'s hostile files: the same seed gives the same input, every kind
    (mesh, URDF, cache, report) comes up, and one input of each ends with diagnostics, the
    damaged cache's verdict being the uncached one (a harness that cannot run finds nothing)."""
    import os

    from tests.robust.hostile import KINDS, hostile_input, run_hostile

    seeds = range(2, 200, 4)
    assert [hostile_input(s) for s in seeds] == [hostile_input(s) for s in seeds]
    first = {}
    for s in seeds:
        first.setdefault(hostile_input(s).kind, s)
    assert sorted(first) == sorted(KINDS)
    for kind, seed in sorted(first.items()):
        proj = tmp_path / f"p{seed}"
        os.makedirs(proj)
        assert run_hostile(seed, str(proj), str(tmp_path / "caches")).startswith("ok"), (kind, seed)
