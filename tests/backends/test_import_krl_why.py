"""Why a KRL motion stays native: the W510 warning names what is known only at run time.

The module below imitates forms found in public KRL programs: `IF ($T1 OR $T2) THEN` and
`PTP $POS_ACT` (HugoDanielson/KukaMiling, Main.src; `SPTP $AXIS_ACT`, Naqiu06 honai.src;
`IF $OUT[99]==FALSE`, Aleynikovich Programas2Tornos m72x860.src; `WAIT FOR permission OR
($MODE_OP == #T1)`, Aleynikovich Libraries IOLib.src; `WAIT SEC tiempoSecado`, Aleynikovich
Work C2_CicloCompleto.src; `LIN_REL {X 150}#TOOL` after a move not read, KukaMiling
getSearchPoint.src), a FRAME array declared in the
.dat without values and a C_PTP with no `$APO.CPTP` set before it (KukaMiling
Jobs/St1_Job1_Side1), a position the program assigns (`POS_A = PUNTO[n]`, ingeniado CAJA_G
caja_g_m1), a point chosen by a loop variable (`xInsideWall[iWall]`, khrzysio Sub_MillLeaf),
inline forms with a velocity variable (`Vel=ptpM % DEFAULT`, ingeniado), a motion data set
declared nowhere (`DATWork`, KukaMiling Moves) and a KSS 8 point without its .dat entry (Bugaj32
podprogramy, `Tool[1]:TOOL_DATA[1]`).
KUKA's meaning (KSS 8.x Operating and Programming Instructions for System Integrators): a data
object keeps its data-list value only until a statement assigns it; `$POS_ACT`/`$AXIS_ACT` are
the current position; `$T1`, `$T2`, `$AUT`, `$EXT`, `$MODE_OP` the operating mode; C_PTP/C_DIS
blend by `$APO.CPTP`/`$APO.CDIS`; an inline form's point P is XP in a data list, its motion data
PDAT/LCPDAT there too.

Witness: the expected reason of each line is written by hand from the module's text, and its
line number is found by searching the text, not from the reader.
"""

from __future__ import annotations

from pathlib import Path

from krl_imported import imported_krl

SRC = """DEF cell( )
   DECL INT n, iWall
   DECL E6POS POS_A
   n = 1
   IF $IN[1] THEN
      PTP $POS_ACT
   ENDIF
   IF ($T1 OR $T2) THEN
      BAS(#INITMOV,0)
   ENDIF
   SPTP $AXIS_ACT
   IF $OUT[99]==FALSE THEN
      WAIT SEC 0.5
   ENDIF
   WAIT FOR permission OR ($MODE_OP == #T1)
   WAIT SEC tiempoSecado
   LIN_REL {X 150} #TOOL
   PTP lfPrePos[1] C_PTP
   LIN lfWorkPos[1]
   POS_A = PUNTO[n]
   LIN POS_A
   FOR iWall = 1 TO 4
      LIN xInsideWall[iWall]
   ENDFOR
   LIN xNowhere
;FOLD PTP HOME CONT Vel=ptpM % DEFAULT;%{PE}%R 5.2.21,%MKUKATPBASIS,%CMOVE,%VPTP,%P 1:PTP, 2:HOME, 3:C_PTP, 5:ptpM, 7:DEFAULT
   PTP XHOME C_PTP
;ENDFOLD
;FOLD PTP P5 CONT Vel= 100 % DATWork Tool[1] Base[0];%{PE}%R 5.4.35,%MKUKATPBASIS,%CMOVE,%VPTP,%P 1:PTP, 2:P5, 3:C_PTP, 5:100, 7:DATWork
   PTP XP5 C_PTP
;ENDFOLD
;FOLD SLIN P2 Vel=0.2 m/s CPDAT4 Tool[1]:TOOL_DATA[1] Base[1]:BASE_DATA[1] ;%{PE}
   SLIN XP2 WITH $VEL = SVEL_CP(0.2, , LCPDAT4), $TOOL = STOOL2(FP2), $BASE = SBASE(FP2.BASE_NO)
;ENDFOLD
   LIN XP5
END
"""

DAT = """DEFDAT cell
DECL FRAME lfPrePos[3]
lfPrePos[1]={X -150.000,Y 0.0,Z 150.000,A 0.0,B 0.0,C 0.0}
DECL FRAME lfWorkPos[12]
DECL E6POS XP5={X 600.0,Y 0.0,Z 800.0,A 0.0,B 90.0,C 0.0,S 2,T 35,E1 0.0,E2 0.0,E3 0.0,E4 0.0,E5 0.0,E6 0.0}
DECL FDAT FP5={TOOL_NO 1,BASE_NO 0,IPO_FRAME #BASE}
DECL E6POS PUNTO[2]
ENDDAT
"""

