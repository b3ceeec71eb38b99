"""External axes in what a user reads besides the vendor programs: the CSV and JSON files and
the plots. Each is read back by an independent reader (the csv and json modules, the SVG as
XML) and its axis values compared with a witness: the rest-to-rest trapezoid of each axis
written here from its definition (full acceleration, the cruise speed that ends on time: d =
v (T - v/a)), between the planned start and end of the move that drives it, at the values the
program text gives (mm, deg). Axes are named `rail`, `pos.1`, `pos.2`, never as arm joints."""

from __future__ import annotations

import csv
import io
import json
import math
import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest
from click.testing import CliRunner
from ext_axes_plans import planned
from ext_axes_witness import CELL_HEAD

from rmot.backends.neutral import CsvBackend, JsonBackend
from rmot.compiler.cli import cli
from rmot.lang import ir, ir_tree
from rmot.lang.plan_types import Plan

SOURCE = CELL_HEAD + """  tool torch = none tcp pose(z=300mm) mass 1 kg on r1
}
program p on r1 with rail, pos {
  tool torch
  move joint joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg)
  move joint pose(x=80mm, y=30mm, z=50mm, rx=170deg, rz=20deg) frame work ext(rail=1200mm, pos=(20deg, 90deg))
  move axes pos to (-10deg, 180deg)
  move joint joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg) ext(rail=0mm, pos=(0deg, 0deg))
}
"""
# the axes' values the program's moves give, in its units: rail mm, pos.1 / pos.2 deg
PROGRAM_VALUES = [(0.0, 0.0, 0.0), (1200.0, 20.0, 90.0), (1200.0, -10.0, 180.0), (0.0, 0.0, 0.0)]
LIMITS = {"rail": (0.0, 4000.0, 1500.0, 2000.0), "pos.1": (-90.0, 90.0, 90.0, 180.0), "pos.2": (-360.0, 360.0, 180.0, 360.0)}
UNITS = {"rail": "mm", "pos.1": "deg", "pos.2": "deg"}




@pytest.fixture(scope="module")
def plan() -> Plan:
    return planned(SOURCE, "/tmp/ext_axes_outputs.rmot")


def _moves(plan: Plan) -> list[tuple[float, float]]:
    """(t_start, t_end) of the program's moves, in order."""
    tp = plan.tasks[0]
    moves = [i for i in ir_tree.walk(tp.task.body) if isinstance(i, ir.Move)]
    return [(tp.record(m.uid).t_start, tp.record(m.uid).t_end) for m in moves]  # type: ignore[union-attr]


def witness(plan: Plan, t: np.ndarray, k: int) -> np.ndarray:
    """Axis k (0 rail, 1 pos.1, 2 pos.2) at times t, in mm / deg, from its trapezoids."""
    accel = [2000.0, 180.0, 360.0][k]
    out = np.full(t.shape, PROGRAM_VALUES[0][k])
    for (t0, t1), before, after in zip(_moves(plan)[1:], PROGRAM_VALUES, PROGRAM_VALUES[1:]):
        a, b, T = before[k], after[k], t1 - t0
        if a == b:
            continue
        d = abs(b - a)
        v = (accel * T - math.sqrt(max(accel * accel * T * T - 4 * accel * d, 0.0))) / 2
        for i in np.nonzero((t >= t0) & (t <= t1))[0]:
            s = t[i] - t0
            r = v / accel
            x = (0.5 * accel * s * s if s < r else d - 0.5 * accel * (T - s) ** 2 if s > T - r
                 else 0.5 * accel * r * r + v * (s - r))
            out[i] = a + math.copysign(x, b - a)
        out[t > t1] = b
    return out


def test_csv_axis_columns_named_by_axis_and_unit(plan: Plan) -> None:
    text = CsvBackend().emit(plan).files["p.csv"]
    rows = list(csv.reader(io.StringIO(text)))
    header = rows[0]
    assert header[13:] == ["rail[mm]", "pos.1[deg]", "pos.2[deg]", "rail_d[mm/s]", "pos.1_d[deg/s]", "pos.2_d[deg/s]"]
    assert not any(re.fullmatch(r"q[7-9]|qd[7-9]", h) for h in header)  # never numbered as arm joints
    values = np.array(rows[1:], dtype=float)
    t = values[:, 0]
    for k in range(3):
        np.testing.assert_allclose(values[:, 13 + k], witness(plan, t, k), atol=1e-6)
        speed = values[:, 16 + k]
        assert np.abs(speed).max() <= LIMITS[header[13 + k].split("[")[0]][2] * (1 + 1e-6)
        # the speed column is the position's rate: the integral of speed gives back the travel
        travel = np.concatenate([[0.0], np.cumsum(0.5 * (speed[1:] + speed[:-1]) * np.diff(t))])
        np.testing.assert_allclose(values[0, 13 + k] + travel, values[:, 13 + k], atol=1e-3 * (1 + np.ptp(values[:, 13 + k])))
    assert np.abs(values[:, 16]).max() == pytest.approx(1500.0, rel=1e-3)  # the rail reaches its top speed over 1200 mm


