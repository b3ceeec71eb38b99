"""`rmot diff` on touch-ups of other people's files: each pair is a real program (a pendant-
saved INFORM job, a hand-written RAPID module with inline robtargets, a RoboDK-written TP
program from a controller backup) and a copy edited by hand here — one target moved by exactly
2.5 mm, one zone changed, one output added — and the diff names exactly those, by line.

Witness: the edits are made in the test (the expected distances and lines come from the edit);
the zone values are the vendors' (INFORM PL=2 = 25 mm, the backend's PL table; RAPID z50 =
50 mm, RAPID Reference zonedata; TP CNT50 read as 50 mm, the TP backend's CNT_MM).
"""

from __future__ import annotations

from pathlib import Path

from click.testing import CliRunner

from rmot.compiler.cli import cli

JOB = """/JOB
//NAME CUT_ONLY
//POS
///NPOS 0,0,0,3,0,0
///TOOL 0
///POSTYPE USER
///USER 1
///RECTAN
///RCONF 1,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0
P00105=216.374,-55.365,150.000,179.9941,-0.0013,-179.9943
P00106=183.974,-55.386,-103.111,179.9969,-0.0014,-179.9945
P00107=217.725,-55.392,-103.109,179.9979,-0.0019,-179.9959
//INST
///DATE 2023/01/24 16:29
///ATTR SC,RW
///GROUP1 RB1
NOP
MOVJ P105 VJ=25.00  //APPROCH CUT
MOVL P106 V=150.0 PL=0  //CUT PRE-SLIDE
MOVL P107 V=150.0 PL=0  //CUT SLIDE
TIMER T=0.50
END
"""

MOD = """MODULE MainModule
PROC main()
SetDO Gripper_open, 1;
MoveJ [[25,450,138.8],[-0.174713,0.907209,0.375778,0.072368],[0,-1,-1,0],[0,9E9,9E9,9E9,9E9,9E9]],v150,z20,tool0\\WObj:=wobj0;
MoveL [[25,550,38.8],[-0.174713,0.907209,0.375778,0.072368],[0,-1,-1,0],[0,9E9,9E9,9E9,9E9,9E9]],v150,z20,tool0\\WObj:=wobj0;
WaitTime 0.5;
MoveL [[25,450,138.8],[-0.174713,0.907209,0.375778,0.072368],[0,-1,-1,0],[0,9E9,9E9,9E9,9E9,9E9]],v150,z20,tool0\\WObj:=wobj0;
ENDPROC
ENDMODULE
"""

TP = """/PROG  A10DEFASTE
/ATTR
DEFAULT_GROUP\t= 1,*,*,*,*;
/MN
   1:  UFRAME_NUM=0 ;
   2:L P[2] 600mm/sec FINE    ;
   3:L P[3] 200mm/sec FINE    ;
   4:L P[4] 180mm/sec FINE    ;
/POS
P[2:""]{
   GP1:
\tUF : 0, UT : 1,\t\tCONFIG : 'N U T, 0, 0, 0',
\tX =  9300.620  mm,\tY =  1562.720  mm,\tZ =  3712.120  mm,
\tW =   175.724 deg,\tP =   -45.994 deg,\tR =  -170.781 deg
};
P[3:""]{
   GP1:
\tUF : 0, UT : 1,\t\tCONFIG : 'N U T, 0, 0, 0',
\tX =  9300.620  mm,\tY =  1562.720  mm,\tZ =  3612.120  mm,
\tW =   175.724 deg,\tP =   -45.994 deg,\tR =  -170.781 deg
};
P[4:""]{
   GP1:
\tUF : 0, UT : 1,\t\tCONFIG : 'N U T, 0, 0, 0',
\tX =  9350.620  mm,\tY =  1562.720  mm,\tZ =  3612.120  mm,
\tW =   175.724 deg,\tP =   -45.994 deg,\tR =  -170.781 deg
};
/END
"""


def _diff(tmp_path: Path, name: str, a: str, b: str) -> tuple[int, list[str]]:
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    (tmp_path / "a" / name).write_text(a)
    (tmp_path / "b" / name).write_text(b)
    result = CliRunner().invoke(cli, ["diff", str(tmp_path / "a" / name), str(tmp_path / "b" / name)],
                                catch_exceptions=False)
    return result.exit_code, [ln.replace(str(tmp_path) + "/", "") for ln in result.output.splitlines()]


def test_inform_touch_up(tmp_path: Path) -> None:
    b = (JOB.replace("P00106=183.974,", "P00106=186.474,")
         .replace("MOVL P107 V=150.0 PL=0", "MOVL P107 V=150.0 PL=2")
         .replace("TIMER T=0.50\n", "TIMER T=0.50\nDOUT OT#(12) ON\n"))
    code, lines = _diff(tmp_path, "CUT_ONLY.JBI", JOB, b)
    assert code == 1
    assert lines == [
        "a/CUT_ONLY.JBI:11:1 -> b/CUT_ONLY.JBI:11:1: target cut_only_p00106 moved 2.500 mm, turned 0.000 deg",
        "a/CUT_ONLY.JBI:20:1 -> b/CUT_ONLY.JBI:20:1: move linear cut_only_p00107: zone fine -> 25 mm",
        "b/CUT_ONLY.JBI:22:1: added set out 12",
        "3 differences",
    ]


def test_rapid_inline_touch_up(tmp_path: Path) -> None:
    lines_b = MOD.split("\n")
    lines_b[4] = lines_b[4].replace("[[25,550,38.8]", "[[25,552.5,38.8]")
    lines_b[6] = lines_b[6].replace("v150,z20", "v150,z50")
    lines_b.insert(5, "SetDO Gripper_close, 1;")
    code, lines = _diff(tmp_path, "MainModule.mod", MOD, "\n".join(lines_b))
    assert code == 1
    assert lines == [
        "a/MainModule.mod:5:1 -> b/MainModule.mod:5:1: move linear pose: target moved 2.500 mm, turned 0.000 deg",
        "b/MainModule.mod:6:1: added set out Gripper_close",
        "a/MainModule.mod:7:1 -> b/MainModule.mod:8:1: move linear pose: zone 20 mm -> 50 mm",
        "3 differences",
    ]


def test_fanuc_touch_up(tmp_path: Path) -> None:
    head, p3 = TP.split('P[3:""]')
    b = (head + 'P[3:""]' + p3.replace("Z =  3612.120", "Z =  3609.620", 1))
    b = (b.replace("   3:L P[3] 200mm/sec FINE    ;", "   3:L P[3] 200mm/sec CNT50    ;\n   4:  DO[5]=ON ;")
         .replace("   4:L P[4]", "   5:L P[4]"))
    code, lines = _diff(tmp_path, "a10defaste.ls", TP, b)
    assert code == 1
    assert lines == [
        "a/a10defaste.ls:16:1 -> b/a10defaste.ls:17:1: target a10defaste_p3 moved 2.500 mm, turned 0.000 deg",
        "a/a10defaste.ls:7:4 -> b/a10defaste.ls:7:4: move linear a10defaste_p3: zone fine -> 50 mm",
        "b/a10defaste.ls:8:4: added set out 5",
        "3 differences",
    ]
