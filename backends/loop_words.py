"""The words of the loop analysis' W420 reasons (backends/loops.py): what an instruction is
called, what each of its fields means, and how two values that differ are shown."""

from __future__ import annotations

from collections.abc import Hashable
from dataclasses import fields, is_dataclass
from typing import Any

from rmot.lang import ir

__all__ = ["field_words", "kind_words", "show", "show_difference", "show_key"]


def kind_words(node: ir.Instr) -> str:
    if isinstance(node, ir.Move):
        return f"{node.kind.name.lower()} move"
    return {
        "SetDigital": "set",
        "SetAnalog": "set analog",
        "WaitTime": "wait",
        "WaitInput": "wait until",
        "WaitCondition": "wait until",
        "If": "if",
        "ProcCall": "call",
        "VarDecl": "var",
        "Assign": "assignment",
        "Loop": "loop",
        "While": "while",
        "Stop": "stop",
    }.get(type(node).__name__, type(node).__name__)


def field_words(name: str) -> str:
    return {
        "motion": "speed/zone",
        "frame": "frame",
        "tool": "tool",
        "config": "config",
        "port": "port",
        "value": "value",
        "kind": "motion kind",
        "target": "target",
        "condition": "condition",
        "duration": "duration",
        "min_duration": "time the external axes need (s)",
        "ext": "external axis values",
    }.get(name, name.replace("_", " "))


def show(v: Any) -> str:
    text = repr(v)
    return text if len(text) <= 60 else text[:57] + "..."


def show_difference(here: Any, first: Any) -> str:
    """`here vs first`; of two records of one type only the fields that differ, by name (a
    Motion that differs only in the time its external axes need says just that)."""
    if type(here) is type(first) and is_dataclass(here) and not isinstance(here, type):
        names = [f.name for f in fields(here) if f.name not in ("uid", "span")
                 and repr(getattr(here, f.name)) != repr(getattr(first, f.name))]
        if names:
            return "; ".join(f"{field_words(n)} {_show_value(getattr(here, n))} vs "
                             f"{_show_value(getattr(first, n))}" for n in names)
    return f"{show(here)} vs {show(first)}"


def _show_value(v: Any) -> str:
    if v is None:
        return "none"
    return f"{v:.6g}" if isinstance(v, float) else show(v)


def show_key(k: Hashable) -> str:
    if isinstance(k, tuple) and len(k) == 2 and isinstance(k[0], ir.Config):
        return f"({k[0]}; turns {k[1]})"
    return str(k)
