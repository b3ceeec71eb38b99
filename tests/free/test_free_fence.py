"""`move free` acceptance on cells the search was not tuned on: a fence between pick and place
(against a hand-placed via route), a goal inside the fence, and a sealed passage at the default
budget. Witnesses: the verifier's whole-path check, the same program with a plain `move joint`
(which must collide), a hand route verified by the same checker, and wall-clock time."""

from __future__ import annotations

import subprocess
import sys
import time
from pathlib import Path

import pytest

from rmot.lang import ir
from rmot.compiler.cli import stages
from rmot.compiler.frontend import load_program

HERE = Path(__file__).parent
CLEARANCE = 0.010


def _front(name: str):  # type: ignore[no-untyped-def]
    result = load_program(str(HERE / name))
    assert not result.has_errors, [d.message for d in result.diagnostics]
    return result.program


@pytest.fixture(scope="module")
def fence_plan():  # type: ignore[no-untyped-def]
    return stages.plan(_front("fence_free.rmot"), use_cache=False)


def test_fence_path_verifies_clean_and_is_ordinary_joint_moves(fence_plan) -> None:  # type: ignore[no-untyped-def]
    assert not [d for d in fence_plan.diagnostics if d.is_error]
    notes = [d for d in fence_plan.diagnostics if d.code.id == "W250"]
    assert len(notes) == 1 and notes[0].span.start.line == 13
    vias = [i for i in fence_plan.tasks[0].task.body if isinstance(i, ir.Move) and i.span == notes[0].span]
    assert len(vias) >= 2 and all(v.kind is ir.MotionKind.JOINT for v in vias)
    report = stages.verify(fence_plan, clearance=CLEARANCE, use_cache=False)
    assert not report.errors and not report.warnings, [d.message for d in report.diagnostics]


def test_a_straight_joint_move_hits_the_fence(tmp_path: Path) -> None:
    """Without the search the same move collides with the fence: the test above can fail."""
    (tmp_path / "fence_cell.rmot").write_text((HERE / "fence_cell.rmot").read_text())
    src = (HERE / "fence_free.rmot").read_text()
    old = "move free place frame place_top clearance 10 mm"
    assert old in src
    path = tmp_path / "fence_straight.rmot"
    path.write_text(src.replace(old, "move joint place frame place_top"))
    report = stages.verify(stages.plan(load_program(str(path)).program, use_cache=False), use_cache=False)
    assert any(d.code.id == "E300" and "'fence'" in d.message for d in report.errors)


def test_fence_cycle_time_within_1_3_of_the_hand_route(fence_plan) -> None:  # type: ignore[no-untyped-def]
    hand = stages.plan(_front("fence_hand.rmot"), use_cache=False)
    hand_report = stages.verify(hand, clearance=CLEARANCE, use_cache=False)
    assert not hand_report.errors and not hand_report.warnings
    assert fence_plan.cycle_time <= 1.3 * hand.cycle_time, (fence_plan.cycle_time, hand.cycle_time)


def _compile(out: Path, cache: Path, *flags: str) -> bytes:
    cmd = [str(Path(sys.executable).parent / "rmot"), "compile", str(HERE / "fence_free.rmot"),
           "--target", "json", "--target", "rapid", "--target", "krl", "-o", str(out), *flags]
    env = {"RMOT_CACHE_DIR": str(cache), "PATH": "/usr/bin:/bin", "PYTHONHASHSEED": "random"}
    subprocess.run(cmd, check=True, capture_output=True, env=env)
    return b"".join(p.read_bytes() for p in sorted(out.rglob("*")) if p.is_file())


def test_fence_output_is_byte_identical_over_three_runs_with_and_without_cache(tmp_path: Path) -> None:
    """Three separate processes: no cache; a cold cache (the search runs and is stored); the
    same cache warm (the stored path is read back). All three write the same bytes."""
    uncached = _compile(tmp_path / "a", tmp_path / "cache_none", "--no-cache")
    cold = _compile(tmp_path / "b", tmp_path / "cache")
    assert list((tmp_path / "cache" / "free").rglob("*.json")), "the cold run stored no path"
    warm = _compile(tmp_path / "c", tmp_path / "cache")
    assert uncached and uncached == cold == warm


def test_goal_inside_the_fence_is_named_in_under_two_seconds() -> None:
    program = _front("fence_goal_inside.rmot")
    start = time.perf_counter()
    plan = stages.plan(program, use_cache=False)
    elapsed = time.perf_counter() - start
    found = [d for d in plan.diagnostics if d.code.id == "E250"]
    assert len(found) == 1 and found[0].span.start.line == 13
    assert "'fence'" in found[0].message and "fence" in found[0].bodies
    assert elapsed < 2.0, elapsed


def test_sealed_passage_ends_within_the_default_budget() -> None:
    """sealed_free.rmot sets no 'samples' or 'budget': the defaults end the search."""
    program = _front("sealed_free.rmot")
    free = next(i.free for i in program.tasks[0].body if isinstance(i, ir.Move) and i.free is not None)
    start = time.perf_counter()
    plan = stages.plan(program, use_cache=False)
    elapsed = time.perf_counter() - start
    found = [d for d in plan.diagnostics if d.code.id == "E252"]
    assert len(found) == 1 and found[0].span.start.line == 11
    assert "budget" in found[0].message
    assert elapsed < free.budget, elapsed


def test_report_draws_the_found_path_and_its_via_points(fence_plan) -> None:  # type: ignore[no-untyped-def]
    """The pictures parse as SVG (the standard library's XML parser, not the writer): per view
    one path line, one dot per via point listed in W250, one rectangle per fixture."""
    import xml.etree.ElementTree as ET

    from rmot.sim.free.drawing import free_path_pictures

    pictures = free_path_pictures(fence_plan)
    assert len(pictures) == 1
    caption, svg = pictures[0]
    assert "fence_free.rmot:13:" in caption and "via points" in caption
    note = next(d for d in fence_plan.diagnostics if d.code.id == "W250")
    n_vias = int(note.message.split(" inserted ")[1].split(" via")[0])
    ns = "{http://www.w3.org/2000/svg}"
    views = [ET.fromstring(part + "</svg>") for part in svg.split("</svg>")[:-1]]
    assert len(views) == 2
    for view in views:
        assert len(view.findall(f"{ns}polyline")) == 1
        assert len(view.findall(f"{ns}circle")) == n_vias
        assert {r.findtext(f"{ns}title") for r in view.findall(f"{ns}rect")} == {
            "stand", "pick_table", "place_table", "fence"}
    again = free_path_pictures(stages.plan(_front("fence_free.rmot"), use_cache=False))
    assert again == pictures
