"""`rmot plot`: the charts of a planned program, checked against the plan itself.

The data behind each chart is tested with computations that do not go through the plot
code: the TCP speed against a finite difference of forward kinematics at a few instants,
the sync bars of two tasks against the sync's meaning (both tasks leave a sync at the same
instant), the limits against the robot model's own arrays. The files are checked to be
real PNG / SVG, byte-identical on a second run.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from rmot.lang import ir, ir_tree
from rmot.compiler.cli import cli
from rmot.compiler.frontend import load_program
from rmot.compiler.plan import plan_program
from rmot.sim.plots import KINDS, figure_bytes, plot_data
from rmot.sim.scene import build_scene

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.fixture(scope="module")
def handover():  # type: ignore[no-untyped-def]
    loaded = load_program(str(EXAMPLES / "handover.rmot"), require_program=True)
    plan = plan_program(loaded.program)
    return plan, plot_data(plan)


def test_tcp_speed_matches_forward_kinematics(handover) -> None:  # type: ignore[no-untyped-def]
    plan, data = handover
    scene = build_scene(plan.program.cell, {})
    for tp, td in zip(plan.tasks, data.tasks):
        robot, base = scene.robots[tp.robot].robot, np.asarray(scene.robots[tp.robot].base)
        moves = {m.uid: m for m in ir_tree.walk(tp.task.body) if isinstance(m, ir.Move)}
        linear = [r for r in tp.records if r.uid in moves and r.variant == 0
                  and moves[r.uid].kind is ir.MotionKind.LINEAR and r.t_end - r.t_start > 0.2]
        assert linear
        for r in linear[:3]:
            t = 0.5 * (r.t_start + r.t_end)  # mid-move: constant programmed speed expected
            h = 1e-3
            tcp = moves[r.uid].tool.tcp.matrix()
            pts = [(base @ robot.fk(tp.trajectory.at(s)) @ tcp)[:3, 3] for s in (t - h, t + h)]
            speed = np.linalg.norm(pts[1] - pts[0]) / (2 * h) * 1000.0
            k = int(np.argmin(np.abs(td.t - t)))
            assert td.tcp_speed[k] == pytest.approx(speed, rel=0.03, abs=2.0)
            assert speed <= moves[r.uid].motion.tcp_speed * 1000.0 * 1.02  # never above the programmed speed


def test_sync_bars_end_together(handover) -> None:  # type: ignore[no-untyped-def]
    _, data = handover
    ends = [{round(t1, 3) for t0, t1, kind, _ in td.bars if kind == "sync" and t1 > t0} for td in data.tasks]
    assert len(ends) == 2
    # a task that waits at a sync leaves it when the other arrives: some end instants coincide
    firsts = [{round(t0, 3) for t0, t1, kind, _ in td.bars if kind == "sync"} | {round(t1, 3) for t0, t1, kind, _ in td.bars if kind == "sync"}
              for td in data.tasks]
    assert ends[0] & firsts[1] and ends[1] & firsts[0]


def test_limits_are_the_robot_model_limits(handover) -> None:  # type: ignore[no-untyped-def]
    plan, data = handover
    scene = build_scene(plan.program.cell, {})
    for tp, td in zip(plan.tasks, data.tasks):
        robot = scene.robots[tp.robot].robot
        np.testing.assert_allclose(np.radians(td.qd_limits), robot.velocity_limits)
        np.testing.assert_allclose(np.radians(td.q_limits), robot.joint_limits)
        np.testing.assert_allclose(np.radians(td.q), tp.trajectory.q)


@pytest.mark.parametrize("what", KINDS)
def test_every_kind_is_a_valid_svg(handover, what: str) -> None:  # type: ignore[no-untyped-def]
    _, data = handover
    svg = figure_bytes(data, what, "svg")
    root = ET.fromstring(svg)
    assert root.tag.endswith("svg")
    assert figure_bytes(data, what, "svg") == svg  # deterministic


def test_cli_writes_png_and_reports_bad_output(tmp_path: Path) -> None:
    runner = CliRunner()
    out = tmp_path / "t.png"
    result = runner.invoke(cli, ["plot", str(EXAMPLES / "handover.rmot"), "-o", str(out), "--what", "timeline"])
    assert result.exit_code == 0, result.output
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert f"wrote {out}" in result.output  # a success says so, as compile and render do
    bad = runner.invoke(cli, ["plot", str(EXAMPLES / "handover.rmot"), "-o", str(tmp_path / "t.jpg")])
    assert bad.exit_code == 2
    missing = runner.invoke(cli, ["plot", str(tmp_path / "none.rmot"), "-o", str(out)])
    assert missing.exit_code == 2 and "E501" in missing.output
    unwritable = runner.invoke(cli, ["plot", str(EXAMPLES / "handover.rmot"), "-o", str(tmp_path / "no" / "dir" / "t.png")])
    assert unwritable.exit_code == 2 and "E600" in unwritable.output
    cell_only = runner.invoke(cli, ["plot", str(EXAMPLES / "cells" / "demo.rmot"), "-o", str(out)])
    assert cell_only.exit_code == 2 and "E119" in cell_only.output


SHIPPED = sorted(p.relative_to(EXAMPLES).as_posix() for p in [*EXAMPLES.glob("*.rmot"), EXAMPLES / "urdf_cell" / "load_jig.rmot"])


@pytest.mark.parametrize("example", SHIPPED)
def test_cli_plots_every_example(example: str, tmp_path: Path) -> None:
    """`rmot plot --what timeline` of every shipped example writes a well-formed SVG naming each
    task of the program, exit 0 (plot shows the plan; collision.rmot's contact is a
    verification finding, not a planning error)."""
    out = tmp_path / "plot.svg"
    result = CliRunner().invoke(cli, ["plot", str(EXAMPLES / example), "--what", "timeline", "-o", str(out)])
    assert result.exit_code == 0, result.output
    root = ET.fromstring(out.read_bytes())
    assert root.tag.endswith("svg")
    program = load_program(str(EXAMPLES / example), require_program=True).program
    text = out.read_text(encoding="utf-8")
    assert all(task.name in text for task in program.tasks)
