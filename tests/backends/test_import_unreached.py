"""What an unconditional forward jump skips every time, with no line naming a label among it,
never runs: it is read into a proc nothing calls (W552), not kept native; anything the
controller may still reach stays native (backends/readers/jump_spans.py).

The witness is a reachability search over the vendor lines written here, apart from the reader:
each line goes on to the next, a jump also (or, unconditional, only) to its label; `END` stops.
"""

from __future__ import annotations

import re
from pathlib import Path

from click.testing import CliRunner
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from rmot.backends.readers.model import Native, walk
from rmot.compiler.cli import cli
from rmot.compiler.cli.import_read import read_on_robot
from tests.backends.test_import_blocks import INFORM_JOB, POS

# the instruction lines rmot reads into procs nothing calls, per file line
UNREACHED = re.compile(r"_unreached_\d+$")

DAT = """DEFDAT pal
DECL E6POS XP1={X 500.0,Y 0.0,Z 500.0,A 0.0,B 90.0,C 0.0,S 2,T 10,E1 0.0}
DECL E6POS XP2={X 550.0,Y 50.0,Z 450.0,A 0.0,B 90.0,C 0.0,S 2,T 10,E1 0.0}
DECL E6POS XP3={X 600.0,Y 0.0,Z 500.0,A 0.0,B 90.0,C 0.0,S 2,T 10,E1 0.0}
ENDDAT
"""

# a palletizing program's shape: the cycle, then `GOTO FINAL` over the section that keeps its
# teach points (moves nothing runs), then the end
TEACH_SECTION = """DEF pal( )
PTP {A1 0, A2 -90, A3 90, A4 0, A5 0, A6 0}
LIN XP1
$OUT[1]=TRUE
GOTO FINAL
;FOLD teach points
PTP XP2
LIN XP3
$OUT[2]=TRUE
;ENDFOLD
FINAL:
$OUT[3]=TRUE
END
"""


def _reader_unreached(path: Path) -> tuple[set[int], set[int]]:
    """(the lines of statements rmot reads into procs nothing calls, the lines it keeps native
    elsewhere) for one imported file."""
    doc = read_on_robot([str(path)], None, None, None)
    unreached = {s.where.line for r in doc.routines if UNREACHED.search(r.name) for s in walk(r.body)}
    native = {s.where.line for r in doc.routines if not UNREACHED.search(r.name) for s in walk(r.body)
              if isinstance(s, Native)}
    return unreached, native


def _reachable(lines: list[str], always: str, conditional: str, label: str) -> set[int]:
    """The line numbers (1-based) some path from the first line of `lines` reaches (the witness):
    a line matching `always` goes only to its label (group `l`), one matching `conditional` to its
    label or on, `END` nowhere, any other line on; `label` matches a label line (group `l`)."""
    where: dict[str, int] = {}
    for k, text in enumerate(lines):
        m = re.fullmatch(label, text)
        if m:
            where.setdefault(m.group("l"), k)
    seen: set[int] = set()
    todo = [0]
    while todo:
        k = todo.pop()
        if k in seen or k >= len(lines):
            continue
        seen.add(k)
        m = re.match(always, lines[k]) or re.match(conditional, lines[k])
        if m and m.group("l") in where:
            todo.append(where[m.group("l")])
        if lines[k] != "END" and not re.match(always, lines[k]):
            todo.append(k + 1)
    return {k + 1 for k in seen}


