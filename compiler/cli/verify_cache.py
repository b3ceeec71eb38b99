"""One verification per plan: the verification Report of a cached Plan, cached beside it.

    from rmot.compiler.cli.verify_cache import cached_verify
    report = cached_verify(plan, clearance=None)      # stages.verify calls this

`rmot check` then `rmot compile` (or `report`, `render`) of the same program plan once
(compiler/plan_cache.py) and, with this module, verify once: the findings are stored as plain
JSON (the plan codec's document, compiler/plan_codec.py: dataclasses and enums of an explicit
registry only, no pickle anywhere) and restored as the same Diagnostic values, so they render
byte for byte as freshly computed ones (file:line:col, message, the source line and caret).

The key (SHA-256) covers everything the verification is a function of:
- the plan's content key (plan_cache.key_of: every input file's bytes, the cell, the robots'
  load keys, a digest of rmot's own files, the planning options) -- only a Plan that came
  through the plan cache in this process has one; any other Plan (--no-cache, a value the
  codec does not encode) is verified afresh and nothing is stored;
- the verification options (--clearance), and the format of this cache;
- the installed numeric libraries the verification runs on (numpy, pinocchio, coal, numba):
  the size and modification time of each one's package file, found without importing it.
The files the scene reads that are not in the program (a URDF robot's collision meshes, and
the cell's meshes again) are listed in the entry with their SHA-256 (or null when missing) and
hashed again on every read: any change is a miss. A mesh modified within 2 s before the
verification started gets no entry (plan_cache.settled: its bytes hashed after verifying may
not be the bytes the scene read).

Entries: <cache dir>/verify/<k[:2]>/<key>.json (the cache directory of lang/_tables.py), written
to a temporary file in the same folder and renamed into place (atomic; safe under concurrent
runs), sealed with an HMAC bound to the key (lang/cache_seal.py). An entry that is not this
cache's for this key, not a regular file or over MAX_ENTRY_BYTES is a miss and is rebuilt; one
that cannot be decoded is removed and rebuilt, never an error. The folder is bounded (MAX_BYTES, least
recently used first). The plan's own diagnostics are not stored: they are taken from the Plan
at hand, so a cached entry never repeats a warning of the run that wrote it (W700).
"""

from __future__ import annotations

import dataclasses
import hashlib
import importlib.util
import json
import os
import time
from pathlib import Path
from typing import TYPE_CHECKING, Any

from rmot.lang.input_file import MAX_STAMPED_BYTES, read_regular
from rmot.lang.cache_seal import read_sealed
from rmot.lang.diagnostics import Diagnostic

if TYPE_CHECKING:
    from rmot.lang import ir
    from rmot.lang.plan_types import Plan
    from rmot.sim.report import Report

__all__ = ["FORMAT", "MAX_BYTES", "cached_verify", "entry_path", "scene_files", "verify_key"]

FORMAT = "rmot-verify-cache/1"
MAX_BYTES = 100 * 1024 * 1024  # bound on the verify folder; least recently used entries go first
MAX_ENTRY_BYTES = 16 * 1024 * 1024  # bound on one entry read back: a larger file is a miss
_LIBRARIES = ("numpy", "pinocchio", "coal", "numba")


def cached_verify(plan: Plan, *, clearance: float | None = None, use_cache: bool = True) -> Report:
    """sim.verify(plan, clearance=clearance), read from the cache when this plan (by content)
    was verified with the same options before."""
    from rmot.compiler import plan_cache  # late: tests replace it (monkeypatch): read at call time

    plan_key = plan_cache.key_of(plan) if use_cache else None
    if plan_key is None:
        return _verify(plan, clearance)
    key = verify_key(plan_key, clearance)
    path = entry_path(key)
    report = _read(path, key, plan)
    if report is not None:
        return report
    started = time.time()
    report = _verify(plan, clearance)
    try:
        _write(path, key, plan, report, started)
    except (OSError, ValueError):  # an unwritable folder (W700 came with the plan), a value not encoded
        return report
    try:
        if plan_cache.eviction_due(path.parent.parent):
            plan_cache.evict(path.parent.parent, MAX_BYTES, suffix=".json")
    except OSError:
        pass
    return report


def _verify(plan: Plan, clearance: float | None) -> Report:
    from rmot.sim.verification import verify  # late: tests replace it (monkeypatch): read at call time

    return verify(plan, clearance=clearance)


def verify_key(plan_key: str, clearance: float | None) -> str:
    """The hex SHA-256 of the plan's key, the options and the numeric libraries (module doc)."""
    h = hashlib.sha256()
    option = "none" if clearance is None else float(clearance).hex()
    for part in (FORMAT, plan_key, f"clearance={option}", _libraries()):
        h.update(part.encode("utf-8") + b"\0")
    return h.hexdigest()


def entry_path(key: str) -> Path:
    from rmot.compiler.plan_cache import cache_dir  # late: loads numpy only when this runs

    return cache_dir() / "verify" / key[:2] / f"{key}.json"


def _libraries() -> str:
    """name:size:mtime of each numeric library's package file (no import: find_spec only)."""
    parts = []
    for name in _LIBRARIES:
        try:
            spec = importlib.util.find_spec(name)
            origin = spec.origin if spec is not None else None
            st = os.stat(origin) if origin else None
        except (ImportError, ValueError, OSError):
            st = None
        parts.append(f"{name}:{st.st_size}:{st.st_mtime_ns}" if st else f"{name}:-")
    return ",".join(parts)


