"""Collision, clearance and the no-miss guarantee, on hand-made plans with a small test arm."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from simkit import arm3, box, cell, make_plan, source, task_plan

from rmot.lang import ir
from rmot.sim import codes
from rmot.sim.verification import verify_with

STEP = 0.004


def _capsule_box_distance(pose: np.ndarray, length: float, radius: float, centre, size) -> float:
    """Independent reference: densely sampled capsule axis against an axis-aligned box."""
    s = np.linspace(-length / 2, length / 2, 400)
    pts = pose[:3, 3] + s[:, None] * pose[:3, 2]
    gap = np.abs(pts - np.asarray(centre)) - np.asarray(size) / 2
    outside = np.linalg.norm(np.maximum(gap, 0), axis=1)
    inside = np.minimum(np.max(gap, axis=1), 0)
    return float(np.min(outside + inside) - radius)


def _reference_contact_times(robot, traj_t, traj_q, solid: int, centre, size, fine: float = 2e-4):
    """Times (on a fine grid, linear joint interpolation) where a capsule solid touches the box."""
    geom = robot.solids[solid].geometry
    times = np.arange(traj_t[0], traj_t[-1], fine)
    q = np.stack([np.interp(times, traj_t, traj_q[:, j]) for j in range(traj_q.shape[1])], axis=1)
    poses = robot.solid_poses_batch(q)[:, solid]
    d = np.array([_capsule_box_distance(p, geom.length, geom.radius, centre, size) for p in poses])
    return times[d <= 0]


def _findings(report, code):
    return [d for d in report.diagnostics if d.code is code or d.code.id == code.id]


class TestFixtureCollision:
    def setup_method(self) -> None:
        self.file = source()
        self.robot = arm3("r1")
        # the arm swings through the vertical in move 2 (line 3); the box sits in link3's path
        self.centre, self.size = (0.0, 0.0, 1.2), (0.05, 0.05, 0.05)
        self.cell = cell([("r1", (0, 0, 0))], fixtures=[box("post", self.size, self.centre)])
        self.tp = task_plan("main", "r1", [(0, -1, 0), (0, -1, 0.2), (0, 1, 0.2), (0, 1, 0)], [0.5, 1.0, 0.5], self.file)
        self.report = verify_with(make_plan(self.cell, [self.tp], self.file), robots={"r1": self.robot})

    def test_found_at_the_move_with_the_bodies(self) -> None:
        """The obstacle across move 2 gives one E300 at line 3 naming link3 and the post."""
        hits = _findings(self.report, codes.COLLISION)
        assert len(hits) == 1
        assert hits[0].span.start.line == 3
        assert hits[0].bodies == ("r1/link3", "post")
        assert hits[0].amount.unit == "mm" and hits[0].amount.value > 0

    def test_time_within_one_sample(self) -> None:
        """Start and end of the finding match a fine-grid reference within one sample step."""
        ref = _reference_contact_times(self.robot, self.tp.trajectory.t, self.tp.trajectory.q, 3, self.centre, self.size)
        hit = _findings(self.report, codes.COLLISION)[0]
        assert ref.size > 0
        assert abs(hit.time_s - ref[0]) <= STEP
        assert abs(hit.end_time_s - ref[-1]) <= STEP

    def test_worst_instant_is_the_deepest_contact(self) -> None:
        """peak_time_s lies in the interval, and the reference depth there is the reported amount."""
        hit = _findings(self.report, codes.COLLISION)[0]
        assert hit.time_s <= hit.peak_time_s <= hit.end_time_s
        traj = self.tp.trajectory
        q = np.array([np.interp(hit.peak_time_s, traj.t, traj.q[:, j]) for j in range(traj.q.shape[1])])
        geom = self.robot.solids[3].geometry
        d = _capsule_box_distance(self.robot.solid_poses(q)[3], geom.length, geom.radius, self.centre, self.size)
        assert abs(-d * 1000 - hit.amount.value) < 0.5  # mm, the reference samples the axis at 400 points


class TestClearance:
    def _plan(self, gap: float):
        """The arm lies horizontal (+x) and turns about J1; a box hangs `gap` above link3."""
        file = source()
        link3_top = 0.4 + 0.04
        size = (0.15, 0.1, 0.05)
        fixture = box("shelf", size, (0.72, 0.0, link3_top + gap + size[2] / 2))
        c = cell([("r1", (0, 0, 0))], fixtures=[fixture])
        half = np.pi / 2
        tp = task_plan("main", "r1", [(-0.6, half, 0), (0.6, half, 0)], [1.0], file)
        return make_plan(c, [tp], file)

    def test_five_mm_is_not_a_collision(self) -> None:
        """A fixture 5 mm above the path gives no error at all."""
        report = verify_with(self._plan(0.005), robots={"r1": arm3("r1")})
        assert not report.has_errors

    def test_reported_with_clearance(self) -> None:
        """With a 10 mm clearance the 5 mm approach is one W301 warning with its distance."""
        report = verify_with(self._plan(0.005), robots={"r1": arm3("r1")}, clearance=0.010)
        near = _findings(report, codes.CLEARANCE)
        assert len(near) == 1 and not report.has_errors
        assert near[0].bodies == ("r1/link3", "shelf")
        assert near[0].amount.value == pytest.approx(5.0, abs=0.2)
        assert near[0].time_s < 0.5 < near[0].end_time_s  # passes under it at J1 = 0, mid-move

    def test_clearance_not_reported_when_far(self) -> None:
        """A fixture 15 mm away is outside a 10 mm clearance."""
        report = verify_with(self._plan(0.015), robots={"r1": arm3("r1")}, clearance=0.010)
        assert _findings(report, codes.CLEARANCE) == []


class TestSelfCollision:
    def test_tool_folds_into_the_arm(self) -> None:
        """Folding J3 back drives the tool into link1 (not adjacent): an E301 at that move."""
        file = source()
        tool = ir.Tool("gun", "r1", ir.Capsule(0.03, 0.3), ir.Pose((0, 0, 0.3)), geometry_pose=ir.Pose((0, 0, 0.15)))
        c = cell([("r1", (0, 0, 0))], tools=[tool])
        tp = task_plan("main", "r1", [(0, 0, 0), (0, 0, 0.5), (0, 0, 3.0)], [0.5, 1.5], file, tool=ir.ToolRef("gun"))
        report = verify_with(make_plan(c, [tp], file), robots={"r1": arm3("r1", vmax=10, amax=100)})
        hits = _findings(report, codes.SELF_COLLISION)
        assert hits and all(h.span.start.line == 3 for h in hits)
        assert any(set(h.bodies) == {"gun", "r1/link1"} for h in hits)
        assert _findings(report, codes.COLLISION) == []

    def test_allowed_contact_is_ignored(self) -> None:
        """A pair listed in the cell's allowed contacts is not reported."""
        file = source()
        tool = ir.Tool("gun", "r1", ir.Capsule(0.03, 0.3), ir.Pose((0, 0, 0.3)), geometry_pose=ir.Pose((0, 0, 0.15)))
        c = cell([("r1", (0, 0, 0))], tools=[tool], allowed=[("gun", "r1")])
        tp = task_plan("main", "r1", [(0, 0, 0), (0, 0, 0.5), (0, 0, 3.0)], [0.5, 1.5], file, tool=ir.ToolRef("gun"))
        report = verify_with(make_plan(c, [tp], file), robots={"r1": arm3("r1", vmax=10, amax=100)})
        assert _findings(report, codes.SELF_COLLISION) == []


