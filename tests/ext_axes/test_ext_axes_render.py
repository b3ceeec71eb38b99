"""Pictures move what external axes carry: the jig on the positioner and the arm on the track
stand, at each instant, where the witness kinematics (ext_axes_witness.py) put them for the
axis values of that instant, and the drawn TCP path follows the carriage."""

from __future__ import annotations

import numpy as np
from ext_axes_witness import CELL, at, positioner_flange, robot_base

from rmot.compiler.frontend import load_text
from rmot.compiler.plan import plan_program
from rmot.sim.render.scene import body_poses, prepare

PROGRAM = """program p on r1 with rail, pos {
  move joint joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg)
  move joint joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg) ext(rail=1500mm, pos=(30deg, 120deg))
}
"""


def test_bodies_stand_where_their_axes_put_them() -> None:
    front = load_text(CELL + PROGRAM, "/tmp/ext_axes_render.rmot")
    assert front.program is not None, [d.message for d in front.diagnostics]
    plan = plan_program(front.program)
    rs = prepare(plan, samples=4)
    end = float(plan.cycle_time)
    start_poses, end_poses = body_poses(rs, np.array([0.0, end]))
    jig = rs.names.index("jig")
    assert np.allclose(start_poses[jig], positioner_flange(0, 0) @ at(z=0.02), atol=1e-9)
    assert np.allclose(end_poses[jig], positioner_flange(30, 120) @ at(z=0.02), atol=1e-9)
    base = rs.names.index(next(n for n in rs.names if n.startswith("r1/")))
    # the same joints at both instants: every link moved exactly by the carriage's 1500 mm
    assert np.allclose(end_poses[base], robot_base(1500) @ np.linalg.inv(robot_base(0)) @ start_poses[base], atol=1e-9)
    path = rs.paths[0]
    assert path[-1][0] - path[0][0] > 1.49  # the TCP path follows the carriage along x
