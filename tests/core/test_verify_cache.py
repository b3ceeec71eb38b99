"""The verification cache (rmot.compiler.cli.verify_cache): `rmot check` then `rmot compile`
(report, render) of the same program verify once.

- findings restored from the cache render byte for byte as freshly computed ones (a program
  with a collision, exit 1), in `check` and `compile`, and as with --no-cache;
- a moved obstacle misses (the new findings appear); --clearance is part of the key;
- a damaged entry is ignored and rebuilt; a changed scene file listed in the entry misses;
- --no-cache neither reads nor writes it.
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from pathlib import Path

import pytest

from rmot.compiler.cli import verify_cache
from tests.core.cache_cli import Counter, count_calls, entry_json, run, write_sealed

ROOT = Path(__file__).resolve().parents[2]

# examples/collision.rmot in a copy of the default cell: the gripper drags through the table
PROGRAM = """use cell "cell.rmot"
program collision on r1 {
  tool gripper
  speed 250 mm/s
  zone fine
  target home = joints(0, -10, 10, 0, 90, 0) deg
  target nest = pose(x=-100mm, z=30mm, rx=180deg)
  target slot = pose(x=100mm, y=100mm, z=30mm, rx=180deg)
  move joint home
  move joint shift(nest, z=100mm) frame table_top
  move linear nest frame table_top speed 100 mm/s
  set out[1] = on
  wait 300 ms
  move linear slot frame pallet
  set out[1] = off
  move linear shift(slot, z=100mm) frame pallet
  move joint home
}
"""
POST = "at pose(x=-700mm, y=300mm, z=800mm)"
POST_MOVED = "at pose(x=300mm, y=-500mm, z=800mm)"  # into the arm's way to the pallet


@pytest.fixture(scope="module")
def project(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Path]:
    """A project folder with the program and its cell; the plan cache of the module's runs."""
    folder = tmp_path_factory.mktemp("verify-cache")
    cell = (ROOT / "compiler" / "default_cell.rmot").read_text(encoding="utf-8")
    assert POST in cell
    (folder / "cell.rmot").write_text(cell, encoding="utf-8")
    (folder / "prog.rmot").write_text(PROGRAM, encoding="utf-8")
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("RMOT_CACHE_DIR", str(folder / "cache"))
        yield folder


@pytest.fixture
def verifications(monkeypatch: pytest.MonkeyPatch) -> Counter:
    """Counts the verifications that really run."""
    return count_calls(monkeypatch, verify_cache, "_verify")


def entries(project: Path) -> list[Path]:
    return sorted((project / "cache" / "verify").glob("*/*.json"))


def clear_verify(project: Path) -> None:
    for path in entries(project):
        path.unlink()


def test_restored_findings_render_byte_identically(project: Path, verifications: Counter) -> None:
    clear_verify(project)
    cold = run(project, "check", "prog.rmot")
    assert cold.exit_code == 1, cold.output
    assert verifications.calls == 1 and len(entries(project)) == 1
    assert "prog.rmot:14:3: error[E300]: 'gripper' collides with 'table'" in cold.stdout
    assert " 14 |   move linear slot frame pallet\n    |   ^~~~~~~~~~~~~~~~~~~~~~~~~~~~~\n" in cold.stdout
    warm = run(project, "check", "prog.rmot")
    assert verifications.calls == 1  # read from the cache, not verified again
    assert (warm.exit_code, warm.stdout, warm.stderr) == (cold.exit_code, cold.stdout, cold.stderr)
    fresh = run(project, "check", "prog.rmot", "--no-cache")
    assert verifications.calls == 2
    assert (fresh.exit_code, fresh.stdout, fresh.stderr) == (cold.exit_code, cold.stdout, cold.stderr)
    for fmt in ("json", "sarif"):  # every field of the diagnostics, not only the text
        warm_fmt = run(project, "check", "prog.rmot", "--format", fmt)
        fresh_fmt = run(project, "check", "prog.rmot", "--format", fmt, "--no-cache")
        assert warm_fmt.stdout == fresh_fmt.stdout and warm_fmt.exit_code == 1
    assert verifications.calls == 4  # two of the four runs were --no-cache


def test_compile_after_check_uses_the_entry_and_prints_the_same(project: Path, verifications: Counter) -> None:
    run(project, "check", "prog.rmot")  # the entry (written by this or an earlier test)
    before = verifications.calls
    warm = run(project, "compile", "prog.rmot", "--target", "rapid", "-o", "out")
    assert verifications.calls == before  # compile right after check: verified zero times
    fresh = run(project, "compile", "prog.rmot", "--target", "rapid", "-o", "out", "--no-cache")
    assert warm.exit_code == fresh.exit_code == 1
    assert warm.stderr == fresh.stderr and "error[E300]" in warm.stderr and "no files written" in warm.stderr
    allowed = run(project, "compile", "prog.rmot", "--target", "rapid", "-o", "a", "--allow-findings")
    allowed_fresh = run(project, "compile", "prog.rmot", "--target", "rapid", "-o", "b", "--allow-findings",
                        "--no-cache")
    assert allowed.exit_code == allowed_fresh.exit_code == 0, allowed.output
    assert allowed.stderr == allowed_fresh.stderr
    assert (project / "a" / "rapid" / "collision.mod").read_bytes() == \
        (project / "b" / "rapid" / "collision.mod").read_bytes()


