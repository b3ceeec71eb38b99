"""Every command reports a missing file (E501) and a file without a program (E119) alike, exit 2."""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner

from rmot.compiler.cli import cli

CELL_ONLY = "cell c {\n  robot r1 = abb_irb120\n}\n"
UNREACHABLE = "program demo on r1 {\n  move joint joints(0, -20, 30, 0, 50, 0) deg\n  move linear pose(x=5000mm, z=500mm)\n}\n"


def _args(command: str, src: Path, tmp_path: Path) -> list[str]:
    extra = {"check": [], "plan": [], "compile": ["--target", "rapid", "-o", str(tmp_path / "out")],
             "render": ["-o", str(tmp_path / "pic.svg")]}[command]
    return [command, str(src), *extra]


@pytest.mark.parametrize("command", ["check", "plan", "compile", "render"])
def test_missing_program_file_is_e501_everywhere(command: str, tmp_path: Path) -> None:
    """A missing file is the front end's E501 in every command, exit 2."""
    result = CliRunner().invoke(cli, _args(command, tmp_path / "absent.rmot", tmp_path))
    assert result.exit_code == 2, result.output
    assert "error[E501]" in result.stderr + result.stdout
    assert "E390" not in result.output and "E408" not in result.output


@pytest.mark.parametrize("command", ["check", "plan", "compile", "render"])
def test_cell_only_file_is_e119_everywhere(command: str, tmp_path: Path) -> None:
    """A file holding only a cell is E119 in every command, exit 2 (not a silent '0 errors')."""
    src = tmp_path / "cell.rmot"
    src.write_text(CELL_ONLY, encoding="utf-8")
    result = CliRunner().invoke(cli, _args(command, src, tmp_path))
    assert result.exit_code == 2, result.output
    assert "error[E119]" in result.stderr + result.stdout
    assert "(0 errors)" not in result.output


@pytest.mark.parametrize("command", ["check", "plan", "render"])
def test_planning_errors_exit_1_everywhere(command: str, tmp_path: Path) -> None:
    """An unreachable target is a finding: exit 1 in check, plan and render alike."""
    src = tmp_path / "prog.rmot"
    src.write_text(UNREACHABLE, encoding="utf-8")
    result = CliRunner().invoke(cli, _args(command, src, tmp_path))
    assert result.exit_code == 1, result.output
    assert "error[E220]" in result.output


def test_plan_accepts_project_root(tmp_path: Path) -> None:
    """`plan --project-root` bounds paths like the other commands: a cell outside it is E504."""
    project = tmp_path / "project"
    project.mkdir()
    (tmp_path / "cell.rmot").write_text(CELL_ONLY, encoding="utf-8")
    src = project / "prog.rmot"
    src.write_text('use cell "../cell.rmot"\nprogram p on r1 {\n  wait 1 s\n}\n', encoding="utf-8")
    inside = CliRunner().invoke(cli, ["plan", str(src), "--project-root", str(tmp_path)])
    assert inside.exit_code == 0, inside.output
    outside = CliRunner().invoke(cli, ["plan", str(src), "--project-root", str(project)])
    assert outside.exit_code == 2 and "error[E504]" in outside.output
