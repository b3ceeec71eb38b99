"""A cache cannot change a verdict: every entry (lalr/, plans/, verify/, load/, source/) is sealed
with an HMAC bound to its key (lang/cache_seal.py). Each attack here is what someone who can
write the cache folder (a shared or restored CI cache) would do; the verdict must stay the one
`--no-cache` gives, and the command must finish (a FIFO or /dev/zero never blocks or floods it).
The witness of each verdict is the same command with --no-cache."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
COLLISION = ROOT / "examples" / "collision.rmot"
_CLI = "import sys; from rmot.compiler.cli import cli; sys.argv[0] = 'rmot'; cli()"


def rmot(cache: Path, *args: str, timeout: float = 240) -> subprocess.CompletedProcess[str]:
    """`rmot ARGS` in a child process with RMOT_CACHE_DIR=cache (a blocked read fails the test by
    its timeout instead of hanging the suite)."""
    env = {**os.environ, "RMOT_CACHE_DIR": str(cache)}
    return subprocess.run([sys.executable, "-c", _CLI, *args], env=env, capture_output=True, text=True,
                          timeout=timeout, cwd=ROOT)


def _entries(cache: Path, folder: str) -> list[Path]:
    return sorted(p for p in (cache / folder).rglob("*") if p.is_file() and not p.name.startswith("."))


def _json_part(data: bytes) -> tuple[bytes, dict]:  # type: ignore[type-arg]
    """(whatever precedes the JSON document, the document) of a verify/ or load/ entry."""
    start = data.index(b"{")
    return data[:start], json.loads(data[start:])


@pytest.fixture(scope="module")
def baseline(tmp_path_factory: pytest.TempPathFactory) -> subprocess.CompletedProcess[str]:
    return rmot(tmp_path_factory.mktemp("nocache"), "check", str(COLLISION), "--no-cache")


@pytest.fixture(scope="module")
def filled(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, subprocess.CompletedProcess[str]]:
    """A cache folder filled by one `rmot check` of the collision example (its secret and every
    entry), and that run; each test attacks its own copy of the folder (`_filled_copy`)."""
    cache = tmp_path_factory.mktemp("filled") / "cache"
    return cache, rmot(cache, "check", str(COLLISION))


def _filled_copy(filled: tuple[Path, subprocess.CompletedProcess[str]], cache: Path) -> subprocess.CompletedProcess[str]:
    """`cache` made a byte-for-byte copy of the filled folder (modes kept: the secret stays
    0600, as the run wrote it; entries are sealed by key and secret, not by folder), and the run
    that filled it."""
    template, run = filled
    assert _entries(template, "verify") and (template / "secret").is_file()  # the run did fill it
    shutil.copytree(template, cache, symlinks=True)
    return run


def test_an_edited_verify_entry_gives_the_uncached_verdict(tmp_path: Path, baseline: subprocess.CompletedProcess[str],
                                                           filled: tuple[Path, subprocess.CompletedProcess[str]]) -> None:
    """The entry's findings emptied and its cycle time made NaN (what faked a clean check)."""
    cache = tmp_path / "cache"
    assert _filled_copy(filled, cache).returncode == baseline.returncode == 1
    for path in _entries(cache, "verify"):
        head, doc = _json_part(path.read_bytes())
        program_file, _, _, tasks = doc["doc"]["$t"]
        doc["doc"]["$t"] = [program_file, {"$d": [["collision", float("nan")]]}, {"$t": []}, tasks]
        path.write_bytes(head + json.dumps(doc).encode())
    again = rmot(cache, "check", str(COLLISION))
    assert (again.returncode, again.stdout) == (baseline.returncode, baseline.stdout), again.stdout + again.stderr
    assert "E300" in again.stdout


