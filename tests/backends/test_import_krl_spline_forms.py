"""KSS 8 spline inline forms with the tool and base data's names after the index, read from the
fold header and the `.dat`: `SPTP P5 CONT Vel=100 % PDAT3 Tool[1]:TOOL_DATA[1] Base[1]:BASE_DATA[1]`
and `SLIN P2 Vel=0.2 m/s CPDAT4 Tool[1]:TOOL_DATA[1] ..` as KUKA.WorkVisual / the KSS 8 pendant
write them (the form imitated from Bugaj32's podprogramy/Podnies().src, whose .dat is not
published; KSS 8.x Operating and Programming Instructions for System Integrators, spline inline
forms: point P is XP in the .dat, CONT approximates by the motion data's APO_DIST mm, Vel in % for
SPTP and m/s for SLIN).

Witness: the numbers typed in the .dat below (APO_DIST 50 mm, XP5/XP2) and the header's speeds,
with the rmot lines they give written by hand.
"""

from __future__ import annotations

from pathlib import Path

from krl_imported import imported_krl

SRC = """DEF pod( )
;FOLD SPTP P5 CONT Vel=100 % PDAT3 Tool[1]:TOOL_DATA[1] Base[1]:BASE_DATA[1] ;%{PE}
   ;FOLD Parameters ;%{h}
      ;Params IlfProvider=kukaroboter.basistech.inlineforms.movement.spline; Kuka.PointName=P5; Kuka.BlendingEnabled=True
   ;ENDFOLD
   SPTP XP5 WITH $VEL_AXIS[1] = SVEL_JOINT(100.0), $TOOL = STOOL2(FP5), $BASE = SBASE(FP5.BASE_NO), $APO = SAPO_PTP(PPDAT3) C_Spl
;ENDFOLD
;FOLD SLIN P2 Vel=0.2 m/s CPDAT4 Tool[1]:TOOL_DATA[1] Base[1]:BASE_DATA[1] ;%{PE}
   SLIN XP2 WITH $VEL = SVEL_CP(0.2, , LCPDAT4), $TOOL = STOOL2(FP2), $BASE = SBASE(FP2.BASE_NO)
;ENDFOLD
END
"""

DAT = """DEFDAT pod
DECL E6POS XP5={X 600.0,Y 0.0,Z 800.0,A 0.0,B 90.0,C 0.0,S 2,T 35}
DECL FDAT FP5={TOOL_NO 1,BASE_NO 1,IPO_FRAME #BASE}
DECL PDAT PPDAT3={VEL 100.0,ACC 100.0,APO_DIST 50.0,APO_MODE #CDIS}
DECL E6POS XP2={X 650.0,Y 0.0,Z 800.0,A 0.0,B 90.0,C 0.0,S 2,T 35}
DECL FDAT FP2={TOOL_NO 1,BASE_NO 1,IPO_FRAME #BASE}
DECL LDAT LCPDAT4={VEL 2.0,ACC 100.0,APO_DIST 100.0,APO_FAC 50.0,ORI_TYP #VAR}
ENDDAT
"""


def test_kss8_spline_inline_forms_with_data_names(tmp_path: Path) -> None:
    output, text = imported_krl(tmp_path, "pod", SRC, DAT)
    assert "motion and I/O: 2 imported, 0 kept native" in output
    # B 90 deg about y: q = (cos 45°, 0, sin 45°, 0); S 2 = elbow up, shoulder front, no flip
    assert "target XP5 = pose(x=600mm, y=0mm, z=800mm, q=(0.7071067812, 0, 0.7071067812, 0))" in text
    assert "move joint XP5 config(shoulder=front, elbow=up, wrist=noflip) speed 100 % zone 50 mm" in text
    # 0.2 m/s = 200 mm/s; no CONT: exact stop (the LDAT's APO_DIST 100 is not used)
    assert "move linear XP2 speed 200 mm/s zone fine" in text
    assert "tool TOOL_DATA_1_" in text and "frame BASE_DATA_1_" in text
