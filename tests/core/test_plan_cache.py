"""The plan cache (rmot.compiler.plan_cache) and its codec (rmot.compiler.plan_codec).

- every shipped example's Plan survives encode -> disk -> decode, field by field, arrays included;
- a changed input byte, option, cell or named file misses; a corrupt entry is rebuilt;
- --no-cache neither reads nor writes; the codec refuses types outside its registry.
"""

from __future__ import annotations

import dataclasses
import enum
import math
import os
import time
import shutil
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from rmot.compiler import plan_cache
from rmot.compiler.frontend import load_program, load_text
from rmot.compiler.plan_cache import cached_plan, evict, plan_key
from rmot.compiler.plan_codec import CodecError, decode, encode

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = sorted(p for p in (ROOT / "examples").rglob("*.rmot")
                  if "program" in p.read_text(encoding="utf-8") and "lib" not in p.parts and "cells" not in p.parts)

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


def same(a: object, b: object, where: str = "plan") -> None:
    """Deep, field-by-field equality (compare=False fields too), arrays by dtype, shape, values, flags."""
    assert type(a) is type(b), f"{where}: {type(a).__name__} != {type(b).__name__}"
    if isinstance(a, np.ndarray):
        assert a.dtype == b.dtype and a.shape == b.shape, f"{where}: {a.dtype}{a.shape} != {b.dtype}{b.shape}"
        assert np.array_equal(a, b, equal_nan=a.dtype.kind in "fc"), f"{where}: values differ"
        assert a.flags.writeable == b.flags.writeable, f"{where}: writeable flag differs"
    elif dataclasses.is_dataclass(a):
        for f in dataclasses.fields(a):
            same(getattr(a, f.name), getattr(b, f.name), f"{where}.{f.name}")
    elif isinstance(a, (tuple, list)):
        assert len(a) == len(b), f"{where}: length {len(a)} != {len(b)}"
        for k, (x, y) in enumerate(zip(a, b)):
            same(x, y, f"{where}[{k}]")
    elif isinstance(a, dict):
        assert list(a) == list(b), f"{where}: keys differ"
        for k in a:
            same(a[k], b[k], f"{where}[{k!r}]")
    elif isinstance(a, float):
        assert (math.isnan(a) and math.isnan(b)) or (a == b and math.copysign(1, a) == math.copysign(1, b)), f"{where}: {a} != {b}"
    else:
        assert a == b, f"{where}: {a!r} != {b!r}"


@pytest.fixture
def cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    folder = tmp_path / "cache"
    monkeypatch.setenv("RMOT_CACHE_DIR", str(folder))
    return folder


def entries(folder: Path) -> list[Path]:
    return sorted(folder.glob("plans/*/*.npz"))


def _program(text: str = THREE, path: str = "three.rmot", **kw: object):  # type: ignore[no-untyped-def]
    front = load_text(text, path, require_program=True, **kw)  # type: ignore[arg-type]
    assert front.program is not None, front.diagnostics
    return front.program


@pytest.mark.slow
@pytest.mark.parametrize("example", EXAMPLES, ids=lambda p: str(p.relative_to(ROOT / "examples")))
def test_every_example_plan_round_trips_through_the_cache(example: Path) -> None:
    # the session's cache folder (tests/conftest.py): later tests of the same example hit it
    front = load_program(str(example), require_program=True)
    assert front.program is not None
    planned = cached_plan(front.program)
    key = plan_key(front.program, 0.004)
    path = plan_cache.cache_dir() / "plans" / key[:2] / f"{key}.npz"
    assert path.is_file()
    again = plan_cache._read(path, key)
    assert again is not None and again is not planned
    same(planned, again)
    doc, arrays = encode(planned)
    same(planned, decode(doc, arrays))
    # shared objects stay shared: each TaskPlan's task is the Program's task
    for tp, task in zip(again.tasks, again.program.tasks):
        assert tp.task is task


