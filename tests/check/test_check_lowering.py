"""Lowering to the IR: SI units, frames composed into the robot base, modal settings, loops, procs, uids."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from rmot.lang import ir, ir_tree
from rmot.compiler.frontend import load_program, load_text
from rmot.lang.diagnostics import render

CELL = """
cell c {
  robot r1 = abb_irb120 at pose(x=100mm, y=-200mm, z=300mm, rz=30deg)
  robot r2 = ur5e at pose(x=1500mm, rz=180deg)
  fixture table = box(800mm, 600mm, 40mm) at pose(x=600mm, y=100mm, z=200mm, rz=10deg)
  tool g = sphere(r=20mm) tcp pose(z=150mm, rx=5deg) mass 1.5 kg on r1
  tool h = none tcp pose(z=100mm) on r2
  frame top = table * pose(z=20mm, rx=-4deg)
  io out[1] = "close" on r1
  io in[2] = "present"
}
"""


def lower(body: str, cell: str = CELL) -> ir.Program:
    result = load_text(cell + body, "/virtual/t.rmot")
    assert not result.has_errors, "\n".join(render(d) for d in result.diagnostics)
    assert result.program is not None
    return result.program


def moves(prog: ir.Program, task: int = 0) -> list[ir.Move]:
    return [i for i in ir_tree.walk(prog.tasks[task].body) if isinstance(i, ir.Move)]


def rpy_matrix(x: float, y: float, z: float, rx: float, ry: float, rz: float) -> np.ndarray:
    """Independent: R = Rz(rz) @ Ry(ry) @ Rx(rx), fixed axes, as LANGUAGE.md defines."""
    cx, sx, cy, sy, cz, sz = math.cos(rx), math.sin(rx), math.cos(ry), math.sin(ry), math.cos(rz), math.sin(rz)
    rot_x = np.array([[1, 0, 0], [0, cx, -sx], [0, sx, cx]])
    rot_y = np.array([[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]])
    rot_z = np.array([[cz, -sz, 0], [sz, cz, 0], [0, 0, 1]])
    m = np.eye(4)
    m[:3, :3] = rot_z @ rot_y @ rot_x
    m[:3, 3] = (x, y, z)
    return m


D = math.radians


class TestUnits:
    @pytest.mark.parametrize(("written", "si"), [
        ("speed 250 mm/s", ("tcp_speed", 0.25)), ("speed 1.5 m/s", ("tcp_speed", 1.5)),
        ("speed 20 cm/s", ("tcp_speed", 0.2)), ("accel 500 mm/s^2", ("tcp_accel", 0.5)),
        ("joint_speed 40 %", ("joint_speed", 0.4)), ("accel 25 %", ("joint_accel", 0.25)),
    ])
    def test_settings_convert_to_si(self, written: str, si: tuple[str, float]) -> None:
        """Every modal quantity lands in the IR in SI units (m/s, m/s^2, fractions)."""
        (m,) = moves(lower(f"program p on r1 {{ {written}; move linear pose(z=500mm) }}"))
        assert getattr(m.motion, si[0]) == pytest.approx(si[1])

    def test_zone_and_time_in_si(self) -> None:
        """zone 5 mm is 0.005 m; time 1500 ms is 1.5 s; zone fine is 0."""
        a, b = moves(lower("program p on r1 { zone 5 mm; move linear pose(z=500mm) time 1500 ms; move linear pose(z=600mm) zone fine }"))
        assert (a.motion.zone.radius, a.motion.duration, b.motion.zone.radius) == (pytest.approx(0.005), pytest.approx(1.5), 0.0)

    def test_joint_values_in_radians(self) -> None:
        """joints(...) deg are radians in the IR; a per-value unit wins over the trailing one."""
        (m,) = moves(lower("program p on r1 { move joint joints(0, -90, 0.5 rad, 0, 90, 180) deg }"))
        assert m.target == ir.JointTarget((0.0, -math.pi / 2, 0.5, 0.0, math.pi / 2, math.pi))

    def test_arithmetic_folds_with_units(self) -> None:
        """Constants fold: 2 * 40 mm + 1 cm = 0.09 m; 100 mm / 2 s = 0.05 m/s."""
        (m,) = moves(lower("program p on r1 { const d = 2 * 40 mm + 1 cm; speed 100 mm / 2 s; move linear pose(x=d, z=500mm) }"))
        assert m.target.in_frame.position[0] == pytest.approx(0.09)  # type: ignore[union-attr]
        assert m.motion.tcp_speed == pytest.approx(0.05)

    def test_inches_and_minutes(self) -> None:
        """1 in is 25.4 mm and 0.5 min is 30 s."""
        prog = lower("program p on r1 { move linear pose(x=1 in, z=500mm); wait 0.5 min }")
        (m,) = moves(prog)
        assert m.target.in_frame.position[0] == pytest.approx(0.0254)  # type: ignore[union-attr]
        assert prog.tasks[0].body[1] == ir.WaitTime(uid=2, duration=pytest.approx(30.0))  # type: ignore[arg-type]


class TestFrames:
    def test_target_in_a_frame_is_expressed_in_the_robot_base(self) -> None:
        """pose = inv(base) * frame(world) * target, checked against an independent numpy product."""
        (m,) = moves(lower("program p on r1 { frame top; move linear pose(x=10mm, y=20mm, z=30mm, rx=180deg, rz=45deg) }"))
        base = rpy_matrix(0.1, -0.2, 0.3, 0, 0, D(30))
        top = rpy_matrix(0.6, 0.1, 0.2, 0, 0, D(10)) @ rpy_matrix(0, 0, 0.02, D(-4), 0, 0)
        target = rpy_matrix(0.01, 0.02, 0.03, D(180), 0, D(45))
        expected = np.linalg.inv(base) @ top @ target
        assert isinstance(m.target, ir.CartesianTarget)
        np.testing.assert_allclose(m.target.pose.matrix(), expected, atol=1e-12)
        np.testing.assert_allclose(m.target.in_frame.matrix(), target, atol=1e-12)
        np.testing.assert_allclose(m.frame.world.matrix(), top, atol=1e-12)
        np.testing.assert_allclose(m.frame.pose.matrix(), np.linalg.inv(base) @ top, atol=1e-12)
        assert m.frame.name == "top"

    def test_default_frame_is_the_robot_base(self) -> None:
        """Without `frame`, a pose target is already in the base frame."""
        (m,) = moves(lower("program p on r1 { move linear pose(x=400mm, z=500mm) }"))
        assert m.frame == ir.FrameRef(None) and m.target.pose == m.target.in_frame  # type: ignore[union-attr]

    def test_world_frame(self) -> None:
        """`frame world` expresses targets in the cell's world frame."""
        (m,) = moves(lower("program p on r1 { frame world; move linear pose(x=400mm, z=500mm) }"))
        expected = np.linalg.inv(rpy_matrix(0.1, -0.2, 0.3, 0, 0, D(30))) @ rpy_matrix(0.4, 0, 0.5, 0, 0, 0)
        np.testing.assert_allclose(m.target.pose.matrix(), expected, atol=1e-12)  # type: ignore[union-attr]

    def test_shift_moves_along_the_reference_axes_and_product_along_the_pose_axes(self) -> None:
        """shift(p, z=..) adds to the position; p * pose(z=..) moves along p's own z."""
        a, b = moves(lower("program p on r1 { target t = pose(x=400mm, z=500mm, rx=180deg)\n"
                           "move linear shift(t, z=50mm); move linear t * pose(z=50mm) }"))
        assert a.target.in_frame.position == pytest.approx((0.4, 0, 0.55))  # type: ignore[union-attr]
        assert b.target.in_frame.position == pytest.approx((0.4, 0, 0.45))  # type: ignore[union-attr]

    def test_inv_and_components(self) -> None:
        """inv(p) * p is the identity; p.x and p.rz read back what was written."""
        (m,) = moves(lower("program p on r1 { target t = pose(x=40mm, y=7mm, rz=30deg)\n"
                           "move linear inv(t) * t * pose(x=t.x, y=t.y, z=500mm, rz=t.rz) }"))
        np.testing.assert_allclose(m.target.in_frame.matrix(), rpy_matrix(0.04, 0.007, 0.5, 0, 0, D(30)), atol=1e-12)  # type: ignore[union-attr]

    def test_quaternion_pose(self) -> None:
        """pose(q=(w, x, y, z)) normalises the quaternion."""
        (m,) = moves(lower("program p on r1 { move linear pose(z=500mm, q=(0, 2, 0, 0)) }"))
        assert m.target.in_frame.quaternion == pytest.approx((0, 1, 0, 0))  # type: ignore[union-attr]


