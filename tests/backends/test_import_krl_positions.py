"""KRL positions computed in straight-line code, read as the rmot targets they are.

The modules below imitate forms found in public KRL programs: the palletizing offsets
`POS_A = PUNTO[n]`, `POS_A.Z = POS_A.Z + INC_Z + 400`, `POS_A.X = POS_A.X - 50` (ingeniado,
CAJA_G caja_g_m1.src and SACO_5 saco_5_m1.src), positions derived from others and from
`$NULLFRAME` (`xHole = $NULLFRAME`, `xHole.X = stHole.rX`, `xAboveTable = xProfile`,
`xAboveTable.Z = grAboveHoldersZ`: khrzysio Sub_Drill DrillHole.src), an array element with a
constant index (`lfWorkPos[1]`, HugoDanielson KukaMiling Jobs St1_Job2_Side1.src).
KUKA's meaning (KSS 8.x Operating and Programming Instructions for System Integrators, structure
variables): `P = Q` copies the whole structure, `P.Z = expr` changes one component and keeps the
others (the Status too), E6POS `{X, Y, Z mm, A, B, C deg}` with R = Rz(A)·Ry(B)·Rx(C).

Witnesses: the offsets are the file's own numbers added by hand; a literal pose's rotation is
compared with numpy's product of the three elementary rotations; where a value may change (a call,
a block, a label, a run-time value, an interrupt) the move stays native, its reason written by hand.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from krl_imported import imported_krl

from rmot.backends.readers import read_files
from rmot.backends.readers.krl_flow import evaluate
from rmot.backends.readers.model import Move, walk

DAT = """DEFDAT pal
DECL E6POS XP1={X 500.0,Y 100.0,Z 300.0,A 0.0,B 90.0,C 0.0,S 2,T 0}
DECL E6POS PUNTO[3]
PUNTO[1]={X 800.0,Y -200.0,Z 150.0,A 30.0,B 0.0,C 180.0,S 2,T 10}
DECL E6POS PG={X 1.0,Y 2.0,Z 3.0,A 0.0,B 0.0,C 0.0,S 2,T 0}
ENDDAT
"""


def _rotation(a: float, b: float, c: float) -> np.ndarray:
    """Rz(A)·Ry(B)·Rx(C), angles in degrees (KUKA's ABC)."""
    a, b, c = np.radians([a, b, c])
    rz = np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]])
    ry = np.array([[np.cos(b), 0, np.sin(b)], [0, 1, 0], [-np.sin(b), 0, np.cos(b)]])
    rx = np.array([[1, 0, 0], [0, np.cos(c), -np.sin(c)], [0, np.sin(c), np.cos(c)]])
    return rz @ ry @ rx


def _quaternion_matrix(w: float, x: float, y: float, z: float) -> np.ndarray:
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def _moves(rmot: str) -> list[str]:
    return [ln.strip() for ln in rmot.splitlines() if ln.strip().startswith(("move ", "native krl"))]


def test_component_offsets_of_a_known_position_are_a_shift(tmp_path: Path) -> None:
    src = """DEF pal( )
DECL E6POS POS_A
DECL E6POS POS_B
$VEL.CP = 0.2
POS_A = XP1
POS_A.Z = POS_A.Z + (400 / 2) + 30 * 2
POS_A.X = POS_A.X - 50
LIN POS_A
POS_B = PUNTO[1]
POS_B.Y = POS_B.Y + 80
LIN POS_B
POS_A.X = 100
LIN POS_A
END
"""
    _, rmot = imported_krl(tmp_path, "pal", src, DAT)
    moves = [m for m in _moves(rmot) if m.startswith("move")]
    # 300 + 200 + 60 = 560 (z + 260); 500 - 50 = 450 (x - 50); then x = 100: x - 400 from XP1
    assert moves[0].startswith("move linear shift(XP1, x=-50mm, z=260mm) speed 200 mm/s"), moves
    assert moves[1].startswith("move linear shift(PUNTO_1_, y=80mm)"), moves
    assert moves[2].startswith("move linear shift(XP1, x=-400mm, z=260mm)"), moves


