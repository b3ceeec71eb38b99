"""Diagnostic codes of the renderer (the 58x block of the E5xx files range)."""

from __future__ import annotations

from rmot.lang.diagnostics import Code

__all__ = ["OUTPUT_FAILED", "FORMAT_UNAVAILABLE", "TIME_OUTSIDE", "SCENE_INCOMPLETE"]

OUTPUT_FAILED = Code("E580", "render-output-failed", "the rendered file cannot be written")
FORMAT_UNAVAILABLE = Code("E581", "render-format-unavailable", "the output format needs a missing encoder")
TIME_OUTSIDE = Code("E582", "render-time-outside-program", "--at names an instant outside the program")
SCENE_INCOMPLETE = Code("W580", "render-scene-incomplete", "a body could not be loaded and is not drawn")
