"""External axes read back: compile -> `rmot import --cell` -> compile of the track and
positioner examples means the same program (readers/axes.py).

Witnesses (none of them the readers under test): the planner's own JSON plan of the original and
of the imported program (the round-trip harness of test_import_round_trip.py: every
instruction's kind, planned joints, branch, TCP pose and timing, and the cycle time), and each
move's external-axis values in that plan (`ext`, mm or deg), which the imported program must reproduce
to 0.001 mm / 0.001 deg. URScript and VAL3 have no external axes: compiling the examples for
them is refused (E607), so there is nothing to round-trip there.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest
from click.testing import CliRunner
from test_import_round_trip import MAIN_FILE, _compile, _leaves, _same_instruction

from rmot.compiler.cli import cli

ROOT = Path(__file__).resolve().parents[2]
AXES_EXAMPLES = ["track_tending", "weld_positioner"]
VENDORS = ["rapid", "krl", "fanuc"]


def _import(files: list[Path], out: Path, cell: Path | None) -> tuple[int, str]:
    args = ["import", *map(str, files), "-o", str(out)] + (["--cell", str(cell)] if cell else [])
    result = CliRunner().invoke(cli, args, catch_exceptions=False)
    return result.exit_code, result.output


def _turn_deg(qa: list[float], qb: list[float]) -> float:
    """The rotation between two unit quaternions, from the chord (2 atan2(|a - b|, |a + b|),
    exact near 0 where acos of their dot product is only good to ~0.005 deg at 9 digits)."""
    sign = 1.0 if sum(x * y for x, y in zip(qa, qb)) >= 0 else -1.0
    minus = math.sqrt(sum((x - sign * y) ** 2 for x, y in zip(qa, qb)))
    plus = math.sqrt(sum((x + sign * y) ** 2 for x, y in zip(qa, qb)))
    return math.degrees(2 * math.atan2(minus, plus))


def _same_move(a: dict, b: dict, cycle: float) -> None:
    """The round-trip harness' comparison, the TCP pose judged here (its orientation by `_turn_deg`)."""
    pa, pb = a["tcp_pose"], b["tcp_pose"]
    if pa is not None and a["kind"] != "move_joint":  # a joint move's target is its joints
        assert math.dist(pa["position_mm"], pb["position_mm"]) <= 0.001, (a["source"], pa, pb)
        turn = _turn_deg(pa["quaternion_wxyz"], pb["quaternion_wxyz"])
        assert turn <= 0.001, (a["source"], turn)
    _same_instruction({**a, "tcp_pose": None}, {**b, "tcp_pose": None}, cycle)


def _axis_values(plan: dict) -> list[dict]:
    return [i.get("ext") or {} for i in _leaves(plan)]


@pytest.mark.parametrize(("vendor", "name"), [(v, n) for v in VENDORS for n in AXES_EXAMPLES])
def test_axes_round_trip(vendor: str, name: str, tmp_path: Path) -> None:
    example = ROOT / "examples" / f"{name}.rmot"
    before = _compile(example, example, vendor, tmp_path / "a")
    files = sorted((tmp_path / "a" / vendor).glob(MAIN_FILE[vendor]))
    imported = tmp_path / f"{name}_imported.rmot"
    code, output = _import(files, imported, example)
    assert code == 0, output
    assert " 0 kept native (100.0 % imported)" in output, output
    assert re.search(r"(?m)^program \w+ on r1 with \w+", imported.read_text()), imported.read_text()
    after = _compile(imported, example, vendor, tmp_path / "b")
    assert abs(after["cycle_time"] - before["cycle_time"]) <= 0.005 * before["cycle_time"]
    for a, b in zip(_leaves(before), _leaves(after), strict=True):
        _same_move(a, b, before["cycle_time"])
    for a, b in zip(_axis_values(before), _axis_values(after), strict=True):
        assert a.keys() == b.keys(), (a, b)
        for axis, value in a.items():  # the plan's mm or deg
            assert abs(value - b[axis]) <= 0.001, (axis, value, b[axis])
