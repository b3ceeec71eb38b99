"""rmot.backends: vendor program writers (text only; no planning here).

`BACKENDS` maps a --target name to its Backend class, read from the one registry of targets
(lang/vendors.py, re-exported here: `register`, `targets`, `controllers`); each vendor
module is imported only when its entry is looked up, so loading one backend never loads the
others.

    from rmot.backends import BACKENDS
    result = BACKENDS["rapid"]().emit(plan)      # EmitResult(files, diagnostics)

Where things are: base.py (the Backend class: EMIT and MOVES tables, the class flags
PRINTS_LOOPS and RUNTIME_CONDITIONS, the defaults every vendor starts from), one module per
vendor (rapid, krl, fanuc_tp, urscript, inform, val3; neutral for CSV/JSON), and what they
share: conventions (number and orientation formats), names (legal identifiers), lowering and
handshake (IR -> IR transforms: splitting, `sync` as I/O), loops and runtime (vendor loops,
runtime expressions), part_load (the load while parts are held), turns, controller_data,
safe_text, codes. A backend reads the IR and the Plan only (pyproject's layer contract).
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from typing import TYPE_CHECKING

from rmot.lang.vendors import Target, controllers, lookup, register, targets, unregister

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
