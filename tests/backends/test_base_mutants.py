"""backends/base.py behaviour that mutation testing (`make mutation`) found untested:
de-duplication of diagnostics, hashable keys, the shared limits and warnings. A toy vendor
with its own limits stands in for a controller; expected values are written out here."""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import Enum

import numpy as np
import pytest

from rmot.backends import codes
from rmot.backends.base import (
    DEFAULT_JOINT_ACCEL, DEFAULT_TCP_ACCEL, Backend, TaskContext, accel_is_default,
    header_lines, key_value, source_ref,
)
from rmot.backends.task_context import unique
from rmot.lang import ir
from rmot.lang.diagnostics import Diagnostic, Severity
from rmot.lang.source import Pos, SourceFile, Span

_FILE = SourceFile("/some/dir/cell.rmot", "a\nb\nc\n")


def _span(line: int) -> Span:
    return Span(_FILE, Pos(line, 1, 2 * (line - 1)), Pos(line, 2, 2 * (line - 1) + 1))


class Toy(Backend):
    name = "toy"
    COMMENT = ";"
    DIGITAL_PORTS = (1, 16)
    MAX_TCP_SPEED = 2.0
    MAX_TCP_SPEED_SOURCE = "the toy manual"


@dataclass
class _Ctx:  # the part of a TaskContext that warn_once reads
    warned: set[str] = field(default_factory=set)


def _motion(tcp_speed: float = 0.5, tcp_accel: float = DEFAULT_TCP_ACCEL,
            joint_accel: float = DEFAULT_JOINT_ACCEL) -> ir.Motion:
    return ir.Motion(tcp_speed, tcp_accel, 1.0, joint_accel, ir.Zone(0.0))


def _move(speed: float = 0.5) -> ir.Move:
    return ir.Move(uid=7, kind=ir.MotionKind.LINEAR, target=ir.JointTarget((0.0,) * 6), motion=_motion(speed),
                   tool=ir.ToolRef(None), frame=ir.FrameRef(None))


def _native(uid: int, vendor: str, text: str) -> ir.Native:
    return ir.Native(uid=uid, vendor=vendor, text=text)


def _diag(message: str = "m", span: Span | None = None, severity: Severity = Severity.ERROR,
          code: object = codes.UNSUPPORTED) -> Diagnostic:
    return Diagnostic(code, severity, message, span)  # type: ignore[arg-type]


class TestUnique:
    def test_exact_repeats_are_dropped_in_order(self) -> None:
        a, b = _diag("a", _span(1)), _diag("b", _span(1))
        assert unique([a, b, a, _diag("a", _span(1)), b]) == (a, b)

    @pytest.mark.parametrize("other", [
        _diag("a", _span(2)), _diag("a (more)", _span(1)), _diag("a", _span(1), Severity.WARNING),
        _diag("a", _span(1), code=codes.BAD_PORT), _diag("a", None),
    ])
    def test_anything_different_is_kept(self, other: Diagnostic) -> None:
        first = _diag("a", _span(1))
        assert unique([first, other]) == (first, other)


class TestKeyValue:
    class Colour(Enum):
        RED = 1

    def test_plain_values_stay(self) -> None:
        for v in (None, "s", True, 3, TestKeyValue.Colour.RED):
            assert key_value(v) == v
        assert key_value(0.1 + 0.2) == 0.3  # rounded to 1e-9

    def test_spans_are_left_out(self) -> None:
        assert key_value(_span(1)) is None

    def test_arrays_keep_shape_and_rounded_values(self) -> None:
        assert key_value(np.array([[1.0, 2.0000000001]])) == ("array", (1, 2), (1.0, 2.0))
        assert key_value(np.array([1.0, 2.0])) != key_value(np.array([[1.0, 2.0]]))
        assert key_value(np.float64(1.5)) == 1.5 and key_value(np.int64(4)) == 4

    def test_containers(self) -> None:
        assert key_value([1.0, "a"]) == (1.0, "a") == key_value((1.0, "a"))
        assert key_value({3, 1, 2}) == key_value({2, 3, 1}) == (1, 2, 3)
        assert list({8, 1}) == [8, 1] and key_value({8, 1}) == (1, 8)  # sorted, not set order
        assert key_value({8: "a", 1: "b"}) == ((1, "b"), (8, "a"))
        assert key_value({"b": 1, "a": 2}) == (("a", 2), ("b", 1))

    def test_dataclasses_by_type_and_fields(self) -> None:
        assert key_value(ir.Zone(0.1)) == ("Zone", (0.1,))
        assert key_value(ir.Zone(0.1)) != key_value(ir.Zone(0.2))

    def test_anything_else_by_its_repr(self) -> None:
        class Thing:
            def __repr__(self) -> str:
                return "<thing>"

        assert key_value(Thing()) == "<thing>"


