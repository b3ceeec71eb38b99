"""Motor ratings and link masses on a cell `model`: `torque 120 N*m` and `mass 4 kg`
on a joint line become the robot's rated torques and link inertias; `rmot check --dynamics`
says per joint whether the motor suffices; the timing respects the ratings.

Witnesses: the static gravity torque of a two-link arm with a point-like mass at the end of
link 2 is m g a cos(q2), written here from the textbook (not rmot's code); the torques along
a timed trajectory are recomputed here with pinocchio's RNEA; bad input is checked by its
diagnostic code and message.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest
from click.testing import CliRunner
from rmot.compiler.cli import cli
from rmot.compiler.frontend import load_text
from rmot.compiler.plan import plan_program
from rmot.sim.robots import load_robot

G = 9.81  # m/s^2, pinocchio's default gravity (0, 0, -9.81)

# joint 1 about the vertical, alpha 90 deg turns joint 2's axis horizontal; link 2 is 500 mm long
# and carries a 10 mm sphere of MASS2 at its end (DH frame 2's origin)
J1_LINE = ("joint revolute dh(a=0mm, alpha=90deg, d=300mm, theta=0deg) range(-170deg, 170deg) "
           "speed 100 deg/s accel 400 deg/s^2")
J2_LINE = ("joint revolute dh(a=500mm, alpha=0deg, d=0mm, theta=0deg) range(-170deg, 170deg) "
           "solid(sphere(r=10mm)) speed 400 deg/s accel 2000 deg/s^2")
TWO_LINK = (
    "cell two {{\n  model arm {{\n    " + J1_LINE + " {j1}\n    " + J2_LINE + " {j2}\n  }}\n"
    "  robot r1 = arm\n}}\n"
)
MASS2 = 8.0


def _robot(j1: str, j2: str):  # type: ignore[no-untyped-def]
    result = load_text(TWO_LINK.format(j1=j1, j2=j2), "two.rmot")
    assert not result.has_errors, result.diagnostics
    return load_robot(result.cell.robot("r1").source.load_key), result  # type: ignore[union-attr]


def _codes(text: str) -> list[tuple[str, str]]:
    result = load_text(text, "two.rmot")
    return [(d.code.id, d.message) for d in result.diagnostics]


def test_ratings_and_masses_are_lowered_into_the_robot() -> None:
    robot, _ = _robot("mass 2 kg torque 120 N*m", f"mass {MASS2:g} kg torque 80 N*m")
    assert robot.has_inertia
    assert list(np.asarray(robot.model.effortLimit)) == [120.0, 80.0]
    for q2 in (0.0, 0.4, -1.1):
        gravity = pin.computeGeneralizedGravity(
            robot.model, robot.model.createData(), np.array([0.3, q2])
        )
        assert gravity[1] == pytest.approx(MASS2 * G * 0.5 * math.cos(q2), rel=1e-9, abs=1e-9)
        assert gravity[0] == pytest.approx(0.0, abs=1e-9)  # a vertical axis carries no weight


def test_a_model_without_masses_has_no_dynamics_and_keeps_its_load_key() -> None:
    robot, result = _robot("", "")
    assert not robot.has_inertia
    key = result.cell.robot("r1").source.load_key  # type: ignore[union-attr]
    # the key of a model without the new fields is written as before (9 numbers per joint)
    assert [len(j) for j in json.loads(key.split(":", 1)[1])["joints"]] == [9, 9]


def test_unrated_joint_is_unknown_not_infinite() -> None:
    robot, _ = _robot("mass 2 kg", f"mass {MASS2:g} kg torque 80 N*m")
    effort = np.asarray(robot.model.effortLimit)
    assert math.isinf(effort[0]) and effort[1] == 80.0


@pytest.mark.parametrize(
    ("j2", "code", "text"),
    [
        (
            "mass 1 kg torque 400 N",
            "E104",
            "joint torque rating must be a torque such as 120 N*m (got 400 N, a force)",
        ),
        ("mass 1 kg torque 0 N*m", "E137", "joint torque rating must be > 0 (got 0 N*m)"),
        ("mass 1 kg torque -5 N*m", "E137", "joint torque rating must be > 0"),
        ("mass 1 kg torque 1e999 N*m", "E013", "number must fit a 64-bit float"),
        (
            "mass 1 kg torque 120 kg",
            "E104",
            "joint torque rating must be a torque such as 120 N*m (got 120 kg, a mass)",
        ),
        ("mass 1 kg torque 120", "E105", "(got 120 without a unit)"),
        ("mass 1 kg torque 120 N*m", None, ""),
        ("mass -1 kg", "E137", "link mass must be >= 0"),
        (
            "mass 1 kg torque 5 N*m torque 6 N*m",
            "E135",
            "a joint must have one torque field (got two)",
        ),
    ],
)
def test_bad_ratings_are_diagnostics(j2: str, code: str | None, text: str) -> None:
    found = _codes(TWO_LINK.format(j1="mass 1 kg", j2=j2))
    if code is None:  # the good line, for contrast
        assert found == []
    else:
        assert any(c == code and text in m for c, m in found), found


def test_masses_on_some_joints_only_is_an_error_and_ratings_without_masses_a_warning() -> None:
    found = _codes(TWO_LINK.format(j1="", j2="mass 1 kg"))
    assert [c for c, _ in found] == ["E809"], found
    assert "joint 1 has none" in found[0][1]
    found = _codes(TWO_LINK.format(j1="torque 50 N*m", j2=""))
    assert [c for c, _ in found] == ["W801"], found


def test_newton_metre_elsewhere_stays_a_name_and_product() -> None:
    """`N*m` is one unit only after a number; `N * m` of two names is still a product."""
    from rmot.lang import parse_text

    result = parse_text("program p {\n  const N = 2\n  const m = 3\n  const k = N*m\n}\n", "t.rmot")
    assert result.diagnostics == ()


# --------------------------------------------------------------------------- timing and report

PROGRAM = """use cell "cell.rmot"
program swing on r1 {{
  move joint joints(0, -60) deg
  move joint joints(0, 60) deg
}}
"""


def _write(tmp_path: Path, j2: str) -> str:
    (tmp_path / "cell.rmot").write_text(
        TWO_LINK.format(j1="mass 2 kg torque 200 N*m", j2=j2), encoding="utf-8"
    )
    (tmp_path / "swing.rmot").write_text(PROGRAM.format(), encoding="utf-8")
    return str(tmp_path / "swing.rmot")


def _plan(path: str):  # type: ignore[no-untyped-def]
    from rmot.compiler.frontend import load_program

    result = load_program(path)
    assert not result.has_errors, result.diagnostics
    return plan_program(result.program)  # type: ignore[arg-type]


def test_rating_slows_the_swing_and_the_report_says_the_motor_suffices(tmp_path: Path) -> None:
    strong = _plan(_write(tmp_path, f"mass {MASS2:g} kg torque 1000 N*m")).tasks[0]
    weak_path = _write(tmp_path, f"mass {MASS2:g} kg torque 50 N*m")  # gravity alone: 39.2 N*m
    weak = _plan(weak_path).tasks[0]
    assert weak.cycle_time > 1.2 * strong.cycle_time
    robot = load_robot(_plan(weak_path).program.cell.robots[0].source.load_key)
    data = robot.model.createData()
    tr = weak.trajectory
    tau = np.array([pin.rnea(robot.model, data, q, v, a) for q, v, a in zip(tr.q, tr.qd, tr.qdd)])
    assert np.abs(tau[:, 1]).max() <= 50.0 * (1 + 1e-3)
    assert np.abs(tau[:, 1]).max() > 49.0  # it runs at the rating, not below it
    out = CliRunner().invoke(cli, ["check", "--no-cache", "--dynamics", weak_path])
    assert out.exit_code == 0, out.output
    assert "J2: " in out.output and "of 50 N·m" in out.output and "the motor suffices" in out.output
    js = CliRunner().invoke(
        cli, ["check", "--no-cache", "--dynamics", "--format", "json", weak_path]
    )
    joints = json.loads(js.output)["programs"][0]["tasks"][0]["dynamics"]["joints"]
    assert [j["suffices"] for j in joints] == [True, True]
    assert joints[1]["rms_utilisation"] == pytest.approx(
        np.sqrt((tau[:, 1] ** 2).mean()) / 50.0, abs=1e-5
    )


def test_plan_cache_key_follows_ratings_masses_and_payload(tmp_path: Path) -> None:
    """A rating, a link mass or a tool mass changes the plan, so each changes the cache key."""
    from rmot.compiler.frontend import load_program
    from rmot.compiler.plan_cache import plan_key

    keys = set()
    for j2 in (
        f"mass {MASS2:g} kg torque 50 N*m",
        f"mass {MASS2:g} kg torque 51 N*m",
        "mass 7 kg torque 50 N*m",
    ):
        result = load_program(_write(tmp_path, j2))
        keys.add(plan_key(result.program, 0.004))  # type: ignore[arg-type]
    assert len(keys) == 3