def test_a_moved_obstacle_misses_and_shows_the_new_findings(project: Path, verifications: Counter) -> None:
    cell = project / "cell.rmot"
    original = cell.read_text(encoding="utf-8")
    try:
        before = run(project, "check", "prog.rmot")
        assert "'post'" not in before.stdout
        calls = verifications.calls
        cell.write_text(original.replace(POST, POST_MOVED), encoding="utf-8")
        moved = run(project, "check", "prog.rmot")
        assert verifications.calls == calls + 1  # not taken from the cache
        assert moved.exit_code == 1
        assert "error[E300]: 'gripper' collides with 'post'" in moved.stdout
        again = run(project, "check", "prog.rmot")  # the moved cell's own entry now
        assert verifications.calls == calls + 1 and again.stdout == moved.stdout
    finally:
        cell.write_text(original, encoding="utf-8")
    back = run(project, "check", "prog.rmot")
    assert back.stdout == before.stdout


def test_clearance_is_part_of_the_key(project: Path, verifications: Counter) -> None:
    plain = run(project, "check", "prog.rmot")
    calls = verifications.calls
    near = run(project, "check", "prog.rmot", "--clearance", "200mm")
    assert verifications.calls == calls + 1
    assert near.stdout != plain.stdout and "warning[W301]" in near.stdout  # approaches closer than 200 mm
    fresh = run(project, "check", "prog.rmot", "--clearance", "200mm", "--no-cache")
    assert fresh.stdout == near.stdout


@pytest.mark.parametrize("damage", ["truncate", "garbage", "empty", "not-a-report", "wrong-key",
                                    "unknown-type", "bad-file-list"])
def test_a_damaged_entry_is_ignored_and_rebuilt(project: Path, verifications: Counter, damage: str) -> None:
    clear_verify(project)
    cold = run(project, "check", "prog.rmot")
    (path,) = entries(project)
    data = path.read_bytes()
    entry = entry_json(path)
    if damage == "truncate":
        path.write_bytes(data[: len(data) // 2])
    elif damage == "garbage":
        path.write_bytes(os.urandom(300))
    elif damage == "empty":
        path.write_bytes(b"")
    elif damage == "not-a-report":
        entry["doc"] = {"$t": ["prog.rmot", {"$d": []}, {"$t": [1, 2]}, None]}
        write_sealed(path, path.stem, entry)
    elif damage == "wrong-key":
        entry["key"] = "0" * 64
        write_sealed(path, path.stem, entry)
    elif damage == "unknown-type":
        entry["doc"] = {"$c": "os:system", "id": 0, "f": {}}
        write_sealed(path, path.stem, entry)
    else:
        entry["files"] = [[1, 2, 3]]
        write_sealed(path, path.stem, entry)
    calls = verifications.calls
    again = run(project, "check", "prog.rmot")
    assert verifications.calls == calls + 1  # the damaged entry was not used
    assert (again.exit_code, again.stdout, again.stderr) == (cold.exit_code, cold.stdout, cold.stderr)
    (rebuilt,) = entries(project)
    assert entry_json(rebuilt)["key"] == rebuilt.stem  # written afresh, readable
    run(project, "check", "prog.rmot")
    assert verifications.calls == calls + 1  # the rebuilt entry is read


def test_a_changed_scene_file_listed_in_the_entry_misses(project: Path, verifications: Counter) -> None:
    """A URDF robot's collision meshes are read by the scene but are not in the plan's key: the
    entry lists each with its SHA-256, checked on every read."""
    clear_verify(project)
    run(project, "check", "prog.rmot")
    (path,) = entries(project)
    mesh = project / "wrist.stl"
    mesh.write_bytes(b"solid a\nendsolid a\n")
    entry = entry_json(path)
    entry["files"] = [[str(mesh), verify_cache._digest(str(mesh))]]
    write_sealed(path, path.stem, entry)
    calls = verifications.calls
    run(project, "check", "prog.rmot")
    assert verifications.calls == calls  # unchanged: read
    mesh.write_bytes(b"solid b\nendsolid b\n")
    run(project, "check", "prog.rmot")
    assert verifications.calls == calls + 1  # changed: verified again
    mesh.unlink()


def test_no_cache_neither_reads_nor_writes(project: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    clear_verify(project)

    def refuse(*args: object) -> None:
        raise AssertionError("the verification cache was touched")

    monkeypatch.setattr(verify_cache, "_read", refuse)
    monkeypatch.setattr(verify_cache, "_write", refuse)
    for args in (["check", "prog.rmot"], ["compile", "prog.rmot", "--target", "rapid", "-o", "out"],
                 ["report", "prog.rmot", "-o", "r.html"]):
        result = run(project, *args, "--no-cache")
        assert result.exit_code == 1 and "error[E300]" in result.output, result.output
    assert entries(project) == []


def test_report_and_render_use_the_entry(project: Path, verifications: Counter) -> None:
    run(project, "check", "prog.rmot")
    calls = verifications.calls
    result = run(project, "report", "prog.rmot", "-o", "r.html")
    assert result.exit_code == 1 and "error[E300]" in result.stderr
    result = run(project, "render", "prog.rmot", "-o", "r.svg", "--at", "3.2")
    assert result.exit_code == 0, result.output
    assert verifications.calls == calls
