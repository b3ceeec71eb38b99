"""`rmot place` finds a base pose with which a failing program verifies — checked by a separate
`rmot check` of the cell it writes — and reports infeasibility where the region provably has
no pose (every point of it is farther from every target than the arm can stretch)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from rmot.compiler.cli import cli

DATA = Path(__file__).resolve().parent / "data"
PROGRAM = str(DATA / "draw.rmot")


def _check(cell: Path) -> dict:
    result = CliRunner().invoke(cli, ["check", PROGRAM, "--cell", str(cell), "--format", "json"])
    return json.loads(result.output)["programs"][0]


@pytest.mark.parametrize(("cell", "code", "region", "samples"), [
    ("cell_far.rmot", "E220", "x=-600mm..0mm, y=-400mm..400mm", "48"),                        # out of reach
    ("cell_turned.rmot", "E221", "x=-300mm..0mm, y=-300mm..300mm, rz=-180deg..180deg", "64"),  # joint limit
    ("cell_blocked.rmot", "E300", "x=-500mm..100mm, y=-500mm..500mm, rz=-180deg..180deg", "128"),  # collision
])
def test_place_fixes_a_failing_placement(tmp_path: Path, cell: str, code: str, region: str, samples: str) -> None:
    """The cell's own pose fails with `code`; the placed copy passes `rmot check`, with the cycle time printed,
    inside the region, and only the robot's `at` changed."""
    before = _check(DATA / cell)
    assert code in {d["code"] for d in before["diagnostics"] if d["severity"] == "error"}
    out = tmp_path / "placed.rmot"
    result = CliRunner().invoke(cli, ["place", PROGRAM, "--cell", str(DATA / cell), "--region", region,
                                      "-o", str(out), "--samples", samples])
    assert result.exit_code == 0, result.output
    after = _check(out)
    assert not [d for d in after["diagnostics"] if d["severity"] == "error"]
    best = next(line for line in result.output.splitlines() if line.startswith("best"))
    assert f"cycle {after['cycle_time_s']:.3f} s" in best
    old, new = (DATA / cell).read_text().splitlines(), out.read_text().splitlines()
    changed = [(a, b) for a, b in zip(old, new) if a != b]
    assert len(old) == len(new) and len(changed) == 1 and changed[0][1].lstrip().startswith("robot r1 = abb_irb120 at pose(")
    x = float(changed[0][1].split("x=")[1].split("mm")[0]) / 1000
    lo, hi = (float(v.replace("mm", "")) / 1000 for v in region.split(",")[0].split("=")[1].split(".."))
    assert lo - 1e-6 <= x <= hi + 1e-6


def test_provably_empty_region_is_reported_infeasible(tmp_path: Path) -> None:
    """A region 5 m away: the IRB 120 reaches 0.58 m to its wrist centre (ABB product specification
    3HAC035960-001), plus 72 mm to the flange and the 100 mm pen — under 1 m — so no pose in it can
    reach the square; place says so, names the targets, exits 1 and writes nothing."""
    square = np.array([[0.25, -0.05], [0.35, 0.05]])  # the square's x, y extent in world (cell: work frame)
    region = ((5.0, 6.0), (5.0, 6.0))
    gap = math.hypot(region[0][0] - square[1, 0], region[1][0] - square[1, 1])
    assert gap > 1.0  # nothing within 1 m: provably empty
    out = tmp_path / "placed.rmot"
    result = CliRunner().invoke(cli, ["place", PROGRAM, "--cell", str(DATA / "cell_far.rmot"),
                                      "--region", "x=5m..6m, y=5m..6m, rz=-180deg..180deg", "-o", str(out), "--samples", "32"])
    assert result.exit_code == 1
    assert "no pose of robot 'r1' in the region verifies" in result.output
    assert "draw.rmot:9:3: target unreachable (no IK solution within the joint limits) from 32 of 32 sampled poses" in result.output
    assert not out.exists()


@pytest.mark.parametrize(("region", "message"), [
    ("x=0..1m, y=0m..1m", "x must be a number with a unit"),
    ("x=0m..1m", "region must give y=LO..HI"),
    ("x=1m..0m, y=0m..1m", "must go from low to high"),
])
def test_bad_region_is_a_usage_error(tmp_path: Path, region: str, message: str) -> None:
    """A region that does not parse exits 2 with a message."""
    result = CliRunner().invoke(cli, ["place", PROGRAM, "--cell", str(DATA / "cell_far.rmot"), "--region", region,
                                      "-o", str(tmp_path / "x.rmot")])
    assert result.exit_code == 2 and message in result.output


def test_halton_points_are_stratified() -> None:
    """The screening sequence: of 256 points, each 1/256 slice of x holds exactly one (base 2), and of the
    first 243 each 1/243 slice of y holds exactly one (base 3) — the van der Corput property."""
    from rmot.compiler.design.place import halton

    u = halton(256, 2)
    assert sorted(int(a * 256) for a in u[:, 0]) == list(range(256))
    assert sorted(int(round(b * 243 * 1e6) // 1e6) for b in u[:243, 1]) == list(range(243))
    assert u.min() >= 0 and u.max() < 1
