"""Torque ratings that are estimates never raise an error (W342 instead of E313).

Witness for the Stäubli TX2-60: the ROS-I `effort` of J2 (47 N·m) against the static torque
of the rated payload alone held stretched out, 3.5 kg x 9.81 m/s² x 0.67 m (the data sheet's
reach) = 23 N·m, before the arm's own links: values that low are not joint ratings, and a
TX2-60 holding its rated payload must check clean.
"""

from __future__ import annotations

import json
from pathlib import Path

from click.testing import CliRunner

from rmot.compiler.cli import check_cmd
from rmot.sim.robots import load_robot

PROGRAM = """cell tx2_cell {
  robot r1 = staubli_tx2_60 at pose(z=375mm)
  tool block = box(60mm, 60mm, 60mm) at pose(z=40mm) tcp pose(z=70mm) mass MASS kg on r1
}

program stretch on r1 {
  tool block
  target up = joints(0, 0, 0, 0, 0, 0) deg
  target out = joints(0, 90, 0, 0, 0, 0) deg
  move joint up
  move joint out
  move joint up
}
"""


def _codes(tmp_path: Path, mass: float) -> list[str]:
    path = tmp_path / "stretch.rmot"
    path.write_text(PROGRAM.replace("MASS", f"{mass:g}"))
    result = CliRunner().invoke(check_cmd.check, [str(path), "--format", "json", "--no-cache"])
    return [d["code"] for d in json.loads(result.output)["programs"][0]["diagnostics"]]


def test_tx2_60_torque_ratings_are_marked_estimates_above_the_payload_torque() -> None:
    robot = load_robot("staubli_tx2_60")
    assert dict(robot.sources)["effort"].startswith("estimate")
    payload_torque = 3.5 * 9.81 * 0.67
    assert robot.model.effortLimit[1] > 2 * payload_torque


def test_tx2_60_stretched_with_rated_payload_is_clean(tmp_path: Path) -> None:
    assert "E313" not in _codes(tmp_path, 3.5)


def test_excess_over_an_estimated_rating_is_a_warning(tmp_path: Path) -> None:
    found = _codes(tmp_path, 60.0)
    assert "W342" in found and "E313" not in found
