"""A safe, generic codec for the Plan: dataclasses, enums, tuples and numpy arrays -> JSON + arrays.

Inputs are data, never code: no pickle. A value is encoded as JSON; every numpy array goes to a
separate list (stored by the caller in an .npz and read back with allow_pickle=False), referenced
from the JSON by index. Types are restored only from an explicit registry of allowed classes:
the dataclasses and enums defined in ALLOWED_MODULES (so a field another stage adds to a Plan
type round-trips without a change here, and a class from anywhere else is refused).

    doc, arrays = encode(plan)        # doc: JSON-able; arrays: list[np.ndarray]
    plan = decode(doc, arrays)        # raises CodecError for anything unexpected

Shared objects (the same ir.Task in Plan.program and in TaskPlan.task, the one SourceFile of
every Span) are written once and referenced afterwards, so sharing survives the round trip.
Dataclasses are rebuilt without calling __init__ (field by field), so a decoded value is the
value that was encoded, whatever its __post_init__ would compute.
"""

from __future__ import annotations

import dataclasses
import enum
import importlib
import math
from typing import Any, Callable

import numpy as np

from rmot.lang.diagnostics import _REGISTRY as _CODE_REGISTRY
from rmot.lang.diagnostics import Code

__all__ = ["ALLOWED_MODULES", "CodecError", "decode", "encode", "allowed_types"]

# The modules whose dataclasses and enums may appear in a Plan (the Plan, the IR, spans, diagnostics).
ALLOWED_MODULES = (
    "rmot.lang.plan_types",
    "rmot.lang.ir",
    "rmot.lang.ir_axes",  # external axes (ir.Cell.external)
    "rmot.lang.payload",  # the load each task carries (TaskPlan.load)
    "rmot.lang.source",
    "rmot.lang.diagnostics",
)

_REGISTRY: dict[str, type] | None = None


class CodecError(ValueError):
    """A value that this codec does not encode, or a document it does not trust."""


def _type_name(cls: type) -> str:
    return f"{cls.__module__}:{cls.__qualname__}"


def allowed_types() -> dict[str, type]:
    """'module:QualName' -> class, for every dataclass and Enum defined in ALLOWED_MODULES."""
    global _REGISTRY
    if _REGISTRY is None:
        found: dict[str, type] = {}
        for name in ALLOWED_MODULES:
            module = importlib.import_module(name)
            for value in vars(module).values():
                if isinstance(value, type) and value.__module__ == name and (
                        dataclasses.is_dataclass(value) or issubclass(value, enum.Enum)):
                    found[_type_name(value)] = value
        _REGISTRY = found
    return _REGISTRY


# ---------------------------------------------------------------------------- encode
def encode(value: Any) -> tuple[Any, list[np.ndarray]]:
    """(JSON-able document, arrays). Raises CodecError for a type outside the registry."""
    arrays: list[np.ndarray] = []
    memo: dict[int, int] = {}
    keep: list[Any] = []  # keeps memoised objects alive so their id() stays unique
    registry = allowed_types()

    def enc(v: Any) -> Any:
        if v is None or type(v) in (bool, str, int):
            return v
        if type(v) is float:
            return v if math.isfinite(v) else {"$f": repr(v)}
        if isinstance(v, enum.Enum):
            name = _type_name(type(v))
            if name not in registry:
                raise CodecError(f"enum type {name} is not in the codec's registry")
            return {"$e": name, "v": v.name}
        if isinstance(v, np.ndarray):
            if v.dtype.hasobject:
                raise CodecError("object arrays are not encoded (they would need pickle)")
            arrays.append(np.ascontiguousarray(v))
            return {"$a": len(arrays) - 1, "w": bool(v.flags.writeable)}
        if isinstance(v, np.generic):
            if isinstance(v, np.object_):
                raise CodecError("object scalars are not encoded")
            return {"$s": v.dtype.str, "v": enc(v.item())}
        if isinstance(v, tuple) and type(v) is tuple:
            return {"$t": [enc(x) for x in v]}
        if type(v) is list:
            return [enc(x) for x in v]
        if type(v) is dict:
            return {"$d": [[enc(k), enc(x)] for k, x in v.items()]}
        if type(v) in (frozenset, set):
            items = [enc(x) for x in v]
            return {"$fs" if type(v) is frozenset else "$set": sorted(items, key=repr)}
        if dataclasses.is_dataclass(v) and not isinstance(v, type):
            ref = memo.get(id(v))
            if ref is not None:
                return {"$r": ref}
            name = _type_name(type(v))
            if registry.get(name) is not type(v):
                raise CodecError(f"type {name} is not in the codec's registry")
            fields = {f.name: enc(getattr(v, f.name)) for f in dataclasses.fields(v)}
            memo[id(v)] = len(memo)
            keep.append(v)
            return {"$c": name, "id": memo[id(v)], "f": fields}
        raise CodecError(f"type {type(v).__module__}.{type(v).__qualname__} is not encoded")

    return enc(value), arrays


