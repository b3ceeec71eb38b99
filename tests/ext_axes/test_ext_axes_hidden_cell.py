"""The issue's cell as a robot programmer writes it from lang/REFERENCE.md §15: declarations that
span lines (a track as well as a positioner), the reference's own example checked clean, the
numbers a user checks by hand (a track move's trapezoid, a track past its range at its line, a
tool hit by the turning jig at the instant a python-fcl witness gives).

Witnesses: the trapezoid is computed here from distance, speed and acceleration; the jig's
contact with the torch is found by python-fcl (an independent collision library) on a box and a
cylinder placed with plain numpy from the cell text's numbers, the turntable's angle following
the hand trapezoid; the reference example is read from the markdown file itself."""

from __future__ import annotations

import math
import re
from pathlib import Path

import fcl
import numpy as np
import pytest
from click.testing import CliRunner

from ext_axes_witness import at, positioner_flange, robot_base, rot

from rmot.backends import BACKENDS
from rmot.compiler.cli import cli
from rmot.compiler.frontend import load_text
from rmot.compiler.plan import plan_program
from rmot.lang import ir
from rmot.sim.verification import verify

REFERENCE = Path(__file__).resolve().parents[2] / "lang" / "REFERENCE.md"

# The declarations, the track broken over three lines as the positioner is over three.
CELL = """cell hidden {
  track rail = linear(axis x, range(0mm, 4000mm))
               speed 1500 mm/s accel 2000 mm/s^2
               at pose(z=0mm)
  robot r1 = kuka_kr16 on rail at pose(z=250mm)
  positioner pos = axes(revolute(axis y, range(-90deg, 90deg)) speed 90 deg/s accel 180 deg/s^2,
                        revolute(axis z, range(-360deg, 360deg)) speed 180 deg/s accel 360 deg/s^2)
                   at pose(x=1800mm, z=700mm)
  fixture jig = box(600mm, 400mm, 40mm) on pos at pose(z=20mm)
  frame work = pos * pose(z=40mm)          # rides on the positioner's flange
  tool torch = cylinder(r=15mm, h=200mm) at pose(z=200mm) tcp pose(z=300mm) on r1
}
"""
HOME = "joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg)"


def _plan(program: str, cell: str = CELL):  # type: ignore[no-untyped-def]
    front = load_text(cell + program, "/tmp/ext_axes_hidden.rmot")
    assert front.program is not None, [d.message for d in front.diagnostics]
    assert not [d for d in front.diagnostics if d.is_error], [d.message for d in front.diagnostics]
    return plan_program(front.program)


def _errors(plan) -> list:  # type: ignore[no-untyped-def,type-arg]
    return [d for d in verify(plan).diagnostics if d.is_error]  # the plan's own findings included


def _record(plan, line: int):  # type: ignore[no-untyped-def]
    tp = plan.tasks[0]
    return next(r for r in tp.records if r.span is not None and r.span.start.line == line)


def trapezoid(distance: float, speed: float, accel: float) -> float:
    """Rest-to-rest time of a move over `distance` at most `speed` and `accel` (triangle if short)."""
    if distance * accel <= speed * speed:
        return 2 * math.sqrt(distance / accel)
    return distance / speed + speed / accel


# ------------------------------------------------------------------ the declarations


def test_a_track_declaration_spans_lines_like_a_positioner() -> None:
    one_line = CELL.replace("""linear(axis x, range(0mm, 4000mm))
               speed 1500 mm/s accel 2000 mm/s^2
               at pose(z=0mm)""", "linear(axis x, range(0mm, 4000mm)) speed 1500 mm/s accel 2000 mm/s^2 at pose(z=0mm)")
    assert one_line != CELL
    program = "program p on r1 with rail, pos {\n  move joint " + HOME + "\n}\n"
    spread, single = (load_text(c + program, "/tmp/t.rmot") for c in (CELL, one_line))
    assert not spread.diagnostics, [d.message for d in spread.diagnostics]
    assert spread.program is not None and single.program is not None
    def numbers(program: ir.Program) -> list[tuple]:  # type: ignore[type-arg]
        assert program.cell.external is not None
        return [(m.name, m.base, [(a.name, a.linear, a.direction, a.low, a.high, a.speed, a.accel) for a in m.axes])
                for m in program.cell.external.mechanisms]
    assert numbers(spread.program) == numbers(single.program)
    assert numbers(spread.program)[0] == ("rail", ir.Pose(), [("rail", True, (1.0, 0.0, 0.0), 0.0, 4.0, 1.5, 2.0)])