REASONS = {
    "PTP $POS_ACT": "`$POS_ACT` is where the robot stands when the line runs: known only at run time",
    "IF ($T1 OR $T2) THEN": "this IF tests the operating mode ($T1, $T2, $AUT, $EXT, $MODE_OP): a pendant setting",
    "BAS(#INITMOV,0)": "this IF tests the operating mode",
    "WAIT FOR permission": "this WAIT tests the operating mode ($T1, $T2, $AUT, $EXT, $MODE_OP)",
    "WAIT SEC tiempoSecado": "the time `tiempoSecado` is a variable: known only at run time",
    "LIN_REL {X 150} #TOOL": "a relative motion starts where the last motion ended, not known here",
    "SPTP $AXIS_ACT": "`$AXIS_ACT` is where the robot stands when the line runs",
    "PTP lfPrePos[1] C_PTP": "C_PTP blends by $APO.CPTP, which no line before it sets",
    "LIN lfWorkPos[1]": "`lfWorkPos[1]` is declared without a value: it is set at run time",
    "LIN POS_A": "`POS_A` is assigned at line 20 (`POS_A = PUNTO[n]`) a value known only at run time",
    "LIN xInsideWall[iWall]": "`xInsideWall[iWall]` is chosen by an index known only at run time",
    "LIN xNowhere": "`xNowhere` is declared in neither the program's .dat nor a $config.dat found",
    ";FOLD PTP HOME": "an inline form rmot cannot read: its velocity `ptpM` is a variable",
    ";FOLD PTP P5": "an inline form rmot cannot read: its motion data `DATWork` (the CONT's APO_DIST) is "
                    "declared in no data list found",
    ";FOLD SLIN P2": "an inline form rmot cannot read: its point `XP2` is declared in neither",
}


def test_each_native_motion_says_why(tmp_path: Path) -> None:
    output = imported_krl(tmp_path, "cell", SRC, DAT)[0]
    lines = SRC.split("\n")
    for start, reason in REASONS.items():
        n = next(i for i, text in enumerate(lines, 1) if text.strip().startswith(start))
        warned = [w for w in output.split("\n") if f"cell.src:{n}:" in w and "W510" in w]
        assert warned and reason in warned[0], (start, warned)
    # an IF on an output's state reads as `if out[99] == off`: no reason to give
    n = next(i for i, text in enumerate(lines, 1) if text.strip().startswith("IF $OUT[99]==FALSE THEN"))
    assert f"cell.src:{n}:" not in output
    # the last line's target XP5 is declared in the .dat with a value: read, not kept (W546 only:
    # the program sets no $TOOL or $BASE before it)
    n = lines.index("   LIN XP5") + 1
    assert [w for w in output.split("\n") if f"cell.src:{n}:" in w and "warning[" in w and "W546" not in w] == []


CALLS = """DEF job( )
   $VEL.CP = 0.1
   MoveSettings(lnUsedBase, lnUsedTool, 100, 200)
   LIN P1
   MoveSettings(lnUsedBase, lnUsedTool, 100, 2)
   LIN P2
   $OUT[3] = TRUE
   LIN P1
END
"""

CALLS_DAT = """DEFDAT job
DECL E6POS P1={X 600.0,Y 0.0,Z 800.0,A 0.0,B 90.0,C 0.0,S 2,T 35}
DECL E6POS P2={X 650.0,Y 0.0,Z 800.0,A 0.0,B 90.0,C 0.0,S 2,T 35}
ENDDAT
"""


def test_a_motion_after_an_unread_call_is_warned_once_per_routine(tmp_path: Path) -> None:
    """`MoveSettings(base, tool, vel, apo)` (HugoDanielson/KukaMiling Jobs, a routine in another
    module setting $BASE, $TOOL, $VEL, $APO, which are global): the LIN after it is read with the
    settings before the call, W527 at the first one (once per routine); the LIN after an output,
    with no call between, is not warned."""
    output = imported_krl(tmp_path, "job", CALLS, CALLS_DAT)[0]
    warned = [w for w in output.split("\n") if "warning[W527]" in w]
    first = CALLS.split("\n").index("   LIN P1") + 1
    assert len(warned) == 1 and f"job.src:{first}:4:" in warned[0], warned
    assert "`MoveSettings(..)` at line 3" in warned[0]


ROUTINE_SETTINGS = """DEF caller()
  $VEL.CP = 0.1
  LIN {X 500, Y 0, Z 400, A 0, B 90, C 0}
  keeps()
  fast()
  LIN {X 500, Y 100, Z 400, A 0, B 90, C 0}
END

DEF keeps()
  LIN {X 500, Y 50, Z 400, A 0, B 90, C 0}
END

DEF fast()
  $VEL.CP = 1.5
  LIN {X 500, Y 200, Z 400, A 0, B 90, C 0}
END
"""


def test_a_routine_moves_at_its_callers_speed_and_keeps_its_own_after_it_returns(tmp_path: Path) -> None:
    """$VEL is global (KSS 8.x System Integrators, system variables): `keeps()` moves at the
    caller's 0.1 m/s, so its proc's move names no speed and the call carries the caller's (`speed
    100 mm/s` before `keeps()`: an rmot proc starts with the caller's settings, REFERENCE §5),
    never KRL's 2 m/s default; `fast()` sets 1.5 m/s, which KRL keeps after it returns while an
    rmot proc's settings end with it: the caller's next motion stays native, its reason naming
    the call."""
    printed, text = imported_krl(tmp_path, "caller", ROUTINE_SETTINGS, "DEFDAT caller\nENDDAT\n")
    keeps = text[text.index("proc keeps()"):text.index("proc fast()")]
    assert "move linear" in keeps and "speed" not in keeps, keeps
    fast = text[text.index("proc fast()"):text.index("  }", text.index("proc fast()"))]
    assert "speed 1500 mm/s" in fast, fast
    main = text[text.index("  }", text.index("proc fast()")):]
    assert main.index("speed 100 mm/s\n") < main.index("keeps()"), main
    after_call = ROUTINE_SETTINGS.splitlines().index("  LIN {X 500, Y 100, Z 400, A 0, B 90, C 0}") + 1
    kept = [ln for ln in printed.splitlines() if ln.startswith(f"{tmp_path / 'caller.src'}:{after_call}:")]
    assert len(kept) == 1 and "W510" in kept[0] and "is set by `fast(..)` at line 5" in kept[0], printed
    assert "W527" not in printed
