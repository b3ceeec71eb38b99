"""Diagnostic codes of the renderer (the 58x block of the E5xx files range)."""

from __future__ import annotations

from rmot.lang.diagnostics import Code

__all__ = ["FORMAT_UNAVAILABLE", "NOTHING_TO_RENDER", "OUTPUT_FAILED", "TIME_OUTSIDE"]

OUTPUT_FAILED = Code("E580", "render-output-failed", "the rendered file cannot be written")
FORMAT_UNAVAILABLE = Code("E581", "render-format-unavailable", "the output format needs a missing encoder")
TIME_OUTSIDE = Code("E582", "render-time-outside-program", "--at names an instant outside the program")
NOTHING_TO_RENDER = Code("E583", "render-no-program", "the input file holds no program to render")
