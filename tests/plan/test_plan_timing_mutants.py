"""Timing behaviour that mutation testing (`make mutation`) found untested.

Every expectation is computed here from the motion model's definition (synchronised straight
line, trapezoid, uniform time stretch, TCP speed of the TCP path), not read from the code.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from rmot.compiler.plan.timing import (
    HoldPiece, PathPiece, TimingError, joint_move_piece, path_piece, stretched,
)


def _trapezoid(length: float, v: float, a: float) -> float:
    """Rest-to-rest time over `length` at path speed <= v and path acceleration <= a."""
    if v * v / a >= length:
        return 2.0 * math.sqrt(length / a)
    return length / v + v / a


def _dense(piece: PathPiece | HoldPiece, n: int = 4001) -> tuple[np.ndarray, ...]:
    t = np.linspace(0.0, piece.duration, n)
    return (t, *piece.sample(t))


class TestJointMove:
    @pytest.mark.parametrize(("q1", "vmax", "amax"), [
        ([1.0, -0.5, 0.25], [1.0, 2.0, 3.0], [4.0, 1.0, 9.0]),  # speed and accel bound by other joints
        ([0.05, 0.02, -0.01], [1.0, 1.0, 1.0], [2.0, 2.0, 2.0]),  # a triangle
        ([3.0, 0.0, 0.0], [0.5, 0.0, 0.0], [1.0, 0.0, 0.0]),  # limits of still joints do not matter
    ])
    def test_duration_is_the_synchronised_trapezoid(self, q1: list[float], vmax: list[float],
                                                    amax: list[float]) -> None:
        """The path speed and acceleration limits of the line are the tightest per-joint
        limits divided by the joint's share of the direction; the duration is their trapezoid."""
        q0, q1a, v, a = np.zeros(3), np.array(q1), np.array(vmax), np.array(amax)
        length = float(np.linalg.norm(q1a))
        share = np.abs(q1a) / length
        moving = share > 0
        v_path = float(np.min(v[moving] / share[moving]))
        a_path = float(np.min(a[moving] / share[moving]))
        piece = joint_move_piece(q0, q1a, v, a)
        assert piece.duration == pytest.approx(_trapezoid(length, v_path, a_path), rel=1e-12)

    def test_profile_starts_and_ends_at_rest_on_the_targets_within_limits(self) -> None:
        """q(0) = q0, q(T) = q1, rest at both ends, every joint within its limits and the
        binding one at its speed limit on the flat part (time-optimal)."""
        q0, q1 = np.array([0.2, -0.1, 0.0]), np.array([1.7, 0.4, -0.3])
        v, a = np.array([1.0, 0.4, 2.0]), np.array([3.0, 3.0, 3.0])
        piece = joint_move_piece(q0, q1, v, a)
        _, q, qd, qdd = _dense(piece)
        assert np.allclose(q[0], q0, atol=1e-12) and np.allclose(q[-1], q1, atol=1e-9)
        assert np.allclose(qd[[0, -1]], 0.0, atol=1e-9)
        assert np.all(np.abs(qd) <= v * (1 + 1e-9)) and np.all(np.abs(qdd) <= a * (1 + 1e-9))
        assert np.max(np.abs(qd) / v) == pytest.approx(1.0, rel=1e-9)
        assert np.allclose(piece.end_q(), q1, atol=1e-9)

    def test_acceleration_is_plus_a_then_zero_then_minus_a(self) -> None:
        """One joint, trapezoid: qdd = +a while speeding up, 0 at top speed, -a while braking."""
        v, a, dist = 1.0, 2.0, 3.0
        piece = joint_move_piece(np.zeros(1), np.array([dist]), np.array([v]), np.array([a]))
        ramp = v / a
        t = np.array([0.25 * ramp, 0.5 * piece.duration, piece.duration - 0.25 * ramp])
        q, qd, qdd = piece.sample(t)
        assert qdd[:, 0] == pytest.approx([a, 0.0, -a], abs=1e-9)
        assert qd[:, 0] == pytest.approx([a * t[0], v, a * 0.25 * ramp], rel=1e-9)
        assert q[0, 0] == pytest.approx(0.5 * a * t[0] ** 2, rel=1e-9)

    def test_zero_move_holds_for_the_given_time(self) -> None:
        q0 = np.array([0.1, 0.2])
        hold = joint_move_piece(q0, q0.copy(), np.ones(2), np.ones(2), duration=1.5)
        assert hold.duration == 1.5
        q, qd, qdd = hold.sample(np.array([0.0, 1.5]))
        assert np.array_equal(q, [q0, q0]) and not qd.any() and not qdd.any()
        assert joint_move_piece(q0, q0.copy(), np.ones(2), np.ones(2)).duration == 0.0

    @pytest.mark.parametrize("bad", [0.0, -1.0])
    def test_non_positive_limit_of_a_moving_joint_is_an_error(self, bad: float) -> None:
        with pytest.raises(TimingError, match="must be positive"):
            joint_move_piece(np.zeros(2), np.array([1.0, 1.0]), np.array([1.0, bad]), np.ones(2))
        with pytest.raises(TimingError, match="must be positive"):
            joint_move_piece(np.zeros(2), np.array([1.0, 1.0]), np.ones(2), np.array([bad, 1.0]))

    def test_fixed_duration_exactly_the_fastest_is_accepted_and_the_message_names_both(self) -> None:
        q1, v, a = np.array([1.0]), np.array([1.0]), np.array([1.0])
        fastest = _trapezoid(1.0, 1.0, 1.0)  # triangle: 2 s
        assert joint_move_piece(np.zeros(1), q1, v, a, duration=fastest).duration == pytest.approx(fastest)
        with pytest.raises(TimingError) as err:
            joint_move_piece(np.zeros(1), q1, v, a, duration=1.5)
        assert str(err.value) == "time must be at least the fastest feasible 2.000 s (got 1.500 s)"


