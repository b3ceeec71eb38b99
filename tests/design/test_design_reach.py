"""Reach maps agree with kinematics computed here, independently of rmot's robot code.

Witnesses: the UR5e DH table as Universal Robots publishes it ("DH parameters for calculations
of kinematics and dynamics", universal-robots.com support article, UR5e row), multiplied out
below with the textbook standard-DH link transform; and pinocchio's own URDF parser for the
URDF arm. Points beyond the sum of the DH link lengths cannot be reached by any arm.
"""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from rmot.compiler.cli import cli
from rmot.sim.robots import load_robot
from rmot.compiler.design.reach import reach_map, sampled_map, slice_grid
from rmot.compiler.design.reach_draw import section
from rmot.compiler.design.study import rotation_rpy

ROOT = Path(__file__).resolve().parents[2]

# UR5e: d (m), a (m), alpha (rad), per joint (Universal Robots' published DH table).
UR5E_D = (0.1625, 0.0, 0.0, 0.1333, 0.0997, 0.0996)
UR5E_A = (0.0, -0.425, -0.3922, 0.0, 0.0, 0.0)
UR5E_ALPHA = (math.pi / 2, 0.0, 0.0, math.pi / 2, -math.pi / 2, 0.0)


def dh_fk(q: np.ndarray) -> np.ndarray:
    """Standard DH: T = Π Rz(θ) Tz(d) Tx(a) Rx(α)."""
    t = np.eye(4)
    for th, d, a, al in zip(q, UR5E_D, UR5E_A, UR5E_ALPHA):
        ct, st, ca, sa = math.cos(th), math.sin(th), math.cos(al), math.sin(al)
        t = t @ np.array([[ct, -st * ca, st * sa, a * ct], [st, ct * ca, -ct * sa, a * st], [0, sa, ca, d], [0, 0, 0, 1]])
    return t


DOWN = rotation_rpy(math.pi, 0.0, 0.0)


@pytest.fixture(scope="module")
def ur5e_top() -> object:
    robot = load_robot("ur5e")
    return reach_map(robot, slice_grid(np.eye(4), 1.2, 0.08, "xy", 0.1), orientation=DOWN)


class TestFixedOrientation:
    def test_every_reached_point_is_reproduced_by_dh_forward_kinematics(self, ur5e_top) -> None:
        """The joint solution kept for each reached point puts the flange there, pointing down (UR's DH table)."""
        m = ur5e_top
        assert m.reached.sum() > 50
        for p, q in zip(m.points[m.reached], m.q[m.reached]):
            t = dh_fk(q)
            assert np.allclose(t[:3, 3], p, atol=1e-7)
            assert np.allclose(t[:3, :3], DOWN, atol=1e-7)

    def test_points_beyond_the_link_lengths_are_never_reached(self, ur5e_top) -> None:
        """No point farther from the base than Σ|a| + Σ|d| is marked reached, and the grid has such points."""
        bound = sum(abs(v) for v in UR5E_A) + sum(abs(v) for v in UR5E_D)
        far = np.linalg.norm(ur5e_top.points, axis=1) > bound
        assert far.sum() > 20
        assert not ur5e_top.reached[far].any()

    def test_points_reached_by_forward_kinematics_are_found(self) -> None:
        """A pose made by DH forward kinematics of random joints is reported reachable at that point and orientation."""
        robot = load_robot("ur5e")
        rng = np.random.default_rng(7)
        for _ in range(6):
            q = rng.uniform(-math.pi, math.pi, 6)
            t = dh_fk(q)
            m = reach_map(robot, t[:3, 3][None], orientation=t[:3, :3])
            assert bool(m.reached[0])
            assert np.allclose(dh_fk(m.q[0]), t, atol=1e-7)

    def test_quality_is_yoshikawas_measure_of_the_kept_solution(self, ur5e_top) -> None:
        """Quality lies in [0, 1] with 1 on the map; the raw value is |det J| of a finite-difference DH Jacobian
        (angular rows times the reach), and no other IK branch of that pose scores higher."""
        q = ur5e_top.quality[ur5e_top.reached]
        assert q.min() >= 0 and math.isclose(q.max(), 1.0)
        robot = load_robot("ur5e")
        t = dh_fk(np.array([0.3, -1.2, 1.4, -0.5, 0.0, 0.2]))  # J5 = 0 on this branch: wrist singular
        m = reach_map(robot, t[:3, 3][None], orientation=t[:3, :3])
        det = abs(np.linalg.det(fd_jacobian(m.q[0], robot.reach)))
        assert math.isclose(m.manipulability_max, det, rel_tol=1e-4)
        assert abs(np.linalg.det(fd_jacobian(np.array([0.3, -1.2, 1.4, -0.5, 0.0, 0.2]), robot.reach))) < 1e-9
        assert m.manipulability_max > 1e-3  # another branch of the same pose is far from singular


