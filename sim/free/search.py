"""RRT-Connect in joint space, then shortcutting: the search behind `move free`.

The algorithm is Kuffner and LaValle's RRT-Connect (ICRA 2000, "RRT-Connect: An Efficient
Approach to Single-Query Path Planning"): two trees, one from the start and one from the goal;
each round draws one configuration, extends one tree a step towards it and pulls the other
tree straight at the new node until it is blocked or the trees meet. The path found is then
shortened: a greedy pass that joins every node to the farthest later node it sees, random
shortcuts between points on the path (Geraerts and Overmars, "Creating High-quality Paths for
Motion Planning", IJRR 2007, section 4: "partial shortcuts" aside), and a relaxation that pulls
each via point towards its neighbours' midpoint while that stays free and shortens the path.

Distances are measured in *seconds at full joint speed*: joint j is scaled by 1 / vmax_j, so
a step is a fixed share of motion time whatever the joint, and the path length is the time a
joint move through the points would take at full speed without acceleration limits (the
metric the cycle time follows).

Deterministic: every random number comes from the `numpy.random.Generator` passed in (never
numpy's global state), nearest neighbours are chosen by a stable argmin, and the search is
bounded by the number of configurations drawn (`samples`). The wall-clock `deadline` is only
a safety stop: when it ends a search the result says so, and that outcome may differ between
machines (the caller reports it as such).
"""

from __future__ import annotations

import time
from collections.abc import Callable

import numpy as np

from rmot.lang.record import record

__all__ = ["Search", "path_length", "search_path", "shorten"]

EdgeCheck = Callable[[np.ndarray, np.ndarray], bool]

STEP = 0.35  # s at full joint speed: the longest edge a tree grows in one extension
SHORTCUTS = 80  # random shortcut attempts after the greedy pass


@record
class Search:
    """What a search found. `path`: configurations from start to goal (None when none was
    found); `samples`: configurations drawn; `stopped`: "" when found, "samples" when the
    sample budget ran out, "time" when the time budget did."""

    path: tuple[tuple[float, ...], ...] | None
    samples: int
    stopped: str
    seconds: float


class _Tree:
    """Nodes (joint values) and each node's parent index (-1 at the root); distances scaled."""

    def __init__(self, root: np.ndarray, capacity: int, scale: np.ndarray) -> None:
        self.scale = scale
        self.nodes = np.empty((capacity, root.size))
        self.parent = np.empty(capacity, dtype=np.int64)
        self.nodes[0], self.parent[0], self.size = root, -1, 1

    def add(self, node: np.ndarray, parent: int) -> int:
        if self.size == self.nodes.shape[0]:
            self.nodes = np.vstack([self.nodes, np.empty_like(self.nodes)])
            self.parent = np.concatenate([self.parent, np.empty_like(self.parent)])
        self.nodes[self.size], self.parent[self.size] = node, parent
        self.size += 1
        return self.size - 1

    def nearest(self, u: np.ndarray) -> int:
        d = np.sum(((self.nodes[:self.size] - u) * self.scale) ** 2, axis=1)
        return int(np.argmin(d))  # the first of equals: stable

    def branch(self, i: int) -> list[np.ndarray]:
        """The nodes from the root to node i."""
        out = []
        while i >= 0:
            out.append(self.nodes[i])
            i = int(self.parent[i])
        return out[::-1]


def _toward(a: np.ndarray, b: np.ndarray, scale: np.ndarray) -> np.ndarray:
    """From a towards b by at most STEP (scaled); b itself when it is that close."""
    d = float(np.linalg.norm((b - a) * scale))
    return b.copy() if d <= STEP else a + (b - a) * (STEP / d)


def search_path(start: np.ndarray, goal: np.ndarray, lo: np.ndarray, hi: np.ndarray, scale: np.ndarray,
                edge_free: EdgeCheck, rng: np.random.Generator, samples: int, deadline_s: float) -> Search:
    """A collision-free joint path from `start` to `goal` (both free), within [lo, hi].

    `scale` (dof,): 1 / max joint speed; `edge_free(qa, qb)`: the straight joint segment
    between two configurations is free (its ends included). Tries the straight move first."""
    t0 = time.monotonic()
    if edge_free(start, goal):
        return Search((tuple(float(v) for v in start), tuple(float(v) for v in goal)), 0, "", time.monotonic() - t0)
    trees = [_Tree(start, 256, scale), _Tree(goal, 256, scale)]
    start_tree = trees[0]
    drawn = 0
    while drawn < samples:
        if time.monotonic() - t0 > deadline_s:
            return Search(None, drawn, "time", time.monotonic() - t0)
        drawn += 1
        q_rand = lo + rng.random(start.size) * (hi - lo)
        grow, other = trees[0], trees[1]
        i = grow.nearest(q_rand)
        q_new = _toward(grow.nodes[i], q_rand, scale)
        if not edge_free(grow.nodes[i].copy(), q_new):
            trees.reverse()
            continue
        new = grow.add(q_new, i)
        j = _connect(other, q_new, edge_free)
        if j is not None:  # both branches end at q_new: join them there once
            a, b = grow.branch(new), other.branch(j)
            path = a + b[::-1][1:] if grow is start_tree else b + a[::-1][1:]
            return Search(tuple(tuple(float(v) for v in q) for q in path), drawn, "", time.monotonic() - t0)
        trees.reverse()
    return Search(None, drawn, "samples", time.monotonic() - t0)


