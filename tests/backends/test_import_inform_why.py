"""INFORM lines with no rmot form say precisely why they stay native (W510 at their line).

Witnesses: the lines are the forms of pendant-saved jobs by other authors (tshikina's
testjob TEST1.JBI: `IMOV LP000 V=201.0`, `WAIT IN#(B004)=ON`, `TIMER T=LI005`; icors2's
Yaskawa-Job-Helper S1_90.JBI: `MOVJ EX001 VJ=100.00`; hehonglu123's Welding_Motoman
linear.JBI: `MOVL C00000 V=10.0 PL=8`, here to a position variable declared in the job); what each needs at run time (a variable's
value) is read from the line by hand here.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from rmot.backends.readers import read_files
from rmot.backends.readers.model import Native, walk


@pytest.mark.parametrize(("line", "why"), [
    ("IMOV LP000 V=201.0", "IMOV moves by an increment from wherever the robot stands"),
    ("WAIT IN#(B004)=ON", "the input's number is variable B004's value at run time"),
    ("TIMER T=LI005", "the time is variable LI005's value at run time"),
    ("MOVJ EX001 VJ=100.00", "moves the station alone to its position variable EXn"),
    ("MOVL P001 V=10.0 PL=8", "PL=8: rmot knows the distances of positioning levels 0..4 only"),
])
def test_why_a_line_stays_native(line: str, why: str, tmp_path: Path) -> None:
    path = tmp_path / "TEST1.JBI"
    path.write_text(f"/JOB\n//NAME TEST1\n//POS\n///NPOS 0,0,0,1,0,0\n///TOOL 0\n///POSTYPE ROBOT\n///RECTAN\n"
                    "P00001=800.000,0.000,600.000,180.0000,0.0000,0.0000\n//INST\n///DATE 2020/11/19 13:27\n"
                    f"///ATTR SC,RW\n///GROUP1 RB1\nNOP\n{line}\nEND\n")
    doc = read_files([str(path)])
    assert [s.text for r in doc.routines for s in walk(r.body) if isinstance(s, Native)] == [line]
    w510 = [d for d in doc.diagnostics if d.code.id == "W510"]
    assert len(w510) == 1 and w510[0].span is not None and w510[0].span.start.line == 14
    assert why in w510[0].message, w510[0].message
