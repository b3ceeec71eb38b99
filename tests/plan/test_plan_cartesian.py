"""Line and arc geometry with SLERP orientation (no robot involved)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rmot.compiler.plan.cartesian import DegenerateArc, arc_path, line_path, rotation_angle, slerp


def _pose(p, rz=0.0):  # type: ignore[no-untyped-def]
    t = np.eye(4)
    c, s = np.cos(rz), np.sin(rz)
    t[:2, :2] = [[c, -s], [s, c]]
    t[:3, 3] = p
    return t


class TestLine:
    def test_positions_are_on_the_segment_at_constant_spacing(self) -> None:
        """Equal steps of u are equal steps along the line."""
        path = line_path(_pose([0, 0, 0]), _pose([0.3, 0.4, 0]))
        pts = path.positions(np.linspace(0, 1, 11))
        assert path.length == pytest.approx(0.5)
        assert np.allclose(np.linalg.norm(np.diff(pts, axis=0), axis=1), 0.05)
        assert np.max(path.distance(pts)) < 1e-15

    def test_orientation_follows_the_shortest_rotation(self) -> None:
        """SLERP from rz=0 to rz=270 deg turns -90 deg (the short way), evenly."""
        path = line_path(_pose([0, 0, 0]), _pose([0.1, 0, 0], np.radians(270)))
        assert path.angle == pytest.approx(np.pi / 2)
        mid = path.poses(np.array([0.5]))[0]
        assert np.degrees(np.arctan2(mid[1, 0], mid[0, 0])) == pytest.approx(-45.0)

    def test_distance_of_an_offset_point(self) -> None:
        """A point 2 mm beside the line is 2 mm from it."""
        path = line_path(_pose([0, 0, 0]), _pose([1, 0, 0]))
        assert path.distance(np.array([[0.5, 0.002, 0]]))[0] == pytest.approx(0.002)


class TestArc:
    def test_arc_passes_through_via_and_keeps_its_radius(self) -> None:
        """The half circle from (0,0) through (0.1,0.1) to (0.2,0): radius 0.1, centre (0.1,0)."""
        path = arc_path(_pose([0, 0, 0]), np.array([0.1, 0.1, 0]), _pose([0.2, 0, 0]))
        assert path.radius == pytest.approx(0.1)
        assert np.allclose(path.center, [0.1, 0, 0])
        pts = path.positions(np.linspace(0, 1, 51))
        assert np.allclose(np.linalg.norm(pts - path.center, axis=1), 0.1)
        assert np.allclose(path.positions(np.array([path.u_at_via(np.array([0.1, 0.1, 0]))]))[0], [0.1, 0.1, 0])
        assert path.length == pytest.approx(np.pi * 0.1)

    @settings(max_examples=40, deadline=None)
    @given(st.lists(st.floats(-0.5, 0.5), min_size=9, max_size=9))
    def test_any_three_distinct_points_give_a_circle_through_all(self, xs: list[float]) -> None:
        """Property: start, via and end lie on the arc's circle, and the arc ends at the end."""
        p0, p1, p2 = np.array(xs[:3]), np.array(xs[3:6]), np.array(xs[6:])
        try:
            path = arc_path(_pose(p0), p1, _pose(p2))
        except DegenerateArc:
            return
        assert np.max(path.distance(np.stack([p0, p1, p2]))) < 1e-7
        assert np.allclose(path.positions(np.array([1.0]))[0], p2, atol=1e-7)
        assert 0 < path.u_at_via(p1) < 1

    @pytest.mark.parametrize(("via", "end", "word"), [
        ([0.1, 0, 0], [0.2, 0, 0], "collinear"),
        ([0.0, 0, 0], [0.2, 0, 0], "distinct"),
        ([0.1, 0.1, 0], [0.0, 0, 0], "distinct"),
    ])
    def test_degenerate_arcs_are_rejected_with_a_reason(self, via, end, word) -> None:  # type: ignore[no-untyped-def]
        """Collinear or coincident points raise DegenerateArc naming the problem."""
        with pytest.raises(DegenerateArc, match=word):
            arc_path(_pose([0, 0, 0]), np.array(via), _pose(end))


def test_slerp_endpoints_and_unit_norm() -> None:
    """SLERP starts and ends at its quaternions and stays unit length."""
    q0 = np.array([1.0, 0, 0, 0])
    q1 = np.array([np.cos(0.5), 0, np.sin(0.5), 0])
    out = slerp(q0, q1, np.linspace(0, 1, 7))
    assert np.allclose(out[0], q0) and np.allclose(out[-1], q1)
    assert np.allclose(np.linalg.norm(out, axis=1), 1)
    assert rotation_angle(q0, q1) == pytest.approx(1.0)
