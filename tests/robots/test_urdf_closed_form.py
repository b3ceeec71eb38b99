"""URDF arms get the OPW closed form and its named branches, as cell models do.

The arm: ABB's IRB 2400 as ROS-Industrial describes it (tests/data/urdf/irb2400.urdf, the
joints of abb_irb2400_support/urdf/irb2400_macro.xacro). Witness: pinocchio's own URDF
parser and FK (not rmot's Robot) of the planned joint values must give the programmed pose,
and `config(...)` must choose a different branch, with the branch asked for.
"""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

from rmot.compiler.cli.compile_cmd import compile_program
from rmot.sim.robots import load_robot

URDF = Path(__file__).resolve().parents[1] / "data" / "urdf" / "irb2400.urdf"

PROGRAM = """cell c {{
  robot r1 = urdf("irb2400.urdf", controller="abb")
}}
program p on r1 {{
  move joint joints(0, 0, 0, 0, 30, 0) deg
  move joint pose(x=900mm, y=200mm, z=800mm, ry=90deg) {config}
}}
"""


def _pinocchio_tool0(q: np.ndarray) -> np.ndarray:
    model = pin.buildModelFromUrdf(str(URDF))
    data = model.createData()
    pin.framesForwardKinematics(model, data, q)
    return data.oMf[model.getFrameId("tool0")].homogeneous


def _planned(tmp_path: Path, config: str) -> tuple[np.ndarray, dict[str, str]]:
    shutil.copy(URDF, tmp_path / "irb2400.urdf")
    path = tmp_path / f"p{abs(hash(config))}.rmot"
    path.write_text(PROGRAM.format(config=config))
    outcome = compile_program(str(path), ("json", "rapid"), use_cache=False)
    assert outcome.exit_code == 0, [d.message for d in outcome.diagnostics]
    listing = json.loads(next(t for n, t in outcome.files.items() if n.startswith("json/")))
    moves = [i for task in listing["tasks"] for i in task["instructions"] if i.get("q_target") is not None]
    return np.asarray(moves[-1]["q_target"], dtype=float), moves[-1]["branch"]


def test_irb2400_urdf_has_the_closed_form() -> None:
    robot = load_robot(str(URDF))
    assert robot.has_closed_form
    q = np.radians([20.0, 10.0, -5.0, 40.0, 50.0, 30.0])
    rows = robot.ik_closed_form(robot.fk(q)[None])[0]
    found = [r for r in rows if np.all(np.isfinite(r))]
    assert len(found) == 8
    for r in found:
        assert np.abs(_pinocchio_tool0(r) - _pinocchio_tool0(q)).max() < 1e-9


@pytest.mark.parametrize("config", ["config(wrist=flip)", "config(shoulder=front, elbow=up, wrist=flip)"])
def test_config_chooses_another_branch(tmp_path: Path, config: str) -> None:
    plain, plain_branch = _planned(tmp_path, "")
    flipped, flipped_branch = _planned(tmp_path, config)
    target = np.eye(4)
    target[:3, :3] = [[0, 0, 1], [0, 1, 0], [-1, 0, 0]]  # ry = 90 deg
    target[:3, 3] = (0.9, 0.2, 0.8)
    for q in (plain, flipped):
        assert np.abs(_pinocchio_tool0(q) - target).max() < 1e-6
    assert plain_branch["wrist"] != "flip" and flipped_branch["wrist"] == "flip"
    assert np.abs(plain - flipped).max() > 0.1
