"""The two external-axes examples through the real command line: each checks clean (exit 0,
no error or warning, only the W603 note) at about its cycle time, and compiles for RAPID, KRL
and Fanuc TP with only the documented warnings (W411, W415, W416), and for INFORM with the pulse
scales the examples declare (W450, W604 too; weld_positioner's coordinated seam as SMOVC);
URScript and VAL3 refuse it with E607 and write nothing for it (lang/REFERENCE.md §15).

(The examples drive external axes, which two of the six controllers and both data formats
refuse, so they are not in test_shipped_examples.py's every-vendor list.)"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner, Result
from ext_axes_witness import at, kr16_flange, rot

from rmot.compiler.cli import cli
from rmot.compiler.frontend import load_text
from rmot.compiler.plan import plan_program
from rmot.lang import ir
from rmot.lang.axis_motion import axis_samples, task_axes

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
# example -> approximate cycle time (s) from `rmot check`; +-25 % as for the other examples
CYCLE = {"weld_positioner.rmot": 59.2, "track_tending.rmot": 15.4}


def _run(*args: str) -> Result:
    return CliRunner().invoke(cli, list(args))


@pytest.mark.parametrize("name", sorted(CYCLE))
def test_checks_clean(name: str) -> None:
    result = _run("check", str(EXAMPLES / name), "--format", "json")
    assert result.exit_code == 0, result.output
    report = json.loads(result.stdout)["programs"][0]
    # only the note that the pairs the axes move are checked sample by sample (W603)
    assert [(d["code"], d["severity"]) for d in report["diagnostics"]] == [("W603", "note")]
    assert report["cycle_time_s"] == pytest.approx(CYCLE[name], rel=0.25)


@pytest.mark.parametrize("name", sorted(CYCLE))
def test_compiles_for_rapid_krl_fanuc_and_the_others_refuse(name: str, tmp_path: Path) -> None:
    ok = _run("compile", str(EXAMPLES / name), "--target", "rapid", "--target", "krl", "--target", "fanuc",
              "-o", str(tmp_path / "a"))
    assert ok.exit_code == 0, ok.stderr
    # W415 a KUKA arm for ABB or Fanuc; W416 Fanuc UTOOL/UFRAME written by the program, W411 the
    # tool's mass for the Fanuc payload schedule (both explained in pick_place.rmot)
    assert set(re.findall(r"warning\[(W\d+)\]", ok.stderr)) <= {"W411", "W415", "W416"}
    assert {p.name for p in (tmp_path / "a").iterdir()} == {"rapid", "krl", "fanuc", ".rmot.output"}
    informed = _run("compile", str(EXAMPLES / name), "--target", "inform", "-o", str(tmp_path / "i"))
    assert informed.exit_code == 0, informed.stderr  # weld_positioner's seam as SMOVC (tests/ext_axes/test_ext_axes_inform_coordinated.py)
    # W450 joint targets as Cartesian + RCONF, W604 the station's own VJ (weld_positioner)
    assert set(re.findall(r"warning\[(W\d+)\]", informed.stderr)) <= {"W411", "W415", "W450", "W604"}
    for vendor in ("urscript", "val3"):
        refused = _run("compile", str(EXAMPLES / name), "--target", vendor, "-o", str(tmp_path / vendor))
        assert refused.exit_code != 0 and "error[E607]" in refused.stderr, refused.stderr
        assert not (tmp_path / vendor / vendor).exists()


def test_the_weld_seam_runs_round_the_pipe_in_the_part_frame_while_the_turntable_turns() -> None:
    """weld_positioner's four coordinated arcs, through a witness FK (the KR 16's ROS-I chain,
    ext_axes_witness.kr16_flange; the positioner 1100 mm out and 600 mm up, tilt about y, turn
    about z, `work` 30 mm above its flange; the wire tip 345 mm beyond the flange): at every
    sample the tip lies on the fillet circle (radius 100 mm, z = 0 in `work`) within the path
    tolerance, moves along it at no more than the weld speed relative to the part, and the
    turntable turns a full turn over the seam while the tip stays near the robot's side."""
    path = EXAMPLES / "weld_positioner.rmot"
    front = load_text(path.read_text(encoding="utf-8"), str(path))
    assert front.program is not None
    plan = plan_program(front.program)
    tp = plan.tasks[0]
    values = axis_samples(tp, task_axes(tp.task, plan.program.cell.external))
    arcs = [m for m in tp.task.body if isinstance(m, ir.Move) and m.coordinated is not None]
    assert [m.kind for m in arcs] == [ir.MotionKind.CIRCULAR] * 4
    first, last = tp.record(arcs[0].uid), tp.record(arcs[-1].uid)
    assert first is not None and last is not None
    inside = (tp.trajectory.t >= first.t_start) & (tp.trajectory.t <= last.t_end)
    tips, world = [], []
    for q, (tilt, turn) in zip(tp.trajectory.q[inside], values[inside], strict=True):
        tip = kr16_flange(q) @ at(z=0.345)
        part = at(1.1, 0.0, 0.6) @ rot("y", math.degrees(tilt)) @ rot("z", math.degrees(turn)) @ at(z=0.03)
        tips.append((np.linalg.inv(part) @ tip)[:3, 3])
        world.append(tip[:3, 3])
    p, w = np.array(tips), np.array(world)
    assert np.abs(np.linalg.norm(p[:, :2], axis=1) - 0.1).max() < 5e-5 and np.abs(p[:, 2]).max() < 5e-5
    speed = np.linalg.norm(np.diff(p, axis=0), axis=1) / np.diff(tp.trajectory.t[inside])
    assert speed.max() <= 0.012 * 1.01
    assert math.degrees(values[inside][-1, 1] - values[inside][0, 1]) == pytest.approx(360.0, abs=0.01)
    assert np.abs(w - [1.0, 0.0, 0.63]).max() < 2e-3  # the tip stays at the seam's point nearest the robot