class TestSettings:
    def test_source_ref_is_the_file_name_and_line(self) -> None:
        assert source_ref(_span(3)) == "cell.rmot:3"
        assert source_ref(None) is None

    @pytest.mark.parametrize(("kind", "motion", "default"), [
        (ir.MotionKind.JOINT, _motion(), True),
        (ir.MotionKind.JOINT, _motion(joint_accel=0.5 * DEFAULT_JOINT_ACCEL), False),
        (ir.MotionKind.JOINT, _motion(tcp_accel=2 * DEFAULT_TCP_ACCEL), True),  # not a joint setting
        (ir.MotionKind.LINEAR, _motion(), True),
        (ir.MotionKind.LINEAR, _motion(tcp_accel=2 * DEFAULT_TCP_ACCEL), False),
        (ir.MotionKind.LINEAR, _motion(joint_accel=0.5 * DEFAULT_JOINT_ACCEL), True),
    ])
    def test_accel_is_default_reads_the_setting_of_the_move_kind(
            self, kind: ir.MotionKind, motion: ir.Motion, default: bool) -> None:
        assert accel_is_default(motion, kind) is default


class TestLimits:
    @pytest.mark.parametrize(("port", "ok"), [(0, False), (1, True), (16, True), (17, False)])
    def test_port_range_is_inclusive(self, port: int, ok: bool) -> None:
        toy = Toy()
        assert toy.port_ok(port, "digital output", _span(1)) is ok
        found = toy._emission.diagnostics
        assert [d.code for d in found] == ([] if ok else [codes.BAD_PORT])
        if not ok:
            assert found[0].message == f"toy: digital output port must be in 1..16 (got {port})"
            assert found[0].severity is Severity.ERROR and found[0].span == _span(1)

    def test_port_range_of_the_call_wins(self) -> None:
        toy = Toy()
        assert toy.port_ok(20, "analog output", None, (17, 24)) and not toy.port_ok(16, "x", None, (17, 24))

    def test_tcp_speed_up_to_the_limit_passes_and_above_is_clamped_with_a_warning(self) -> None:
        toy = Toy()
        assert toy.tcp_speed_within_limit(_move(2.0)) == 2.0 and not toy._emission.diagnostics
        assert toy.tcp_speed_within_limit(_move(2.5)) == 2.0
        (d,) = toy._emission.diagnostics
        assert d.code is codes.LIMIT_CLAMPED and d.severity is Severity.WARNING
        assert d.message == ("toy: TCP speed 2500.0 mm/s must be at most 2000.0 mm/s for toy "
                             "(the toy manual); clamped to 2000.0 mm/s")

    def test_warn_once_per_key(self) -> None:
        toy, ctx = Toy(), _Ctx()
        for key in ("a", "a", "b", "a"):
            toy.warn_once(ctx, key, codes.ACCEL_IGNORED, f"w {key}", None)  # type: ignore[arg-type]
        assert [d.message for d in toy._emission.diagnostics] == ["toy: w a", "toy: w b"]
        assert all(d.severity is Severity.WARNING for d in toy._emission.diagnostics)

    def test_branch_or_default_needs_all_three_fields(self) -> None:
        from dataclasses import replace

        toy = Toy()
        move = replace(_move(), span=_span(2))
        full = ir.Config(ir.Shoulder.BACK, ir.Elbow.DOWN, ir.Wrist.FLIP)
        assert toy.branch_or_default(full, move) == full and not toy._emission.diagnostics
        partial = ir.Config(ir.Shoulder.BACK, ir.Elbow.DOWN, None)
        for branch in (None, partial):
            assert toy.branch_or_default(branch, move) == ir.Config(
                ir.Shoulder.FRONT, ir.Elbow.UP, ir.Wrist.NOFLIP)
        assert [d.code for d in toy._emission.diagnostics] == [codes.NO_BRANCH, codes.NO_BRANCH]
        assert toy._emission.diagnostics[0].message == (
            "toy: Cartesian target must have a planned IK branch for the configuration data (got none)")
        assert toy._emission.diagnostics[0].span == move.span