class TestRobotRobot:
    def _report(self, r2_waits: float):
        file = source()
        c = cell([("r1", (0, 0, 0)), ("r2", (1.2, 0, 0))])
        # r1 reaches toward +x and back; r2 (mirrored) reaches toward -x, optionally after a wait
        out = [(0, 0, 0), (0, 1.2, 0), (0, 0, 0)]
        t1 = task_plan("left", "r1", out, [1.0, 1.0], file, first_line=2)
        back = [(0, 0, 0), (0, -1.2, 0), (0, 0, 0)]
        if r2_waits:
            t2 = task_plan("right", "r2", [(0, 0, 0)] + back, [r2_waits, 1.0, 1.0], file, first_line=10, first_uid=10)
        else:
            t2 = task_plan("right", "r2", back, [1.0, 1.0], file, first_line=10, first_uid=10)
        robots = {"r1": arm3("r1"), "r2": arm3("r2")}
        return verify_with(make_plan(c, [t1, t2], file), robots=robots)

    def test_simultaneous_reach_collides(self) -> None:
        """Both arms reaching into the shared space at once: an E302 naming bodies of both."""
        hits = _findings(self._report(0.0), codes.ROBOT_COLLISION)
        assert hits
        for h in hits:
            owners = {b.split("/")[0] for b in h.bodies}
            assert owners == {"r1", "r2"}
            assert 0.0 < h.time_s <= h.end_time_s < 2.0

    def test_waiting_robot_does_not_collide(self) -> None:
        """Once r2 waits until r1 is back, the shared timeline has no robot contact."""
        report = self._report(2.0)
        assert _findings(report, codes.ROBOT_COLLISION) == []
        assert report.cycle_times == {"left": pytest.approx(2.0), "right": pytest.approx(4.0)}


