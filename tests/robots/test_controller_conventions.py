"""Controller conventions of the robots a cell brings: `model` blocks and URDF files.

Witnesses: the reference chains of tests/robots/reference_arms.py (ROS-Industrial and KUKA
descriptions, each with its driver's pendant mapping), composed with plain numpy by
test_reference_fk.reference_fk. A URDF is written here from those numbers (with ROS-I's
`base` and `tool0` links); a model block is the data sheet's DH table with the pendant's
signs, zeros and Fanuc's J2/J3 coupling declared. Both must reproduce the reference at
random pendant values, and vendor targets must refuse what is not declared.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from reference_arms import BY_NAME, RefArm
from rmot.compiler.cli.compile_cmd import compile_program
from rmot.compiler.frontend import load_program
from rmot.sim.robots import load_robot
from test_reference_fk import reference_fk

JOINT = "speed 200 deg/s accel 800 deg/s^2"

# KR 6 R900 sixx, data sheet PF0030 dimensions 400/25/455/35/420/80 mm, in standard DH with
# the KCP's signs: A1, A4, A6 turn clockwise (pendant sign -1), A3 = 0 forearm in line.
KUKA_MODEL = f"""
  model kr6 {{
    joint revolute dh(a=25mm,  alpha=-90deg, d=400mm, theta=0deg)  pendant(sign=-1) range(-170deg, 170deg) {JOINT}
    joint revolute dh(a=455mm, alpha=0deg,   d=0mm,   theta=0deg)  range(-190deg, 45deg) {JOINT}
    joint revolute dh(a=-35mm, alpha=90deg,  d=0mm,   theta=90deg) range(-120deg, 156deg) {JOINT}
    joint revolute dh(a=0mm,   alpha=-90deg, d=420mm, theta=0deg)  pendant(sign=-1) range(-185deg, 185deg) {JOINT}
    joint revolute dh(a=0mm,   alpha=90deg,  d=0mm,   theta=0deg)  range(-120deg, 120deg) {JOINT}
    joint revolute dh(a=0mm,   alpha=0deg,   d=80mm,  theta=0deg)  pendant(sign=-1) range(-350deg, 350deg) {JOINT}
    CONTROLLER
  }}"""

# M-20iA, data sheet dimensions 150/790/250/835/100 mm, in standard DH from the J2 height (the
# Fanuc world frame): J3 is the forearm's angle to the horizontal (coupled_to=2), J3..J6 turn
# the other way round than the DH joints, J2 = 0 upper arm up, J3 = 0 forearm horizontal.
FANUC_MODEL = f"""
  model m20 {{
    joint revolute dh(a=150mm,  alpha=-90deg, d=0mm,   theta=0deg)   range(-170deg, 170deg) {JOINT}
    joint revolute dh(a=790mm,  alpha=0deg,   d=0mm,   theta=-90deg) range(-100deg, 160deg) {JOINT}
    joint revolute dh(a=-250mm, alpha=90deg,  d=0mm,   theta=180deg) pendant(sign=-1, coupled_to=2) range(-185deg, 273deg) {JOINT}
    joint revolute dh(a=0mm,    alpha=-90deg, d=835mm, theta=0deg)   pendant(sign=-1) range(-200deg, 200deg) {JOINT}
    joint revolute dh(a=0mm,    alpha=90deg,  d=0mm,   theta=0deg)   pendant(sign=-1) range(-140deg, 140deg) {JOINT}
    joint revolute dh(a=0mm,    alpha=0deg,   d=100mm, theta=0deg)   pendant(sign=-1) range(-270deg, 270deg) {JOINT}
    flange pose(rz=180deg)
    controller fanuc
  }}"""

PROGRAM = """
program p on r1 {
  move joint joints(10, 20, 10, 0, 45, 0) deg
  move joint pose(x=400mm, y=100mm, z=300mm, ry=180deg) CONFIG
}
"""


def _cell(tmp_path: Path, model: str, robot: str, config: str = "", name: str = "cell.rmot") -> str:
    text = f"cell c {{{model}\n  robot r1 = {robot}\n}}\n" + PROGRAM.replace("CONFIG", config)
    path = tmp_path / name
    path.write_text(text)
    return str(path)


def _robot_of(path: str):  # type: ignore[no-untyped-def]
    front = load_program(path)
    assert front.program is not None, [d.message for d in front.diagnostics]
    return load_robot(front.program.cell.robots[0].source.ref)


def _worst(robot, arm: RefArm, seed: int = 3) -> float:  # type: ignore[no-untyped-def]
    """The largest pose difference (m, or rad-scaled rotation entries) over 200 random pendant values."""
    qs = np.random.default_rng(seed).uniform(robot.joint_limits[:, 0], robot.joint_limits[:, 1], (200, 6))
    return max(float(np.abs(robot.fk(q) - reference_fk(arm, q)).max()) for q in qs)


def _codes(outcome) -> set[str]:  # type: ignore[no-untyped-def]
    return {d.code.id for d in outcome.diagnostics if d.is_error}


# ----------------------------------------------------------------------------- model blocks

def test_kuka_model_with_pendant_signs_is_the_reference(tmp_path: Path) -> None:
    path = _cell(tmp_path, KUKA_MODEL.replace("CONTROLLER", "controller kuka"), "kr6")
    robot = _robot_of(path)
    assert robot.controller == "kuka" and robot.has_closed_form
    assert _worst(robot, BY_NAME["kuka_kr6_r900"]) < 1e-9


def test_fanuc_model_with_the_j2_j3_coupling_is_the_reference(tmp_path: Path) -> None:
    robot = _robot_of(_cell(tmp_path, FANUC_MODEL, "m20"))
    assert robot.controller == "fanuc"
    assert _worst(robot, BY_NAME["fanuc_m20ia"]) < 1e-9


@pytest.mark.parametrize("model", [KUKA_MODEL.replace("CONTROLLER", "controller kuka"), FANUC_MODEL])
def test_model_closed_form_honours_config(tmp_path: Path, model: str) -> None:
    """Every closed-form row reproduces the pose in pendant values, and two branches give
    different joints with the branch names asked for."""
    robot = _robot_of(_cell(tmp_path, model, "kr6" if "kr6" in model else "m20"))
    q = np.radians([10.0, 20.0, 10.0, 30.0, 45.0, 20.0])
    pose = robot.fk(q)
    rows = robot.ik_closed_form(pose[None])[0]
    found = [r for r in rows if np.all(np.isfinite(r))]
    assert len(found) >= 4
    for r in found:
        assert np.abs(robot.fk(r) - pose).max() < 1e-9
    names = {str(robot.branch(r)) for r in found}
    assert len(names) == len(found)  # each branch its own name


def test_vendor_refuses_undeclared_and_other_makers_model(tmp_path: Path) -> None:
    undeclared = _cell(tmp_path, KUKA_MODEL.replace("CONTROLLER", ""), "kr6", name="a.rmot")
    outcome = compile_program(undeclared, ("krl", "rapid", "csv"), use_cache=False)
    assert set(outcome.refused) == {"krl", "rapid"} and "E480" in _codes(outcome)
    assert any(name.startswith("csv/") for name in outcome.files)
    declared = _cell(tmp_path, KUKA_MODEL.replace("CONTROLLER", "controller kuka"), "kr6", name="b.rmot")
    outcome = compile_program(declared, ("krl", "rapid"), use_cache=False)
    assert outcome.refused == ("rapid",) and _codes(outcome) == {"E481"}
    assert any(name.startswith("krl/") for name in outcome.files)
    message = next(d.message for d in outcome.diagnostics if d.code.id == "E481")
    assert "KUKA" in message and "krl" in message


def test_krl_targets_of_the_model_are_the_library_arms(tmp_path: Path) -> None:
    """The KRL E6AXIS and E6POS (with Status and Turn) of the declared model are those of the
    library KR 6 R900 (itself checked against KUKA's description) for the same program."""
    def decls(model: str, robot: str, name: str) -> list[str]:
        outcome = compile_program(_cell(tmp_path, model, robot, name=name), ("krl",), use_cache=False)
        text = "\n".join(t for n, t in outcome.files.items() if n.endswith(".dat"))
        return [line for line in text.splitlines() if line.strip().startswith("DECL E6")]

    model = decls(KUKA_MODEL.replace("CONTROLLER", "controller kuka"), "kr6", "m.rmot")
    assert len(model) == 2 and "A1 10.0000" in model[0]
    assert model == decls("", "kuka_kr6_r900", "l.rmot")


@pytest.mark.parametrize("line, code", [
    ("pendant(sign=2)", "E185"), ("pendant(coupled_to=5)", "E185"), ("pendant(zero=1mm)", "E104"),
])
def test_bad_pendant(tmp_path: Path, line: str, code: str) -> None:
    model = FANUC_MODEL.replace("pendant(sign=-1, coupled_to=2)", line)
    front = load_program(_cell(tmp_path, model, "m20"))
    assert code in {d.code.id for d in front.diagnostics}


def test_unknown_controller_word(tmp_path: Path) -> None:
    front = load_program(_cell(tmp_path, KUKA_MODEL.replace("CONTROLLER", "controller kukka"), "kr6"))
    found = [d for d in front.diagnostics if d.code.id == "E186"]
    assert found and "did you mean 'kuka'" in found[0].message


# ----------------------------------------------------------------------------- URDF files

def _urdf(arm: RefArm, limits_deg: np.ndarray, with_base: bool = True) -> str:
    """A URDF of the reference chain: base_link, ROS-I's `base` (the controller frame) and
    `tool0` (the flange), written from the reference's numbers only."""
    def origin(xyz, rpy) -> str:  # type: ignore[no-untyped-def]
        return f'<origin xyz="{xyz[0]!r} {xyz[1]!r} {xyz[2]!r}" rpy="{rpy[0]!r} {rpy[1]!r} {rpy[2]!r}"/>'

    out = ['<robot name="ref">', '<link name="base_link"/>']
    if with_base and arm.controller is not None:
        out += ['<link name="base"/>', '<joint name="base_link-base" type="fixed"><parent link="base_link"/>'
                f'<child link="base"/>{origin(*arm.controller)}</joint>']
    parent = "base_link"
    for k, ((xyz, rpy, axis), (lo, hi)) in enumerate(zip(arm.joints, limits_deg), 1):
        out += [f'<link name="link_{k}"/>', f'<joint name="joint_{k}" type="revolute"><parent link="{parent}"/>'
                f'<child link="link_{k}"/>{origin(xyz, rpy)}<axis xyz="{axis[0]} {axis[1]} {axis[2]}"/>'
                f'<limit lower="{math.radians(lo)!r}" upper="{math.radians(hi)!r}" effort="100" velocity="3"/></joint>']
        parent = f"link_{k}"
    for k, (xyz, rpy) in enumerate(arm.tool):
        child = "tool0" if k == len(arm.tool) - 1 else f"tool_{k}"
        out += [f'<link name="{child}"/>', f'<joint name="{parent}-{child}" type="fixed"><parent link="{parent}"/>'
                f'<child link="{child}"/>{origin(xyz, rpy)}</joint>']
        parent = child
    return "\n".join(out + ["</robot>"])


@pytest.mark.parametrize("name, maker", [("fanuc_m20ia", "fanuc"), ("yaskawa_gp8", "yaskawa"),
                                         ("abb_irb120", "abb"), ("staubli_tx2_60", "staubli")])
def test_urdf_with_controller_is_the_reference(tmp_path: Path, name: str, maker: str) -> None:
    arm = BY_NAME[name]
    limits = np.degrees(load_robot(name).joint_limits)  # the range only; the witness is the chain
    (tmp_path / "arm.urdf").write_text(_urdf(arm, limits))
    robot = _robot_of(_cell(tmp_path, "", f'urdf("arm.urdf", controller="{maker}")'))
    assert robot.controller == maker
    assert _worst(robot, arm) < 1e-9


def test_urdf_without_the_controller_frame_is_refused_with_its_name(tmp_path: Path) -> None:
    arm = BY_NAME["yaskawa_gp8"]
    (tmp_path / "arm.urdf").write_text(_urdf(arm, np.degrees(load_robot("yaskawa_gp8").joint_limits), with_base=False))
    front = load_program(_cell(tmp_path, "", 'urdf("arm.urdf", controller="yaskawa")'))
    found = [d for d in front.diagnostics if d.code.id == "E187"]
    assert found and "'base'" in found[0].message and "base=" in found[0].message


def test_urdf_without_controller_is_refused_by_vendors(tmp_path: Path) -> None:
    arm = BY_NAME["abb_irb120"]
    (tmp_path / "arm.urdf").write_text(_urdf(arm, np.degrees(load_robot("abb_irb120").joint_limits)))
    outcome = compile_program(_cell(tmp_path, "", 'urdf("arm.urdf")'), ("rapid", "json"), use_cache=False)
    assert outcome.refused == ("rapid",) and _codes(outcome) == {"E480"}
    message = next(d.message for d in outcome.diagnostics if d.code.id == "E480")
    assert 'controller="abb"' in message


def test_config_on_an_arm_without_branch_names_is_an_error_at_the_move(tmp_path: Path) -> None:
    """A 6R model whose wrist axes do not meet (a 50 mm offset at J5) has no branch names:
    config(...) cannot be honoured and is refused at its move, not ignored."""
    offset = KUKA_MODEL.replace("CONTROLLER", "controller kuka").replace(
        "dh(a=0mm,   alpha=90deg,  d=0mm,   theta=0deg)", "dh(a=0mm,   alpha=90deg,  d=50mm,  theta=0deg)")
    path = _cell(tmp_path, offset, "kr6", config="config(wrist=flip)")
    assert load_robot(load_program(path).program.cell.robots[0].source.ref).branch(np.zeros(6)).wrist is None
    outcome = compile_program(path, ("json",), use_cache=False)
    found = [d for d in outcome.diagnostics if d.code.id == "E188"]
    line = next(k for k, text in enumerate(Path(path).read_text().splitlines(), 1) if "config(wrist=flip)" in text)
    assert found and found[0].span.start.line == line
    assert "drop the config" in found[0].message


@pytest.mark.parametrize("name", ["meshes/link_1.stl", "package://arm_support/meshes/link_1.stl"])
def test_missing_urdf_mesh_is_not_found_with_the_path(tmp_path: Path, name: str) -> None:
    """A mesh that simply is not there is E501 naming the path searched, not E504 (outside)."""
    text = _urdf(BY_NAME["abb_irb120"], np.degrees(load_robot("abb_irb120").joint_limits))
    text = text.replace('<link name="link_1"/>', f'<link name="link_1"><collision><geometry><mesh filename="{name}"/>'
                        '</geometry></collision></link>')
    (tmp_path / "arm.urdf").write_text(text)
    front = load_program(_cell(tmp_path, "", 'urdf("arm.urdf", controller="abb")'))
    found = [d for d in front.diagnostics if d.is_error and d.code.id != "E101"]  # E101: the program's robot
    assert [d.code.id for d in found] == ["E501"], [d.message for d in found]
    assert "must exist" in found[0].message and str(tmp_path / "meshes" / "link_1.stl") in found[0].message \
        or str(tmp_path / "arm_support" / "meshes" / "link_1.stl") in found[0].message
