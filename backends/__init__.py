"""rmot.backends: vendor program writers (text only; no planning here).

The one registry of output targets. Every list of vendors in the project derives from it:
`compile --target` (compiler/cli/compile_cmd.py), the front end's `native NAME { }` check
(compiler/passes/lower_body.py: `controllers()`), the backends' own "another controller's
native block" warning (backends/base.py) and the tests. Adding a backend is one module plus one
`register(...)` line below (CONTRIBUTING.md).

`BACKENDS` maps a --target name to its Backend class; each vendor module is imported only
when its entry is looked up, so loading one backend never loads the others.

    from rmot.backends import BACKENDS
    result = BACKENDS["rapid"]().emit(plan)      # EmitResult(files, diagnostics)
"""

from __future__ import annotations

import importlib
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from rmot.backends.base import Backend

__all__ = ["BACKENDS", "TARGETS", "Target", "controllers", "register", "targets", "unregister"]


@dataclass(frozen=True)
class Target:
    """One output target: its --target name, where its Backend class lives (a "module:Class"
    path, imported on first use, or the class itself) and whether it is a controller language
    (`native NAME { }` blocks may name it; csv and json are not)."""

    name: str
    where: str | type[Backend]
    controller: bool = True

    def backend(self) -> type[Backend]:
        if not isinstance(self.where, str):
            return self.where
        module_name, _, cls_name = self.where.partition(":")
        cls: type[Backend] = getattr(importlib.import_module(module_name), cls_name)
        if cls.name != self.name:
            raise TypeError(f"backend '{self.name}' is registered as {self.where}, whose name is "
                            f"'{cls.name}'")
        return cls


_REGISTRY: dict[str, Target] = {}


def register(name: str, where: str | type[Backend], *, controller: bool = True) -> Target:
    """Add output target `name` (see Target); a name registered twice is a programming error."""
    if name in _REGISTRY:
        raise ValueError(f"backend '{name}' is registered twice")
    _REGISTRY[name] = entry = Target(name, where, controller)
    return entry


def unregister(name: str) -> None:
    """Remove a target (tests that register a toy backend clean up with this)."""
    del _REGISTRY[name]


def targets() -> tuple[str, ...]:
    """Every --target name, in registration order."""
    return tuple(_REGISTRY)


def controllers() -> tuple[str, ...]:
    """The controller languages (targets a `native` block may name), in registration order."""
    return tuple(t.name for t in _REGISTRY.values() if t.controller)


# --target name -> "module:Class" (one line per backend)
register("rapid", "rmot.backends.rapid:RapidBackend")
register("krl", "rmot.backends.krl:KrlBackend")
register("fanuc", "rmot.backends.fanuc_tp:FanucBackend")
register("urscript", "rmot.backends.urscript:UrScriptBackend")
register("inform", "rmot.backends.inform:InformBackend")
register("val3", "rmot.backends.val3:Val3Backend")
register("csv", "rmot.backends.neutral:CsvBackend", controller=False)
register("json", "rmot.backends.neutral:JsonBackend", controller=False)


TARGETS: tuple[str, ...] = targets()
"""The targets registered when this package is imported (`targets()` is the live list)."""


class _LazyBackends(Mapping[str, "type[Backend]"]):
    """A read-only mapping that imports a vendor module on first lookup."""

    def __getitem__(self, key: str) -> type[Backend]:
        return _REGISTRY[key].backend()

    def __iter__(self) -> Iterator[str]:
        return iter(_REGISTRY)

    def __len__(self) -> int:
        return len(_REGISTRY)


BACKENDS: Mapping[str, type[Backend]] = _LazyBackends()
