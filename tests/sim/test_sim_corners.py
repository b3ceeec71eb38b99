"""Blended corners: a fixture inside the region a controller may drive (sim/corners.py).

Witness: the gap between the gripper box and the post is plain arithmetic on the cell's
numbers (tests/data/corners/corner.rmot): the box's +y face is at 200 + 35 = 235 mm at the
corner, the post's -y face at POST_Y - 10 mm; the box's bottom is 20 mm above the TCP, the
post's top 10 mm above it (the gap is the hypotenuse of the two); the Fanuc bound is half
the 150 mm descent after the corner (the shorter neighbour; the move before it is 400 mm).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from click.testing import CliRunner

from rmot.compiler.cli import check_cmd, compile_cmd

SOURCE = (Path(__file__).parent.parent / "data" / "corners" / "corner.rmot").read_text()
BLENDED_LINE = 19  # the linear move to the corner


def _program(tmp_path: Path, post_y_mm: float, zone: str) -> Path:
    path = tmp_path / "corner.rmot"
    path.write_text(SOURCE.replace("POST_Y", f"{post_y_mm}mm").replace("ZONE", zone))
    return path


def _findings(path: Path, code: str) -> list[dict]:
    result = CliRunner().invoke(check_cmd.check, [str(path), "--format", "json", "--no-cache"])
    assert result.exit_code == 0, result.output  # warnings only
    report = json.loads(result.output)["programs"][0]
    return [d for d in report["diagnostics"] if d["code"] == code]


def test_post_inside_the_zone_sphere_is_reported_for_the_sphere_vendors(tmp_path: Path) -> None:
    found = _findings(_program(tmp_path, 260, "50 mm"), "W340")
    assert len(found) == 1
    assert found[0]["line"] == BLENDED_LINE
    assert found[0]["amount"]["value"] == pytest.approx(math.hypot(260 - 10 - 235, 20 - 10), abs=0.01)
    for words in ("RAPID zone", "KRL C_DIS", "URScript r", "VAL3 blend", "INFORM PL"):
        assert words in found[0]["message"]


def _compiled(path: Path, target: str) -> list:
    outcome = compile_cmd.compile_program(str(path), (target,), use_cache=False)
    return [d for d in outcome.diagnostics if d.code.id == "W341"]


def test_post_beyond_the_sphere_but_within_the_fanuc_bound(tmp_path: Path) -> None:
    """Outside the zone sphere: `rmot check` (no target) is clean, a Fanuc compile is told."""
    path = _program(tmp_path, 310, "50 mm")
    assert not _findings(path, "W340") and not _findings(path, "W341")
    (found,) = _compiled(path, "fanuc")
    assert found.span.start.line == BLENDED_LINE
    assert found.amount.value == pytest.approx(math.hypot(310 - 10 - 235, 20 - 10), abs=0.01)
    assert "Fanuc CNT" in found.message and "(75.0 mm)" in found.message
    assert "KRL C_PTP" not in found.message  # a linear move: KRL writes C_DIS
    assert not _compiled(path, "rapid") and not _compiled(path, "krl")


def test_fine_corner_and_distant_post_are_clean(tmp_path: Path) -> None:
    assert not _findings(_program(tmp_path, 260, "fine"), "W340")
    far = _program(tmp_path, 400, "50 mm")
    assert not _findings(far, "W340") and not _findings(far, "W341")


def test_json_gives_each_moves_verified_blend_radius(tmp_path: Path) -> None:
    """min(zone, half of each neighbouring move) = min(90, 400 / 2, 150 / 2) mm; 0 where it stops."""
    path = _program(tmp_path, 400, "90 mm")
    result = CliRunner().invoke(check_cmd.check, [str(path), "--format", "json", "--no-cache"])
    (task,) = json.loads(result.output)["programs"][0]["tasks"]
    assert task["accelerations"].startswith("estimate")  # the IRB 1600's: marked per arm
    radii = {i["line"]: i["blend_radius_mm"] for i in task["instructions"] if i["kind"] == "move"}
    assert radii == {BLENDED_LINE - 2: 0.0, BLENDED_LINE - 1: 0.0, BLENDED_LINE: 75.0, BLENDED_LINE + 1: 0.0}


def test_a_blended_joint_move_names_krl_c_ptp_too(tmp_path: Path) -> None:
    """A PTP's corner (KRL C_PTP, a share of half the PTP motion) has the same bound as Fanuc's
    CNT: a KRL compile reports it for a joint move, not for a linear one (above)."""
    path = tmp_path / "corner.rmot"
    path.write_text(SOURCE.replace("POST_Y", "310mm").replace("ZONE", "50 mm").replace(
        "move linear pose(x=800mm, y=200mm, z=1000mm", "move joint pose(x=800mm, y=200mm, z=1000mm"))
    (found,) = _compiled(path, "krl")
    assert "Fanuc CNT and KRL C_PTP" in found.message and found.span.start.line == BLENDED_LINE
