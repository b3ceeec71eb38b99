"""Every example of LANGUAGE.md parses and lowers, with the cell and files it needs."""

from __future__ import annotations

from pathlib import Path

import pytest

from rmot.lang import ir
from rmot.compiler.frontend import load_program
from rmot.compiler.passes.context import RobotInfo, default_robot_loader
from rmot.lang.diagnostics import render

# verbatim from LANGUAGE.md section 3
CELL = '''cell demo {
  robot r1 = abb_irb120 at pose(x=0mm)                 # from the built-in robot library
  robot r2 = urdf("robots/ur5.urdf") at pose(x=1200mm, rz=180deg)
  fixture table = box(800mm, 600mm, 30mm) at pose(x=500mm, z=-15mm)
  fixture post  = cylinder(r=40mm, h=900mm) at pose(x=-400mm, y=300mm)
  fixture fence = mesh("meshes/fence.stl", unit=mm) at pose(y=-900mm)
  tool gripper  = mesh("meshes/gripper.stl") tcp pose(z=150mm) mass 1.2 kg on r1
  frame table_top = table * pose(z=15mm)
  io out[1] = "gripper_close" on r1
  io in[2]  = "part_present" on r1
}
'''

# verbatim from LANGUAGE.md section 4
PICK_PLACE = r'''use cell "cells/demo.rmot"

program pick_place on r1 {
  tool gripper                      # active tool (default: the robot flange)
  frame table_top                   # active reference frame (default: the robot base)
  speed 500 mm/s                    # default TCP speed of linear/circular moves
  joint_speed 50 %                  # default share of each joint's max speed for joint moves
  accel 2 m/s^2
  zone 5 mm                         # blending radius; `zone fine` = exact stop

  target home  = joints(0, -30, 30, 0, 60, 0) deg
  target above = pose(x=100mm, y=200mm, z=150mm, rx=180deg)
  const rows = 3

  proc pick(p: pose) {
    move linear shift(p, z=50mm)
    move linear p speed 100 mm/s zone fine
    set out[1] = on
    wait 300 ms
    move linear shift(p, z=50mm)
  }

  move joint home
  for r in 0 .. rows {               # compile-time loop: r = 0, 1, 2
    pick(shift(above, x=r * 80mm, z=-150mm))
    move joint home config(shoulder=front, elbow=up, wrist=noflip)
  }
  move circular via pose(x=300mm, y=100mm, z=200mm, rx=180deg)
                to   pose(x=200mm, z=200mm, rx=180deg) speed 50 mm/s
  if in[2] == on { move joint home } else { wait until in[2] == on timeout 5 s }
  pulse out[3] for 200 ms
  native rapid "TPWrite \"cycle done\";"   # emitted by that backend only
}
'''

# verbatim from LANGUAGE.md section 4, "Several robots"; the targets come from an import
HANDOVER = '''program handover {
  task r1 { move joint a1; sync meet; move linear a2 }
  task r2 { move joint b1; sync meet; move linear b2 }
}
'''
HANDOVER_TARGETS = '''target a1 = joints(0, -20, 20, 0, 60, 0) deg
target a2 = pose(x=400mm, z=300mm, rx=180deg)
target b1 = joints(0, -90, 90, -90, -90, 0) deg
target b2 = pose(x=-400mm, z=300mm, rx=180deg)
'''


def _loader(key: str) -> RobotInfo:
    """The real robot library; the URDF of the example stands for a 6-axis arm."""
    return RobotInfo(6, ("R",) * 6) if key.endswith(".urdf") else default_robot_loader(key)


@pytest.fixture
def project(tmp_path: Path) -> Path:
    (tmp_path / "cells" / "meshes").mkdir(parents=True)
    (tmp_path / "cells" / "robots").mkdir()
    (tmp_path / "cells" / "demo.rmot").write_text(CELL)
    for mesh in ("fence.stl", "gripper.stl"):
        (tmp_path / "cells" / "meshes" / mesh).write_text("solid m\nendsolid m\n")
    (tmp_path / "cells" / "robots" / "ur5.urdf").write_text("<robot name='ur5'/>")
    return tmp_path


def _load(path: Path) -> ir.Program | ir.Cell:
    result = load_program(str(path), robot_loader=_loader)
    assert not result.has_errors, "\n".join(render(d) for d in result.diagnostics)
    return result.program or result.cell  # type: ignore[return-value]


def test_cell_example(project: Path) -> None:
    """The cell: two robots (library + URDF), three fixtures, a tool, a frame on a fixture, two signals."""
    cell = _load(project / "cells" / "demo.rmot")
    assert isinstance(cell, ir.Cell)
    assert [r.source.kind for r in cell.robots] == [ir.RobotSourceKind.LIBRARY, ir.RobotSourceKind.URDF]
    assert [type(f.geometry) for f in cell.fixtures] == [ir.Box, ir.Cylinder, ir.Mesh]
    assert cell.frames[0].pose.position == pytest.approx((0.5, 0.0, 0.0))  # table centre at z=-15mm, +15mm
    assert cell.tools[0].tcp.position == pytest.approx((0, 0, 0.15)) and cell.tools[0].mass == pytest.approx(1.2)


def test_pick_place_example(project: Path) -> None:
    """The program: a loop of 3 picks (each iteration lowered), a circular move, a runtime if, a
    pulse and native text."""
    (project / "pick_place.rmot").write_text(PICK_PLACE)
    prog = _load(project / "pick_place.rmot")
    assert isinstance(prog, ir.Program)
    body = prog.tasks[0].body
    kinds = [type(i).__name__ for i in body]
    assert kinds == ["Move", "Loop", "Move", "If", "Pulse", "Native"]
    loop = body[1]
    assert isinstance(loop, ir.Loop) and [it.value for it in loop.iterations] == [0, 1, 2]
    kinds_per_iteration = [[type(i).__name__ for i in it.body] for it in loop.iterations]
    assert kinds_per_iteration == [["ProcCall", "Move"]] * 3
    circular = body[2]
    assert isinstance(circular, ir.Move) and circular.kind is ir.MotionKind.CIRCULAR and circular.via is not None


def test_handover_example(project: Path) -> None:
    """Two tasks with a matching sync barrier."""
    (project / "targets.rmot").write_text(HANDOVER_TARGETS)
    (project / "handover.rmot").write_text('use cell "cells/demo.rmot"\nimport "targets.rmot"\n' + HANDOVER)
    prog = _load(project / "handover.rmot")
    assert isinstance(prog, ir.Program)
    assert [[type(i).__name__ for i in t.body] for t in prog.tasks] == [["Move", "Sync", "Move"]] * 2