def test_an_entry_sealed_by_another_cache_is_not_trusted(tmp_path: Path, baseline: subprocess.CompletedProcess[str],
                                                         filled: tuple[Path, subprocess.CompletedProcess[str]]) -> None:
    """A verify entry emptied and sealed again with the secret of the attacker's own cache (the
    HMAC computed here with the standard library), then copied into the victim's cache: a miss."""
    import hashlib
    import hmac

    victim = tmp_path / "victim"
    _filled_copy(filled, victim)
    forged_secret = os.urandom(32)
    for path in _entries(victim, "verify"):
        _, doc = _json_part(path.read_bytes())
        doc["doc"]["$t"][2] = {"$t": []}
        payload = json.dumps(doc).encode()
        mac = hmac.new(forged_secret, path.stem.encode() + b"\0" + payload, hashlib.sha256).hexdigest()
        path.write_bytes(b"rmot-sealed/1\n" + mac.encode() + b"\n" + payload)
    again = rmot(victim, "check", str(COLLISION))
    assert (again.returncode, again.stdout) == (baseline.returncode, baseline.stdout)


@pytest.mark.parametrize("kind", ["fifo", "dev_zero", "symlink_out", "huge"])
def test_a_special_file_as_an_entry_is_a_miss(kind: str, tmp_path: Path, baseline: subprocess.CompletedProcess[str],
                                              filled: tuple[Path, subprocess.CompletedProcess[str]]) -> None:
    """Every entry of every folder replaced by a FIFO (blocked forever before), a link to
    /dev/zero (read until memory ran out), a link to a file outside the cache, a sparse file
    of 4 GiB: each is a miss, rebuilt, and the verdict is the uncached one."""
    cache = tmp_path / "cache"
    _filled_copy(filled, cache)
    outside = tmp_path / "outside.json"
    outside.write_bytes(b"{}")
    for folder in ("lalr", "source", "plans", "verify", "load"):
        for path in _entries(cache, folder):
            path.unlink()
            if kind == "fifo":
                os.mkfifo(path)
            elif kind == "dev_zero":
                path.symlink_to("/dev/zero")
            elif kind == "symlink_out":
                path.symlink_to(outside)
            else:
                with open(path, "wb") as f:
                    f.truncate(4 << 30)
    again = rmot(cache, "check", str(COLLISION), timeout=240)
    assert (again.returncode, again.stdout) == (baseline.returncode, baseline.stdout), again.stderr


def test_a_damaged_lalr_table_is_rebuilt_not_an_error_in_the_program(tmp_path: Path) -> None:
    """Shift actions of the cached table pointed at a wrong state: the table was read and every
    parse became `E001 internal parser error` in the user's file; now it is a miss."""
    cache = tmp_path / "cache"
    program = ROOT / "examples" / "pick_place.rmot"
    assert rmot(cache, "ir", str(program)).returncode == 0
    (path,) = _entries(cache, "lalr")
    damage_lalr(path)
    again = rmot(cache, "ir", str(program))
    assert again.returncode == 0 and "E001" not in again.stderr, again.stderr


def damage_lalr(path: Path) -> None:
    """Every shift of the cached parse table at `path` points at the start state."""
    data = path.read_bytes()
    start = data.index(b"{")
    doc = json.loads(data[start:])
    for row in doc["states"]:
        for action in row:
            if action[1] == "s":
                action[2] = doc["start"]
    path.write_bytes(data[:start] + json.dumps(doc).encode())


def test_an_untrustworthy_secret_is_replaced(tmp_path: Path, baseline: subprocess.CompletedProcess[str],
                                             filled: tuple[Path, subprocess.CompletedProcess[str]]) -> None:
    """A secret readable by others (or a FIFO in its place) is not used: a new one is made."""
    cache = tmp_path / "cache"
    _filled_copy(filled, cache)
    secret = cache / "secret"
    secret.unlink()
    os.mkfifo(secret)
    again = rmot(cache, "check", str(COLLISION))
    assert (again.returncode, again.stdout) == (baseline.returncode, baseline.stdout)
    assert secret.is_file() and secret.stat().st_mode & 0o777 == 0o600
