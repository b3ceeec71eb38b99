"""Blocks and conditions a reader must not flatten. Fanuc TP structured blocks (B-83284EN, "IF ... THEN / ELSE / ENDIF" and "FOR / ENDFOR"):
an I/O condition is read as an rmot `if`; a block on a register or a FOR loop is kept native
whole, because reading its body as straight-line code would plan and verify one run of it as if
it always happened (found in a pendant backup, kamilkozdro/FanucProgramAnalyze `gratowanie.ls`:
`IF (R[1]=1) THEN` around a move and an output)."""

from __future__ import annotations

import re
from pathlib import Path

from click.testing import CliRunner
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from rmot.compiler.cli import cli

POS = """/POS
P[1]{
   GP1:
	UF : 0, UT : 1,		CONFIG : 'N U T, 0, 0, 0',
	X =   500.000  mm,	Y =     0.000  mm,	Z =   500.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[2]{
   GP1:
	UF : 0, UT : 1,		CONFIG : 'N U T, 0, 0, 0',
	X =   500.000  mm,	Y =   100.000  mm,	Z =   400.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
/END
"""


def _import(tmp_path: Path, body: list[str]) -> tuple[str, str]:
    lines = "".join(f"{n:4d}:  {text} ;\n" for n, text in enumerate(body, 1))
    return _read(tmp_path, "blk.ls", f"/PROG  BLK\n/ATTR\n/MN\n{lines}{POS}")


