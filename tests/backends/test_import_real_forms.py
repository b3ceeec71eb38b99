"""Forms real pendant and PolyScope files use that rmot's own output never does, read back:
Fanuc `DO[n]=(ON)`, `WAIT (DI[n])`, cm/min and inch/min feedrates, motion options kept after
the move (W517), point-logic lines and multi-group positions; URScript `while True:` read as
one cycle (W518), `get_inverse_kin(P, qnear=Q)` and `pose_trans(P, p[..])`.

Witnesses: the hand-written lines below follow the R-30iB Operator's Manual (feedrate units:
1 cm/min = 10/60 mm/s, 1 inch/min = 25.4/60 mm/s) and the URScript manual (pose_trans: the
offset is in the first pose's frame); expected values are computed here from those rules.
"""

from __future__ import annotations

import re
from pathlib import Path

from click.testing import CliRunner

from rmot.backends.readers import read_files, span_of
from rmot.backends.readers.model import For, If, Move, Native, SetOut, WaitIn, walk
from rmot.backends.readers.writer import stub_warnings
from rmot.compiler.cli import cli
from rmot.lang.parse import parse_text

TP = """/PROG  DEMO
/ATTR
OWNER\t\t= MNEDITOR;
/MN
   1:  UFRAME_NUM=0 ;
   2:  UTOOL_NUM=1 ;
   3:  DO[5]=(ON) ;
   4:  WAIT (DI[7])    ;
   5:  WAIT (!DI[8])    ;
   6:L P[1] 240cm/min CNT100 COORD PTH    ;
   7:L P[1] 60inch/min FINE TB   .10sec,DO[3]=ON    ;
      1:  DO[4]=(OFF) ;
       ------ ;
   8:L P[1] 100mm/sec FINE Tool_Offset,PR[15]    ;
/POS
P[1]{
   GP1:
\tUF : 0, UT : 1,\t\tCONFIG : 'N U T, 0, 0, 0',
\tX =   100.000  mm,\tY =   200.000  mm,\tZ =   300.000  mm,
\tW =   180.000 deg,\tP =     0.000 deg,\tR =     0.000 deg
   GP2:
\tUF : 0, UT : 1,
\tJ1=  1500.000  mm
};
/END
"""


def _stmts(path: Path) -> list[object]:
    doc = read_files([str(path)])
    return [s for r in doc.routines for s in walk(r.body)]


def test_fanuc_pendant_forms(tmp_path: Path) -> None:
    path = tmp_path / "demo.ls"
    path.write_text(TP)
    stmts = _stmts(path)
    outs = [s for s in stmts if isinstance(s, SetOut)]
    assert [(s.signal, s.value) for s in outs] == [(5, 1.0), (3, 1.0), (4, 0.0)]
    waits = [s for s in stmts if isinstance(s, WaitIn)]
    assert [(w.cond.signal, w.cond.on) for w in waits] == [(7, True), (8, False)]
    moves = [s for s in stmts if isinstance(s, Move)]
    assert len(moves) == 2  # the Tool_Offset move stays native (the register is the controller's)
    assert abs(moves[0].speed - 240 * 10 / 60) < 1e-9 and moves[0].zone == 100.0
    assert abs(moves[1].speed - 60 * 25.4 / 60) < 1e-9
    assert moves[0].pose is not None and abs(moves[0].pose.position[2] - 0.3) < 1e-12  # GP1, not GP2's J1
    natives = [s.text for s in stmts if isinstance(s, Native)]
    # neither option can stand on its own line (axes.py reads COORD with the move where it can)
    assert natives[:2] == ["!COORD ;", "!PTH ;"] and natives[-1].startswith("L P[1] 100mm/sec")


def test_fanuc_option_warnings_are_located(tmp_path: Path) -> None:
    path = tmp_path / "demo.ls"
    path.write_text(TP)
    doc = read_files([str(path)])
    w517 = [d for d in doc.diagnostics if d.code.id == "W517"]
    assert [d.span.start.line for d in w517] == [10, 10, 11]


SCRIPT = """def Prog():
  global W1_p=p[.4, -.2, .3, 0, 3.14159265358979, 0]
  global W1_q=[0, -1.57, 1.57, -1.57, -1.57, 0]
  while (True):
    movej(get_inverse_kin(W1_p, qnear=W1_q), a=1.4, v=1.05)
    movel(pose_trans(W1_p, p[0, 0, -0.05, 0, 0, 0]), a=1.2, v=0.25)
    set_standard_digital_out(2, True)
  end
end
"""


