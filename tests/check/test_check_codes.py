"""The front end's diagnostic codes: registered, unique, in their stage's range, each used by a fixture."""

from __future__ import annotations

import re
from pathlib import Path

from rmot.lang import check_codes as check_codes
from rmot.lang import codes as lang_codes
from rmot.lang.diagnostics import Code, all_codes

BAD = Path(__file__).resolve().parents[1] / "data" / "bad"


def _codes(module: object) -> list[Code]:
    return [getattr(module, name) for name in module.__all__]  # type: ignore[attr-defined]


def test_codes_are_registered_and_in_range() -> None:
    """E0xx for the language, E1xx/W1xx for checks, E5xx/W5xx for files; names are kebab-case."""
    registered = {c.id: c for c in all_codes()}
    for code in _codes(lang_codes):
        assert re.fullmatch(r"E0\d\d", code.id) and registered[code.id] is code
    for code in _codes(check_codes):
        # E809/W801: a cell model's masses and ratings, numbered in the design range
        # and reported by the front end's model pass (compiler/passes/lower_model.py)
        assert re.fullmatch(r"[EW]1\d\d|[EW]5\d\d|E809|W801", code.id), code
        assert registered[code.id] is code
    for code in _codes(lang_codes) + _codes(check_codes):
        assert re.fullmatch(r"[a-z]+(-[a-z0-9]+)*", code.name), code


def test_most_codes_have_a_fixture() -> None:
    """Each front-end code except the few that need generated input appears in a bad fixture."""
    text = "".join(p.read_text(encoding="utf-8") for p in BAD.glob("*.rmot"))
    generated = {"E009", "E010", "E502", "E503", "E505", "E121"}  # tested in test_check_bad_inputs
    generated |= {"E011", "E012", "E520", "E521", "E522"}  # line breaks, OS errors: tests/robust
    generated |= {"E564", "E565"}  # outputs that would replace inputs or foreign folders: tests/robust/cases.py
    generated |= {"W123"}  # a warning (fixtures declare errors): tested in test_check_config_and_ranges
    generated |= {"W135"}  # a warning: tested in tests/robots/test_cell_model.py
    generated |= {"W140"}  # a warning: tested in test_check_parts
    generated |= {"W170", "W171"}  # warnings: tested in test_check_speed_turns
    generated |= {"W150", "W151"}  # warnings: tested in tests/runtime/test_runtime_frontend.py
    generated |= {"W153"}  # a warning: tested in tests/check/test_proc_never_called.py
    generated |= {"E166", "E167", "E168", "W152"}  # group inputs, each located: tests/runtime/test_group_input.py
    generated |= {"E809", "W801"}  # model masses and ratings: tests/robots/test_model_dynamics.py
    generated |= {"E187", "E540", "E541", "E542", "E543"}  # need URDF / xacro / STEP files: tests/robots/test_xacro.py,
    # tests/robots/test_controller_conventions.py, tests/sim/test_step.py
    generated |= {"E547", "E548", "E549", "W547", "W548"}  # robot tables of `rmot robots add`: tests/robots/test_robots_add.py
    missing = [c.id for c in _codes(lang_codes) + _codes(check_codes) if c.id not in text and c.id not in generated]
    assert missing == [], missing