def test_a_rotated_or_computed_position_is_its_literal_pose(tmp_path: Path) -> None:
    src = """DEF pal( )
DECL E6POS POS_B
DECL FRAME xHole
$VEL.CP = 0.2
POS_B = XP1
POS_B.A = 90
POS_B.C = POS_B.C - 45
LIN POS_B
xHole = $NULLFRAME
xHole.X = 120.5
xHole.Z = 7
LIN xHole
END
"""
    _, rmot = imported_krl(tmp_path, "pal", src, DAT)
    moves = [m for m in _moves(rmot) if m.startswith("move")]
    m = re.match(r"move linear pose\(x=(\S+)mm, y=(\S+)mm, z=(\S+)mm, q=\((\S+), (\S+), (\S+), (\S+)\)\)", moves[0])
    assert m is not None, moves
    assert [float(m.group(k)) for k in (1, 2, 3)] == [500.0, 100.0, 300.0]
    q = [float(m.group(k)) for k in (4, 5, 6, 7)]
    assert np.allclose(_quaternion_matrix(*q), _rotation(90.0, 90.0, -45.0), atol=1e-9)
    assert moves[1].startswith("move linear pose(x=120.5mm, y=0mm, z=7mm, q=(1, 0, 0, 0))"), moves


def test_a_value_that_may_change_keeps_the_move_native(tmp_path: Path) -> None:
    src = """DEF pal( )
DECL E6POS POS_A
DECL E6POS POS_C
DECL INT n
$VEL.CP = 0.2
POS_A = XP1
POS_A.Z = POS_A.Z + INC_Z
LIN POS_A
POS_C = XP1
Grip(POS_C)
LIN POS_C
PG = PUNTO[1]
Grip(1)
LIN PG
POS_A = XP1
FOR n = 1 TO 3
   POS_A.Z = POS_A.Z + 10
   LIN POS_A
ENDFOR
LIN POS_A
POS_C = XP1
IF $IN[1] THEN
   POS_C.Z = 10
ENDIF
LIN POS_C
POS_C = XP1
AGAIN:
LIN POS_C
END
"""
    out, rmot = imported_krl(tmp_path, "pal", src, DAT)
    natives = [m for m in _moves(rmot) if m.startswith("native krl \"LIN")]
    # every LIN of this module has a value known only at run time (or after a change it cannot see)
    assert len(natives) == 7, _moves(rmot)
    reasons = {  # the line that made each value unknown, written by hand from the module above
        8: "`POS_A` is assigned at line 7 (`POS_A.Z = POS_A.Z + INC_Z`) a value known only at run time",
        11: "`POS_C` is known before `Grip(..)` at line 10, which may change it",
        14: "`PG` is known before `Grip(..)` at line 13, which may change it",
        18: "`POS_A` is assigned inside the block at line 16 (a loop repeats it, a branch may not run)",
        20: "`POS_A` is assigned inside the block at line 16",
        25: "`POS_C` is assigned inside the block at line 22",
        28: "`POS_C` is unknown after the label at line 27, where a jump may land",
    }
    for line, why in reasons.items():
        assert f"pal.src:{line}:" in out and why in out.split(f"pal.src:{line}:")[1].split("\n")[0], (line, out)


def test_an_interrupt_leaves_only_the_routine_s_own_positions_known(tmp_path: Path) -> None:
    src = """DEF pal( )
DECL E6POS POS_A
INTERRUPT DECL 3 WHEN $IN[3] DO Stop( )
$VEL.CP = 0.2
POS_A = XP1
PG = PUNTO[1]
LIN POS_A
LIN PG
END
"""
    _, rmot = imported_krl(tmp_path, "pal", src, DAT)
    assert "move linear XP1 speed 200 mm/s" in rmot
    assert 'native krl "LIN PG"' in rmot


def test_known_positions_carry_into_a_branch_that_does_not_change_them(tmp_path: Path) -> None:
    src = """DEF pal( )
DECL E6POS POS_A
$VEL.CP = 0.2
POS_A = XP1
POS_A.Y = POS_A.Y + 25
IF $IN[1] THEN
   LIN POS_A
ENDIF
LIN POS_A
END
"""
    _, rmot = imported_krl(tmp_path, "pal", src, DAT)
    assert len([m for m in _moves(rmot) if m.startswith("move linear shift(XP1, y=25mm)")]) == 2, _moves(rmot)


