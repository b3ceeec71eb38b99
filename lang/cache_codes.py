"""Diagnostic codes of the plan cache (E700–E709, W700–W709)."""

from __future__ import annotations

from rmot.lang.diagnostics import Code

__all__ = ["CACHE_UNWRITABLE"]

CACHE_UNWRITABLE = Code("W700", "plan-cache-unwritable",
                        "the plan cache directory cannot be written; the plan was computed without it")