class TestModalSettings:
    def test_defaults(self) -> None:
        """Never-set settings: 250 mm/s, 100 %, 2 m/s^2, joint accel 1.0, zone fine, flange, base."""
        (m,) = moves(lower("program p on r1 { move linear pose(z=500mm) }"))
        assert m.motion == ir.Motion(0.25, 2.0, 1.0, 1.0, ir.Zone(0.0), None)
        assert m.tool == ir.ToolRef(None) and m.frame == ir.FrameRef(None)

    def test_modifiers_override_for_one_move_only(self) -> None:
        """A move's own speed/zone/tool win for that move; the next move sees the modal value again."""
        a, b = moves(lower("program p on r1 { speed 300 mm/s; zone 2 mm\n"
                           "move linear pose(z=500mm) speed 50 mm/s zone fine tool g\n move linear pose(z=600mm) }"))
        assert (a.motion.tcp_speed, a.motion.zone.radius, a.tool.name) == (pytest.approx(0.05), 0.0, "g")
        assert (b.motion.tcp_speed, b.motion.zone.radius, b.tool.name) == (pytest.approx(0.3), pytest.approx(0.002), None)

    def test_tool_ref_carries_tcp_and_mass(self) -> None:
        """`tool g` resolves to the tool's TCP pose and mass on every later move."""
        (m,) = moves(lower("program p on r1 { tool g; move linear pose(z=500mm) }"))
        np.testing.assert_allclose(m.tool.tcp.matrix(), rpy_matrix(0, 0, 0.15, D(5), 0, 0), atol=1e-12)
        assert m.tool.mass == pytest.approx(1.5)

    def test_settings_inside_a_proc_do_not_leak(self) -> None:
        """A setting in a proc body ends with the proc (block scope)."""
        prog = lower("program p on r1 { proc slow() { speed 10 mm/s; move linear pose(z=400mm) }\n"
                     "slow(); move linear pose(z=500mm) }")
        a, b = moves(prog)
        assert (a.motion.tcp_speed, b.motion.tcp_speed) == (pytest.approx(0.01), pytest.approx(0.25))

    def test_config_fills_the_ir_config(self) -> None:
        """config(shoulder=back, wrist=flip) sets those fields and leaves elbow free."""
        (m,) = moves(lower("program p on r1 { move joint pose(z=500mm) config(shoulder=back, wrist=flip) }"))
        assert m.config == ir.Config(ir.Shoulder.BACK, None, ir.Wrist.FLIP)