def test_every_axis_option_and_on_may_start_a_line() -> None:
    """A track's options, and `on` in any declaration that takes it, may each start a line."""
    cell = """cell c {
  track rail = linear(axis x, range(0mm, 4000mm))
    speed 1500 mm/s
    accel 2000 mm/s^2
    solid(box(600mm, 500mm, 100mm), at=pose(z=150mm))
    mass 250 kg
    at pose(z=0mm)
  robot r1 = kuka_kr16
    on rail
    at pose(z=250mm)
  positioner turn = axes(revolute(axis z, range(-360deg, 360deg)) speed 180 deg/s accel 360 deg/s^2)
    on rail
    at pose(x=900mm, z=400mm)
  fixture plate = cylinder(r=300mm, h=30mm)
    on turn at pose(z=15mm)
  tool torch = none tcp pose(z=300mm)
    on r1
}
"""
    front = load_text(cell + "program p on r1 with rail, turn {\n  move joint " + HOME + "\n}\n", "/tmp/t.rmot")
    assert front.program is not None and not [d for d in front.diagnostics if d.is_error], [d.message for d in front.diagnostics]
    external = front.program.cell.external
    assert external is not None
    rail, turn = external.mechanisms
    assert (rail.axes[0].speed, rail.axes[0].accel, rail.axes[0].mass) == pytest.approx((1.5, 2.0, 250.0))
    assert "rail.solid1" in {f.name for f in front.program.cell.fixtures} and turn.on == "rail"
    assert {(m.body, m.mechanism) for m in external.mounts} >= {("r1", "rail"), ("plate", "turn")}
    assert front.program.cell.robots[0].base.position == pytest.approx((0.0, 0.0, 0.25))


def test_a_speed_line_after_a_move_stays_a_speed_setting() -> None:
    """Only a track or positioner declaration continues on a line starting with `speed`."""
    plan = _plan("program p on r1 with rail, pos {\n  move joint " + HOME + "\n  speed 123 mm/s\n"
                 "  move linear pose(x=1000mm, z=800mm, ry=180deg)\n}\n")
    moves = [i for i in plan.tasks[0].task.body if isinstance(i, ir.Move)]
    assert moves[1].motion.tcp_speed == pytest.approx(0.123) != moves[0].motion.tcp_speed


# ------------------------------------------------------------------ the reference's example


def _reference_example() -> str:
    text = REFERENCE.read_text(encoding="utf-8")
    section = text[text.index("## 15. External axes"):]
    found = re.search(r"```rmot\n(.*?)```", section, re.S)
    assert found is not None
    return found.group(1)


def test_the_reference_example_checks_clean(tmp_path: Path) -> None:
    """`rmot check` of §15's first example: exit 0, no error or warning (the W603 note only)."""
    path = tmp_path / "weld_cell.rmot"
    path.write_text(_reference_example(), encoding="utf-8")
    result = CliRunner().invoke(cli, ["check", str(path)])
    assert result.exit_code == 0, result.output
    assert re.findall(r"(?:error|warning)\[(\w+)\]", result.output) == []


# ------------------------------------------------------------------ the numbers a user checks


def test_a_track_move_lasts_the_hand_trapezoid_and_counts_in_the_cycle() -> None:
    plan = _plan("program p on r1 with rail, pos {\n  tool torch\n  move joint " + HOME + "\n"
                 "  move axes rail to 3000mm\n  move axes rail to 2500mm\n}\n")
    first, second = _record(plan, 16), _record(plan, 17)
    # 3000 mm at 1500 mm/s, 2000 mm/s^2: 0.75 s ramps of 562.5 mm and 1875 mm cruising: 2.75 s;
    # 500 mm back is a triangle (500 mm * 2000 mm/s^2 < (1500 mm/s)^2): 2 sqrt(0.25 s^2) = 1.0 s
    assert first.t_end - first.t_start == pytest.approx(trapezoid(3.0, 1.5, 2.0), abs=plan.step)
    assert trapezoid(3.0, 1.5, 2.0) == pytest.approx(2.75) and trapezoid(0.5, 1.5, 2.0) == pytest.approx(1.0)
    assert second.t_end - second.t_start == pytest.approx(trapezoid(0.5, 1.5, 2.0), abs=plan.step)
    assert plan.cycle_time == pytest.approx(2.75 + 1.0, abs=2 * plan.step)  # the first move is not counted


