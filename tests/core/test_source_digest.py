"""The plan cache's digest of rmot's own files, memoised in the cache folder by a stamp of the
files' sizes and modification times: the memo never changes the digest."""

from __future__ import annotations

import hashlib
from pathlib import Path

import pytest

from rmot.compiler import plan_cache


def _direct() -> str:
    h = hashlib.sha256()
    for name, path in plan_cache._source_files():
        h.update(f"{name}\0".encode() + hashlib.sha256(path.read_bytes()).digest())
    return h.hexdigest()


def _fresh(monkeypatch: pytest.MonkeyPatch, folder: Path) -> str:
    monkeypatch.setenv("RMOT_CACHE_DIR", str(folder))
    plan_cache.source_digest.cache_clear()
    try:
        return plan_cache.source_digest()
    finally:
        plan_cache.source_digest.cache_clear()


def test_the_memo_gives_the_digest_of_the_files(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    first = _fresh(monkeypatch, tmp_path)  # computed and written
    memos = list((tmp_path / "source").iterdir())
    assert len(memos) == 1 and memos[0].read_bytes().endswith(b"\n" + first.encode()) and first == _direct()
    assert _fresh(monkeypatch, tmp_path) == first  # read back


@pytest.mark.parametrize("bad", ["", "zz" * 32, "0" * 63, "\x00\x01"])
def test_a_damaged_memo_is_recomputed(bad: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    _fresh(monkeypatch, tmp_path)
    memo = next((tmp_path / "source").iterdir())
    memo.write_text(bad, encoding="latin-1")
    assert _fresh(monkeypatch, tmp_path) == _direct()


def test_the_stamp_follows_every_file(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Any file's size or time in the stamp: the memo of another stamp is never read."""
    _fresh(monkeypatch, tmp_path)
    memo = next((tmp_path / "source").iterdir())
    plan_cache.write_entry(memo, "source:" + memo.name, b"f" * 64)  # as if the files had changed since
    assert _fresh(monkeypatch, tmp_path) == "f" * 64  # same stamp: the memo is trusted...
    name = plan_cache._source_files()[0][0]
    monkeypatch.setattr(plan_cache, "_source_files",
                        lambda real=plan_cache._source_files: [(n, _Touched(p) if n == name else p) for n, p in real()])
    assert _fresh(monkeypatch, tmp_path) == _direct()  # ...a new stamp is not


class _Touched(type(Path())):  # type: ignore[misc]
    """The same file with a later modification time."""

    def stat(self, **kwargs):  # type: ignore[no-untyped-def, override]
        st = super().stat(**kwargs)
        return type("S", (), {"st_size": st.st_size, "st_mtime_ns": st.st_mtime_ns + 1})()



def test_the_listing_is_every_file_of_the_four_packages_but_bytecode() -> None:
    """Against pathlib's recursive glob (the listing before it was made faster): the same
    files under the same names, in name order, each one once."""
    import importlib.util

    witness = set()
    for package in ("rmot.lang", "rmot.compiler", "rmot.backends", "rmot.sim"):
        spec = importlib.util.find_spec(package)
        assert spec is not None and spec.submodule_search_locations
        for root in spec.submodule_search_locations:
            for path in Path(root).rglob("*"):
                if path.is_file() and "__pycache__" not in path.parts and path.suffix != ".pyc":
                    witness.add((f"{package}/{path.relative_to(root).as_posix()}", path))
    listed = plan_cache._source_files()
    assert set(listed) == witness and len(listed) == len(witness) > 150
    assert [n for n, _ in listed] == sorted(n for n, _ in listed)
    assert "rmot.lang/record.py" in {n for n, _ in listed}
