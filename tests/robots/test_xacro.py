"""xacro descriptions with packages, expanded inside the project (compiler/passes/xacro_files.py).

The package is ROS-Industrial's layout (abb_irb2400_support/urdf/irb2400_macro.xacro with a
`prefix` macro, a top file including it through `$(find ...)`, a `package://` mesh). Witness:
pinocchio's FK of the plain URDF (tests/data/urdf/irb2400.urdf, the same joints written out)
must equal the expanded arm's at random joint values; hostile files get located errors.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest
import trimesh

from rmot.compiler.frontend import load_program
from rmot.sim.robots import load_robot

PLAIN = Path(__file__).resolve().parents[1] / "data" / "urdf" / "irb2400.urdf"
DECL = 'urdf("vendor/abb_irb2400_support/urdf/irb2400.xacro", packages={abb_irb2400_support: "vendor/abb_irb2400_support"})'


def _package(root: Path, top: str | None = None, macro_extra: str = "") -> Path:
    """vendor/abb_irb2400_support in `root`: the macro made from the plain URDF, a top file."""
    src = PLAIN.read_text()
    body = src[src.index('<link name="base_link">'):src.index("</robot>")]
    body = body.replace('name="', 'name="${prefix}').replace('link="', 'link="${prefix}')
    body = body.replace('velocity="2.618"', 'velocity="${radians(150)}"')  # 150 deg/s = 2.618 rad/s
    body = body.replace('<link name="${prefix}link_1"/>', '<link name="${prefix}link_1"><collision><geometry>'
                        '<mesh filename="package://abb_irb2400_support/meshes/link_1.stl"/></geometry></collision></link>')
    pkg = root / "vendor" / "abb_irb2400_support"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "meshes").mkdir()
    trimesh.creation.box((0.1, 0.1, 0.1)).export(str(pkg / "meshes" / "link_1.stl"))
    (pkg / "urdf" / "irb2400_macro.xacro").write_text(
        '<?xml version="1.0"?>\n<robot xmlns:xacro="http://ros.org/wiki/xacro">\n'
        f'<xacro:macro name="abb_irb2400" params="prefix">\n{body}{macro_extra}</xacro:macro>\n</robot>\n')
    (pkg / "urdf" / "irb2400.xacro").write_text(top or (
        '<?xml version="1.0"?>\n<robot name="abb_irb2400" xmlns:xacro="http://ros.org/wiki/xacro">\n'
        '  <xacro:include filename="$(find abb_irb2400_support)/urdf/irb2400_macro.xacro"/>\n'
        '  <xacro:abb_irb2400 prefix=""/>\n</robot>\n'))
    return pkg


def _front(root: Path, decl: str = DECL):  # type: ignore[no-untyped-def]
    (root / "p.rmot").write_text(f"cell c {{\n  robot r1 = {decl}\n}}\n")
    return load_program(str(root / "p.rmot"))


def _errors(front) -> list[tuple[str, str]]:  # type: ignore[no-untyped-def]
    return [(d.code.id, d.message) for d in front.diagnostics if d.is_error]


def test_xacro_package_expands_to_the_plain_urdf(tmp_path: Path) -> None:
    _package(tmp_path)
    front = _front(tmp_path)
    assert not _errors(front)
    robot = load_robot(front.cell.robots[0].source.ref)
    assert robot.has_closed_form and any(s.name.startswith("link_1") for s in robot.solids)
    plain = pin.buildModelFromUrdf(str(PLAIN))
    data = plain.createData()
    for q in np.random.default_rng(5).uniform(robot.joint_limits[:, 0], robot.joint_limits[:, 1], (50, 6)):
        pin.framesForwardKinematics(plain, data, q)
        assert np.abs(robot.fk(q) - data.oMf[plain.getFrameId("tool0")].homogeneous).max() < 1e-12
    assert np.allclose(robot.velocity_limits[:3], np.radians(150.0))


@pytest.mark.parametrize("top_or_extra, code, words", [
    ('<robot xmlns:xacro="http://ros.org/wiki/xacro"><xacro:property name="h" value="$(env HOME)"/></robot>', "E541", "$(env"),
    ('<robot xmlns:xacro="http://ros.org/wiki/xacro"><link name="${__import__(\'os\').getcwd()}"/></robot>', "E541", "__import__"),
    ('<robot xmlns:xacro="http://ros.org/wiki/xacro"><link name="${load_yaml(\'x.yaml\')}"/></robot>', "E541", "call"),
    ('<robot xmlns:xacro="http://ros.org/wiki/xacro"><link name="${9 ** 9 ** 9}"/></robot>', "E541", "power"),
    ('<!DOCTYPE r [<!ENTITY a "aaaa">]><robot>&a;</robot>', "E541", "entity"),
    ('<robot xmlns:xacro="http://ros.org/wiki/xacro"><xacro:include filename="../../../../outside.xacro"/></robot>',
     "E541", "outside the project"),
    ('<robot xmlns:xacro="http://ros.org/wiki/xacro"><xacro:include filename="$(find other_pkg)/x.xacro"/></robot>',
     "E542", "other_pkg"),
    ('<robot xmlns:xacro="http://ros.org/wiki/xacro"><xacro:nosuchmacro/></robot>', "E540", "must expand"),
    ('<robot', "E540", "must expand"),
])
def test_hostile_or_broken_xacro_is_a_located_error(tmp_path: Path, top_or_extra: str, code: str, words: str) -> None:
    (tmp_path / "outside.xacro").write_text("<robot/>")
    project = tmp_path / "proj"
    _package(project, top=top_or_extra)
    front = _front(project)
    found = _errors(front)
    assert found and found[0][0] == code and words in found[0][1], found
    span = next(d.span for d in front.diagnostics if d.code.id == code)
    assert span is not None and span.start.line == 2


def test_packages_must_be_folders_inside_the_project(tmp_path: Path) -> None:
    _package(tmp_path / "proj")
    found = _errors(_front(tmp_path / "proj", DECL.replace('"vendor/abb_irb2400_support"}', '"../elsewhere"}')))
    assert found and found[0][0] == "E504"
    found = _errors(_front(tmp_path / "proj", DECL.replace('"vendor/abb_irb2400_support"}', '"vendor/missing"}')))
    assert found and found[0][0] == "E501" and "vendor/missing" in found[0][1]