@pytest.mark.parametrize("move,line_text", [
    ("move axes rail to 4200mm", "4200 mm"),
    ("move joint " + HOME + " ext(rail=4500mm)", "4500 mm"),
])
def test_a_track_target_past_its_range_is_a_finding_naming_rail_at_its_line(move: str, line_text: str) -> None:
    plan = _plan("program p on r1 with rail, pos {\n  tool torch\n  move joint " + HOME + "\n"
                 "  move axes rail to -100mm\n  move joint " + HOME + " ext(rail=0mm)\n  " + move + "\n}\n")
    found = [(d.span.start.line, d.message) for d in _errors(plan) if d.code.id == "E605"]
    assert found == [(16, "axis 'rail' must stay within [0 mm, 4000 mm] (got -100 mm)"),
                     (18, f"axis 'rail' must stay within [0 mm, 4000 mm] (got {line_text})")]


def _jig(turn_deg: float) -> fcl.CollisionObject:
    """The jig (600 x 400 x 40 mm box, 20 mm above the flange) with the positioner at (0, turn)."""
    pose = at(1.8, 0.0, 0.7) @ rot("z", turn_deg) @ at(z=0.02)
    return fcl.CollisionObject(fcl.Box(0.6, 0.4, 0.04), fcl.Transform(pose[:3, :3], pose[:3, 3]))


def _torch(tip: tuple[float, float, float]) -> fcl.CollisionObject:
    """The torch (15 mm radius, 200 mm long, ending at the TCP) pointing straight down at `tip`."""
    centre = np.asarray(tip) + (0.0, 0.0, 0.1)
    return fcl.CollisionObject(fcl.Cylinder(0.015, 0.2), fcl.Transform(np.eye(3), centre))


def _gap(turn_deg: float, tip: tuple[float, float, float]) -> float:
    return float(fcl.distance(_jig(turn_deg), _torch(tip), fcl.DistanceRequest(), fcl.DistanceResult()))


def test_the_turning_jig_hits_the_torch_at_the_move_axes_line_and_the_fcl_time() -> None:
    """The torch is held 250 mm out from the turntable axis, its tip 20 mm below the jig's top,
    beside the jig's short half-width (200 mm at 90 deg); turning the jig back to 0 deg brings
    its 300 mm half-length round into the torch. fcl finds the angle of first contact; the hand
    trapezoid (90 deg at 180 deg/s and 360 deg/s^2: a triangle of 1 s) the instant."""
    tip = (2.05, 0.0, 0.72)
    plan = _plan("program p on r1 with rail, pos {\n  tool torch\n  move joint " + HOME + "\n"
                 "  move axes pos to (0deg, 90deg)\n"
                 "  move joint pose(x=2050mm, y=0mm, z=900mm, rx=180deg) frame world ext(rail=900mm)\n"
                 "  move linear pose(x=2050mm, y=0mm, z=720mm, rx=180deg) frame world speed 100 mm/s\n"
                 "  move axes pos to (0deg, 0deg)\n}\n")
    hits = [d for d in _errors(plan) if d.code.id == "E300"]
    assert [(d.span.start.line, set(d.bodies)) for d in hits] == [(19, {"torch", "jig"})]
    assert _gap(90.0, tip) > 0.03 and _gap(0.0, tip) < 0  # clear where it starts, deep where it ends
    lo, hi = 0.0, 90.0  # the turn at first contact: gap(hi) > 0 >= gap(lo)
    for _ in range(50):
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if _gap(mid, tip) > 0 else (mid, hi)
    swept = math.radians(90.0 - hi)
    accel = math.radians(360.0)
    half = math.radians(45.0)
    after = math.sqrt(2 * swept / accel) if swept <= half else 1.0 - math.sqrt(2 * (2 * half - swept) / accel)
    rec = _record(plan, 19)
    assert rec.t_end - rec.t_start == pytest.approx(1.0, abs=plan.step)
    assert hits[0].time_s == pytest.approx(rec.t_start + after, abs=2 * plan.step)


def test_the_same_hold_clear_of_the_jig_is_clean() -> None:
    """350 mm out the torch is beyond the jig's corners (360 mm) only by less than its radius:
    400 mm out it is clear all the way round."""
    plan = _plan("program p on r1 with rail, pos {\n  tool torch\n  move joint " + HOME + "\n"
                 "  move axes pos to (0deg, 90deg)\n"
                 "  move joint pose(x=2200mm, y=0mm, z=900mm, rx=180deg) frame world ext(rail=900mm)\n"
                 "  move linear pose(x=2200mm, y=0mm, z=720mm, rx=180deg) frame world speed 100 mm/s\n"
                 "  move axes pos to (0deg, 0deg)\n}\n")
    assert _errors(plan) == []


# ------------------------------------------------------------------ frames and loops


