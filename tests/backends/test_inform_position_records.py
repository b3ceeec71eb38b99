"""An INFORM line `rmot import` keeps native that moves to a robot position of its job (a
pendant's pulse position read without --pulses-per-degree) compiles back for INFORM with that
position's record (readers/position_records.py, backends/inform_records.py, lang/REFERENCE.md
§5 `native`, §14).

Witnesses: //POS is read here with a small state machine over the pseudo-instructions (YRC1000
INSTRUCTIONS, position data: `///TOOL n`, `///USER n`, `///POSTYPE`, `///PULSE`/`///RECTAN`,
`///RCONF` hold for the positions after them), in the source job and in the compiled one; each
native move must name, in the compiled job, a position with the tool, coordinate system,
configuration and values its position has in the source. The compiled job must also pass the
independent INFORM validator of tests/backends/vendor_validators.py (counts, order, names).
"""

from __future__ import annotations

import re
from pathlib import Path

from click.testing import CliRunner
from vendor_validators import check_inform

from rmot.compiler.cli import cli

JOB = """/JOB
//NAME TCPCHK
//POS
///NPOS 5,0,0,0,0,0
///TOOL 1
///POSTYPE PULSE
///PULSE
C00000=-4317,-84436,-64683,-41499,-71625,29263
C00001=-4317,-90930,-87249,-44324,-63766,32764
///TOOL 2
C00002=-4317,-91143,-89097,-44673,-63021,33127
///USER 3
///TOOL 1
///POSTYPE USER
///RECTAN
///RCONF 0,0,0,0,0,0,0,0
C00003=400.000,50.000,250.000,180.0000,0.0000,0.0000
///POSTYPE ROBOT
///RECTAN
///RCONF 0,0,0,0,0,0,0,0
C00004=450.000,0.000,300.000,180.0000,0.0000,0.0000
//INST
///DATE 2025/06/18 13:27
///ATTR SC,RW
///GROUP1 RB1
NOP
MOVJ C00004 VJ=50.00
MOVL C00003 V=20.0 UNTIL IN#(5)=ON
MOVJ C00001 VJ=30.00
MOVL C00002 V=10.6
MOVJ C00004 VJ=50.00
END
"""


def _positions(job: str) -> dict[str, tuple[int, str, str, int | None, str, str]]:
    """Each C position: (tool file, POSTYPE, data form, user frame, RCONF, values)."""
    state: dict[str, str] = {"TOOL": "0", "POSTYPE": "ROBOT", "USER": "", "RCONF": "", "FORM": "PULSE"}
    out = {}
    pos = job.split("//POS\n", 1)[1].split("//INST", 1)[0]
    for line in pos.splitlines():
        if m := re.fullmatch(r"///(TOOL|USER|POSTYPE|RCONF) (.*)", line):
            state[m.group(1)] = m.group(2)
        elif line in ("///PULSE", "///RECTAN"):
            state["FORM"] = line[3:]
        elif m := re.fullmatch(r"(C\d{5})=(.*)", line):
            postype, form = state["POSTYPE"], state["FORM"]
            user = int(state["USER"]) if postype == "USER" else None
            out[m.group(1)] = (int(state["TOOL"]), postype, form, user, state["RCONF"] if form == "RECTAN" else "", m.group(2))
    return out


def _moves(job: str) -> list[tuple[str, str]]:
    """(instruction word and its speed, position) of each move, in order."""
    inst = job.split("//INST", 1)[1]
    return [(f"{m.group(1)} {m.group(3)}", m.group(2)) for m in re.finditer(r"(?m)^(MOV[JL]) (C\d{5}) (\S+)", inst)]


def _import_compile(tmp_path: Path, job: str) -> tuple[str, str, str]:
    (tmp_path / "TCPCHK.JBI").write_text(job)
    result = CliRunner().invoke(cli, ["import", str(tmp_path / "TCPCHK.JBI"), "-o", str(tmp_path / "p.rmot")],
                                catch_exceptions=False)
    assert result.exit_code == 0, result.output
    result = CliRunner().invoke(cli, ["compile", str(tmp_path / "p.rmot"), "--target", "inform", "-o", str(tmp_path / "out"),
                                      "--allow-findings", "--no-cache"], catch_exceptions=False)
    compiled = next((p.read_text() for p in (tmp_path / "out" / "inform").glob("*.JBI")), "") \
        if (tmp_path / "out" / "inform").exists() else ""
    return (tmp_path / "p.rmot").read_text(), compiled, result.output


