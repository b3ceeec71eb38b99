"""Diagnostic codes of the command line's own file handling (E53x: reports it reads back)."""

from __future__ import annotations

from rmot.lang.diagnostics import Code

__all__ = ["REPORT_UNREADABLE", "REPORT_FORMAT", "REPORTS_MISMATCH", "REPORT_UNWRITABLE"]

REPORT_UNREADABLE = Code("E530", "report-unreadable", "a report given to merge-reports cannot be read")
REPORT_FORMAT = Code("E531", "report-format", "a file given to merge-reports is not a JUnit, SARIF or rmot JSON report")
REPORTS_MISMATCH = Code("E532", "reports-mismatch", "reports given to merge-reports differ in format or version")
REPORT_UNWRITABLE = Code("E533", "report-unwritable", "the merged report cannot be written where -o says")

# one CLI pipeline (compiler/cli/stages.py): a stage that fails unexpectedly
INTERNAL_ERROR = Code("E550", "internal-error",
                      "a stage of rmot failed unexpectedly (a bug in rmot, not in the input): "
                      "the message names the stage and the exception; please report it")
__all__ += ["INTERNAL_ERROR"]
