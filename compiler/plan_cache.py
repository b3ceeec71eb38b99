"""One plan per program: a content-addressed cache of Plans shared by check, compile, render, plan.

    from rmot.compiler.plan_cache import cached_plan
    plan = cached_plan(front.program, step=0.004, use_cache=not no_cache)

The key (SHA-256) covers everything the plan is a function of:
- the checked ir.Program, encoded by the plan codec — it holds the text of every source file
  the front end read (program, imports, cell: each Span keeps its SourceFile), the cell, the
  robots' load keys (library name, URDF path, or a cell model's full parameters, its link
  masses and motor ratings included); the tools' and parts' masses, which the timing's joint
  torque limits depend on, are fields of the program;
- the bytes of every file the program names by absolute path (URDFs, meshes, a URDF chain's file);
- a digest of rmot's own files (code, robot library, grammar, data), so any change to the
  compiler invalidates every entry (rmot's version number adds nothing to it: a release with
  the same files plans the same);
- the planning options (the sampling step).

Entries live in the user's cache directory, never beside the program: $RMOT_CACHE_DIR, else
$XDG_CACHE_HOME/rmot, else ~/.cache/rmot; one file per plan, plans/<k[:2]>/<key>.npz (JSON
document + arrays, read with allow_pickle=False: no pickle anywhere). Writes go to a temporary
file in the same folder and are renamed into place (atomic, safe under concurrent runs: two
runs writing the same key write the same bytes). Every entry is sealed with an HMAC bound to
its key (lang/cache_seal.py): an entry that is not this cache's for this key, is not a regular
file, exceeds MAX_ENTRY_BYTES, cannot be read, is truncated or was written by another version
is a miss and is rebuilt, never an error. The cache is bounded
(MAX_BYTES): after a write the least recently used entries beyond it are removed.
A directory that cannot be written gives warning W700 in the plan's diagnostics.
"""

from __future__ import annotations

import dataclasses
import functools
import hashlib
import importlib.util
import io
import json
import os
import tempfile
import time
import weakref
import zipfile
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from rmot.compiler.plan_codec import CodecError, decode, encode
from rmot.lang.cache_seal import cache_dir, read_sealed, seal  # one cache directory: lang's, the stage upstream
from rmot.lang.input_file import MAX_STAMPED_BYTES, read_regular
from itertools import islice
from rmot.lang.ir_tree import walk_bodies
from rmot.lang import cache_codes
from rmot.lang.diagnostics import Diagnostic, Severity
from rmot.lang.plan_types import Plan

if TYPE_CHECKING:
    from rmot.lang import ir
    from rmot.lang.plan_types import Plan

__all__ = [
    "MAX_BYTES", "cache_dir", "cached_plan", "evict", "eviction_due", "key_of", "plan_by_key",
    "plan_key", "SETTLE_S", "settled", "source_digest", "write_entry",
]

FORMAT = "rmot-plan-cache/1"
MAX_BYTES = 500 * 1024 * 1024  # bound on the plans folder; least recently used entries go first
MAX_ENTRY_BYTES = 256 * 1024 * 1024  # bound on one plan entry read back: a larger file is a miss
_PACKAGES = ("rmot.lang", "rmot.compiler", "rmot.backends", "rmot.sim")
_KEY_PREFIXES = ("urdf-chain:",)  # load keys that carry a JSON list holding a file path
_STALE_TEMP_S = 3600.0
# A full scan costs a stat per entry (~1,300 in a full cache: a third of a small program's
# compile in a fuzz run), so it runs at most once per this many seconds per cache; between
# scans the folder may exceed MAX_BYTES by what is written in that time.
_EVICT_EVERY_S = 30.0
# the content key of each Plan cached_plan returned in this process (the verification cache,
# compiler/cli/verify_cache.py, keys its entries by it); weak: a Plan is not kept alive by it
_KEYS: weakref.WeakKeyDictionary[Plan, str] = weakref.WeakKeyDictionary()


def key_of(plan: Plan) -> str | None:
    """The content key of `plan` if cached_plan returned it in this process, else None (a plan
    made with use_cache=False, or from a program the codec does not encode)."""
    return _KEYS.get(plan)


def plan_by_key(key: str) -> Plan | None:
    """The Plan cached under `key` (a key plan_key gave for the default step), or None."""
    if len(key) != 64 or any(c not in "0123456789abcdef" for c in key):
        return None
    plan = _read(cache_dir() / "plans" / key[:2] / f"{key}.npz", key)
    if plan is not None:
        _KEYS[plan] = key
    return plan


# A program of more instructions than this (each loop iteration counted) is planned without
# the caches: its key and entries cost more than its planning (100,000 moves: the front end
# 15 s, the plan 2 s, encoding the key and the plan and load entries 100 s more).
MAX_CACHED_INSTRUCTIONS = 20_000


def cacheable(program: ir.Program) -> bool:
    """True when `program` holds at most MAX_CACHED_INSTRUCTIONS instructions."""


    every = walk_bodies(task.body for task in program.tasks)
    return sum(1 for _ in islice(every, MAX_CACHED_INSTRUCTIONS + 1)) <= MAX_CACHED_INSTRUCTIONS