class TestControlFlow:
    def test_for_is_half_open_and_unrolled(self) -> None:
        """for i in 0 .. 3 runs i = 0, 1, 2."""
        ms = moves(lower("program p on r1 { for i in 0 .. 3 { move linear pose(x=i * 10mm, z=500mm) } }"))
        assert [m.target.in_frame.position[0] for m in ms] == pytest.approx([0, 0.01, 0.02])  # type: ignore[union-attr]

    def test_repeat_and_nested_loops(self) -> None:
        """repeat 2 around for 0..3 gives six moves."""
        assert len(moves(lower("program p on r1 { repeat 2 { for i in 0 .. 3 { move linear pose(z=500mm) } } }"))) == 6

    def test_proc_call_is_inlined_as_a_node(self) -> None:
        """A call becomes ir.ProcCall with the substituted body and the arguments as written."""
        prog = lower("program p on r1 { proc pick(q: pose, h: length) { move linear shift(q, z=h) }\n"
                     "pick(pose(x=1mm, z=500mm), 20 mm) }")
        (call,) = prog.tasks[0].body
        assert isinstance(call, ir.ProcCall) and call.proc == "pick" and call.args == ("pose(x=1mm, z=500mm)", "20 mm")
        assert call.body[0].target.in_frame.position == pytest.approx((0.001, 0, 0.52))  # type: ignore[union-attr]

    def test_if_is_kept_as_a_runtime_branch(self) -> None:
        """if in[2] == off keeps both arms; the signal name comes from the cell."""
        (branch,) = lower("program p on r1 { if in[2] == off { wait 1 s } else { set out[1] = on } }").tasks[0].body
        assert isinstance(branch, ir.If)
        assert branch.condition == ir.InputCondition(port=2, value=False, signal="present")
        assert branch.otherwise == (ir.SetDigital(uid=3, port=1, value=True, signal="close"),)

    def test_io_instructions(self) -> None:
        """set, pulse, wait and wait until lower to their IR nodes in SI."""
        body = lower("program p on r1 { set aout[1] = 4.5; pulse out[3] for 200 ms; wait until in[2] timeout 5 s }").tasks[0].body
        assert body == (ir.SetAnalog(uid=1, port=1, value=4.5), ir.Pulse(uid=2, port=3, duration=pytest.approx(0.2)),  # type: ignore[arg-type]
                        ir.WaitInput(uid=3, condition=ir.InputCondition(port=2, value=True, signal="present"), timeout=5.0))

    def test_uids_are_unique_and_in_source_order(self) -> None:
        """After unrolling and inlining, uids count 1, 2, 3, ... in walk order across tasks."""
        prog = lower("program p { task r1 { proc a() { wait 1 s; sync s }\n for i in 0 .. 2 { a() } }\n"
                     " task r2 { sync s; sync s; if in[2] { wait 1 s } } }")
        uids = [i.uid for t in prog.tasks for i in ir_tree.walk(t.body)]
        assert uids == list(range(1, len(uids) + 1))

    def test_native_text(self) -> None:
        """native keeps the vendor and the unescaped text."""
        (n,) = lower('program p on r1 { native krl "$OUT[1] = TRUE" }').tasks[0].body
        assert n == ir.Native(uid=1, vendor="krl", text="$OUT[1] = TRUE")


