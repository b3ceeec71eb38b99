"""`rmot robots add`: a DH table becomes a library definition that reproduces its reference.

Witness: the MH5's URDF chain as Yaskawa publishes it (tests/robots/reference_arms_motoman.py,
composed by test_reference_fk.reference_fk with the driver's one-to-one pendant mapping), not
the table nor the code under test.
"""

from __future__ import annotations

import numpy as np
import pytest
from click.testing import CliRunner

from rmot.compiler.cli import cli
from rmot.sim.robots.add_robot import add_from_dh
from rmot.sim.robots.build import build_robot
from rmot.sim.robots.library_common import ACC_EST, YASKAWA_CONV, acc_estimate, sources
from rmot.sim.robots.opw import OpwJointMap, OpwParams
from rmot.sim.robots.spec import opw_spec

# Yaskawa MH5 in pendant values (S L U R B T; U, R, B, T turn against the DH z axes: sign -1),
# frame 0 = the robot frame at the L-axis height, lengths of Yaskawa's mh5_macro.xacro.
MH5 = """\
name: my_mh5
vendor: yaskawa
model: Motoman MH5
dh: standard
source: Yaskawa-Global/motoman_ros2_support_packages motoman_mh5_support/urdf/mh5_macro.xacro
joints:
  - {a: 88, alpha: -90, d: 0, theta: 0, range: [-170, 170], speed: 376}
  - {a: 310, alpha: 0, d: 0, theta: -90, range: [-65, 150], speed: 350}
  - {a: 40, alpha: -90, d: 0, theta: 0, range: [-70, 190], speed: 400, sign: -1}
  - {a: 0, alpha: 90, d: 305, theta: 0, range: [-190, 190], speed: 450, sign: -1}
  - {a: 0, alpha: -90, d: 0, theta: 0, range: [-135, 135], speed: 450, sign: -1}
  - {a: 0, alpha: 0, d: 80, theta: 0, range: [-360, 360], speed: 720, sign: -1}
"""


def _built(text: str):  # type: ignore[no-untyped-def]
    """The printed definition evaluated with the library's own names (our output, not user input)."""
    names = dict(opw_spec=opw_spec, OpwParams=OpwParams, OpwJointMap=OpwJointMap, acc_estimate=acc_estimate,
                 sources=sources, ACC_EST=ACC_EST, YASKAWA_CONV=YASKAWA_CONV)
    return build_robot(eval(text.split("\n", 1)[1], {"__builtins__": {}}, names))  # noqa: S307


def test_mh5_table_becomes_a_definition_equal_to_yaskawas_urdf():
    from reference_arms_motoman import MOTOMAN_ARMS
    from test_reference_fk import reference_fk

    added = add_from_dh("mh5.yaml", MH5)
    assert not [d for d in added.diagnostics if d.is_error]
    assert added.max_mm < 1e-6 and added.max_rad < 1e-9
    robot = _built(added.text)
    assert robot.has_closed_form and robot.conventions == YASKAWA_CONV
    ref = next(a for a in MOTOMAN_ARMS if a.name == "yaskawa_mh5")
    for q in np.random.default_rng(3).uniform(robot.joint_limits[:, 0], robot.joint_limits[:, 1], (40, 6)):
        a, b = robot.fk(q), reference_fk(ref, q)
        assert np.abs(a - b).max() < 1e-8
    assert [d.code.id for d in added.diagnostics] == ["W548"]


@pytest.mark.parametrize("text, code, line", [
    ("name: [unclosed\n", "E547", 2),
    (MH5.replace("speed: 350}", "}"), "E548", 8),
    (MH5.replace("theta: -90,", "theta: ninety,"), "E548", 8),
    (MH5.replace("sign: -1}", "sign: 2}", 1), "E548", 9),
    (MH5.replace("vendor: yaskawa", "vendor: yaskawaa"), "E548", 1),
    ("\n".join(MH5.splitlines()[:-1]) + "\n", "E549", 7),
    (MH5.replace("{a: 0, alpha: 90, d: 305", "{a: 20, alpha: 90, d: 305"), "E549", 1),
])
def test_bad_tables_are_located_errors(text, code, line):
    """Unreadable (E547), a field missing or bad (E548, at its joint), not an OPW arm (E549)."""
    added = add_from_dh("t.yaml", text)
    errors = [d for d in added.diagnostics if d.is_error]
    assert [d.code.id for d in errors] == [code] and added.text == ""
    assert errors[0].span is not None and errors[0].span.start.line == line, errors[0].message


