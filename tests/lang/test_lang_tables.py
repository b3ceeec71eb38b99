"""The LALR tables as cached data (lang/_tables.py) and the lark versions they are read from."""

from __future__ import annotations

import json
import re
from pathlib import Path

import lark
import pytest
from rmot.lang import _tables, parse
from tests.core.cache_cli import entry_json, write_sealed
from rmot.lang._tables import (
    GRAMMAR,
    LARK_VERSIONS,
    build_tables,
    from_data,
    load_tables,
    tables_key,
)

ROOT = Path(__file__).resolve().parents[2]
PROGRAM = "program p on r1 {\n  move linear pose(x=1mm) speed 10 mm/s zone fine\n  wait 1 s\n}\n"


def _shape(t: _tables.LalrTables) -> tuple:  # type: ignore[type-arg]
    """The tables up to lark's state numbering (which differs between builds: lark numbers its
    states by set iteration order): states renumbered breadth-first from the start state over
    sorted symbols, reductions named by their rule."""
    rules = [repr(r.serialize()) for r in t.rules]
    order, seen = [t.start], {t.start: 0}
    for state in order:
        for _, (kind, arg) in sorted(t.states[state].items()):
            if kind == "s" and arg not in seen:
                seen[arg] = len(order)
                order.append(arg)
    states = [sorted((name, kind, seen[arg] if kind == "s" else rules[arg]) for name, (kind, arg) in t.states[s].items())
              for s in order]
    terminals = sorted((x.name, x.pattern.type, x.pattern.value) for x in t.terminals)
    return terminals, sorted(rules), states, seen[t.end], len(t.states)


def test_lark_is_a_version_whose_internals_were_checked() -> None:
    """Fails loudly on a lark release nobody checked the parse loop against (see LARK_VERSIONS)."""
    assert lark.__version__ in LARK_VERSIONS, (
        f"lark {lark.__version__} is not one of {LARK_VERSIONS}: lang/_lalr.py and lang/_tables.py read "
        "lark's internal tables; check them against this release, then add it to LARK_VERSIONS")


def test_pyproject_pins_lark_to_those_versions() -> None:
    text = (ROOT / "pyproject.toml").read_text(encoding="utf-8")
    pins = re.findall(r'"lark\s*([=<>~!][^"]*)"', text)  # requirement strings, not module names
    assert pins == [f"=={v}" for v in LARK_VERSIONS] or pins == [f"=={LARK_VERSIONS[0]}"], pins


def test_tables_read_back_equal_lark_s_own(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Written, read from the JSON file, rebuilt into lark objects: the same tables lark computed."""
    monkeypatch.setenv("RMOT_CACHE_DIR", str(tmp_path))
    text = GRAMMAR.read_text(encoding="utf-8")
    first = load_tables(text)
    files = list((tmp_path / "lalr").glob("*.json"))
    assert [f.name for f in files] == [f"{tables_key(text)}.json"]
    doc = entry_json(files[0])  # plain JSON (sealed), no pickle
    assert doc["key"] == tables_key(text) and doc["format"] == _tables.FORMAT
    fresh = from_data(build_tables(text))
    assert _shape(load_tables(text)) == _shape(fresh) == _shape(first)
    assert _shape(load_tables(text, use_cache=False)) == _shape(fresh)


def test_the_key_follows_the_grammar_text_and_lark() -> None:
    text = GRAMMAR.read_text(encoding="utf-8")
    assert tables_key(text) != tables_key(text + "\n// changed\n")
    assert tables_key(text) == tables_key(str(text))


@pytest.mark.parametrize("damage", ["garbage", "truncated", "other key", "bad rule index", "bad state"])
def test_a_damaged_file_is_ignored_and_rewritten(damage: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("RMOT_CACHE_DIR", str(tmp_path))
    text = GRAMMAR.read_text(encoding="utf-8")
    good = _shape(load_tables(text))
    path = tmp_path / "lalr" / f"{tables_key(text)}.json"
    doc = entry_json(path)
    if damage == "garbage":
        path.write_bytes(b"\x80not json")
    elif damage == "truncated":
        path.write_text(json.dumps(doc)[:5000], encoding="utf-8")
    else:
        if damage == "other key":
            doc["key"] = "0" * 64
        elif damage == "bad rule index":
            row = next(r for r in doc["states"] if any(a[1] == "r" for a in r))
            next(a for a in row if a[1] == "r")[2] = 10**6
        else:
            doc["start"] = -1
        write_sealed(path, tables_key(text), doc)  # sealed: the reader's shape checks refuse it
    assert _shape(load_tables(text)) == good
    rewritten = entry_json(path)
    assert rewritten["key"] == tables_key(text) and _shape(from_data(rewritten)) == good


def test_an_unwritable_cache_folder_still_parses(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    blocker = tmp_path / "file"
    blocker.write_text("not a folder", encoding="utf-8")
    monkeypatch.setenv("RMOT_CACHE_DIR", str(blocker))
    text = GRAMMAR.read_text(encoding="utf-8")
    assert _shape(load_tables(text)) == _shape(from_data(build_tables(text)))


def test_a_parse_on_cached_tables_gives_the_program() -> None:
    result = parse.parse_text(PROGRAM, "p.rmot")
    assert not result.diagnostics and result.module is not None
    assert [type(s).__name__ for s in result.module.body[0].body] == ["Move", "WaitTime"]
