"""An INFORM job whose control group holds the robot and its station (`///GROUP1 RB1,ST1`):
the station's position `ECnnnnn` stands right after the robot's in the move (`MOVL C00000
EC00000 V=1600.0`, as MQCIA's pendant-saved DROP01.JBI writes it), one interpolation for both,
as a base axis' `BCnnnnn` is (backends/inform_axes.py: "one control group, one interpolation").
rmot's move with `ext(...)` is that: every axis starts and stops with the arm.

Witness: the station's angles are the job's pulses over the cell's declared scale
(weld_positioner.rmot: `inform(pulses_per_deg=1000)` on both axes), worked by hand here:
EC00000=0,90000 is (0 deg, 90 deg); the same line in a job whose station is its own group
(`///GROUP2 ST1`, where only `+MOVJ ECn` moves it) stays native.
"""

from __future__ import annotations

import re
from pathlib import Path

from test_import_axes import _import_on_positioner

JOB = ("/JOB\n//NAME HAND\n//POS\n///NPOS 1,0,1,0,0,0\n///TOOL 0\n///POSTYPE ROBOT\n///RECTAN\n"
       "///RCONF 0,0,0,0,0,0,0,0\nC00000=1000.000,0.000,630.000,135.0000,0.0000,90.0000\n"
       "///POSTYPE PULSE\n///PULSE\nEC00000=0,90000\n//INST\n///DATE 2000/01/01 00:00\n"
       "///ATTR SC,RW\n{groups}\nNOP\nMOVL C00000 EC00000 V=100.0\nEND\n")


def test_station_in_the_robots_group_moves_with_the_arm(tmp_path: Path) -> None:
    output = _import_on_positioner(tmp_path, "HAND.JBI", JOB.format(groups="///GROUP1 RB1,ST1"))
    assert "W510" not in output and "W523" not in output, output
    assert re.search(r"move linear hand_c00000 ext\(pos=\(0deg, 90deg\)\) speed 100 mm/s",
                     (tmp_path / "out.rmot").read_text())


def test_station_in_its_own_group_stays_native(tmp_path: Path) -> None:
    output = _import_on_positioner(tmp_path, "HAND.JBI", JOB.format(groups="///GROUP1 RB1\n///GROUP2 ST1"))
    assert re.search(r"HAND\.JBI:\d+:1: warning\[W510\]: .*station \(EC\) position", output), output
    assert "ext(" not in (tmp_path / "out.rmot").read_text()