def test_table_without_source_warns_and_cites_unknown():
    added = add_from_dh("t.yaml", "\n".join(row for row in MH5.splitlines() if not row.startswith("source")))
    assert [d.code.id for d in added.diagnostics] == ["W547", "W548"]
    assert "source='unknown'" in added.text


def test_cli_prints_the_definition_or_a_located_error(tmp_path):
    table = tmp_path / "mh5.yaml"
    table.write_text(MH5)
    out = tmp_path / "mh5_def.py"
    ok = CliRunner().invoke(cli, ["robots", "add", str(table), "-o", str(out)])
    assert ok.exit_code == 0, ok.output
    assert out.read_text().startswith("# Motoman MH5") and "checked: FK" in ok.stderr
    table.write_text(MH5.replace("speed: 350}", "}"))
    bad = CliRunner().invoke(cli, ["robots", "add", str(table)])
    assert bad.exit_code == 2 and f"{table}:8:5: error[E548]" in bad.stderr, bad.stderr
    assert isinstance(bad.exception, SystemExit)  # exit 2, no traceback


def _urdf_of(ref) -> str:  # type: ignore[no-untyped-def]
    """A URDF of a reference chain: its joints, `base` (the controller frame) and `tool0`."""
    def origin(xyz, rpy) -> str:  # type: ignore[no-untyped-def]
        return f'<origin xyz="{" ".join(map(repr, xyz))}" rpy="{" ".join(map(repr, rpy))}"/>'

    links = ["base_link"] + [f"link_{i}" for i in range(1, 7)]
    out = ['<robot name="arm">'] + [f'<link name="{n}"/>' for n in links + ["base", "tool0"]]
    for i, (xyz, rpy, axis) in enumerate(ref.joints, 1):
        out.append(f'<joint name="joint_{i}" type="revolute"><parent link="{links[i - 1]}"/><child link="{links[i]}"/>'
                   f'{origin(xyz, rpy)}<axis xyz="{" ".join(map(repr, axis))}"/>'
                   '<limit lower="-2.5" upper="2.5" effort="100" velocity="3"/></joint>')
    out.append(f'<joint name="base_link-base" type="fixed"><parent link="base_link"/><child link="base"/>'
               f'{origin(*ref.controller)}</joint>')
    assert len(ref.tool) == 1
    out.append(f'<joint name="link_6-tool0" type="fixed"><parent link="link_6"/><child link="tool0"/>{origin(*ref.tool[0])}'
               '</joint>')
    return "\n".join(out + ["</robot>"])


def test_urdf_becomes_a_definition_equal_to_its_chain(tmp_path):
    """The GP12's ROS-I chain as a URDF, from `base` to `tool0`: the definition's FK is the chain's."""
    from reference_arms_motoman import MOTOMAN_ARMS
    from test_reference_fk import reference_fk

    from rmot.sim.robots.add_robot import add_from_urdf

    ref = next(a for a in MOTOMAN_ARMS if a.name == "yaskawa_gp12")
    path = tmp_path / "gp12.urdf"
    path.write_text(_urdf_of(ref))
    added = add_from_urdf(str(path), "my_gp12", "yaskawa", "ROS-I gp12_macro.xacro", base="base", tip="tool0")
    assert [d.code.id for d in added.diagnostics] == ["W548"] and added.max_mm < 1e-6
    robot = _built(added.text)
    for q in np.random.default_rng(4).uniform(robot.joint_limits[:, 0], robot.joint_limits[:, 1], (40, 6)):
        a, b = robot.fk(q), reference_fk(ref, q)
        # the URDF's tool0 turn is written 3.1415926 -1.570796: 3e-7 rad off pi, -pi/2
        assert np.abs(a[:3, 3] - b[:3, 3]).max() < 1e-8 and np.abs(a[:3, :3] - b[:3, :3]).max() < 1e-6
    turned = add_from_urdf(str(path), "my_gp12", "yaskawa", "", base="base", tip="link_6")  # flange z across J6
    assert [d.code.id for d in turned.diagnostics] == ["E549"]