def cached_plan(program: ir.Program, *, step: float = 0.004, use_cache: bool = True) -> Plan:
    """plan_program(program, step=step), read from the cache when the same inputs were planned
    (a program too large to be worth caching is planned afresh, and no entry names it)."""
    if not use_cache or not cacheable(program):
        return _plan(program, step)
    try:
        key = plan_key(program, step)
    except (CodecError, OSError):  # a value the codec does not know: plan without the cache
        return _plan(program, step)
    path = cache_dir() / "plans" / key[:2] / f"{key}.npz"
    plan = _read(path, key)
    if plan is not None:
        _KEYS[plan] = key
        return plan
    plan = _plan(program, step)
    try:
        _write(path, key, plan)
    except CodecError:
        return plan
    except OSError as exc:
        plan = _with_warning(plan, path.parent.parent.parent, exc)
        _KEYS[plan] = key
        return plan
    _KEYS[plan] = key
    try:
        if eviction_due(path.parent.parent):
            evict(path.parent.parent, MAX_BYTES)
    except OSError:
        pass
    return plan


def _plan(program: ir.Program, step: float) -> Plan:
    from rmot.compiler.plan import plan_program  # late: tests replace it (monkeypatch): read at call time

    return plan_program(program, step=step)


def _with_warning(plan: Plan, folder: Path, exc: OSError) -> Plan:

    msg = (f"plan cache directory '{folder}' must be writable (got {exc.strerror or exc}); "
           "set RMOT_CACHE_DIR or pass --no-cache")
    note = Diagnostic(cache_codes.CACHE_UNWRITABLE, Severity.WARNING, msg, None)
    return dataclasses.replace(plan, diagnostics=plan.diagnostics + (note,))


# ---------------------------------------------------------------------------- the key
def plan_key(program: ir.Program, step: float) -> str:
    """The hex SHA-256 of everything the plan of `program` depends on (see the module doc)."""
    h = hashlib.sha256()
    doc, arrays = encode(program)
    text = json.dumps(doc, sort_keys=True, separators=(",", ":"), allow_nan=False)
    for part in (FORMAT, source_digest(), float(step).hex()):
        h.update(part.encode() + b"\0")
    h.update(text.encode())
    for a in arrays:
        h.update(f"{a.dtype.str}{a.shape}".encode())
        h.update(np.ascontiguousarray(a).tobytes())
    for path in sorted(_named_files(doc)):
        h.update(b"\0file\0" + path.encode() + b"\0")
        try:
            h.update(hashlib.sha256(read_regular(path, MAX_STAMPED_BYTES)).digest())
        except OSError:
            h.update(b"<unreadable>")
    return h.hexdigest()


def _named_files(doc: Any) -> set[str]:
    """Absolute paths of existing files among the strings of a document (and of load keys)."""
    found: set[str] = set()
    stack = [doc]
    while stack:
        v = stack.pop()
        if isinstance(v, str):
            if v.startswith(_KEY_PREFIXES):
                try:
                    stack.append(json.loads(v.split(":", 1)[1]))
                except ValueError:
                    pass
            elif 1 < len(v) < 4096 and "\n" not in v and os.path.isabs(v) and os.path.isfile(v):
                found.add(v)
        elif isinstance(v, dict):
            stack.extend(v.values())
        elif isinstance(v, list):
            stack.extend(v)
    return found


# A file modified less than this before a command started is not vouched for by a cache entry:
# its bytes read after planning may not be the bytes the front end read ("racy git").
SETTLE_S = 2.0


def settled(paths: list[str], started: float) -> bool:
    """Whether no file of `paths` was modified since SETTLE_S before `started` (a missing
    file counts as settled: its stamp says missing, and its appearing is a change)."""
    for path in paths:
        try:
            if os.stat(path).st_mtime >= started - SETTLE_S:
                return False
        except OSError:
            continue
    return True


@functools.cache
def source_digest() -> str:
    """SHA-256 over rmot's own files (every file of its four packages but bytecode), once a process.

    Reading and hashing them all took ~0.1 s of every cached command, so the digest is kept in
    the cache folder (source/<stamp>) under a stamp of every file's path, size and modification
    time: a changed file changes the stamp, and the contents are hashed again."""
    files = _source_files()
    stamp = hashlib.sha256()
    for name, path in files:
        st = path.stat()
        stamp.update(f"{name}\0{st.st_size}\0{st.st_mtime_ns}\0".encode())
    memo = cache_dir() / "source" / stamp.hexdigest()
    sealed = read_sealed(memo, "source:" + memo.name, 64)
    known = sealed.decode("ascii", "replace") if sealed is not None else ""
    if len(known) == 64 and all(c in "0123456789abcdef" for c in known):
        return known
    h = hashlib.sha256()
    for name, path in files:
        h.update(f"{name}\0".encode())
        h.update(hashlib.sha256(path.read_bytes()).digest())
    digest = h.hexdigest()
    try:
        write_entry(memo, "source:" + memo.name, digest.encode("ascii"))
    except OSError:
        pass  # an unwritable cache folder: hashed again next time
    return digest


