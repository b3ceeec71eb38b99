"""The torque check runs on library arms: their inertias and torque limits are in the model."""

from __future__ import annotations

import json

from click.testing import CliRunner

from rmot.compiler.cli import check_cmd
from rmot.sim.robots import load_robot

CELL = """cell heavy {
  robot r1 = ur10e at pose()
  tool block = box(100mm, 100mm, 100mm) at pose(z=60mm) tcp pose(z=120mm) mass MASS kg on r1
}
"""

PROGRAM = """use cell "heavy.rmot"
program lift on r1 {
  tool block
  target a = joints(0, -90, 90, -90, -90, 0) deg
  target b = joints(60, -60, 60, -90, -90, 0) deg
  move joint a
  move joint b
  move joint a
}
"""


def _check(tmp_path, mass: float) -> dict:  # type: ignore[no-untyped-def]
    (tmp_path / "heavy.rmot").write_text(CELL.replace("MASS", f"{mass:g}"))
    (tmp_path / "lift.rmot").write_text(PROGRAM)
    result = CliRunner().invoke(check_cmd.check, [str(tmp_path / "lift.rmot"), "--format", "json"])
    return {"exit": result.exit_code, "doc": json.loads(result.output) if result.output.strip().startswith("{") else result.output}


def _codes(doc) -> set[str]:  # type: ignore[no-untyped-def]
    text = json.dumps(doc)
    return {c for c in ("E313",) if c in text}


def test_ur10e_has_rated_payload_and_urs_torque_limits():
    """UR10e: rated 12.5 kg (data sheet), joint torque limits as UR publishes them."""
    r = load_robot("ur10e")
    assert r.rated_payload_kg == 12.5 and r.has_inertia
    assert list(r.model.effortLimit) == [330.0, 330.0, 150.0, 56.0, 56.0, 56.0]


def test_an_80_kg_tool_on_a_ur10e_is_a_torque_finding(tmp_path):
    """80 kg on a UR10e (rated 12.5 kg) needs several times the shoulder's 330 N·m: E313.
    The same program with a 5 kg tool passes the torque check."""
    heavy = _check(tmp_path, 80.0)
    assert heavy["exit"] == 1, heavy
    assert "E313" in _codes(heavy["doc"])
    light = _check(tmp_path, 5.0)
    assert light["exit"] == 0 and "E313" not in _codes(light["doc"]), light
