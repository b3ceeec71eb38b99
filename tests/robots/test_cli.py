"""`rmot robots`: exact text for known poses, JSON, and exit code 2 on bad input."""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner

from rmot.compiler.cli import cli
from rmot.sim.robots import list_robots, load_robot


def run(*args: str):  # type: ignore[no-untyped-def]
    return CliRunner().invoke(cli, ["robots", *args])


def test_list_names_every_library_robot():
    """`robots list` prints one line per library robot, in name order."""
    result = run("list")
    assert result.exit_code == 0
    assert [line.split()[0] for line in result.output.splitlines()] == list(list_robots())
    assert [row["name"] for row in json.loads(run("list", "--json").output)] == list(list_robots())


def test_fk_of_the_irb120_calibration_pose_exact_text():
    """ABB tool0 at all-zero joints: (374, 0, 630) mm, ry = 90° (rx folded into rz at the lock)."""
    result = run("fk", "abb_irb120", "0", "0", "0", "0", "0", "0")
    assert result.exit_code == 0
    assert result.output == (
        "x y z (mm):    374.000 0.000 630.000\n"
        "rx ry rz (deg): 0.000 90.000 0.000\n"
        "branch: shoulder=front, elbow=up, wrist=noflip\n"
    )


def test_fk_accepts_negative_degrees_and_prints_json():
    """Negative joint values are values, not options; --json gives mm and degrees."""
    result = run("fk", "kuka_kr6_r900", "0", "-90", "90", "0", "0", "0", "--json")
    assert result.exit_code == 0
    data = json.loads(result.output)
    assert data["position_mm"] == [525.0, 0.0, 890.0]
    assert data["rpy_deg"] == [0.0, 90.0, 0.0]
    assert data["branch"] == {"shoulder": "front", "elbow": "up", "wrist": "noflip"}


def test_ik_lists_each_branch_and_round_trips_fk():
    """`robots ik` of an fk output lists branches whose joints give back the pose."""
    fk = json.loads(run("fk", "abb_irb1600", "10", "20", "-30", "40", "50", "60", "--json").output)
    x, y, z = (str(v) for v in fk["position_mm"])
    rx, ry, rz = (str(v) for v in fk["rpy_deg"])
    result = run("ik", "abb_irb1600", x, y, z, rx, ry, rz, "--json")
    assert result.exit_code == 0
    data = json.loads(result.output)
    assert data["status"] == "ok"
    names = [tuple(s["branch"].values()) for s in data["solutions"]]
    assert len(names) == len(set(names)) >= 2
    r = load_robot("abb_irb1600")
    for s in data["solutions"]:
        pos = r.fk(np.radians(s["joints"]))[:3, 3] * 1000
        np.testing.assert_allclose(pos, fk["position_mm"], atol=1e-3)
    text = run("ik", "abb_irb1600", x, y, z, rx, ry, rz).output.splitlines()
    assert text[0] == "status: ok" and "10.000 20.000 -30.000 40.000 50.000 60.000" in "\n".join(text)


def test_ik_of_an_unreachable_pose_exits_1_with_the_distance():
    """A pose 3.4 m beyond the IRB 120: status unreachable with the distance, exit 1."""
    result = run("ik", "abb_irb120", "4000", "0", "500", "0", "180", "0")
    assert result.exit_code == 1
    assert result.output.startswith("status: unreachable (the pose is 3429.9 mm outside the workspace")


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (("fk", "abb_irb12", "0", "0", "0", "0", "0", "0"), "unknown robot 'abb_irb12'; did you mean 'abb_irb120'?"),
        (("fk", "abb_irb120", "0", "0", "0"), "abb_irb120 needs 6 joint values (got 3)"),
        (("fk", "abb_irb120", "0", "0", "x", "0", "0", "0"), "joint value 3 must be a number (got 'x')"),
        (("fk", "abb_irb120", "0", "0", "0", "0", "0", "inf"), "joint value 6 must be a finite number (got 'inf')"),
        (("ik", "ur5e", "1", "2", "3"), "a pose needs 6 values X Y Z RX RY RZ (got 3)"),
        (("show", "nosuch"), "unknown robot 'nosuch'"),
    ],
)
def test_bad_input_exits_2_with_a_message(args, message):
    """Unknown robot, wrong count, non-numeric input: a message and exit 2, no traceback."""
    result = run(*args)
    assert result.exit_code == 2
    assert message in result.output and "Traceback" not in result.output


def test_show_prints_the_dh_table_limits_and_reach():
    """`robots show` has the DH rows in mm/deg, the limits in degrees and the reach."""
    out = run("show", "abb_irb120").output
    assert "abb_irb120: ABB IRB 120-3/0.58, 6 axes, reach 580.0 mm" in out
    assert "     1     R     1        0.000    290.000      0.000     -90.000" in out
    assert "     3    -110.00      70.00       250.0" in out
    data = json.loads(run("show", "ur5e", "--json").output)
    assert [row["d_mm"] for row in data["dh"]] == [162.5, 0.0, 0.0, 133.3, 99.7, 99.6]