def _read(tmp_path: Path, name: str, text: str) -> tuple[str, str]:
    """The program `rmot import` writes for a file `name` holding `text` (from `program` on), and
    what it prints."""
    path = tmp_path / name
    path.write_text(text)
    out = tmp_path / "imported.rmot"
    result = CliRunner().invoke(cli, ["import", str(path), "-o", str(out)], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    program = out.read_text()
    return program[program.index("program"):], result.output


def test_a_block_on_a_register_is_kept_native_whole(tmp_path: Path) -> None:
    """R[1] is tested before the program sets it: its value comes from an earlier run or another
    program, which no rmot variable or input reading here would say (fanuc_regs.py)."""
    program, output = _import(tmp_path, ["J P[1] 100% FINE", "IF (R[1]=1) THEN", "L P[2] 100mm/sec FINE",
                                         "DO[108]=ON", "R[1]=0", "ENDIF", "J P[1] 100% FINE"])
    assert "move linear" not in program and "set out[108]" not in program
    assert 'native fanuc "L P[2] 100mm/sec FINE ;"' in program and 'native fanuc "ENDIF ;"' in program
    assert program.count("move joint") == 2
    assert "motion and I/O: 2 imported, 2 kept native" in output
    assert "inside `IF (R[1]=1) THEN` at line 5" in output


def test_an_input_block_is_an_if_with_its_else(tmp_path: Path) -> None:
    program, output = _import(tmp_path, ["J P[1] 100% FINE", "IF (DI[3]=ON AND !DI[4]) THEN",
                                         "L P[2] 100mm/sec FINE", "DO[108]=ON", "ELSE", "DO[2]=ON", "ENDIF"])
    assert "W510" not in output
    assert ("  if in[3] == on and in[4] == off {\n    move linear blk_p2 speed 100 mm/s zone fine\n"
            "    set out[108] = on\n  } else {\n    set out[2] = on\n  }\n") in program


def test_a_for_loop_whose_counter_the_body_writes_is_kept_native_whole(tmp_path: Path) -> None:
    program, _ = _import(tmp_path, ["FOR R[1]=1 TO 3", "IF (DI[1]=ON) THEN", "DO[1]=ON", "ENDIF", "R[1]=R[1]+1", "ENDFOR",
                                    "DO[2]=ON"])
    lines = [ln.strip() for ln in program.splitlines() if ln.startswith("  native") or "set out" in ln]
    assert lines == [
        'native fanuc "FOR R[1]=1 TO 3 ;"   # ' + str(tmp_path / "blk.ls") + ":4:4",
        'native fanuc "IF (DI[1]=ON) THEN ;"   # ' + str(tmp_path / "blk.ls") + ":5:4",
        'native fanuc "DO[1]=ON ;"   # ' + str(tmp_path / "blk.ls") + ":6:4",
        'native fanuc "ENDIF ;"   # ' + str(tmp_path / "blk.ls") + ":7:4",
        'native fanuc "R[1]=R[1]+1 ;"   # ' + str(tmp_path / "blk.ls") + ":8:4",
        'native fanuc "ENDFOR ;"   # ' + str(tmp_path / "blk.ls") + ":9:4",
        "set out[2] = on"]


def test_a_for_loop_on_its_own_counter_is_an_rmot_for(tmp_path: Path) -> None:
    """B-83284EN "FOR/ENDFOR": R[4] runs 1, 2, 3 (at most the TO value, one up at ENDFOR); the
    offset register the body builds from it moves the target 20, 40, 60 mm up."""
    program, output = _import(tmp_path, ["PR[5]=LPOS-LPOS", "FOR R[4:k]=1 TO 3", "PR[5,3]=R[4:k]*20",
                                         "J P[1] 50% FINE Offset,PR[5]", "IF (DI[1]=ON) THEN", "DO[1]=ON", "ENDIF",
                                         "ENDFOR", "FOR R[4:k]=0 TO 1", "DO[2]=ON", "ENDFOR", "FOR R[6]=3 DOWNTO 1",
                                         "DO[3]=ON", "ENDFOR", "FOR R[7]=3 TO 1", "DO[4]=ON", "ENDFOR"])
    assert ("  for k in 1 .. 4 {\n" in program and "move joint shift(blk_p1, z=(k * 20) * 1 mm)" in program
            and "    if in[1] == on {\n      set out[1] = on\n    }\n  }\n  for k in 0 .. 2 {\n    set out[2] = on\n  }\n"
            in program)
    assert 'native fanuc "FOR R[6]=3 DOWNTO 1 ;"' in program  # counting down: no rmot for
    assert 'native fanuc "FOR R[7]=3 TO 1 ;"' in program  # runs no time: no rmot for
    assert output.count("W510") == 6


def test_a_block_not_closed_is_read_line_by_line(tmp_path: Path) -> None:
    program, output = _import(tmp_path, ["IF (R[1]=1) THEN", "DO[1]=ON"])
    assert "set out[1] = on" in program and "IF (R[1]=1) THEN" in output


def _rapid(tmp_path: Path, routines: str) -> tuple[str, str]:
    """The program `rmot import` writes for a module M with a target p1 and `routines`."""
    return _read(tmp_path, "m.mod", "MODULE M\n  CONST robtarget p1:=[[500,0,500],[0,1,0,0],[0,0,0,0],"
                 f"[9E9,9E9,9E9,9E9,9E9,9E9]];\n{routines}ENDMODULE\n")


def test_a_rapid_if_on_a_declared_num_is_not_read_as_an_input(tmp_path: Path) -> None:
    """RAPID's `IF sig = 1 THEN` tests a digital input signal, but `IF reg1 = 1 THEN` on a `PERS num
    reg1` the module declares is a test of that data: it must not become `if in[1] == on` with a
    signal named reg1 in the stub cell."""
    program, _ = _rapid(tmp_path, "  PERS num reg1:=0;\n  PROC main()\n    IF reg1 = 1 THEN\n      MoveL p1, v100, fine, tool0;\n"
                              "    ENDIF\n    IF di1 = 1 THEN\n      MoveL p1, v100, fine, tool0;\n    ENDIF\n  ENDPROC\n")
    cell = (tmp_path / "imported_cell.rmot").read_text()
    assert "if reg1 == 1 {" in program and "if in[1] == on {" in program
    assert 'io in[1] = "di1"' in cell and '"reg1"' not in cell


INFORM_JOB = """/JOB
//NAME J1
//POS
///NPOS 2,0,0,0,0,0
///TOOL 0
///POSTYPE ROBOT
///RECTAN
///RCONF 0,0,0,0,0,0,0,0
C00000=500.000,0.000,500.000,180.0000,0.0000,0.0000
C00001=500.000,100.000,500.000,180.0000,0.0000,0.0000
//INST
///DATE 2025/01/01 00:00
///ATTR SC,RW
///GROUP1 RB1
NOP
MOVJ C00000 VJ=50.00
{body}
MOVJ C00000 VJ=50.00
END
"""


def _inform(tmp_path: Path, body: str) -> tuple[str, str]:
    return _read(tmp_path, "J1.JBI", INFORM_JOB.replace("{body}", body))


def test_what_an_inform_jump_on_a_variable_skips_is_kept_native(tmp_path: Path) -> None:
    """`JUMP *SKIP IF I000<>1` over a move and an output: the controller runs them or not as I000
    decides; read as straight-line code they would be planned as always run."""
    program, output = _inform(tmp_path, "JUMP *SKIP IF I000<>1\nMOVL C00001 V=100.0\nDOUT OT#(3) ON\n*SKIP")
    assert "move linear" not in program and "set out[3]" not in program
    assert 'native inform "MOVL C00001 V=100.0"' in program and 'native inform "DOUT OT#(3) ON"' in program
    assert program.count("move joint") == 2
    assert "`JUMP *SKIP IF I000<>1` at line 17 jumps over this" in output


def test_what_an_inform_backward_jump_repeats_is_kept_native(tmp_path: Path) -> None:
    program, output = _inform(tmp_path, "*AGAIN\nMOVL C00001 V=100.0\nJUMP *AGAIN IF I001<5")
    assert "move linear" not in program and "jumps back over this" in output


def test_an_input_jump_is_still_read_as_an_if(tmp_path: Path) -> None:
    program, output = _inform(tmp_path, "JUMP *L1 IF IN#(2)=OFF\nMOVL C00001 V=100.0\n*L1")
    assert "if in[2] == on {" in program and "move linear" in program and "W510" not in output


def test_what_a_tp_jump_on_a_register_skips_is_kept_native(tmp_path: Path) -> None:
    """R[1] counts up from what an earlier run left: no rmot reading of it is certain (fanuc_regs.py)."""
    program, output = _import(tmp_path, ["R[1]=R[1]+1", "DO[1]=ON", "IF R[1]<>1,JMP LBL[2]", "L P[2] 100mm/sec FINE",
                                         "DO[3]=ON", "LBL[2:skip]", "DO[4]=ON"])
    assert "move linear" not in program and "set out[3]" not in program
    assert "set out[1] = on" in program and "set out[4] = on" in program
    assert "motion and I/O: 2 imported, 2 kept native" in output


def test_a_tp_jump_on_one_parenthesised_input_is_an_if(tmp_path: Path) -> None:
    """`IF (DI[7]),JMP LBL[2]` (the pendant's expression form) skips DO[3] when DI[7] is on."""
    program, output = _import(tmp_path, ["IF (DI[7]),JMP LBL[2]", "DO[3]=ON", "LBL[2]"])
    assert "  if in[7] == off {\n    set out[3] = on\n  }\n" in program and "W510" not in output


def test_a_tp_program_that_jumps_back_to_its_first_line_is_one_cycle(tmp_path: Path) -> None:
    """`LBL[1]` .. `JMP LBL[1]`: the controller repeats it forever; rmot reads one cycle (W518), as an
    outermost KRL `LOOP`, while a conditional jump inside still keeps what it skips native."""
    program, output = _import(tmp_path, ["LBL[1]", "DO[3]=ON", "IF TIMER[2]>1,JMP LBL[5]", "DO[4]=ON", "LBL[5]",
                                         "JMP LBL[1]"])
    assert "warning[W518]" in output and "set out[3] = on" in program
    assert 'native fanuc "DO[4]=ON ;"' in program


def test_what_an_unconditional_jump_skips_says_so(tmp_path: Path) -> None:
    """Nothing lands among what it skips: it never runs, and is read into a proc nothing calls
    (test_import_unreached.py has where something may land)."""
    program, output = _import(tmp_path, ["DO[1]=ON", "JMP LBL[9]", "DO[2]=ON", "LBL[9]", "DO[3]=ON"])
    assert "proc blk_unreached_6() {\n    set out[2] = on\n  }" in program and "set out[3] = on" in program
    assert "blk.ls:5:4: warning[W552]: line 6 never runs: `JMP LBL[9]` jumps over it every time" in output


def test_what_a_rapid_goto_skips_is_kept_native(tmp_path: Path) -> None:
    program, output = _read(tmp_path, "g.mod", "MODULE G\n  CONST robtarget p1:=[[500,0,500],[0,1,0,0],[0,0,0,0],"
                            "[9E9,9E9,9E9,9E9,9E9,9E9]];\n  VAR num n:=0;\n  PROC main()\n    IF n > 2 GOTO skip;\n"
                            "    MoveL p1, v100, fine, tool0;\n    skip:\n    SetDO do1, 1;\n  ENDPROC\nENDMODULE\n")
    assert "move linear" not in program and 'native rapid "MoveL p1, v100, fine, tool0;"' in program
    assert "`IF n > 2 GOTO skip` at line 5 jumps over this" in output


def test_what_a_krl_goto_skips_is_kept_native(tmp_path: Path) -> None:
    program, _ = _read(tmp_path, "g.src", "DEF g()\n  DECL INT n\n  IF n > 2 THEN\n    GOTO skip\n  ENDIF\n"
                       "  LIN {X 500, Y 0, Z 500, A 0, B 90, C 0}\n  skip:\n  $OUT[1] = TRUE\nEND\n")
    assert "move linear" not in program and 'native krl "LIN {X 500, Y 0, Z 500, A 0, B 90, C 0}"' in program
    assert "set out[1] = on" in program


def test_a_rapid_label_is_a_statement_of_its_own(tmp_path: Path) -> None:
    """`skip:     SetDO do1, 1;` and `back:` on a line of its own (RAPID Technical reference manual,
    labels): the instruction after a label is read, the label stays native where GOTOs find it."""
    program, _ = _rapid(tmp_path, "  PROC main()\n    IF DInput(di1) = 1 GOTO skip;\n    SetDO do2, 1;\n"
                              "    skip:     SetDO do3, 1;\n    back:\n    MoveL p1, v100, fine, tool0;\n    x := 1;\n"
                              "  ENDPROC\n")
    assert 'native rapid "SetDO do2, 1;"' in program  # what the GOTO skips
    assert 'native rapid "skip:"' in program and 'native rapid "back:"' in program
    assert "  set out[3] = on\n" in program and "  move linear p1 speed 100 mm/s zone fine\n" in program
    assert 'native rapid "x := 1;"' in program  # an assignment, not a label
    test, _ = _rapid(tmp_path, "  VAR num n := 1;\n  PROC main()\n    n := 2;\n    TEST n\n    CASE 1:\n      SetDO do1, 1;\n"
                               "    DEFAULT:  SetDO do2, 1;\n    ENDTEST\n  ENDPROC\n")
    assert "  if n == 1 {\n    set out[1] = on\n  } else {\n    set out[2] = on\n  }\n" in test  # DEFAULT: no label


def test_a_tp_counting_loop_whose_counter_is_not_its_own_stays_native(tmp_path: Path) -> None:
    """`R[1]=1`, `LBL[1]`, .., `R[1]=R[1]+1`, `IF R[1]<=4,JMP LBL[1]` is rmot's `for` only where
    nothing else uses R[1]: a second increment in the body (the controller runs 2 iterations, not
    4), a jump into the loop, or a read after it (the value the loop left) keep it native."""
    loop = ["R[1]=1", "LBL[1]", "DO[1]=ON", "R[1]=R[1]+1", "IF R[1]<=4,JMP LBL[1]"]
    read, _ = _import(tmp_path, loop)
    assert "for r1 in 1 .. 5 {\n    set out[1] = on\n  }" in read and "var " not in read  # the counter is the for's
    for body in (loop[:3] + ["R[1]=R[1]+1"] + loop[3:], loop + ["IF R[1]=5,JMP LBL[1]"], loop + ["IF (R[1]=5) THEN",
                                                                                                   "DO[2]=ON", "ENDIF"]):
        program, _ = _import(tmp_path, body)
        assert "for r1" not in program and 'native fanuc "DO[1]=ON ;"' in program, body
    again, _ = _import(tmp_path, loop + ["R[1]=1", "LBL[2]", "DO[3]=ON", "R[1]=R[1]+1", "IF R[1]<=2,JMP LBL[2]"])
    assert again.count("for r1 in") == 2  # the counter counting a second loop is still each loop's own


def test_an_inform_counting_loop_whose_counter_is_not_its_own_stays_native(tmp_path: Path) -> None:
    read, _ = _inform(tmp_path, "SET D001 1\n*L1\nDOUT OT#(3) ON\nINC D001\nJUMP *L1 IF D001<=3")
    assert "for d001 in 1 .. 4 {" in read
    program, _ = _inform(tmp_path, "SET D001 1\n*L1\nDOUT OT#(3) ON\nINC D001\nINC D001\nJUMP *L1 IF D001<=3")
    assert "for d001" not in program and 'native inform "DOUT OT#(3) ON"' in program


def _lines_read(program: str) -> list[str]:
    """Each `set out[n]` / native DO line of the program, in order, as `DO[n]`."""
    found = re.findall(r'^\s*(?:set out\[(\d+)\] = on|native fanuc "DO\[(\d+)\]=ON ;")', program, re.M)
    return [f"DO[{a or b}]" for a, b in found]


def test_overlapping_jump_spans_keep_each_instruction_once(tmp_path: Path) -> None:
    """The second jump sits inside the first one's span and reaches past it: kept in a later
    pass, every instruction stays exactly once and in order."""
    program, _ = _import(tmp_path, ["IF TIMER[1]>1,JMP LBL[1]", "IF TIMER[2]>1,JMP LBL[2]", "IF (DI[1]=ON) THEN",
                                    "DO[1]=ON", "ENDIF", "LBL[1]", "DO[3]=ON", "LBL[2]", "DO[4]=ON"])
    assert _lines_read(program) == ["DO[1]", "DO[3]", "DO[4]"]  # the IF block's lines once
    assert 'native fanuc "DO[3]=ON ;"' in program and "  set out[4] = on\n" in program


def test_a_jump_to_a_label_inside_a_block_waits_for_the_block_to_be_kept(tmp_path: Path) -> None:
    """LBL[2] is inside an IF the first jump's span keeps native: the backward jump to it then
    repeats only what lies between them, and DO[9] after it is read (not everything to the end)."""
    program, _ = _import(tmp_path, ["IF TIMER[1]>1,JMP LBL[1]", "IF (DI[1]=ON) THEN", "DO[1]=ON", "LBL[2]", "DO[2]=ON",
                                    "ENDIF", "LBL[1]", "DO[3]=ON", "IF TIMER[2]>1,JMP LBL[2]", "DO[9]=ON"])
    assert 'native fanuc "DO[3]=ON ;"' in program and "  set out[9] = on\n" in program
    assert _lines_read(program) == ["DO[1]", "DO[2]", "DO[3]", "DO[9]"]


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.lists(st.tuples(st.integers(0, 11), st.integers(1, 4), st.booleans()), min_size=1, max_size=5))
def test_jump_spans_keep_every_instruction_once_in_order(tmp_path: Path, jumps: list[tuple[int, int, bool]]) -> None:
    """Random jumps (conditional or not, forward or back) among 12 outputs and 4 labels: each
    output is read or kept once, in order (the main body, and apart each proc of what never runs)."""
    body = [f"DO[{k + 1}]=ON" for k in range(12)]
    for n, at in enumerate((3, 6, 9, 11), 1):
        body.insert(at + n - 1, f"LBL[{n}]")
    for at, label, conditional in sorted(jumps, reverse=True):
        body.insert(at, f"IF TIMER[1]>1,JMP LBL[{label}]" if conditional else f"JMP LBL[{label}]")
    program, _ = _import(tmp_path, body)
    procs = re.findall(r"  proc \w+_unreached_\d+\(\) \{\n.*?\n  \}\n", program, re.S)  # what never runs (W552)
    main = re.sub(r"  proc \w+_unreached_\d+\(\) \{\n.*?\n  \}\n", "", program, flags=re.S)
    parts = [_lines_read(main), *(_lines_read(p) for p in procs)]
    assert all(part == sorted(part, key=lambda d: int(d[3:-1])) for part in parts), body  # each in order
    assert sorted(sum(parts, []), key=lambda d: int(d[3:-1])) == [f"DO[{k + 1}]" for k in range(12)], body  # once