def test_polyscope_program(tmp_path: Path) -> None:
    path = tmp_path / "prog.script"
    path.write_text(SCRIPT)
    doc = read_files([str(path)])
    stmts = [s for r in doc.routines for s in walk(r.body)]
    assert not any(isinstance(s, Native) for s in stmts)
    moves = [s for s in stmts if isinstance(s, Move)]
    assert moves[0].target == "W1_p" and moves[0].kind == "joint"
    assert moves[1].target == "W1_p * pose(z=-50mm)"  # along the pose's own z (pose_trans)
    assert [d.code.id for d in doc.diagnostics] == ["W518", "W546"]  # W546: no set_tcp before the first move
    assert doc.diagnostics[0].span.start.line == 4 and doc.diagnostics[1].span.start.line == 5


KRL = """DEF demo( )
$VEL.CP = 0.2
$APO.CDIS = 2.0
$TOOL = {FRAME: X 0.000,Y 0.000,Z 150.000,A 0.000,B 0.000,C 0.000}
$BASE = {FRAME: X 0.000,Y 0.000,Z 0.000,A 0.000,B 0.000,C 0.000}
PTP HOME
LIN {X 500.000,Y -100.000,Z 400.000,A 180.000,B 0.000,C 180.000}
LIN_REL {Z 50} C_DIS
LIN_REL {X 10} #TOOL
LIN_REL {Z 5}
IF $IN[1] THEN
LIN_REL {Z 5}
ENDIF
PTP XHOME
END
"""


def test_krl_hand_and_robodk_forms(tmp_path: Path) -> None:
    """KSS 8.x: `PTP HOME` goes to $config.dat's XHOME (shipped {A1 0, A2 -90, A3 90, ..}), a
    `$TOOL = {FRAME: ..}` written in the program is a tool of that TCP, LIN_REL moves from where
    the last move ended (in the base, or with #TOOL in the tool frame)."""
    path = tmp_path / "demo.src"
    path.write_text(KRL)
    doc = read_files([str(path)])
    stmts = [s for r in doc.routines for s in walk(r.body)]
    moves = [s for s in stmts if isinstance(s, Move)]
    assert moves[0].target == "HOME" and moves[-1].target == "HOME"
    home = next(t for t in doc.targets if t.name == "HOME")
    assert home.joints == (0.0, -90.0, 90.0, 0.0, 0.0, 0.0)
    lit = moves[1].target
    assert moves[2].target == f"shift({lit}, z=50mm)" and moves[2].zone == 2.0
    assert moves[3].target == f"shift({lit}, z=50mm) * pose(x=10mm)"
    assert moves[4].target == f"shift(shift({lit}, z=50mm) * pose(x=10mm), z=5mm)"
    natives = [s.text for s in stmts if isinstance(s, Native)]
    assert natives == ["LIN_REL {Z 5}"]  # where a block starts the robot's place is not known
    tool = next(t for t in doc.tools if t.name == moves[1].tool)
    assert abs(tool.tcp.position[2] - 0.15) < 1e-12 and moves[1].frame == "base"
    assert sum(d.code.id == "W511" and "XHOME" in d.message for d in doc.diagnostics) == 1


def test_urscript_function_with_parameters(tmp_path: Path) -> None:
    """A function with parameters is a proc (parameters declared `number`, W519, a keyword
    renamed); its lines that do not use a parameter are read, the others stay native."""
    path = tmp_path / "lib.script"
    path.write_text("def blink(port, time=0.5):\n  set_standard_digital_out(3, True)\n  sleep(0.2)\n"
                    "  set_standard_digital_out(port, False)\nend\n")
    doc = read_files([str(path)])
    proc = next(r for r in doc.routines if r.name == "blink")
    assert proc.params == (("port", "number"), ("time", "number"))
    assert [type(s).__name__ for s in proc.body] == ["SetOut", "Wait", "Native"]
    assert [d.code.id for d in doc.diagnostics].count("W519") == 1
    out = tmp_path / "lib.rmot"
    from click.testing import CliRunner

    from rmot.compiler.cli import cli
    result = CliRunner().invoke(cli, ["import", str(path), "-o", str(out)])
    assert result.exit_code == 0 and "proc blink(port: number, time_: number)" in out.read_text(), result.output
    checked = CliRunner().invoke(cli, ["check", str(out)])
    assert checked.exit_code == 0, checked.output


