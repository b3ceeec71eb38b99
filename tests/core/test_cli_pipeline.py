"""One CLI pipeline: a stage that fails unexpectedly is the same diagnostic in
every command — E550 internal-error naming the stage, exit 2, no traceback. Each test makes one
stage raise (monkeypatched) and runs a command through the real `rmot` group."""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner

from rmot.compiler.cli import cli

PROGRAM = """
program boom on r1 {
  tool gripper
  move joint joints(0, -20, 30, 0, 50, 0) deg
  move joint joints(10, -20, 30, 0, 50, 0) deg
}
"""


class Boom(RuntimeError):
    pass


def _raise(*args: object, **kwargs: object) -> None:
    raise Boom("stage exploded")


@pytest.fixture
def program(tmp_path: Path) -> Path:
    src = tmp_path / "boom.rmot"
    src.write_text(PROGRAM, encoding="utf-8")
    return src


def commands(src: Path, out: Path) -> dict[str, list[str]]:
    return {
        "check": ["check", str(src), "--no-cache"],
        "compile": ["compile", str(src), "--target", "rapid", "-o", str(out / "v"), "--no-cache"],
        "plan": ["plan", str(src), "--no-cache"],
        "render": ["render", str(src), "-o", str(out / "a.svg"), "--no-cache"],
        "plot": ["plot", str(src), "-o", str(out / "a.svg"), "--no-cache"],
        "report": ["report", str(src), "-o", str(out / "a.html"), "--no-cache"],
        "ir": ["ir", str(src)],
    }


STAGES = {  # (module, attribute) the stage is looked up by, and its name in the message
    "front end": ("rmot.compiler.frontend", "load_program", "the front end"),
    "planner": ("rmot.compiler.plan_cache", "cached_plan", "the planner"),
    "verification": ("rmot.sim.verification", "verify", "the verification"),
}
ALL = ("front end", "planner", "verification")
USES = {"check": ALL, "compile": ALL, "report": ALL, "plan": ALL[:2], "render": ALL[:2],
        "plot": ALL[:2], "ir": ALL[:1]}
CASES = [(cmd, stage) for cmd, stages in USES.items() for stage in stages]


@pytest.mark.parametrize(("command", "stage"), CASES, ids=[f"{c}-{s}" for c, s in CASES])
def test_stage_failure_is_e550_everywhere(command: str, stage: str, program: Path,
                                          tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    module, attr, name = STAGES[stage]
    monkeypatch.setattr(f"{module}.{attr}", _raise)
    result = CliRunner().invoke(cli, commands(program, tmp_path)[command])
    assert result.exit_code == 2, result.output
    assert "error[E550]" in result.output and "Boom: stage exploded" in result.output, result.output
    if command != "ir":  # ir calls the front end itself: the group names the command
        assert f"internal error in {name}" in result.output
    assert "Traceback" not in result.output and isinstance(result.exception, SystemExit)


def test_a_backend_failure_refuses_that_vendor_only(program: Path, tmp_path: Path,
                                                    monkeypatch: pytest.MonkeyPatch) -> None:
    from rmot.backends import BACKENDS

    monkeypatch.setattr(BACKENDS["rapid"], "emit", _raise)
    args = ["compile", str(program), "--target", "rapid", "--target", "krl",
            "-o", str(tmp_path / "v"), "--no-cache"]
    result = CliRunner().invoke(cli, args)
    assert result.exit_code == 1, result.output
    assert "error[E550]: internal error in backend rapid (Boom: stage exploded)" in result.output
    assert sorted(p.name for p in (tmp_path / "v").iterdir()) == [".rmot.output", "krl"]  # the marker of rmot's own folders


def test_an_exception_in_a_command_itself_is_e550(program: Path, tmp_path: Path,
                                                  monkeypatch: pytest.MonkeyPatch) -> None:
    """Outside any stage (here: the CSV formatter of `rmot plan`), the command group gives the
    same diagnostic, naming the command."""
    monkeypatch.setattr("rmot.compiler.cli.plan_cmd.trajectory_csv", _raise)
    args = ["plan", str(program), "--csv", str(tmp_path / "t.csv"), "--no-cache"]
    result = CliRunner().invoke(cli, args)
    assert result.exit_code == 2
    assert "error[E550]: internal error in `rmot plan` (Boom: stage exploded)" in result.output
