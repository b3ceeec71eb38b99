"""torque.exceeds samples a timed chain EXCEEDS_CHUNK samples at a time (bounded
memory): the same answer as one pass over every sample, on a case of many chunks whose only
excess lies in a late chunk, on one without any excess, and the same torques, bit for bit."""

from __future__ import annotations

import numpy as np
import pytest

from rmot.compiler.plan import torque as torque_mod
from rmot.compiler.plan.move_chain import SequencePiece
from rmot.compiler.plan.timing import HoldPiece, joint_move_piece
from rmot.sim.robots import load_robot

# the UR5e swinging its arm up through horizontal (tests/plan/test_plan_torque.py): with 8 kg
# at the tool the plain timing needs more than J2's rating, with 1 kg it does not
START, END = np.radians([0, -160, 0, -90, -90, 0]), np.radians([0, -20, 0, -90, -90, 0])


def _swing_after_rest(rest_s: float = 0.5) -> SequencePiece:
    """Standing still at START (gravity only: within the ratings), then the swing: an excess
    only in the last part of the piece."""
    robot = load_robot("ur5e")
    swing = joint_move_piece(START, END, robot.velocity_limits, robot.accel_limits)
    return SequencePiece((HoldPiece(START.copy(), rest_s), swing), 6)


def _limits(mass: float) -> torque_mod.TorqueLimits:
    limits = torque_mod.torque_limits(load_robot("ur5e"), mass, np.array([0.0, 0.0, 0.05]))
    assert limits is not None  # the UR5e has cited torque ratings
    return limits


@pytest.mark.parametrize("mass, expected", [(8.0, True), (1.0, False)])
def test_exceeds_in_chunks_equals_one_pass(monkeypatch: pytest.MonkeyPatch, mass: float,
                                           expected: bool) -> None:
    piece, limits = _swing_after_rest(), _limits(mass)
    n = int(np.ceil(piece.duration / torque_mod.CHECK_STEP)) + 1
    times = np.linspace(0.0, piece.duration, n)
    tau = limits.torques(*piece.sample(times))
    over = np.any(np.abs(tau) > limits.limit, axis=1)
    assert bool(over.any()) is expected
    if expected:  # the excess lies beyond the rest, many chunks of 7 samples in
        assert int(np.argmax(over)) > 0.5 / torque_mod.CHECK_STEP > 10 * 7
    monkeypatch.setattr(torque_mod, "EXCEEDS_CHUNK", 10**9)
    assert torque_mod.exceeds(limits, piece) is expected
    monkeypatch.setattr(torque_mod, "EXCEEDS_CHUNK", 7)
    assert torque_mod.exceeds(limits, piece) is expected
    # the chunks' torques are the one pass's, to the bit: no sample near a rating can flip
    parts = [limits.torques(*piece.sample(times[lo:lo + 7])) for lo in range(0, n, 7)]
    assert np.array_equal(np.concatenate(parts), tau)