class TestNoMissGuarantee:
    def test_fast_move_past_thin_plate(self) -> None:
        """A 1 mm plate that no sample touches, swept through between two samples, is found."""
        file = source()
        robot = arm3("r1", vmax=200, amax=1e5)
        half = np.pi / 2
        tp = task_plan("main", "r1", [(-1.0, half, 0), (1.0, half, 0)], [0.05], file)
        traj = tp.trajectory
        # the plate stands radially at the mid-angle between two samples of the fastest part
        k = int(np.argmin(np.abs(traj.q[:, 0])))
        angle = float((traj.q[k, 0] + traj.q[k + 1, 0]) / 2)
        size, radius = (0.2, 0.001, 0.3), 0.72
        centre = (radius * np.cos(angle), radius * np.sin(angle), 0.4)
        plate = box("plate", size, centre, rpy=(0, 0, angle))
        c = cell([("r1", (0, 0, 0))], fixtures=[plate])
        # reference: at the samples themselves nothing touches (the step jumps over the plate)
        sample_poses = robot.solid_poses_batch(traj.q)[:, 3]
        assert float(np.max(np.abs(np.diff(traj.q[:, 0])))) * radius > 0.1  # > 10 cm per sample
        local = [np.linalg.inv(plate.pose.matrix()) @ p for p in sample_poses]
        sampled = [_capsule_box_distance(p, 0.4, 0.04, (0, 0, 0), size) for p in local]
        assert min(sampled) > 0
        report = verify_with(make_plan(c, [tp], file), robots={"r1": robot})
        hits = _findings(report, codes.COLLISION)
        assert [h.bodies for h in hits] == [("r1/link3", "plate")]
        assert traj.t[k] <= hits[0].time_s <= traj.t[k + 1]


@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(fraction=st.floats(0.05, 0.95), along=st.floats(0.0, 1.0), link=st.sampled_from([2, 3]))
def test_box_on_swept_path_is_always_found(fraction: float, along: float, link: int) -> None:
    """A 1 cm box placed at any point of link2's or link3's swept axis is found as a collision."""
    file = source()
    robot = arm3("r1")
    tp = task_plan("main", "r1", [(-0.8, 0.3, 0.4), (0.7, 1.1, -0.6)], [1.2], file)
    traj = tp.trajectory
    t = traj.t[0] + fraction * traj.duration
    q = traj.at(t)
    pose = robot.solid_poses(q)[link]
    length = robot.solids[link].geometry.length
    point = pose[:3, 3] + (along - 0.5) * length * pose[:3, 2]
    c = cell([("r1", (0, 0, 0))], fixtures=[box("dot", (0.01, 0.01, 0.01), tuple(point))])
    report = verify_with(make_plan(c, [tp], file), robots={"r1": robot})
    hits = [d for d in _findings(report, codes.COLLISION) if "dot" in d.bodies]
    assert hits
    assert any(h.time_s - STEP <= t <= h.end_time_s + STEP for h in hits)


def test_advance_walks_on_through_a_contact_shallower_than_the_motion_sums_rounding() -> None:
    """Two faces touching give a signed distance like -1e-12 m; where the accumulated motion
    bound is large, cum[i] - d rounds to cum[i] and the contact proves no later sample. The
    walk must still move on to the next sample (it stalled on sample i before)."""
    import numpy as np

    from rmot.sim.collide import _advance

    move = np.full(4, 1e6)
    evaluated, dists, split = _advance(np.arange(5), np.zeros(5), move, 0.0, lambda i: -1e-12, lipschitz=True)
    assert list(evaluated) == [0, 1, 2, 3, 4] and split.size == 0
