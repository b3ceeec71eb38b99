"""The README's `rmot compare` and `rmot place` transcripts are the commands' real output."""

from __future__ import annotations

import re
import shlex
from pathlib import Path

import pytest
from click.testing import CliRunner

from rmot.compiler.cli import cli

ROOT = Path(__file__).resolve().parents[2]
README = (ROOT / "README.md").read_text(encoding="utf-8")


def _transcripts() -> list[tuple[str, list[str]]]:
    out = []
    for block in re.findall(r"```console\n(.*?)```", README, flags=re.S):
        lines = block.splitlines()
        if lines and (lines[0].startswith("$ rmot compare") or lines[0].startswith("$ rmot place")):
            out.append((lines[0][2:], lines[1:]))
    return out


def test_the_readme_shows_both_design_transcripts() -> None:
    """The section 'Designing the cell' has a compare and a place transcript."""
    assert sorted(c.split()[1] for c, _ in _transcripts()) == ["compare", "place"]


@pytest.mark.parametrize(("command", "expected"), _transcripts(), ids=lambda v: str(v)[:30])
def test_design_transcripts_match_the_real_output(command: str, expected: list[str], tmp_path: Path, monkeypatch) -> None:
    """Run from the repository root, the command prints exactly the README's lines (the output file goes to a scratch folder)."""
    monkeypatch.chdir(ROOT)
    args = shlex.split(command)[1:]
    if "-o" in args:
        args[args.index("-o") + 1] = str(tmp_path / args[args.index("-o") + 1])
    result = CliRunner().invoke(cli, args, prog_name="rmot")
    assert result.exit_code == 0, result.output
    shown = [line.replace(str(tmp_path) + "/", "") for line in result.output.splitlines()]
    assert shown == expected
