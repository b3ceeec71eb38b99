"""`--shard K/N`: a deterministic, size-balanced share of the programs for one CI runner.

Every runner of an N-way CI matrix is given the same program list and its own K. Each one
computes the same assignment independently, so together they check every program exactly
once, and none needs to talk to another. The assignment depends only on the set of paths
(as given, with '/' separators) and their sizes in bytes, never on the order they were
given in, the machine, the clock or a hash seed:

1. programs are sorted by size, largest first (ties by path), and
2. each goes to the shard with the least total size so far (ties: the lowest shard number).

This is the "longest processing time first" rule (Graham, 1969): the largest shard is at most
4/3 of the optimum, good enough to balance a plant's programs when size stands in for cost.
Within a shard the programs keep the order they were given in, so reports stay readable.
"""

from __future__ import annotations

import heapq
import os
import re
from collections.abc import Sequence

from rmot.lang.record import record

__all__ = ["Shard", "parse_shard", "select_shard"]

_SHARD = re.compile(r"^\s*([0-9]+)\s*/\s*([0-9]+)\s*$")
MAX_SHARDS = 10_000  # more runners than any CI matrix allows (GitHub's limit is 256 jobs)


@record
class Shard:
    """Shard `index` (1-based) of `count`."""

    index: int
    count: int


def parse_shard(text: str) -> Shard:
    """'2/4' -> Shard(2, 4); raises ValueError with a message a user can act on."""
    match = _SHARD.match(text)
    if not match:
        raise ValueError(f"must be K/N with whole numbers, e.g. 1/4 (got '{text}')")
    index, count = int(match.group(1)), int(match.group(2))
    if not 1 <= count <= MAX_SHARDS:
        raise ValueError(f"N must be between 1 and {MAX_SHARDS} (got {count})")
    if not 1 <= index <= count:
        raise ValueError(f"K must be between 1 and N={count} (got {index})")
    return Shard(index, count)


def _size(path: str) -> int:
    """Bytes on disk; a file that cannot be read still gets a shard (its check reports E501)."""
    try:
        return os.path.getsize(path)
    except OSError:
        return 0


def _key(path: str) -> str:
    return path.replace(os.sep, "/")


def assign(programs: Sequence[str], count: int, sizes: dict[str, int] | None = None) -> list[list[str]]:
    """All `count` shards (0-based list), each in the order the programs were given."""
    unique = list(dict.fromkeys(programs))
    size = {p: (sizes[p] if sizes is not None else _size(p)) for p in unique}
    order = sorted(unique, key=lambda p: (-size[p], _key(p)))
    heap = [(0, k) for k in range(count)]
    owner: dict[str, int] = {}
    for path in order:
        load, k = heapq.heappop(heap)
        owner[path] = k
        heapq.heappush(heap, (load + size[path], k))
    shards: list[list[str]] = [[] for _ in range(count)]
    for path in unique:
        shards[owner[path]].append(path)
    return shards


def select_shard(programs: Sequence[str], shard: Shard, sizes: dict[str, int] | None = None) -> list[str]:
    """The programs shard `shard` checks (possibly none when there are more shards than programs)."""
    return assign(programs, shard.count, sizes)[shard.index - 1]
