"""Shared by the verify- and load-cache tests: run the CLI from a project folder (relative
paths, as a user types them) and count how often a stage really runs."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import pytest
from click.testing import CliRunner, Result

from rmot.compiler.cli import cli


class Counter:
    def __init__(self) -> None:
        self.calls = 0


def count_calls(monkeypatch: pytest.MonkeyPatch, module: Any, name: str) -> Counter:
    """Replace module.name by a wrapper that counts its calls, then calls the original."""
    counter = Counter()
    real = getattr(module, name)

    def counted(*args: object, **kwargs: object) -> object:
        counter.calls += 1
        return real(*args, **kwargs)

    monkeypatch.setattr(module, name, counted)
    return counter


def run(project: Path, *args: str) -> Result:
    """`rmot ARGS` with `project` as the working directory."""
    cwd = os.getcwd()
    os.chdir(project)
    try:
        return CliRunner().invoke(cli, list(args))
    finally:
        os.chdir(cwd)


def entry_json(path: Path) -> Any:
    """The JSON document a sealed cache entry holds (lang/cache_seal.py: MAGIC, MAC line, payload)."""
    import json

    from rmot.lang.cache_seal import MAGIC

    data = path.read_bytes()
    assert data.startswith(MAGIC)
    return json.loads(data[data.index(b"\n", len(MAGIC)) + 1:])


def write_sealed(path: Path, key: str, doc: Any) -> None:
    """`doc` stored at `path` as a validly sealed entry of `key`: what it holds is then
    checked by the reader's decoding, not stopped by the MAC."""
    import json

    from rmot.lang.cache_seal import seal

    sealed = seal(key, json.dumps(doc).encode("utf-8"))
    assert sealed is not None
    path.write_bytes(sealed)
