"""INFORM lines with no rmot form say precisely why they stay native (W510 at their line).

Witnesses: the lines are the forms of pendant-saved jobs by other authors (tshikina's
testjob TEST1.JBI: `IMOV LP000 V=201.0`, `WAIT IN#(B004)=ON`, `TIMER T=LI005`; icors2's
Yaskawa-Job-Helper S1_90.JBI: `MOVJ EX001 VJ=100.00`); what each needs at run time (a variable's
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
])
def test_why_a_line_stays_native(line: str, why: str, tmp_path: Path) -> None:
    path = tmp_path / "TEST1.JBI"
    path.write_text(f"/JOB\n//NAME TEST1\n//POS\n///NPOS 0,0,0,0,0,0\n//INST\n///DATE 2020/11/19 13:27\n"
                    f"///ATTR SC,RW\n///GROUP1 RB1\nNOP\n{line}\nEND\n")
    doc = read_files([str(path)])
    assert [s.text for r in doc.routines for s in walk(r.body) if isinstance(s, Native)] == [line]
    w510 = [d for d in doc.diagnostics if d.code.id == "W510"]
    assert len(w510) == 1 and w510[0].span is not None and w510[0].span.start.line == 10
    assert why in w510[0].message, w510[0].message
