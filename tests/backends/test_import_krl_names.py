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
from rmot.backends.readers.model import If, Move, Native, Pulse, SetOut, WaitIn, walk
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
    and its global BOOL (a variable: native); with the config read, a name declared nowhere is
    another module's variable, not an input."""
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
    assert [s.cond.signal for s in stmts if isinstance(s, WaitIn)] == [21]
    assert [s.signal for s in stmts if isinstance(s, SetOut)] == [22]
    assert [s.text for s in stmts if isinstance(s, Native)] == ["WAIT FOR bAutoRun", "WAIT FOR bUnknownFlag"]


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
END
"""
    (tmp_path / "tend.src").write_text(src)
    doc = read_files([str(tmp_path / "tend.src")])
    stmts = [s for r in doc.routines for s in walk(r.body)]
    assert [s.cond.signal for s in stmts if isinstance(s, WaitIn)] == ["InPinzaAbierta"]
    branch = next(s for s in stmts if isinstance(s, If))
    assert [(c.signal, c.on) for c in branch.cond.parts] == [("InPinzaAbierta", False), ("InPinza2Abierta", False)]
    warned = [(d.span.start.line, d.message.split("`")[1]) for d in doc.diagnostics if d.code.id == "W521"]
    assert warned == [(2, "InPinzaAbierta"), (3, "InPinza2Abierta")]
    assert "WAIT FOR bDone" in [s.text for s in stmts if isinstance(s, Native)]
    out = tmp_path / "tend.rmot"
    result = CliRunner().invoke(cli, ["import", str(tmp_path / "tend.src"), "-o", str(out)])
    assert result.exit_code == 0, result.output
    assert not parse_text(out.read_text(), str(out)).diagnostics
    stub = (tmp_path / "tend_cell.rmot").read_text()
    assert 'io in[1] = "inpinzaabierta"' in stub and 'io in[2] = "inpinza2abierta"' in stub  # KRL names: any case
