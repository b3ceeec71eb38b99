"""`move free`: the language, the search's findings, determinism, the emitted via points, and
the found path's freedom witnessed by python-fcl (not coal, which the verifier uses)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import fcl
import numpy as np
import pytest

from rmot.lang import ir
from rmot.compiler.cli import stages
from rmot.compiler.frontend import load_program
from rmot.lang.diagnostics import Severity

HERE = Path(__file__).parent


def _front(name: str):  # type: ignore[no-untyped-def]
    result = load_program(str(HERE / name))
    assert not result.has_errors, [d.message for d in result.diagnostics]
    return result.program


def _variant(tmp_path: Path, name: str, old: str, new: str) -> str:
    """`name` with `old` replaced by `new`, written beside a copy of its cell."""
    src = (HERE / name).read_text()
    assert old in src
    for cell in HERE.glob("*_cell.rmot"):
        (tmp_path / cell.name).write_text(cell.read_text())
    path = tmp_path / name
    path.write_text(src.replace(old, new))
    return str(path)


def _codes(plan) -> list[str]:  # type: ignore[no-untyped-def]
    return [d.code.id for d in plan.diagnostics]


@pytest.fixture(scope="module")
def wall_plan():  # type: ignore[no-untyped-def]
    return stages.plan(_front("wall_free.rmot"), use_cache=False)


# --------------------------------------------------------------------------- language


def test_move_free_lowers_to_a_joint_move_with_its_search_options(tmp_path: Path) -> None:
    path = _variant(tmp_path, "wall_free.rmot", "clearance 10 mm",
                    "clearance 15 mm samples 300 budget 30 s speed 200 mm/s zone 5 mm")
    result = load_program(path)
    moves = [i for i in result.program.tasks[0].body if isinstance(i, ir.Move)]
    free = moves[2]
    assert free.kind is ir.MotionKind.JOINT
    assert free.free == ir.FreeMotion(clearance=pytest.approx(0.015), samples=300, budget=30.0)
    assert free.motion.zone.radius == pytest.approx(0.005)
    assert all(m.free is None for m in moves if m is not free)


@pytest.mark.parametrize("modifier, code", [
    ("time 2 s", "E180"),            # its path is unknown before planning
    ("clearance 2 m", "E125"),       # beyond what any cell leaves room for
    ("samples 0", "E118"),           # a whole number >= 1
    ("samples 2.5", "E118"),
    ("clearance 10", "E105"),        # a length needs its unit
    ("budget 0 s", "E118"),
])
def test_bad_move_free_options_are_located_errors(tmp_path: Path, modifier: str, code: str) -> None:
    path = _variant(tmp_path, "wall_free.rmot", "clearance 10 mm", modifier)
    result = load_program(path)
    found = [(d.code.id, d.span.start.line) for d in result.diagnostics if d.is_error]
    assert (code, 12) in found, found


# --------------------------------------------------------------------------- the search


def test_wall_path_verifies_clean_and_lists_its_via_points(wall_plan) -> None:  # type: ignore[no-untyped-def]
    notes = [d for d in wall_plan.diagnostics if d.code.id == "W250"]
    assert len(notes) == 1 and notes[0].severity is Severity.NOTE and notes[0].span.start.line == 12
    assert "via point" in notes[0].message
    body = wall_plan.tasks[0].task.body
    vias = [i for i in body if isinstance(i, ir.Move) and isinstance(i.target, ir.JointTarget)
            and (i.target.name or "").startswith("place_via")]
    assert vias and all(v.kind is ir.MotionKind.JOINT and v.span == notes[0].span for v in vias)
    report = stages.verify(wall_plan, clearance=0.010, use_cache=False)
    assert not report.errors and not report.warnings, [d.message for d in report.diagnostics]


def test_straight_move_through_the_wall_is_what_the_search_avoids(tmp_path: Path) -> None:
    """The same program with `move joint` collides with the wall: the test can fail."""
    path = _variant(tmp_path, "wall_free.rmot", "move free place frame place_top clearance 10 mm",
                    "move joint place frame place_top")
    report = stages.verify(stages.plan(load_program(path).program, use_cache=False), use_cache=False)
    assert any(d.code.id == "E300" and "'wall'" in d.message for d in report.errors)


def test_cycle_time_within_1_3_of_a_hand_placed_route(wall_plan) -> None:  # type: ignore[no-untyped-def]
    hand = stages.plan(_front("wall_hand.rmot"), use_cache=False)
    assert not stages.verify(hand, clearance=0.010, use_cache=False).errors
    assert wall_plan.cycle_time <= 1.3 * hand.cycle_time


def test_goal_inside_a_fixture_is_found_before_any_search() -> None:
    plan = stages.plan(_front("goal_in_fixture.rmot"), use_cache=False)
    found = [d for d in plan.diagnostics if d.code.id == "E250"]
    assert len(found) == 1
    d = found[0]
    assert d.span.start.line == 13 and "'wall'" in d.message and "no path was searched" in d.message
    assert "wall" in d.bodies
    assert "W250" not in _codes(plan)


def test_impossible_passage_ends_with_a_finding_within_the_budget(tmp_path: Path) -> None:
    path = _variant(tmp_path, "sealed_free.rmot", "clearance 10 mm", "clearance 10 mm samples 60")
    result = load_program(path)
    plan = stages.plan(result.program, use_cache=False)
    found = [d for d in plan.diagnostics if d.code.id == "E252"]
    assert len(found) == 1 and found[0].span.start.line == 11
    assert "none within the budget of 60 samples" in found[0].message


# --------------------------------------------------------------------------- determinism


def _compile_json(out: Path, cache: Path) -> bytes:
    cmd = [str(Path(sys.executable).parent / "rmot"), "compile", str(HERE / "wall_free.rmot"), "--target", "json",
           "--target", "rapid", "-o", str(out), "--no-cache"]
    env = {"RMOT_CACHE_DIR": str(cache), "PATH": "/usr/bin:/bin", "PYTHONHASHSEED": "random"}
    subprocess.run(cmd, check=True, capture_output=True, env=env)
    return (out / "json" / "wall_free.json").read_bytes() + (out / "rapid" / "wall_free.mod").read_bytes()


def test_output_is_byte_identical_across_runs_and_processes(tmp_path: Path, wall_plan) -> None:  # type: ignore[no-untyped-def]
    first = _compile_json(tmp_path / "a", tmp_path / "cache_a")
    second = _compile_json(tmp_path / "b", tmp_path / "cache_b")
    assert first == second
    again = stages.plan(_front("wall_free.rmot"), use_cache=False)
    assert [d.message for d in again.diagnostics] == [d.message for d in wall_plan.diagnostics]
    assert np.array_equal(again.tasks[0].trajectory.q, wall_plan.tasks[0].trajectory.q)
    doc = json.loads((tmp_path / "a" / "json" / "wall_free.json").read_text())
    vias = [m for m in doc["tasks"][0]["instructions"] if m["source"] == "wall_free.rmot:12"]
    assert len(vias) >= 2 and all(m["kind"] == "move_joint" for m in vias)


def test_cached_search_gives_the_same_plan(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                           wall_plan) -> None:  # type: ignore[no-untyped-def]
    monkeypatch.setenv("RMOT_CACHE_DIR", str(tmp_path))
    program = _front("wall_free.rmot")
    fresh = stages.plan(program, use_cache=True)
    assert list((tmp_path / "free").rglob("*.json"))
    cached = stages.plan(_front("wall_free.rmot"), use_cache=True)
    for plan in (fresh, cached):
        assert np.array_equal(plan.tasks[0].trajectory.q, wall_plan.tasks[0].trajectory.q)


# --------------------------------------------------------------------------- fcl witness


def _fcl_object(geometry: object, pose: np.ndarray) -> fcl.CollisionObject:
    if isinstance(geometry, ir.Box):
        shape = fcl.Box(*geometry.size)
    elif isinstance(geometry, ir.Capsule):
        shape = fcl.Capsule(geometry.radius, geometry.length)
    elif isinstance(geometry, ir.Cylinder):
        shape = fcl.Cylinder(geometry.radius, geometry.height)
    elif isinstance(geometry, ir.Sphere):
        shape = fcl.Sphere(geometry.radius)
    else:
        raise AssertionError(f"no fcl shape for {geometry!r}")
    return fcl.CollisionObject(shape, fcl.Transform(pose[:3, :3], pose[:3, 3]))


def test_fcl_witness_every_sample_of_the_move_keeps_the_clearance(wall_plan) -> None:  # type: ignore[no-untyped-def]
    """python-fcl (FCL's own GJK), not the verifier's coal, measures every 4 ms sample of the
    free move's time window: the tool and the wrist-side links keep 10 mm from every fixture."""
    from rmot.sim.robots import load_robot

    program = wall_plan.program
    cell = program.cell
    tp = wall_plan.tasks[0]
    robot = load_robot(cell.robot("r1").source.load_key)
    base = cell.robot("r1").base.matrix()
    uids = [i.uid for i in tp.task.body if isinstance(i, ir.Move)]
    free_uid = next(i.uid for i in tp.task.body if isinstance(i, ir.Move) and i.free is not None)
    t0 = tp.record(uids[uids.index(free_uid) - 2]).t_end if len(uids) > 2 else 0.0
    t1 = tp.record(free_uid).t_end
    mask = (tp.trajectory.t >= t0) & (tp.trajectory.t <= t1)
    qs = tp.trajectory.q[mask]
    assert len(qs) > 50
    fixtures = [(f.name, _fcl_object(f.geometry, f.pose.matrix())) for f in cell.fixtures if f.name != "stand"]
    tool = cell.tools[0]
    request, nearest = fcl.DistanceRequest(), np.inf
    for q in qs:
        flange = base @ np.asarray(robot.fk(q))
        solids = np.asarray(robot.solid_poses(q))
        moving = [_fcl_object(tool.geometry, flange @ tool.geometry_pose.matrix())]
        moving += [_fcl_object(s.geometry, base @ solids[k]) for k, s in enumerate(robot.solids) if s.joint_id >= 1]
        for _, fx in fixtures:
            for body in moving:
                result = fcl.DistanceResult()
                nearest = min(nearest, fcl.distance(body, fx, request, result))
    assert nearest >= 0.010 - 1e-4, nearest


def test_check_json_and_ir_planned_show_the_via_points(tmp_path: Path) -> None:
    from click.testing import CliRunner

    from rmot.compiler.cli import cli

    env = {"RMOT_CACHE_DIR": str(tmp_path)}
    program = str(HERE / "wall_free.rmot")
    out = CliRunner().invoke(cli, ["check", program, "--format", "json"], env=env)
    assert out.exit_code == 0, out.output
    notes = [d for d in json.loads(out.output)["programs"][0]["diagnostics"] if d["code"] == "W250"]
    assert len(notes) == 1 and notes[0]["severity"] == "note" and notes[0]["line"] == 12
    dump = CliRunner().invoke(cli, ["ir", program, "--planned"], env=env)
    assert dump.exit_code == 0
    lines = [line for line in dump.stdout.splitlines() if "@12:3" in line]
    assert len(lines) >= 3 and all("name=place_via" in line for line in lines[:-1])
    assert "free(clearance=0.01 samples=1000 budget=120)" in lines[-1]


@pytest.mark.parametrize("old, new, why", [
    ("  move joint home\n  move joint pick frame pick_top\n", "", "first move"),
    ("  move free place frame place_top clearance 10 mm\n",
     "  repeat 2 {\n  move free place frame place_top clearance 10 mm\n  }\n", "loop"),
])
def test_move_free_without_one_known_start_is_refused(tmp_path: Path, old: str, new: str, why: str) -> None:
    path = _variant(tmp_path, "wall_free.rmot", old, new)
    plan = stages.plan(load_program(path).program, use_cache=False)
    found = [d for d in plan.diagnostics if d.code.id == "E253"]
    assert found, (why, [d.message for d in plan.diagnostics])
    assert ("first move" in found[0].message) == (why == "first move")
    assert "W250" not in _codes(plan)
