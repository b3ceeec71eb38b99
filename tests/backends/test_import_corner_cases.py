"""Vendor forms a reader once read silently wrong: each is now read exactly or kept native.

Witnesses: INFORM if-chains (`JUMP *L IF IN#(n)=X` to one label, or to a label past the other
tests, as backends/inform.py writes `and` and `or`) are run by a small INFORM interpreter
written here from the language's rules (DX100/YRC1000 INFORM manual, JUMP: the job continues at
the label when the condition holds; labels `*L`), for every level of the inputs, against a
separate evaluation of the condition the import reads.
"""

from __future__ import annotations

import itertools
import re
from pathlib import Path

import pytest

from rmot.backends.readers import read_files
from rmot.backends.readers.model import Cond, Conds, GroupIn, If, Native, SetOut, walk

_JOB_HEAD = ("/JOB\n//NAME CHAIN\n//POS\n///NPOS 0,0,0,0,0,0\n//INST\n///DATE 2020/11/19 13:27\n"
             "///ATTR SC,RW\n///GROUP1 RB1\nNOP\n")


def _job(lines: list[str], tmp_path: Path) -> str:
    path = tmp_path / "CHAIN.JBI"
    path.write_text(_JOB_HEAD + "\n".join(lines) + "\nEND\n")
    return str(path)


def _runs(lines: list[str], inputs: dict[int, bool]) -> list[str]:
    """The outputs an INFORM job's lines set, in order, with inputs at the given levels."""
    labels = {ln: k for k, ln in enumerate(lines) if re.fullmatch(r"\*L\w+", ln)}
    k, done = 0, []
    while k < len(lines):
        ln, k = lines[k], k + 1
        if m := re.fullmatch(r"JUMP (\*L\w+) IF IN#\((\d+)\)=(ON|OFF)", ln):
            k = labels[m.group(1)] if inputs[int(m.group(2))] == (m.group(3) == "ON") else k
        elif m := re.fullmatch(r"JUMP (\*L\w+)", ln):
            k = labels[m.group(1)]
        elif m := re.fullmatch(r"DOUT OT#\((\d+)\) ON", ln):
            done.append(m.group(1))
        else:
            assert ln in labels, ln
    return done


def _holds(c: Cond | Conds | GroupIn, inputs: dict[int, bool]) -> bool:
    assert isinstance(c, (Cond, Conds)) and not (isinstance(c, Cond) and c.output), c
    if isinstance(c, Cond):
        return inputs[int(c.signal)] == c.on
    assert c.op in ("and", "or"), c
    values = [_holds(p, inputs) for p in c.parts]
    return all(values) if c.op == "and" else any(values)


def _imported_runs(s: If, inputs: dict[int, bool]) -> list[str]:
    arm = s.then if _holds(s.cond, inputs) else s.orelse
    return [str(x.signal) for x in arm if isinstance(x, SetOut)]


@pytest.mark.parametrize("lines", [
    # `and`: two jumps over the arm to one label (it runs when neither input is on)
    ["JUMP *L4 IF IN#(1)=ON", "JUMP *L4 IF IN#(2)=ON", "DOUT OT#(5) ON", "*L4"],
    # three, with an else arm
    ["JUMP *L1 IF IN#(1)=OFF", "JUMP *L1 IF IN#(2)=ON", "JUMP *L1 IF IN#(3)=OFF", "DOUT OT#(5) ON",
     "JUMP *L2", "*L1", "DOUT OT#(6) ON", "*L2"],
    # `or`: a jump past the other test when in[1] is on, a jump over the arm when in[2] is off
    ["JUMP *L7 IF IN#(1)=ON", "JUMP *L8 IF IN#(2)=OFF", "*L7", "DOUT OT#(5) ON", "*L8"],
    ["JUMP *L7 IF IN#(1)=OFF", "JUMP *L7 IF IN#(3)=ON", "JUMP *L8 IF IN#(2)=ON", "*L7", "DOUT OT#(5) ON",
     "JUMP *L9", "*L8", "DOUT OT#(6) ON", "*L9"],
])
def test_an_inform_jump_chain_reads_as_one_condition(lines: list[str], tmp_path: Path) -> None:
    doc = read_files([_job(lines, tmp_path)])
    body = doc.routines[0].body
    assert not [d for d in doc.diagnostics if d.code.id == "W510"], doc.diagnostics
    assert len(body) == 1 and isinstance(body[0], If), body
    for levels in itertools.product((False, True), repeat=3):
        inputs = dict(enumerate(levels, 1))
        assert _imported_runs(body[0], inputs) == _runs(lines, inputs), (inputs, body[0].cond)


def test_a_chain_whose_label_another_line_jumps_to_stays_native(tmp_path: Path) -> None:
    lines = ["JUMP *L4 IF IN#(1)=ON", "JUMP *L4 IF IN#(2)=ON", "DOUT OT#(5) ON", "*L4", "DOUT OT#(6) ON",
             "JUMP *L4 IF IN#(3)=ON"]
    doc = read_files([_job(lines, tmp_path)])
    natives = [s.text for s in walk(doc.routines[0].body) if isinstance(s, Native)]
    assert not [s for s in walk(doc.routines[0].body) if isinstance(s, If)]
    assert natives == [ln for ln in lines if not ln.startswith("DOUT")], natives