def test_a_frame_built_on_a_riding_frame_rides_with_it() -> None:
    """`frame seam = work * pose(x=-150mm)` is on the part: with the turntable at 90 deg its
    target turns with it (witness: numpy from the cell's numbers), and RAPID writes its work
    object coordinated with the unit."""
    cell = CELL.replace("  tool torch", "  frame seam = work * pose(x=-150mm)\n  tool torch")
    plan = _plan("program p on r1 with rail, pos {\n  tool torch\n  move joint " + HOME + "\n"
                 "  move joint pose(z=100mm, rx=180deg) frame seam ext(rail=900mm, pos=(0deg, 90deg))\n}\n", cell)
    assert [(m.body, m.mechanism) for m in plan.program.cell.external.mounts if m.kind == "frame"] == [
        ("work", "pos"), ("seam", "pos")]
    rec = _record(plan, 17)
    got = robot_base(900.0) @ rec.tcp_pose.matrix()
    want = positioner_flange(0.0, 90.0) @ at(z=0.04) @ at(x=-0.15) @ at(z=0.1) @ rot("x", 180.0)
    assert np.abs(got - want).max() < 1e-6
    assert np.abs(want[:3, 3] - (1.8, -0.15, 0.84)).max() < 1e-9  # turned a quarter: -150 mm along y
    (text,) = BACKENDS["rapid"]().emit(plan).files.values()
    assert 'PERS wobjdata seam:=[FALSE,FALSE,"POS",[[-150.000,0.000,40.000]' in text


def test_a_frame_on_two_mechanisms_through_a_riding_frame_is_e602() -> None:
    cell = CELL.replace("  tool torch", "  frame odd = work * rail\n  tool torch")
    front = load_text(cell + "program p on r1 with rail, pos {\n  move joint " + HOME + "\n}\n", "/tmp/t.rmot")
    assert [(d.code.id, d.span.start.line) for d in front.diagnostics if d.is_error] == [("E602", 11)]
    assert "must ride on one mechanism (got pos, rail)" in front.diagnostics[0].message


def test_a_loop_unrolled_for_its_axes_says_so_in_words() -> None:
    """The first round moves the track, the others do not: each vendor unrolls it (W420) and
    says what differs by name, not as a record's repr."""
    plan = _plan("program p on r1 with rail, pos {\n  tool torch\n  move joint " + HOME + "\n"
                 "  for i in 0 .. 2 {\n    move joint " + HOME + " ext(rail=500mm)\n    wait 100 ms\n  }\n}\n")
    result = BACKENDS["krl"]().emit(plan)
    (w420,) = [d.message for d in result.diagnostics if d.code.id == "W420"]
    assert "Motion(" not in w420 and "time the external axes need (s) none vs " in w420


# ------------------------------------------------------------------ plots


def test_the_tcp_speed_plot_of_a_coordinated_seam_is_relative_to_the_part() -> None:
    """A 60 mm seam at 20 mm/s in the part frame while the turntable turns 60 deg: the plotted
    TCP speed cruises at the programmed 20 mm/s (the speed the program states, relative to the
    part); in world the torch point also sweeps round the turntable axis, far faster."""
    from rmot.sim.plots import plot_data

    plan = _plan("program p on r1 with rail, pos {\n  tool torch\n  move joint " + HOME + "\n"
                 "  move joint pose(x=-130mm, y=0mm, z=5mm, rx=180deg) frame work ext(rail=900mm)\n"
                 "  move linear pose(x=-70mm, y=0mm, z=5mm, rx=180deg) frame work ext(pos=(0deg, 60deg)) speed 20 mm/s\n}\n")
    assert _errors(plan) == []
    rec = _record(plan, 17)
    td = plot_data(plan).tasks[0]
    middle = (td.t > rec.t_start + 0.25 * (rec.t_end - rec.t_start)) & (td.t < rec.t_end - 0.25 * (rec.t_end - rec.t_start))
    assert middle.sum() > 100
    np.testing.assert_allclose(td.tcp_speed[middle], 20.0, rtol=0.01)
    # 60 mm at 20 mm/s: 3 s (the turntable's 60 deg alone would take 0.8 s)
    assert rec.t_end - rec.t_start == pytest.approx(3.0, abs=0.2)


# ------------------------------------------------------------------ slots in `with` order


def _slot_program(with_clause: str, cell: str = CELL):  # type: ignore[no-untyped-def]
    return _plan("program p on r1 with " + with_clause + " {\n  tool torch\n  move joint " + HOME + "\n"
                 "  move joint pose(x=-100mm, y=50mm, z=120mm, rx=180deg) frame work ext(rail=900mm, pos=(30deg, 90deg))\n}\n", cell)