def test_krl_bas_tool_and_base(tmp_path: Path) -> None:
    """KSS BAS.SRC: `BAS(#TOOL, n)` / `BAS(#BASE, n)` select TOOL_DATA[n] / BASE_DATA[n] (data of
    $config.dat: the stub puts them at identity, W511 at the line where it is written), BASE 0 the
    robot base."""
    path = tmp_path / "bas.src"
    path.write_text("DEF bas( )\nBAS (#TOOL,2)\nBAS (#BASE,0)\nPTP {A1 0,A2 -90,A3 90,A4 0,A5 0,A6 0}\n"
                    "BAS (#BASE,3)\nPTP {A1 5,A2 -90,A3 90,A4 0,A5 0,A6 0}\nEND\n")
    doc = read_files([str(path)])
    moves = [s for r in doc.routines for s in walk(r.body) if isinstance(s, Move)]
    assert [(m.tool, m.frame) for m in moves] == [("tool2", "base"), ("tool2", "base3")]
    assert {t.controller for t in doc.tools} | {f.controller for f in doc.frames} == {
        "TOOL_DATA[2] of $config.dat", "BASE_DATA[3] of $config.dat"}
    stubbed = stub_warnings(doc, span_of)
    assert {d.span.start.line for d in stubbed if d.code.id == "W511" and d.span is not None} == {2, 5}
    assert not any(isinstance(s, Native) for r in doc.routines for s in walk(r.body))


def test_inform_base_positions_and_nwait(tmp_path: Path) -> None:
    """A RoboDK-style job: `///POSTYPE BASE` positions are in the base (the `///USER n` before
    them applies to POSTYPE USER only), `NWAIT` is read with W517 at its line."""
    path = tmp_path / "PROG1.JBI"
    path.write_text("/JOB\n//NAME PROG1\n//POS\n///NPOS 2,0,0,0,0,0\n///USER 1\n///TOOL 1\n///POSTYPE BASE\n"
                    "///RECTAN\n///RCONF 1,0,0,0,0,0,0,0\nC00000=400.000,0.000,300.000,180.0000,0.0000,0.0000\n"
                    "C00001=400.000,100.000,300.000,180.0000,0.0000,0.0000\n//INST\n///DATE 2024/01/10 10:00\n"
                    "///ATTR SC,RW\n///GROUP1 RB1\nNOP\nMOVJ C00000 VJ=50.00\nMOVL C00001 V=111.1 PL=0 NWAIT\n"
                    "DOUT OT#(1) ON\nEND\n")
    doc = read_files([str(path)])
    moves = [s for r in doc.routines for s in walk(r.body) if isinstance(s, Move)]
    assert [(m.frame, m.speed) for m in moves] == [("base", None), ("base", 111.1)]
    assert [(d.code.id, d.span.start.line) for d in doc.diagnostics] == [("W517", 18)]


def test_val3_refuses_xml_with_entities(tmp_path: Path) -> None:
    """A VAL3 file is data: XML with a DOCTYPE (entity expansion) is a located E510, never parsed."""
    path = tmp_path / "start.pgx"
    path.write_text('<?xml version="1.0"?>\n<!DOCTYPE p [<!ENTITY a "aaaa">]>\n<Programs><Program name="start">'
                    "<Code>begin\nend</Code></Program></Programs>\n")
    from click.testing import CliRunner

    from rmot.compiler.cli import cli
    result = CliRunner().invoke(cli, ["import", str(path), "-o", str(tmp_path / "x.rmot")])
    assert result.exit_code == 2 and f"{path}:1:1: error[E510]" in result.output, result.output


def test_val3_project_naming_no_program(tmp_path: Path) -> None:
    """A `.pjx` that names no `.pgx` (or only paths outside its folder) is a located E510."""
    path = tmp_path / "app.pjx"
    path.write_text('<Project><Programs><Program file="../../etc/start.pgx" /></Programs></Project>\n')
    from click.testing import CliRunner

    from rmot.compiler.cli import cli
    result = CliRunner().invoke(cli, ["import", str(path), "-o", str(tmp_path / "x.rmot")])
    assert result.exit_code == 2 and f"{path}:1:1: error[E510]" in result.output, result.output


