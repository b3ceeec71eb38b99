"""`rmot compare` gives the numbers separate `rmot check` runs give, and its torques are
pinocchio's RNEA on the planned samples (computed here from the URDF, not through rmot)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from rmot.compiler.cli import cli

ROOT = Path(__file__).resolve().parents[2]
PICK = str(ROOT / "examples" / "pick_place.rmot")
JIG = str(ROOT / "examples" / "urdf_cell" / "load_jig.rmot")


def _check_json(program: str, *extra: str) -> dict:
    result = CliRunner().invoke(cli, ["check", program, "--format", "json", *extra])
    assert result.exit_code in (0, 1), result.output
    return json.loads(result.output)["programs"][0]


def _compare_json(program: str, *robots: str) -> dict:
    args = ["compare", program, "--format", "json"]
    for r in robots:
        args += ["--robot", r]
    result = CliRunner().invoke(cli, args)
    assert result.exit_code in (0, 1), result.output
    return json.loads(result.output)


@pytest.fixture(scope="module")
def pick_compare() -> dict:
    return _compare_json(PICK, "abb_irb1600", "ur10e")


def test_compare_equals_check_on_the_cells_own_robot(pick_compare: dict) -> None:
    """The cell's own arm: the same verdict and cycle time as `rmot check`."""
    check = _check_json(PICK)
    arm = pick_compare["arms"][0]
    assert arm["robot"] == "abb_irb1600"
    assert arm["verified"] == (not any(d["severity"] == "error" for d in check["diagnostics"]))
    assert arm["cycle_time_s"] == pytest.approx(check["cycle_time_s"], abs=1e-6)


def test_compare_equals_check_of_a_cell_edited_to_the_other_arm(pick_compare: dict, tmp_path: Path) -> None:
    """Another arm: the same verdict, first findings and cycle time as `rmot check` with the cell's
    robot declaration edited by hand to that arm."""
    text = (ROOT / "compiler" / "default_cell.rmot").read_text(encoding="utf-8")
    assert "= abb_irb1600 at" in text
    cell = tmp_path / "cell.rmot"
    cell.write_text(text.replace("= abb_irb1600 at", "= ur10e at"), encoding="utf-8")
    check = _check_json(PICK, "--cell", str(cell))
    arm = pick_compare["arms"][1]
    errors = [d for d in check["diagnostics"] if d["severity"] == "error"]
    assert arm["verified"] is (not errors) and not arm["verified"]
    assert arm["cycle_time_s"] is None  # an arm that does not verify has no cycle time a consumer could rank by
    assert [(f["code"], f["line"], f["message"]) for f in arm["first_findings"]] == \
        [(d["code"], d["line"], d["message"]) for d in errors[:3]]


def _rnea_on_plan(pin):  # type: ignore[no-untyped-def]
    """(tau (N,6), qd (N,6), effort (6,)) by pinocchio's RNEA on load_jig's planned samples, the model read
    from the URDF here, the tool's 0.5 kg as a point mass half way to the TCP (cell.rmot: tcp z=120mm)."""
    from rmot.compiler.frontend import load_program
    from rmot.compiler.plan import plan_program

    plan = plan_program(load_program(JIG, require_program=True).program)
    traj = plan.tasks[0].trajectory
    model = pin.buildModelFromUrdf(str(ROOT / "examples" / "urdf_cell" / "arm6.urdf"))
    tool0 = model.frames[model.getFrameId("tool0")]
    lever = tool0.placement.act(np.array([0.0, 0.0, 0.120 / 2]))
    model.inertias[tool0.parentJoint] += pin.Inertia(0.5, lever, np.zeros((3, 3)))
    data = model.createData()
    tau = np.array([pin.rnea(model, data, q, qd, qdd) for q, qd, qdd in zip(traj.q, traj.qd, traj.qdd)])
    return tau, np.asarray(traj.qd), np.asarray(model.effortLimit)


