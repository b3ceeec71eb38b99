"""Every failure class of hostile or damaged input as a regression test: each reproducer
(tests/robust/cases.py) runs through the real command line in this process and must end with
the expected exit code and diagnostic codes, never a traceback; no vendor file may carry
injected text."""

from __future__ import annotations

import builtins
import os
import pathlib
from pathlib import Path

import pytest

from tests.robust.cases import CASES, Case
from tests.robust.runner import run_case


def _deny(monkeypatch: pytest.MonkeyPatch, marker: str) -> None:
    """Reading any path containing `marker` fails with EACCES, as for a non-root user after
    chmod 000 (the suite may run as root, which chmod does not stop)."""
    real_read_bytes, real_open = pathlib.Path.read_bytes, builtins.open

    def read_bytes(self: Path) -> bytes:
        if marker in str(self):
            raise PermissionError(13, "Permission denied", str(self))
        return real_read_bytes(self)

    def fake_open(file, *args, **kwargs):  # type: ignore[no-untyped-def]
        if isinstance(file, str) and marker in file:
            raise PermissionError(13, "Permission denied", file)
        return real_open(file, *args, **kwargs)

    real_os_open = os.open

    def fake_os_open(path, *args, **kwargs):  # type: ignore[no-untyped-def]  # lang/input_file.read_regular
        if marker in os.fsdecode(path):
            raise PermissionError(13, "Permission denied", os.fsdecode(path))
        return real_os_open(path, *args, **kwargs)

    monkeypatch.setattr(pathlib.Path, "read_bytes", read_bytes)
    monkeypatch.setattr(builtins, "open", fake_open)
    monkeypatch.setattr(os, "open", fake_os_open)


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.name)
def test_reproducer(case: Case, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    if case.setup == "lock":
        _deny(monkeypatch, f"{os.sep}locked{os.sep}")
    elif case.setup == "lock_stl":
        _deny(monkeypatch, "part.stl")
    out = run_case(case, str(tmp_path))
    assert out.exception is None, f"traceback: {out.exception!r}\n{out.output}"
    assert out.exit_code in case.exit_codes, out.output
    for code in case.codes:
        assert code in out.output, out.output
    for bad in case.absent:
        assert not any(bad.encode() in data for data in out.files.values()), bad
    assert "Traceback" not in out.output
    if case.setup == "keep_inputs":  # nothing the case's project held was replaced or removed
        for rel, text in case.files.items():
            assert (tmp_path / rel).read_text(encoding="utf-8") == text, rel
        assert not any(p.name.startswith(".rmot-") or p.suffix in (".csv", ".mod") for p in tmp_path.rglob("*")), \
            sorted(tmp_path.rglob("*"))


def test_form_feed_line_and_quoted_source_agree(tmp_path: Path) -> None:
    """`file:line:col` and the quoted line name the same line for every convention the lexer
    accepts (LF, CRLF, a form feed inside a line): the caret sits under the named column."""
    from rmot.compiler.frontend import load_text
    from rmot.lang.diagnostics import render

    for text in ("program p on r1 {\f\n  move joint nowhere\n}\n", "program p on r1 {\r\n\f  move joint nowhere\r\n}\r\n"):
        d = next(d for d in load_text(text, str(tmp_path / "p.rmot")).diagnostics if d.code.id == "E101")
        lines = render(d).splitlines()
        source, caret = lines[1], lines[2]
        line = text.split("\n")[d.span.start.line - 1].rstrip("\r")
        bar = source.index("| ") + 2
        assert source[bar:].replace("\u240d", "\r").replace(" ", "") == line.replace("\f", "").replace(" ", "")
        assert caret.index("^") - bar == d.span.start.col - 1
        assert source[bar + d.span.start.col - 1:].startswith("nowhere")


def test_every_python_line_break_is_refused_or_counted(tmp_path: Path) -> None:
    """Each character str.splitlines breaks at is either refused with a diagnostic at its own
    position (E010/E011/E012) or, for form feed, not a line break anywhere in rmot."""
    from rmot.compiler.frontend import load_text

    for ch in "\r\x0b\x0c\x1c\x1d\x1e\x85\u2028\u2029":
        text = f"program p on r1 {{\n  wait 1 s {ch} \n  move joint nowhere\n}}\n"
        diags = load_text(text, str(tmp_path / "p.rmot")).diagnostics
        if ch == "\x0c":
            assert [(d.code.id, d.span.start.line) for d in diags] == [("E101", 3)]
            continue
        assert len(diags) == 1 and diags[0].code.id in ("E010", "E011", "E012"), (repr(ch), diags)
        assert (diags[0].span.start.line, diags[0].span.start.col) == (2, 12), repr(ch)
