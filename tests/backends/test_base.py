"""The shared backend helpers: number formatting, orientation conventions, config helpers, the
Backend defaults every vendor shares (EMIT table, native blocks, TaskContext.with_state)."""

from __future__ import annotations

import math
from typing import get_args

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from rmot.backends import BACKENDS, TARGETS, controllers, targets
from rmot.backends.base import (
    EmitResult, axis_quadrant, euler_xyz_moving_deg, euler_zyx_deg, fmt, rotation_vector, turn_bits,
)
from rmot.lang import ir

quaternions = st.tuples(*[st.floats(-1, 1) for _ in range(4)]).filter(
    lambda q: 0.1 < math.sqrt(sum(c * c for c in q)))


def _pose(q: tuple[float, float, float, float]) -> ir.Pose:
    n = math.sqrt(sum(c * c for c in q))
    w, x, y, z = (c / n for c in q)
    if w < 0:
        w, x, y, z = -w, -x, -y, -z
    return ir.Pose((0.0, 0.0, 0.0), (w, x, y, z))


def _matrix(pose: ir.Pose) -> np.ndarray:
    w, x, y, z = pose.quaternion
    return Rotation.from_quat([x, y, z, w]).as_matrix()


class TestFmt:
    @pytest.mark.parametrize(("value", "decimals", "expected"), [
        (1.23456, 3, "1.235"), (-0.0, 3, "0.000"), (-0.0004, 3, "0.000"), (-0.0006, 3, "-0.001"),
        (150.0, 1, "150.0"), (2.5, 0, "2"),
    ])
    def test_fixed_point(self, value: float, decimals: int, expected: str) -> None:
        """Fixed decimals, and a negative zero prints without its sign."""
        assert fmt(value, decimals) == expected


class TestOrientation:
    @settings(max_examples=200, deadline=None)
    @given(quaternions)
    def test_zyx_matches_scipy_intrinsic_zyx(self, q: tuple[float, float, float, float]) -> None:
        """(A, B, C) rebuild R = Rz(A)·Ry(B)·Rx(C) (KUKA ABC, Fanuc WPR reversed)."""
        pose = _pose(q)
        a, b, c = euler_zyx_deg(pose)
        r = Rotation.from_euler("ZYX", [a, b, c], degrees=True).as_matrix()
        np.testing.assert_allclose(r, _matrix(pose), atol=1e-8)  # 1e-8 rad: far below 0.001 deg
        assert -90.0 <= b <= 90.0

    @settings(max_examples=200, deadline=None)
    @given(quaternions)
    def test_xyz_moving_matches_scipy(self, q: tuple[float, float, float, float]) -> None:
        """(rx, ry, rz) rebuild R = Rx·Ry·Rz (Stäubli)."""
        pose = _pose(q)
        r = Rotation.from_euler("XYZ", euler_xyz_moving_deg(pose), degrees=True).as_matrix()
        np.testing.assert_allclose(r, _matrix(pose), atol=1e-8)  # 1e-8 rad: far below 0.001 deg

    @settings(max_examples=200, deadline=None)
    @given(quaternions)
    def test_rotation_vector_matches_scipy(self, q: tuple[float, float, float, float]) -> None:
        """UR's rotation vector is axis * angle with the angle in [0, pi]."""
        pose = _pose(q)
        rv = np.array(rotation_vector(pose))
        np.testing.assert_allclose(Rotation.from_rotvec(rv).as_matrix(), _matrix(pose), atol=1e-9)
        assert np.linalg.norm(rv) <= math.pi + 1e-12

    def test_gimbal_lock_keeps_the_rotation(self) -> None:
        """At B = 90 deg the angles still rebuild the rotation (C is set to 0)."""
        pose = ir.Pose.from_xyz_rpy(0, 0, 0, 0.3, math.pi / 2, 0.2)
        a, b, c = euler_zyx_deg(pose)
        assert c == 0.0 and b == pytest.approx(90.0)
        r = Rotation.from_euler("ZYX", [a, b, c], degrees=True).as_matrix()
        np.testing.assert_allclose(r, pose.matrix()[:3, :3], atol=1e-9)


