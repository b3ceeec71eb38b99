"""The front end's result taken from the caches (rmot.compiler.cli.load_cache): a program
already planned is not parsed and lowered again while no file it read has changed.

- a warm `check` / `compile` runs no front end and prints byte for byte what a fresh run prints,
  front-end warnings included;
- a changed byte of the program, of an import that contributes nothing to the program, or of
  the cell is seen (the front end runs and reports it); a damaged entry is ignored;
- a file modified just before the front end read it gets no entry ("racy" files);
- --no-cache and other working directories do not share entries.
"""

from __future__ import annotations

import os
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from rmot.compiler import frontend, plan_cache
from rmot.compiler.cli import load_cache
from tests.core.cache_cli import Counter, count_calls, entry_json, run, write_sealed

ROOT = Path(__file__).resolve().parents[2]
PROGRAM = """import "lib.rmot"
program three on r1 {
  tool gripper
  target home = joints(0, -10, 10, 0, 90, 0) deg
  target a = pose(x=-100mm, y=0mm, z=100mm, rx=180deg)
  move joint home speed 300 mm/s
  frame table_top
  move linear a
  move joint home zone fine
}
"""
LIB = "const lift = 100 mm\n"


def write_old(path: Path, text: str) -> None:
    """Write `text` with a modification time a minute ago (a file saved before the run; an
    editor or `cp -p` may also keep an old time: the bytes are what is compared)."""
    path.write_text(text, encoding="utf-8")
    past = time.time() - 60
    os.utime(path, (past, past))


@pytest.fixture(scope="module")
def project(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Path]:
    folder = tmp_path_factory.mktemp("load-cache")
    write_old(folder / "p.rmot", PROGRAM)
    write_old(folder / "lib.rmot", LIB)
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("RMOT_CACHE_DIR", str(folder / "cache"))
        yield folder


@pytest.fixture
def front_ends(monkeypatch: pytest.MonkeyPatch) -> Counter:
    return count_calls(monkeypatch, frontend, "load_program")


def entries(project: Path) -> list[Path]:
    return sorted((project / "cache" / "load").glob("*/*.json"))


def test_warm_runs_skip_the_front_end_and_print_the_same(project: Path, front_ends: Counter) -> None:
    cold = run(project, "check", "p.rmot")
    assert cold.exit_code == 0, cold.output
    assert "p.rmot:6:19: warning[W170]" in cold.stdout and "   |                   ^~~~~~~~~~~~~~\n" in cold.stdout
    assert len(entries(project)) == 1
    calls = front_ends.calls
    warm = run(project, "check", "p.rmot")
    assert front_ends.calls == calls  # not parsed nor lowered again
    assert (warm.exit_code, warm.stdout, warm.stderr) == (cold.exit_code, cold.stdout, cold.stderr)
    fresh = run(project, "check", "p.rmot", "--no-cache")
    assert front_ends.calls == calls + 1
    assert (fresh.stdout, fresh.stderr) == (cold.stdout, cold.stderr)
    warm_c = run(project, "compile", "p.rmot", "--target", "rapid", "--target", "krl", "-o", "a")
    assert front_ends.calls == calls + 1
    fresh_c = run(project, "compile", "p.rmot", "--target", "rapid", "--target", "krl", "-o", "b",
                  "--no-cache")
    assert warm_c.exit_code == fresh_c.exit_code == 0 and warm_c.stderr == fresh_c.stderr
    assert "warning[W170]" in warm_c.stderr
    a = sorted(p.relative_to(project / "a") for p in (project / "a").rglob("*") if p.is_file())
    b = sorted(p.relative_to(project / "b") for p in (project / "b").rglob("*") if p.is_file())
    assert a == b and len(a) >= 2
    assert all((project / "a" / p).read_bytes() == (project / "b" / p).read_bytes() for p in a)