XPOINTS = """&ACCESS RV
DEFDAT  XPOINTS PUBLIC
DECL GLOBAL E6POS XST2={X 162.5,Y -1116.0,Z 504.0,A -23.0,B 86.0,C 67.0,S 6,T 26}
DECL E6POS XLOCAL={X 1.0,Y 2.0,Z 3.0,A 0.0,B 0.0,C 0.0,S 6,T 26}
DECL GLOBAL E6POS XMOVED={X 1.0,Y 2.0,Z 3.0,A 0.0,B 0.0,C 0.0,S 6,T 26}
ENDDAT
"""


def test_a_global_of_a_public_data_list_in_the_folder_is_read(tmp_path: Path) -> None:
    """`DEFDAT XPOINTS PUBLIC` with `DECL GLOBAL E6POS XST2=..` (HugoDanielson KukaMiling
    Dat/xPoints.dat) used by another module (Moves/FromSt1/st1_st2.src); a non-GLOBAL one and a
    GLOBAL one another .src of the folder assigns stay native."""
    (tmp_path / "xPoints.dat").write_text(XPOINTS)
    (tmp_path / "other.src").write_text("DEF other( )\nXMOVED = $POS_ACT\nEND\n")
    src = "DEF st1( )\n$VEL.CP = 0.2\nPTP XST2\nLIN XLOCAL\nLIN XMOVED\nEND\n"
    out, rmot = imported_krl(tmp_path, "st1", src, "DEFDAT st1\nENDDAT\n")
    assert "target XST2 = pose(x=162.5mm, y=-1116mm, z=504mm" in rmot
    assert "move joint XST2" in rmot
    assert 'native krl "LIN XLOCAL"' in rmot and 'native krl "LIN XMOVED"' in rmot
    assert "nor GLOBAL in a public data list" in out


def test_a_data_list_that_is_not_public_keeps_its_globals(tmp_path: Path) -> None:
    (tmp_path / "xPoints.dat").write_text(XPOINTS.replace(" PUBLIC", ""))
    _, rmot = imported_krl(tmp_path, "st1", "DEF st1( )\nPTP XST2\nEND\n", "DEFDAT st1\nENDDAT\n")
    assert 'native krl "PTP XST2"' in rmot


def test_a_constant_of_the_data_list_is_a_position(tmp_path: Path) -> None:
    """`DECL CONST POS xAboveMagazine={..}` (khrzysio Objects/ToolMagazine.dat)."""
    dat = "DEFDAT mag\nDECL CONST POS xAboveMagazine={X 500.000,Y 200.000,Z 300.000,A 0.0,B 0.0,C 0.0}\nENDDAT\n"
    _, rmot = imported_krl(tmp_path, "mag", "DEF mag( )\n$VEL.CP = 0.2\nLIN xAboveMagazine\nEND\n", dat)
    assert "move linear xAboveMagazine speed 200 mm/s" in rmot


WALLS = """DEFDAT wall
DECL E6POS xInsideWall[4]
xInsideWall[1]={X 100.0,Y 0.0,Z 300.0,A 0.0,B 90.0,C 0.0,S 2,T 0}
xInsideWall[2]={X 200.0,Y 0.0,Z 300.0,A 0.0,B 90.0,C 0.0,S 2,T 0}
xInsideWall[3]={X 300.0,Y 0.0,Z 300.0,A 0.0,B 90.0,C 0.0,S 2,T 0}
ENDDAT
"""


def test_a_for_over_known_array_elements_is_written_out(tmp_path: Path) -> None:
    """`FOR iWall = 1 TO 4` .. `LIN xInsideWall[iWall] C_DIS` (khrzysio Sub_MillLeaf
    LeafMillHandle.src): KRL's FOR includes both bounds, so 1 TO 3 is three moves in order."""
    src = """DEF wall( )
DECL INT iWall
$VEL.CP = 0.2
$APO.CDIS = 5
FOR iWall = 1 TO 3
   LIN xInsideWall[iWall] C_DIS
   WAIT SEC 0.5
ENDFOR
FOR iWall = 1 TO 4
   LIN xInsideWall[iWall] C_DIS
ENDFOR
END
"""
    out, rmot = imported_krl(tmp_path, "wall", src, WALLS)
    moves = [m.split(" speed")[0] for m in _moves(rmot)]
    assert moves[:3] == [f"move linear xInsideWall_{k}_" for k in (1, 2, 3)], moves
    assert rmot.count("wait 0.5 s") == 3
    assert "warning[W538]" in out and "xInsideWall[1..3]" in out
    # element 4 has no value: that loop stays a loop, its move native
    assert 'native krl "LIN xInsideWall[iWall] C_DIS"' in rmot and "for iWall in 1 .. 5" in rmot