POLYSCOPE_EXPORT = """def prog():
  set_tcp(p[0.0,0.0,0.15,0.0,0.0,0.0])
  set_target_payload(1.200000, [0.000000, 0.000000, 0.050000], [0.0, 0.0, 0.0, 0.0, 0.0, 0.0])
  step_count_1 = 0.0
  thread Step_Counter_Thread_1():
    while (True):
      step_count_1 = step_count_1 + 1.0
      sync()
    end
  end
  run Step_Counter_Thread_1()
  global Waypoint_1_p=p[.4, -.2, .3, 0, 3.14159265358979, 0]
  global Waypoint_1_q=[0, -1.57, 1.57, -1.57, -1.57, 0]
  while (True):
    $ 1 "Robot Program"
    $ 2 "MoveJ"
    movej(get_inverse_kin(Waypoint_1_p, qnear=Waypoint_1_q), a=1.3962634015954636, v=1.0471975511965976)
    $ 3 "Wait digital_in[3]=HI"
    while (not(get_standard_digital_in(3) == True)):
      sync()
    end
    $ 4 "If digital_in[1]≟False"
    if (get_standard_digital_in(1) == False):
      $ 5 "Set DO[2]=On"
      set_standard_digital_out(2, True)
    end
    while (not(get_configurable_digital_in(0))):
      sync()
    end
  end
end
"""


def test_polyscope_export_with_step_counter(tmp_path: Path) -> None:
    """A PolyScope export: the step-counter thread runs its own `while (True):`, so the program's
    `while (True):` is still the outermost loop of the program (read as one cycle); PolyScope's
    wait `while (not(get_standard_digital_in(n) == True)): sync() end` waits for the input (URScript
    manual: sync() ends the physical time step); an `if (...)` in parentheses reads its input;
    set_target_payload right after set_tcp is the tool's load like set_payload."""
    path = tmp_path / "prog.script"
    path.write_text(POLYSCOPE_EXPORT)
    doc = read_files([str(path)])
    stmts = [s for r in doc.routines for s in walk(r.body)]
    assert [s.target for s in stmts if isinstance(s, Move)] == ["Waypoint_1_p"]
    waits = [s for s in stmts if isinstance(s, WaitIn)]
    assert [(w.cond.signal, w.cond.on) for w in waits] == [(3, True), (0 + 8, True)]
    assert [(s.signal, s.value) for s in stmts if isinstance(s, SetOut)] == [(2, 1.0)]
    assert [(s.cond.signal, s.cond.on) for s in stmts if isinstance(s, If)] == [(1, False)]
    natives = [s.text for s in stmts if isinstance(s, Native)]
    assert natives[0] == "step_count_1 = 0.0" and not any("while (True)" == n for n in natives[5:])
    assert [d.span.start.line for d in doc.diagnostics if d.code.id == "W518"] == [14]
    tool = doc.tools[0]
    assert abs(tool.mass - 1.2) < 1e-12 and abs(tool.tcp.position[2] - 0.15) < 1e-12


ROBODK_UR = """def Prog1():
  global speed_ms    = 0.300
  global accel_mss   = 3.000
  global blend_radius_m = 0.001
  def Sub():
    movel(p[0.5, 0, 0.3, 0, 3.14159265358979, 0],accel_mss,speed_ms,0,0)
  end
  set_tcp(p[0.000000, 0.000000, 0.150000, 0.000000, 0.000000, 0.000000])
  speed_ms    = 0.250
  movel(p[0.4, -0.1, 0.3, 0, 3.14159265358979, 0],accel_mss,speed_ms,0,blend_radius_m)
  movec(p[0.45, -0.05, 0.3, 0, 3.14159265358979, 0],p[0.5, -0.1, 0.3, 0, 3.14159265358979, 0],accel_mss,speed_ms,0)
  Sub()
end
"""