def test_a_krl_goto_out_of_a_loop_keeps_the_loop_and_what_it_skips_native(tmp_path: Path) -> None:
    """`GOTO skip` inside an IF inside a WHILE leaves both: which of the loop's lines run, and
    whether `$OUT[4]` after it does, is known only at run time. Read as rmot's while, `set out[2]`
    would be planned on every pass and `set out[4]` always."""
    program, output = _read(tmp_path, "n.src", "DEF n()\n  DECL INT n\n  n = 0\n  WHILE n < 3\n    n = n + 1\n"
                            "    IF $IN[1] THEN\n      GOTO skip\n    ENDIF\n    $OUT[2] = TRUE\n  ENDWHILE\n"
                            "  $OUT[4] = TRUE\n  skip:\n  $OUT[3] = TRUE\nEND\n")
    assert "while" not in program and 'native krl "$OUT[2] = TRUE"' in program and 'native krl "WHILE n < 3"' in program
    assert 'native krl "$OUT[4] = TRUE"' in program and "  set out[3] = on\n" in program
    assert "`GOTO skip` at line 7 inside this block jumps out of it" in output
    assert "`GOTO skip` at line 7 jumps over this as a run-time value decides" in output


def test_a_tp_jump_out_of_an_if_block_keeps_what_it_skips_native(tmp_path: Path) -> None:
    """The jump ends an inner IF's arm: its label is outside the outer IF, whose lines then run
    as DI[2] decides; the whole block and DO[2] after it are native."""
    program, output = _import(tmp_path, ["IF (DI[1]=ON) THEN", "IF (DI[2]=ON) THEN", "JMP LBL[5]", "ENDIF", "DO[4]=ON",
                                         "ENDIF", "DO[2]=ON", "LBL[5]", "DO[3]=ON"])
    assert 'native fanuc "DO[2]=ON ;"' in program and 'native fanuc "DO[4]=ON ;"' in program and "if in[" not in program
    assert "set out[3] = on" in program and "W552" not in output
    assert "`JMP LBL[5]` at line 6 jumps over this as a run-time value decides" in output


def test_a_tp_jump_ending_an_if_arm_makes_what_it_skips_the_else(tmp_path: Path) -> None:
    program, output = _import(tmp_path, ["IF (DI[1]=ON) THEN", "JMP LBL[5]", "ENDIF", "DO[2]=ON", "LBL[5]", "DO[3]=ON"])
    assert "  if not in[1] == on {\n    set out[2] = on\n  }\n" in program and "set out[3] = on" in program
    assert "JMP" not in program and "JMP" not in output  # the jump is the if's structure: no W510 for it
