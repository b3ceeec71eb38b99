"""A feeder's parts in the pictures: the stack grows. Each carton the palletiser has put down
is drawn where it lies, the one in the gripper with it, the one waiting at the infeed stop
there, and no carton that the feeder has not yet presented.

The witness is the plan's own timeline, read here without the phase code: the `detach`
records of the task (their start times) count the cartons put down before an instant, and
the robot's forward kinematics at that instant gives where they were put.
"""

from __future__ import annotations

import base64
from pathlib import Path

import numpy as np
import pytest

from rmot.lang import ir, ir_tree
from rmot.compiler.frontend import load_program
from rmot.compiler.plan import plan_program
from rmot.sim.render.html import scene_data
from rmot.sim.render.scene import prepare, soup

PALLET = Path(__file__).resolve().parents[2] / "examples" / "palletizing.rmot"


@pytest.fixture(scope="module")
def rs():  # type: ignore[no-untyped-def]
    front = load_program(str(PALLET))
    assert front.program is not None
    return prepare(plan_program(front.program))


def _detach_times(rs) -> list[float]:  # type: ignore[no-untyped-def]
    """Start times of the `detach carton` records on the main timeline, in order."""
    tp = rs.plan.tasks[0]
    detaches = {i.uid for i in ir_tree.walk(tp.task.body) if isinstance(i, ir.Detach)}
    return sorted(float(r.t_start) for r in tp.records if r.variant == 0 and r.uid in detaches)


def _cartons(data: dict, frame: int) -> dict[str, np.ndarray]:  # type: ignore[type-arg]
    """carton name -> (3, 4) pose of every carton the viewer draws (a non-degenerate pose) in a frame."""
    poses = np.frombuffer(base64.b64decode(str(data["poses"])), "<f4").reshape(len(data["times"]), -1, 3, 4)  # type: ignore[arg-type]
    names = [b["name"] for b in data["bodies"]]  # type: ignore[attr-defined]
    return {n: poses[frame, i] for i, n in enumerate(names) if n.startswith("carton#") and np.any(poses[frame, i, :, :3])}


def test_the_viewer_draws_the_cartons_put_down_so_far(rs) -> None:  # type: ignore[no-untyped-def]
    detached = _detach_times(rs)
    assert len(detached) == 36  # the example stacks 36 cartons
    data = scene_data(rs, fps=0.5)
    times = np.asarray(data["times"])
    spot = rs.plan.program.cell.parts[0].pose.matrix()[:3, 3]
    for frame in (0, len(times) // 2, len(times) - 1):
        t = times[frame]
        shown = _cartons(data, frame)
        put = sum(1 for d in detached if d < t - 1e-6)
        away = [n for n, pose in shown.items() if np.linalg.norm(pose[:, 3] - spot) > 0.05]
        if frame == len(times) - 1:
            assert len(shown) == put == 36 and len(away) == 36  # the whole stack, the infeed empty
        else:  # those put down, plus at most the one carried and the one waiting at the infeed
            assert put <= len(away) <= put + 1 and len(shown) <= put + 2
    assert not [n for n, pose in _cartons(data, 0).items() if np.linalg.norm(pose[:, 3] - spot) > 1e-6]


def test_a_frame_at_the_start_has_no_stack_and_at_the_end_all_of_it(rs) -> None:  # type: ignore[no-untyped-def]
    from rmot.sim.render.scene import body_poses

    def carton_triangles(t: float) -> int:
        poses = body_poses(rs, np.array([t]))[0]
        tris, _, colors = soup(rs, poses)
        cardboard = np.all(np.isclose(colors, (0.78, 0.56, 0.30), atol=1e-3), axis=1)
        area = np.linalg.norm(np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0]), axis=1)
        return int((cardboard & (area > 1e-9)).sum())  # a carton not there yet is shrunk to a point

    one = 12  # a box is 12 triangles
    assert carton_triangles(0.0) == one  # only the carton waiting at the infeed stop
    assert carton_triangles(float(rs.plan.cycle_time)) == 36 * one


def test_the_report_lists_each_carton_put_down_where_when_and_by_which_line(rs) -> None:  # type: ignore[no-untyped-def]
    from rmot.sim.parts import placements
    from rmot.sim.report_html import _placed_table

    placed = placements(rs.scene, rs.plan)
    assert [p.name for p in placed] == [f"carton#{k}" for k in range(1, 37)]
    assert np.allclose([p.t for p in placed], _detach_times(rs), atol=1e-9)
    lines = PALLET.read_text(encoding="utf-8").splitlines()
    detach_line = next(k for k, text in enumerate(lines, 1) if text.strip().startswith("detach carton"))
    assert {p.span.start.line for p in placed} == {detach_line}
    # each carton stays where the tool left it: the same offset from the flange at every detach
    # (every carton is gripped alike), by the robot library's forward kinematics at that instant
    tp = rs.plan.tasks[0]
    entry = rs.scene.robots[tp.robot]
    offsets = [np.linalg.inv(entry.base @ np.asarray(entry.robot.fk(tp.trajectory.at(p.t)))) @ p.pose for p in placed]
    assert all(np.allclose(o, offsets[0], atol=1e-5) for o in offsets)  # 10 um: grips differ by trajectory sampling
    assert len({tuple(np.round(p.pose[:3, 3], 4)) for p in placed}) == 36  # 36 distinct places
    loops = [text.split()[1] for text in lines if text.strip().startswith("for ")]  # the loop variables, outermost first
    assert placed[0].iteration == ", ".join(f"{v} = 0" for v in loops)
    assert placed[-1].iteration != placed[0].iteration and placed[-1].iteration.startswith(f"{loops[0]} = ")
    table = "".join(_placed_table(placed))
    assert "Parts placed (36)" in table and table.count("<tr>") == 37 and f"palletizing.rmot:{detach_line}" in table
