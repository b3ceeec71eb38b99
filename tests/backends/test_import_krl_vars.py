"""`rmot import` of KRL globals the program sets and tests, read as task variables (REFERENCE §14,
"KRL globals and flags"; backends/readers/krl_vars.py).

The programs imitate real forms: a bag-drop flag a palletising program raises and clears and tests
at the top of each box (ingeniado CAJA_G caja_g_m1.src: `IF (ERROR_SACO_CAIDO == TRUE ) THEN`
.. `ERROR_SACO_CAIDO = FALSE`, later `ERROR_SACO_CAIDO = TRUE`; Aleynikovich cnc5916.src:
`DESCARGACNC1=TRUE`, `IF DESCARGACNC1 THEN DESCARGACNC1=FALSE`), next to an exit request only a
PLC raises (`IF SALIR == TRUE THEN`, the program only sets `SALIR=FALSE`) and a pump output it
sets and never tests (`BOMBA =TRUE`). KRL semantics: KSS 8.x Operating and Programming
Instructions for System Integrators, "Variables and declarations" ($config.dat globals keep their
value between runs). Witnesses: rmot's own compiler (the imported program compiles), the KRL it
writes read back and written again (the same KRL statements), and the text of the .src written here.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from click.testing import CliRunner

from krl_imported import imported_krl
from rmot.compiler.cli import cli

DAT = """DEFDAT caja
  DECL E6AXIS XHOME={A1 0.0,A2 -90.0,A3 90.0,A4 0.0,A5 0.0,A6 0.0}
  DECL E6AXIS XP1={A1 10.0,A2 -90.0,A3 90.0,A4 0.0,A5 0.0,A6 0.0}
ENDDAT
"""

SRC = """DEF caja( )
  DECL INT n
  PTP XHOME
  FOR n = 1 TO 3
    IF (ERROR_SACO_CAIDO == TRUE) THEN
      WAIT FOR $IN[3]
      ERROR_SACO_CAIDO = FALSE
    ENDIF
    IF SALIR == TRUE THEN
      $OUT[2] = TRUE
    ENDIF
    BOMBA = TRUE
    PTP XP1
    IF NOT $IN[4] THEN
      ERROR_SACO_CAIDO = TRUE
    ENDIF
    BOMBA = FALSE
  ENDFOR
  SALIR = FALSE
END
"""


def _body(rmot: str) -> list[str]:
    return [ln.strip() for ln in rmot.splitlines()]


def test_global_bool_the_program_raises_and_clears(tmp_path: Path) -> None:
    """No $config.dat: a name assigned TRUE and FALSE and tested is a BOOL global (W542 at its
    first assignment, starting off); one only reset (SALIR) or never tested (BOMBA) stays native."""
    output, rmot = imported_krl(tmp_path, "caja", SRC, DAT)
    body = _body(rmot)
    for line in ["var ERROR_SACO_CAIDO: bool = off", "if ERROR_SACO_CAIDO {", "ERROR_SACO_CAIDO = off",
                 "ERROR_SACO_CAIDO = on", "wait until in[3] == on"]:
        assert line in body, (line, rmot)
    src = tmp_path / "caja.src"
    w542 = re.findall(rf"{re.escape(str(src))}:(\d+):(\d+): warning\[W542\]: (.*)", output)
    assert [(a, b) for a, b, _ in w542] == [("7", "7")], output  # ERROR_SACO_CAIDO = FALSE, its first assignment
    assert "starting at off" in w542[0][2] and "output SIGNAL" in w542[0][2]
    for line in ["IF SALIR == TRUE THEN", "BOMBA = TRUE", "SALIR = FALSE"]:
        assert f'native krl "{line}"' in rmot, (line, rmot)


def test_global_round_trips_through_krl(tmp_path: Path) -> None:
    """Compiled to KRL, the variable is the program's own (`DECL BOOL` in its .dat, set at the
    start); read back and compiled again, the KRL statements are the same."""
    _, rmot = imported_krl(tmp_path, "caja", SRC, DAT)
    written = []
    for k, source in enumerate([tmp_path / "caja.rmot", tmp_path / "again" / "caja.rmot"]):
        out = tmp_path / f"o{k}"
        result = CliRunner().invoke(cli, ["compile", str(source), "--target", "krl", "-o", str(out),
                                          "--allow-findings"])
        assert "error[" not in result.output, result.output
        krl = (out / "krl" / "caja.src").read_text()
        written.append([ln.strip() for ln in krl.splitlines() if ln.strip() and not ln.strip().startswith(";")])
        if k == 0:
            assert "DECL BOOL ERROR_SACO_CAIDO=FALSE" in (out / "krl" / "caja.dat").read_text()
            (tmp_path / "again").mkdir()
            result = CliRunner().invoke(cli, ["import", str(out / "krl" / "caja.src"), "-o",
                                              str(tmp_path / "again" / "caja.rmot"), "--robot", "kuka_kr16"])
            assert result.exit_code == 0 and "W542" not in result.output, result.output
    assert written[0] == written[1]
    assert "IF ERROR_SACO_CAIDO THEN" in written[0] and "ERROR_SACO_CAIDO=TRUE" in written[0]


CONFIG = """DEFDAT $CONFIG PUBLIC
  DECL INT N_SACO=2
  DECL BOOL DESCARGACNC1=TRUE
  SIGNAL BOMBA $OUT[5]
  DECL REAL ALTURA