def test_robodk_positional_arguments_and_variables(tmp_path: Path) -> None:
    """RoboDK's UR post writes `movel(p[..],accel_mss,speed_ms,0,blend_radius_m)`: positional
    arguments in the URScript manual's order (movel(pose, a, v, t, r), movec(via, to, a, v, r)),
    values held in variables set in straight-line code. In a sub-routine a variable the program
    sets more than once is not certain (it depends on the call): that move stays native."""
    path = tmp_path / "prog.script"
    path.write_text(ROBODK_UR)
    stmts = _stmts(path)
    moves = [s for s in stmts if isinstance(s, Move)]
    assert [(m.kind, m.speed, m.accel, m.zone) for m in moves] == [
        ("linear", 0.250 * 1000, 3.000 * 1000, 0.001 * 1000), ("circular", 0.250 * 1000, 3.000 * 1000, None)]
    natives = [s.text for s in stmts if isinstance(s, Native)]
    assert any(n.startswith("movel(p[0.5") for n in natives)  # speed_ms is set twice


POLYSCOPE_LOOP = """def Untitled():
  while (True):
    $ 8 "Wait DI[0]=HI"
    while (get_standard_digital_in(0) == False):
      sync()
    end
    $ 9 "Loop 3 times"
    Loop_1 = 0
    while (Loop_1 < 3):
      movel(p[-0.1439, -0.4356, 0.1020, -0.0012, 3.1162, 0.0388], a=1.2, v=0.25)
      Loop_1 = Loop_1 + 1
    end
  end
end
"""


def test_polyscope_wait_and_counted_loop(tmp_path: Path) -> None:
    """PolyScope's `while (get_standard_digital_in(0) == False): sync() end` loops while the input
    is off: it waits for it on; its "Loop 3 times" (`Loop_1 = 0`, `while (Loop_1 < 3):`, ..,
    `Loop_1 = Loop_1 + 1`) runs the body for Loop_1 = 0, 1, 2."""
    path = tmp_path / "prog.script"
    path.write_text(POLYSCOPE_LOOP)
    stmts = _stmts(path)
    assert not any(isinstance(s, Native) for s in stmts)
    waits = [s for s in stmts if isinstance(s, WaitIn)]
    assert [(w.cond.signal, w.cond.on) for w in waits] == [(0, True)]
    loops = [s for s in stmts if isinstance(s, For)]
    assert [(f.var, f.first, f.stop) for f in loops] == [("Loop_1", 0, 3)]
    assert len(range(loops[0].first, loops[0].stop)) == 3


PROCESS_MOVES = """def glue():
  set_digital_out(2, True)
  movep(p[0.4, 0.1, 0.3, 0, 3.14159265358979, 0], a=1.2, v=0.1, r=0.005)
  movep(p[0.5, 0.1, 0.3, 0, 3.14159265358979, 0], 1.2, 0.05, 0.002)
  set_digital_out(2, False)
  set_digital_out(9, True)
end
"""


def test_process_moves_and_the_old_output_name(tmp_path: Path) -> None:
    """`movep(pose, a, v, r)` (URScript manual, module motion: move process, linear in tool space
    at the constant tool speed v, blended with radius r) is a linear move at v with zone r;
    positional arguments in the manual's order. `set_digital_out(n, b)`, the deprecated name of
    set_standard_digital_out, sets standard output n for n in 0..7; output 9 is outside that
    range and stays native."""
    path = tmp_path / "glue.script"
    path.write_text(PROCESS_MOVES)
    stmts = _stmts(path)
    moves = [s for s in stmts if isinstance(s, Move)]
    assert [(m.kind, m.speed, m.zone) for m in moves] == [
        ("linear", 0.1 * 1000, 0.005 * 1000), ("linear", 0.05 * 1000, 0.002 * 1000)]
    outs = [s for s in stmts if isinstance(s, SetOut)]
    assert [(s.signal, s.value) for s in outs] == [(2, 1.0), (2, 0.0)]
    natives = [s for s in stmts if isinstance(s, Native)]
    assert [n.text for n in natives] == ["set_digital_out(9, True)"]
    assert natives[0].where.line == 6


KRC4_SPLINE = """DEF glue( )
$VEL.CP = 0.2
$APO.CDIS = 5
SLIN {X 500, Y 0, Z 600, A 0, B 90, C 0} C_SPL
SPLINE
  SLIN {X 500, Y 0, Z 500, A 0, B 90, C 0}
  SCIRC {X 550, Y 50, Z 500, A 0, B 90, C 0}, {X 500, Y 100, Z 500, A 0, B 90, C 0}
ENDSPLINE C_SPL
SPLINE
  SPL {X 600, Y 100, Z 500, A 0, B 90, C 0}
ENDSPLINE
SPTP {A1 0, A2 -90, A3 90, A4 0, A5 0, A6 0} C_SPL
END
"""


