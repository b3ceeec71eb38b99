"""ast.SettingKind: the setting keywords, each with a handler in the modal pass's table.

Witness: the grammar file lang/grammar/rmot.lark, read as text (not through the parser under
test): every kind is a keyword it spells in quotes, and every setting rule it names
(`*_setting`, `mod_*`, `model_*` yielding a Setting) builds a Setting of a known kind."""

from __future__ import annotations

import re
from enum import StrEnum
from pathlib import Path

import pytest

from rmot.compiler.passes.modal import SETTING_HANDLERS, require_setting_handlers
from rmot.lang import ast
from rmot.lang import parse_text

ROOT = Path(__file__).resolve().parents[2]
GRAMMAR = (ROOT / "lang" / "grammar" / "rmot.lark").read_text(encoding="utf-8")


@pytest.mark.parametrize("kind", list(ast.SettingKind))
def test_every_kind_is_a_keyword_of_the_grammar(kind: ast.SettingKind) -> None:
    assert re.search(rf'"{kind.value}"', GRAMMAR), f"'{kind}' is not a keyword of rmot.lark"


def test_kinds_compare_as_the_keyword_written() -> None:
    assert ast.SettingKind.JOINT_SPEED == "joint_speed"
    assert f"'{ast.SettingKind.ZONE}'" == "'zone'"  # diagnostics print the keyword


def test_the_modal_table_has_every_kind() -> None:
    assert set(SETTING_HANDLERS) == set(ast.SettingKind)


def test_a_kind_without_a_handler_is_refused() -> None:
    class More(StrEnum):
        TOOL = "tool"
        FORCE = "force"

    with pytest.raises(TypeError, match="no handler for setting kind force"):
        require_setting_handlers({"tool": None}, More)
    with pytest.raises(TypeError, match="unknown kind zone"):
        require_setting_handlers({"tool": None, "force": None, "zone": None}, More)


def test_the_parser_builds_settings_of_the_enum() -> None:
    text = ("move linear p speed 100 mm/s accel 2 m/s^2 zone fine tool g frame f "
            "config(elbow=up) time 2 s joint_speed 50 %")
    result = parse_text(text, "t.rmot")
    assert result.module is not None and not result.diagnostics
    (move,) = result.module.body
    assert isinstance(move, ast.Move)
    assert all(type(m.kind) is ast.SettingKind for m in move.modifiers)
