"""Where the paths `move free` found are kept: the plan cache's `free/` folder.

The search (rmot.sim.free) reads and writes paths through a store handed to it, so the
simulator never reaches up into the compiler's caches. Entries are sealed like every cache
entry (lang/cache_seal.py: an HMAC bound to the key, a bounded regular file inside the cache);
anything else is a miss and the search runs again. A path read back is still only a proposal:
its segments and timed path are verified like any other motion.
"""

from __future__ import annotations

import hashlib
from pathlib import Path

from rmot.compiler.plan_cache import MAX_BYTES, cache_dir, evict, eviction_due, source_digest, write_entry
from rmot.lang.cache_seal import read_sealed

__all__ = ["FreePathCache", "MAX_ENTRY_BYTES"]

MAX_ENTRY_BYTES = 4 * 1024 * 1024  # a path of a few hundred via points is a few kB


class FreePathCache:
    """The `free/` entries of the plan cache, keyed by the search's own key and rmot's source."""

    def load(self, key: str) -> bytes | None:
        return read_sealed(self._path(key), "free:" + key, MAX_ENTRY_BYTES)

    def save(self, key: str, data: bytes) -> None:
        entry = self._path(key)
        try:
            write_entry(entry, "free:" + key, data)
            if eviction_due(entry.parent.parent):
                evict(entry.parent.parent, MAX_BYTES, suffix=".json")
        except OSError:
            pass  # an unwritable cache only costs the next run the search

    @staticmethod
    def _path(key: str) -> Path:
        """The entry's file: the key with the digest of rmot's own source, so a changed search
        never reads an old path (the seed itself does not change with the source)."""
        entry = hashlib.sha256((key + source_digest()).encode()).hexdigest()
        return cache_dir() / "free" / entry[:2] / f"{entry}.json"