ENDDAT
"""

COUNTED = """DEF cnt( )
  ALTURA = 0
  N_SACO = N_SACO + 1
  IF N_SACO >= 4 THEN
    DESCARGACNC1 = TRUE
  ENDIF
  BOMBA = TRUE
  IF DESCARGACNC1 THEN
    DESCARGACNC1 = FALSE
    PTP XHOME
  ENDIF
  ALTURA = ALTURA + 2.5
END
"""


def test_globals_typed_by_the_config_found(tmp_path: Path) -> None:
    """A $config.dat beside the program gives the type and start value (INT, REAL, BOOL); its
    SIGNAL stays an output; a REAL the program sets first thing gets no start-value warning."""
    (tmp_path / "$config.dat").write_text(CONFIG)
    output, rmot = imported_krl(tmp_path, "cnt", COUNTED, DAT.replace("caja", "cnt"))
    body = _body(rmot)
    for line in ["var N_SACO: int = 2", "var DESCARGACNC1: bool = on", "var ALTURA: num = 0", "N_SACO = N_SACO + 1",
                 "if N_SACO >= 4 {", "DESCARGACNC1 = on", "if DESCARGACNC1 {", "DESCARGACNC1 = off",
                 "ALTURA = ALTURA + 2.5", "set out[5] = on"]:
        assert line in body, (line, rmot)
    notes = re.findall(r"cnt\.src:(\d+):\d+: warning\[W542\]: `(\w+)`([^\n]*)", output)
    assert [(line, name) for line, name, _ in notes] == [("2", "ALTURA"), ("3", "N_SACO"), ("5", "DESCARGACNC1")]
    assert "starting at 2 (the value the file stores" in notes[1][2] and str(tmp_path / "$config.dat") in notes[1][2]
    assert "sets it before it reads it" in notes[0][2] and "give the $config.dat" not in notes[0][2]


def test_global_another_routine_sets_stays_native(tmp_path: Path) -> None:
    """A global a called routine of the file also assigns is not a task variable (rmot's procs do not
    see one): the test on it stays native."""
    src = SRC.replace("END\n", "END\n", 1) + "DEF sub( )\n  ERROR_SACO_CAIDO = TRUE\nEND\n"
    output, rmot = imported_krl(tmp_path, "caja", src, DAT)
    assert "W542" not in output and "var ERROR_SACO_CAIDO" not in rmot
    assert 'native krl "IF (ERROR_SACO_CAIDO == TRUE) THEN"' in rmot


FLAGS = """DEF fl( )
  $FLAG[3] = FALSE
  PTP XHOME
  WAIT FOR $FLAG[1]
  $FLAG[1] = FALSE
  IF $IN[2] THEN
    $FLAG[3] = TRUE
  ENDIF
  IF $FLAG[3] AND $IN[5] THEN
    PTP XP1
  ENDIF
  WAIT FOR $FLAG[7]
  WAIT FOR $CYCFLAG[2]