@pytest.mark.parametrize("with_clause", ["rail, pos", "pos, rail"])
def test_the_checklist_names_the_slot_each_value_is_written_in(with_clause: str) -> None:
    """The header's `eax_b = pos.1` (RAPID) and `E2 = pos.1` (KRL) must name the axis whose value
    that slot of the targets holds, whatever the `with` order; the values read back by the
    checklist's names are the program's (900 mm, 30 deg, 90 deg)."""
    plan = _slot_program(with_clause)
    want = {"rail": 900.0, "pos.1": 30.0, "pos.2": 90.0}
    (rapid,) = BACKENDS["rapid"]().emit(plan).files.values()
    slots = {"abcdef".index(s): name for s, name in re.findall(r"!\s+eax_([a-f]) = ([\w.]+):", rapid)}
    extax = re.search(r"CONST robtarget \w+:=\[.*,\[([^\]]*)\]\];", rapid)
    assert extax is not None and len(slots) == 3
    values = [float(v) for v in extax.group(1).split(",")]
    assert {name: values[k] for k, name in slots.items()} == pytest.approx(want)
    files = BACKENDS["krl"]().emit(plan).files
    src, dat = (next(t for n, t in files.items() if n.endswith(ext)) for ext in (".src", ".dat"))
    slots = {int(k): name for k, name in re.findall(r";\s+E(\d) = ([\w.]+):", src)}
    e6pos = re.search(r"DECL E6POS \w+=\{(.*)\}", dat)
    assert e6pos is not None and len(slots) == 3
    e = {int(k): float(v) for k, v in re.findall(r"E(\d) (-?[\d.]+)", e6pos.group(1))}
    assert {name: e[k] for k, name in slots.items()} == pytest.approx(want)


def test_fanuc_numbers_the_rail_e1_when_the_positioner_is_declared_first() -> None:
    track = "  track rail = linear(axis x, range(0mm, 4000mm))\n               speed 1500 mm/s accel 2000 mm/s^2\n               at pose(z=0mm)\n"
    assert track in CELL
    robot = "  robot r1 = kuka_kr16 on rail at pose(z=250mm)\n"
    cell = CELL.replace(track, "").replace(robot, "").replace("  fixture jig", track + robot + "  fixture jig")
    assert cell.index("positioner pos") < cell.index("track rail")
    (text,) = BACKENDS["fanuc"]().emit(_slot_program("rail, pos", cell)).files.values()
    assert re.findall(r"!\s*GP1 E(\d) = rail", text) == ["1"] and "E1=   900.000  mm" in text


# ------------------------------------------------------------------ modifiers that would be ignored


def _diagnostics(program: str) -> list[tuple[str, int, int, str]]:
    front = load_text(CELL + program, "/tmp/ext_axes_hidden.rmot")
    found = list(front.diagnostics)
    if front.program is not None and not [d for d in found if d.is_error]:
        found = list(verify(plan_program(front.program)).diagnostics)
    return [(d.code.id, d.span.start.line, d.span.start.col, d.message) for d in found if d.is_error]


@pytest.mark.parametrize("modifier,col", [("speed 100 mm/s", 28), ("zone 10 mm", 28), ("frame work", 28)])
def test_move_axes_refuses_a_modifier_it_would_ignore(modifier: str, col: int) -> None:
    found = _diagnostics("program p on r1 with rail, pos {\n  move joint " + HOME + "\n  move axes rail to 1000mm "
                         + modifier + "\n}\n")
    assert [(c, line, column) for c, line, column, _ in found] == [("E611", 15, col)]
    assert f"'move axes' takes no '{modifier.split()[0]}'" in found[0][3]


def test_move_axes_keeps_its_time_or_says_it_cannot() -> None:
    """`time 5 s` stretches the 1000 mm rail move (1.414 s at full acceleration: a triangle) to
    5 s; `time 0.5 s` is shorter than the rail can go: E227 at the line, naming both times."""
    plan = _plan("program p on r1 with rail, pos {\n  move joint " + HOME + "\n  move axes rail to 1000mm time 5 s\n}\n")
    rec = _record(plan, 15)
    assert rec.t_end - rec.t_start == pytest.approx(5.0, abs=plan.step) and _errors(plan) == []
    assert trapezoid(1.0, 1.5, 2.0) == pytest.approx(math.sqrt(2.0))
    found = _diagnostics("program p on r1 with rail, pos {\n  move joint " + HOME + "\n  move axes rail to 1000mm time 0.5 s\n}\n")
    assert [(c, line) for c, line, _, _ in found] == [("E227", 15)]
    assert "at least the 1.414 s the external axes need" in found[0][3] and "(got 0.500 s)" in found[0][3]
    found = _diagnostics("program p on r1 with rail, pos {\n  move joint " + HOME + "\n  move joint " + HOME
                         + " ext(rail=1000mm) time 0.5 s\n}\n")
    assert [(c, line) for c, line, _, _ in found] == [("E227", 15)]


