"""Diagnostic codes of the pictures: the renderer (E58x, in the E5xx files range) and the plots
and reports made of them (E600/W600)."""

from __future__ import annotations

from rmot.lang.diagnostics import Code

__all__ = [
    "FORMAT_UNAVAILABLE", "NOTHING_TO_RENDER", "OUTPUT_FAILED", "REPORT_PART_MISSING", "TIME_OUTSIDE",
    "VIEW_OUTPUT_FAILED",
]

OUTPUT_FAILED = Code("E580", "render-output-failed", "the rendered file cannot be written")
FORMAT_UNAVAILABLE = Code("E581", "render-format-unavailable", "the output format needs a missing encoder")
TIME_OUTSIDE = Code("E582", "render-time-outside-program", "--at names an instant outside the program")
NOTHING_TO_RENDER = Code("E583", "render-no-program", "the input file holds no program to render")

# `rmot plot` and `rmot report`
VIEW_OUTPUT_FAILED = Code("E600", "view-output-failed", "the plot or report file cannot be written")
REPORT_PART_MISSING = Code("W600", "report-part-missing", "a picture or plot of the report could not be made")