def test_native_moves_go_to_their_positions_with_their_tools_and_frames(tmp_path: Path) -> None:
    program, compiled, output = _import_compile(tmp_path, JOB)
    assert program.count('native inform "C0000') == 3 and "error[" not in output, output  # C00001..C00003's records
    # the validator knows the motion forms rmot writes; the native UNTIL line is the job's own
    assert [f for f in check_inform({"TCPCHK.JBI": compiled}) if "UNTIL IN#(5)=ON" not in f] == []
    source, written = _positions(JOB), _positions(compiled)
    moves_in, moves_out = _moves(JOB), _moves(compiled)
    assert [m for m, _ in moves_in] == [m for m, _ in moves_out]  # the same moves, in order
    for (_, a), (_, b) in zip(moves_in, moves_out):  # the three kept native, and rmot's own after them
        assert written[b] == source[a], (a, b)
    assert len({b for _, b in moves_out[1:4]}) == 3  # each its own position
    assert moves_out[1][1] != "C00003"  # placed first in //POS: renamed (C00003 is one of rmot's own positions)


def test_a_record_rmot_cannot_vouch_for_is_refused_at_the_line(tmp_path: Path) -> None:
    unwritable = "native line names C00001, whose record cannot be written: "
    cases = [
        ("TOOL : tool1; PULSE : -4317,-90930", "TOOL : hammer; PULSE : -4317,-90930",
         unwritable + "its TOOL `hammer` names no tool of robot 'r1' (or flange)"),
        ("PULSE : -4317,-90930,-87249,-44324,-63766,32764", "PULSE : -4317,-90930,-87249,-44324,-63766",
         unwritable + "its PULSE must be six whole encoder counts"),
        ("PULSE : -4317,-90930,", "PULSE : -4317.5,-90930,", unwritable + "its PULSE must be six whole encoder counts"),
        ("TOOL : tool1; PULSE : -4317,-90930", "TOOL : tool1; SPEED : 3; PULSE : -4317,-90930",
         unwritable + "`SPEED : 3` is not one of the items"),
        ("C00001{ TOOL : tool1; PULSE : -4317,-90930,-87249,-44324,-63766,32764 }",
         "C00001{ TOOL : tool1; POSTYPE : ROBOT; RCONF : 0,0; RECTAN : 1,2,3,4,5,nan }",
         unwritable + "its RECTAN must be six finite numbers"),
        ("C00001{ TOOL : tool1; PULSE : -4317,-90930,-87249,-44324,-63766,32764 }",
         "C00001{ TOOL : tool1; POSTYPE : USER; USER : nowhere; RCONF : 0,0; RECTAN : 1,2,3,4,5,6 }",
         unwritable + "its USER `nowhere` names no frame the cell numbers"),
        ('native inform "C00001{', 'native inform "C00009{',
         "native line names C00001, a position of the job it came from with no native position record `C00001{..}`"),
    ]
    for k, (old, new, message) in enumerate(cases):
        folder = tmp_path / str(k)
        folder.mkdir()
        (folder / "TCPCHK.JBI").write_text(JOB)
        CliRunner().invoke(cli, ["import", str(folder / "TCPCHK.JBI"), "-o", str(folder / "p.rmot")])
        text = (folder / "p.rmot").read_text()
        assert old in text, (k, text)
        (folder / "p.rmot").write_text(text.replace(old, new, 1))
        result = CliRunner().invoke(cli, ["compile", str(folder / "p.rmot"), "--target", "inform", "-o", str(folder / "out")])
        assert not (folder / "out" / "inform").exists() and "Traceback" not in result.output
        assert re.search(r"p\.rmot:\d+:\d+: error\[E411\]: inform: " + re.escape(message), result.output), (k, result.output)


def test_two_records_of_one_position_that_differ_are_refused(tmp_path: Path) -> None:
    (tmp_path / "TCPCHK.JBI").write_text(JOB)
    CliRunner().invoke(cli, ["import", str(tmp_path / "TCPCHK.JBI"), "-o", str(tmp_path / "p.rmot")])
    text = (tmp_path / "p.rmot").read_text()
    record = next(line for line in text.splitlines() if 'native inform "C00001{' in line)
    (tmp_path / "p.rmot").write_text(text.replace(record, record + "\n" + record.replace("32764", "32765")))
    result = CliRunner().invoke(cli, ["compile", str(tmp_path / "p.rmot"), "--target", "inform", "-o", str(tmp_path / "out")])
    assert "error[E411]: inform: native line names C00001, whose record cannot be written: two records give C00001 " \
           "different data" in result.output, result.output