def _import(tmp_path: Path, name: str, text: str, extra: dict[str, str] | None = None) -> tuple[str, str]:
    for other, content in (extra or {}).items():
        (tmp_path / other).write_text(content)
    (tmp_path / name).write_text(text)
    out = tmp_path / "imported.rmot"
    result = CliRunner().invoke(cli, ["import", str(tmp_path / name), "-o", str(out)], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    return out.read_text(), result.output


def test_a_krl_teach_section_after_goto_final_is_a_proc_nothing_calls(tmp_path: Path) -> None:
    program, output = _import(tmp_path, "pal.src", TEACH_SECTION, {"pal.dat": DAT})
    proc = program[program.index("proc pal_unreached_7() {"):]
    proc = proc[:proc.index("\n  }\n")]
    assert "move joint XP2" in proc and "move linear XP3" in proc and "set out[2] = on" in proc
    body = program[program.index("\n  }\n"):]
    assert "XP2" not in body and "XP3" not in body and "set out[2]" not in body
    assert "move linear XP1" in body and "set out[3] = on" in body and 'native krl "GOTO FINAL"' in body
    assert "pal.src:5:1: warning[W552]: lines 7-9 never run: `GOTO FINAL` jumps over them" in output
    assert "motion and I/O: 7 imported, 0 kept native (100.0 %)" in output  # the section's lines count as read
    unreached, _ = _reader_unreached(tmp_path / "pal.src")
    reached = _reachable(TEACH_SECTION.splitlines(), r"GOTO (?P<l>\w+)", r"(?!)", r"(?P<l>\w+):")
    assert unreached == {7, 8, 9} and not unreached & reached and {6, 10} - reached == {6, 10}


def test_the_imported_teach_section_checks_and_compiles_without_it(tmp_path: Path) -> None:
    """The proc is checked for names like any proc no task calls; nothing plans or compiles it,
    as the controller runs none of it: the compiled program has the jump and the label only."""
    program, _ = _import(tmp_path, "pal.src", TEACH_SECTION, {"pal.dat": DAT})
    rmot_file = tmp_path / "imported.rmot"
    checked = CliRunner().invoke(cli, ["check", str(rmot_file)], catch_exceptions=False)
    assert checked.exit_code == 0, checked.output
    compiled = CliRunner().invoke(cli, ["compile", str(rmot_file), "--target", "krl", "-o", str(tmp_path / "out")],
                                  catch_exceptions=False)
    assert compiled.exit_code == 0, compiled.output
    src = next((tmp_path / "out").rglob("*.src")).read_text()
    assert "GOTO FINAL" in src and "FINAL:" in src and "$OUT[2]" not in src and "$OUT[3]" in src


def test_what_a_krl_goto_in_a_native_block_skips_stays_native(tmp_path: Path) -> None:
    """The GOTO sits in a SWITCH arm (kept native); `CASE 2` runs the lines after the ENDSWITCH:
    they are reached, so they stay native with the jump's reason."""
    text = ("DEF pal( )\nDECL INT n\nPTP {A1 0, A2 -90, A3 90, A4 0, A5 0, A6 0}\nSWITCH n\nCASE 1\nGOTO skip\n"
            "CASE 2\n$OUT[1]=TRUE\nENDSWITCH\nLIN XP1\nskip:\n$OUT[3]=TRUE\nEND\n")
    program, output = _import(tmp_path, "pal.src", text, {"pal.dat": DAT})
    assert "W552" not in output and "proc" not in program and 'native krl "LIN XP1"' in program


def test_a_teach_section_inside_a_span_kept_native_is_still_a_proc(tmp_path: Path) -> None:
    """A GOTO FINAL in a SWITCH arm keeps native what lies between it and FINAL that runs (LIN
    XP1); the teach section the last GOTO FINAL skips is read once, into the proc, not also kept
    native there."""
    text = ("DEF pal( )\nDECL INT n\nPTP {A1 0, A2 -90, A3 90, A4 0, A5 0, A6 0}\nSWITCH n\nCASE 1\nGOTO FINAL\n"
            "ENDSWITCH\nLIN XP1\nGOTO FINAL\nPTP XP2\nLIN XP3\nFINAL:\n$OUT[3]=TRUE\nEND\n")
    program, output = _import(tmp_path, "pal.src", text, {"pal.dat": DAT})
    assert 'native krl "LIN XP1"' in program and "proc pal_unreached_10() {" in program
    assert 'native krl "PTP XP2"' not in program and 'native krl "LIN XP3"' not in program
    assert "motion and I/O: 4 imported, 1 kept native" in output


def test_a_skipped_span_that_sets_a_variable_stays_native(tmp_path: Path) -> None:
    """A proc sees no task variable: a section that assigns one cannot be a proc (E101)."""
    text = ("DEF pal( )\nDECL INT n\nn = 1\nPTP {A1 0, A2 -90, A3 90, A4 0, A5 0, A6 0}\nGOTO skip\nn = n + 1\n"
            "LIN XP1\nskip:\nIF n == 2 THEN\n$OUT[3]=TRUE\nENDIF\nEND\n")
    program, output = _import(tmp_path, "pal.src", text, {"pal.dat": DAT})
    assert "var n: int" in program, program  # the witness that n is a task variable here
    assert "W552" not in output and 'native krl "LIN XP1"' in program


def test_a_rapid_goto_over_moves_is_a_proc_and_a_conditional_one_is_not(tmp_path: Path) -> None:
    module = ("MODULE G\n  CONST robtarget p1:=[[500,0,500],[0,1,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];\n"
              "  PROC main()\n    MoveJ p1, v100, fine, tool0;\n    GOTO done;\n    MoveL p1, v200, z10, tool0;\n"
              "    SetDO do1, 1;\n    done:\n    SetDO do2, 1;\n  ENDPROC\nENDMODULE\n")
    program, output = _import(tmp_path, "g.mod", module)
    assert ("proc g_unreached_6() {\n    tool flange\n    frame base\n    move linear p1 speed 200 mm/s zone 10 mm\n"
            "    set out[1] = on\n  }") in program
    assert "warning[W552]" in output
    conditional, output = _import(tmp_path, "g.mod", module.replace("GOTO done;", "IF n > 2 GOTO done;").replace(
        "  PROC main", "  VAR num n := 0;\n  PROC main"))
    assert "W552" not in output and "proc" not in conditional and 'native rapid "MoveL p1' in conditional


def test_a_tp_label_named_by_another_line_keeps_the_span_native(tmp_path: Path) -> None:
    """`WAIT .. TIMEOUT,LBL[4]` lands among what `JMP LBL[9]` skips: it runs when the wait times out."""
    lines = ["DO[1]=ON", "$WAITTMOUT=100", "WAIT DI[1]=ON TIMEOUT,LBL[4]", "JMP LBL[9]", "LBL[4]", "DO[2]=ON",
             "LBL[9]", "DO[3]=ON"]
    program, output = _import(tmp_path, "t.ls", _tp(lines))
    assert "W552" not in output and "proc" not in program and 'native fanuc "DO[2]=ON ;"' in program
    assert "`JMP LBL[9]` at line 7 jumps over this every time (it runs only where another jump lands in it" in output


def test_a_computed_tp_label_keeps_every_span_native(tmp_path: Path) -> None:
    """`JMP LBL[R[1]]` may land on any label: nothing is known unreached."""
    lines = ["JMP LBL[9]", "LBL[3]", "DO[2]=ON", "LBL[9]", "DO[3]=ON", "JMP LBL[R[1]]"]
    _, output = _import(tmp_path, "t.ls", _tp(lines))
    assert "W552" not in output
    _, output = _import(tmp_path, "t.ls", _tp(lines[:-1]))
    assert "warning[W552]" in output  # the same program without it


def test_an_inform_jump_over_moves_is_a_proc(tmp_path: Path) -> None:
    job = INFORM_JOB.replace("{body}", "JUMP *ENDE\nMOVL C00001 V=100.0\nDOUT OT#(3) ON\n*ENDE\nDOUT OT#(4) ON")
    program, output = _import(tmp_path, "J1.JBI", job)
    assert "proc J1_unreached_" in program and "warning[W552]" in output
    proc = program[program.index("proc J1_unreached_"):]
    assert "move linear" in proc[:proc.index("}")] and "set out[3] = on" in proc[:proc.index("}")]
    conditional, output = _import(tmp_path, "J1.JBI", job.replace("JUMP *ENDE", "JUMP *ENDE IF I000<>1"))
    assert "W552" not in output and "proc" not in conditional  # I000 decides at run time


def _tp(body: list[str]) -> str:
    lines = "".join(f"{n:4d}:  {text} ;\n" for n, text in enumerate(body, 1))
    return f"/PROG  T\n/ATTR\n/MN\n{lines}{POS}"


# random TP programs: moves, outputs, jumps (unconditional, on an input, on a register, a wait's
# timeout exit), labels and END, with spans an unconditional jump skips to its label
_TP_WORDS = st.sampled_from(["L P[1] 100mm/sec FINE", "DO[1]=ON", "DO[2]=OFF", "JMP LBL[1]", "JMP LBL[2]",
                             "IF DI[1]=ON,JMP LBL[2]", "IF R[1]=1,JMP LBL[3]", "LBL[1]", "LBL[2]", "LBL[3]",
                             "WAIT DI[2]=ON TIMEOUT,LBL[1]", "END"])
_TP_SKIP = st.builds(lambda k, inner: [f"JMP LBL[{k}]", *inner, f"LBL[{k}]"], st.integers(1, 4),
                     st.lists(_TP_WORDS, max_size=4))
_TP_BODY = st.lists(st.one_of(_TP_WORDS.map(lambda w: [w]), _TP_SKIP), min_size=1, max_size=6).map(
    lambda parts: [w for part in parts for w in part])


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(body=_TP_BODY)
def test_nothing_a_tp_path_reaches_is_read_as_unreached(tmp_path: Path, body: list[str]) -> None:
    """Whatever the program, every line rmot reads into a proc nothing calls is one no path from
    the first line reaches (the witness above), and no line is both read so and kept native."""
    (tmp_path / "t.ls").write_text(_tp(["$WAITTMOUT=100", *body]))
    unreached, native = _reader_unreached(tmp_path / "t.ls")
    lines = ["$WAITTMOUT=100", *body]
    reached = {k + 3 for k in _reachable(lines, r"JMP LBL\[(?P<l>\d+)\]",
                                         r"(IF .*,JMP|WAIT .*TIMEOUT,)\s*LBL\[(?P<l>\d+)\]", r"LBL\[(?P<l>\d+)\]")}
    assert not unreached & reached, (body, unreached)  # /MN's first instruction is the file's line 4
    assert not unreached & native


def test_the_arms_of_a_tp_select_are_jumps_a_value_decides(tmp_path: Path) -> None:
    """`SELECT R[1]=1,JMP LBL[10]`, `=2,..`, `ELSE,JMP LBL[99]` (B-83284EN, SELECT): each arm jumps
    as R[1] decides, never every time; what they skip stays native, and none of it is unreached."""
    lines = ["SELECT R[1]=1,JMP LBL[10]", "=2,JMP LBL[20]", "ELSE,JMP LBL[99]", "LBL[10]", "DO[1]=ON", "JMP LBL[99]",
             "LBL[20]", "DO[2]=ON", "LBL[99]", "DO[3]=ON"]
    program, output = _import(tmp_path, "t.ls", _tp(lines))
    assert "`ELSE,JMP LBL[99]` at line 6 jumps over this as a run-time value decides" in output
    assert "every time" not in output and "W552" not in output and "set out[3] = on" in program


RAPID_HANDLER = """MODULE H
  CONST robtarget p1:=[[500,0,500],[0,1,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
  VAR num n := 0;
  PROC main()
    MoveJ p1, v100, fine, tool0;
    n := n + 1;
    WHILE n < 3 DO
      IF n > 2 GOTO skip;
      n := n + 1;
      skip:
    ENDWHILE
    GOTO done;
    MoveL p1, v200, z10, tool0;
  ERROR
    SetDO do1, 1;
    done:
    TRYNEXT;
  ENDPROC
ENDMODULE
"""


def test_rapid_lines_kept_native_keep_their_semicolons_and_a_handler_is_not_unreached(tmp_path: Path) -> None:
    """A RAPID statement ends with `;`; a block's own line, a label and a handler keyword do not
    (ABB Technical reference manual RAPID overview, basic elements). The error handler runs on an
    error, so what the GOTO skips up to it stays native; compiled back, the routine's lines are
    RAPID's."""
    program, output = _import(tmp_path, "h.mod", RAPID_HANDLER)
    assert "W552" not in output
    for line in ['native rapid "ERROR"', 'native rapid "SetDO do1, 1;"', 'native rapid "TRYNEXT;"',
                 'native rapid "IF n > 2 GOTO skip;"', 'native rapid "n := n + 1;"', 'native rapid "skip:"']:
        assert line in program, line
    rmot_file = tmp_path / "imported.rmot"
    compiled = CliRunner().invoke(cli, ["compile", str(rmot_file), "--target", "rapid", "-o", str(tmp_path / "out")],
                                  catch_exceptions=False)
    assert compiled.exit_code == 0, compiled.output
    text = next((tmp_path / "out").rglob("*.mod")).read_text()
    body = text[text.index("PROC main()") + len("PROC main()"):text.index("ENDPROC")]
    statements = [ln.strip() for ln in body.splitlines() if ln.strip() and not ln.strip().startswith("!")]
    unended = [s for s in statements if not s.endswith(";")]
    assert unended == ["WHILE n < 3 DO", "skip:", "ENDWHILE", "ERROR", "done:"], unended


def test_an_unreached_span_inside_a_block_an_outer_span_keeps_is_read_once(tmp_path: Path) -> None:
    """DO[1] never runs (the IF's own `JMP LBL[5]` skips it) and lies in the span the run-time jump
    to LBL[9] keeps native: it is in the proc alone, not also kept native there."""
    lines = ["R[1]=R[1]+1", "IF R[1]<>1,JMP LBL[9]", "IF (DI[1]=ON) THEN", "JMP LBL[5]", "DO[1]=ON", "LBL[5]", "DO[2]=ON",
             "ENDIF", "LBL[9]", "DO[3]=ON"]
    program, output = _import(tmp_path, "t.ls", _tp(lines))
    assert "proc t_unreached_8() {\n    set out[1] = on\n  }" in program and 'native fanuc "DO[1]=ON ;"' not in program
    assert "motion and I/O: 2 imported, 1 kept native" in output
