"""Every vendor writes what the plan assumed for joint-move speeds:
`speed R %` on a joint move gives the same files as `joint_speed R %`, and a TCP speed on a
joint move (W170, not used by the plan) gives the same files as no speed at all — no backend
turns it into a controller TCP limit the plan did not time (ABB MoveJ writes vmax, VAL3 movej
tmax 9999, KRL PTP/Fanuc J/INFORM MOVJ/URScript movej take joint speeds only)."""

from __future__ import annotations

import pytest
from rmot.backends import BACKENDS
from rmot.compiler.frontend import load_text
from rmot.compiler.plan import plan_program

ARMS = {
    "rapid": "abb_irb120",
    "krl": "kuka_kr6_r900",
    "fanuc": "fanuc_lrmate200id",
    "inform": "yaskawa_gp8",
    "val3": "staubli_tx2_60",
    "urscript": "ur5e",
}


def emitted(vendor: str, modifier: str) -> dict[str, str]:
    text = f"""cell c {{
  robot r1 = {ARMS[vendor]}
}}
program speeds on r1 {{
  target home = joints(0, 10, 20, 0, 30, 0) deg
  target other = joints(40, 20, 10, 30, 40, 50) deg
  move joint home
  move joint other {modifier}
  move joint home
}}
"""
    front = load_text(text, "speeds.rmot")
    assert front.program is not None, [d.message for d in front.diagnostics]
    plan = plan_program(front.program)
    assert not [d for d in plan.diagnostics if d.is_error]
    result = BACKENDS[vendor]().emit(plan)
    assert not result.has_errors
    return result.files


@pytest.mark.parametrize("vendor", sorted(ARMS))
def test_speed_percent_is_written_as_joint_speed(vendor: str) -> None:
    a, b = emitted(vendor, "speed 20 %"), emitted(vendor, "joint_speed 20 %")
    assert a == b
    assert a != emitted(vendor, "")  # the share is written: the files differ from full speed


@pytest.mark.parametrize("vendor", sorted(ARMS))
def test_tcp_speed_on_a_joint_move_is_not_written(vendor: str) -> None:
    assert emitted(vendor, "speed 100 mm/s") == emitted(vendor, "")