class TestTasksAndCells:
    def test_multi_task_program(self) -> None:
        """Each task is named after its robot and gets the shared settings."""
        prog = lower("program p { speed 100 mm/s; target t = pose(z=500mm)\n"
                     "task r1 { move linear t }\n task r2 { tool h; move linear t } }")
        assert [(t.name, t.robot) for t in prog.tasks] == [("r1", "r1"), ("r2", "r2")]
        assert moves(prog, 1)[0].tool.name == "h" and moves(prog, 1)[0].motion.tcp_speed == pytest.approx(0.1)

    def test_default_cell_is_used_without_a_cell(self) -> None:
        """A program with no cell runs in the built-in default cell on its robot r1."""
        result = load_text("program p on r1 { tool gripper; frame table_top; move linear pose(z=100mm) }", "/virtual/t.rmot")
        assert not result.has_errors and result.cell is not None and result.cell.name == "default_cell"
        assert {f.name for f in result.cell.frames} >= {"table_top", "pallet"}

    def test_cell_option_wins_over_use_cell(self, tmp_path: Path) -> None:
        """--cell replaces the cell the program names with `use cell`."""
        (tmp_path / "a.rmot").write_text("cell a { robot r1 = abb_irb120 }")
        (tmp_path / "b.rmot").write_text("cell b { robot r1 = abb_irb1600 }")
        (tmp_path / "p.rmot").write_text('use cell "a.rmot"\nprogram p on r1 { wait 1 s }')
        assert load_program(str(tmp_path / "p.rmot")).cell.name == "a"  # type: ignore[union-attr]
        assert load_program(str(tmp_path / "p.rmot"), cell=str(tmp_path / "b.rmot")).cell.name == "b"  # type: ignore[union-attr]

    def test_mesh_paths_are_absolute_and_scaled(self, tmp_path: Path) -> None:
        """mesh("m/x.stl", unit=mm) is resolved against the cell file and scaled by 0.001."""
        (tmp_path / "m").mkdir()
        (tmp_path / "m" / "x.stl").write_text("solid x\nendsolid x\n")
        (tmp_path / "c.rmot").write_text('cell c { robot r1 = abb_irb120\n fixture f = mesh("m/x.stl", unit=mm) }')
        result = load_program(str(tmp_path / "c.rmot"))
        (f,) = result.cell.fixtures  # type: ignore[union-attr]
        assert f.geometry == ir.Mesh(str(tmp_path / "m" / "x.stl"), 0.001)

    def test_project_root_option_allows_paths_above_the_file(self, tmp_path: Path) -> None:
        """An import of ../lib.rmot is refused by default and allowed under a wider project root."""
        (tmp_path / "sub").mkdir()
        (tmp_path / "lib.rmot").write_text("const h = 5 mm")
        (tmp_path / "sub" / "p.rmot").write_text('import "../lib.rmot"\nprogram p on r1 { wait 1 s }')
        assert [d.code.id for d in load_program(str(tmp_path / "sub" / "p.rmot")).diagnostics] == ["E504"]
        assert load_program(str(tmp_path / "sub" / "p.rmot"), project_root=str(tmp_path)).diagnostics == ()

    def test_imported_procs_targets_and_consts(self, tmp_path: Path) -> None:
        """import brings a library's procs, targets and consts; its procs see its own consts."""
        (tmp_path / "lib.rmot").write_text("const lift = 30 mm\ntarget spot = pose(z=500mm)\nproc up(q: pose) { move linear shift(q, z=lift) }")
        (tmp_path / "p.rmot").write_text('import "lib.rmot"\nprogram p on r1 { up(spot) }')
        result = load_program(str(tmp_path / "p.rmot"))
        assert not result.has_errors, [render(d) for d in result.diagnostics]
        (m,) = moves(result.program)  # type: ignore[arg-type]
        assert m.target.in_frame.position == pytest.approx((0, 0, 0.53))  # type: ignore[union-attr]


