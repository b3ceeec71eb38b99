"""`rmot import` of the acceleration and blend forms the backends write: RAPID `AccSet`, Fanuc
`ACCn`, URScript movej `a=`/`v=` (the plan's leading-axis peak rates) and KRL `C_PTP C_DIS`.

Witnesses: hand-written vendor lines whose meaning is the vendor manual's (AccSet Acc, Ramp;
TP motion option ACC; movej a, v of the leading axis), and for URScript the closed-form
trapezoid of a rest-to-rest joint move (computed here from the library's joint limits, as
`rmot robots show` prints them), not the reader under test.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

from click.testing import CliRunner

from rmot.compiler.cli import cli
from rmot.sim.robots.loader import load_robot

MODULE = """MODULE m
  CONST jointtarget a:=[[0,0,0,0,30,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
  CONST jointtarget b:=[[20,0,0,0,30,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
  PROC main()
    AccSet 40, 100;
    MoveAbsJ a\\NoEOffs, vmax, fine, tool0;
    AccSet 40, 50;
    MoveAbsJ b\\NoEOffs, vmax, fine, tool0;
  ENDPROC
ENDMODULE
"""


def _import(tmp_path: Path, name: str, text: str, *extra: str) -> tuple[str, str]:
    src = tmp_path / name
    src.write_text(text)
    out = tmp_path / "out.rmot"
    result = CliRunner().invoke(cli, ["import", str(src), "-o", str(out), *extra], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    return out.read_text(), result.output


def test_rapid_accset(tmp_path: Path) -> None:
    """Ramp 100 % is the normal jerk: Acc becomes the joint share; another Ramp stays native."""
    program, output = _import(tmp_path, "m.mod", MODULE)
    moves = [ln.strip() for ln in program.splitlines() if ln.strip().startswith("move joint")]
    assert "accel 40 %" in moves[0]
    assert "W510" in output and "AccSet 40, 50;" in output
    assert 'native rapid "AccSet 40, 50;"' in program


def test_fanuc_acc_on_joint_and_linear_moves(tmp_path: Path) -> None:
    ls = """/PROG  T
/MN
   1:  UFRAME_NUM=0 ;
   2:  UTOOL_NUM=0 ;
   3:  J P[1] 100% FINE ACC35 ;
   4:  L P[2] 100mm/sec FINE ACC35 ;
/POS
P[1]{
   GP1:
\tUF : 0, UT : 0,\t\tCONFIG : 'N U T, 0, 0, 0',
\tX =   500.000  mm,\tY =     0.000  mm,\tZ =   500.000  mm,
\tW =   180.000 deg,\tP =     0.000 deg,\tR =     0.000 deg
};
P[2]{
   GP1:
\tUF : 0, UT : 0,\t\tCONFIG : 'N U T, 0, 0, 0',
\tX =   500.000  mm,\tY =     0.000  mm,\tZ =   400.000  mm,
\tW =   180.000 deg,\tP =     0.000 deg,\tR =     0.000 deg
};
/END
"""
    program, output = _import(tmp_path, "T.ls", ls)
    assert re.search(r"move joint \S+ .*accel 35 %", program), program
    # ACC overrides a linear move's acceleration too: the joint share rmot's plan bounds the
    # move's joints by, with W540 (its TCP acceleration stays the default)
    assert re.search(r"move linear \S+ .*accel 35 %", program), program
    assert "W540" in output and "W510" not in output


def _trapezoid_rates(delta_deg: list[float], vmax: list[float], amax: list[float],
                     share_v: float, share_a: float) -> tuple[float, float]:
    """The leading axis' peak speed and acceleration of a rest-to-rest joint-space line under
    each joint's limits times the shares (the textbook trapezoid)."""
    d = [abs(math.radians(x)) for x in delta_deg]
    lead = max(d)
    s_dot = min(share_v * v / x for v, x in zip(vmax, d) if x > 0)
    s_ddot = min(share_a * a / x for a, x in zip(amax, d) if x > 0)
    peak = min(s_dot, math.sqrt(s_ddot))  # triangular when the top speed is not reached
    return peak * lead, s_ddot * lead


def test_urscript_movej_rates(tmp_path: Path) -> None:
    """The second movej starts where the first stopped: its shares follow from the rates."""
    robot = load_robot("ur5e")
    vmax, amax = list(robot.velocity_limits), list(robot.accel_limits)
    q0, q1 = [0.0, -90.0, 90.0, 0.0, 90.0, 0.0], [150.0, -60.0, 70.0, 10.0, 90.0, 0.0]
    v, a = _trapezoid_rates([b - c for b, c in zip(q1, q0)], vmax, amax, 0.6, 0.3)
    rad = [", ".join(f"{math.radians(x):.9f}" for x in q) for q in (q0, q1)]
    script = (f"def p():\n  movej([{rad[0]}], a=13.962634, v=3.141593, r=0)\n"
              f"  movej([{rad[1]}], a={a:.9f}, v={v:.9f}, r=0)\n"
              f"  movel(p[0.4, 0.1, 0.4, 3.1416, 0, 0], a=1.2, v=0.25, r=0)\n"
              f"  movej([{rad[0]}], a={a:.9f}, v={v:.9f}, r=0)\nend\np()\n")
    program, output = _import(tmp_path, "p.script", script, "--robot", "ur5e")
    moves = [ln.strip() for ln in program.splitlines() if ln.strip().startswith("move joint")]
    assert "%" not in moves[0]  # the first move: 180 deg/s, 800 deg/s^2 of JOINT_LIMITS = 100 %
    assert "speed 60 %" in moves[1] and "accel 30 %" in moves[1], moves[1]
    assert "%" not in moves[2] and "W515" in output  # after a movel the start is unknown


def test_krl_ptp_blended_into_lin(tmp_path: Path) -> None:
    src = """DEF k()
  $APO.CPTP=5
  $APO.CDIS=3.250
  PTP {A1 0,A2 -90,A3 90,A4 0,A5 30,A6 0} C_PTP C_DIS
  $VEL.CP=0.2
  LIN {X 500,Y 0,Z 500,A 0,B 90,C 0}
END
"""
    program, output = _import(tmp_path, "k.src", src)
    assert re.search(r"move joint joints\(.*\) deg.* zone 3\.25 mm", program), program
    assert "W510" not in output
