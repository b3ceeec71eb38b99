"""`rmot plan`: cycle time per task, diagnostics on stderr, CSV trajectory, exit codes."""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner

from rmot.compiler.cli import cli

GOOD = """program demo on r1 {
  tool gripper
  speed 250 mm/s
  zone 5 mm
  move joint joints(0, -20, 30, 0, 50, 0) deg
  move linear pose(x=900mm, y=-100mm, z=500mm, rx=180deg)
  move linear pose(x=900mm, y=100mm, z=500mm, rx=180deg) zone fine
  set out[1] = on
  wait 200 ms
  move joint joints(0, -20, 30, 0, 50, 0) deg
}
"""


def _run(tmp_path: Path, text: str, *args: str):  # type: ignore[no-untyped-def]
    src = tmp_path / "prog.rmot"
    src.write_text(text, encoding="utf-8")
    return CliRunner().invoke(cli, ["plan", str(src), *args])


def test_clean_program_prints_cycle_time_and_exits_0(tmp_path: Path) -> None:
    """A plannable program: exit 0, one line per task with its cycle time, nothing on stderr."""
    result = _run(tmp_path, GOOD)
    assert result.exit_code == 0, result.output
    assert result.stdout.startswith("task demo (r1): cycle time ")
    assert result.stdout.rstrip().endswith(" s")
    assert result.stderr == ""


def test_csv_holds_every_sample(tmp_path: Path) -> None:
    """--csv writes a header and one row per sample at the step; no temporary file remains."""
    out = tmp_path / "traj.csv"
    result = _run(tmp_path, GOOD, "--csv", str(out), "--step", "10ms")
    assert result.exit_code == 0, result.output
    lines = out.read_text().splitlines()
    assert lines[0] == "task,t," + ",".join(f"{k}{j}" for k in ("q", "qd", "qdd") for j in range(1, 7))
    times = [float(line.split(",")[1]) for line in lines[1:]]
    assert times[:3] == [0.0, 0.01, 0.02]
    cycle = float(result.stdout.split("cycle time ")[1].split()[0])
    assert times[-1] == pytest.approx(cycle, abs=1e-6)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["prog.rmot", "traj.csv"]


def test_planning_error_is_rendered_and_exits_1(tmp_path: Path) -> None:
    """An unreachable target: the diagnostic with file:line:col and carets, exit 1 (a finding, as in check)."""
    text = GOOD.replace("move joint joints(0, -20, 30, 0, 50, 0) deg\n}", "move linear pose(x=5000mm, z=500mm)\n}")
    result = _run(tmp_path, text)
    assert result.exit_code == 1
    assert f"{tmp_path / 'prog.rmot'}:10:3: error[E220]: target must be within the robot's reach" in result.stderr
    assert " 10 |   move linear pose(x=5000mm, z=500mm)" in result.stderr


def test_input_error_exits_2_without_planning(tmp_path: Path) -> None:
    """A front-end error is reported and nothing is planned."""
    result = _run(tmp_path, "program demo on r1 {\n  move joint nowhere\n}\n")
    assert result.exit_code == 2
    assert "error[" in result.stderr and "cycle time" not in result.stdout


@pytest.mark.parametrize("step", ["0", "fast", "5 min"])
def test_bad_step_is_a_usage_error(tmp_path: Path, step: str) -> None:
    """--step must be a time between 0.1 ms and 1 s: usage error, exit 2."""
    result = _run(tmp_path, GOOD, "--step", step)
    assert result.exit_code == 2
    assert "step must be" in result.output
