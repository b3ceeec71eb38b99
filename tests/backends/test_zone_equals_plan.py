"""Every backend prints the blend radius the plan verified, not the programmed zone.

The program blends a 200 mm move into a 50 mm one with `zone 50 mm`: the planner keeps the
blend inside half of each neighbouring move (compiler/plan/blend.py), min(50, 200 / 2, 50 / 2)
= 25 mm, the value the JSON report gives as the move's `blend_radius_mm`. Each vendor's text is
read by a pattern of its own documented form (RAPID zonedata's pzone_tcp, KRL $APO.CDIS mm,
Fanuc CNTn at 1 mm per step, URScript r in m, INFORM PL level distances 0/12.5/25/50/100 mm,
VAL3 mdesc leave/reach mm, CSV/JSON blend mm).
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from rmot.backends import BACKENDS
from rmot.compiler.cli import stages
from rmot.sim.timing_report import timing_json

PROGRAM = """program shrink on r1 {
  tool gripper
  speed 250 mm/s
  move joint joints(0, 0, 0, 0, 90, 0) deg zone fine
  move joint pose(x=800mm, y=-200mm, z=1000mm, rx=180deg) zone fine
  move linear pose(x=800mm, y=0mm, z=1000mm, rx=180deg) zone 50 mm
  move linear pose(x=800mm, y=0mm, z=950mm, rx=180deg) zone fine
}
"""
BLENDED_LINE = 6
PL_MM = {0: 0.0, 1: 12.5, 2: 25.0, 3: 50.0, 4: 100.0}  # INFORM PL level -> distance (backends/inform.py)


@pytest.fixture(scope="module")
def plan(tmp_path_factory: pytest.TempPathFactory):  # type: ignore[no-untyped-def]
    path = tmp_path_factory.mktemp("shrink") / "shrink.rmot"
    path.write_text(PROGRAM)
    front = stages.load(str(path), use_cache=False)
    assert front.program is not None
    return stages.plan(front.program, use_cache=False)


def _mm(vendor: str, text: str) -> float:
    """The blend radius (mm) a vendor's text gives to the one blended move."""
    if vendor == "rapid":
        custom = re.search(r"zonedata:\[FALSE,([\d.]+),", text) or re.search(r"zonedata [^:]*:=\[FALSE,([\d.]+),", text)
        if custom:
            return float(custom.group(1))
        return float(re.search(r",\s*z(\d+)\s*,", text).group(1))  # type: ignore[union-attr]
    if vendor == "krl":
        return float(re.search(r"\$APO\.CDIS\s*=\s*([\d.]+)", text).group(1))  # type: ignore[union-attr]
    if vendor == "fanuc":
        return float(re.search(r"CNT(\d+)", text).group(1))  # type: ignore[union-attr]
    if vendor == "urscript":
        radii = [float(r) for r in re.findall(r"r=([\d.]+)\)", text)]
        return max(radii) * 1000.0
    if vendor == "inform":
        return max(PL_MM[int(p)] for p in re.findall(r"PL=(\d)", text))
    if vendor == "val3":
        return max(float(v) for v in re.findall(r'leave="([\d.]+)"', text))
    raise AssertionError(vendor)


def test_json_gives_the_shrunk_radius(plan) -> None:  # type: ignore[no-untyped-def]
    (task,) = timing_json(plan)
    radii = {i["line"]: i["blend_radius_mm"] for i in task["instructions"] if i["kind"] == "move"}
    assert radii[BLENDED_LINE] == pytest.approx(min(50.0, 200.0 / 2, 50.0 / 2))


@pytest.mark.parametrize("vendor", ["rapid", "krl", "fanuc", "urscript", "inform", "val3"])
def test_every_vendor_prints_the_json_radius(plan, vendor: str) -> None:  # type: ignore[no-untyped-def]
    (task,) = timing_json(plan)
    expected = max(i["blend_radius_mm"] for i in task["instructions"] if i["kind"] == "move")
    result = BACKENDS[vendor]().emit(plan, source_map=False)
    text = "\n".join(result.files.values())
    assert _mm(vendor, text) == pytest.approx(expected, abs=1e-3), text


def test_neutral_formats_print_the_json_radius(plan) -> None:  # type: ignore[no-untyped-def]
    result = BACKENDS["json"]().emit(plan, source_map=False)
    (doc,) = [json.loads(t) for name, t in result.files.items() if Path(name).suffix == ".json"]
    blends = [i.get("blend_mm") for task in doc["tasks"] for i in task["instructions"] if "blend_mm" in i]
    assert max(blends) == pytest.approx(25.0)


def test_krl_ptp_blended_into_a_lin_is_c_ptp_c_dis(tmp_path_factory: pytest.TempPathFactory) -> None:
    """PTP -> LIN approximation is `PTP p C_PTP C_DIS` with $APO.CDIS the plan's radius (KUKA
    mxAutomation manual, PTP approximation); PTP -> PTP stays `C_PTP`. Read back by the KRL
    checker of tests/backends/vendor_validators.py."""
    from vendor_validators import check_krl

    path = tmp_path_factory.mktemp("ptp") / "ptp.rmot"
    path.write_text(PROGRAM.replace("move joint pose(x=800mm, y=-200mm, z=1000mm, rx=180deg) zone fine",
                                    "move joint pose(x=800mm, y=-200mm, z=1000mm, rx=180deg) zone 30 mm")
                    .replace("joints(0, 0, 0, 0, 90, 0) deg zone fine",
                             "joints(0, 0, 0, 0, 90, 0) deg zone fine\n  move joint joints(-5, 0, 0, 0, 90, 0) deg zone 10 mm"))
    front = stages.load(str(path), use_cache=False)
    assert front.program is not None
    files = BACKENDS["krl"]().emit(stages.plan(front.program, use_cache=False), source_map=False).files
    src = next(t for n, t in files.items() if n.endswith(".src")).splitlines()
    ptps = [k for k, line in enumerate(src) if line.strip().startswith("PTP ")]
    assert src[ptps[1]].strip().endswith(" C_PTP")  # into the next PTP
    assert src[ptps[2]].strip().endswith(" C_PTP C_DIS")  # into the LIN
    assert src[ptps[2] - 1].strip() == "$APO.CDIS=30.000"
    assert check_krl(files) == []