class TestConfigHelpers:
    @pytest.mark.parametrize(("deg", "quadrant"), [
        (0, 0), (45, 0), (90, 1), (179, 1), (-1, -1), (-90, -1), (-91, -2), (270, 3), (-270, -3),
    ])
    def test_abb_quadrant(self, deg: float, quadrant: int) -> None:
        """cf = floor(angle / 90 deg), negative angles in negative quadrants."""
        assert axis_quadrant(math.radians(deg)) == quadrant

    def test_kuka_turn_bits(self) -> None:
        """Bit i is set when axis i+1 is negative."""
        q = np.radians([-10, 20, -30, 0, -5, 90])
        assert turn_bits(q) == 0b010101

    def test_kuka_turn_bits_of_an_axis_at_zero(self) -> None:
        """An axis planned at 0 with float noise (-0.0, -1e-12 rad) prints as 0.000 in E6AXIS and
        is not negative: no Turn bit (a KR 16 at A1 = 0.000 deg must not get T 1)."""
        assert turn_bits(np.array([-0.0, -1e-12, 0.0, -1e-9, 0.0, 0.0])) == 0
        assert float(fmt(np.degrees(-1e-9), 3)) == 0.0  # what the controller reads
        assert turn_bits(np.radians([-0.01, 0, 0, 0, 0, 0])) == 0b1  # a real negative angle keeps its bit


class TestRegistry:
    def test_every_target_has_a_lazy_entry(self) -> None:
        """The registry lists every --target name in the documented order."""
        assert TARGETS == targets() and set(controllers()) | {"csv", "json"} == set(TARGETS)
        assert list(BACKENDS) == list(TARGETS)

    @pytest.mark.parametrize("target", ["rapid", "krl", "fanuc"])
    def test_lookup_gives_the_backend_class(self, target: str) -> None:
        """Looking a target up imports its module and gives a class named after it."""
        cls = BACKENDS[target]
        assert cls.name == target and cls.file_ext.startswith(".")

    def test_emit_result_reports_errors(self) -> None:
        """EmitResult.has_errors is true exactly when a diagnostic is an error."""
        from rmot.backends import codes
        from rmot.lang.diagnostics import Diagnostic, Severity

        warn = Diagnostic(codes.SPEED_ROUNDED, Severity.WARNING, "w", None)
        err = Diagnostic(codes.UNSUPPORTED, Severity.ERROR, "e", None)
        assert not EmitResult({}, (warn,)).has_errors
        assert EmitResult({}, (warn, err)).has_errors


VENDORS = controllers()


class TestSharedDefaults:
    @pytest.mark.parametrize("target", VENDORS)
    def test_every_ir_instruction_has_a_method(self, target: str) -> None:
        """Every vendor prints every IR instruction type through a method named in its EMIT table."""
        cls = BACKENDS[target]
        assert set(cls.EMIT) == set(get_args(ir.Instr))  # every member of the IR's Instr union
        assert {ir.Move, ir.SetDigital, ir.Loop, ir.While, ir.Stop} <= set(cls.EMIT)
        assert all(callable(getattr(cls, method, None)) for method in cls.EMIT.values())

    @pytest.mark.parametrize("target", VENDORS)
    def test_own_native_block_passes_through(self, target: str) -> None:
        """A native block for the vendor's own name is printed as written (no warning)."""
        from backend_fixtures import Row, emit_row

        text = "first_line\nsecond_line"
        result = emit_row(BACKENDS[target], Row("native", ir.Native(uid=1, vendor=target, text=text), ()))
        printed = "\n".join(result.files.values())
        assert "first_line" in printed and "second_line" in printed
        assert not [d for d in result.diagnostics if d.code.id == "W407"]

    def test_with_state_keeps_the_task_and_adds_the_vendor_state(self) -> None:
        """TaskContext.with_state copies every TaskContext field and sets the subclass's own."""
        from dataclasses import dataclass, fields

        from backend_fixtures import sample_program

        from rmot.backends.base import TaskContext

        @dataclass(frozen=True)
        class Extra(TaskContext):
            notes: list[str]

        plan = sample_program()
        task = TaskContext(plan, plan.tasks[0], plan.program.cell.robots[0], "demo", source_map=False)
        extra = task.with_state(Extra, notes=["x"])
        assert all(getattr(extra, f.name) == getattr(task, f.name) for f in fields(TaskContext))
        first_move = plan.tasks[0].task.body[0]
        assert extra.notes == ["x"]
        assert extra.record(first_move) is task.record(first_move) and extra.record(first_move).uid == first_move.uid
