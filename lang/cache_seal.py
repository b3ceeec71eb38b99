"""Cache entries a reader can vouch for: sealed with an HMAC bound to their key, read only from
bounded regular files inside the cache directory.

Every cache of rmot (LALR tables, plans, verification reports, front-end results, the source
digest memo) stores a value computed from a key. A cache folder can be restored from a CI
cache, shared, or edited by hand; an entry that was not written by rmot under the same key
must never change a verdict. So each entry is

    b"rmot-sealed/1\\n" + hex HMAC-SHA256(secret, key NUL payload) + b"\\n" + payload

where `secret` is 32 random bytes in `<cache>/secret`, created with the cache (mode 0600,
owned by the user running rmot). A reader recomputes the HMAC; an entry whose MAC does not
match, that is not a regular file (a FIFO, a device, a symlink: opened with O_NOFOLLOW and
O_NONBLOCK, so a FIFO never blocks), that is larger than its cache's bound, or whose folder
resolves outside the cache directory, is a miss: the caller rebuilds the value and writes it
anew. A secret that is not a regular file of 32 bytes, owned by this user and unreadable by
others, is replaced by a new one (every entry then misses once).

What this trusts (lang/REFERENCE.md §9): whoever can read `<cache>/secret`. A cache restored
together with its secret is trusted as a whole, exactly like the rmot installation itself; an
entry copied in without the secret, edited, truncated, moved to another key, or swapped for a
special file is rebuilt. The MAC is not a defence against an attacker who can read the secret.
"""

from __future__ import annotations

import hashlib
import hmac
import os
import tempfile
from pathlib import Path

from rmot.lang.input_file import read_regular

__all__ = ["MAGIC", "cache_dir", "read_sealed", "seal", "secret", "unseal"]

MAGIC = b"rmot-sealed/1\n"
_SECRET_BYTES = 32
_MAC_HEX = 64
_SECRETS: dict[str, bytes] = {}  # per cache directory, read once a process


def cache_dir() -> Path:
    """The one cache directory of every cache entry: $RMOT_CACHE_DIR, else
    $XDG_CACHE_HOME/rmot, else ~/.cache/rmot."""
    explicit = os.environ.get("RMOT_CACHE_DIR")
    if explicit:
        return Path(explicit)
    xdg = os.environ.get("XDG_CACHE_HOME")
    base = Path(xdg) if xdg and os.path.isabs(xdg) else Path.home() / ".cache"
    return base / "rmot"


def secret() -> bytes | None:
    """The cache's secret, created when missing or untrustworthy; None when it can be neither
    read nor created (an unwritable cache: nothing sealed is then read or written)."""
    path = cache_dir() / "secret"
    known = _SECRETS.get(str(path)) or _read_secret(path)
    if known is not None:
        _SECRETS[str(path)] = known
        return known
    try:
        path.parent.mkdir(parents=True, exist_ok=True, mode=0o700)
        fd, tmp = tempfile.mkstemp(prefix=".secret-", dir=path.parent)  # mode 0600
        try:
            with os.fdopen(fd, "wb") as f:
                f.write(os.urandom(_SECRET_BYTES))
            if os.path.lexists(path) and _read_secret(path) is None:
                os.replace(tmp, path)  # an untrustworthy secret: replaced, every entry misses
            else:
                os.link(tmp, path)  # FileExistsError when a concurrent run made one first
        finally:
            os.unlink(tmp)
    except FileExistsError:
        pass
    except OSError:
        return None
    return _read_secret(path)


def _read_secret(path: Path) -> bytes | None:
    data = _read_regular(path, _SECRET_BYTES, owner_only=True)
    return data if data is not None and len(data) == _SECRET_BYTES else None


def _read_regular(path: Path, max_bytes: int, *, owner_only: bool = False) -> bytes | None:
    """The bytes of `path` if it is a regular file (not followed through a symlink, never
    blocking on a FIFO) of at most max_bytes; else None."""
    try:
        return read_regular(path, max_bytes, owner_only=owner_only, follow_links=False)
    except (OSError, ValueError):
        return None


def _mac(key: bytes, key_text: str, payload: bytes) -> bytes:
    return hmac.new(key, key_text.encode("utf-8", "surrogateescape") + b"\0" + payload,
                    hashlib.sha256).hexdigest().encode("ascii")


def seal(key_text: str, payload: bytes) -> bytes | None:
    """The sealed form of `payload` stored under `key_text`; None without a secret (no entry
    is written then)."""
    key = secret()
    if key is None:
        return None
    return MAGIC + _mac(key, key_text, payload) + b"\n" + payload


def unseal(key_text: str, data: bytes) -> bytes | None:
    """The payload of sealed `data` when its MAC is this cache's for `key_text`, else None."""
    head = len(MAGIC) + _MAC_HEX + 1
    if len(data) < head or not data.startswith(MAGIC) or data[head - 1:head] != b"\n":
        return None
    key = secret()
    if key is None:
        return None
    payload = data[head:]
    if not hmac.compare_digest(data[len(MAGIC):head - 1], _mac(key, key_text, payload)):
        return None
    return payload


def read_sealed(path: Path, key_text: str, max_bytes: int) -> bytes | None:
    """The payload of the entry at `path` (a file inside the cache directory) written under
    `key_text`, or None: missing, not a regular file, over max_bytes, outside the cache
    directory once links are resolved, or not sealed by this cache for this key."""
    try:
        inside = Path(os.path.realpath(path.parent)).is_relative_to(os.path.realpath(cache_dir()))
    except (OSError, ValueError):
        return None
    if not inside:
        return None
    data = _read_regular(path, max_bytes + len(MAGIC) + _MAC_HEX + 1)
    return None if data is None else unseal(key_text, data)
