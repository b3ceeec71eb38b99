"""Vendor forms a reader once read silently wrong: each is now read exactly or kept native.

Witnesses: INFORM if-chains (`JUMP *L IF IN#(n)=X` to one label, or to a label past the other
tests, as backends/inform.py writes `and` and `or`) are run by a small INFORM interpreter
written here from the language's rules (DX100/YRC1000 INFORM manual, JUMP: the job continues at
the label when the condition holds; labels `*L`), for every level of the inputs, against a
separate evaluation of the condition the import reads.
"""

from __future__ import annotations

import itertools
import json
import math
import re
from collections.abc import Callable
from pathlib import Path

import pytest
from click.testing import CliRunner

from krl_imported import imported_krl

from rmot.backends.readers import read_files
from rmot.backends.readers.model import Cond, Conds, GroupIn, If, Native, SetOut, walk
from rmot.compiler.cli import cli

_JOB_HEAD = ("/JOB\n//NAME CHAIN\n//POS\n///NPOS 0,0,0,0,0,0\n//INST\n///DATE 2020/11/19 13:27\n"
             "///ATTR SC,RW\n///GROUP1 RB1\nNOP\n")


def _job(lines: list[str], tmp_path: Path) -> str:
    path = tmp_path / "CHAIN.JBI"
    path.write_text(_JOB_HEAD + "\n".join(lines) + "\nEND\n")
    return str(path)


# a vendor's jumps, as its manual gives them: (a label line, a conditional jump (named groups n,
# op, level, label) and whether it jumps at the input's level and that operator, a jump, an
# output set on (group: its number))
Grammar = tuple[str, str, Callable[[bool, str, str], bool], str, str]
# INFORM (DX100/YRC1000 INFORM manual, JUMP: `JUMP *L IF IN#(n)=X` jumps when the input is at X)
INFORM = (r"\*L\w+", r"JUMP (?P<label>\*L\w+) IF IN#\((?P<n>\d+)\)(?P<op>=)(?P<level>ON|OFF)", lambda on, op, level: on == (level == "ON"),
          r"JUMP (\*L\w+)", r"DOUT OT#\((\d+)\) ON")
# TP (B-83284EN, IF ..,JMP LBL[n]: the program continues at the label when the comparison holds)
TP = (r"LBL\[\d+\]", r"IF DI\[(?P<n>\d+)\](?P<op>=|<>)(?P<level>ON|OFF),JMP (?P<label>LBL\[\d+\])",
      lambda on, op, level: (on == (level == "ON")) == (op == "="), r"JMP (LBL\[\d+\])", r"DO\[(\d+)\]=ON")


def _runs(lines: list[str], inputs: dict[int, bool], grammar: Grammar = INFORM) -> list[str]:
    """The outputs a program's lines set, in order, with inputs at the given levels."""
    label, cond_jump, jumps_when, jump, out = grammar
    labels = {ln: k for k, ln in enumerate(lines) if re.fullmatch(label, ln)}
    k, done = 0, []
    while k < len(lines):
        ln, k = lines[k], k + 1
        if m := re.fullmatch(cond_jump, ln):
            k = labels[m["label"]] if jumps_when(inputs[int(m["n"])], m["op"], m["level"]) else k
        elif m := re.fullmatch(jump, ln):
            k = labels[m.group(1)]
        elif m := re.fullmatch(out, ln):
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
    _read_as_the_program_runs(_job(lines, tmp_path), lambda inputs: _runs(lines, inputs))


def _read_as_the_program_runs(path: str, runs: Callable[[dict[int, bool]], list[str]]) -> None:
    """The file reads as one `if` whose arms set the outputs the program sets, inputs 1..3 at every level."""
    doc = read_files([path])
    body = doc.routines[0].body
    assert not [d for d in doc.diagnostics if d.code.id == "W510"], doc.diagnostics
    assert len(body) == 1 and isinstance(body[0], If), body
    for levels in itertools.product((False, True), repeat=3):
        inputs = dict(enumerate(levels, 1))
        assert _imported_runs(body[0], inputs) == runs(inputs), (inputs, body[0].cond)


