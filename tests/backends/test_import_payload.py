"""`rmot import --cell`: a vendor's payload switch comes back as `attach PART` / `detach PART`.

The vendor lines are written here by hand from the vendors' manuals (RAPID GripLoad/loaddata,
KRL $LOAD/LOAD, URScript set_payload, TP PAYLOAD[i]), not by rmot's backends; their numbers
are worked out by hand from the cell below (the witness): the gripper `grip` has its TCP
100 mm out along the flange z axis and 1 kg at rmot's tool centre (half way, 50 mm); the part
`box1` (2 kg) is held with its centre 50 mm beyond the TCP, so

  * the parts' load in the tool frame (RAPID loaddata): 2 kg at [0, 0, 50] mm;
  * tool + part on the flange (KRL LOAD, URScript): 3 kg at (1 * 50 + 2 * 150) / 3 = 116.667 mm;
  * back to the tool alone: 1 kg at 50 mm (KRL, URScript), `load0` (RAPID).
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from click.testing import CliRunner

from rmot.compiler.cli import cli

CELL = """cell grip_cell {
  robot r1 = abb_irb1600
  part box1 = box(200mm, 100mm, 100mm) at pose(x=600mm, z=300mm) mass 2 kg
  part plate = box(300mm, 300mm, 20mm) at pose(x=600mm, y=400mm, z=300mm) mass 5 kg
  tool grip = box(50mm, 50mm, 100mm) at pose(z=50mm) tcp pose(z=100mm) mass 1 kg on r1
}
"""
# a second 2 kg part as small as box1: a 2 kg load fits both
TWIN = CELL.replace("  tool grip", "  part box2 = box(200mm, 100mm, 100mm) at pose(x=600mm, y=-400mm, z=300mm) mass 2 kg\n  tool grip")

RAPID = """MODULE grip_demo
  PERS tooldata grip:=[TRUE,[[0,0,100],[1,0,0,0]],[1,[0,0,50],[1,0,0,0],0,0,0]];
  PERS loaddata box_load:=[2,[0,0,50],[1,0,0,0],0,0,0];
  CONST jointtarget home:=[[0,0,0,0,30,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
  PROC main()
    MoveAbsJ home,v1000,fine,grip;
    GripLoad box_load;
    MoveAbsJ home,v1000,fine,grip;
    GripLoad load0;
  ENDPROC
ENDMODULE
"""
KRL_SRC = """DEF grip_demo( )
  $TOOL=grip
  $LOAD=grip_load
  $BASE=$NULLFRAME
  PTP home
  $LOAD=grip_box
  PTP home
  $LOAD=grip_load
END
"""
KRL_DAT = """DEFDAT grip_demo
  DECL FRAME grip={X 0.0,Y 0.0,Z 100.0,A 0.0,B 0.0,C 0.0}
  DECL LOAD grip_load={M 1.0,CM {X 0.0,Y 0.0,Z 50.0,A 0.0,B 0.0,C 0.0},J {X 0.0,Y 0.0,Z 0.0}}
  DECL LOAD grip_box={M 3.0,CM {X 0.0,Y 0.0,Z 116.667,A 0.0,B 0.0,C 0.0},J {X 0.0,Y 0.0,Z 0.0}}
  DECL E6AXIS home={A1 0.0,A2 -90.0,A3 90.0,A4 0.0,A5 30.0,A6 0.0}
ENDDAT
"""
URSCRIPT = """def grip_demo():
  set_tcp(p[0.0, 0.0, 0.1, 0.0, 0.0, 0.0])
  set_payload(1.0, [0.0, 0.0, 0.05])
  movej([0.0, -1.5708, 1.5708, 0.0, 0.5236, 0.0], a=1.4, v=1.05)
  set_payload(3.0, [0.0, 0.0, 0.116667])
  movej([0.0, -1.5708, 1.5708, 0.0, 0.5236, 0.0], a=1.4, v=1.05)
  set_payload(1.0, [0.0, 0.0, 0.05])
end
"""
FANUC = """/PROG  GRIP_DEMO
/ATTR
COMMENT\t\t= "hand";
DEFAULT_GROUP\t= 1,*,*,*,*;
/MN
   1:  UFRAME_NUM=0 ;
   2:  UTOOL_NUM=1 ;
   3:  J P[1] 100% FINE ;
   4:  !box taken: 3.000 kg ;
   5:  PAYLOAD[1] ;
   6:  J P[1] 100% FINE ;
   7:  !box left: 1.000 kg ;
   8:  PAYLOAD[2] ;
/POS
P[1]{
   GP1:
\tUF : 0, UT : 1,\t\tCONFIG : 'N U T, 0, 0, 0',
\tX =   600.000  mm,\tY =     0.000  mm,\tZ =   800.000  mm,
\tW =   180.000 deg,\tP =     0.000 deg,\tR =     0.000 deg
};
/END
"""
FILES = {"rapid": {"grip_demo.mod": RAPID}, "krl": {"grip_demo.src": KRL_SRC, "grip_demo.dat": KRL_DAT},
         "urscript": {"grip_demo.script": URSCRIPT}, "fanuc": {"GRIP_DEMO.ls": FANUC}}
SWITCH_LINES = {"rapid": (7, 9), "krl": (6, 8), "urscript": (5, 7), "fanuc": (10, 13)}  # vendor file lines


def _import(tmp_path: Path, vendor: str, cell: str | None) -> tuple[int, str, str]:
    paths = []
    for name, text in FILES[vendor].items():
        (tmp_path / name).write_text(text)
        paths.append(str(tmp_path / name))
    args = ["import", paths[0], "-o", str(tmp_path / "out.rmot")]
    if cell is not None:
        (tmp_path / "cell.rmot").write_text(cell)
        args += ["--cell", str(tmp_path / "cell.rmot")]
    result = CliRunner().invoke(cli, args, catch_exceptions=False)
    return result.exit_code, result.output, (tmp_path / "out.rmot").read_text()


def _statements(program: str) -> list[str]:
    return [line.strip() for line in program.splitlines() if line.startswith("  ") and not line.strip().startswith(("#", "target"))]


@pytest.mark.parametrize("vendor", sorted(FILES))
def test_switches_become_attach_and_detach(vendor: str, tmp_path: Path) -> None:
    code, output, program = _import(tmp_path, vendor, CELL)
    assert code == 0, output
    body = _statements(program)
    grips = [s for s in body if s.split()[0] in ("attach", "detach")]
    assert grips == ["attach box1", "detach box1"], program
    # each at the switch's place: after the first move, after the second
    moves = [i for i, s in enumerate(body) if s.startswith("move")]
    assert body.index("attach box1") == moves[0] + 1 and body.index("detach box1") == moves[1] + 1, program
    assert "W510" not in output and "W516" not in output, output
    assert " 0 kept native (100.0 % imported)" in output, output


@pytest.mark.parametrize("vendor", sorted(FILES))
def test_two_parts_fit_kept_native_naming_both(vendor: str, tmp_path: Path) -> None:
    code, output, program = _import(tmp_path, vendor, TWIN)
    assert code == 0, output
    line = SWITCH_LINES[vendor][0]
    assert re.search(rf":{line}:\d+: warning\[W516\]: .*box1, box2", output), output
    assert not re.search(rf":{line}:\d+: warning\[W510\]", output), output  # one warning a line
    assert "attach" not in program and f"native {vendor}" in program, program


@pytest.mark.parametrize("vendor", sorted(FILES))
def test_without_a_cell_kept_native(vendor: str, tmp_path: Path) -> None:
    code, output, program = _import(tmp_path, vendor, None)
    assert code == 0, output
    for line in SWITCH_LINES[vendor]:
        assert re.search(rf":{line}:\d+: warning\[W510\]", output), output
    assert "attach" not in program and "detach" not in program, program


@pytest.mark.parametrize("data", [
    "[2.5,[0,0,50]",  # 2.5 kg: neither box1 (2 kg) nor plate (5 kg)
    "[2,[0,0,150]",  # box1's mass, its centre 150 mm from the TCP: beyond its 122.5 mm half-diagonal
])
def test_no_part_fits_kept_native(data: str, tmp_path: Path) -> None:
    files = dict(FILES["rapid"])
    FILES["rapid"] = {"grip_demo.mod": RAPID.replace("[2,[0,0,50]", data)}
    try:
        code, output, program = _import(tmp_path, "rapid", CELL)
    finally:
        FILES["rapid"] = files
    assert code == 0 and "warning[W516]" in output and "no part of the cell (box1, plate)" in output, output
    assert 'native rapid "GripLoad box_load;"' in program and "loaddata box_load" in program, program
