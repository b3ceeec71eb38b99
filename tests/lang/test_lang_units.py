"""Units: one table (lang/units.py) for the lexer, the E007 suggestions and the evaluator."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from rmot.compiler.frontend import load_text
from rmot.compiler.passes import values
from rmot.lang import parse_text
from rmot.lang.units import BASE_UNITS, UNIT_TABLE

ROOT = Path(__file__).resolve().parents[2]
_PATH = str(ROOT / "examples" / "units_probe.rmot")
_WORDS = st.sampled_from([*BASE_UNITS, "s", "x", "kgs", "foo", "mm2", "sec", "deg", "h"]) | st.from_regex(r"[a-z]{1,4}", fullmatch=True)
_SETTINGS = settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def _program(expr: str) -> str:
    return f"program p {{\n  speed {expr}\n  move joint joints(0, 0, 0, 0, 0, 0) deg\n}}\n"


def _codes(text: str) -> list[str]:
    return [d.code.id for d in load_text(text, _PATH).diagnostics if d.is_error]


class TestOneTable:
    def test_evaluator_reads_the_language_table(self) -> None:
        """The compiler's unit table is the language's table (no second list to drift)."""
        assert values.UNIT_TABLE is UNIT_TABLE

    @pytest.mark.parametrize("unit", sorted(UNIT_TABLE))
    def test_every_unit_in_the_table_parses_as_that_unit(self, unit: str) -> None:
        """Each unit of the table lexes as one unit token after a number."""
        result = parse_text(f"const c = 2 {unit}\n")
        assert result.diagnostics == ()
        number = result.module.body[0].value
        assert number.unit == unit

    @pytest.mark.parametrize(("text", "si"), [("3 cm/s", 0.03), ("2 in/s", 0.0508), ("4 cm/s^2", 0.04),
                                              ("1 in/s^2", 0.0254)])
    def test_inch_and_centimetre_rates_are_converted(self, text: str, si: float) -> None:
        """cm/s and in/s (missing from an older suggestion list) are full units with SI factors."""
        factor, _ = UNIT_TABLE[text.split()[1]]
        assert math.isclose(float(text.split()[0]) * factor, si)


class TestUnknownCompound:
    @pytest.mark.parametrize("unit", ["kg/s", "g/s", "min/s", "ms/s", "s/s", "kg/s^2"])
    def test_unknown_compound_unit_is_e007_not_a_traceback(self, unit: str) -> None:
        """`speed 3 kg/s` reports one E007 at the unit (it used to raise KeyError)."""
        result = load_text(_program(f"3 {unit}"), _PATH)
        errors = [d for d in result.diagnostics if d.is_error]
        assert [d.code.id for d in errors] == ["E007"]
        assert f"(got '{unit}')" in errors[0].message
        assert errors[0].span.start.line == 2 and errors[0].span.start.col == 11

    def test_suggestion_names_the_nearest_unit(self) -> None:
        """The did-you-mean comes from the same table: `ms/s` suggests a speed unit."""
        message = load_text(_program("3 ms/s"), _PATH).diagnostics[0].message
        assert "did you mean 'mm/s'?" in message or "did you mean 'm/s'?" in message

    def test_unknown_unit_in_joints_is_e007(self) -> None:
        """`joints(...) g/s` is E007 too, not a KeyError in the joint evaluator."""
        text = "program p {\n  move joint joints(0, 0, 0, 0, 0, 0) g/s\n}\n"
        assert _codes(text) == ["E007"]


# the speed units and their SI factors, written out here (not read from lang/units.py): the
# inch is 25.4 mm exactly (international yard and pound agreement, 1959)
_SPEED_SI = {"mm/s": 1e-3, "cm/s": 1e-2, "m/s": 1.0, "in/s": 0.0254}
_SPEED_RANGE = (1e-3, 10.0)  # m/s: `speed` accepts 1 mm/s .. 10000 mm/s (E125 outside, inclusive)


@_SETTINGS
@given(st.floats(0, 1e4, allow_nan=False).map(lambda x: f"{x:g}"),
       st.sampled_from(sorted(_SPEED_SI)) | st.tuples(_WORDS, _WORDS).map("/".join))
def test_number_word_over_word_is_a_speed_or_an_error(number: str, unit: str) -> None:
    """`speed <number> <word>/<word>` never raises, and it is accepted exactly when the word
    pair is a speed unit and the value lies in the accepted range; the move then runs at the
    value in m/s (an independent conversion), otherwise there is an error and no program."""
    result = load_text(_program(f"{number} {unit}"), _PATH)
    si = float(number) * _SPEED_SI[unit] if unit in _SPEED_SI else None
    lo, hi = _SPEED_RANGE
    assume(si is None or not (math.isclose(si, lo) or math.isclose(si, hi)))  # no boundary ties
    if si is not None and lo <= si <= hi:
        assert not result.has_errors, [d.message for d in result.diagnostics]
        assert result.program is not None
        move = result.program.tasks[0].body[0]
        assert math.isclose(move.motion.tcp_speed, si, rel_tol=1e-12)
    else:
        assert result.has_errors and result.program is None


@_SETTINGS
@given(st.integers(0, 999).map(str), st.sampled_from(sorted(UNIT_TABLE)), st.integers(-3, 5))
def test_number_unit_power_never_raises(number: str, unit: str, k: int) -> None:
    """Any `<number> <unit>^k` gives diagnostics, never an exception."""
    result = load_text(_program(f"{number} {unit}^{k}"), _PATH)
    assert result.has_errors
