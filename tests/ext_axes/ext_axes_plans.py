"""The plan of a program text that must load and plan without errors, for the external-axes
tests (the code under test; the witnesses are in ext_axes_witness)."""

from __future__ import annotations

from rmot.compiler.frontend import load_text
from rmot.compiler.plan import plan_program
from rmot.lang.plan_types import Plan


def planned(source: str, path: str) -> Plan:
    """The plan of `source` (read as the file `path`); fails the test on any error."""
    front = load_text(source, path)
    assert front.program is not None, [d.message for d in front.diagnostics]
    result = plan_program(front.program)
    errors = [d.message for d in result.diagnostics if d.is_error]
    assert not errors, errors
    return result