def test_a_chain_whose_label_another_line_jumps_to_stays_native(tmp_path: Path) -> None:
    lines = ["JUMP *L4 IF IN#(1)=ON", "JUMP *L4 IF IN#(2)=ON", "DOUT OT#(5) ON", "*L4", "DOUT OT#(6) ON",
             "JUMP *L4 IF IN#(3)=ON"]
    doc = read_files([_job(lines, tmp_path)])
    natives = [s.text for s in walk(doc.routines[0].body) if isinstance(s, Native)]
    assert not [s for s in walk(doc.routines[0].body) if isinstance(s, If)]
    # the outputs too: the native jumps skip DOUT OT#(5) and repeat DOUT OT#(6) as the inputs decide
    assert natives == lines, natives


def _tp(lines: list[str], tmp_path: Path) -> str:
    path = tmp_path / "CHAIN.LS"
    path.write_text("/PROG  CHAIN\n/ATTR\n/MN\n" + "".join(f"  {k}:  {ln} ;\n" for k, ln in enumerate(lines, 1))
                    + "/POS\n/END\n")
    return str(path)


@pytest.mark.parametrize("lines", [
    ["IF DI[1]=ON,JMP LBL[4]", "IF DI[2]<>OFF,JMP LBL[4]", "DO[5]=ON", "LBL[4]"],
    ["IF DI[1]<>ON,JMP LBL[1]", "IF DI[2]=ON,JMP LBL[1]", "IF DI[3]=OFF,JMP LBL[1]", "DO[5]=ON",
     "JMP LBL[2]", "LBL[1]", "DO[6]=ON", "LBL[2]"],
    ["IF DI[1]=ON,JMP LBL[7]", "IF DI[2]<>ON,JMP LBL[8]", "LBL[7]", "DO[5]=ON", "LBL[8]"],
])
def test_a_tp_jump_chain_reads_as_one_condition(lines: list[str], tmp_path: Path) -> None:
    _read_as_the_program_runs(_tp(lines, tmp_path), lambda inputs: _runs(lines, inputs, TP))


def test_a_tp_chain_whose_label_another_line_jumps_to_stays_native(tmp_path: Path) -> None:
    lines = ["IF DI[1]=ON,JMP LBL[4]", "DO[5]=ON", "LBL[4]", "DO[6]=ON", "IF DI[3]=ON,JMP LBL[4]"]
    doc = read_files([_tp(lines, tmp_path)])
    assert not [s for s in walk(doc.routines[0].body) if isinstance(s, If)]
    natives = [s.text for s in walk(doc.routines[0].body) if isinstance(s, Native)]
    assert natives == [f"{ln} ;" for ln in lines], natives  # the outputs the native jumps skip and repeat too


# KRL work copies: KSS 8.x Operating and Programming Instructions for System Integrators, data
# lists: a variable declared in the module's .dat is the module's (every routine of it reads and
# writes the same one), so a called routine may change it; a label is where a GOTO lands.
_KRL_DAT = """DEFDAT cell
DECL E6POS XP1={X 500.0,Y 100.0,Z 300.0,A 0.0,B 90.0,C 0.0,S 2,T 0}
DECL E6POS PG={X 1.0,Y 2.0,Z 3.0,A 0.0,B 0.0,C 0.0,S 2,T 0}
DECL INT I
ENDDAT
"""


def _krl_moves(tmp_path: Path, body: str) -> tuple[list[str], str]:
    """The moves of the imported main routine (`move` or kept native) and what the import printed."""
    src = f"DEF cell( )\n$VEL.CP = 0.2\n{body}END\n\nDEF Shift( )\nPG.Y = 0\nEND\n"
    printed, rmot = imported_krl(tmp_path, "cell", src, _KRL_DAT)
    return [ln.strip() for ln in rmot.splitlines() if ln.strip().startswith(("move ", "native krl \"LIN"))], printed