def test_second_run_reads_the_plan_and_does_not_plan(cache: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    program = _program()
    first = cached_plan(program)
    assert len(entries(cache)) == 1

    def boom(*args: object) -> None:
        raise AssertionError("planned again although the plan was cached")

    monkeypatch.setattr(plan_cache, "_plan", boom)
    second = cached_plan(_program())  # a fresh front-end run of the same text
    same(first, second)


def test_changed_byte_option_or_cell_misses(cache: Path, tmp_path: Path) -> None:
    base = plan_key(_program(), 0.004)
    assert plan_key(_program(), 0.004) == base  # deterministic
    assert plan_key(_program(THREE.replace("400 mm/s", "401 mm/s")), 0.004) != base
    assert plan_key(_program(THREE + "# a comment\n"), 0.004) != base  # any byte of the source
    assert plan_key(_program(), 0.008) != base  # the sampling step
    cell = (ROOT / "compiler" / "default_cell.rmot").read_text(encoding="utf-8")
    (tmp_path / "cell.rmot").write_text(cell, encoding="utf-8")
    explicit = plan_key(_program(path=str(tmp_path / "p.rmot"), cell=str(tmp_path / "cell.rmot")), 0.004)
    (tmp_path / "cell.rmot").write_text(cell + "\n# moved nothing, changed a byte\n", encoding="utf-8")
    assert plan_key(_program(path=str(tmp_path / "p.rmot"), cell=str(tmp_path / "cell.rmot")), 0.004) != explicit


def test_a_named_file_s_bytes_are_in_the_key(tmp_path: Path) -> None:
    # the URDF cell names a mesh and a URDF by path: changing either file's bytes changes the key
    shutil.copytree(ROOT / "examples" / "urdf_cell", tmp_path / "u")
    prog = tmp_path / "u" / "load_jig.rmot"
    key = plan_key(load_program(str(prog), require_program=True).program, 0.004)
    with open(tmp_path / "u" / "arm6.urdf", "a", encoding="utf-8") as f:
        f.write("\n<!-- one more byte -->\n")
    assert plan_key(load_program(str(prog), require_program=True).program, 0.004) != key
    key2 = plan_key(load_program(str(prog), require_program=True).program, 0.004)
    mesh = next((tmp_path / "u" / "meshes").iterdir())
    mesh.write_bytes(mesh.read_bytes() + b"\n")
    assert plan_key(load_program(str(prog), require_program=True).program, 0.004) != key2


@pytest.mark.parametrize("damage", ["truncate", "garbage", "empty", "wrong-key"])
def test_a_corrupt_entry_is_rebuilt(cache: Path, damage: str) -> None:
    program = _program()
    planned = cached_plan(program)
    (path,) = entries(cache)
    data = path.read_bytes()
    if damage == "truncate":
        path.write_bytes(data[: len(data) // 2])
    elif damage == "garbage":
        path.write_bytes(b"PK\x03\x04" + os.urandom(200))
    elif damage == "empty":
        path.write_bytes(b"")
    else:  # a valid entry read under another key: refused and removed
        key = path.stem
        assert plan_cache._read(path, "f" * 64) is None and not path.exists()
        cached_plan(program)
        assert plan_cache._read(path, key) is not None
        return
    rebuilt = cached_plan(program)
    same(planned, rebuilt)
    (again,) = entries(cache)
    assert plan_cache._read(again, again.stem) is not None  # written afresh, readable


def test_no_cache_never_reads_nor_writes(cache: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    def refuse(*args: object) -> None:
        raise AssertionError("the cache was touched")

    monkeypatch.setattr(plan_cache, "_read", refuse)
    monkeypatch.setattr(plan_cache, "_write", refuse)
    plan = cached_plan(_program(), use_cache=False)
    assert plan.tasks and not cache.exists()


def test_cli_no_cache_leaves_the_cache_folder_alone(cache: Path, tmp_path: Path) -> None:
    from rmot.compiler.cli import cli

    prog = tmp_path / "three.rmot"
    prog.write_text(THREE, encoding="utf-8")
    result = CliRunner().invoke(cli, ["check", "--no-cache", str(prog)])
    assert result.exit_code == 0, result.output
    assert not cache.exists()
    result = CliRunner().invoke(cli, ["check", str(prog)])
    assert result.exit_code == 0, result.output
    assert len(entries(cache)) == 1
    out = tmp_path / "out"
    fresh = CliRunner().invoke(cli, ["compile", str(prog), "--target", "rapid", "-o", str(out / "a"), "--no-cache"])
    cached = CliRunner().invoke(cli, ["compile", str(prog), "--target", "rapid", "-o", str(out / "b")])
    assert fresh.exit_code == cached.exit_code == 0, fresh.output + cached.output
    assert list((out / "a").rglob("*.mod")) and [p.read_bytes() for p in sorted((out / "a").rglob("*.*"))] == \
        [p.read_bytes() for p in sorted((out / "b").rglob("*.*"))]  # the cached plan emits the same bytes
    fresh = CliRunner().invoke(cli, ["plan", str(prog), "--no-cache", "--step", "8ms"])
    cached = CliRunner().invoke(cli, ["plan", str(prog), "--step", "8ms"])
    assert fresh.exit_code == cached.exit_code == 0 and fresh.output == cached.output and "cycle time" in fresh.output
    assert len(entries(cache)) == 2  # --step 8ms is another plan


def test_an_unwritable_cache_warns_w700_and_still_plans(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    blocker = tmp_path / "not-a-folder"
    blocker.write_text("x", encoding="utf-8")
    monkeypatch.setenv("RMOT_CACHE_DIR", str(blocker))
    plan = cached_plan(_program())
    assert plan.tasks
    assert [d.code.id for d in plan.diagnostics] == ["W700"]
    assert not plan.diagnostics[0].is_error


def test_cache_folder_follows_the_environment(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    monkeypatch.delenv("RMOT_CACHE_DIR", raising=False)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert plan_cache.cache_dir() == tmp_path / "xdg" / "rmot"
    monkeypatch.delenv("XDG_CACHE_HOME")
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    assert plan_cache.cache_dir() == tmp_path / "home" / ".cache" / "rmot"
    monkeypatch.setenv("RMOT_CACHE_DIR", str(tmp_path / "mine"))
    assert plan_cache.cache_dir() == tmp_path / "mine"


def test_evict_removes_least_recently_used_beyond_the_bound(tmp_path: Path) -> None:
    folder = tmp_path / "plans"
    for k in range(5):
        p = folder / f"{k:02d}" / f"{k:02d}{'a' * 62}.npz"
        p.parent.mkdir(parents=True)
        p.write_bytes(b"x" * 1000)
        os.utime(p, (1000 + k, 1000 + k))  # entry 0 is the oldest
    stale = folder / "00" / ".tmp-dead.npz"
    stale.write_bytes(b"x")
    os.utime(stale, (0, 0))
    assert evict(folder, 2500) == 4  # three entries and the stale temporary file
    assert sorted(p.name[:2] for p in folder.glob("*/*.npz")) == ["03", "04"]


def test_eviction_scans_at_most_once_per_interval(tmp_path: Path) -> None:
    """The full scan (a stat per entry) runs on the first write and then not again until the
    marker is _EVICT_EVERY_S old: a run of compiles does not pay it every time."""
    from rmot.compiler.plan_cache import _EVICT_EVERY_S, eviction_due

    folder = tmp_path / "plans"
    folder.mkdir()
    assert eviction_due(folder) is True
    assert eviction_due(folder) is False
    old = time.time() - _EVICT_EVERY_S - 1
    os.utime(folder / ".last-eviction", (old, old))
    assert eviction_due(folder) is True
    assert eviction_due(folder) is False


class _Foreign(enum.Enum):
    A = 1


@dataclasses.dataclass(frozen=True)
class _Stranger:
    x: int


@pytest.mark.parametrize("value", [_Foreign.A, _Stranger(1), object(), np.array([object()])])
def test_codec_refuses_types_outside_its_registry(value: object) -> None:
    with pytest.raises(CodecError):
        encode(value)


@pytest.mark.parametrize("doc", [
    {"$c": "os:system", "id": 0, "f": {}},
    {"$c": "builtins:object", "id": 0, "f": {}},
    {"$e": "tests:_Foreign", "v": "A"},
    {"$r": 7},
    {"$a": 3, "w": False},
    {"unknown": 1},
    {"$c": "rmot.lang.source:Pos", "id": 0, "f": {"line": 1}},  # a field missing: a stale entry
])
def test_codec_refuses_documents_it_did_not_write(doc: object) -> None:
    with pytest.raises(CodecError):
        decode(doc, [])


def test_codec_round_trips_plain_values() -> None:
    from rmot.lang import ir

    value = (1, -0.0, float("inf"), float("nan"), "s", None, True, [1, (2, 3)], {"k": (ir.Pose(),), 2: frozenset({1})},
             np.float32(1.5), np.arange(6, dtype=np.int16).reshape(2, 3), ir.MotionKind.LINEAR)
    doc, arrays = encode(value)
    same(value, decode(doc, arrays), "value")


def test_concurrent_runs_share_one_valid_entry(cache: Path, tmp_path: Path) -> None:
    import subprocess
    import sys

    prog = tmp_path / "three.rmot"
    prog.write_text(THREE, encoding="utf-8")
    cmd = [sys.executable, "-c", "import sys; from rmot.compiler.cli import main; sys.argv[0] = 'rmot'; main()",
           "check", "--format", "json", str(prog)]
    env = dict(os.environ, RMOT_CACHE_DIR=str(cache))
    runs = [subprocess.Popen(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) for _ in range(3)]
    outputs = [r.communicate() for r in runs]
    assert [r.returncode for r in runs] == [0, 0, 0], outputs
    assert len({out for out, _ in outputs}) == 1  # the same report, whoever wrote the entry
    (entry,) = entries(cache)  # one entry, no temporary file left behind
    assert not list(cache.glob("plans/*/.tmp-*"))
    assert plan_cache._read(entry, entry.stem) is not None
