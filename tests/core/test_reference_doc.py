"""lang/REFERENCE.md stays true: every registered diagnostic code is in its table, codes are
unique, and every complete `rmot` example compiles (error examples give their code).

Regenerate the code table after adding codes:

    .venv/bin/python tests/core/test_reference_doc.py --write
"""

from __future__ import annotations

import importlib
import re
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
REFERENCE = ROOT / "lang" / "REFERENCE.md"
PACKAGES = {"lang": "rmot.lang", "compiler": "rmot.compiler", "sim": "rmot.sim", "backends": "rmot.backends"}
BEGIN, END = "<!-- codes:begin -->", "<!-- codes:end -->"
_FENCE = re.compile(r"^```([A-Za-z0-9_-]*)[^\n]*\n(.*?)^```", re.S | re.M)
_ROW = re.compile(r"^\| ([EW]\d{3}) \| `([^`]+)` \|", re.M)
_EXPECTED = re.compile(r"^#\s*E:\s*([EW]\d{3})\b")
_COMPLETE = re.compile(r"^\s*(program|cell)\b", re.M)


def codes_modules() -> list[str]:
    """Every `*codes.py` module under the four package folders, as import names."""
    names = []
    for folder, package in PACKAGES.items():
        for path in sorted((ROOT / folder).glob("**/*codes.py")):
            rel = path.relative_to(ROOT / folder).with_suffix("")
            names.append(".".join((package, *rel.parts)))
    return names


def registered_codes() -> tuple:
    """Every code the package's codes modules define (a new module is picked up by the glob).

    Read from the modules themselves, not from all_codes(): tests register codes of their
    own (E999) in the same process, and those belong in no reference.
    """
    found = {}
    for name in codes_modules():
        for value in vars(importlib.import_module(name)).values():
            if type(value).__name__ == "Code":
                found[value.id] = value
    return tuple(sorted(found.values(), key=lambda c: c.id))


def code_table() -> str:
    """The markdown table of section 10, one row per registered code, sorted by id."""
    owner = {}
    for name in codes_modules():
        for value in vars(importlib.import_module(name)).values():
            if type(value).__name__ == "Code":
                owner.setdefault(value.id, name)
    rows = ["| id | name | summary | registered in |", "|---|---|---|---|"]
    for c in registered_codes():
        summary = c.summary.replace("|", "\\|")
        rows.append(f"| {c.id} | `{c.name}` | {summary} | `{owner.get(c.id, '?')}` |")
    return "\n".join(rows)


def write_table() -> None:
    text = REFERENCE.read_text(encoding="utf-8")
    head, rest = text.split(BEGIN, 1)
    _, tail = rest.split(END, 1)
    REFERENCE.write_text(f"{head}{BEGIN}\n{code_table()}\n{END}{tail}", encoding="utf-8")


def _blocks(kind: str) -> list[tuple[int, str]]:
    text = REFERENCE.read_text(encoding="utf-8")
    return [(text.count("\n", 0, m.start()) + 1, m.group(2)) for m in _FENCE.finditer(text) if m.group(1) == kind]


def _table_rows() -> dict[str, list[str]]:
    text = REFERENCE.read_text(encoding="utf-8")
    section = text.split(BEGIN, 1)[1].split(END, 1)[0]
    rows: dict[str, list[str]] = {}
    for code_id, name in _ROW.findall(section):
        rows.setdefault(code_id, []).append(name)
    return rows


def _load(source: str, tmp_path: Path):  # type: ignore[no-untyped-def]
    from rmot.compiler.frontend import load_text

    return load_text(source, str(tmp_path / "example.rmot"))