@pytest.mark.parametrize(("body", "why"), [
    ("PG = XP1\nShift()\nLIN PG\n", "known before `Shift(..)` at line 4"),
    ("PG = XP1\nnext:\nLIN PG\n", "the label at line 4"),
    ("PG = XP1\nPG.Y = $POS_ACT.Y\nLIN PG\n", "assigned at line 4"),
    ("PG = XP1\nIF $IN[1] THEN\nPG = $POS_ACT\nENDIF\nLIN PG\n", "assigned at line 5"),
    ("PG = XP1\nFOR I = 1 TO 3\nPG.X = XP1.X + I * 10\nShift()\nLIN PG\nENDFOR\n", "assigned inside the block at line 4"),
    ("PG = XP1\nIF $IN[1] THEN\nPG.X = XP1.X + 5\nENDIF\nLIN PG\n", "assigned inside the block at line 4"),
    ("PG = XP1\nFOR I = 1 TO 3\nLIN PG\nPG.X = XP1.X + I * 10\nENDFOR\n", "assigned inside the block at line 4"),
    ("PG = XP1\nFOR I = 1 TO 3\nPG.X = XP1.X + I * 10\nENDFOR\nLIN PG\n", "assigned inside the block at line 4"),
    ("PG = XP1\nPG.X = XP1.X + Offset(3)\nLIN PG\n", "assigned at line 4"),
    ("IF $IN[1] THEN\nPG = XP1\nELSE\nLIN PG\nENDIF\n", "assigned inside the block at line 3"),
    ("FOR I = 1 TO 3\nLIN PG\nPG = XP1\nENDFOR\n", "assigned inside the block at line 3"),
])
def test_a_krl_work_copy_a_line_may_change_is_not_its_target(body: str, why: str, tmp_path: Path) -> None:
    moves, printed = _krl_moves(tmp_path, body)
    assert not [m for m in moves if "XP1" in m], moves
    assert moves and moves[-1].startswith('native krl "LIN PG"'), moves
    warned = [ln for ln in printed.splitlines() if "warning[W510]" in ln and "LIN PG" in ln]
    assert len(warned) == 1 and why in warned[0], printed


@pytest.mark.parametrize("body", [
    "PG = XP1\nFOR I = 1 TO 3\nPG.X = XP1.X + I * 10\nLIN PG\nENDFOR\n",
    # the KRL backend's form: the copy made afresh in the loop, right before its moves
    "FOR I = 1 TO 3\nShift()\nPG = XP1\nPG.X = XP1.X + I * 10\nLIN PG\nPG = XP1\nPG.X = XP1.X + I * 5\nLIN PG\n"
    "ENDFOR\nShift()\n",
])
def test_a_krl_work_copy_reads_as_its_shift_while_nothing_changes_it(body: str, tmp_path: Path) -> None:
    moves, _ = _krl_moves(tmp_path, body)
    assert moves and all(m.startswith("move linear shift(XP1, x=") for m in moves), moves


@pytest.mark.parametrize(("name", "said"), [
    ("xInsideWall[1]", "`xInsideWall[1]` is an array element, and an rmot name has no index: written as `xInsideWall_1_`"),
    ("fixture", "`fixture` must not be an rmot keyword"),
])
def test_a_renamed_krl_name_says_why(name: str, said: str, tmp_path: Path) -> None:
    """The KRL array element `xInsideWall[1]` (khrzysio Sub_Drill's form) and a keyword; `fixture`
    is rmot's keyword (lang/REFERENCE.md), the bracket KRL's array index (KSS 8.x, arrays)."""
    dat = (f"DEFDAT wall\nDECL E6POS {name.split('[')[0]}{'[2]' if '[' in name else ''}\n"
           f"{'' if '[' in name else 'DECL E6POS '}{name}={{X 800.0,Y -200.0,Z 150.0,A 30.0,B 0.0,C 180.0,S 2,T 10}}\n"
           "ENDDAT\n")
    printed, rmot = imported_krl(tmp_path, "wall", f"DEF wall( )\n$VEL.CP = 0.2\nLIN {name}\nEND\n", dat)
    warned = [ln for ln in printed.splitlines() if "warning[W514]" in ln]
    assert len(warned) == 1 and said in warned[0], printed
    assert "move linear" in rmot, rmot


