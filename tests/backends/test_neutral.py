"""Neutral files: the CSV equals the Plan's arrays, the JSON round-trips the Plan, both deterministic."""

from __future__ import annotations

import csv
import io
import json
import math
from pathlib import Path

import numpy as np
import pytest
from plans_b import demo_plan

from rmot.backends import BACKENDS
from rmot.backends.neutral import CSV_DECIMALS, CsvBackend, JsonBackend
from rmot.lang import ir, ir_tree, plan_types

GOLDEN = Path(__file__).parent / "golden" / "neutral"


def with_trajectory(plan: plan_types.Plan, n: int = 50, variant: bool = True) -> plan_types.Plan:
    """The plan with a smooth sampled trajectory (and one if-variant) instead of two samples."""
    t = np.arange(n) * plan.step
    q = np.stack([np.sin(t * (j + 1)) * (0.5 + 0.1 * j) - 0.2 * j for j in range(6)], axis=1)
    qd = np.gradient(q, plan.step, axis=0)
    traj = plan_types.Trajectory(t, q, qd, np.gradient(qd, plan.step, axis=0))
    tp = plan.tasks[0]
    variants = (plan_types.Variant(1, 8, "otherwise", plan_types.Trajectory(t[:5], -q[:5], -qd[:5], qd[:5])),) if variant else ()
    return plan_types.Plan(plan.program, (plan_types.TaskPlan(tp.task, tp.robot, traj, tp.records, variants),), plan.step)


class TestCsv:
    def test_header_and_values_equal_the_plan_arrays(self) -> None:
        """Header t,q1..q6,qd1..qd6; every value equals the Plan's array to the printed precision."""
        plan = with_trajectory(demo_plan())
        files = CsvBackend().emit(plan).files
        assert list(files) == ["demo.csv"]
        rows = list(csv.reader(io.StringIO(files["demo.csv"])))
        assert rows[0] == ["t"] + [f"q{j}" for j in range(1, 7)] + [f"qd{j}" for j in range(1, 7)]
        values = np.array(rows[1:], dtype=float)
        traj = plan.tasks[0].trajectory
        assert values.shape == (traj.t.size, 13)
        np.testing.assert_allclose(values[:, 0], traj.t, atol=10 ** -CSV_DECIMALS)
        np.testing.assert_allclose(values[:, 1:7], traj.q, atol=10 ** -CSV_DECIMALS)
        np.testing.assert_allclose(values[:, 7:], traj.qd, atol=10 ** -CSV_DECIMALS)

    def test_fixed_step(self) -> None:
        """Rows are at the plan's fixed step."""
        plan = with_trajectory(demo_plan())
        rows = list(csv.reader(io.StringIO(CsvBackend().emit(plan).files["demo.csv"])))[1:]
        np.testing.assert_allclose(np.diff([float(r[0]) for r in rows]), plan.step, atol=1e-9)

    def test_empty_trajectory_is_an_error(self) -> None:
        """A task with no samples cannot be written: E452 at the task."""
        plan = demo_plan()
        tp = plan.tasks[0]
        empty = plan_types.Trajectory(np.zeros(0), np.zeros((0, 6)), np.zeros((0, 6)), np.zeros((0, 6)))
        bad = plan_types.Plan(plan.program, (plan_types.TaskPlan(tp.task, tp.robot, empty, tp.records),))
        result = CsvBackend().emit(bad)
        assert result.files == {}
        assert [(d.code.id, d.severity.value) for d in result.diagnostics] == [("E452", "error")]

    def test_negative_zero_never_printed(self) -> None:
        """-0.0 in the arrays prints as 0."""
        plan = demo_plan()
        tp = plan.tasks[0]
        z = np.full((2, 6), -0.0)
        traj = plan_types.Trajectory(np.array([0.0, 0.004]), z, z.copy(), z.copy())
        p = plan_types.Plan(plan.program, (plan_types.TaskPlan(tp.task, tp.robot, traj, tp.records),))
        assert "-0" not in CsvBackend().emit(p).files["demo.csv"]


