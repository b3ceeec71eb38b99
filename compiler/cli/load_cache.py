"""The front end's result for a program already planned: taken from the plan cache, not
recomputed, when no file it read has changed.

`rmot check` then `rmot compile` of the same program: the second command would parse, check
and lower the program again (~0.2 s, most of a small program's cached compile) only to compute
the key of the plan it then reads from the cache. This module remembers, per invocation (the
program's path as given and resolved, --cell, --project-root, the working directory, rmot's
own files), the plan's key and the front end's diagnostics, with the SHA-256 of every file the
front end and the verification read: the program, its imports, the cell (FrontendResult.sources),
the files the program names by absolute path (URDFs, meshes) and a URDF robot's meshes. On the
next run, if every one of those files still has the same resolved path and bytes, the program
is the cached Plan's own (the plan codec stores the whole checked ir.Program) and the front end
is skipped; any change, a missing plan entry, or a damaged entry: the front end runs as always.

    result = load_cache.load(path, cell=..., project_root=..., require_program=True)
    plan = load_cache.planned(result.program)    # the cached Plan, or None
    load_cache.record(result.program, plan)      # after planning a program load() computed

Only an error-free front-end result is stored (its warnings with it, as the plan codec's JSON:
no pickle). Entries: <cache dir>/load/<k[:2]>/<key>.json, written atomically (temporary file
+ rename) and sealed with an HMAC bound to the key (lang/cache_seal.py); an entry that is not
this cache's, not a regular file or larger than MAX_BYTES is a miss, a damaged one is removed,
and the front end runs.
"""

from __future__ import annotations

import hashlib
import json
import os
import time
from pathlib import Path
from typing import TYPE_CHECKING, Any

from rmot.lang.input_file import MAX_STAMPED_BYTES, read_regular
from rmot.lang.diagnostics import Diagnostic
from rmot.lang.cache_seal import read_sealed

if TYPE_CHECKING:
    from rmot.lang import ir
    from rmot.compiler.frontend import FrontendResult
    from rmot.lang.plan_types import Plan

__all__ = ["FORMAT", "load", "load_key", "planned", "record"]

FORMAT = "rmot-load-cache/1"
MAX_BYTES = 50 * 1024 * 1024
# the program a load() in this process gave: (program, its Plan) when read from the cache,
# (program, entry key, result) when computed; one program at a time (each load() resets them)
_READ: dict[int, tuple[ir.Program, Plan]] = {}
_COMPUTED: dict[int, tuple[ir.Program, str, FrontendResult, float]] = {}


def load(path: str, *, cell: str | None = None, project_root: str | None = None,
         require_program: bool = True) -> FrontendResult:
    """frontend.load_program(path, ...), or the same result rebuilt from the caches."""
    from rmot.compiler import frontend  # late: tests replace it (monkeypatch): read at call time

    _READ.clear()
    _COMPUTED.clear()
    try:
        key = load_key(path, cell, project_root, require_program)
    except OSError:
        key = None
    if key is not None:
        hit = _read(_entry_path(key), key)
        if hit is not None:
            result, plan = hit
            assert result.program is not None
            _READ[id(result.program)] = (result.program, plan)
            return result
    started = time.time()
    result = frontend.load_program(path, cell=cell, project_root=project_root,
                                   require_program=require_program)
    if key is not None and result.program is not None and not result.has_errors:
        _COMPUTED[id(result.program)] = (result.program, key, result, started)
    return result


def planned(program: ir.Program) -> Plan | None:
    """The cached Plan whose program load() returned, or None."""
    known = _READ.pop(id(program), None)
    return known[1] if known is not None and known[0] is program else None


def record(program: ir.Program, plan: Plan) -> None:
    """Remember the load() that computed `program` and the key of its `plan` (never raises for
    an unwritable folder or a value the codec does not encode: the next run loads afresh)."""
    from rmot.compiler import plan_cache  # late: tests replace it (monkeypatch): read at call time

    pending = _COMPUTED.pop(id(program), None)
    plan_key = plan_cache.key_of(plan)
    if pending is None or pending[0] is not program or plan_key is None:
        return
    _, key, result, started = pending
    try:
        _write(_entry_path(key), key, plan_key, result, plan, started)
        folder = _entry_path(key).parent.parent
        if plan_cache.eviction_due(folder):
            plan_cache.evict(folder, MAX_BYTES, suffix=".json")
    except (OSError, ValueError):  # CodecError is a ValueError
        pass