def test_torques_equal_pinocchio_rnea_on_the_planned_samples() -> None:
    """compare's JSON: peak and RMS torque and peak power per joint are pinocchio's RNEA on the plan's samples."""
    pin = pytest.importorskip("pinocchio")
    report = _compare_json(JIG, str(ROOT / "examples" / "urdf_cell" / "arm6.urdf"))["arms"][0]
    tau, qd, effort = _rnea_on_plan(pin)
    dyn = report["dynamics"]
    assert [j["joint"] for j in dyn] == [1, 2, 3, 4, 5, 6]
    np.testing.assert_allclose([j["peak_torque"] for j in dyn], np.abs(tau).max(axis=0), atol=1e-4)
    np.testing.assert_allclose([j["rms_torque"] for j in dyn], np.sqrt((tau ** 2).mean(axis=0)), atol=1e-4)
    np.testing.assert_allclose([j["peak_power_w"] for j in dyn], np.abs(tau * qd).max(axis=0), atol=1e-4)
    np.testing.assert_allclose([j["rated_torque"] for j in dyn], effort, atol=1e-9)
    assert dyn[1]["peak_torque"] > 1.0  # the shoulder holds the arm up: the numbers are not trivially zero


def test_check_dynamics_prints_the_rnea_numbers() -> None:
    """`rmot check --dynamics`: one line per joint with RNEA's peak / RMS torque, peak power and the share of the rating."""
    pin = pytest.importorskip("pinocchio")
    result = CliRunner().invoke(cli, ["check", JIG, "--dynamics"])
    assert result.exit_code == 0, result.output
    tau, qd, effort = _rnea_on_plan(pin)
    peak, rms, power = np.abs(tau).max(axis=0), np.sqrt((tau ** 2).mean(axis=0)), np.abs(tau * qd).max(axis=0)
    expected = [f"  J{j + 1}: {peak[j]:.2f} / {rms[j]:.2f} N·m, {power[j]:.1f} W, {peak[j] / effort[j] * 100:.0f}% of {effort[j]:g} N·m"
                f" (RMS {rms[j] / effort[j] * 100:.0f}%): "
                + ("the motor suffices" if peak[j] <= effort[j] * 1.001 else "EXCEEDS the motor's rating")
                for j in range(6)]
    lines = result.output.splitlines()
    start = lines.index("dynamics: task 'load_jig' (arm6), peak / RMS torque, peak power, peak / rated torque:")
    assert lines[start + 1:start + 7] == expected


def test_library_arms_get_torque_figures(pick_compare: dict) -> None:
    """Library arms carry inertias: every joint gets a peak torque below its rated
    torque on the verified program, and a positive RMS no larger than the peak."""
    arm = pick_compare["arms"][0]
    assert arm["dynamics"] is not None and len(arm["dynamics"]) == 6
    for joint in arm["dynamics"]:
        assert 0 < joint["peak_torque"] <= joint["rated_torque"]


def test_a_robot_without_inertias_says_so() -> None:
    """A `model` robot of a cell has no inertia data: no torque figures, and a note saying why."""
    doc = _compare_json(str(ROOT / "examples" / "model_arm.rmot"))
    arm = doc["arms"][0]
    assert arm["dynamics"] is None and "no inertia data" in arm["note"]


def test_unknown_arm_is_a_finding_not_a_traceback(tmp_path: Path) -> None:
    """An arm file that does not load is reported as not verified, with E320; a name that is no
    library robot and no URDF file is a bad option, E804, before anything is planned."""
    doc = _compare_json(PICK, str(tmp_path / "missing.urdf"))
    assert doc["arms"][0]["verified"] is False
    assert doc["arms"][0]["first_findings"][0]["code"] == "E320"
    result = CliRunner().invoke(cli, ["compare", PICK, "--robot", "no_such_arm", "--format", "json"])
    assert result.exit_code == 2 and "error[E804]" in result.output


def test_compare_place_places_each_arm_first() -> None:
    """--place: an arm that fails at the cell's pose (out of reach) is placed in the region and then verifies,
    with the pose named in the note; the cycle time is that of the placed check."""
    data = Path(__file__).resolve().parent / "data"
    args = ["compare", str(data / "draw.rmot"), "--cell", str(data / "cell_far.rmot"), "--robot", "abb_irb120",
            "--format", "json"]
    plain = json.loads(CliRunner().invoke(cli, args).output)["arms"][0]
    assert plain["verified"] is False and plain["first_findings"][0]["code"] == "E220"
    result = CliRunner().invoke(cli, args + ["--place", "--region", "x=-600mm..0mm, y=-400mm..400mm"])
    assert result.exit_code == 0, result.output
    placed = json.loads(result.output)["arms"][0]
    assert placed["verified"] is True and "placed at x=" in placed["note"]


