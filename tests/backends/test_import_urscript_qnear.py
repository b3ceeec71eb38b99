"""URScript `movej(get_inverse_kin(P, qnear=Q))` (PolyScope's MoveJ waypoint) read with the branch
the controller takes: the solution of P nearest Q (URScript manual, `get_inverse_kin`).

Witnesses: P is written from Q by the UR5e's published DH parameters (Universal Robots, "DH
parameters for calculations of kinematics and dynamics": d1 0.1625, a2 -0.425, a3 -0.3922,
d4 0.1333, d5 0.0997, d6 0.0996 m) with scipy's rotation vectors, independently of rmot's
kinematics; so the solution nearest Q is Q itself, and the planner's own JSON plan (q_target)
must end the imported move at Q. The start lies on the other wrist branch, where rmot's rule
without the config (nearest the current joints) ends elsewhere."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from scipy.spatial.transform import Rotation

from rmot.compiler.cli import cli

_D = (0.1625, 0.0, 0.0, 0.1333, 0.0997, 0.0996)
_A = (0.0, -0.425, -0.3922, 0.0, 0.0, 0.0)
_ALPHA = (math.pi / 2, 0.0, 0.0, math.pi / 2, -math.pi / 2, 0.0)


def _dh_pose(q: tuple[float, ...]) -> str:
    """The UR5e flange pose of joints q (rad) as URScript writes it, p[x, y, z, rx, ry, rz]."""
    t = np.eye(4)
    for theta, d, a, alpha in zip(q, _D, _A, _ALPHA, strict=True):
        ct, st, ca, sa = math.cos(theta), math.sin(theta), math.cos(alpha), math.sin(alpha)
        t = t @ np.array([[ct, -st * ca, st * sa, a * ct], [st, ct * ca, -ct * sa, a * st], [0, sa, ca, d], [0, 0, 0, 1]])
    values = [*t[:3, 3], *Rotation.from_matrix(t[:3, :3]).as_rotvec()]
    return "p[" + ", ".join(f"{v:.10f}" for v in values) + "]"


START = (0.3, -0.8, 1.4, 2.1, -1.4, 5.1)  # beside the other wrist branch of Q's pose (J5 < 0)
Q = (0.3, -1.2, 1.5, -0.8, 1.4, 2.0)
Q_TURNED = (0.3, -1.2, 1.5, -0.8, 1.4, 2.0 - 2 * math.pi)  # J6 one turn back (within ±360°): the same pose


def _script(q: tuple[float, ...], start: tuple[float, ...] = START, qnear: str = "Waypoint_1_q") -> str:
    return (f"def prog():\n  global Waypoint_1_p={_dh_pose(q)}\n  global Waypoint_1_q=[{', '.join(map(str, q))}]\n"
            f"  movej([{', '.join(map(str, start))}], a=1.4, v=1.05)\n"
            f"  movej(get_inverse_kin(Waypoint_1_p, qnear={qnear}), a=1.4, v=1.05)\nend\n")


def _import(tmp_path: Path, script: str, *options: str) -> tuple[Path, str]:
    path = tmp_path / "prog.script"
    path.write_text(script)
    out = tmp_path / "prog.rmot"
    result = CliRunner().invoke(cli, ["import", str(path), "-o", str(out), *options], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    return out, result.output


def _planned_end(tmp_path: Path, program: Path) -> list[float]:
    result = CliRunner().invoke(cli, ["compile", str(program), "--target", "json", "-o", str(tmp_path / "plan"),
                                      "--allow-findings"], catch_exceptions=False)
    assert result.exit_code in (0, 1), result.output
    plan = json.loads(next((tmp_path / "plan" / "json").glob("*.json")).read_text())
    moves = [i for i in plan["tasks"][0]["instructions"] if "q_target" in i]
    return [float(v) for v in moves[-1]["q_target"]]


@pytest.mark.parametrize("q", [Q, Q_TURNED], ids=["other-wrist", "j6-next-turn"])
def test_the_imported_move_ends_at_the_joints_qnear_names(q: tuple[float, ...], tmp_path: Path) -> None:
    program, output = _import(tmp_path, _script(q), "--robot", "ur5e")
    assert "W529" not in output
    assert "move joint Waypoint_1_p config(" in program.read_text()
    assert _planned_end(tmp_path, program) == pytest.approx(q, abs=math.radians(0.001))


def test_without_the_branch_rmot_would_end_elsewhere(tmp_path: Path) -> None:
    """The reason for the config: the same program without it plans (nearest the current joints)
    to other joints than the controller's, so the test above can fail."""
    program, _ = _import(tmp_path, _script(Q), "--robot", "ur5e")
    text = program.read_text()
    start = text.index(" config(")
    program.write_text(text[:start] + text[text.index(")", start) + 1:])
    assert _planned_end(tmp_path, program) != pytest.approx(Q, abs=math.radians(0.001))


def test_without_the_arm_the_move_says_the_branch_was_not_read(tmp_path: Path) -> None:
    program, output = _import(tmp_path, _script(Q))
    assert "warning[W529]" in output and "nearest qnear `Waypoint_1_q`" in output and "--cell or --robot" in output
    assert "prog.script:5:3" in output
    assert "move joint Waypoint_1_p zone fine" in program.read_text()


def test_a_qnear_known_only_at_run_time_is_said(tmp_path: Path) -> None:
    script = _script(Q, qnear="get_actual_joint_positions()").replace(
        "qnear=get_actual_joint_positions()", "qnear=q_now")
    program, output = _import(tmp_path, script, "--robot", "ur5e")
    assert "warning[W529]" in output and "`q_now` is not known here" in output
    assert "config(" not in program.read_text()


def test_a_plain_pose_movej_is_left_to_the_current_joints(tmp_path: Path) -> None:
    """`movej(P)` without qnear: the controller too solves near the current joints; no warning."""
    _, output = _import(tmp_path, _script(Q).replace("get_inverse_kin(Waypoint_1_p, qnear=Waypoint_1_q)",
                                                      "Waypoint_1_p"), "--robot", "ur5e")
    assert "W529" not in output