def test_json_carries_axes_per_sample_and_target_with_units(plan: Plan) -> None:
    result = JsonBackend().emit(plan)
    doc = json.loads(result.files["p.json"])
    task = doc["tasks"][0]
    assert [(a["name"], a["mechanism"], a["kind"], a["unit"]) for a in task["axes"]] == [
        ("rail", "rail", "linear", "mm"), ("pos.1", "pos", "revolute", "deg"), ("pos.2", "pos", "revolute", "deg")]
    for a in task["axes"]:
        low, high, speed, accel = LIMITS[a["name"]]
        assert (a["range"], a["speed_limit"], a["accel_limit"]) == ([low, high], speed, accel)
        assert (a["speed_unit"], a["accel_unit"]) == (f"{a['unit']}/s", f"{a['unit']}/s^2")
    t = np.array(task["trajectory"]["t"])
    ext = np.array(task["trajectory"]["ext"])
    assert ext.shape == (t.size, 3) and np.array(task["trajectory"]["ext_d"]).shape == (t.size, 3)
    for k in range(3):
        np.testing.assert_allclose(ext[:, k], witness(plan, t, k), atol=1e-6)
    moves = [i for i in task["instructions"] if i["kind"].startswith("move_")]
    assert [tuple(m["ext"][n] for n in ("rail", "pos.1", "pos.2")) for m in moves] == PROGRAM_VALUES


def test_plot_data_and_svg_name_the_axes(plan: Plan) -> None:
    """The panels the plots are built from: one per axis after the six joints, labelled by name
    and unit, limits dashed at the axis' range / speed / accel; the SVG carries a group per axis."""
    from rmot.sim.plots import figure_bytes, make_figure, plot_data

    data = plot_data(plan)
    for what, unit_suffix, limit_of in (("joints", "", lambda n: LIMITS[n][:2]), ("speeds", "/s", lambda n: (-LIMITS[n][2], LIMITS[n][2])),
                                         ("accels", "/s²", lambda n: (-LIMITS[n][3], LIMITS[n][3]))):
        fig = make_figure(data, what)
        labels = [ax.get_ylabel() for ax in fig.axes]
        assert labels == [f"J{j} [deg{unit_suffix}]" for j in range(1, 7)] + [f"{n} [{UNITS[n]}{unit_suffix}]" for n in LIMITS]
        for ax, name in zip(fig.axes[6:], LIMITS):
            dashed = sorted(line.get_ydata()[0] for line in ax.get_lines() if line.get_linestyle() == "--")
            assert dashed == pytest.approx(sorted(limit_of(name)))
        if what == "joints":
            for k, ax in enumerate(fig.axes[6:]):
                line = ax.get_lines()[0]
                np.testing.assert_allclose(line.get_ydata(), witness(plan, np.asarray(line.get_xdata()), k), atol=1e-6)
    svg = ET.fromstring(figure_bytes(data, "joints", "svg"))
    ids = {g.get("id") for g in svg.iter("{http://www.w3.org/2000/svg}g")}
    assert {"ext-rail", "ext-pos.1", "ext-pos.2"} <= ids


def test_cli_csv_json_plot_of_the_track_example(tmp_path) -> None:  # type: ignore[no-untyped-def]
    """End to end from the command line: the track example's CSV and JSON name the rail."""
    runner = CliRunner()
    out = tmp_path / "out"
    r = runner.invoke(cli, ["compile", "examples/track_tending.rmot", "--target", "csv", "--target", "json", "-o", str(out)])
    assert r.exit_code == 0, r.output
    header = (out / "csv" / "track_tending.csv").read_text().splitlines()[0].split(",")
    assert header[-2:] == ["rail[mm]", "rail_d[mm/s]"]
    doc = json.loads((out / "json" / "track_tending.json").read_text())
    rails = [i["ext"]["rail"] for i in doc["tasks"][0]["instructions"] if "ext" in i]
    assert {600.0, 2000.0, 3400.0, 0.0} == set(rails)
    r = runner.invoke(cli, ["plot", "examples/track_tending.rmot", "-o", str(tmp_path / "a.svg"), "--what", "speeds"])
    assert r.exit_code == 0, r.output
    assert 'id="ext-rail"' in (tmp_path / "a.svg").read_text()


def test_tcp_speed_counts_the_carriage() -> None:
    """`move axes rail to ...` with the arm's joints held: the TCP moves with the carriage, so
    the TCP-speed plot's curve is the rail's trapezoid speed (witness: its derivative)."""
    from rmot.sim.plots import plot_data

    source = CELL_HEAD + """  tool torch = none tcp pose(z=300mm) on r1
}
program p on r1 with rail {
  tool torch
  move joint joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg)
  move axes rail to (1000mm)
}
"""
    plan = planned(source, "/tmp/ext_axes_tcp.rmot")
    td = plot_data(plan).tasks[0]
    t0, t1 = _moves(plan)[1]
    inside = (td.t > t0 + 0.02) & (td.t < t1 - 0.02)
    rail = np.gradient(np.array([witness_rail(t, t0, t1) for t in td.t]), td.t)
    np.testing.assert_allclose(td.tcp_speed[inside], np.abs(rail[inside]), rtol=1e-3, atol=1.0)


def witness_rail(t: float, t0: float, t1: float, d: float = 1000.0, accel: float = 2000.0) -> float:
    """The rail (mm) of a 0 -> d rest-to-rest trapezoid over [t0, t1] at `accel` mm/s^2."""
    T = t1 - t0
    v = (accel * T - math.sqrt(max(accel * accel * T * T - 4 * accel * d, 0.0))) / 2
    s, r = min(max(t - t0, 0.0), T), v / accel
    if s < r:
        return 0.5 * accel * s * s
    if s > T - r:
        return d - 0.5 * accel * (T - s) ** 2
    return 0.5 * accel * r * r + v * (s - r)
