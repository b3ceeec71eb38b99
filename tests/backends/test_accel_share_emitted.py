"""A joint move blended with a slower-accelerating one is timed with the chain's smallest
`accel` (one constant set of limits per blended chain); KRL's RMOT_PTP tells the controller the
share the plan timed each move with (InstructionRecord.accel_share), not the move's own `accel`.

Witness: the planned trajectory itself: over the last move's interval, the largest joint
acceleration as a share of that joint's limit (the robot model's `accel_limits`) is what the
verified motion used; the printed share must cover it and not exceed it by more than 3 %
(a time-optimal stop reaches its limit). Printing the move's own 100 % fails this.
"""

from __future__ import annotations

import re

import numpy as np
from backend_fixtures import ROOT
from rmot.backends import BACKENDS
from rmot.lang import ir
from rmot.compiler.frontend import load_text
from rmot.compiler.plan import plan_program
from rmot.sim.robots.loader import load_robot

PROGRAM = """program acc on r1 {
  move joint joints(0, 0, 0, 0, 45, 0) deg zone fine
  move joint joints(40, 10, 10, 0, 45, 0) deg accel 40 % zone 50 mm
  move joint joints(80, 0, 20, 0, 45, 0) deg zone fine
}
"""


def test_krl_prints_the_share_the_chain_was_timed_with() -> None:
    front = load_text(PROGRAM, str(ROOT / "acc.rmot"))
    assert front.program is not None, [d.message for d in front.diagnostics]
    plan = plan_program(front.program)
    (tp,) = plan.tasks
    robot = next(r for r in plan.program.cell.robots if r.name == tp.robot)
    limits = np.asarray(load_robot(robot.source.load_key).accel_limits)
    moves = [i for i in tp.task.body if isinstance(i, ir.Move)]
    last = tp.record(moves[-1].uid)
    assert last is not None
    traj = tp.trajectory
    inside = (traj.t >= last.t_start - 1e-9) & (traj.t <= last.t_end + 1e-9)
    used = float(np.max(np.abs(traj.qdd[inside]) / limits))
    (src,) = (t for n, t in BACKENDS["krl"]().emit(plan).files.items() if n.endswith(".src"))
    shares = [float(a) / 100.0 for a in re.findall(r"RMOT_PTP\([\d.]+,([\d.]+)\)", src)]
    assert len(shares) == 3
    assert used - 1e-3 <= shares[-1] <= used + 0.03, (shares, used)


def test_fanuc_and_inform_print_the_chain_share_too() -> None:
    """Fanuc `ACCn` and INFORM `ACC=n DEC=n` on both moves of the chain timed at 40 %."""
    front = load_text(PROGRAM, str(ROOT / "acc.rmot"))
    assert front.program is not None
    plan = plan_program(front.program)
    fanuc = "\n".join(BACKENDS["fanuc"]().emit(plan).files.values())
    assert re.findall(r"^\s*\d+:\s+J P\[\d+\] \d+% \w+(.*?) ;$", fanuc, re.M) == ["", " ACC40", " ACC40"]
    inform = "\n".join(BACKENDS["inform"]().emit(plan).files.values())
    assert re.findall(r"^MOVJ \S+ VJ=\S+(?: PL=\d)?(.*)$", inform, re.M) == ["", " ACC=40 DEC=40", " ACC=40 DEC=40"]