class TestCodeTable:
    def test_every_registered_code_is_in_the_table(self) -> None:
        """Each code of all_codes() has a row in REFERENCE.md with its id and name."""
        rows = _table_rows()
        missing = [f"{c.id} {c.name}" for c in registered_codes() if c.name not in rows.get(c.id, [])]
        assert not missing, f"not in lang/REFERENCE.md (run this file with --write): {missing}"

    def test_table_lists_no_unregistered_code(self) -> None:
        """Every row of the table is a registered code (no stale rows)."""
        known = {(c.id, c.name) for c in registered_codes()}
        stale = [(i, n) for i, names in _table_rows().items() for n in names if (i, n) not in known]
        assert not stale, f"stale rows in lang/REFERENCE.md: {stale}"

    def test_codes_modules_are_found(self) -> None:
        """The glob finds the codes module of every stage that registers codes."""
        found = set(codes_modules())
        assert {"rmot.lang.codes", "rmot.lang.check_codes", "rmot.compiler.plan.codes",
                "rmot.sim.codes", "rmot.backends.codes"} <= found


class TestCodeUniqueness:
    def test_ids_are_unique(self) -> None:
        """No two registered codes share an id."""
        ids = [c.id for c in registered_codes()]
        assert len(ids) == len(set(ids))

    def test_names_are_unique(self) -> None:
        """No two registered codes share a name (a name must say which code it is)."""
        by_name: dict[str, list[str]] = {}
        for c in registered_codes():
            by_name.setdefault(c.name, []).append(c.id)
        shared = {name: ids for name, ids in by_name.items() if len(ids) > 1}
        assert not shared, f"codes sharing a name: {shared}"

    def test_ids_follow_the_numbering(self) -> None:
        """Every id is E or W plus three digits."""
        bad = [c.id for c in registered_codes() if not re.fullmatch(r"[EW]\d{3}", c.id)]
        assert not bad


class TestExamples:
    def test_reference_has_examples(self) -> None:
        """The reference carries complete and error examples (the other tests are not vacuous)."""
        assert len(_blocks("rmot")) >= 4 and len(_blocks("rmot-error")) >= 5

    @pytest.mark.parametrize("line,source", _blocks("rmot"), ids=lambda v: f"line{v}" if isinstance(v, int) else "")
    def test_complete_example_compiles(self, line: int, source: str, tmp_path: Path) -> None:
        """A `rmot` block is a complete program or cell that loads without any diagnostic."""
        assert _COMPLETE.search(source), f"REFERENCE.md:{line}: an `rmot` block must hold a program or a cell"
        result = _load(source, tmp_path)
        problems = [f"{d.code.id}: {d.message}" for d in result.diagnostics]
        assert not problems, f"REFERENCE.md:{line}: {problems}"
        if re.search(r"^\s*program\b", source, re.M):
            assert result.program is not None and result.program.tasks

    @pytest.mark.parametrize("line,source", _blocks("rmot-error"), ids=lambda v: f"line{v}" if isinstance(v, int) else "")
    def test_error_example_gives_its_code(self, line: int, source: str, tmp_path: Path) -> None:
        """A `rmot-error` block produces the code named on its first line (`# E: E104`)."""
        first = source.splitlines()[0] if source else ""
        match = _EXPECTED.match(first)
        assert match, f"REFERENCE.md:{line}: first line must be '# E: Exxx' (got {first!r})"
        result = _load(source, tmp_path)
        got = [d.code.id for d in result.diagnostics]
        assert match.group(1) in got, f"REFERENCE.md:{line}: expected {match.group(1)}, got {got}"


def test_json_report_example_follows_the_schema() -> None:
    """The JSON report shown in section 9 is valid against rmot.sim.report.JSON_SCHEMA."""
    import json

    from rmot.sim.report import JSON_SCHEMA, validate_json

    blocks = _blocks("json")
    assert blocks, "REFERENCE.md must show a JSON report example"
    for line, source in blocks:
        assert validate_json(json.loads(source), JSON_SCHEMA) == [], f"REFERENCE.md:{line}"


if __name__ == "__main__":
    if sys.argv[1:] == ["--write"]:
        write_table()
        print(f"wrote the code table of {REFERENCE}")
    else:
        print(code_table())