def _check_dynamics_json(program: str, *extra: str) -> dict:
    """`rmot check --format json --dynamics`, validated against the report's normative schema."""
    from rmot.sim.report import validate_json

    result = CliRunner().invoke(cli, ["check", program, "--format", "json", *extra])
    assert result.exit_code in (0, 1), result.output
    doc = json.loads(result.output)
    assert validate_json(doc) == []
    return doc["programs"][0]


def test_check_json_dynamics_equals_pinocchio_rnea() -> None:
    """`rmot check --format json --dynamics`: each task's `dynamics` block gives per joint pinocchio's RNEA peak
    and RMS torque and peak power on the planned samples, the URDF's effort limit as rated torque and their ratio."""
    pin = pytest.importorskip("pinocchio")
    task = _check_dynamics_json(JIG, "--dynamics")["tasks"][0]
    tau, qd, effort = _rnea_on_plan(pin)
    dyn = task["dynamics"]
    assert dyn["model"] == "arm6" and dyn["note"] == ""
    joints = dyn["joints"]
    assert [j["joint"] for j in joints] == [1, 2, 3, 4, 5, 6] and {j["unit"] for j in joints} == {"N·m"}
    peak = np.abs(tau).max(axis=0)
    np.testing.assert_allclose([j["peak_torque"] for j in joints], peak, atol=1e-5)
    np.testing.assert_allclose([j["rms_torque"] for j in joints], np.sqrt((tau ** 2).mean(axis=0)), atol=1e-5)
    np.testing.assert_allclose([j["peak_power_w"] for j in joints], np.abs(tau * qd).max(axis=0), atol=1e-5)
    np.testing.assert_allclose([j["rated_torque"] for j in joints], effort, atol=1e-9)
    np.testing.assert_allclose([j["utilisation"] for j in joints], peak / effort, atol=1e-6)
    assert joints[1]["peak_torque"] > 1.0


def test_check_json_has_dynamics_only_when_asked() -> None:
    """Without --dynamics the JSON report's tasks carry no `dynamics` key (the version 2 layout is unchanged)."""
    program = _check_dynamics_json(JIG)
    assert program["tasks"] and all("dynamics" not in t for t in program["tasks"])


def test_check_json_dynamics_of_a_robot_without_inertias() -> None:
    """A `model` robot has no inertia data: `joints` is null and the note says why."""
    program = _check_dynamics_json(str(ROOT / "examples" / "model_arm.rmot"), "--dynamics")
    dyn = program["tasks"][0]["dynamics"]
    assert dyn["joints"] is None and "no inertia data" in dyn["note"]


def test_schema_holds_the_dynamics_block_to_its_keys() -> None:
    """The schema's `dynamics` block is closed: an unknown key, a missing key or a wrong unit is a violation."""
    from rmot.sim.report import JSON_SCHEMA, validate_json

    joint = {"joint": 1, "unit": "N·m", "peak_torque": 1.0, "rms_torque": 0.5, "peak_power_w": 2.0,
             "rated_torque": None, "utilisation": None}
    task = {"task": "t", "robot": "r1", "cycle_time_s": 1.0, "moving_s": 1.0, "waiting_s": 0.0, "sync_s": 0.0,
            "instructions": [], "dynamics": {"model": "m", "joints": [joint], "note": ""}}

    def doc(t: dict) -> dict:
        return {"version": 2, "programs": [{"file": "f", "cycle_time_s": 1.0, "assumptions": None,
                                            "tasks": [t], "diagnostics": []}]}

    assert validate_json(doc(task), JSON_SCHEMA) == []
    extra = {**task, "dynamics": {**task["dynamics"], "extra": 1}}
    assert validate_json(doc(extra), JSON_SCHEMA) == ["$.programs[0].tasks[0].dynamics: must not have key 'extra'"]
    missing = {**task, "dynamics": {"model": "m", "joints": None}}
    assert validate_json(doc(missing), JSON_SCHEMA) == ["$.programs[0].tasks[0].dynamics: must have key 'note'"]
    bad_unit = {**task, "dynamics": {**task["dynamics"], "joints": [{**joint, "unit": "Nm"}]}}
    assert len(validate_json(doc(bad_unit), JSON_SCHEMA)) == 1
