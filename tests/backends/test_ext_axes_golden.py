"""Golden files of an example that drives external axes (examples/track_tending.rmot), for the
vendors that write external axes; the other external-axes tests are in tests/ext_axes."""

from __future__ import annotations

import pytest
from backend_fixtures import check_golden, example_plans

from rmot.backends import BACKENDS


@pytest.mark.parametrize("vendor", ["rapid", "krl", "fanuc", "inform"])
def test_track_tending_golden(vendor: str) -> None:
    """examples/track_tending.rmot for RAPID, KRL and Fanuc TP equals its golden files, read by hand once:
    RAPID robtargets carry the carriage in eax_a (600, 2000, 3400 mm), the work objects are
    fixed in the robot's world with the track at 0 (door_a 550 mm above the base's 250 mm);
    KRL E6POS carry it in E1 and each PTP that moves the track sets $VEL_EXTAX[1]/$ACC_EXTAX[1];
    Fanuc positions carry it as `E1=` of group 1, the stations' frames as UFRAMEs in the world;
    INFORM positions are C in ROBOT coordinates (the arm's base on the carriage: x 0 at the
    stations, y +-1100/-1000 mm) beside BC pulses at the declared 200 pulses/mm (120000, 400000,
    680000 for 600, 2000, 3400 mm), NPOS 11,11,0,0,0,0, ///GROUP1 RB1,BS1 and no station."""
    result = BACKENDS[vendor]().emit(example_plans(("track_tending",))["track_tending"])
    assert not result.has_errors
    check_golden(vendor, "track_tending", result.files)


def test_weld_positioner_inform_golden() -> None:
    """examples/weld_positioner.rmot for INFORM equals its golden file, read by hand once: the
    seam's four quarter arcs as one SMOVC start line and a via and an FPT end per quarter, each
    with `+MOVJ ECn` and no VJ (the station follows the robot's V=12.0, relative to the part);
    the vias' turntable at 45, 135, 225, 315 deg (45000.. pulses at the declared 1000/deg), the
    ends at 90..360 deg; approach, departure and the turntable's return as MOVL/MOVJ with the
    station's own VJ; ///GROUP1 RB1, ///GROUP2 ST1 and the R1:S1 calibration in the checklist
    (the positioner's axes at X 1100, Y 0, Z 600 mm in the robot's frame)."""
    result = BACKENDS["inform"]().emit(example_plans(("weld_positioner",))["weld_positioner"])
    assert not result.has_errors
    check_golden("inform", "weld_positioner", result.files)
