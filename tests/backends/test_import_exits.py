"""A line that leaves the routine (RAPID RETURN/RAISE, KRL RETURN, TP END, INFORM RET) or jumps
forward inside a block the readers read: what it skips is never read as always run
(backends/readers/jump_spans.py). Where an if's arm ends in it, the lines it skips are the
if's other arm (`IF stop THEN .. RETURN ENDIF` rest = `if stop { .. } else { rest }`); else the
block, and what follows it, stay native.

The witness is an interpreter of the KRL lines written here, apart from the reader: for every
state of the inputs, the outputs a routine sets, in order, are those its reading sets.
"""

from __future__ import annotations

import itertools
import re
from pathlib import Path

from click.testing import CliRunner
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from rmot.backends.readers.model import Cond, Conds, If, Native, SetOut, Stmt, Stop, walk
from rmot.compiler.cli import cli
from rmot.compiler.cli.import_read import read_on_robot
from tests.backends.test_import_blocks import INFORM_JOB, POS


def _import(tmp_path: Path, name: str, text: str) -> tuple[str, str]:
    (tmp_path / name).write_text(text)
    out = tmp_path / "imported.rmot"
    result = CliRunner().invoke(cli, ["import", str(tmp_path / name), "-o", str(out)], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    program = out.read_text()
    return program[program.index("program"):], result.output


def _tp(body: list[str]) -> str:
    lines = "".join(f"{n:4d}:  {text} ;\n" for n, text in enumerate(body, 1))
    return f"/PROG  T\n/ATTR\n/MN\n{lines}{POS}"


def test_a_krl_return_guard_is_the_if_else_it_is(tmp_path: Path) -> None:
    """HugoDanielson's milling jobs: `IF NOT spindle_still THEN .. RETURN ENDIF`, then the cut."""
    program, output = _import(tmp_path, "k.src", "DEF k()\n  s()\nEND\nDEF s()\n  IF $IN[1] THEN\n    $OUT[1] = TRUE\n"
                              "    RETURN\n  ENDIF\n  $OUT[2] = TRUE\n  LIN {X 500, Y 0, Z 500, A 0, B 90, C 0}\nEND\n")
    assert "    if in[1] == on {\n      set out[1] = on\n    } else {\n      set out[2] = on\n      move linear" in program
    assert "W510" not in output and "motion and I/O: 3 imported, 0 kept native" in output


def test_a_guard_with_nothing_before_the_return_is_a_negated_if(tmp_path: Path) -> None:
    program, _ = _import(tmp_path, "k.src", "DEF k()\n  s()\nEND\nDEF s()\n  IF $IN[1] THEN\n    RETURN\n  ENDIF\n"
                         "  $OUT[2] = TRUE\nEND\n")
    assert "    if not in[1] == on {\n      set out[2] = on\n    }\n" in program


def test_a_return_inside_a_loop_keeps_the_loop_and_the_rest_native(tmp_path: Path) -> None:
    """The loop's end is not the routine's: which passes run, and whether `$OUT[3]` does, is run time."""
    program, output = _import(tmp_path, "k.src", "DEF k()\n  s()\nEND\nDEF s()\n  WHILE $IN[2]\n    IF $IN[1] THEN\n"
                              "      RETURN\n    ENDIF\n    $OUT[2] = TRUE\n  ENDWHILE\n  $OUT[3] = TRUE\nEND\n")
    assert "while" not in program and 'native krl "$OUT[2] = TRUE"' in program and 'native krl "$OUT[3] = TRUE"' in program
    assert "`RETURN` at line 7 inside this block leaves the routine" in output
    assert "`RETURN` at line 7 leaves the routine before this as a run-time value decides" in output


def test_a_rapid_raise_keeps_what_follows_native(tmp_path: Path) -> None:
    module = ("MODULE R\n  PROC main()\n    sub;\n  ENDPROC\n  PROC sub()\n    IF DInput(di1) = 1 THEN\n      RETURN;\n"
              "    ENDIF\n    SetDO do2, 1;\n    IF DInput(di2) = 1 RAISE 1;\n    SetDO do3, 1;\n  ENDPROC\nENDMODULE\n")
    program, output = _import(tmp_path, "r.mod", module)
    assert "if not in[1] == on {\n      set out[2] = on\n" in program
    assert 'native rapid "SetDO do3, 1;"' in program and "set out[3]" not in program
    assert "`IF DInput(di2) = 1 RAISE 1` at line 10 leaves the routine before this as a run-time value" in output


def test_a_tp_end_inside_an_if_block_is_its_else(tmp_path: Path) -> None:
    program, output = _import(tmp_path, "t.ls", _tp(["IF (DI[1]=ON) THEN", "DO[1]=ON", "END", "ENDIF", "DO[2]=ON"]))
    assert "  if in[1] == on {\n    set out[1] = on\n  } else {\n    set out[2] = on\n  }\n" in program
    assert "W510" not in output


def test_an_inform_conditional_return_keeps_what_follows_native(tmp_path: Path) -> None:
    program, output = _import(tmp_path, "J1.JBI", INFORM_JOB.replace("{body}", "RET IF IN#(1)=ON\nDOUT OT#(2) ON"))
    assert 'native inform "DOUT OT#(2) ON"' in program and "set out[2]" not in program
    assert "`RET IF IN#(1)=ON` at line 17 leaves the routine before this as a run-time value decides" in output


# random KRL routines: outputs and IF blocks on inputs whose arms may end in RETURN or `GOTO done`,
# then the label `done:` and more outputs
_OUT = st.integers(1, 6).map(lambda k: [f"$OUT[{k}] = TRUE"])
_ARM = st.tuples(st.lists(_OUT, max_size=2), st.sampled_from(["", "RETURN", "GOTO done"])).map(
    lambda a: [ln for part in a[0] for ln in part] + ([a[1]] if a[1] else []))
_IF = st.tuples(st.integers(1, 3), _ARM, st.one_of(st.none(), _ARM)).map(
    lambda t: [f"IF $IN[{t[0]}] THEN", *t[1], *(["ELSE", *t[2]] if t[2] is not None else []), "ENDIF"])
_ROUTINE = st.tuples(st.lists(st.one_of(_OUT, _IF), min_size=1, max_size=5), st.lists(_OUT, max_size=2)).map(
    lambda t: [ln for part in t[0] for ln in part] + ["done:"] + [ln for part in t[1] for ln in part])


def _run_krl(lines: list[str], inputs: dict[int, bool]) -> list[int]:
    """The outputs the KRL lines set, in order, with `inputs` (the witness)."""
    ends: dict[int, int] = {}  # each IF's and ELSE's ENDIF
    elses: dict[int, int] = {}
    stack: list[int] = []
    for k, ln in enumerate(lines):
        if ln.startswith("IF "):
            stack.append(k)
        elif ln == "ELSE":
            elses[stack[-1]] = k
        elif ln == "ENDIF":
            start = stack.pop()
            ends[start] = k
            if start in elses:
                ends[elses[start]] = k
    label = next((k for k, ln in enumerate(lines) if ln == "done:"), None)
    outs, pc = [], 0
    while pc < len(lines):
        ln = lines[pc]
        if ln.startswith("$OUT["):
            outs.append(int(ln[5:ln.index("]")]))
        elif ln.startswith("IF ") and not inputs[int(ln[7:ln.index("]")])]:
            pc = elses.get(pc, ends[pc])
        elif ln == "ELSE":
            pc = ends[pc]
        elif ln == "RETURN" or (ln == "GOTO done" and label is None):
            break
        elif ln == "GOTO done":
            pc = label
        pc += 1
    return outs


def _run_read(body: tuple[Stmt, ...], inputs: dict[int, bool], outs: list[int]) -> bool:
    """The outputs the read statements set (appended to `outs`); whether a stop ended them."""
    for s in body:
        if isinstance(s, SetOut):
            outs.append(int(s.signal))
        elif isinstance(s, Stop):
            return True
        elif isinstance(s, If):
            if _run_read(s.then if _holds(s.cond, inputs) else s.orelse, inputs, outs):
                return True
        else:
            assert isinstance(s, Native) and re.fullmatch(r"\w+:", s.text), s
    return False


def _holds(cond: Cond | Conds, inputs: dict[int, bool]) -> bool:
    if isinstance(cond, Cond):
        return inputs[int(cond.signal)] == cond.on
    assert cond.op == "not", cond
    return not _holds(cond.parts[0], inputs)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(lines=_ROUTINE)
def test_a_routine_read_without_native_lines_sets_what_the_krl_does(tmp_path: Path, lines: list[str]) -> None:
    """For every state of three inputs, the outputs the read routine sets are the KRL's; where a
    jump or exit stays native, the lines it may skip are native too."""
    path = tmp_path / "k.src"
    path.write_text("DEF k()\n  s()\nEND\nDEF s()\n" + "".join(f"  {ln}\n" for ln in lines) + "END\n")
    doc = read_on_robot([str(path)], None, None, None)
    body = next(r.body for r in doc.routines if r.name.lower() == "s")
    jumps = [s.where.line for s in walk(body) if isinstance(s, Native) and re.match(r"(GOTO|RETURN)\b", s.text)]
    if jumps:  # a jump kept: what it may skip is native, up to `done:` (to the end after a RETURN)
        done = 5 + lines.index("done:")
        returns = any(isinstance(s, Native) and s.text == "RETURN" for s in walk(body))
        assert all(s.where.line < min(jumps) or (s.where.line > done and not returns)
                   for s in walk(body) if isinstance(s, SetOut)), lines
        return
    for state in itertools.product([False, True], repeat=3):
        inputs = dict(zip((1, 2, 3), state))
        read: list[int] = []
        _run_read(body, inputs, read)
        assert read == _run_krl(lines, inputs), (lines, inputs)


def test_an_arm_ending_in_a_conditional_return_is_no_else(tmp_path: Path) -> None:
    """`IF DInput(di3) = 1 RETURN;` may not leave: the lines after the IF run either way, or not."""
    module = ("MODULE R\n  PROC main()\n    sub;\n  ENDPROC\n  PROC sub()\n    IF DInput(di1) = 1 THEN\n      SetDO do1, 1;\n"
              "      IF DInput(di3) = 1 RETURN;\n    ENDIF\n    SetDO do2, 1;\n  ENDPROC\nENDMODULE\n")
    program, _ = _import(tmp_path, "r.mod", module)
    assert "else" not in program and 'native rapid "SetDO do2, 1;"' in program and "set out[2]" not in program


def test_lines_another_jump_lands_in_are_no_else(tmp_path: Path) -> None:
    """`back:` lies among what `GOTO done` skips and `GOTO back` lands there: those lines run on
    two paths, so they cannot be one arm of the IF."""
    program, _ = _import(tmp_path, "k.src", "DEF k()\n  s()\nEND\nDEF s()\n  IF $IN[2] THEN\n    GOTO back\n  ENDIF\n"
                         "  IF $IN[1] THEN\n    GOTO done\n  ENDIF\n  $OUT[2] = TRUE\n  back:\n  $OUT[3] = TRUE\n"
                         "  done:\n  $OUT[4] = TRUE\nEND\n")
    assert 'native krl "$OUT[3] = TRUE"' in program and "set out[3]" not in program and "set out[4] = on" in program


def test_a_krl_exit_leaves_its_loop_not_the_routine(tmp_path: Path) -> None:
    """EXIT inside an IF inside a WHILE: the loop is kept native (its passes end as $IN[2] decides),
    and what follows the loop runs either way, read. In a loop kept native it changes nothing."""
    program, output = _import(tmp_path, "k.src", "DEF k()\n  s()\nEND\nDEF s()\n  WHILE $IN[1]\n    $OUT[1] = TRUE\n"
                              "    IF $IN[2] THEN\n      EXIT\n    ENDIF\n    $OUT[3] = TRUE\n  ENDWHILE\n"
                              "  $OUT[4] = TRUE\nEND\n")
    assert 'native krl "WHILE $IN[1]"' in program and 'native krl "$OUT[3] = TRUE"' in program
    assert "    set out[4] = on\n" in program and "`EXIT` at line 8 inside this block jumps out of it" in output
    native_loop, _ = _import(tmp_path, "k.src", "DEF k()\n  s()\nEND\nDEF s()\n  LOOP\n    $OUT[1] = TRUE\n"
                             "    IF $IN[2] THEN\n      EXIT\n    ENDIF\n    $OUT[3] = TRUE\n  ENDLOOP\n"
                             "  $OUT[4] = TRUE\nEND\n")
    assert "    set out[4] = on\n" in native_loop


def test_a_urscript_function_return_is_an_exit(tmp_path: Path) -> None:
    """`return` inside an if of a function: what follows is the if's else; a `break` inside an if
    of a loop read as rmot's while keeps that loop native, and what follows it is read."""
    script = ("def main():\n  def sub():\n    if get_standard_digital_in(1):\n      set_standard_digital_out(1, True)\n"
              "      return None\n    end\n    set_standard_digital_out(2, True)\n  end\n"
              "  def loop():\n    while get_standard_digital_in(3):\n      if get_standard_digital_in(4):\n"
              "        break\n      end\n      set_standard_digital_out(5, True)\n    end\n"
              "    set_standard_digital_out(6, True)\n  end\n  sub()\n  loop()\nend\nmain()\n")
    program, output = _import(tmp_path, "u.script", script)
    assert "  proc sub() {\n    if in[1] == on {\n      set out[1] = on\n    } else {\n      set out[2] = on\n" in program
    assert 'native urscript "set_standard_digital_out(5, True)"' in program and "    set out[6] = on\n" in program
    assert "`break` at line 12 inside this block jumps out of it" in output
