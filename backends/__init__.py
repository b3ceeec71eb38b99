"""rmot.backends: vendor program writers (text only; no planning here).

`BACKENDS` maps a --target name to its Backend class, read from the one registry of targets
(compiler/vendors.py, re-exported here: `register`, `targets`, `controllers`); each vendor
module is imported only when its entry is looked up, so loading one backend never loads the
others.

    from rmot.backends import BACKENDS
    result = BACKENDS["rapid"]().emit(plan)      # EmitResult(files, diagnostics)
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from typing import TYPE_CHECKING

from rmot.compiler.vendors import Target, controllers, lookup, register, targets, unregister

if TYPE_CHECKING:
    from rmot.backends.base import Backend

__all__ = ["BACKENDS", "TARGETS", "Target", "controllers", "register", "targets", "unregister"]

TARGETS: tuple[str, ...] = targets()
"""The targets registered when this package is imported (`targets()` is the live list)."""


class _LazyBackends(Mapping[str, "type[Backend]"]):
    """A read-only mapping that imports a vendor module on first lookup."""

    def __getitem__(self, key: str) -> type[Backend]:
        cls: type[Backend] = lookup(key).backend()
        return cls

    def __iter__(self) -> Iterator[str]:
        return iter(targets())

    def __len__(self) -> int:
        return len(targets())


BACKENDS: Mapping[str, type[Backend]] = _LazyBackends()
