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
    ("PAUSE", "PAUSE holds the job until the operator starts it again, and it runs on from there"),
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


def _job(name: str, lines: list[str]) -> str:
    return (f"/JOB\n//NAME {name}\n//POS\n///NPOS 2,0,0,0,0,0\n///TOOL 0\n///POSTYPE ROBOT\n///RECTAN\n"
            "C00000=800.000,0.000,600.000,180.0000,0.0000,0.0000\n"
            "C00001=800.000,100.000,600.000,180.0000,0.0000,0.0000\n//INST\n///DATE 2020/11/19 13:27\n"
            "///ATTR SC,RW\n///GROUP1 RB1\nNOP\n" + "".join(f"{ln}\n" for ln in lines) + "END\n")


def _body(tmp_path: Path, jobs: dict[str, list[str]]) -> list[tuple[str, str]]:
    paths = []
    for name, lines in jobs.items():
        (tmp_path / f"{name}.JBI").write_text(_job(name, lines))
        paths.append(str(tmp_path / f"{name}.JBI"))
    doc = read_files(paths)
    return [(r.name, type(s).__name__ + (f" {s.text}" if isinstance(s, Native) else ""))
            for r in doc.routines for s in walk(r.body)]


def test_a_pause_mid_job_holds_and_runs_on(tmp_path: Path) -> None:
    """A pendant's PAUSE between moves (YASNAC-era jobs pause for a look, then run on when
    started, YRC1000 INSTRUCTIONS "PAUSE"): native at its place, the moves after it read and
    planned as the controller runs them (it was read as `stop`, and the rest never ran)."""
    assert _body(tmp_path, {"CIRC": ["MOVL C00000 V=46.0", "PAUSE", "MOVL C00001 V=11.0"]}) == [
        ("CIRC", "Move"), ("CIRC", "Native PAUSE"), ("CIRC", "Move")]


def test_the_stop_the_backend_writes_reads_back_as_stop(tmp_path: Path) -> None:
    """rmot's `stop` in the main job is `MSG "STOP"`, `PAUSE`, `JUMP *L001` to the label before
    END (backends/inform.py); in a called job `MSG "STOP"`, `PAUSE`: both read as `stop`, the
    label with nothing to do gone. A jump to that label from anything else keeps it."""
    main = ["MOVL C00000 V=46.0", "CALL JOB:SUB", 'MSG "STOP"', "PAUSE", "JUMP *L001", "MOVL C00001 V=11.0", "*L001"]
    assert _body(tmp_path, {"MAIN": main, "SUB": ["MOVL C00001 V=11.0", 'MSG "STOP"', "PAUSE"]}) == [
        ("MAIN", "Move"), ("MAIN", "Call"), ("MAIN", "Stop"), ("MAIN", "Move"), ("SUB", "Move"), ("SUB", "Stop")]
    other = ["JUMP *L001 IF IN#(1)=ON", *main]
    assert ("MAIN", "Native *L001") in _body(tmp_path, {"MAIN": other})