class TestStretch:
    def test_stretch_is_uniform_in_time(self) -> None:
        """Stretched by k: q(k t) = q(t), qd / k, qdd / k^2, same end, duration k T."""
        piece = joint_move_piece(np.zeros(2), np.array([1.0, -2.0]), np.ones(2), np.full(2, 2.0))
        assert isinstance(piece, PathPiece)
        k = 1.7
        slow = stretched(piece, piece.duration * k)
        assert slow.duration == pytest.approx(piece.duration * k, rel=1e-12)
        t = np.linspace(0.0, piece.duration, 57)
        q, qd, qdd = piece.sample(t)
        qs, qds, qdds = slow.sample(t * k)
        assert np.allclose(qs, q, atol=1e-12)
        assert np.allclose(qds, qd / k, atol=1e-12) and np.allclose(qdds, qdd / k**2, atol=1e-12)
        assert slow.time_at(0.5) == pytest.approx(piece.time_at(0.5) * k, rel=1e-12)

    def test_time_at_inverts_the_path_parameter(self) -> None:
        """time_at(s) is the instant the path reaches s: the trapezoid's closed form (speed
        0.5, acceleration 2: ramps of 0.0625 over 0.25 s each), and the sampled path there."""
        v, a = 0.5, 2.0
        piece = joint_move_piece(np.zeros(2), np.array([2.0, 0.0]), np.full(2, v), np.full(2, a))
        assert isinstance(piece, PathPiece)
        ramp, t_ramp = v * v / (2 * a), v / a
        for s in (0.0, 0.03, 0.0625, 1.0, 1.9375, 1.97, 2.0):  # joint 1 is the path parameter here
            if s <= ramp:
                expected = math.sqrt(2 * s / a)
            elif s <= 2.0 - ramp:
                expected = t_ramp + (s - ramp) / v
            else:
                expected = piece.duration - math.sqrt(2 * (2.0 - s) / a)
            t = piece.time_at(s)
            assert t == pytest.approx(expected, abs=1e-9)
            assert piece.sample(np.array([t]))[0][0, 0] == pytest.approx(s, abs=1e-9)


class TestPathTcpLimits:
    """A path whose first three coordinates are the TCP position (an identity arm): the TCP
    speed and acceleration are then those of q[:3], computed here by finite differences."""

    def _path(self) -> tuple[np.ndarray, np.ndarray]:
        u = np.linspace(0.0, 1.0, 120)
        wp = np.stack([0.6 * np.cos(2 * u), 0.6 * np.sin(2 * u), 0.2 * u], axis=1)
        arc = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(wp, axis=0), axis=1))])
        return wp, arc

    def test_tcp_speed_limit_holds_and_is_reached(self) -> None:
        wp, ss = self._path()
        v, a = np.full(3, 10.0), np.full(3, 50.0)
        limit = 0.25
        piece = path_piece(wp, ss, v, a, 3, tcp=wp, tcp_speed=np.full(len(ss), limit),
                           tcp_accel=np.full(len(ss), np.inf))
        free = path_piece(wp, ss, v, a, 3)
        _, _, qd, _ = _dense(piece)
        speed = np.linalg.norm(qd, axis=1)
        assert np.max(speed) <= limit * (1 + 1e-6)
        assert np.max(speed) == pytest.approx(limit, rel=1e-3)
        assert piece.duration > free.duration * 2  # the joints alone would go much faster
        assert piece.duration == pytest.approx(ss[-1] / limit, rel=0.05)  # mostly at the limit

    def test_tcp_accel_limit_holds(self) -> None:
        wp, ss = self._path()
        v, a = np.full(3, 10.0), np.full(3, 50.0)
        acc = 0.5
        piece = path_piece(wp, ss, v, a, 3, tcp=wp, tcp_speed=np.full(len(ss), np.inf),
                           tcp_accel=np.full(len(ss), acc))
        t, _, qd, _ = _dense(piece, 8001)
        speed = np.linalg.norm(qd, axis=1)
        tangential = np.diff(speed) / np.diff(t)
        assert np.max(np.abs(tangential)) <= acc * (1 + 1e-2)
        # rest to rest at |s''| <= acc over the length: at least the triangle time
        assert piece.duration >= 2 * math.sqrt(ss[-1] / acc) * (1 - 1e-6)

    def test_velocity_scale_per_waypoint(self) -> None:
        """vscale halves the joint speed limit on the second half of a straight path."""
        ss = np.linspace(0.0, 2.0, 81)
        wp = np.stack([ss, np.zeros_like(ss)], axis=1)
        scale = np.where(ss <= 1.0, 1.0, 0.5)
        piece = path_piece(wp, ss, np.ones(2), np.full(2, 100.0), 2, scale)
        t, q, qd, _ = _dense(piece)
        late = q[:, 0] > 1.1
        assert np.max(np.abs(qd[late, 0])) <= 0.5 * (1 + 1e-6)
        assert np.max(np.abs(qd[q[:, 0] < 0.9, 0])) == pytest.approx(1.0, rel=1e-3)
        assert piece.duration == pytest.approx(1.0 / 1.0 + 1.0 / 0.5, rel=0.03)