def test_a_for_beyond_the_bound_stays_a_loop(tmp_path: Path) -> None:
    src = "DEF wall( )\nDECL INT i\n$VEL.CP = 0.2\nFOR i = 1 TO 65\n   LIN xInsideWall[i]\nENDFOR\nEND\n"
    out, rmot = imported_krl(tmp_path, "wall", src, WALLS)
    assert "wall.src:4:1: warning[W537]" in out and "65 iterations" in out
    assert "for i in 1 .. 66" in rmot


def test_a_counter_used_elsewhere_keeps_the_loop(tmp_path: Path) -> None:
    src = "DEF wall( )\nDECL INT i\n$VEL.CP = 0.2\nFOR i = 1 TO 3\n   LIN xInsideWall[i]\n   $OUT[i] = TRUE\nENDFOR\nEND\n"
    out, rmot = imported_krl(tmp_path, "wall", src, WALLS)
    assert "W538" not in out and "for i in 1 .. 4" in rmot


def test_a_for_with_a_loop_inside_stays_a_loop(tmp_path: Path) -> None:
    """Written-out loops never nest: a hostile file cannot multiply its lines 64 times per level."""
    src = ("DEF wall( )\nDECL INT i, j\n$VEL.CP = 0.2\nFOR i = 1 TO 3\n   LIN xInsideWall[i]\n   FOR j = 1 TO 2\n"
           "      WAIT SEC 0.1\n   ENDFOR\nENDFOR\nEND\n")
    out, rmot = imported_krl(tmp_path, "wall", src, WALLS)
    assert "W538" not in out and "for i in 1 .. 4" in rmot


def test_the_shifted_value_is_the_data_list_pose_moved_in_its_base(tmp_path: Path) -> None:
    """The pose a shifted move goes to, against numpy: XP1's {X 500, Y 100, Z 300} plus the offsets
    (x - 50, z + 260) and XP1's rotation Rz(0)·Ry(90)·Rx(0), unchanged by X/Y/Z assignments."""
    (tmp_path / "pal.src").write_text("DEF pal( )\nDECL E6POS POS_A\n$VEL.CP = 0.2\nPOS_A = XP1\n"
                                      "POS_A.Z = POS_A.Z + (400 / 2) + 30 * 2\nPOS_A.X = POS_A.X - 50\nLIN POS_A\nEND\n")
    (tmp_path / "pal.dat").write_text(DAT)
    doc = read_files([str(tmp_path / "pal.src")])
    moves = [s for r in doc.routines for s in walk(r.body) if isinstance(s, Move)]
    assert len(moves) == 1 and moves[0].pose is not None
    matrix = np.array(moves[0].pose.matrix())
    assert np.allclose(matrix[:3, 3], np.array([450.0, 100.0, 560.0]) / 1000.0, atol=1e-12)
    assert np.allclose(matrix[:3, :3], _rotation(0.0, 90.0, 0.0), atol=1e-12)


def test_only_constant_arithmetic_is_evaluated() -> None:
    """KRL's arithmetic (`* /` before `+ -`, unary minus), values worked out by hand; a variable, a
    division by zero, an overflow and a hostile nesting are not constants (None), never an error."""
    known = {"P": {"Z": 300.0}}

    def component(name: str, part: str) -> float | None:
        return known.get(name, {}).get(part)

    assert evaluate("P.Z + (400 / 2) + 30 * 2", component) == 560.0
    assert evaluate("-(2 + 3) * 2", component) == -10.0
    assert evaluate("2 * -3", component) == -6.0
    for text in ("INC_Z + 1", "1 / 0", "1e400", "(" * 5000 + "1" + ")" * 5000, "-" * 5000 + "1", "Q.Z", "2 +"):
        assert evaluate(text, component) is None, text
