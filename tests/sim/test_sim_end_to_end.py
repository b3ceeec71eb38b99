"""`rmot check` on real programs: front end -> planner -> verification, in the default cell."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET

import pytest
from click.testing import CliRunner

from rmot.compiler.cli import check_cmd
from rmot.sim.report import validate_json

HEADER = """program NAME on r1 {
  tool gripper
  frame table_top
  speed 500 mm/s
  target home = joints(0, -30, 30, 0, 60, 0) deg
  move joint home
  move linear pose(x=100mm, y=200mm, z=150mm, rx=180deg)
"""

CLEAN = HEADER + """  move linear pose(x=100mm, y=200mm, z=50mm, rx=180deg) zone fine
  move joint home
}
"""

# line 8 drives the TCP 50 mm below the table top; the gripper's tip is 20 mm above its TCP
CRASH = HEADER + """  move linear pose(x=100mm, y=200mm, z=-50mm, rx=180deg) zone fine
  move joint home
}
"""


@pytest.fixture(scope="module")
def programs(tmp_path_factory):
    root = tmp_path_factory.mktemp("progs")
    (root / "clean.rmot").write_text(CLEAN.replace("NAME", "clean"))
    (root / "crash.rmot").write_text(CRASH.replace("NAME", "crash"))
    (root / "typo.rmot").write_text(CLEAN.replace("NAME", "typo").replace("move joint home\n}", "move joint hme\n}"))
    return root


def _run(*args: str):
    return CliRunner().invoke(check_cmd.check, list(args))


def test_clean_program_exits_zero(programs) -> None:
    """A program that stays 20 mm above the table: exit 0, a summary with its cycle time."""
    result = _run(str(programs / "clean.rmot"), "--clearance", "10mm")
    assert result.exit_code == 0, result.output
    assert "clean.rmot: ok: cycle time" in result.output


def test_crash_found_at_its_line(programs) -> None:
    """The gripper pushed 30 mm into the table: E300 at line 8 with both bodies and the depth."""
    result = _run(str(programs / "crash.rmot"), "--format", "json")
    assert result.exit_code == 1
    doc = json.loads(result.output)
    assert validate_json(doc) == []
    hits = [d for d in doc["programs"][0]["diagnostics"] if d["code"] == "E300"]
    assert len(hits) == 1
    hit = hits[0]
    assert hit["line"] == 8 and hit["bodies"] == ["gripper", "table"]
    # TCP 50 mm below the table top, tool tip 20 mm above the TCP: 30 mm deep
    assert hit["amount"] == {"value": pytest.approx(30.0, abs=0.5), "unit": "mm"}
    assert hit["time_s"] < hit["end_time_s"] <= doc["programs"][0]["cycle_time_s"]


def test_front_end_error_exits_two(programs) -> None:
    """A typo is an input error: its diagnostic in compiler style, exit code 2."""
    result = _run(str(programs / "typo.rmot"))
    assert result.exit_code == 2
    assert "typo.rmot:" in result.output and "error[E" in result.output


def test_parallel_jobs_same_output(programs) -> None:
    """--jobs 2 over three programs gives the serial run's bytes (JUnit here)."""
    files = [str(programs / n) for n in ("crash.rmot", "clean.rmot", "typo.rmot")]
    serial = _run(*files, "--format", "junit")
    parallel = _run(*files, "--format", "junit", "--jobs", "2")
    assert serial.exit_code == parallel.exit_code == 2
    assert serial.output == parallel.output
    cases = ET.fromstring(serial.output).findall("./testsuite/testcase")
    assert [c.get("name").rsplit("/", 1)[-1] for c in cases] == ["crash.rmot", "clean.rmot", "typo.rmot"]
    assert len(cases[0].findall("failure")) == 1


def test_images_for_error_findings(programs, tmp_path) -> None:
    """--images writes one PNG per error finding, named after the program and the code."""
    out = tmp_path / "img"
    result = _run(str(programs / "crash.rmot"), "--images", str(out))
    assert result.exit_code == 1
    files = sorted(p.name for p in out.iterdir())
    assert files == ["crash-01-E300.png"]
    assert (out / files[0]).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