def test_krl_spline_single_motions_and_blocks(tmp_path: Path) -> None:
    """KSS 8.3 (System Integrators, spline motions): `SLIN .. C_SPL` is approximated by $APO.CDIS
    (5 mm here); a SPLINE block passes exactly through its points, so one of SLIN/SCIRC segments
    is linear/circular moves without zone, the last blended by `ENDSPLINE C_SPL`; a block with an
    SPL segment (a spline curve) stays native line by line, located; SPTP C_SPL stays native."""
    path = tmp_path / "glue.src"
    path.write_text(KRC4_SPLINE)
    stmts = _stmts(path)
    moves = [s for s in stmts if isinstance(s, Move)]
    assert [(m.kind, m.speed, m.zone) for m in moves] == [
        ("linear", 0.2 * 1000, 5.0), ("linear", 200.0, None), ("circular", 200.0, 5.0)]
    natives = [s for s in stmts if isinstance(s, Native)]
    assert [(n.text.split()[0], n.where.line) for n in natives] == [
        ("SPLINE", 9), ("SPL", 10), ("ENDSPLINE", 11), ("SPTP", 12)]


KRC2_CELL_LOOP = """DEF cycle( )
BAS (#INITMOV,0 )
LOOP
  WAIT FOR $IN[21]==TRUE
  $OUT[3]=TRUE
  PTP {A1 0, A2 -90, A3 90, A4 0, A5 0, A6 0}
  sub()
ENDLOOP
END
DEF sub( )
LOOP
  $OUT[4]=TRUE
ENDLOOP
END
"""

FUNCTIONS_ONLY = """&ACCESS RVP
DEFFCT INT rpm(tool :IN)
  INT tool
  RETURN tool * 100
ENDFCT
"""


def test_krl_outermost_loop_is_one_cycle_and_function_modules(tmp_path: Path) -> None:
    """A pendant program's main `LOOP .. ENDLOOP` (KSS 8.x: an endless loop, left only by EXIT)
    is the cycle the controller repeats: its body is read as one cycle of the program, W518 at
    the LOOP line. A LOOP in a called routine is `while on` (neither ends); one with an EXIT
    rmot cannot place stays native. A module of functions only (`DEFFCT`) imports (its functions kept as a
    comment) instead of being refused."""
    path = tmp_path / "cycle.src"
    path.write_text(KRC2_CELL_LOOP)
    doc = read_files([str(path)])
    main, sub = doc.routines
    assert [type(s).__name__ for s in main.body] == ["Native", "WaitIn", "SetOut", "Move", "Call"]  # BAS kept
    # a LOOP in a called routine never ends, nor does the routine: `while on { }` says the same
    assert [(type(s).__name__, s.cond.text, [type(b).__name__ for b in s.body]) for s in sub.body  # type: ignore[union-attr]
            ] == [("While", "on", ["SetOut"])]
    assert any(d.code.id == "W518" and d.span.start.line == 3 for d in doc.diagnostics)
    exit_path = tmp_path / "exit.src"
    exit_path.write_text(KRC2_CELL_LOOP.replace("  sub()\n", "  EXIT\n"))
    assert isinstance(read_files([str(exit_path)]).routines[0].body[1], Native)
    fct = tmp_path / "rpm.src"
    fct.write_text(FUNCTIONS_ONLY)
    assert read_files([str(fct)]).routines == ()


KRC2_CONDITIONS = """DEF cell( )
WAIT FOR $IN[18] AND $IN[19] AND NOT $IN[25]
IF ($IN[1] AND $IN[2]) OR ($IN[3]==FALSE) THEN
  $OUT[3]=TRUE
ENDIF
WAIT FOR $IN[18] AND $IN[19]==FALSE
END
"""