def _source_files() -> list[tuple[str, Path]]:
    """(package/relative path, path) of rmot's own files, sorted by that name.

    os.walk, not Path.rglob: every cached command lists these ~190 files, and rglob took
    9-19 ms of a 0.3 s cached compile, os.walk about a tenth of that."""
    out: list[tuple[str, Path]] = []
    for package in _PACKAGES:
        spec = importlib.util.find_spec(package)
        for root in (spec.submodule_search_locations or []) if spec else []:
            for folder, dirs, names in os.walk(root):
                dirs[:] = [d for d in dirs if d != "__pycache__"]
                rel = os.path.relpath(folder, root).replace(os.sep, "/")
                prefix = f"{package}/" if rel == "." else f"{package}/{rel}/"
                out.extend((prefix + name, Path(folder, name)) for name in names
                           if not name.endswith(".pyc") and os.path.isfile(os.path.join(folder, name)))
    out.sort(key=lambda entry: entry[0])
    return out


# ---------------------------------------------------------------------------- entries
def _read(path: Path, key: str) -> Plan | None:
    """The Plan stored under `path`, or None (a missing, corrupt or foreign entry is removed)."""

    payload = read_sealed(path, key, MAX_ENTRY_BYTES)
    if payload is None:  # missing, foreign, tampered with, not a bounded regular file: a miss
        if os.path.lexists(path):
            _remove(path)
        return None
    try:
        with np.load(io.BytesIO(payload), allow_pickle=False) as z:
            meta = json.loads(bytes(z["__meta__"]).decode("utf-8"))
            if meta.get("format") != FORMAT or meta.get("key") != key:
                raise CodecError("an entry of another format or key")
            arrays = [z[f"a{i}"] for i in range(int(meta["arrays"]))]
        plan = decode(meta["doc"], arrays)
        if not isinstance(plan, Plan):
            raise CodecError("the entry does not hold a Plan")
    except (OSError, ValueError, KeyError, TypeError, EOFError, zipfile.BadZipFile, CodecError, UnicodeDecodeError,
            RecursionError):
        _remove(path)
        return None
    try:
        os.utime(path)  # recently used: evicted last
    except OSError:
        pass
    return plan


def _write(path: Path, key: str, plan: Plan) -> None:
    doc, arrays = encode(plan)
    meta = json.dumps({"format": FORMAT, "key": key, "arrays": len(arrays), "doc": doc},
                      separators=(",", ":"), allow_nan=False).encode("utf-8")
    buffer = io.BytesIO()
    members: dict[str, Any] = {"__meta__": np.frombuffer(meta, dtype=np.uint8)}
    members.update({f"a{i}": a for i, a in enumerate(arrays)})
    np.savez(buffer, **members)
    write_entry(path, key, buffer.getvalue())


def write_entry(path: Path, key: str, data: bytes) -> None:
    """A cache entry sealed under `key` (lang/cache_seal.py) written atomically: a temporary
    `.tmp-*` file beside it (evict removes those a killed run left), renamed onto it. Not
    lang/atomic.py: an entry is not the user's output, so no fsync (a torn entry is
    detected and rebuilt) and no umask mode (the cache is the user's own; mkstemp's 0600).
    Nothing is written when the cache has no secret (it could never be read back)."""
    sealed = seal(key, data)
    if sealed is None:
        raise OSError("the cache's secret can be neither read nor created")
    data = sealed
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=".tmp-", suffix=path.suffix, dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        os.replace(tmp, path)
    except BaseException:
        _remove(Path(tmp))
        raise


def _remove(path: Path) -> None:
    try:
        path.unlink()
    except OSError:
        pass


def eviction_due(folder: Path) -> bool:
    """True at most once per _EVICT_EVERY_S (a marker file's mtime, touched when it is)."""
    marker = folder / ".last-eviction"
    try:
        if time.time() - marker.stat().st_mtime < _EVICT_EVERY_S:
            return False
    except FileNotFoundError:
        pass
    marker.touch()
    return True


def evict(folder: Path, max_bytes: int, suffix: str = ".npz") -> int:
    """Remove the least recently used entries (files `*/*<suffix>`) until the folder holds at
    most max_bytes; also temporary files left by killed runs. Returns the number removed."""
    entries = []
    removed = 0
    now = time.time()
    for path in Path(folder).glob(f"*/*{suffix}"):
        try:
            st = path.stat()
        except OSError:
            continue
        if path.name.startswith(".tmp-"):
            if now - st.st_mtime > _STALE_TEMP_S:
                _remove(path)
                removed += 1
            continue
        entries.append((st.st_mtime, st.st_size, path))
    total = sum(size for _, size, _ in entries)
    for _, size, path in sorted(entries):
        if total <= max_bytes:
            break
        _remove(path)
        total -= size
        removed += 1
    return removed