class TestText:
    def test_comment_and_indent(self) -> None:
        toy = Toy()
        assert toy.comment("hello") == "; hello" and toy.comment("") == ";"
        assert Toy.indent(["a", "", "b"], "  ") == ["  a", "", "  b"]

    def test_native_blocks_of_another_vendor_are_skipped_with_a_warning(self) -> None:
        toy = Toy()
        assert toy.native(_native(1, "TOY", "line 1\nline 2"), None) == ["line 1", "line 2"]  # type: ignore[arg-type]
        assert toy.native(_native(2, "rapid", "MoveJ ..."), None) == [  # type: ignore[arg-type]
            "; native rapid block skipped"]
        assert toy.native(_native(3, "cobol", "x"), None) == ["; native cobol block skipped"]  # type: ignore[arg-type]
        first, second = toy._emission.diagnostics
        assert first.code is codes.NATIVE_SKIPPED and first.severity is Severity.WARNING
        assert first.message == "toy: native rapid block is not emitted for toy"
        assert second.message.startswith("toy: native cobol block is not emitted for toy (not one of rapid, ")


# --------------------------------------------------------------------------- with a plan


def _plan_ctx(move: ir.Move, q: np.ndarray | None, dof: int = 6) -> tuple[Toy, TaskContext]:
    from backend_fixtures import hand_plan

    plan = hand_plan((move,), {} if q is None else {move.uid: (q, None)}, dof=dof)
    tp = plan.tasks[0]
    return Toy(), TaskContext(plan, tp, plan.program.cell.robot(tp.robot), "main")


def _planned_move(zone: float = 0.0, **motion: float) -> ir.Move:
    from backend_fixtures import motion as make_motion, span_at

    return ir.Move(uid=3, kind=ir.MotionKind.LINEAR, target=ir.JointTarget((0.0,) * 6),
                   motion=make_motion(zone=zone), tool=ir.ToolRef(None), frame=ir.FrameRef(None),
                   span=span_at(5))


