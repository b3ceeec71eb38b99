"""Diagnostic codes of `rmot plot` and `rmot report` (the E60x/W60x block)."""

from __future__ import annotations

from rmot.lang.diagnostics import Code

__all__ = ["OUTPUT_FAILED", "PART_MISSING"]

OUTPUT_FAILED = Code("E600", "view-output-failed", "the plot or report file cannot be written")
PART_MISSING = Code("W600", "report-part-missing", "a picture or plot of the report could not be made")