END
"""


def test_controller_flags(tmp_path: Path) -> None:
    """`$FLAG[n]` the main DEF sets TRUE and FALSE is the bool variable FLAG_n (W542, set first thing:
    no start-value note); the Ethernet KRL handshake `WAIT FOR $FLAG[1]` `$FLAG[1]=FALSE` (KamWisa
    binarystream.src, Shangmc BinaryFixed.src: the EKI driver raises the flag when data arrives) and
    a cyclic flag stay native, each W510 saying why; a flag the program never sets is the input of
    its name (W549)."""
    output, rmot = imported_krl(tmp_path, "fl", FLAGS, DAT.replace("caja", "fl"))
    body = _body(rmot)
    for line in ["var FLAG_3: bool = off", "FLAG_3 = on", "if FLAG_3 and in[5] == on {"]:
        assert line in body, (line, rmot)
    assert "FLAG_3 = off" not in body  # the first assignment is the start value
    notes = re.findall(r"fl\.src:(\d+):(\d+): warning\[W542\]: ([^\n]*)", output)
    assert [(a, b) for a, b, _ in notes] == [("2", "3")] and "`$FLAG[3]`" in notes[0][2]
    assert "sets it before it reads it" in notes[0][2]
    why = dict(re.findall(r"fl\.src:(\d+):\d+: warning\[W510\]: ([^\n]*)", output))
    assert why["4"].startswith("`$FLAG[1]` is a global flag the program only sets to FALSE"), why
    assert why["5"].startswith("`$FLAG[1]` is a global flag the program only sets to FALSE"), why
    assert "12" not in why and "wait until in[1] == on" in body, rmot
    assert re.search(r"fl\.src:12:\d+: warning\[W549\]: `\$FLAG\[7\]` is a global flag the program tests but never sets",
                     output), output
    assert why["13"].startswith("it reads a cyclic flag ($CYCFLAG[n]"), why


def test_reset_only_flag_says_why(tmp_path: Path) -> None:
    """The exit request a PLC raises and the program only clears: each of its lines' W510 names it."""
    output, _ = imported_krl(tmp_path, "caja", SRC, DAT)
    why = dict(re.findall(r"caja\.src:(\d+):\d+: warning\[W510\]: ([^\n]*)", output))
    for line in ("9", "19"):
        assert why[line].startswith("`SALIR` is a global flag the program only sets to FALSE: another program"), why


def test_goto_to_the_end_is_stop(tmp_path: Path) -> None:
    """`GOTO FINAL` out of an IF where `FINAL:` is the main DEF's last statement (ingeniado CAJA_G
    coge_g.src) reaches END: `stop`, as RETURN there; a GOTO ending an IF's arm, to a label with
    statements after it, makes what it skips the IF's other arm."""
    src = ("DEF cg( )\n  PTP XHOME\n  IF $IN[2] THEN\n    $OUT[1] = TRUE\n    GOTO FINAL\n  ENDIF\n"
           "  IF $IN[3] THEN\n    GOTO OTRO\n  ENDIF\n  PTP XP1\n  OTRO:\n  PTP XHOME\n  FINAL:\nEND\n")
    output, rmot = imported_krl(tmp_path, "cg", src, DAT.replace("caja", "cg"))
    body = _body(rmot)
    at = body.index("if in[2] == on {")
    assert body[at + 1:at + 4] == ["set out[1] = on", "stop", "}"], rmot
    at = body.index("if not in[3] == on {")
    assert body[at + 1].startswith("move joint XP1") and body[at + 2] == "}", rmot
    assert "GOTO FINAL" not in rmot and "GOTO OTRO" not in rmot and "GOTO OTRO" not in output


LOOPS = """DEF lp( )
  DECL INT n, x, planta
  FOR x=1 TO 6
  $VEL_AXIS[x]=85
  $ACC_AXIS[x]=40
  ENDFOR
  PTP XHOME
  FOR x=1 TO 6
    $VEL_AXIS[x]=20
  ENDFOR
  PTP XP1
  FOR n = 1 TO 3
    IF (n == 2) THEN
      $OUT[1] = TRUE
    ENDIF
    PTP XHOME
  ENDFOR
  FOR planta = 1 TO 5
    PTP XP1
    planta = planta + 1
    $OUT[3] = TRUE
  ENDFOR
  FOR n = 1 TO 8
    n = n * 2
    PTP XP1
  ENDFOR
END
"""