def load_key(path: str, cell: str | None, project_root: str | None, require_program: bool) -> str:
    """The hex SHA-256 of one invocation of the front end (module doc)."""
    from rmot.compiler.plan_cache import source_digest  # late: loads numpy only when this runs

    parts = [FORMAT, source_digest(), os.getcwd(), path, os.path.abspath(path),
             os.path.realpath(path), "" if cell is None else cell,
             "" if cell is None else os.path.realpath(cell),
             "" if project_root is None else os.path.abspath(project_root),
             str(bool(require_program))]
    h = hashlib.sha256()
    for part in parts:
        h.update(part.encode("utf-8", "surrogateescape") + b"\0")
    return h.hexdigest()


def _entry_path(key: str) -> Path:
    from rmot.compiler.plan_cache import cache_dir  # late: loads numpy only when this runs

    return cache_dir() / "load" / key[:2] / f"{key}.json"


def _stamp(path: str) -> list[Any]:
    """[path, its resolved path, SHA-256 of its bytes or None]."""
    try:
        digest: str | None = hashlib.sha256(read_regular(path, MAX_STAMPED_BYTES)).hexdigest()
    except OSError:
        digest = None
    return [path, os.path.realpath(path), digest]


def _write(entry: Path, key: str, plan_key: str, result: FrontendResult, plan: Plan,
           started: float) -> None:
    from rmot.compiler.cli.verify_cache import scene_files  # late: loads coal only when this runs
    from rmot.compiler.plan_cache import _named_files, settled  # late: loads numpy only when this runs
    from rmot.compiler.plan_codec import encode  # late: loads numpy only when this runs

    if not result.sources:
        raise ValueError("the front end did not say which files it read")
    program_doc, _ = encode(result.program)
    files = sorted({*result.sources, *_named_files(program_doc), *scene_files(plan)})
    if not settled(files, started):
        return  # a file changed while (or just before) the front end read it: no entry
    doc, arrays = encode(tuple(result.diagnostics))
    if arrays:
        raise ValueError("diagnostics hold no arrays")
    data = json.dumps({"format": FORMAT, "key": key, "plan": plan_key,
                       "files": [_stamp(p) for p in files], "sources": list(result.sources),
                       "doc": doc}, separators=(",", ":"), allow_nan=False).encode("utf-8")
    from rmot.compiler.plan_cache import write_entry  # late: loads numpy only when this runs

    write_entry(entry, key, data)


def _read(entry: Path, key: str) -> tuple[FrontendResult, Plan] | None:
    from rmot.compiler import plan_cache  # late: tests replace it (monkeypatch): read at call time
    from rmot.compiler.frontend import FrontendResult  # late: loads coal only when this runs
    from rmot.compiler.plan_codec import CodecError, decode  # late: loads numpy only when this runs


    data = read_sealed(entry, key, MAX_BYTES)
    if data is None:  # missing, foreign, tampered with, not a bounded regular file: a miss
        return None
    try:
        doc = json.loads(data.decode("utf-8"))
        if not isinstance(doc, dict) or doc.get("format") != FORMAT or doc.get("key") != key:
            raise CodecError("an entry of another format or key")
        for stamp in doc["files"]:
            if not (isinstance(stamp, list) and len(stamp) == 3 and isinstance(stamp[0], str)):
                raise CodecError("a malformed file list")
            if _stamp(stamp[0]) != stamp:
                return None  # a file the front end or the verification read has changed
        diagnostics = decode(doc["doc"], [])
        sources = doc["sources"]
        if not (isinstance(diagnostics, tuple) and all(type(d) is Diagnostic for d in diagnostics)
                and not any(d.is_error for d in diagnostics)
                and isinstance(sources, list) and all(isinstance(s, str) for s in sources)
                and isinstance(doc["plan"], str)):
            raise CodecError("the entry does not hold a front-end result")
    except (ValueError, KeyError, TypeError, AttributeError, IndexError, RecursionError):
        _remove(entry)
        return None
    plan = plan_cache.plan_by_key(doc["plan"])
    if plan is None:
        return None  # the plan was evicted or damaged: the front end runs, and planning
    program = plan.program
    return FrontendResult(program, program.cell, diagnostics, tuple(sources)), plan


def _remove(path: Path) -> None:
    try:
        path.unlink()
    except OSError:
        pass
