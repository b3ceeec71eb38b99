"""Mutation testing: mutmut over one module with only its own test files.

    python -m tests.mutation.mutate base          # or: diagnostics, timing, all
    make mutation                                 # all three, one after the other

mutmut (3.x) names a mutant after its file's path (`src/` stripped) and imports the mutated
copy from `mutants/src`; rmot maps `rmot.lang` to `lang/` (pyproject's package-dir), so each
run works in a staging directory (build/mutation/<name>/, git-ignored) that holds the
sources as `src/rmot/<package>/`, the tests and the examples, and a pyproject.toml with the
mutmut settings of that module. The score and the surviving mutants are printed at the end
(`mutmut results` / `mutmut show <name>` in that directory tell more). Not part of
`make test`: a run takes minutes to hours on a loaded machine.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PACKAGES = ("lang", "compiler", "backends", "sim")

# module -> (its file under src/rmot, the test files that are its witnesses)
TARGETS: dict[str, tuple[str, tuple[str, ...]]] = {
    "base": ("backends/base.py", (
        "tests/backends/test_base.py", "tests/backends/test_routine_dedupe.py",
        "tests/backends/test_base_mutants.py",
    )),
    "diagnostics": ("lang/diagnostics.py", (
        "tests/core/test_diagnostics.py", "tests/core/test_diagnostics_mutants.py",
    )),
    "timing": ("compiler/plan/timing.py", (
        "tests/plan/test_plan_timing.py", "tests/plan/test_plan_timing_mutants.py",
    )),
}


# mutmut runs each test more than once in one process (stats, then the clean run, then the
# mutants in forks): hypothesis then sees a test method called from several class instances
# and fails its differing_executors health check; a fixed derandomized profile without the
# example database also keeps every mutant's verdict reproducible.
_HYPOTHESIS_PROFILE = """

# --- appended by tests/mutation/mutate.py for the mutation run only
from hypothesis import HealthCheck as _HealthCheck, settings as _settings

_settings.register_profile("mutation", derandomize=True, database=None,
                           suppress_health_check=list(_HealthCheck))
_settings.load_profile("mutation")
"""


def _stage(name: str, out: Path) -> Path:
    """A fresh staging directory for `name`: sources as src/rmot/*, tests, examples, config."""
    source, tests = TARGETS[name]
    stage = out / name
    if stage.exists():
        shutil.rmtree(stage)
    ignore = shutil.ignore_patterns("__pycache__", "*.pyc")
    for pkg in PACKAGES:
        shutil.copytree(ROOT / pkg, stage / "src" / "rmot" / pkg, ignore=ignore)
    for extra in ("tests", "examples"):
        shutil.copytree(ROOT / extra, stage / extra, ignore=ignore)
    with (stage / "tests" / "conftest.py").open("a", encoding="utf-8") as conftest:
        conftest.write(_HYPOTHESIS_PROFILE)
    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    pytest_opts = project["tool"]["pytest"]["ini_options"]
    present = [t for t in tests if (ROOT / t).exists()]
    lines = [
        "[tool.pytest.ini_options]",
        f"markers = {json.dumps(pytest_opts.get('markers', []))}",
        'addopts = "-p no:cacheprovider -q"',
        "",
        "[tool.mutmut]",
        'source_paths = ["src"]',
        'also_copy = ["examples"]',
        f'only_mutate = ["src/rmot/{source}"]',
        f"pytest_add_cli_args_test_selection = {json.dumps(present)}",
        "use_git_change_detection = false",
        "",
    ]
    (stage / "pyproject.toml").write_text("\n".join(lines), encoding="utf-8")
    return stage


def _mutmut(stage: Path, *args: str) -> subprocess.CompletedProcess[str]:
    exe = Path(sys.executable).with_name("mutmut")
    env = dict(os.environ, PYTHONDONTWRITEBYTECODE="1")
    return subprocess.run([str(exe), *args], cwd=stage, env=env, text=True, capture_output=True,
                          check=False)


def run(name: str, out: Path, children: int) -> dict[str, int]:
    """Run mutmut for `name`; return the count of each outcome."""
    stage = _stage(name, out)
    done = _mutmut(stage, "run", "--max-children", str(children))
    (stage / "mutmut-run.log").write_text(done.stdout + done.stderr, encoding="utf-8")
    listed = _mutmut(stage, "results", "--all", "true")
    counts: dict[str, int] = {}
    survivors: list[str] = []
    for line in listed.stdout.splitlines():
        mutant, _, status = line.strip().rpartition(": ")
        if not mutant:
            continue
        counts[status] = counts.get(status, 0) + 1
        if status == "survived":
            survivors.append(mutant)
    killed = counts.get("killed", 0) + counts.get("timeout", 0)
    total = sum(counts.values()) - counts.get("no tests", 0) - counts.get("skipped", 0)
    score = 100.0 * killed / total if total else 0.0
    print(f"{name}: {counts}; score {killed}/{total} = {score:.1f} % (killed incl. timeouts, "
          f"over mutants reached by the tests)")
    (stage / "survivors.txt").write_text("".join(f"{m}\n" for m in survivors), encoding="utf-8")
    print(f"  survivors listed in {stage / 'survivors.txt'} (`mutmut show NAME` there shows one)")
    return counts


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("names", nargs="*", default=["all"], choices=[*TARGETS, "all"])
    parser.add_argument("--out", type=Path, default=ROOT / "build" / "mutation")
    parser.add_argument("--children", type=int, default=1, help="parallel mutants (default 1)")
    args = parser.parse_args(argv)
    names = list(TARGETS) if "all" in args.names else args.names
    for name in names:
        run(name, args.out, args.children)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