class TestWithPlan:
    def test_header_names_program_file_line_target_and_cell(self) -> None:
        from backend_fixtures import hand_plan

        plan = hand_plan((), {}, name="pick")
        assert header_lines(plan, "toy") == [
            "generated by rmot from program 'pick' (demo.rmot:1)",
            "target: toy; cell: democell; do not edit by hand"]
        assert header_lines(plan, "toy", findings=True)[2] == (
            "WARNING: verification reported errors; compiled with --allow-findings")
        toy = Toy(allow_findings_header=True)
        _, ctx = _plan_ctx(_planned_move(), np.zeros(6))
        assert toy.header(ctx)[0] == "; generated by rmot from program 'demo' (demo.rmot:1)"
        assert len(toy.header(ctx)) == 3 and len(Toy().header(ctx)) == 2

    def test_move_record_or_the_reported_gap(self) -> None:
        move = _planned_move()
        toy, ctx = _plan_ctx(move, np.full(6, 0.5))
        rec = toy.move_record(move, ctx)
        assert not isinstance(rec, list) and np.allclose(rec.q_target, 0.5)
        toy, ctx = _plan_ctx(move, None)
        assert toy.move_record(move, ctx) == ["; move (uid 3) not emitted: no planned joints"]
        (d,) = toy._emission.diagnostics
        assert d.code is codes.MISSING_RECORD and d.span == move.span
        assert d.message == "toy: move (uid 3) must have a planned joint solution (got none)"

    def test_six_axis_data_needs_six_axes(self) -> None:
        class Six(Toy):
            SIX_AXIS_DATA = "toy six-axis data"

        move = _planned_move()
        _, ctx = _plan_ctx(move, np.zeros(7), dof=7)
        six = Six()
        assert six.move_record(move, ctx) == ["; move not emitted: robot is not a 6-axis arm"]
        (d,) = six._emission.diagnostics
        assert d.code is codes.NOT_SIX_AXIS
        assert d.message == "toy: robot 'r1' must have 6 axes for toy six-axis data (got 7)"
        assert not isinstance(Toy().move_record(move, ctx), list)  # a vendor without the rule

    def test_planned_zone_is_fine_where_the_plan_stops(self) -> None:
        move = _planned_move(zone=0.05)
        _, ctx = _plan_ctx(move, np.zeros(6))
        rec = ctx.record(move)
        assert rec is not None and rec.blend_radius == 0.05
        assert Backend.planned_zone(move, rec) == ir.Zone(0.05)
        from dataclasses import replace

        assert Backend.planned_zone(move, replace(rec, blend_radius=0.0)) == ir.Zone(0.0)

    def test_warn_accel_once_per_task_only_for_a_programmed_acceleration(self) -> None:
        plain = ir.Move(uid=1, kind=ir.MotionKind.LINEAR, target=ir.JointTarget((0.0,) * 6),
                        motion=_motion(), tool=ir.ToolRef(None), frame=ir.FrameRef(None))
        fast = ir.Move(uid=2, kind=ir.MotionKind.LINEAR, target=ir.JointTarget((0.0,) * 6),
                       motion=_motion(tcp_accel=3 * DEFAULT_TCP_ACCEL), tool=ir.ToolRef(None),
                       frame=ir.FrameRef(None))
        toy, ctx = Toy(), _Ctx()
        toy.warn_accel(plain, ctx, "the controller's own")  # type: ignore[arg-type]
        assert not toy._emission.diagnostics
        toy.warn_accel(fast, ctx, "the controller's own")  # type: ignore[arg-type]
        toy.warn_accel(fast, ctx, "the controller's own")  # type: ignore[arg-type]
        (d,) = toy._emission.diagnostics
        assert d.code is codes.ACCEL_IGNORED
        assert d.message == "toy: programmed accelerations are not expressed (the controller's own)"

    def test_warn_payload_once_per_tool_with_mass_and_centre_of_gravity(self) -> None:
        tool = ir.ToolRef("grip", ir.Pose((0.0, 0.0, 0.2)), 1.5)
        move = ir.Move(uid=1, kind=ir.MotionKind.LINEAR, target=ir.JointTarget((0.0,) * 6),
                       motion=_motion(), tool=tool, frame=ir.FrameRef(None))
        massless = ir.Move(uid=2, kind=ir.MotionKind.LINEAR, target=ir.JointTarget((0.0,) * 6),
                           motion=_motion(), tool=ir.ToolRef("light"), frame=ir.FrameRef(None))
        toy, ctx = Toy(), _Ctx()
        for m in (move, move, massless):
            toy.warn_payload(m, ctx, "the toy's load screen")  # type: ignore[arg-type]
        (d,) = toy._emission.diagnostics
        assert d.code is codes.PAYLOAD_NOT_EXPRESSED
        # the centre of gravity half way along the flange -> TCP vector: 100 mm on z
        assert d.message == ("toy: tool 'grip' payload (1.500 kg, centre of gravity [0.0,0.0,100.0] mm "
                             "in the flange frame) must be set in the toy's load screen")