def test_an_axis_set_twice_in_one_ext_is_e604() -> None:
    found = _diagnostics("program p on r1 with rail, pos {\n  move joint " + HOME + " ext(rail=100mm, rail=200mm)\n}\n")
    assert [(c, line) for c, line, _, _ in found] == [("E604", 14)]
    assert "must set 'rail' once" in found[0][3]


def test_e605_runs_from_the_instant_the_rail_leaves_its_range_and_is_not_repeated() -> None:
    """0 -> 4200 mm on the rail's trapezoid (1500 mm/s, 2000 mm/s^2): it passes 4000 mm 200 mm
    before the end, in the braking ramp, sqrt(2 * 0.2 m / 2 m/s^2) = 0.447 s before the move
    ends. The moves after it leave the rail there: the finding is the move that took it out."""
    plan = _plan("program p on r1 with rail, pos {\n  tool torch\n  move joint " + HOME + "\n  move axes rail to 4200mm\n"
                 "  move joint joints(10deg, -90deg, 90deg, 0deg, 45deg, 0deg)\n  move axes pos to (10deg, 0deg)\n}\n")
    found = [d for d in _errors(plan) if d.code.id == "E605"]
    assert [d.span.start.line for d in found] == [16]
    rec = _record(plan, 16)
    assert rec.t_end - rec.t_start == pytest.approx(trapezoid(4.2, 1.5, 2.0), abs=plan.step)
    assert found[0].time_s == pytest.approx(rec.t_end - math.sqrt(2 * 0.2 / 2.0), abs=plan.step)
    assert found[0].end_time_s == pytest.approx(rec.t_end)


# ------------------------------------------------------------------ other arms on the track


def test_an_arm_family_name_suggests_its_variants() -> None:
    front = load_text(CELL.replace("kuka_kr16", "abb_irb2600") + "program p on r1 with rail, pos {\n}\n", "/tmp/t.rmot")
    assert [(d.code.id, d.span.start.line) for d in front.diagnostics] == [("E111", 5)]
    assert front.diagnostics[0].message == "unknown robot model 'abb_irb2600'; did you mean 'abb_irb2600_12_165'?"


@pytest.mark.parametrize("arm,home", [("abb_irb2600_12_165", "joints(0deg, 0deg, 0deg, 0deg, 30deg, 0deg)"),
                                      ("fanuc_m20ia", "joints(0deg, 0deg, 0deg, 0deg, -90deg, 0deg)")])
def test_other_arms_on_the_track_re_expand_for_every_axis_vendor(arm: str, home: str) -> None:
    """The emit test's program (coordinated work object, MoveExtJ, a world-fixed numbered frame)
    with an ABB and a Fanuc arm on the carriage: each vendor's targets, read back by that test's
    readers and placed through the witness' numpy mechanisms, reach the planned TCP within 0.01 mm."""
    from test_ext_axes_emit import SOURCE, fanuc_targets, krl_targets, planned_tcp_world, rapid_targets

    source = SOURCE.replace("kuka_kr16", arm).replace("joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg)", home)
    front = load_text(source, "/tmp/ext_axes_arms.rmot")
    assert front.program is not None and not front.diagnostics, [d.message for d in front.diagnostics]
    plan = plan_program(front.program)
    assert not [d for d in plan.diagnostics if d.is_error]  # planned (the jig's collisions are not this test's)
    outputs = {vendor: BACKENDS[vendor]().emit(plan).files for vendor in ("rapid", "krl", "fanuc")}
    krl = {name.rsplit(".", 1)[1]: text for name, text in outputs["krl"].items()}
    read = {"rapid": rapid_targets(*outputs["rapid"].values()), "krl": krl_targets(krl["src"], krl["dat"]),
            "fanuc": fanuc_targets(*outputs["fanuc"].values())[0]}
    for vendor, got in read.items():
        want = planned_tcp_world(plan, axes_only=vendor == "fanuc")
        assert len(got) == len(want) >= 4, vendor
        for g, w in zip(got, want, strict=True):
            assert np.abs(g[:3, 3] - w[:3, 3]).max() < 1e-5, vendor


