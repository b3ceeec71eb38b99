"""rmot.backends: vendor program writers (text only; no planning here).

`BACKENDS` maps a --target name to its Backend class; each vendor module is imported only
when its entry is looked up, so loading one backend never loads the others.

    from rmot.backends import BACKENDS
    result = BACKENDS["rapid"]().emit(plan)      # EmitResult(files, diagnostics)
"""

from __future__ import annotations

import importlib
from collections.abc import Iterator, Mapping
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from rmot.backends.base import Backend

__all__ = ["BACKENDS", "TARGETS"]

# --target name -> (module, class name)
_REGISTRY: dict[str, tuple[str, str]] = {
    "rapid": ("rmot.backends.rapid", "RapidBackend"),
    "krl": ("rmot.backends.krl", "KrlBackend"),
    "fanuc": ("rmot.backends.fanuc_tp", "FanucBackend"),
    "urscript": ("rmot.backends.urscript", "UrScriptBackend"),
    "inform": ("rmot.backends.inform", "InformBackend"),
    "val3": ("rmot.backends.val3", "Val3Backend"),
    "csv": ("rmot.backends.neutral", "CsvBackend"),
    "json": ("rmot.backends.neutral", "JsonBackend"),
}

TARGETS: tuple[str, ...] = tuple(_REGISTRY)


class _LazyBackends(Mapping[str, "type[Backend]"]):
    """A read-only mapping that imports a vendor module on first lookup."""

    def __getitem__(self, key: str) -> type[Backend]:
        module_name, cls_name = _REGISTRY[key]
        return getattr(importlib.import_module(module_name), cls_name)  # type: ignore[no-any-return]

    def __iter__(self) -> Iterator[str]:
        return iter(_REGISTRY)

    def __len__(self) -> int:
        return len(_REGISTRY)


BACKENDS: Mapping[str, type[Backend]] = _LazyBackends()
