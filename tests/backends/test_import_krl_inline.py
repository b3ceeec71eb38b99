"""KRL inline forms (KR C4 / KSS 8 `;FOLD` with `%{PE}`), read from the fold header and the
`.dat`'s E6POS/PDAT/LDAT: a module written by hand in the format KUKA's pendant saves
(KSS 8.x Operating and Programming Instructions for System Integrators, "Inline forms": PTP
with PDAT VEL/ACC/APO_DIST, LIN with LDAT and Vel in m/s, OUT, WAIT, CONT = approximated).

Witness: the numbers typed in the module below (APO_DIST 100 and 20 mm, Vel 0.2 and 1 m/s, the
E6POS values) and the expected rmot lines written from them by hand.
"""

from __future__ import annotations

from pathlib import Path

from click.testing import CliRunner

from rmot.compiler.cli import cli

SRC = """&ACCESS RVP
&REL 1
&PARAM TEMPLATE = C:\\KRC\\Roboter\\Template\\vorgabe
&PARAM EDITMASK = *
DEF pick( )
;FOLD INI;%{PE}
  ;FOLD BASISTECH INI
    GLOBAL INTERRUPT DECL 3 WHEN $STOPMESS==TRUE DO IR_STOPM ( )
    INTERRUPT ON 3
    BAS (#INITMOV,0 )
  ;ENDFOLD (BASISTECH INI)
;ENDFOLD (INI)

;FOLD PTP HOME Vel=100 % DEFAULT;%{PE}%MKUKATPBASIS,%CMOVE,%VPTP,%P 1:PTP, 2:HOME, 3:, 5:100, 7:DEFAULT
$BWDSTART=FALSE
PDAT_ACT=PDEFAULT
FDAT_ACT=FHOME
BAS(#PTP_PARAMS,100)
$H_POS=XHOME
PTP XHOME
;ENDFOLD
;FOLD PTP P1 CONT Vel=100 % PDAT1 Tool[1]:gripper Base[1]:table;%{PE}
$BWDSTART=FALSE
PDAT_ACT=PPDAT1
FDAT_ACT=FP1
BAS(#PTP_PARAMS,100)
PTP XP1 C_PTP
;ENDFOLD
;FOLD LIN P2 Vel=0.2 m/s CPDAT1 Tool[1]:gripper Base[1]:table;%{PE}
$BWDSTART=FALSE
LDAT_ACT=LCPDAT1
FDAT_ACT=FP2
BAS(#CP_PARAMS,0.2)
LIN XP2
;ENDFOLD
;FOLD OUT 1 'gripper' State=TRUE ;%{PE}
$OUT[1]=TRUE
;ENDFOLD
;FOLD WAIT Time=0.5 sec;%{PE}
WAIT SEC 0.5
;ENDFOLD
;FOLD LIN P3 CONT Vel=1 m/s CPDAT2 Tool[1]:gripper Base[1]:table;%{PE}
$BWDSTART=FALSE
LDAT_ACT=LCPDAT2
FDAT_ACT=FP3
BAS(#CP_PARAMS,1)
LIN XP3 C_DIS
;ENDFOLD
;FOLD WAIT FOR IN 3 'part' State=TRUE ;%{PE}
WAIT FOR $IN[3]
;ENDFOLD
;FOLD SPTP HOME Vel=100 % DEFAULT ADAT0 Tool[1]:gripper Base[0];%{PE}
SPTP XHOME
;ENDFOLD
END
"""

DAT = """&ACCESS RVP
DEFDAT pick
DECL E6AXIS XHOME={A1 0.0,A2 -90.0,A3 90.0,A4 0.0,A5 0.0,A6 0.0,E1 0.0,E2 0.0,E3 0.0,E4 0.0,E5 0.0,E6 0.0}
DECL E6POS XP1={X 600.0,Y 0.0,Z 400.0,A 0.0,B 90.0,C 0.0,S 6,T 50,E1 0.0,E2 0.0,E3 0.0,E4 0.0,E5 0.0,E6 0.0}
DECL FDAT FP1={TOOL_NO 1,BASE_NO 1,IPO_FRAME #BASE,POINT2[] " "}
DECL PDAT PPDAT1={VEL 100.000,ACC 100.000,APO_DIST 100.000}
DECL E6POS XP2={X 600.0,Y 0.0,Z 300.0,A 0.0,B 90.0,C 0.0,S 6,T 50,E1 0.0,E2 0.0,E3 0.0,E4 0.0,E5 0.0,E6 0.0}
DECL LDAT LCPDAT1={VEL 2.000,ACC 100.000,APO_DIST 100.000,APO_FAC 50.0000,ORI_TYP #VAR}
DECL E6POS XP3={X 600.0,Y 100.0,Z 400.0,A 0.0,B 90.0,C 0.0,S 6,T 50,E1 0.0,E2 0.0,E3 0.0,E4 0.0,E5 0.0,E6 0.0}
DECL LDAT LCPDAT2={VEL 2.000,ACC 100.000,APO_DIST 20.000,APO_FAC 50.0000,ORI_TYP #VAR}
ENDDAT
"""


def test_krc4_inline_forms(tmp_path: Path) -> None:
    (tmp_path / "pick.src").write_text(SRC)
    (tmp_path / "pick.dat").write_text(DAT)
    out = tmp_path / "pick.rmot"
    result = CliRunner().invoke(cli, ["import", str(tmp_path / "pick.src"), "-o", str(out), "--robot", "kuka_kr16"])
    assert result.exit_code == 0, result.output
    assert "8 imported, 0 kept native" in result.output
    assert f"{tmp_path / 'pick.src'}:6:1: warning[W511]: the `INI` fold" in result.output
    assert "BASE_DATA[1]" in result.output and "TOOL_DATA[1]" in result.output
    moves = [ln.strip() for ln in out.read_text().splitlines() if ln.strip().startswith(("move", "set", "wait"))]
    assert moves == [
        "move joint XHOME speed 100 % zone fine",
        "move joint XP1 config(shoulder=front, elbow=up, wrist=flip) speed 100 % zone 100 mm",
        "move linear XP2 speed 200 mm/s zone fine",
        "set out[1] = on",
        "wait 0.5 s",
        "move linear XP3 speed 1000 mm/s zone 20 mm",
        "wait until in[3] == on",
        "move joint XHOME speed 100 % zone fine",
    ]
    text = out.read_text()
    assert "target XP1 = pose(x=600mm, y=0mm, z=400mm, q=(0.7071067812, 0, 0.7071067812, 0))" in text  # B 90
    assert "target XHOME = joints(0, -90, 90, 0, 0, 0) deg" in text