def fd_jacobian(q: np.ndarray, reach: float, h: float = 1e-6) -> np.ndarray:
    """Central differences of dh_fk: linear rows d p / d q, angular rows from dR Rᵀ (times reach)."""
    jac = np.zeros((6, 6))
    r0 = dh_fk(q)[:3, :3]
    for k in range(6):
        dq = np.zeros(6)
        dq[k] = h
        tp, tm = dh_fk(q + dq), dh_fk(q - dq)
        jac[:3, k] = (tp[:3, 3] - tm[:3, 3]) / (2 * h)
        w = (tp[:3, :3] - tm[:3, :3]) / (2 * h) @ r0.T
        jac[3:, k] = np.array([w[2, 1], w[0, 2], w[1, 0]]) * reach
    return jac


class TestAnyOrientation:
    def test_sampled_cells_hold_their_sample_by_urdf_forward_kinematics(self) -> None:
        """Every reached cell of an any-orientation map holds the flange of its q, by pinocchio's own URDF model."""
        pin = pytest.importorskip("pinocchio")
        path = str(ROOT / "examples" / "urdf_cell" / "arm6.urdf")
        model = pin.buildModelFromUrdf(path)
        data = model.createData()
        frame = model.getFrameId("tool0")
        robot = load_robot(path)
        step = 0.1
        m = sampled_map(robot, slice_grid(np.eye(4), 1.2, step, "xz", 0.0), step, samples=40_000)
        assert m.reached.sum() > 30
        for p, q in zip(m.points[m.reached], m.q[m.reached]):
            pin.framesForwardKinematics(model, data, q)
            assert np.all(np.abs(data.oMf[frame].translation - p) <= step / 2 + 1e-9)


def test_section_of_a_box_is_its_outline() -> None:
    """A plane through a tessellated 1 x 2 x 3 m box cuts it along a 1 x 2 rectangle (perimeter 6 m)."""
    from rmot.lang import ir
    from rmot.sim.render.tessellate import tessellate

    tri = tessellate(ir.Box((1.0, 2.0, 3.0))).vertices
    segs = section(tri, 2, 0.3)
    assert math.isclose(float(np.linalg.norm(segs[:, 1] - segs[:, 0], axis=1).sum()), 6.0, rel_tol=1e-9)
    assert np.allclose(np.abs(segs[:, :, :2]).max(axis=(0, 1)), [0.5, 1.0])


class TestCommand:
    def test_svg_draws_one_cell_per_reached_point(self, tmp_path: Path) -> None:
        """The SVG's coloured cells are the reached points of both slices plus the 64-step colour bar."""
        out = tmp_path / "ur5e.svg"
        args = ["reach", "--robot", "ur5e", "--orientation", "rx=180deg", "--step", "100mm", "-o", str(out)]
        result = CliRunner().invoke(cli, args)
        assert result.exit_code == 0, result.output
        rects = ET.parse(out).getroot().findall("{http://www.w3.org/2000/svg}rect")
        robot = load_robot("ur5e")
        from rmot.compiler.design.reach import reach_bound

        bound = reach_bound(robot)
        n = sum(int(reach_map(robot, slice_grid(np.eye(4), bound, 0.1, plane, 0.0), orientation=DOWN).reached.sum())
                for plane in ("xy", "xz"))
        assert len(rects) == 1 + n + 64
        again = tmp_path / "again.svg"
        CliRunner().invoke(cli, args[:-1] + [str(again)])
        assert again.read_bytes() == out.read_bytes()

    def test_html_embeds_the_reached_points(self, tmp_path: Path) -> None:
        """The interactive page carries every reached point of the 3-D grid (decoded from its JSON block)."""
        import base64
        import json

        out = tmp_path / "cell.html"
        result = CliRunner().invoke(cli, ["reach", str(ROOT / "compiler" / "default_cell.rmot"), "--tool", "gripper",
                                          "--orientation", "rx=180deg", "--step", "200mm", "-o", str(out)])
        assert result.exit_code == 0, result.output
        text = out.read_text(encoding="utf-8")
        data = json.loads(re.search(r'id="rmot-data">(.*?)</script>', text, re.S).group(1))
        pts = np.frombuffer(base64.b64decode(data["points"]), dtype="<f4").reshape(-1, 3)
        assert len(pts) > 20 and len(data["fixtures"]) == 6
        assert np.allclose(data["base"], [0.0, 0.0, 0.4])

    @pytest.mark.parametrize(("args", "message"), [
        (["--robot", "no_such_arm", "-o", "x.png"], "no_such_arm"),
        (["--robot", "ur5e", "--orientation", "rx=180", "-o", "x.png"], "rx must be a number with a unit"),
        (["--robot", "ur5e", "--tool", "gripper", "-o", "x.png"], "--tool needs a cell"),
    ])
    def test_bad_input_is_a_usage_error(self, tmp_path: Path, args: list[str], message: str) -> None:
        """Bad options exit 2 with a message, never a traceback."""
        args = [a if a != "x.png" else str(tmp_path / a) for a in args]
        result = CliRunner().invoke(cli, ["reach", *args])
        assert result.exit_code == 2
        assert message in result.output
        assert "Traceback" not in result.output
