"""`IkResult.solutions` and `IkResult.branches` as immutable sequences over arrays.

A result of an arm whose joints span more than 360° holds every 2π-equivalent of every branch
(a UR5e: 512 solutions). A tuple of 512 row arrays costs ~50 µs to build, far more than the IK
itself; `JointRows` keeps the rows in ONE read-only (m, dof) array and makes a row (a read-only
view) when it is asked for, and `BranchRows` keeps each row's branch as a code into a table of
the 8 configurations. Both behave as the tuples did: len, bool, indexing (negative too),
slicing (to the same type), iteration, `==` with a tuple or another view (element-wise, with
`np.array_equal` for rows), repr as a tuple's; nothing can be assigned.

`Lazy`: rows made and sorted (stable, by their distances from the seed, as
`ik.solve_exact`'s np.argsort) the first time anything past the nearest row is asked for; the
nearest row (the first one of that sort) is known without them (robots/fastsolve.py).
"""

from __future__ import annotations

import operator
from collections.abc import Callable, Iterator, Sequence
from typing import Any, overload

import numpy as np

from rmot.lang import ir

__all__ = ["BranchRows", "JointRows", "Lazy"]


class Lazy:
    """Rows not made yet: `make(*args)` makes them once, as (rows (m, dof), branch codes (m,))
    sorted; `get` returns them (rows read-only)."""

    __slots__ = ("_make", "_args", "_rows", "_codes")

    def __init__(self, make: Callable[..., tuple[np.ndarray, np.ndarray]], *args: Any) -> None:
        self._make, self._args = make, args
        self._rows: np.ndarray | None = None
        self._codes: np.ndarray | None = None

    def get(self) -> tuple[np.ndarray, np.ndarray]:
        rows, codes = self._rows, self._codes
        if rows is None or codes is None:
            rows, codes = self._make(*self._args)
            rows.setflags(write=False)
            self._rows, self._codes, self._args = rows, codes, ()
        return rows, codes


class JointRows(Sequence[np.ndarray]):
    """The joint solutions: rows of one read-only (m, dof) array (see the module docstring)."""

    __slots__ = ("_rows", "_lazy", "_first", "_count")
    __hash__ = None  # type: ignore[assignment]  # as a tuple of arrays: not hashable

    def __init__(self, rows: np.ndarray | None, lazy: Lazy | None = None,
                 first: np.ndarray | None = None, count: int = 0) -> None:
        """rows: the sorted read-only rows; or lazy (then first = the nearest row, count = m)."""
        self._rows = rows
        self._lazy = lazy
        self._first = first if rows is None else None
        self._count = count

    @property
    def array(self) -> np.ndarray:
        """All rows as one read-only (m, dof) array, nearest to the seed first."""
        rows = self._rows
        if rows is None:
            assert self._lazy is not None
            rows = self._rows = self._lazy.get()[0]
            self._first = None
        return rows

    def __len__(self) -> int:
        rows = self._rows
        return self._count if rows is None else len(rows)

    @overload
    def __getitem__(self, index: int) -> np.ndarray: ...

    @overload
    def __getitem__(self, index: slice) -> JointRows: ...

    def __getitem__(self, index: int | slice) -> np.ndarray | JointRows:
        if isinstance(index, slice):
            return JointRows(self.array[index])
        i = operator.index(index)
        first = self._first
        if first is not None and (i == 0 or i == -self._count):
            return first
        n = len(self)
        if not -n <= i < n:
            raise IndexError("tuple index out of range")
        row: np.ndarray = self.array[i]
        return row

    def __iter__(self) -> Iterator[np.ndarray]:
        return iter(self.array)

    def __reversed__(self) -> Iterator[np.ndarray]:
        return iter(self.array[::-1])

    def __eq__(self, other: object) -> bool:
        if isinstance(other, JointRows):
            return np.array_equal(self.array, other.array)
        if isinstance(other, tuple):
            return len(other) == len(self) and all(
                np.array_equal(a, b) for a, b in zip(self.array, other))
        return NotImplemented

    def __array__(self, dtype: Any = None, copy: bool | None = None) -> np.ndarray:
        rows = self.array
        if dtype is not None and np.dtype(dtype) != rows.dtype:
            return rows.astype(dtype)
        return rows.copy() if copy else rows

    def __repr__(self) -> str:
        return repr(tuple(self))


class BranchRows(Sequence[ir.Config]):
    """Each solution's branch: a tuple of Configs, or table[code] per row (see the module
    docstring)."""

    __slots__ = ("_items", "_codes", "_table", "_lazy", "_first", "_count")

    def __init__(self, items: tuple[ir.Config, ...] | None = None, codes: np.ndarray | None = None,
                 table: tuple[ir.Config, ...] = (), lazy: Lazy | None = None,
                 first: ir.Config | None = None, count: int = 0) -> None:
        """items: the Configs; or codes (sorted) into table; or lazy (then first = the nearest
        row's Config, count = m) into table."""
        self._items, self._codes, self._table, self._lazy = items, codes, table, lazy
        self._first, self._count = first, count

    def _all(self) -> tuple[ir.Config, ...]:
        items = self._items
        if items is None:
            table = self._table
            items = self._items = tuple([table[c] for c in self._sorted_codes().tolist()])
        return items

    def _sorted_codes(self) -> np.ndarray:
        codes = self._codes
        if codes is None:
            assert self._lazy is not None
            codes = self._codes = self._lazy.get()[1]
            self._lazy = self._first = None
        return codes

    def __len__(self) -> int:
        if self._items is not None:
            return len(self._items)
        codes = self._codes
        return self._count if codes is None else len(codes)

    @overload
    def __getitem__(self, index: int) -> ir.Config: ...

    @overload
    def __getitem__(self, index: slice) -> BranchRows: ...

    def __getitem__(self, index: int | slice) -> ir.Config | BranchRows:
        if isinstance(index, slice):
            return BranchRows(self._all()[index])
        items = self._items
        if items is not None:
            return items[index]
        i = operator.index(index)
        first = self._first
        if first is not None and (i == 0 or i == -self._count):
            return first
        n = len(self)
        if not -n <= i < n:
            raise IndexError("tuple index out of range")
        return self._table[int(self._sorted_codes()[i])]

    def __iter__(self) -> Iterator[ir.Config]:
        return iter(self._all())

    def __eq__(self, other: object) -> bool:
        if isinstance(other, BranchRows):
            return self._all() == other._all()
        if isinstance(other, tuple):
            return self._all() == other
        return NotImplemented

    def __hash__(self) -> int:
        return hash(self._all())

    def __repr__(self) -> str:
        return repr(self._all())