# ---------------------------------------------------------------------------- decode
def decode(doc: Any, arrays: list[np.ndarray] | dict[int, np.ndarray]) -> Any:
    """The value `encode` was given. Raises CodecError for a document it did not write."""
    registry = allowed_types()
    objects: dict[int, Any] = {}

    def dec(v: Any) -> Any:
        if v is None or isinstance(v, (bool, str, int, float)):
            return v
        if isinstance(v, list):
            return [dec(x) for x in v]
        if not isinstance(v, dict) or len(v) == 0:
            raise CodecError(f"unexpected value in a plan document: {type(v).__name__}")
        if "$t" in v:
            return tuple(dec(x) for x in v["$t"])
        if "$r" in v:
            try:
                return objects[v["$r"]]
            except KeyError:
                raise CodecError("a reference to an object not yet decoded") from None
        if "$c" in v:
            obj = _decode_object(v, registry, dec)
            objects[v["id"]] = obj
            return obj
        if "$a" in v:
            a = arrays[v["$a"]]
            a = np.array(a)  # own the memory (the npz member may be a view of the file)
            a.setflags(write=bool(v["w"]))
            return a
        if "$e" in v:
            cls = registry.get(v["$e"])
            if cls is None or not issubclass(cls, enum.Enum):
                raise CodecError(f"enum {v['$e']!r} is not allowed in a plan document")
            return cls[v["v"]]
        if "$f" in v:
            return float(v["$f"])
        if "$s" in v:
            return np.dtype(v["$s"]).type(dec(v["v"]))
        if "$d" in v:
            return {dec(k): dec(x) for k, x in v["$d"]}
        if "$fs" in v:
            return frozenset(dec(x) for x in v["$fs"])
        if "$set" in v:
            return {dec(x) for x in v["$set"]}
        raise CodecError(f"unexpected object in a plan document: {sorted(v)[:3]}")

    try:
        return dec(doc)
    except CodecError:
        raise
    except (KeyError, IndexError, TypeError, ValueError, AttributeError) as exc:
        raise CodecError(f"malformed plan document ({exc.__class__.__name__}: {exc})") from None


def _decode_object(v: dict[str, Any], registry: dict[str, type], dec: Callable[[Any], Any]) -> Any:
    """A registered dataclass instance from its fields, built without running its __init__ (the
    fields were checked when it was encoded); a type not registered, or fields that differ from
    the class (an entry written by another version), is a CodecError."""
    cls = registry.get(v["$c"])
    if cls is None or not dataclasses.is_dataclass(cls):
        raise CodecError(f"type {v['$c']!r} is not allowed in a plan document")
    names = {f.name for f in dataclasses.fields(cls)}
    given = v["f"]
    if set(given) != names:
        raise CodecError(f"fields of {v['$c']} differ from the class (stale entry)")
    obj = object.__new__(cls)
    for key, item in given.items():
        object.__setattr__(obj, key, dec(item))
    return _intern(obj)


def _intern(obj: Any) -> Any:
    """A registered diagnostic Code decodes to the registered object itself (codes are singletons)."""
    if type(obj) is Code:
        known = _CODE_REGISTRY.get(obj.id)
        if known is not None and known == obj:
            return known
    return obj
