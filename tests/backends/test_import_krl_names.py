"""KRL names a taught program reads: positions in `.dat` arrays, SIGNAL names of inputs and
outputs (in the program, its `.dat` or the robot's `$config.dat`), names declared nowhere the
import sees, inline forms commented out, and the KSS 8 inline form's `C_DIS C_DIS`.

Witness: KRL syntax per KSS 8.x Operating and Programming Instructions for System Integrators
("SIGNAL", arrays in data lists, `$config.dat` in KRC:\\R1\\System); the expected statements are
written by hand from the numbers typed in the modules below; a FRAME's orientation is checked
against scipy's ZYX Euler rotation (A about Z, B about Y, C about X), not the reader's own code;
the rmot text the import writes is checked by rmot's own parser.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from click.testing import CliRunner
from scipy.spatial.transform import Rotation

from rmot.backends.readers import read_files
from rmot.backends.readers.model import Cond, Conds, If, Move, Native, Pulse, SetOut, WaitIn, leaves, walk
from rmot.compiler.cli import cli
from rmot.lang.parse import parse_text

SRC = """&ACCESS RVP
DEF mill( )
SIGNAL doClamp $OUT[7]
$APO.CDIS = 3
$APO.CPTP = 50
PTP lfPrePos[1] C_PTP
LIN lfWorkPos[ 2 ] C_DIS C_DIS
LIN lfMoved[1]
;FOLD PTP P9 CONT Vel=100 % PDAT9 Tool[1] Base[0];%{PE}
  ;$BWDSTART = FALSE
  ;PTP XP9 C_PTP
;ENDFOLD
WAIT FOR ( diPartReady == TRUE )
IF NOT diPartReady THEN
  doClamp = TRUE
