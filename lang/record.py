"""`record`: `@dataclass(frozen=True)` with `__eq__`, `__hash__` and `__repr__` shared, not generated.

Why: Python 3.11's `dataclass` writes the source of six methods for every frozen class and
compiles each with `exec`: about 1 ms a class on this machine, and the AST, the IR and the
plan types define over a hundred of them, all created on every start of `rmot` (part of
the start-up of `rmot check`). Equality, hashing and repr need no per-class code: three
shared functions, closed over the class's field names (fetched at C speed by one
`operator.attrgetter` per class), so only `__init__`, `__setattr__` and `__delattr__` are still
generated (measured in tests/benchmarks/bench_startup.py).

The behaviour is exactly `@dataclass(frozen=True, ...)`'s (Python 3.11, dataclasses.py):
- `a == b` compares the tuple of the fields with `compare=True` when both are of the same
  class, else NotImplemented (so `==` falls back to identity and `!=` to its negation);
- `hash(a)` is the hash of the tuple of the fields with `hash=True`, or `compare=True` when
  `hash` is None: the same number dataclass computes, so sets and dicts iterate in the
  same order;
- `repr(a)` is `QualName(f1=..., f2=...)` over the fields with `repr=True`, with `...` for
  an object met again inside its own repr.
`dataclasses.fields`, `replace`, `asdict` and `is_dataclass` work as before: the class is a
dataclass (`eq` and `repr` are off only in what dataclass generates).
tests/core/test_record.py checks all of this against classes made by dataclass itself.
"""

from __future__ import annotations

import reprlib
from collections.abc import Callable
from dataclasses import dataclass, field, fields
from operator import attrgetter
from typing import Any, TypeVar, dataclass_transform, overload

__all__ = ["record"]

_T = TypeVar("_T")


@overload
def record(cls: type[_T], /) -> type[_T]: ...
@overload
def record(*, slots: bool = ..., kw_only: bool = ...) -> Callable[[type[_T]], type[_T]]: ...


@dataclass_transform(frozen_default=True, eq_default=True, field_specifiers=(field,))
def record(cls: type[_T] | None = None, /, *, slots: bool = False,
           kw_only: bool = False) -> type[_T] | Callable[[type[_T]], type[_T]]:
    """A frozen dataclass of `cls` (module doc); `slots` and `kw_only` as dataclass's."""

    def wrap(c: type[_T]) -> type[_T]:
        own = c.__dict__
        if "__eq__" in own or "__hash__" in own or "__repr__" in own:
            raise TypeError(f"{c.__qualname__}: a record's __eq__, __hash__ and __repr__ are "
                            "shared; use @dataclass for a class that defines its own")
        made: Any = dataclass(c, frozen=True, eq=False, repr=False, slots=slots, kw_only=kw_only)
        every = fields(made)
        compared = _tuple_of([f.name for f in every if f.compare])
        hashed = _tuple_of([f.name for f in every if (f.compare if f.hash is None else f.hash)])
        shown = tuple(f.name for f in every if f.repr)
        for method in (_eq_of(compared), _hash_of(hashed), _repr_of(shown)):
            method.__qualname__ = f"{made.__qualname__}.{method.__name__}"
            setattr(made, method.__name__, method)
        return made  # type: ignore[no-any-return]

    return wrap if cls is None else wrap(cls)


def _tuple_of(names: list[str]) -> Callable[[Any], tuple[Any, ...]]:
    """self -> (self.n1, self.n2, ...): always a tuple, as dataclass builds one (attrgetter
    of a single name returns the bare value, of none is an error)."""
    if len(names) >= 2:
        return attrgetter(*names)
    if len(names) == 1:
        one = attrgetter(names[0])
        return lambda self: (one(self),)
    return lambda self: ()


# Closures over each class's getters, not methods looking the getters up on the instance: a
# closure is made without compiling anything, and reads its getter at local-variable speed.
def _eq_of(key: Callable[[Any], tuple[Any, ...]]) -> Callable[[Any, Any], Any]:
    def __eq__(self: Any, other: Any) -> Any:
        if other.__class__ is self.__class__:
            return key(self) == key(other)
        return NotImplemented
    return __eq__


def _hash_of(key: Callable[[Any], tuple[Any, ...]]) -> Callable[[Any], int]:
    def __hash__(self: Any) -> int:
        return hash(key(self))
    return __hash__


def _repr_of(shown: tuple[str, ...]) -> Callable[[Any], str]:
    @reprlib.recursive_repr()
    def __repr__(self: Any) -> str:
        fields_text = ", ".join(f"{name}={getattr(self, name)!r}" for name in shown)
        return f"{self.__class__.__qualname__}({fields_text})"
    return __repr__
