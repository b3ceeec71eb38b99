"""Flags and markers a program tests but never sets, read as the inputs named after them (W549).

A Fanuc flag F[n] the program only tests is set by another program, the background logic or the
PLC; a marker M[n] is set by the background logic, again and again, to the expression a program
assigned it (FANUC R-30iB mixed logic, "Marker"). From the program's side both are state it does
not control, as an input is: read so, every arm of a branch on them is planned and verified. A
flag the program resets (a handshake) and a marker it assigns (background logic it defines) stay
native. The stub cell gives each a port no native line of the program names, so compiled back
the input is not a signal a kept line still uses. rmot's own checker and compiler are the
witnesses that the result is a program.
"""

from __future__ import annotations

import ast
import itertools
import re
from pathlib import Path

from click.testing import CliRunner
from test_import_urscript_runtime import _eval as python_meaning

from rmot.backends.readers import read_files
from rmot.backends.readers.model import Cond, Conds, If, SetOut, walk
from rmot.compiler.cli import cli

PROGRAM = """/PROG  BITS
/ATTR
DEFAULT_GROUP	= 1,*,*,*,*;
/MN
   1:  UFRAME_NUM=0 ;
   2:  UTOOL_NUM=1 ;
   3:J P[1] 100% FINE ;
   4:  WAIT (!F[525]) ;
   5:  WAIT (M[3] AND DI[4]) ;
   6:  IF (F[525:part ready] OR M[3]) THEN ;
   7:  DO[2]=ON ;
   8:  ELSE ;
   9:  DO[2]=OFF ;
  10:  ENDIF ;
  11:  WAIT (F[7]) ;
  12:  F[7]=(OFF) ;
  13:  M[9]=(DI[1] AND DI[2]) ;
  14:  WAIT (M[9]) ;
  15:L P[1] 100mm/sec FINE ;
/POS
P[1]{
   GP1:
	UF : 0, UT : 1,		CONFIG : 'N U T, 0, 0, 0',
	X =   500.000  mm,	Y =     0.000  mm,	Z =   500.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
/END
"""


def _rmot(*args: str | Path) -> tuple[int, str]:
    result = CliRunner().invoke(cli, [str(a) for a in args], catch_exceptions=False)
    return result.exit_code, result.output


def _imported(tmp_path: Path) -> tuple[str, str, str]:
    (tmp_path / "bits.ls").write_text(PROGRAM)
    code, output = _rmot("import", tmp_path / "bits.ls", "-o", tmp_path / "bits.rmot")
    assert code == 0, output
    return (tmp_path / "bits.rmot").read_text(), (tmp_path / "bits_cell.rmot").read_text(), output


def test_flags_and_markers_set_elsewhere_are_inputs(tmp_path: Path) -> None:
    program, cell, output = _imported(tmp_path)
    ports = dict(re.findall(r'io in\[(\d+)\] = "([^"]+)"', cell))
    flag = next(k for k, v in ports.items() if v == "f[525]")
    marker = next(k for k, v in ports.items() if v == "m[3]")
    assert f"wait until in[{flag}] == off" in program
    assert f"wait until in[{marker}] == on and in[4] == on" in program
    assert f"if in[{flag}] == on or in[{marker}] == on {{" in program
    # W549 once per flag or marker, at its first use, naming it as the program writes it
    assert re.findall(r"bits\.ls:(\d+):\d+: warning\[W549\]: `([^`]+)`", output) == [("8", "F[525:part ready]"),
                                                                                  ("9", "M[3]")]


def test_a_handshake_flag_and_a_marker_the_program_assigns_stay_native(tmp_path: Path) -> None:
    program, _, output = _imported(tmp_path)
    for line in ("WAIT (F[7]) ;", "F[7]=(OFF) ;", "M[9]=(DI[1] AND DI[2]) ;", "WAIT (M[9]) ;"):
        assert f'native fanuc "{line}"' in program, line
    assert "`F[7]`" not in output and "`M[9]`" not in output


def test_the_inputs_take_ports_no_native_line_names(tmp_path: Path) -> None:
    """DI[1] and DI[2] stay in the kept marker line and DI[4] is read: the two named inputs take
    3 and 5, so the compiled program's DI[3] and DI[5] are theirs alone."""
    _, cell, _ = _imported(tmp_path)
    assert sorted(re.findall(r'io in\[(\d+)\] = "([fm]\[\d+\])"', cell)) == [("3", "f[525]"), ("5", "m[3]")]


def test_the_imported_program_checks_and_compiles(tmp_path: Path) -> None:
    _imported(tmp_path)
    assert _rmot("check", tmp_path / "bits.rmot")[0] == 0
    code, output = _rmot("compile", tmp_path / "bits.rmot", "--target", "fanuc", "-o", tmp_path / "out")
    assert code == 0, output
    tp = (tmp_path / "out" / "fanuc" / "BITS.ls").read_text()
    assert re.search(r"WAIT DI\[3:f_525_\]=OFF ;", tp) and re.search(r"WAIT DI\[5:m_3_\]=ON AND DI\[4\]=ON ;", tp), tp
    assert "M[9]=(DI[1] AND DI[2]) ;" in tp  # the kept line, on the signals it named


