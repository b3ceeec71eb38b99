"""Timing pieces (one acceleration-limited model): exact limits, analytic durations, time stretching."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rmot.compiler.plan.timing import TimingError, joint_move_piece, path_piece, stretched


def trapezoid_time(dist: float, v: float, a: float) -> float:
    """Rest-to-rest time of one axis under |v|, |a| limits (the textbook trapezoid/triangle)."""
    if v * v / a >= dist:
        return 2 * math.sqrt(dist / a)
    return dist / v + v / a


class TestJointMove:
    @pytest.mark.parametrize("dist", [0.05, 0.5, 1.0, 3.0])
    def test_single_joint_duration_equals_the_trapezoid_time(self, dist: float) -> None:
        """One joint moving: the duration equals the analytic trapezoid time."""
        v, a = np.array([2.0, 1.0, 1.0]), np.array([6.0, 3.0, 3.0])
        piece = joint_move_piece(np.zeros(3), np.array([dist, 0, 0]), v, a)
        expected = trapezoid_time(dist, 2.0, 6.0)
        assert piece.duration == pytest.approx(expected, rel=1e-9)

    def test_all_joints_start_and_stop_together_on_a_straight_line(self) -> None:
        """Phase synchronisation: q(t) stays on the joint-space line from start to target."""
        q0, q1 = np.zeros(3), np.array([1.0, -0.3, 0.1])
        piece = joint_move_piece(q0, q1, np.full(3, 1.0), np.full(3, 3.0))
        q, qd, _ = piece.sample(np.linspace(0, piece.duration, 101))
        frac = q[:, 0] / q1[0]
        assert np.allclose(q, frac[:, None] * q1, atol=1e-9)
        assert np.allclose(qd[[0, -1]], 0)

    def test_time_modifier_stretches_or_rejects(self) -> None:
        """A fixed duration is met exactly; one shorter than feasible is a TimingError."""
        q1 = np.array([1.0, 0.0])
        fast = joint_move_piece(np.zeros(2), q1, np.ones(2), np.full(2, 4.0))
        slow = joint_move_piece(np.zeros(2), q1, np.ones(2), np.full(2, 4.0), duration=3.0)
        assert slow.duration == pytest.approx(3.0)
        with pytest.raises(TimingError, match="at least"):
            joint_move_piece(np.zeros(2), q1, np.ones(2), np.full(2, 4.0), duration=fast.duration * 0.9)


class TestPathPiece:
    def _curve(self) -> tuple[np.ndarray, np.ndarray]:
        ss = np.linspace(0, 1, 80)
        return np.stack([np.sin(3 * ss), ss**2, np.cos(2 * ss)], axis=1), ss

    def test_limits_hold_at_every_dense_sample(self) -> None:
        """|qd| <= vmax (1+1e-6) and |qdd| <= amax (1+1e-3) on a 1 ms grid, not just toppra's."""
        wp, ss = self._curve()
        v, a = np.array([1.0, 0.8, 1.2]), np.array([2.0, 3.0, 2.5])
        piece = path_piece(wp, ss, v, a, 3)
        _, qd, qdd = piece.sample(np.arange(0, piece.duration, 0.0005))
        assert np.all(np.abs(qd) <= v * (1 + 1e-6))
        assert np.all(np.abs(qdd) <= a * (1 + 1e-3))
        assert np.max(np.abs(qd) / v) > 0.95  # and it is not needlessly slow

    def test_path_is_followed_and_rests_at_the_ends(self) -> None:
        """The timed trajectory starts and ends at the path's ends, at rest."""
        wp, ss = self._curve()
        piece = path_piece(wp, ss, np.ones(3), np.ones(3), 3)
        q, qd, _ = piece.sample(np.array([0.0, piece.duration]))
        assert np.allclose(q, wp[[0, -1]], atol=1e-9)
        assert np.allclose(qd, 0, atol=1e-9)

    def test_stretched_lasts_exactly_and_slows_down(self) -> None:
        """Stretching to T gives duration T and velocities scaled by the stretch."""
        wp, ss = self._curve()
        piece = path_piece(wp, ss, np.ones(3), np.ones(3), 3)
        long = stretched(piece, 2 * piece.duration)
        assert long.duration == pytest.approx(2 * piece.duration)
        _, qd1, _ = piece.sample(np.array([0.3 * piece.duration]))
        _, qd2, _ = long.sample(np.array([0.6 * piece.duration]))
        assert np.allclose(qd2, qd1 / 2)
