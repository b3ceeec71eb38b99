"""lang/editors/: the TextMate grammar and the VS Code extension's files load and agree with
the language: every keyword the parser knows is coloured as a keyword, comments are the
lexer's, each file the extension names exists.

The witness of what is a keyword is the parser itself (lang/_build.py KEYWORDS and the
keywords the LALR tables accept at a statement's start), not a list written here; the
grammar is run by a small TextMate-style matcher (each pattern's regex tried at the
earliest position, first pattern wins, as TextMate does).
"""

from __future__ import annotations

import json
import re
from pathlib import Path
from typing import Any

import pytest

from rmot.compiler.lsp.features import statement_keywords
from rmot.lang.lexer import IO_WORDS
from rmot.lang.parse import KEYWORDS
from rmot.lang.units import UNIT_NAMES

EDITORS = Path(__file__).resolve().parents[2] / "lang" / "editors"


def _json(name: str) -> Any:
    return json.loads((EDITORS / name).read_text(encoding="utf-8"))


def _patterns(grammar: dict[str, Any]) -> list[dict[str, Any]]:
    return [grammar["repository"][p["include"][1:]] for p in grammar["patterns"]]


def _scopes(line: str) -> list[tuple[str, str]]:
    """(text, scope) of each token the grammar finds in `line` (TextMate's rule: the match
    that starts earliest wins, ties to the first pattern)."""
    rules = []
    for rule in _patterns(_json("rmot.tmLanguage.json")):
        regex = rule.get("match") or rule["begin"] + r"(?:[^\"\\]|\\.)*" + rule["end"]
        rules.append((re.compile(regex), rule))
    out, pos = [], 0
    while pos < len(line):
        found = [(m.start(), i, m, rule) for i, (rx, rule) in enumerate(rules) if (m := rx.search(line, pos))]
        if not found:
            break
        _start, _i, match, rule = min(found, key=lambda f: (f[0], f[1]))
        if "captures" in rule:
            out += [(match.group(int(k)), v["name"]) for k, v in rule["captures"].items() if match.group(int(k))]
        else:
            out.append((match.group(0), rule["name"]))
        pos = max(match.end(), pos + 1)
    return out


def test_grammar_loads_with_the_language_scope() -> None:
    grammar = _json("rmot.tmLanguage.json")
    assert grammar["scopeName"] == "source.rmot"
    for p in grammar["patterns"]:
        assert p["include"][1:] in grammar["repository"]


@pytest.mark.parametrize("word", sorted(KEYWORDS | set(statement_keywords())))
def test_every_parser_keyword_is_a_keyword(word: str) -> None:
    scopes = dict(_scopes(f"{word} "))
    assert word in scopes, f"{word!r} is not coloured"
    assert scopes[word].startswith(("keyword", "constant.language", "support")), scopes


def test_a_line_gets_its_scopes() -> None:
    tokens = _scopes('  move linear shift(p, z=100mm) speed 250 mm/s   # "not a string"')
    assert ("move", "keyword.control.rmot") in tokens
    assert ("shift", "support.function.rmot") in tokens
    assert ("100", "constant.numeric.rmot") in tokens and ("mm", "keyword.other.unit.rmot") in tokens
    assert ("mm/s", "keyword.other.unit.rmot") in tokens
    assert tokens[-1] == ('# "not a string"', "comment.line.number-sign.rmot")
    tokens = _scopes("target home = joints(0, -10, 10, 0, 90, 0) deg")
    assert tokens[:2] == [("target", "keyword.declaration.rmot"), ("home", "entity.name.rmot")]


@pytest.mark.parametrize("unit", UNIT_NAMES)
def test_every_unit_is_a_unit(unit: str) -> None:
    assert ("2", "constant.numeric.rmot") in _scopes(f"wait 2 {unit}")
    assert (unit, "keyword.other.unit.rmot") in _scopes(f"wait 2 {unit}")


def test_the_extension_names_files_that_exist() -> None:
    package = _json("package.json")
    (language,) = package["contributes"]["languages"]
    assert language["extensions"] == [".rmot"]
    (grammar,) = package["contributes"]["grammars"]
    assert grammar["scopeName"] == "source.rmot" and (EDITORS / grammar["path"]).is_file()
    assert (EDITORS / language["configuration"]).is_file() and (EDITORS / package["main"]).is_file()
    config = _json("language-configuration.json")
    assert config["comments"] == {"lineComment": "#"}  # the lexer's comment (lang/lexer.py)
    assert ["{", "}"] in config["brackets"] and ["(", ")"] in config["brackets"]


@pytest.mark.parametrize("word", sorted(IO_WORDS))
def test_an_io_word_is_a_read_only_before_a_bracket(word: str) -> None:
    """As the lexer types it (lang/lexer.py IO_WORDS): `gin[1]` a port read, `gin` alone a name."""
    assert (word, "support.variable.io.rmot") in _scopes(f"if {word} [1] > 2")
    assert (word, "support.variable.io.rmot") not in _scopes(f"var k = {word} + 1")