# ---------------------------------------------------------------------------- files read
def scene_files(plan: Plan) -> list[str]:
    """Absolute paths of the mesh files the verification's scene reads: every ir.Mesh of the
    cell (fixtures, tools, parts) and every mesh solid of its robots (a URDF's meshes)."""
    from rmot.lang import ir  # late: tests replace it (monkeypatch): read at call time

    found: set[str] = set()
    stack: list[Any] = [plan.program.cell]
    seen: set[int] = set()
    while stack:
        v = stack.pop()
        if isinstance(v, ir.Mesh):
            found.add(os.path.abspath(v.path))
        elif isinstance(v, (tuple, list)):
            stack.extend(v)
        elif dataclasses.is_dataclass(v) and not isinstance(v, type) and id(v) not in seen:
            seen.add(id(v))
            stack.extend(getattr(v, f.name) for f in dataclasses.fields(v) if f.name != "span")
    for path in _robot_meshes(plan.program.cell):
        found.add(path)
    return sorted(found)


def _robot_meshes(cell: ir.Cell) -> list[str]:
    from rmot.lang import ir  # late: tests replace it (monkeypatch): read at call time
    from rmot.sim.robots import load_robot  # late: loads coal only when this runs

    out = []
    for inst in cell.robots:
        try:  # loaded already by the verification that just ran (load_robot caches per key)
            robot = load_robot(inst.source.load_key)
        except Exception:  # a robot that does not load is a finding of the report
            continue
        out += [os.path.abspath(s.geometry.path) for s in robot.solids if isinstance(s.geometry, ir.Mesh)]
    return out


def _digest(path: str) -> str | None:
    try:
        return hashlib.sha256(read_regular(path, MAX_STAMPED_BYTES)).hexdigest()
    except OSError:
        return None


# ---------------------------------------------------------------------------- entries
def _write(path: Path, key: str, plan: Plan, report: Report, started: float) -> None:
    from rmot.compiler.plan_cache import settled  # late: loads numpy only when this runs
    from rmot.compiler.plan_codec import encode  # late: loads numpy only when this runs

    n = len(plan.diagnostics)
    if tuple(report.diagnostics[:n]) != tuple(plan.diagnostics):
        raise ValueError("the report does not start with the plan's diagnostics")
    value = (report.program_file, report.cycle_times, tuple(report.diagnostics[n:]), report.tasks)
    doc, arrays = encode(value)  # CodecError is a ValueError
    if arrays:
        raise ValueError("a report holds no arrays")
    paths = scene_files(plan)
    if not settled(paths, started):
        return  # a mesh changed while (or just before) the scene read it: no entry
    files = [[p, _digest(p)] for p in paths]
    data = json.dumps({"format": FORMAT, "key": key, "files": files, "doc": doc},
                      separators=(",", ":"), allow_nan=False).encode("utf-8")
    from rmot.compiler.plan_cache import write_entry  # late: loads numpy only when this runs

    write_entry(path, key, data)


def _read(path: Path, key: str, plan: Plan) -> Report | None:
    """The Report stored under `path` for `plan`, or None (missing, stale or damaged: a damaged
    or foreign entry is removed; a stale one is overwritten by the caller)."""
    from rmot.compiler.plan_codec import CodecError, decode  # late: loads numpy only when this runs


    data = read_sealed(path, key, MAX_ENTRY_BYTES)
    if data is None:  # missing, foreign, tampered with, not a bounded regular file: a miss
        return None
    try:
        entry = json.loads(data.decode("utf-8"))
        if not isinstance(entry, dict) or entry.get("format") != FORMAT or entry.get("key") != key:
            raise CodecError("an entry of another format or key")
        for name, digest in entry["files"]:
            if not isinstance(name, str) or _digest(name) != digest:
                return None  # a mesh the scene reads changed: verify again
        report = _report(decode(entry["doc"], []), plan)
    except (ValueError, KeyError, TypeError, AttributeError, IndexError, RecursionError):
        # CodecError, JSONDecodeError and UnicodeDecodeError are ValueErrors
        _remove(path)
        return None
    try:
        os.utime(path)  # recently used: evicted last
    except OSError:
        pass
    return report


def _report(value: Any, plan: Plan) -> Report:
    """The Report of a decoded entry; TypeError when it is not the shape _write stores."""
    from rmot.sim.report import Report  # late: loads numpy only when this runs

    program_file, cycle_times, diagnostics, tasks = value
    if not (isinstance(program_file, str) and isinstance(cycle_times, dict)
            and all(isinstance(k, str) and isinstance(t, float) for k, t in cycle_times.items())
            and isinstance(diagnostics, tuple) and all(type(d) is Diagnostic for d in diagnostics)
            and (tasks is None or isinstance(tasks, tuple) and all(isinstance(t, dict) for t in tasks))):
        raise TypeError("the entry does not hold a report")
    return Report(program_file, cycle_times, tuple(plan.diagnostics) + diagnostics, tasks)


def _remove(path: Path) -> None:
    try:
        path.unlink()
    except OSError:
        pass
