"""The one registry of output targets: --target name -> Backend class.

Every list of vendors in the project derives from it: `compile --target`
(compiler/cli/compile_cmd.py), the front end's `native NAME "..."` check
(compiler/passes/lower_body.py: `controllers()`), the backends' warning for another
controller's native block (backends/base.py), `rmot.backends.BACKENDS` and the tests. Adding a
backend is one module under backends/ plus one `register(...)` line below (CONTRIBUTING.md).

It lives in the compiler (not in backends/) because the front end must know the controller
names and the compiler never imports a backend (tests/core/test_architecture.py): a target is
named here by its "module:Class" path, imported only when it is looked up.
"""

from __future__ import annotations

import importlib

from rmot.lang.record import record

__all__ = ["Target", "controllers", "lookup", "register", "targets", "unregister"]


@record
class Target:
    """One output target: its --target name, where its Backend class lives (a "module:Class"
    path, imported on first use, or the class itself) and whether it is a controller language
    (`native NAME "..."` may name it; csv and json are not)."""

    name: str
    where: str | type
    controller: bool = True

    def backend(self) -> type:
        """The Backend class (imported on first use); its `name` must be this target's."""
        if isinstance(self.where, str):
            module_name, _, cls_name = self.where.partition(":")
            cls: type = getattr(importlib.import_module(module_name), cls_name)
        else:
            cls = self.where
        if getattr(cls, "name", None) != self.name:
            raise TypeError(f"backend '{self.name}' is registered as {self.where}, whose name is "
                            f"'{getattr(cls, 'name', None)}'")
        cls.validate_kinds()  # type: ignore[attr-defined]  # every motion kind has a handler
        return cls


_REGISTRY: dict[str, Target] = {}


def register(name: str, where: str | type, *, controller: bool = True) -> Target:
    """Add output target `name` (see Target); a name registered twice is a programming error."""
    if name in _REGISTRY:
        raise ValueError(f"backend '{name}' is registered twice")
    _REGISTRY[name] = entry = Target(name, where, controller)
    return entry


def unregister(name: str) -> None:
    """Remove a target (a test that registers a toy backend cleans up with this)."""
    del _REGISTRY[name]


def lookup(name: str) -> Target:
    """The registered target `name` (KeyError when there is none)."""
    return _REGISTRY[name]


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