@pytest.mark.parametrize("vendor", ["urscript", "val3"])
def test_urscript_and_val3_refuse_saying_where_the_task_can_go(vendor: str) -> None:
    plan = _plan("program p on r1 with rail, pos {\n  tool torch\n  move joint " + HOME + " ext(rail=500mm)\n}\n")
    result = BACKENDS[vendor]().emit(plan)
    assert [(d.code.id, d.span.start.line) for d in result.diagnostics if d.is_error] == [("E607", 15)]
    assert result.has_errors  # the CLI writes nothing for the vendor then
    message = next(d.message for d in result.diagnostics if d.is_error)
    assert "drives external axes (rail, pos.1, pos.2)" in message and "rapid, krl, fanuc and inform only" in message


def test_a_target_built_from_a_riding_frame_is_flagged_where_it_reads_it() -> None:
    """`work * pose(...)` as a value is the part's place with the axes at home: with the turntable
    at 90 deg the TCP goes there (the witness: work at home), not onto the turned part, and W607
    says so at each expression; the same pose given in `frame work` follows the part, silently."""
    front = load_text(CELL + "program p on r1 with rail, pos {\n  tool torch\n  target t = work * pose(x=-100mm, z=100mm, rx=180deg)\n"
                      "  move joint " + HOME + "\n  move joint t frame world ext(rail=900mm, pos=(0deg, 90deg))\n"
                      "  move joint work * pose(x=-100mm, z=100mm, rx=180deg) frame world\n"
                      "  move joint pose(x=-100mm, z=100mm, rx=180deg) frame work\n}\n", "/tmp/t.rmot")
    assert [(d.code.id, d.span.start.line, d.span.start.col) for d in front.diagnostics] == [("W607", 15, 14), ("W607", 18, 14)]
    assert front.program is not None
    plan = plan_program(front.program)
    at_home = at(1.8, 0.0, 0.74) @ at(x=-0.1, z=0.1) @ rot("x", 180.0)
    on_part = positioner_flange(0.0, 90.0) @ at(z=0.04) @ at(x=-0.1, z=0.1) @ rot("x", 180.0)
    for line, want in ((17, at_home), (18, at_home), (19, on_part)):
        got = robot_base(900.0) @ _record(plan, line).tcp_pose.matrix()
        assert np.abs(got - want).max() < 1e-6, line


def test_fanuc_taught_frame_values_re_expand_within_0_01_mm_on_a_turned_track() -> None:
    """A track along y turned -60 deg about z: the controller's world (the robot base with the
    axes at home) is turned too, so the cell's numbered frame `table` has unround values there.
    The header's `UFRAME[3] must hold` values (what a person teaches) are read back by the emit
    test's reader: every position re-expands within 0.01 mm (to 0.1 mm they missed by 0.03 mm)."""
    import test_ext_axes_emit as emit

    def base(rail_mm: float) -> np.ndarray:
        return at(x=0.2) @ rot("z", -60.0) @ at(y=rail_mm / 1000) @ at(z=0.25)

    source = emit.SOURCE.replace("linear(axis x, range(0mm, 4000mm)) speed 1500 mm/s accel 2000 mm/s^2 at pose(z=0mm)",
                                 "linear(axis y, range(0mm, 4000mm)) speed 1500 mm/s accel 2000 mm/s^2 at pose(x=200mm, rz=-60deg)")
    front = load_text(source, "/tmp/ext_axes_turned.rmot")
    assert front.program is not None and not front.diagnostics
    plan = plan_program(front.program)
    (text,) = BACKENDS["fanuc"]().emit(plan).files.values()
    assert "!UFRAME[3] = table must hold: ;" in text
    saved = emit.robot_base
    emit.robot_base = base  # the readers place UFRAME 0 at the controller's world: this track's
    try:
        got, _ = emit.fanuc_targets(text)
        want = emit.planned_tcp_world(plan, axes_only=True)
    finally:
        emit.robot_base = saved
    assert len(got) == len(want) == 5
    assert max(float(np.abs(g[:3, 3] - w[:3, 3]).max()) for g, w in zip(got, want, strict=True)) < 1e-5


def test_fanuc_held_values_fit_a_comment_to_the_micrometre() -> None:
    from rmot.backends.fanuc_tp_text import COMMENT_MAX, held_frame_values

    assert held_frame_values(1279.4, 416.0, 350.0, 0.0, 0.0, 90.0) == ["X 1279.400 Y 416.000 Z 350.000", "W 0.000 P 0.000 R 90.000"]
    rows = held_frame_values(-12345.678, -416.0, -350.25, -179.999, -89.5, 180.0)
    assert rows == ["X -12345.678 Y -416.000", "Z -350.250", "W -179.999 P -89.500 R 180.000"]
    assert all(len(r) <= COMMENT_MAX for r in rows)