ENDIF
PULSE(doClamp, TRUE, 0.5)
WAIT FOR bBusy
lfMoved[1].X = 5
END
"""

DAT = """DEFDAT mill
DECL FRAME lfPrePos[2]
lfPrePos[1]={X 100.0,Y 0.0,Z 150.0,A 0.0,B 0.0,C 0.0}
DECL FRAME lfWorkPos[3]
lfWorkPos[2]={X 10.0,Y -20.0,Z 30.0,A 30.0,B -45.0,C 60.0}
DECL FRAME lfMoved[1]
lfMoved[1]={X 1.0,Y 2.0,Z 3.0,A 0.0,B 0.0,C 0.0}
DECL BOOL bBusy=FALSE
SIGNAL diPartReady $IN[12]
ENDDAT
"""


def _read(tmp_path: Path, src: str = SRC, dat: str = DAT) -> tuple[list[object], object]:
    (tmp_path / "mill.src").write_text(src)
    (tmp_path / "mill.dat").write_text(dat)
    doc = read_files([str(tmp_path / "mill.src")])
    return [s for r in doc.routines for s in walk(r.body)], doc


def test_dat_arrays_signals_and_disabled_folds(tmp_path: Path) -> None:
    stmts, doc = _read(tmp_path)
    moves = [s for s in stmts if isinstance(s, Move)]
    # the array elements are targets; `C_DIS C_DIS` blends by $APO.CDIS = 3 mm
    assert [m.target_name for m in moves] == ["lfPrePos[1]", "lfWorkPos[2]"]
    assert moves[1].kind == "linear" and moves[1].zone == 3.0
    assert moves[0].kind == "joint" and moves[0].zone == 50.0  # $APO.CPTP 50 %: the backend's 1 mm per %
    # lfMoved is assigned in the program: its .dat value holds only until then, the move stays native
    natives = [s.text for s in stmts if isinstance(s, Native)]
    assert "LIN lfMoved[1]" in natives
    # a FRAME {A 30, B -45, C 60}: rotation Rz(A)·Ry(B)·Rx(C) (scipy's intrinsic ZYX)
    work = next(t for t in doc.targets if t.name == "lfWorkPos[2]")
    w, x, y, z = work.pose.quaternion
    expected = Rotation.from_euler("ZYX", [30.0, -45.0, 60.0], degrees=True).as_matrix()
    assert np.allclose(Rotation.from_quat([x, y, z, w]).as_matrix(), expected, atol=1e-12)
    assert np.allclose(work.pose.position, (0.010, -0.020, 0.030), atol=1e-15)
    # the commented-out inline form does nothing on the controller: skipped, W520 at its fold line
    assert not any(m.target_name == "P9" for m in moves)
    assert [d.span.start.line for d in doc.diagnostics if d.code.id == "W520"] == [9]
    # SIGNAL names: the .dat's input, the program's output (wait, if, set, pulse)
    waits = [s for s in stmts if isinstance(s, WaitIn)]
    assert waits[0].cond.signal == 12 and waits[0].cond.on
    branch = next(s for s in stmts if isinstance(s, If))
    assert branch.cond.signal == 12 and not branch.cond.on
    assert [(s.signal, s.value) for s in stmts if isinstance(s, SetOut)] == [(7, 1.0)]
    assert [(s.signal, s.seconds) for s in stmts if isinstance(s, Pulse)] == [(7, 0.5)]
    # bBusy is a BOOL of the .dat: a variable, never an input
    assert "WAIT FOR bBusy" in natives
    assert not any(d.code.id == "W521" for d in doc.diagnostics)


CONFIG = """DEFDAT $CONFIG
DECL GLOBAL E6AXIS XHOME={A1 10.0,A2 -80.0,A3 70.0,A4 0.0,A5 20.0,A6 0.0,E1 0.0}
SIGNAL InGripOpen $IN[21]
SIGNAL OutGripClose $OUT[22]
DECL GLOBAL BOOL bAutoRun=TRUE
ENDDAT
"""

CELL_SRC = """DEF cell( )
PTP XHOME
WAIT FOR InGripOpen
OutGripClose = TRUE
WAIT FOR bAutoRun
WAIT FOR bUnknownFlag
PTP XHOME
END
"""


def test_config_dat_of_the_robot_tree(tmp_path: Path) -> None:
    """R1/Program/cell.src reads R1/System/$config.dat: its XHOME (no W511 guess), its SIGNALs,
    and its global BOOL the program never sets (another program's: the input of its name, W549);
    with the config read, a name declared nowhere is another module's variable, not an input."""
    program = tmp_path / "R1" / "Program"
    program.mkdir(parents=True)
    (tmp_path / "R1" / "System").mkdir()
    (tmp_path / "R1" / "System" / "$config.dat").write_text(CONFIG)
    (program / "cell.src").write_text(CELL_SRC)
    doc = read_files([str(program / "cell.src")])
    stmts = [s for r in doc.routines for s in walk(r.body)]
    home = next(t for t in doc.targets if t.name == "XHOME")
    assert home.joints == (10.0, -80.0, 70.0, 0.0, 20.0, 0.0)
    assert not any(d.code.id == "W511" for d in doc.diagnostics)
    assert [[c.signal for c in leaves(s.cond)] for s in stmts if isinstance(s, WaitIn)] == [[21], ["bAutoRun"]]
    assert [s.signal for s in stmts if isinstance(s, SetOut)] == [22]
    assert [s.text for s in stmts if isinstance(s, Native)] == ["WAIT FOR bUnknownFlag"]


def test_a_name_declared_nowhere_is_read_as_a_named_input(tmp_path: Path) -> None:
    """Without a $config.dat, a name the program neither declares nor assigns, read in a
    condition, is external state: the input of that name, W521 once at its first use; the stub
    cell declares it and the rmot text parses. A name the program assigns stays native."""
    src = """DEF tend( )
WAIT FOR ( InPinzaAbierta == TRUE )
IF ((InPinzaAbierta==FALSE) OR (InPinza2Abierta==FALSE)) THEN
  $OUT[3] = TRUE
ENDIF
bDone = TRUE
WAIT FOR bDone
PULSE ( PaletCompleto, TRUE, 0.5 )
PULSE ( bDone, TRUE, 0.5 )
END
"""
    (tmp_path / "tend.src").write_text(src)
    doc = read_files([str(tmp_path / "tend.src")])
    stmts = [s for r in doc.routines for s in walk(r.body)]
    assert [s.cond.signal for s in stmts if isinstance(s, WaitIn)] == ["InPinzaAbierta"]
    branch = next(s for s in stmts if isinstance(s, If))
    assert [(c.signal, c.on) for c in branch.cond.parts] == [("InPinzaAbierta", False), ("InPinza2Abierta", False)]
    warned = [(d.span.start.line, d.message.split("`")[1]) for d in doc.diagnostics if d.code.id == "W521"]
    assert warned == [(2, "InPinzaAbierta"), (3, "InPinza2Abierta"), (8, "PaletCompleto")]
    # PULSE's signal is always an output (KSS 8.x PULSE): an undeclared name there is the output
    assert [(s.signal, s.seconds) for s in stmts if isinstance(s, Pulse)] == [("PaletCompleto", 0.5)]
    assert "PULSE ( bDone, TRUE, 0.5 )" in [s.text for s in stmts if isinstance(s, Native)]
    assert "WAIT FOR bDone" in [s.text for s in stmts if isinstance(s, Native)]
    out = tmp_path / "tend.rmot"
    result = CliRunner().invoke(cli, ["import", str(tmp_path / "tend.src"), "-o", str(out)])
    assert result.exit_code == 0, result.output
    assert not parse_text(out.read_text(), str(out)).diagnostics
    stub = (tmp_path / "tend_cell.rmot").read_text()
    assert 'io in[1] = "inpinzaabierta"' in stub and 'io in[2] = "inpinza2abierta"' in stub  # KRL names: any case
    assert 'io out[1] = "paletcompleto"' in stub


SPLINE_SRC = """DEF weld( )
$APO.CDIS = 1
SPTP P1 WITH $VEL_AXIS[1]=40, $VEL_AXIS[2]=40, $VEL_AXIS[3]=40, $VEL_AXIS[4]=40, $VEL_AXIS[5]=40, $VEL_AXIS[6]=40
SLIN P2 WITH $VEL.CP = 0.25, $APO.CDIS = 8 C_SPL
SLIN P2:{X 0,Y 0,Z 10.0,A 90.0,B 0,C 0}
SPTP P1 WITH $VEL_AXIS[1]=40, $VEL_AXIS[2]=20
SLIN P2 WITH $VEL.ORI1 = 100
PTP P1:{X 0,Y 0,Z 10.0,A 0,B 0,C 0}
LIN P2 C_DIS
END
"""

SPLINE_DAT = """DEFDAT weld
DECL E6POS P1={X 500.0,Y 0.0,Z 600.0,A 0.0,B 90.0,C 0.0,S 2,T 10}
DECL E6POS P2={X 600.0,Y 100.0,Z 400.0,A 10.0,B 20.0,C 30.0,S 2,T 10}
ENDDAT
"""


def test_with_values_and_the_geometric_operator(tmp_path: Path) -> None:
    """KSS 8.3: a spline motion's WITH values hold for that motion only ($VEL_AXIS all six equal
    → `speed 40 %`; $VEL.CP 0.25 m/s → 250 mm/s; $APO.CDIS 8 with C_SPL → zone 8 mm; after it
    the modal $APO.CDIS 1 again); `P2:{Z 10, A 90}` is P2 composed with that frame (P2 · F, the
    frame in P2's own axes), checked against scipy; a PTP to such a composition, different axis
    speeds, or another WITH variable stay native."""
    stmts, _ = _read(tmp_path, SPLINE_SRC, SPLINE_DAT)
    moves = [s for s in stmts if isinstance(s, Move)]
    assert (moves[0].kind, moves[0].joint_pct, moves[0].zone) == ("joint", 40.0, None)
    assert (moves[1].kind, moves[1].speed, moves[1].zone) == ("linear", 250.0, 8.0)
    assert moves[2].target.startswith("P2 * pose(") and moves[2].speed == 2000.0 and moves[2].zone is None
    assert moves[3].target == "P2" and moves[3].zone == 1.0  # the modal $APO.CDIS after the WITH
    natives = [s.text for s in stmts if isinstance(s, Native) and not s.text.startswith("$")]  # not the restated settings
    assert natives == ["SPTP P1 WITH $VEL_AXIS[1]=40, $VEL_AXIS[2]=20", "SLIN P2 WITH $VEL.ORI1 = 100",
                       "PTP P1:{X 0,Y 0,Z 10.0,A 0,B 0,C 0}"]
    p2 = Rotation.from_euler("ZYX", [10.0, 20.0, 30.0], degrees=True)
    frame = Rotation.from_euler("ZYX", [90.0, 0.0, 0.0], degrees=True)
    position = np.array([0.6, 0.1, 0.4]) + p2.apply([0.0, 0.0, 0.010])
    w, x, y, z = moves[2].pose.quaternion
    assert np.allclose(moves[2].pose.position, position, atol=1e-12)
    assert np.allclose(Rotation.from_quat([x, y, z, w]).as_matrix(), (p2 * frame).as_matrix(), atol=1e-12)
    out = tmp_path / "weld.rmot"
    assert CliRunner().invoke(cli, ["import", str(tmp_path / "mill.src"), "-o", str(out)]).exit_code == 0
    assert "move linear P2 * pose(x=0mm, y=0mm, z=10mm, q=(" in out.read_text()
    assert not parse_text(out.read_text(), str(out)).diagnostics


def test_home_from_the_config_dat_beside_the_program(tmp_path: Path) -> None:
    """`PTP HOME` reads XHOME of a $config.dat lying beside the .src (no shipped-value guess)."""
    (tmp_path / "$config.dat").write_text(CONFIG)
    (tmp_path / "go.src").write_text("DEF go( )\nPTP HOME\nEND\n")
    doc = read_files([str(tmp_path / "go.src")])
    assert next(t for t in doc.targets if t.name == "XHOME").joints == (10.0, -80.0, 70.0, 0.0, 20.0, 0.0)
    assert not any(d.code.id == "W511" for d in doc.diagnostics)


PARAMS_SRC = """DEF cell( )
Grip(2, TRUE)
Grip(nVar, TRUE)
END

DEF Grip(nStation:IN, bClose:IN)
INT nStation
BOOL bClose
SWITCH nStation
CASE 1, 2
  $OUT[10] = TRUE
CASE 3
  $OUT[11] = TRUE
DEFAULT
  $OUT[12] = TRUE
ENDSWITCH
IF bClose THEN
  $OUT[13] = TRUE
ENDIF
IF (nStation > 1) AND $IN[4] THEN
  Place(nStation)
ENDIF
WHILE nStation == 1
  WAIT SEC 1
ENDWHILE
END

DEF Place(n:IN)
REAL n
WAIT SEC 0.5
END
"""


def test_routine_parameters_switch_and_calls(tmp_path: Path) -> None:
    """A DEF's `:IN` parameters declared INT/REAL (number) or BOOL are the proc's parameters;
    `SWITCH` on one (KSS 8.x: the first CASE with a value equal to the selector runs, else
    DEFAULT) is an `if`/`else` chain, tests on them are decided by the compiler; a call with
    literal arguments (or the caller's parameters) is a call; a variable argument, or a WHILE on
    a parameter, stays native. The expected structure is written by hand from the KRL above;
    rmot's own parser accepts the imported text."""
    (tmp_path / "cell.src").write_text(PARAMS_SRC)
    doc = read_files([str(tmp_path / "cell.src")])
    grip = next(r for r in doc.routines if r.name == "Grip")
    assert grip.params == (("nStation", "number"), ("bClose", "bool"))
    chain = grip.body[0]
    assert isinstance(chain, If) and chain.cond.text == "nStation == 1 or nStation == 2"
    inner = chain.orelse[0]
    assert isinstance(inner, If) and inner.cond.text == "nStation == 3"
    assert [s.signal for s in inner.orelse] == [12]
    assert grip.body[1].cond.text == "bClose"
    test, level = grip.body[2].cond.parts
    assert isinstance(test, Conds) and test.text == "nStation > 1" and level == Cond(4, True)
    natives = [s.text for r in doc.routines for s in walk(r.body) if isinstance(s, Native)]
    assert natives == ["Grip(nVar, TRUE)", "WHILE nStation == 1", "WAIT SEC 1", "ENDWHILE"]
    out = tmp_path / "cell.rmot"
    assert CliRunner().invoke(cli, ["import", str(tmp_path / "cell.src"), "-o", str(out)]).exit_code == 0
    text = out.read_text()
    assert "proc Grip(nStation: number, bClose: bool) {" in text and "Grip(2, true)" in text
    assert "Place(nStation)" in text
    assert not parse_text(text, str(out)).diagnostics


def test_a_module_taking_parameters_is_a_proc(tmp_path: Path) -> None:
    """`DEF Job(nSt:IN)` as the module's own DEF: a routine other programs call (W522 at its
    line); the program body is empty and the proc keeps its parameter."""
    (tmp_path / "job.src").write_text("DEF Job(nSt:IN)\nINT nSt\nIF nSt == 2 THEN\n  $OUT[1] = TRUE\nENDIF\nEND\n")
    doc = read_files([str(tmp_path / "job.src")])
    assert doc.main == "" and doc.routines[0].params == (("nSt", "number"),)
    assert [d.span.start.line for d in doc.diagnostics if d.code.id == "W522"] == [1]
    out = tmp_path / "job.rmot"
    assert CliRunner().invoke(cli, ["import", str(tmp_path / "job.src"), "-o", str(out)]).exit_code == 0
    assert "proc Job(nSt: number) {" in out.read_text() and "if nSt == 2 {" in out.read_text()
    assert not parse_text(out.read_text(), str(out)).diagnostics


def test_inline_form_defaults_of_the_config_dat(tmp_path: Path) -> None:
    """`;FOLD PTP HOME CONT Vel=100 % DEFAULT`: the target XHOME and the approximation distance of
    PDEFAULT (APO_DIST 50 mm, typed below) are $config.dat's."""
    config = CONFIG.replace("ENDDAT", "DECL PDAT PDEFAULT={VEL 100.0,ACC 100.0,APO_DIST 50.0}\nENDDAT")
    (tmp_path / "$config.dat").write_text(config)
    (tmp_path / "go.src").write_text(
        "DEF go( )\n;FOLD PTP HOME CONT Vel=100 % DEFAULT;%{PE}\n$BWDSTART=FALSE\nPDAT_ACT=PDEFAULT\n"
        "FDAT_ACT=FHOME\nBAS(#PTP_PARAMS,100)\n$H_POS=XHOME\nPTP XHOME C_PTP\n;ENDFOLD\nEND\n")
    doc = read_files([str(tmp_path / "go.src")])
    move = next(s for s in doc.routines[0].body if isinstance(s, Move))
    assert (move.target_name, move.joints, move.zone, move.joint_pct) == (
        "XHOME", (10.0, -80.0, 70.0, 0.0, 20.0, 0.0), 50.0, 100.0)


def test_a_proc_keeps_its_local_variables_native(tmp_path: Path) -> None:
    """`DEF Job(n:IN)` with a local `INT k` it computes and tests: a proc has no variables in rmot
    (a `var` lives in the task's own body, E157), so the lines using `k` stay native and the
    imported proc compiles once something calls it (rmot's own checker is the witness)."""
    (tmp_path / "job.src").write_text("DEF Job(n:IN)\nINT n, k\nk = n + 1\nLIN {X 600, Y 0, Z 800, A 0, B 90, C 0}\n"
                                      "IF k > 2 THEN\n  $OUT[1] = TRUE\nENDIF\nEND\n")
    out = tmp_path / "job.rmot"
    assert CliRunner().invoke(cli, ["import", str(tmp_path / "job.src"), "-o", str(out)]).exit_code == 0
    text = out.read_text()
    assert "var " not in text and 'native krl "IF k > 2 THEN"' in text, text
    called = text.replace("\n}\n", "\n  move joint joints(0, -90, 90, 0, 0, 0) deg\n  Job(3)\n}\n", 1)
    assert called != text
    out.write_text(called)
    result = CliRunner().invoke(cli, ["check", str(out)])
    assert result.exit_code in (0, 1) and "error[" not in result.output, result.output


def test_a_routine_of_another_file_is_called_with_its_arguments(tmp_path: Path) -> None:
    """`job(3)` in main.src calls `DEF job(n:IN)` of job.src, given with it: the call is read with
    its argument (the proc runs, so its move is planned and verified), and the proc's motion takes
    its caller's `$VEL.CP` (a routine runs with the settings its caller left, KSS 8.x system
    variables), never the 2 m/s a program starts with after BAS(#INITMOV)."""
    (tmp_path / "main.src").write_text("DEF main( )\n$VEL.CP = 0.5\n$TOOL = $NULLFRAME\n$BASE = $NULLFRAME\n"
                                       "PTP {A1 0, A2 -90, A3 90, A4 0, A5 0, A6 0}\nLIN {X 500, Y 0, Z 800, A 0, B 90, C 0}\n"
                                       "job(3)\nEND\n")
    (tmp_path / "job.src").write_text("DEF job(n:IN)\nINT n\nLIN {X 600, Y 0, Z 800, A 0, B 90, C 0}\nEND\n")
    out = tmp_path / "main.rmot"
    result = CliRunner().invoke(cli, ["import", str(tmp_path / "main.src"), str(tmp_path / "job.src"), "-o", str(out)])
    assert result.exit_code == 0, result.output
    text = out.read_text()
    assert "\n  job(3)\n" in text and 'native krl "job(3)"' not in text, text
    proc_move = next(ln for ln in text.splitlines() if "x=600mm" in ln)
    assert "speed" not in proc_move, proc_move  # the caller's speed, not 2000 mm/s
    result = CliRunner().invoke(cli, ["check", str(out)])
    assert result.exit_code in (0, 1) and "error[" not in result.output, result.output