@pytest.mark.parametrize(("name", "old", "new", "expect"), [
    ("lib.rmot", LIB, "const lift = 100 mm\nconst lift = 5 mm\n", "error[E"),  # an import adds nothing
    ("p.rmot", PROGRAM, PROGRAM.replace("speed 300 mm/s", "speed 301 mm/s"), "got 301 mm/s"),
])
def test_a_changed_input_file_runs_the_front_end(project: Path, front_ends: Counter, name: str,
                                                 old: str, new: str, expect: str) -> None:
    run(project, "check", "p.rmot")
    calls = front_ends.calls
    try:
        write_old(project / name, new)  # same length or not, an old time: the bytes decide
        changed = run(project, "check", "p.rmot")
        assert front_ends.calls == calls + 1
        assert expect in changed.stdout, changed.output
    finally:
        write_old(project / name, old)
    back = run(project, "check", "p.rmot")
    assert back.exit_code == 0 and expect not in back.stdout


def test_a_changed_cell_runs_the_front_end(project: Path, front_ends: Counter) -> None:
    cell = (ROOT / "compiler" / "default_cell.rmot").read_text(encoding="utf-8")
    write_old(project / "cell.rmot", cell)
    args = ["check", "p.rmot", "--cell", "cell.rmot"]
    first = run(project, *args)
    run(project, *args)
    calls = front_ends.calls
    write_old(project / "cell.rmot", cell.replace("mass 1.2 kg", "mass 1.3 kg"))
    changed = run(project, *args)
    assert front_ends.calls == calls + 1
    assert changed.exit_code == first.exit_code == 0


def test_a_file_modified_just_before_the_run_gets_no_entry(project: Path, front_ends: Counter,
                                                            tmp_path: Path) -> None:
    (tmp_path / "lib.rmot").write_text(LIB, encoding="utf-8")
    (tmp_path / "p.rmot").write_text(PROGRAM, encoding="utf-8")
    now = time.time() + 1  # saved while the run starts (a machine under load may take a while)
    os.utime(tmp_path / "lib.rmot", (now, now))
    before = set(entries(project))
    result = run(tmp_path, "check", "p.rmot")
    assert result.exit_code == 0
    assert set(entries(project)) == before
    assert plan_cache.settled([str(tmp_path / "p.rmot")], time.time() + plan_cache.SETTLE_S + 1)


@pytest.mark.parametrize("damage", ["garbage", "not-diagnostics", "bad-files", "unknown-plan"])
def test_a_damaged_entry_is_ignored(project: Path, front_ends: Counter, damage: str) -> None:
    cold = run(project, "check", "p.rmot")
    cwd = os.getcwd()
    os.chdir(project)
    try:
        path = load_cache._entry_path(load_cache.load_key("p.rmot", None, None, True))
    finally:
        os.chdir(cwd)
    entry = entry_json(path)
    if damage == "garbage":
        path.write_bytes(b"\xff" + os.urandom(100))
    elif damage == "not-diagnostics":
        entry["doc"] = {"$t": [1]}
        write_sealed(path, path.stem, entry)
    elif damage == "bad-files":
        entry["files"] = [{"a": 1}]
        write_sealed(path, path.stem, entry)
    else:
        entry["plan"] = "f" * 64
        write_sealed(path, path.stem, entry)
    calls = front_ends.calls
    again = run(project, "check", "p.rmot")
    assert front_ends.calls == calls + 1
    assert (again.exit_code, again.stdout) == (cold.exit_code, cold.stdout)


def test_the_key_holds_the_invocation(tmp_path: Path) -> None:
    base = load_cache.load_key("p.rmot", None, None, True)
    assert load_cache.load_key("p.rmot", None, None, True) == base
    assert load_cache.load_key("./p.rmot", None, None, True) != base  # printed differently
    assert load_cache.load_key("p.rmot", "cell.rmot", None, True) != base
    assert load_cache.load_key("p.rmot", None, str(tmp_path), True) != base
    assert load_cache.load_key("p.rmot", None, None, False) != base
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        assert load_cache.load_key("p.rmot", None, None, True) != base  # another p.rmot
    finally:
        os.chdir(cwd)
