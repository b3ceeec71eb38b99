"""One row type for every ROS-Industrial library arm, and every library arm's kinematics kept.

tests/robots/data/library_fk.json holds each library arm's flange pose (the top three rows of
the 4x4, m) at three configurations (zero; 70 % and 20 % of the way through each joint's
range), written by the library as it stood before the Motoman and Stäubli modules took the
shared RosiArm row (commit d05a854, `rmot.sim.robots.load_robot(name).fk(q)`, rounded to
1e-12). A change of any number of any arm's row shows up here; tests/robots/test_reference_fk.py
checks the same arms against their URDF chains composed independently.
"""

from __future__ import annotations

import inspect
import json
from pathlib import Path

import numpy as np
import pytest

from rmot.sim.robots import load_robot
from rmot.sim.robots.library import SPECS
from rmot.sim.robots.library_rosi_rows import RosiArm

FROZEN = json.loads((Path(__file__).parent / "data" / "library_fk.json").read_text(encoding="utf-8"))
ROSI_MODULES = ("library_abb", "library_fanuc", "library_motoman", "library_staubli")


def test_every_library_arm_is_frozen() -> None:
    assert sorted(FROZEN) == sorted(SPECS)


@pytest.mark.parametrize("name", sorted(FROZEN))
def test_forward_kinematics_unchanged(name: str) -> None:
    robot = load_robot(name)
    lim = np.asarray(robot.joint_limits, dtype=float)
    qs = [np.zeros(robot.dof), lim[:, 0] * 0.3 + lim[:, 1] * 0.7, lim[:, 0] * 0.8 + lim[:, 1] * 0.2]
    for q, frozen in zip(qs, FROZEN[name], strict=True):
        np.testing.assert_allclose(np.asarray(robot.fk(q))[:3].ravel(), frozen, atol=2e-12)


@pytest.mark.parametrize("module", ROSI_MODULES)
def test_each_rosi_brand_module_lists_rosi_arm_rows_only(module: str) -> None:
    """No brand keeps a row class of its own: the module defines none, and its table is RosiArm rows."""
    mod = __import__(f"rmot.sim.robots.{module}", fromlist=["_ARMS"])
    own = [c for _, c in inspect.getmembers(mod, inspect.isclass) if c.__module__ == mod.__name__]
    assert own == []
    assert mod._ARMS and all(type(row) is RosiArm for row in mod._ARMS)
    assert {row.name for row in mod._ARMS} <= set(SPECS)