def _connect(tree: _Tree, target: np.ndarray, edge_free: EdgeCheck) -> int | None:
    """Grow `tree` straight at `target` step by step; the index of the node at `target` if it
    gets there, else None."""
    i = tree.nearest(target)
    while True:
        u = _toward(tree.nodes[i], target, tree.scale)
        if not edge_free(tree.nodes[i].copy(), u):
            return None
        i = tree.add(u, i)
        if np.array_equal(u, target):
            return i


def shorten(path: list[np.ndarray], edge_free: EdgeCheck, rng: np.random.Generator, scale: np.ndarray,
            attempts: int = SHORTCUTS) -> list[np.ndarray]:
    """The path with fewer, shorter detours: greedy farthest-visible joins, then `attempts`
    random shortcuts between points on two different segments, then the greedy pass again."""
    path = _greedy(path, edge_free)
    for _ in range(attempts):
        if len(path) < 3:
            break
        lengths = np.linalg.norm(np.diff(np.asarray(path) * scale, axis=0), axis=1)
        cum = np.concatenate([[0.0], np.cumsum(lengths)])
        s1, s2 = np.sort(rng.random(2)) * cum[-1]
        i, j = int(np.searchsorted(cum, s1, side="right")) - 1, int(np.searchsorted(cum, s2, side="right")) - 1
        i, j = min(i, len(path) - 2), min(j, len(path) - 2)
        if i == j:
            continue
        a = _point(path, cum, i, s1)
        b = _point(path, cum, j, s2)
        if edge_free(a, b) and _length([path[i], a, b, path[j + 1]], scale) < _length(path[i:j + 2], scale):
            path = path[:i + 1] + [a, b] + path[j + 1:]
    return _relaxed(_greedy(path, edge_free), edge_free, scale)


RELAX_ROUNDS = 4  # passes of pulling each via point towards its neighbours' midpoint


def _relaxed(path: list[np.ndarray], edge_free: EdgeCheck, scale: np.ndarray) -> list[np.ndarray]:
    """Smoothing: each via point moves towards the midpoint of its neighbours (the whole way,
    half or a quarter) while both its segments stay free and the path gets shorter; a joint
    the detour does not need (a wrist a random sample turned) goes back to the straight line."""
    path = list(path)
    for _ in range(RELAX_ROUNDS):
        moved = False
        for k in range(1, len(path) - 1):
            mid = (path[k - 1] + path[k + 1]) / 2
            before = _length(path[k - 1:k + 2], scale)
            for share in (1.0, 0.5, 0.25):
                q = path[k] + (mid - path[k]) * share
                if (_length([path[k - 1], q, path[k + 1]], scale) < before - 1e-9
                        and edge_free(path[k - 1], q) and edge_free(q, path[k + 1])):
                    path[k], moved = q, True
                    break
        if not moved:
            break
    return path


def _point(path: list[np.ndarray], cum: np.ndarray, i: int, s: float) -> np.ndarray:
    seg = cum[i + 1] - cum[i]
    f = float((s - cum[i]) / seg) if seg > 0 else 0.0
    point: np.ndarray = path[i] + (path[i + 1] - path[i]) * f
    return point


def _greedy(path: list[np.ndarray], edge_free: EdgeCheck) -> list[np.ndarray]:
    """From each kept node, jump to the farthest later node reachable in a straight line."""
    out = [path[0]]
    i = 0
    while i < len(path) - 1:
        j = len(path) - 1
        while j > i + 1 and not edge_free(path[i], path[j]):
            j -= 1
        out.append(path[j])
        i = j
    return out


def _length(points: list[np.ndarray], scale: np.ndarray) -> float:
    return float(np.sum(np.linalg.norm(np.diff(np.asarray(points) * scale, axis=0), axis=1)))


def path_length(points: list[np.ndarray] | tuple[tuple[float, ...], ...], scale: np.ndarray | None = None) -> float:
    """Length of a joint path: Euclidean in joint space (rad), or in scaled units with `scale`."""
    arr = np.asarray(points, dtype=float)
    if scale is not None:
        arr = arr * scale
    return float(np.sum(np.linalg.norm(np.diff(arr, axis=0), axis=1)))