class TestMoreForms:
    def test_keyword_joints_in_any_order(self) -> None:
        """joints(j2=..., j1=..., ...) orders the values by joint number."""
        (m,) = moves(lower("program p on r1 { move joint joints(j2=-90deg, j1=10deg, j3=0rad, j4=0deg, j5=90deg, j6=0deg) }"))
        assert m.target == ir.JointTarget((D(10), D(-90), 0.0, 0.0, D(90), 0.0))

    def test_program_frame_and_tool_reset(self) -> None:
        """A frame declared in the program works like a cell frame; `tool flange` and `frame base` reset."""
        a, b = moves(lower("program p on r1 { frame f = pose(x=1m); tool g; frame f\n move linear pose(z=500mm)\n"
                           " tool flange; frame base; move linear pose(z=500mm) }"))
        assert (a.frame.name, a.tool.name, b.frame, b.tool) == ("f", "g", ir.FrameRef(None), ir.ToolRef(None))

    def test_else_if_nests_a_branch(self) -> None:
        """`else if` is an If inside the else arm."""
        (outer,) = lower("program p on r1 { if in[1] { wait 1 s } else if in[2] == off { wait 2 s } }").tasks[0].body
        assert isinstance(outer, ir.If) and isinstance(outer.otherwise[0], ir.If)
        assert outer.otherwise[0].condition.value is False

    def test_wait_until_without_timeout(self) -> None:
        """No timeout means wait forever (timeout None)."""
        (w,) = lower("program p on r1 { wait until in[2] == on }").tasks[0].body
        assert isinstance(w, ir.WaitInput) and w.timeout is None

    def test_sync_in_a_single_task_program_is_allowed(self) -> None:
        """A sync with no partner task is a no-op in a one-robot program (kept in the IR)."""
        assert lower("program p on r1 { sync here }").tasks[0].body == (ir.Sync(uid=1, name="here"),)

    def test_program_without_on_uses_the_only_robot(self) -> None:
        """`program p { ... }` in a one-robot cell runs on that robot."""
        result = load_text("program p { wait 1 s }", "/virtual/t.rmot")
        assert result.program is not None and result.program.tasks[0].robot == "r1"

    def test_spans_point_at_the_source(self) -> None:
        """Each IR node keeps the span of the statement that produced it (inlined ones: the proc body)."""
        prog = lower("program p on r1 {\n  proc a() {\n    wait 1 s\n  }\n  a()\n}")
        (call,) = prog.tasks[0].body
        assert (call.span.start.line, call.body[0].span.start.line) == (CELL.count("\n") + 5, CELL.count("\n") + 3)  # type: ignore[union-attr]
