"""KRL on a controller the cell declares as KSS >= 8.2 (`robot r1 = NAME controller kss 8.3`):
a blended PTP is written with the exact radius form `$APO.CDIS=r` + `PTP p C_DIS` (KUKA System
Software 8.2/8.3 Operating and Programming Instructions for System Integrators, "Approximate
positioning"), whose corner keeps to the zone sphere, so no W341 names KRL C_PTP for it; without
the declaration the C_PTP form (W403) and its corner bound (W341) stay.

Witnesses: the radius each move must carry is the JSON report's `blend_radius_mm` (the plan's
verified value, read through `rmot check --format json`), and min(zone, half of each neighbour)
by hand from tests/data/corners/corner.rmot (50 mm here); the text is read by the KRL checker of
vendor_validators.py.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from click.testing import CliRunner

from rmot.compiler.cli import check_cmd, compile_cmd
from vendor_validators import check_krl

SOURCE = (Path(__file__).resolve().parents[1] / "data" / "corners" / "corner.rmot").read_text()
BLENDED_LINE = 19  # the move to the corner, a PTP here


def _program(tmp_path: Path, controller: str, post_y: str = "310mm") -> Path:
    path = tmp_path / "corner.rmot"
    path.write_text(SOURCE.replace("POST_Y", post_y).replace("ZONE", "50 mm")
                    .replace("move linear pose(x=800mm, y=200mm, z=1000mm",
                             "move joint pose(x=800mm, y=200mm, z=1000mm")
                    .replace("robot r1 = abb_irb1600 at", f"robot r1 = abb_irb1600 {controller} at"))
    return path


def _krl(path: Path) -> tuple[str, dict[str, str], list]:  # type: ignore[type-arg]
    outcome = compile_cmd.compile_program(str(path), ("krl",), use_cache=False)
    files = {name.rsplit("/", 1)[-1]: text for name, text in outcome.files.items()}
    src = next(t for n, t in files.items() if n.endswith(".src"))
    return src, files, list(outcome.diagnostics)


def _blend_radii(path: Path) -> dict[int, float]:
    result = CliRunner().invoke(check_cmd.check, [str(path), "--format", "json", "--no-cache"])
    (task,) = json.loads(result.output)["programs"][0]["tasks"]
    return {i["line"]: i["blend_radius_mm"] for i in task["instructions"] if i["kind"] == "move"}


def _approximated_ptps(src: str) -> list[tuple[str, tuple[str, ...]]]:
    """(the approximation suffix, the $APO distances set since the previous motion) of each
    approximated PTP."""
    out: list[tuple[str, tuple[str, ...]]] = []
    since: list[str] = []
    for line in (ln.strip() for ln in src.splitlines()):
        if m := re.match(r"^\$APO\.(CDIS|CPTP)=(\S+)$", line):
            since.append(f"{m.group(1)}={m.group(2)}")
        elif m := re.match(r"^(PTP|LIN|CIRC) [\w,]+( C_\w+(?: C_\w+)?)?$", line):
            if m.group(1) == "PTP" and m.group(2):
                out.append((m.group(2).strip(), tuple(since)))
            since = []
    return out


def test_kss_82_writes_the_blend_radius_with_c_dis(tmp_path: Path) -> None:
    path = _program(tmp_path, "controller kss 8.3")
    src, files, diagnostics = _krl(path)
    radius = _blend_radii(path)[BLENDED_LINE]
    assert radius == pytest.approx(50.0)  # min(50, 400 / 2, 150 / 2) mm
    assert _approximated_ptps(src) == [("C_DIS", (f"CDIS={radius:.3f}",))]
    assert check_krl(files, kss_exact_ptp=True) == []
    codes = [d.code.id for d in diagnostics]
    assert "W403" not in codes and "W341" not in codes  # exact, and inside the zone sphere


@pytest.mark.parametrize("controller", ["", "controller kss 8.1"])
def test_older_or_undeclared_kss_keeps_c_ptp_and_its_bound(tmp_path: Path, controller: str) -> None:
    path = _program(tmp_path, controller)
    src, files, diagnostics = _krl(path)
    # a PTP blended into a LIN: C_PTP with C_DIS for the CP part (mxAutomation manual, PTP)
    assert _approximated_ptps(src) == [("C_PTP C_DIS", ("CPTP=50", "CDIS=50.000"))]
    assert check_krl(files) == []
    codes = [d.code.id for d in diagnostics]
    assert "W403" in codes and "W341" in codes


@pytest.mark.parametrize("controller", ["controller vkrc 8.3", "controller kss 8.3mm",
                                        "controller kss 0"])
def test_unknown_software_or_release_is_e118(tmp_path: Path, controller: str) -> None:
    path = _program(tmp_path, controller)
    result = CliRunner().invoke(check_cmd.check, [str(path), "--no-cache"])
    assert result.exit_code == 2 and "error[E118]" in result.output
    assert f"{path}:9:" in result.output  # the robot's line