def test_loops_over_axes_and_counters(tmp_path: Path) -> None:
    """`FOR x=1 TO 6 $VEL_AXIS[x]=85 $ACC_AXIS[x]=40 ENDFOR` (Shangmc main.src, ingeniado
    saco_20_m2.src) sets every axis's speed: the next PTP's `speed 85 %` (its acceleration 40 %
    as rmot's own RMOT_PTP loop writes it); `IF (n == 2)` in `FOR n` is a test the compiler decides at
    each iteration; `FOR planta = 1 TO 5` whose body adds 1 to its counter once (`PLANTA = PLANTA +
    1`, caja_g_m1.src: KRL runs it for 1, 3, 5, counted by hand here) is a loop of 3 iterations; a
    counter the body sets otherwise stays native."""
    output, rmot = imported_krl(tmp_path, "lp", LOOPS, DAT.replace("caja", "lp"))
    body = _body(rmot)
    assert "move joint XHOME speed 85 % accel 40 % zone fine" in body, rmot
    assert "move joint XP1 speed 20 % accel 40 % zone fine" in body, rmot
    at = body.index("for n in 1 .. 4 {")
    assert body[at + 1:at + 4] == ["if n == 2 {", "set out[1] = on", "}"], rmot
    at = body.index("for planta in 1 .. 4 {")
    assert body[at + 1:at + 4] == ["move joint XP1 speed 20 % accel 40 % zone fine", "set out[3] = on", "}"], rmot
    why = dict(re.findall(r"lp\.src:(\d+):\d+: warning\[W510\]: ([^\n]*)", output))
    assert sorted(why, key=int) == ["23", "24", "25", "26"], why
    assert why["23"].startswith("the loop's counter `n` is assigned in its body"), why
    result = CliRunner().invoke(cli, ["compile", str(tmp_path / "lp.rmot"), "--target", "krl", "-o",
                                      str(tmp_path / "o"), "--allow-findings"])
    assert "error[" not in result.output, result.output
    krl = (tmp_path / "o" / "krl" / "lp.src").read_text()
    assert "RMOT_PTP(85.000,40.000)" in krl and "IF n == 2 THEN" in krl
    again = CliRunner().invoke(cli, ["import", str(tmp_path / "o" / "krl" / "lp.src"), "-o", str(tmp_path / "a.rmot"),
                                     "--robot", "kuka_kr16"])
    assert again.exit_code == 0, again.output
    back = _body((tmp_path / "a.rmot").read_text())
    at = back.index("for n in 1 .. 4 {")
    assert back[at + 1:at + 4] == ["if n == 2 {", "set out[1] = on", "}"], back


def test_condition_on_an_output_signal_reads_the_output(tmp_path: Path) -> None:
    """`SIGNAL OutMarchaCinta $OUT[..]` of a $config.dat, tested (Aleynikovich bto.src `IF OutMarchaCinta
    THEN`): the condition reads the output's state, `out[5]` (KSS 8.x "SIGNAL": the name is the
    output, read and written); the same name set is still the output instruction."""
    (tmp_path / "$config.dat").write_text("DEFDAT $CONFIG PUBLIC\n  SIGNAL OutMarchaCinta $OUT[5]\n"
                                          "  SIGNAL InListo $IN[7]\nENDDAT\n")
    src = ("DEF sg( )\n  PTP XHOME\n  IF OutMarchaCinta THEN\n    PTP XP1\n  ENDIF\n"
           "  WAIT FOR InListo AND NOT OutMarchaCinta\n  OutMarchaCinta = TRUE\nEND\n")
    output, rmot = imported_krl(tmp_path, "sg", src, DAT.replace("caja", "sg"))
    assert "W510" not in output, output
    body = _body(rmot)
    assert "if out[5] == on {" in body and "wait until in[7] == on and out[5] == off" in body, body
    assert "set out[5] = on" in body


def test_config_bool_the_program_never_sets(tmp_path: Path) -> None:
    """A BOOL global of the $config.dat found that the program only tests (`WAIT FOR REPITE_SACO`,
    ingeniado caja_g_m1.src, a flag the PLC's program sets) is state another program sets, as a
    whole number it only tests is a group input (W534): the input of its name, W549 once (not a
    task variable)."""
    (tmp_path / "$config.dat").write_text("DEFDAT $CONFIG PUBLIC\n  DECL BOOL REPITE_SACO=FALSE\nENDDAT\n")
    src = "DEF rs( )\n  PTP XHOME\n  WAIT FOR REPITE_SACO\n  PTP XP1\nEND\n"
    output, rmot = imported_krl(tmp_path, "rs", src, DAT.replace("caja", "rs"))
    assert "W510" not in output and "wait until in[1] == on" in _body(rmot), (output, rmot)
    assert re.findall(r"rs\.src:(\d+):\d+: warning\[W549\]: `REPITE_SACO`", output) == ["3"], output
    assert 'io in[1] = "repite_saco"' in (tmp_path / "rs_cell.rmot").read_text().lower()
    assert "W542" not in output and "var REPITE_SACO" not in rmot