KRL = """DEF flag()
$TOOL = {X 0, Y 0, Z 100, A 0, B 0, C 0}
$BASE = $NULLFRAME
PTP {A1 0, A2 -90, A3 90, A4 0, A5 0, A6 0}
$OUT[1] = $IN[1] AND $IN[3]
WAIT FOR $FLAG[3]
IF $FLAG[3] AND $IN[2] THEN
  $OUT[5] = TRUE
ENDIF
WAIT FOR $FLAG[4]
$FLAG[4] = FALSE
END
"""


def test_a_krl_flag_the_program_never_sets_is_an_input(tmp_path: Path) -> None:
    """KRL alike: `$FLAG[3]`, only tested, is the input `$flag[3]` (W549 once), on port 4: the
    kept `$OUT[1] = $IN[1] AND $IN[3]` names 1 and 3, and 2 is read; `$FLAG[4]`, which the
    program resets after waiting for it, is a handshake and stays native."""
    (tmp_path / "flag.src").write_text(KRL)
    code, output = _rmot("import", tmp_path / "flag.src", "-o", tmp_path / "flag.rmot")
    program, cell = (tmp_path / "flag.rmot").read_text(), (tmp_path / "flag_cell.rmot").read_text()
    assert code == 0 and 'io in[4] = "$flag[3]"' in cell, (output, cell)
    assert 'native krl "$OUT[1] = $IN[1] AND $IN[3]"' in program
    assert "wait until in[4] == on" in program and "if in[4] == on and in[2] == on {" in program
    assert re.findall(r"flag\.src:(\d+):\d+: warning\[W549\]: `([^`]+)`", output) == [("6", "$FLAG[3]")]
    assert 'native krl "WAIT FOR $FLAG[4]"' in program and 'native krl "$FLAG[4] = FALSE"' in program


# outputs set to a condition's value (VASC pendant programs), and the German pendant's spelling
EXPRESSIONS = ["!DI[3]", "DI[1] AND !DO[5]", "F[12]", "(DI[1] AND !DI[2]) OR F[12]", "!F[12] AND (DI[1] OR DO[5])"]


def _meaning(cond: object, state: dict[str, bool]) -> bool:
    """What the read condition means for one state of the signals (the model's and/or/not)."""
    if isinstance(cond, Cond):
        key = f"{'DO' if cond.output else 'DI'}{cond.signal}" if isinstance(cond.signal, int) else cond.signal
        return state[key.replace("[", "").replace("]", "")] == cond.on
    assert isinstance(cond, Conds), cond
    if cond.op == "logic" and cond.text == "{0}":
        return _meaning(cond.parts[0], state)
    values = [_meaning(p, state) for p in cond.parts]
    return not values[0] if cond.op == "not" else all(values) if cond.op == "and" else any(values)


def test_an_output_set_to_a_condition_is_an_if_setting_it_on_or_off(tmp_path: Path) -> None:
    """`DO[n]=(expr)` gives the output the expression's value once, as the line runs (B-83284EN,
    mixed logic): read as `if expr { set out[n] = on } else { set out[n] = off }`. Witness: the
    TP expression evaluated by Python's own parser for every state of its signals."""
    lines = [f"  {k + 4:3d}:  DO[9]=({e}) ;" for k, e in enumerate(EXPRESSIONS)]
    lines.append(f"  {len(EXPRESSIONS) + 4:3d}:  A[10]=(!E[4] AND F[12]) ;")
    path = tmp_path / "outs.ls"
    path.write_text(PROGRAM.replace("   4:  WAIT (!F[525]) ;\n", "\n".join(lines) + "\n"))
    ifs = [s for r in read_files([str(path)]).routines for s in walk(r.body) if isinstance(s, If)]
    for expr, found in zip([*EXPRESSIONS, "!DI[4] AND F[12]"], ifs[:len(EXPRESSIONS) + 1]):
        out = 10 if expr.startswith("!DI[4]") else 9
        assert found.then == (SetOut(out, 1.0, found.where),) and found.orelse == (SetOut(out, 0.0, found.where),)
        names = sorted(set(re.findall(r"[A-Z]+\[\d+\]", expr)))
        python = ast.parse(re.sub(r"([A-Z]+)\[(\d+)\]", r"\1\2", expr.replace("!", " not ").replace("AND", "and")
                                  .replace("OR", "or")).strip(), mode="eval")
        for values in itertools.product((False, True), repeat=len(names)):
            state = {n.replace("[", "").replace("]", ""): v for n, v in zip(names, values)}
            assert _meaning(found.cond, state) == python_meaning(python, state), (expr, state)
    assert len(ifs) == len(EXPRESSIONS) + 2  # and the IF .. THEN of the program itself
    # each such line is one instruction imported, not the two outputs its arms set
    code, output = _rmot("import", path, "-o", tmp_path / "outs.rmot")
    assert code == 0 and "motion and I/O: 11 imported, 2 kept native" in output, output
