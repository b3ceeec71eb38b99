"""The README's promises: its two commands exist, and its console transcripts are true."""

from __future__ import annotations

import re
import shlex
from pathlib import Path

import pytest
from click.testing import CliRunner

from rmot.compiler.cli import cli

ROOT = Path(__file__).resolve().parents[2]
README = (ROOT / "README.md").read_text(encoding="utf-8")


def _console_blocks() -> list[str]:
    return re.findall(r"```console\n(.*?)```", README, flags=re.S)


def _sessions(block: str) -> list[tuple[str, list[str]]]:
    """(command, expected output lines) for each `$ ` line of a transcript."""
    out: list[tuple[str, list[str]]] = []
    for line in block.splitlines():
        if line.startswith("$ "):
            out.append((line[2:], []))
        elif out:
            out[-1][1].append(line)
    return out


def test_the_two_commands_are_make_targets() -> None:
    """`make demo` and `make test` are the README's two commands, and the Makefile has both."""
    assert "make demo" in README and "make test" in README
    makefile = (ROOT / "Makefile").read_text(encoding="utf-8")
    assert re.search(r"^demo:", makefile, re.M) and re.search(r"^test:", makefile, re.M)
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    assert "make demo" in ci and "make test" in ci


def _transcripts() -> list[tuple[str, str, list[str], dict[str, str]]]:
    """Every `rmot check` transcript, with the files a preceding `cat` shows."""
    cases = []
    for block in _console_blocks():
        files: dict[str, str] = {}
        sessions = _sessions(block)
        for i, (command, lines) in enumerate(sessions):
            args = shlex.split(command)
            if args[0] == "cat":
                files[args[1]] = "\n".join(lines) + "\n"
            elif args[:2] == ["rmot", "check"]:
                exit_line = sessions[i + 1] if i + 1 < len(sessions) else None
                code = exit_line[1][0] if exit_line and exit_line[0] == "echo $?" else "0"
                cases.append((command, code, lines, dict(files)))
    return cases


@pytest.mark.parametrize(("command", "code", "expected", "files"), _transcripts(), ids=lambda v: str(v)[:40])
def test_console_transcripts_match_the_real_output(command: str, code: str, expected: list[str],
                                                   files: dict[str, str], tmp_path: Path, monkeypatch) -> None:
    """Each `$ rmot check ...` in the README prints exactly what the README shows, with its exit code."""
    for name, text in files.items():
        (tmp_path / name).write_text(text, encoding="utf-8")
    monkeypatch.chdir(tmp_path if files else ROOT)
    args = shlex.split(command)[1:]
    if "--images" in args:  # pictures go to a scratch folder; the text output is the same
        args[args.index("--images") + 1] = str(tmp_path / "findings")
    result = CliRunner().invoke(cli, args, prog_name="rmot")
    assert result.exit_code == int(code), result.output
    shown = [line for line in result.output.splitlines() if not line.startswith("note: collisions are checked")]
    assert shown == [line for line in expected if not line.startswith("note: collisions are checked")]


def test_the_program_in_the_tour_compiles_beside_the_examples() -> None:
    """The README's .rmot program is real: it loads without a diagnostic next to examples/."""
    from rmot.compiler.frontend import load_text

    (block,) = re.findall(r"```rmot\n(.*?)```", README, flags=re.S)
    result = load_text(block, str(ROOT / "examples" / "readme_tour.rmot"), project_root=str(ROOT / "examples"))
    assert result.program is not None
    assert [d.message for d in result.diagnostics] == []
    assert result.program.name == "pick_place"