_TP_JOINTS = ((10.0, 20.0, -15.0, 30.0, -40.0, 50.0), (15.0, 25.0, -10.0, 25.0, -45.0, 55.0))


def _tp_joint_form(tmp_path: Path) -> Path:
    """A TP program whose positions are stored in joint form (`J1= .. deg`, R-30iB Operator's
    Manual, position data), the second reached by a linear move with tool 1 (named `torch`)."""
    points = "".join(f"P[{n}]{{\n   GP1:\n\tUF : 0, UT : 1,\n\t" + ",\t".join(
        f"J{k}= {v:.3f} deg" for k, v in enumerate(q, 1)) + "\n};\n" for n, q in enumerate(_TP_JOINTS, 1))
    path = tmp_path / "JFORM.LS"
    path.write_text("/PROG  JFORM\n/ATTR\n/MN\n   1:  ! UTOOL[1] = torch ;\n   2:  UTOOL_NUM=1 ;\n"
                    "   3:  J P[1] 30% FINE ;\n   4:  L P[2] 100mm/sec FINE ;\n/POS\n" + points + "/END\n")
    return path


def test_a_tp_linear_move_to_a_joint_form_position_without_a_cell_stays_native(tmp_path: Path) -> None:
    out = tmp_path / "jform.rmot"
    result = CliRunner().invoke(cli, ["import", str(_tp_joint_form(tmp_path)), "-o", str(out)])
    assert result.exit_code == 0, result.output
    assert 'native fanuc "L P[2] 100mm/sec FINE ;"' in out.read_text() and "move linear" not in out.read_text()
    assert "JFORM.LS:7:4: warning[W510]: jform_p2 is stored in joint form" in result.output, result.output


def test_a_tp_linear_move_to_a_joint_form_position_goes_to_its_tcp_pose(tmp_path: Path) -> None:
    """With --cell (the arm and the program's tool), L P[2] goes to the TCP pose of P[2]'s joints:
    the arm's forward kinematics times the tool's TCP. Witness: the planner's own IK ends the
    imported linear move at P[2]'s joints (its JSON plan's q_target, to 0.001 deg)."""
    cell = tmp_path / "cell.rmot"
    cell.write_text("cell fk_cell {\n  robot r1 = fanuc_lrmate200ib\n  tool torch = none tcp pose(x=0mm, y=0mm, "
                    "z=150mm, q=(1, 0, 0, 0)) mass 1 kg on r1\n}\n")
    out = tmp_path / "jform.rmot"
    result = CliRunner().invoke(cli, ["import", str(_tp_joint_form(tmp_path)), "-o", str(out), "--cell", str(cell)])
    assert result.exit_code == 0 and "0 kept native" in result.output, result.output
    assert "move linear jform_p2_tcp speed 100 mm/s" in out.read_text(), out.read_text()
    result = CliRunner().invoke(cli, ["compile", str(out), "--cell", str(cell), "--target", "json", "-o",
                                      str(tmp_path / "plan"), "--allow-findings"])
    assert result.exit_code in (0, 1), result.output
    plan = json.loads(next((tmp_path / "plan" / "json").glob("*.json")).read_text())
    moves = [i for i in plan["tasks"][0]["instructions"] if "q_target" in i]
    assert [i["kind"] for i in moves] == ["move_joint", "move_linear"], moves
    assert all(abs(math.degrees(got) - want) < 1e-3 for got, want in zip(moves[1]["q_target"], _TP_JOINTS[1], strict=True))