class TestJson:
    def _doc(self) -> tuple[plan_types.Plan, dict]:  # type: ignore[type-arg]
        plan = with_trajectory(demo_plan())
        (text,) = JsonBackend().emit(plan).files.values()
        return plan, json.loads(text)

    def test_round_trip_of_records(self) -> None:
        """Every record comes back: uid, kind, file:line, times, joints, branch, TCP pose in mm + quaternion, blend."""
        plan, doc = self._doc()
        task = doc["tasks"][0]
        assert (doc["program"], doc["cell"], task["name"], task["robot"], task["dof"]) == ("demo", "democell", "main", "r1", 6)
        nodes = {n.uid: n for n in ir_tree.walk(plan.tasks[0].task.body)}
        assert len(task["instructions"]) == len(plan.tasks[0].records)
        for got, rec in zip(task["instructions"], plan.tasks[0].records):
            node = nodes[rec.uid]
            assert got["uid"] == rec.uid
            assert got["kind"] == f"move_{node.kind.name.lower()}"  # type: ignore[union-attr]
            assert got["source"] == f"demo.rmot:{node.span.start.line}"  # type: ignore[union-attr]
            assert (got["t_start"], got["t_end"]) == (pytest.approx(rec.t_start), pytest.approx(rec.t_end))
            np.testing.assert_allclose(got["q_target"], rec.q_target, atol=1e-9)
            assert ir.Config(ir.Shoulder(got["branch"]["shoulder"]), ir.Elbow(got["branch"]["elbow"]),
                             ir.Wrist(got["branch"]["wrist"])) == rec.branch
            np.testing.assert_allclose(np.array(got["tcp_pose"]["position_mm"]) / 1000, rec.tcp_pose.position, atol=1e-9)  # type: ignore[union-attr]
            np.testing.assert_allclose(got["tcp_pose"]["quaternion_wxyz"], rec.tcp_pose.quaternion, atol=1e-9)  # type: ignore[union-attr]
            assert got["blend_mm"] == pytest.approx(rec.blend_radius * 1000)

    def test_trajectory_and_variants(self) -> None:
        """The sampled trajectory and each variant's equal the Plan's arrays."""
        plan, doc = self._doc()
        task, traj = doc["tasks"][0], plan.tasks[0].trajectory
        np.testing.assert_allclose(task["trajectory"]["t"], traj.t, atol=1e-9)
        np.testing.assert_allclose(task["trajectory"]["q"], traj.q, atol=1e-9)
        np.testing.assert_allclose(task["trajectory"]["qd"], traj.qd, atol=1e-9)
        (variant,) = task["variants"]
        assert (variant["index"], variant["if_uid"], variant["arm"]) == (1, 8, "otherwise")
        np.testing.assert_allclose(variant["trajectory"]["q"], plan.tasks[0].variants[0].trajectory.q, atol=1e-9)
        assert doc["step"] == plan.step and doc["cycle_time"] == pytest.approx(float(traj.t[-1]))

    def test_keys_sorted_and_bytes_deterministic(self) -> None:
        """Keys sorted, no -0, and two emits of equal plans give the same bytes."""
        a = JsonBackend().emit(with_trajectory(demo_plan())).files
        b = JsonBackend().emit(with_trajectory(demo_plan())).files
        assert a == b
        (text,) = a.values()
        assert text == json.dumps(json.loads(text), sort_keys=True, separators=(",", ":")) + "\n"
        assert "-0.0," not in text and "-0.0]" not in text

    def test_matches_golden_file(self) -> None:
        """The demo plan's JSON equals the reviewed golden file."""
        (text,) = JsonBackend().emit(with_trajectory(demo_plan(), n=5, variant=False)).files.values()
        assert text == (GOLDEN / "demo.json").read_text(encoding="utf-8")

    def test_registered(self) -> None:
        """--target csv and json resolve to the neutral backends."""
        assert (BACKENDS["csv"], BACKENDS["json"]) == (CsvBackend, JsonBackend)
        assert math.isclose(float(json.loads(JsonBackend().emit(demo_plan()).files["demo.json"])["step"]), 0.004)