def test_krl_combined_input_conditions(tmp_path: Path) -> None:
    """KRL conditions over several inputs (KSS 8.x operator priority: NOT, then AND, then OR;
    comparisons last, so `$IN[18] AND $IN[19]==FALSE` compares the AND and stays native) are
    rmot's `and`/`or`/`not` conditions; the rmot text is checked by rmot's own parser."""
    path = tmp_path / "cell.src"
    path.write_text(KRC2_CONDITIONS)
    doc = read_files([str(path)])
    body = doc.routines[0].body
    assert isinstance(body[0], WaitIn) and isinstance(body[1], If) and isinstance(body[2], Native)
    out = tmp_path / "cell.rmot"
    assert CliRunner().invoke(cli, ["import", str(path), "-o", str(out)]).exit_code == 0
    text = out.read_text()
    assert "wait until in[18] == on and in[19] == on and in[25] == off" in text
    assert "if (in[1] == on and in[2] == on) or in[3] == off {" in text
    assert not parse_text(text, str(out)).diagnostics


PULSE_JOB = """/JOB
//NAME P1
//POS
///NPOS 1,0,0,0,0,0
///TOOL 0
///POSTYPE PULSE
///PULSE
C00000=1000,0,0,0,0,0
//INST
///DATE 2020/01/01 00:00
///ATTR SC,RW
///GROUP1 RB1
NOP
MOVJ C00000 VJ=50.00
END
"""


def test_inform_pulse_position_move_names_why_it_stays_native(tmp_path: Path) -> None:
    """A move to a `///PULSE` position (encoder counts: INFORM manual, position data) off the
    zero needs the arm's pulses per degree, which the library does not hold: the move stays
    native, W510 at its line names the position and why."""
    path = tmp_path / "P1.JBI"
    path.write_text(PULSE_JOB)
    doc = read_files([str(path)])
    assert [s.text for s in doc.routines[0].body if isinstance(s, Native)] == ["MOVJ C00000 VJ=50.00"]
    w510 = [d for d in doc.diagnostics if d.code.id == "W510"]
    assert len(w510) == 1 and w510[0].span.start.line == 14 and "C00000 is a pulse position" in w510[0].message


POINT_LOGIC = """/PROG  PSPS
/ATTR
DEFAULT_GROUP\t= 1,*,*,*,*;
/MN
   1:  UFRAME_NUM=0 ;
   2:  UTOOL_NUM=1 ;
   3:J P[1] 100% CNT0 ACC100 TB    .10sec,P-SPS    ;
      1:  DO[23]=OFF ;
      2:  WAIT (DI[23])    ;
       ------ ;
   4:L P[1] 100mm/sec FINE PTH ;
/POS
P[1]{
   GP1:
\tUF : 0, UT : 1,\t\tCONFIG : 'N U T, 0, 0, 0',
\tX =   500.000  mm,\tY =     0.000  mm,\tZ =   500.000  mm,
\tW =   180.000 deg,\tP =     0.000 deg,\tR =     0.000 deg
};
/END
"""


def test_a_timed_point_logic_option_compiles_back_as_a_comment(tmp_path: Path) -> None:
    """A TP motion option is part of its motion instruction (R-30iB Operator's Manual, "Motion
    option instructions"): `TB .10sec,P-SPS` (a VASS point-logic block) or `PTH` written alone
    on a line would not load. Kept after the move as a TP comment, the compiled program carries
    it as one; the point logic's lines are read after the move."""
    (tmp_path / "psps.ls").write_text(POINT_LOGIC)
    result = CliRunner().invoke(cli, ["import", str(tmp_path / "psps.ls"), "-o", str(tmp_path / "psps.rmot")],
                                catch_exceptions=False)
    assert result.exit_code == 0, result.output
    program = (tmp_path / "psps.rmot").read_text()
    assert 'native fanuc "!TB .10sec,P-SPS ;"' in program and 'native fanuc "!PTH ;"' in program
    assert program.index("!TB .10sec") < program.index("set out[23] = off") < program.index("wait until in[23]")
    assert "as a comment (a TP motion option cannot stand on its own line)" in result.output
    result = CliRunner().invoke(cli, ["compile", str(tmp_path / "psps.rmot"), "--target", "fanuc", "-o",
                                      str(tmp_path / "out")], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    main = (tmp_path / "out" / "fanuc" / "PSPS.ls").read_text().split("/MN")[1].split("/POS")[0]
    assert re.search(r"^\s*\d+:\s*!TB \.10sec,P-SPS ;$", main, re.M) and re.search(r"^\s*\d+:\s*!PTH ;$", main, re.M)
    assert not re.search(r"^\s*\d+:\s*(?:TB|TA|DB|PTH)\b", main, re.M), main
