"""Malformed inputs: each fixture's `# E:` expectations are exactly the diagnostics reported.

Expectations are read out of the fixtures in tests/data/bad/ (mypy style), in comments, each
with the diagnostic's full message in double quotes (`\"` and `\\` inside; `$BAD` stands
for the fixtures' directory):
  `# E: E101 @14 "unknown name 'x'"`      an error with code E101 on this line at column 14
  `# E@file.rmot:3:1: E109 "..."`          an error in another file (or on a line that cannot
                                          hold a comment)
  `# E@3:10: E003 "..."`                   the same for this file
  `# E@-: E501 "..."`                      a diagnostic without a source position
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from rmot.compiler.frontend import load_program, load_text
from rmot.lang.diagnostics import Diagnostic, Severity, render

BAD = Path(__file__).resolve().parents[1] / "data" / "bad"
_MESSAGE = r'"((?:[^"\\]|\\.)*)"'
_ONE = re.compile(r"(E\d{3})\s*@(\d+)\s*" + _MESSAGE)
_ELSEWHERE = re.compile(r"#\s*E@(?:(?:([\w.]+):)?(\d+):(\d+)|(-)):\s*(E\d{3})\s*" + _MESSAGE)
_ANY = re.compile(r"#\s*E[:@]")  # every comment that means to be an expectation

Expectation = tuple[str, int, int, str, str]  # file name, line, column, code, message


def _unquote(text: str) -> str:
    return re.sub(r"\\(.)", r"\1", text)


def fixtures() -> list[Path]:
    return sorted(BAD.glob("*.rmot"))


def expectations(path: Path) -> set[Expectation]:
    """{(file name, line, column, code, message)} the fixture declares ("-", 0, 0: no span)."""
    out: set[Expectation] = set()
    for lineno, line in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1):
        for m in _ELSEWHERE.finditer(line):
            if m.group(4):
                out.add(("-", 0, 0, m.group(5), _unquote(m.group(6))))
            else:
                out.add((m.group(1) or path.name, int(m.group(2)), int(m.group(3)), m.group(5),
                         _unquote(m.group(6))))
        same = line.find("# E:")
        if same >= 0:
            for code, col, message in _ONE.findall(line[same:]):
                out.add((path.name, lineno, int(col), code, _unquote(message)))
    return out


def _found(diagnostics: tuple[Diagnostic, ...]) -> set[Expectation]:
    """Every diagnostic as an expectation, the span-less ones too."""
    out: set[Expectation] = set()
    for d in diagnostics:
        message = d.message.replace(str(BAD), "$BAD")
        if d.span is None:
            out.add(("-", 0, 0, d.code.id, message))
        else:
            out.add((Path(d.span.path).name, d.span.start.line, d.span.start.col, d.code.id, message))
    return out


def test_every_expectation_comment_is_read() -> None:
    """A fixture comment that means an expectation but does not parse (a typo, a missing
    message) would silently expect nothing: each one yields as many expectations as it
    names codes, and every fixture expects at least one diagnostic (40+ fixtures)."""
    files = fixtures()
    assert len(files) >= 40
    for path in files:
        assert expectations(path), f"{path.name} declares no expectation"
        for lineno, line in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1):
            start = _ANY.search(line)
            if start is None:
                continue
            codes = re.findall(r"\bE\d{3}\b", re.sub(_MESSAGE, "", line[start.start():]))
            same = line.find("# E:")
            read = len(_ELSEWHERE.findall(line)) + (len(_ONE.findall(line[same:])) if same >= 0 else 0)
            assert read == len(codes), f"{path.name}:{lineno}: unreadable expectation {line.strip()!r}"


def test_matcher_compares_messages_and_spanless_diagnostics() -> None:
    """The matcher itself: a wrong message or an extra diagnostic without a span is a mismatch."""
    (path,) = [p for p in fixtures() if p.name == "many_errors.rmot"]
    found = _found(load_program(str(path)).diagnostics)
    assert found == expectations(path)
    first = sorted(found)[0]
    assert found - {first} | {(*first[:4], first[4] + " (changed)")} != expectations(path)
    from rmot.lang import codes
    from rmot.lang.diagnostics import Severity

    extra = Diagnostic(codes.SYNTAX, Severity.ERROR, "somewhere", None)
    assert ("-", 0, 0, codes.SYNTAX.id, "somewhere") in _found((extra,))


@pytest.mark.parametrize("path", fixtures(), ids=lambda p: p.stem)
def test_fixture_reports_exactly_its_expected_errors(path: Path) -> None:
    """(file, line, column, code, message) of every error match the fixture's inline
    expectations; rendering works. (Warnings are other tests' business: several fixtures hold a
    proc no task calls, W153.)"""
    result = load_program(str(path))
    assert result.program is None
    errors = tuple(d for d in result.diagnostics if d.severity is Severity.ERROR)
    assert _found(errors) == expectations(path)
    for d in errors:
        text = render(d)
        where = f"{d.span}: " if d.span is not None else "rmot: "
        assert text.startswith(f"{where}error[{d.code.id}]: {d.message}")


def test_duplicate_definition_has_a_note_at_the_first() -> None:
    """The duplicate's note points at the first definition's line."""
    result = load_program(str(fixtures()[0].parent / "duplicate_target.rmot"))
    (d,) = result.diagnostics
    (text, span), = d.notes
    assert "first defined here" in text and span is not None and (span.start.line, span.start.col) == (2, 10)


def test_all_semantic_errors_of_a_file_come_in_one_run() -> None:
    """Four independent mistakes give four diagnostics, in source order."""
    result = load_program(str(fixtures()[0].parent / "many_errors.rmot"))
    assert [d.span.start.line for d in result.diagnostics] == [2, 3, 4, 5]  # type: ignore[union-attr]


class TestWholeFileProblems:
    def _one(self, tmp_path: Path, data: bytes) -> tuple[str, int, int]:
        f = tmp_path / "bad.rmot"
        f.write_bytes(data)
        result = load_program(str(f))
        assert result.program is None and result.diagnostics
        d = result.diagnostics[0]
        render(d)
        line, col = (d.span.start.line, d.span.start.col) if d.span else (0, 0)
        return d.code.id, line, col

    def test_empty_file(self, tmp_path: Path) -> None:
        """An empty file is E009 at 1:1."""
        assert self._one(tmp_path, b"") == ("E009", 1, 1)

    def test_binary_garbage(self, tmp_path: Path) -> None:
        """Random bytes with NULs are a binary file (E010) or not UTF-8 (E502), never a traceback."""
        code, _, _ = self._one(tmp_path, bytes(range(256)) * 4)
        assert code in ("E010", "E502")

    def test_not_utf8(self, tmp_path: Path) -> None:
        """A Latin-1 byte is E502 at the line and column where it stands."""
        assert self._one(tmp_path, "program p on r1 {\n  wait 1 s # caf\xe9\n}\n".encode("latin-1")) == ("E502", 2, 17)

    def test_ten_megabyte_file(self, tmp_path: Path) -> None:
        """A 10 MB source is refused before it is read (E503)."""
        assert self._one(tmp_path, b"wait 1 s\n" * (10 * 1024 * 1024 // 9))[0] == "E503"

    def test_byte_order_mark_is_accepted(self, tmp_path: Path) -> None:
        """A UTF-8 BOM (Windows editors) is not an error."""
        f = tmp_path / "bom.rmot"
        f.write_bytes("\ufeffprogram p on r1 { wait 1 s }\n".encode())
        assert load_program(str(f)).diagnostics == ()

    def test_missing_main_file(self, tmp_path: Path) -> None:
        """A file that does not exist is E501 without a span."""
        result = load_program(str(tmp_path / "nope.rmot"))
        assert [d.code.id for d in result.diagnostics] == ["E501"]

    def test_cell_only_file_has_no_program(self) -> None:
        """A file holding only a cell gives the cell, no program, no error."""
        result = load_text("cell c { robot r1 = abb_irb120 }", "c.rmot")
        assert result.diagnostics == () and result.program is None
        assert result.cell is not None and result.cell.name == "c"


def test_unrolling_beyond_the_limit_is_reported_once() -> None:
    """A loop that unrolls past MAX_INSTRUCTIONS stops with one E121 at the statement that overflows."""
    # 150,000 rounds (under the loop-round budget, E124) of two instructions each
    result = load_text("program p on r1 {\n  repeat 150000 { wait 1 ms; wait 1 ms }\n}\n", "/virtual/big.rmot")
    assert [(d.code.id, d.span.start.line) for d in result.diagnostics] == [("E121", 2)]  # type: ignore[union-attr]


def test_broken_urdf_is_a_file_error(tmp_path: Path) -> None:
    """A URDF the robot library cannot load is E505 at the path."""
    (tmp_path / "bad.urdf").write_text("<robot")
    (tmp_path / "c.rmot").write_text('cell c {\n  robot r1 = urdf("bad.urdf")\n}\n')
    result = load_program(str(tmp_path / "c.rmot"))
    assert [(d.code.id, d.span.start.line, d.span.start.col) for d in result.diagnostics] == [("E505", 2, 19)]  # type: ignore[union-attr]
