"""One program per vendor golden file: tests/backends/programs/tour.rmot has an
arc, blended joint moves, I/O waits with and without timeout, an if/else, a proc, a tool
change and a frame change, a numbered tool and frame and unnumbered ones. Its files for all
six vendors are in golden/<vendor>/tour__<file>, reviewed line by line against the manuals
(the review notes are in lang/REFERENCE.md §8 and the backends' docstrings); after a
deliberate change regenerate with `RMOT_UPDATE_GOLDEN=1 pytest tests/backends/test_golden_tour.py`
and review the diff by hand. test_vendor_validators.py runs them through the independent
validators."""

from __future__ import annotations

from pathlib import Path

import pytest
from backend_fixtures import check_golden

from rmot.backends import BACKENDS
from rmot.lang import plan_types
from rmot.backends import controllers

TOUR = Path(__file__).parent / "programs" / "tour.rmot"
VENDORS = controllers()


@pytest.fixture(scope="module")
def tour() -> plan_types.Plan:
    from rmot.compiler.frontend import load_program
    from rmot.compiler.plan import plan_program

    front = load_program(str(TOUR))
    assert front.program is not None and not any(d.is_error for d in front.diagnostics)
    plan = plan_program(front.program)
    assert not any(d.is_error for d in plan.diagnostics)
    return plan


@pytest.mark.parametrize("vendor", VENDORS)
def test_tour_matches_golden_files(tour: plan_types.Plan, vendor: str) -> None:
    result = BACKENDS[vendor]().emit(tour)
    assert not result.has_errors, [d.message for d in result.diagnostics if d.is_error]
    check_golden(vendor, "tour", result.files)


@pytest.mark.parametrize("vendor", VENDORS)
def test_tour_diagnostics(tour: plan_types.Plan, vendor: str) -> None:
    """The tour's warnings are the documented ones: the brand (an ABB arm) for every other
    vendor, Fanuc's overwritten UTOOL/UFRAME for the unnumbered pointer, flange and side frame."""
    codes = {d.code.id for d in BACKENDS[vendor]().emit(tour).diagnostics}
    assert ("W415" in codes) == (vendor != "rapid")
    assert ("W416" in codes) == (vendor == "fanuc")
