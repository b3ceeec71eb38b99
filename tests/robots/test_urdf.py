"""URDF robots: the UR5 URDF of example-robot-data against UR's DH table, bad files."""

from __future__ import annotations

import importlib.metadata
import os

import numpy as np
import pytest

from rmot.lang import ir
from rmot.sim.robots import IkStatus, RobotError, load_robot
from rmot.sim.robots.build import build_robot
from rmot.sim.robots.spec import ur_spec
from rmot.sim.robots.urik import UrParams


def ur5_urdf() -> str:
    files = importlib.metadata.files("example-robot-data") or []
    return str(next(f for f in files if f.name == "ur5_robot.urdf").locate())


def ur5_from_dh():
    """UR5 (CB3) from UR's official DH table (not a library entry)."""
    params = UrParams(0.089159, -0.425, -0.39225, 0.10915, 0.09465, 0.0823)
    spec = ur_spec(name="ur5", model="UR5", source="UR DH table", params=params, speed_deg_s=(180,) * 6,
                   accel_deg_s2=(720,) * 6, reach=0.85, shoulder_off=0.136, elbow_off=0.120,
                   radii=(0.075, 0.065, 0.055, 0.045, 0.045))
    return build_robot(spec)


def test_ur5_dh_equals_ur5_urdf_up_to_base_and_flange():
    """The UR5 DH chain equals the URDF chain: base_link is DH frame 0 turned by π about z,
    tool0 is DH frame 6 (the transforms are fitted at q = 0, checked on random q)."""
    urdf, dh = load_robot(ur5_urdf()), ur5_from_dh()
    base = np.diag([-1.0, -1.0, 1.0, 1.0])
    flange = np.linalg.inv(base @ dh.fk(np.zeros(6))) @ urdf.fk(np.zeros(6))
    np.testing.assert_allclose(flange, np.eye(4), atol=1e-9)
    for q in np.random.default_rng(0).uniform(-np.pi, np.pi, (100, 6)):
        np.testing.assert_allclose(base @ dh.fk(q) @ flange, urdf.fk(q), atol=1e-9)


def test_urdf_robot_attributes_and_mesh_solids():
    """A URDF robot has its limits, a reach, and collision meshes that exist, one per link."""
    r = load_robot(ur5_urdf())
    assert r.dof == 6 and not r.has_closed_form and r.branch(np.zeros(6)) == ir.Config()
    np.testing.assert_allclose(r.joint_limits[2], [-np.pi, np.pi])
    assert 0.9 < r.reach < 1.0
    meshes = [s for s in r.solids if isinstance(s.geometry, ir.Mesh)]
    assert len(meshes) >= 7 and all(os.path.isfile(s.geometry.path) for s in meshes)
    assert {s.joint_id for s in r.solids} == set(range(7))


def test_urdf_numeric_ik_is_verified_and_deterministic():
    """Numeric IK on the URDF arm reproduces the pose to 1e-9 and repeats exactly."""
    r = load_robot(ur5_urdf())
    q = np.array([0.3, -1.2, 1.4, -0.9, 1.1, 0.4])
    target = r.fk(q)
    a, b = r.ik(target), r.ik(target)
    assert a.status is IkStatus.OK
    np.testing.assert_array_equal(a.solutions[0], b.solutions[0])
    got = r.fk(a.solutions[0])
    assert np.abs(got[:3, 3] - target[:3, 3]).max() < 1e-9
    assert np.abs(got[:3, :3] - target[:3, :3]).max() < 1e-9


def test_bad_urdf_inputs_raise_robot_error(tmp_path):
    """Missing files, non-URDF text and arms without limits raise RobotError, nothing else."""
    with pytest.raises(RobotError, match="does not exist"):
        load_robot(str(tmp_path / "missing.urdf"))
    junk = tmp_path / "junk.urdf"
    junk.write_text("this is not xml")
    with pytest.raises(RobotError, match="cannot load URDF"):
        load_robot(str(junk))
    wheel = tmp_path / "wheel.urdf"
    wheel.write_text(
        '<robot name="w"><link name="a"/><link name="b"/>'
        '<joint name="j" type="continuous"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/></joint></robot>'
    )
    with pytest.raises(RobotError, match="not a usable serial arm"):
        load_robot(str(wheel))


def test_urdf_meshes_resolve_relative_to_the_file_and_primitives_convert(tmp_path):
    """A relative mesh path resolves against the URDF's folder; box/cylinder/sphere become ir shapes."""
    stl = os.path.join(os.path.dirname(ur5_urdf()), "..", "meshes", "ur5", "collision", "base.stl")
    (tmp_path / "meshes").mkdir()
    (tmp_path / "meshes" / "part.stl").write_bytes(open(stl, "rb").read())
    (tmp_path / "arm.urdf").write_text(
        '<robot name="arm">'
        '<link name="base"><collision><geometry><mesh filename="meshes/part.stl" scale="0.001 0.001 0.001"/></geometry></collision></link>'
        '<link name="l1"><collision><origin xyz="0 0 0.1"/><geometry><box size="0.1 0.2 0.3"/></geometry></collision></link>'
        '<link name="l2"><collision><geometry><cylinder radius="0.05" length="0.4"/></geometry></collision>'
        '<collision><geometry><sphere radius="0.07"/></geometry></collision></link>'
        '<link name="tool0"/>'
        '<joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><origin xyz="0 0 0.2"/>'
        '<axis xyz="0 0 1"/><limit lower="-3" upper="3" velocity="2" effort="1"/></joint>'
        '<joint name="j2" type="prismatic"><parent link="l1"/><child link="l2"/><origin xyz="0.3 0 0"/>'
        '<axis xyz="1 0 0"/><limit lower="0" upper="0.5" velocity="0.5" effort="1"/></joint>'
        '<joint name="f" type="fixed"><parent link="l2"/><child link="tool0"/><origin xyz="0 0 0.05"/></joint>'
        "</robot>"
    )
    r = load_robot(str(tmp_path / "arm.urdf"))
    assert r.dof == 2 and r.joint_types == ("R", "P")
    np.testing.assert_allclose(r.fk(np.array([np.pi / 2, 0.2]))[:3, 3], [0.0, 0.5, 0.25], atol=1e-12)
    kinds = {type(s.geometry).__name__: s for s in r.solids}
    assert kinds["Mesh"].geometry.path == str(tmp_path / "meshes" / "part.stl") and kinds["Mesh"].geometry.scale == 0.001
    assert kinds["Box"].geometry.size == (0.1, 0.2, 0.3) and kinds["Box"].placement.position == (0.0, 0.0, 0.1)
    assert kinds["Cylinder"].geometry == ir.Cylinder(0.05, 0.4) and kinds["Sphere"].geometry == ir.Sphere(0.07)
    np.testing.assert_allclose(r.velocity_limits, [2.0, 0.5])
