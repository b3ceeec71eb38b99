"""RAPID, KRL and Fanuc TP for the shipped examples (real front end and planner) and for the
hand-built all-instructions sample: golden files, determinism, only documented refusals,
and rapidchecker on every RAPID module.

Golden files live in tests/backends/golden/<vendor>/<example>__<file>. They were reviewed by
hand against the vendor manuals (RAPID MoveL/MoveC/MoveAbsJ/robtarget/confdata, KRL
E6POS/E6AXIS/C_DIS/$BASE/$TOOL, TP /MN /POS and the CONFIG string). After a deliberate change
of the front end, planner or backend, regenerate with
`RMOT_UPDATE_GOLDEN=1 pytest tests/backends/test_examples.py` and review the diff by hand.
"""

from __future__ import annotations

import warnings

import pytest
from backend_fixtures import check_golden, example_plans, handshake_missing, sample_program

from rmot.backends import BACKENDS
from rmot.lang import plan_types

VENDORS = ("rapid", "krl", "fanuc")
EXAMPLES = ("inspect", "pick_place", "handover")
# sync is an I/O handshake there (backends/handshake.py)
HANDSHAKE_VENDORS = {v for v in VENDORS if BACKENDS[v].SYNC_HANDSHAKE}


@pytest.fixture(scope="module")
def plans() -> dict[str, plan_types.Plan]:
    return {**example_plans(EXAMPLES), "sample": sample_program()}


@pytest.mark.parametrize("vendor", VENDORS)
@pytest.mark.parametrize("example", ["inspect", "sample"])
def test_matches_golden_files(plans: dict[str, plan_types.Plan], example: str, vendor: str) -> None:
    """The inspect example and the all-instructions sample equal the reviewed golden files."""
    result = BACKENDS[vendor]().emit(plans[example])
    assert not result.has_errors, [d.message for d in result.diagnostics if d.is_error]
    check_golden(vendor, example, result.files)


@pytest.mark.parametrize("vendor", VENDORS)
@pytest.mark.parametrize("example", EXAMPLES)
def test_only_documented_refusals(plans: dict[str, plan_types.Plan], example: str, vendor: str) -> None:
    """Errors are only: a move the planner could not solve (E401), sync for KRL/TP in a cell
    without the handshake signals (E409); all have spans."""
    plan = plans[example]
    result = BACKENDS[vendor]().emit(plan)
    allowed = ({"E401"} if any(d.is_error for d in plan.diagnostics) else set()) | (
        {"E409"} if vendor in HANDSHAKE_VENDORS and handshake_missing(plan) else set())
    assert {d.code.id for d in result.diagnostics if d.is_error} <= allowed
    assert all(d.span is not None for d in result.diagnostics)


@pytest.mark.parametrize("vendor", VENDORS)
@pytest.mark.parametrize("example", EXAMPLES)
def test_two_emits_are_byte_identical(plans: dict[str, plan_types.Plan], example: str, vendor: str) -> None:
    """The same plan gives the same files, byte for byte."""
    assert BACKENDS[vendor]().emit(plans[example]).files == BACKENDS[vendor]().emit(plans[example]).files


@pytest.mark.parametrize("example", EXAMPLES)
def test_every_rapid_module_passes_rapidchecker(plans: dict[str, plan_types.Plan], example: str) -> None:
    """Every emitted RAPID module parses with rapidchecker (syntax, indentation, whitespace)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        from rapidchecker.cli import check_file

        for name, text in BACKENDS["rapid"]().emit(plans[example]).files.items():
            assert [str(e) for e in check_file(text)] == [], name