def test_a_number_on_a_riding_frame_is_flagged_as_unused() -> None:
    cell = CELL.replace("frame work = pos * pose(z=40mm)          # rides on the positioner's flange",
                        "frame work = pos * pose(z=40mm) number 2")
    front = load_text(cell + "program p on r1 with rail, pos {\n  move joint " + HOME + "\n}\n", "/tmp/t.rmot")
    assert [(d.code.id, d.span.start.line, d.span.start.col) for d in front.diagnostics] == [("W608", 10, 42)]
    assert front.program is not None
    plan = plan_program(front.program)
    (text,) = BACKENDS["fanuc"]().emit(plan).files.values()
    assert "UFRAME[2]" not in text  # indeed not used


def _synced(d: float, duration: float, accel: float, s: float) -> float:
    """A rest-to-rest move of `d` over exactly `duration` at full `accel`, cruise lowered to fit
    (v = (aT - sqrt(a^2 T^2 - 4 a d)) / 2): the distance done after `s`."""
    v = (accel * duration - math.sqrt(max(accel * accel * duration * duration - 4 * accel * d, 0.0))) / 2
    s, ramp = min(max(s, 0.0), duration), v / accel
    if s < ramp:
        return 0.5 * accel * s * s
    if s > duration - ramp:
        return d - 0.5 * accel * (duration - s) ** 2
    return 0.5 * accel * ramp * ramp + v * (s - ramp)


def test_the_jig_turning_while_the_arm_comes_down_is_hit_at_the_first_contact_fcl_finds() -> None:
    """The arm lowers the torch beside the jig while the turntable turns it back from 90 to 0
    deg, both in one joint move. Witness: at every planned sample, the torch placed by the
    ROS-Industrial KR 16 chain (ext_axes_witness.kr16_flange) on the carriage, the jig turned
    by the time-synchronised trapezoid computed here, their distance by python-fcl: the first
    sample in contact is the reported instant (within a sample)."""
    from ext_axes_witness import kr16_flange

    plan = _plan("program p on r1 with rail, pos {\n  tool torch\n  move joint " + HOME + "\n"
                 "  move axes pos to (0deg, 90deg)\n"
                 "  move joint pose(x=2050mm, y=0mm, z=900mm, rx=180deg) frame world ext(rail=900mm)\n"
                 "  move joint pose(x=2050mm, y=0mm, z=720mm, rx=180deg) frame world ext(pos=(0deg, 0deg))\n}\n")
    hits = [d for d in _errors(plan) if d.code.id == "E300"]
    assert [(d.span.start.line, set(d.bodies)) for d in hits] == [(18, {"torch", "jig"})]
    rec, traj = _record(plan, 18), plan.tasks[0].trajectory
    inside = np.flatnonzero((traj.t >= rec.t_start) & (traj.t <= rec.t_end))
    first = None
    for i in inside:
        turn = 90.0 - _synced(90.0, rec.t_end - rec.t_start, 360.0, float(traj.t[i]) - rec.t_start)
        torch = robot_base(900.0) @ kr16_flange(traj.q[i]) @ at(z=0.2)
        body = fcl.CollisionObject(fcl.Cylinder(0.015, 0.2), fcl.Transform(torch[:3, :3], torch[:3, 3]))
        if fcl.distance(_jig(turn), body, fcl.DistanceRequest(), fcl.DistanceResult()) < 0:
            first = float(traj.t[i])
            break
    assert first is not None and rec.t_start < first < rec.t_end
    assert hits[0].time_s == pytest.approx(first, abs=1.5 * plan.step)


def test_e605_in_both_arms_of_an_if_is_reported_in_each() -> None:
    cell = CELL.replace("}\n", "  io in[1] = \"ready\" on r1\n}\n", 1)
    front = load_text(cell + "program p on r1 with rail, pos {\n  move joint " + HOME + "\n  if in[1] == on {\n"
                      "    move axes rail to 4200mm\n  } else {\n    move axes rail to 4200mm\n  }\n"
                      "  move joint joints(10deg, -90deg, 90deg, 0deg, 45deg, 0deg)\n}\n", "/tmp/t.rmot")
    assert front.program is not None
    found = [d.span.start.line for d in verify(plan_program(front.program)).diagnostics if d.code.id == "E605"]
    assert found == [17, 19]