def test_assignments_in_the_set_up_fold_make_no_variable(tmp_path: Path) -> None:
    """`bTornillo=$IN[139]` in the template's USER INI fold (Aleynikovich C2_CicloCompleto.src), which
    the import keeps as a comment: the variable would start off and never get that value, so
    neither it nor a global set there is a task variable; the tests on them stay native."""
    src = ("DEF ini( )\n  BOOL b\n  ;FOLD INI;%{PE}\n    ;FOLD USER INI\n      b = $IN[3]\n      G_FLAG = TRUE\n"
           "    ;ENDFOLD (USER INI)\n  ;ENDFOLD (INI)\n  PTP XHOME\n  IF b THEN\n    PTP XP1\n  ENDIF\n"
           "  IF G_FLAG THEN\n    G_FLAG = FALSE\n  ENDIF\nEND\n")
    output, rmot = imported_krl(tmp_path, "ini", src, DAT.replace("caja", "ini"))
    assert "var " not in rmot and "W542" not in output
    assert 'native krl "IF b THEN"' in rmot and 'native krl "IF G_FLAG THEN"' in rmot
    why = dict(re.findall(r"ini\.src:(\d+):\d+: warning\[W510\]: ([^\n]*)", output))
    assert why["10"].startswith("it tests `b`, which only the set-up fold (INI, USER INI) assigns"), why


def test_switch_and_repeat_on_a_config_int(tmp_path: Path) -> None:
    """A state machine on an INT global of the $config.dat found (`SWITCH EstadoActual`, luciagumbau228
    RSR0001.src): set first thing, it is the start value; SWITCH → an if chain, REPEAT .. UNTIL →
    the body then `while not`; KRL's REPEAT runs its body once before testing (KSS 8.x "REPEAT")."""
    (tmp_path / "$config.dat").write_text("DEFDAT $CONFIG PUBLIC\n  DECL INT ESTADO=0\nENDDAT\n")
    src = ("DEF sw( )\n  ESTADO = 1\n  PTP XHOME\n  SWITCH ESTADO\n  CASE 1\n    PTP XP1\n    ESTADO = 2\n"
           "  DEFAULT\n    PTP XHOME\n  ENDSWITCH\n  REPEAT\n    ESTADO = ESTADO + 1\n  UNTIL ESTADO >= 3\nEND\n")
    output, rmot = imported_krl(tmp_path, "sw", src, DAT.replace("caja", "sw"))
    body = _body(rmot)
    at = body.index("var ESTADO: int = 1")
    assert body[at + 1:] == ["move joint XHOME speed 100 % zone fine", "if ESTADO == 1 {",
                             "move joint XP1 speed 100 % zone fine", "ESTADO = 2", "} else {",
                             "move joint XHOME speed 100 % zone fine", "}", "ESTADO = ESTADO + 1",
                             "while not (ESTADO >= 3) {", "ESTADO = ESTADO + 1", "}", "}"], rmot
    assert "W510" not in output and "sets it before it reads it" in output


def _krl_for_runs(first: int, last: int, step: int) -> int:
    """How often KSS 8.x runs `FOR k = first TO last` whose body ends `k = k + step`: k = first;
    while k <= last: body (k + step), then k + 1 (the manual's FOR, simulated)."""
    k, runs = first, 0
    while k <= last:
        runs, k = runs + 1, k + step + 1
    return runs


@pytest.mark.parametrize("first,last,step", [(1, 5, 1), (1, 10, 2), (0, 0, 3), (3, 2, 1), (-4, 7, 4)])
def test_stepped_loop_counts_as_krl_runs_it(first: int, last: int, step: int) -> None:
    from rmot.backends.readers.krl_text import lines
    from rmot.backends.readers.krl_vars import counted_loop
    found = lines("s.src", f"FOR k = {first} TO {last}\n  PTP XP1\n  k = k + {step}\n  $OUT[1] = TRUE\nENDFOR\n")
    loop = counted_loop(found, 0)
    assert isinstance(loop, tuple) and loop[3] == found[2].where
    assert loop[2] - loop[1] == _krl_for_runs(first, last, step)


@pytest.mark.parametrize("text", [
    "FOR k = 1 TO 5\n  k = k + 1\n  L1:\nENDFOR\n",                       # a label after the increment
    "FOR k = 1 TO 5\n  k = k + 1\n  IF $IN[1] THEN\n    GOTO L1\n  ENDIF\nENDFOR\n",  # a jump after it
    "FOR k = 1 TO 5\n  IF $IN[1] THEN\n    k = k + 1\n  ENDIF\nENDFOR\n",  # not in every iteration
    "FOR k = 1 TO 5\n  $OUT[k] = TRUE\n  k = k + 1\nENDFOR\n",              # read in the body
    "FOR k = 1 TO 5\n  k = k + 1\nENDFOR\nn = k\n",                         # read after the loop
    "FOR k = 1 TO 5\n  k = k - 1\nENDFOR\n",                                # not an increment
])
def test_counter_set_otherwise_stays_native(text: str) -> None:
    from rmot.backends.readers.krl_text import lines
    from rmot.backends.readers.krl_vars import counted_loop
    assert counted_loop(lines("s.src", text), 0) == "the loop's counter `k` is assigned in its body (KRL then skips iterations)"
