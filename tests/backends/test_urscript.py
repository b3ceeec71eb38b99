"""URScript backend: instruction table, refusals, numeric round trip through FK, determinism."""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest
from backend_fixtures import FRONT_UP_NOFLIP, diagnostic_keys, motion, span_at
from backend_fixtures import blocks as shared_blocks
from plans_b import (GRIPPER_TCP, HOME_Q, PICK_POSE, cart, demo_plan, fk_plan, make_plan, move,
                     record, sample_joints)
from scipy.spatial.transform import Rotation

from rmot.backends import BACKENDS
from rmot.backends.urscript import UrScriptBackend
from rmot.lang import ir, ir_tree

GOLDEN = Path(__file__).parent / "golden" / "urscript"
J, L, C = ir.MotionKind.JOINT, ir.MotionKind.LINEAR, ir.MotionKind.CIRCULAR


def blocks(text: str) -> dict[int, list[str]]:
    """Source line -> the stripped lines printed under its `# demo.rmot:N` comment (no set_tcp,
    set_payload: they belong to the next move)."""
    return shared_blocks(text, "# ", skip=("set_tcp", "set_payload"))


def emit(plan: object) -> tuple[str, list[str]]:
    result = UrScriptBackend().emit(plan)  # type: ignore[arg-type]
    (text,) = result.files.values()
    return text, diagnostic_keys(result.diagnostics)


# rows: source line of demo_body() -> the URScript printed for it
TABLE = [
    (3, ["movej([0.000000, -0.523599, 0.523599, 0.000000, 1.047198, 0.000000], a=13.962634, v=1.570796, r=0.000000)"]),
    (4, ["movel(p[0.450000, 0.100000, 0.300000, 3.141593, 0.000000, 0.000000], a=2.000000, v=0.500000, r=0.025000)"]),
    (5, ["movel(p[0.400000, -0.150000, 0.250000, 2.902453, 1.202235, 0.000000], a=2.000000, v=0.100000, r=0.000000)"]),
    (6, ["set_standard_digital_out(1, True)"]),
    (7, ["sleep(0.3000)"]),
    (8, ["rmot_thread = run rmot_pulse_3_200ms()"]),
    (9, ["rmot_waited = 0.0", "while not (get_standard_digital_in(2) == True) and rmot_waited < 5.0000:",
         "sync()", "rmot_waited = rmot_waited + get_steptime()", "end",
         "if not (get_standard_digital_in(2) == True):",
         'popup("wait for input 2 == True timed out after 5.000 s; program stopped", title="rmot", '
         'error=True, blocking=True)', "halt", "end"]),
    (10, ["if get_standard_digital_in(2) == True:"]),
    (13, ["while not (get_standard_digital_in(2) == False):", "sync()", "end", "end"]),
    (14, ["pick()"]),
    (15, ["movel(p[0.450000, 0.100000, 0.300000, 3.141593, 0.000000, 0.000000], a=2.000000, v=0.100000, r=0.000000)"]),
    (16, ["set_standard_digital_out(1, False)", "end"]),
    (17, ["movec(p[0.400000, -0.150000, 0.250000, 2.902453, 1.202235, 0.000000], "
          "p[0.450000, 0.100000, 0.300000, 3.141593, 0.000000, 0.000000], a=2.000000, v=0.100000, r=0.000000, mode=0)"]),
    (18, ['textmsg("cycle done")']),
]


class TestTable:
    @pytest.mark.parametrize(("line", "expected"), TABLE, ids=[f"line{r[0]}" for r in TABLE])
    def test_instruction_text(self, line: int, expected: list[str]) -> None:
        """Each IR instruction prints as the URScript the vendor manual prescribes."""
        text, _ = emit(demo_plan())
        assert blocks(text)[line] == expected

    def test_pulse_thread_and_tool(self) -> None:
        """A pulse is a thread (set, sleep, reset) defined before use; set_tcp carries the tool."""
        text, _ = emit(demo_plan())
        assert ("  thread rmot_pulse_3_200ms():\n    set_standard_digital_out(3, True)\n"
                "    sleep(0.2000)\n    set_standard_digital_out(3, False)\n  end\n") in text
        assert text.index("def pick():") < text.index("  pick()")
        assert "set_tcp(p[0.010000, -0.020000, 0.150000, " in text

    def test_other_vendors_native_blocks_warn(self) -> None:
        """Native blocks of other vendors are skipped with a warning at their span, never silently."""
        _, diags = emit(demo_plan())
        assert diags == ["warning:W407:19", "warning:W407:20"]

    def test_matches_golden_file(self) -> None:
        """The demo program's URScript equals the hand-reviewed golden file."""
        text, _ = emit(demo_plan())
        assert text == (GOLDEN / "demo.script").read_text(encoding="utf-8")


class TestRefusalsAndWarnings:
    def _plan(self, body: tuple[ir.Instr, ...], robot: str = "ur5e") -> object:
        recs = [record(n, 0.0, np.asarray(HOME_Q), FRONT_UP_NOFLIP, PICK_POSE)
                for n in ir_tree.walk(body) if isinstance(n, ir.Move)]
        return make_plan(body, recs, robot)

    def test_single_task_sync_is_a_noop(self) -> None:
        """A single task's sync is a no-op comment (two tasks get the I/O handshake: test_handshake.py)."""
        text, diags = emit(self._plan((ir.Sync(uid=1, name="meet", span=span_at(4)),)))
        assert diags == []
        assert "  # sync meet: no-op (single task)" in text.splitlines()

    def test_port_out_of_range_is_refused(self) -> None:
        """Digital ports beyond the standard and configurable banks are an error."""
        _, diags = emit(self._plan((ir.SetDigital(uid=1, port=16, value=True, span=span_at(5)),)))
        assert diags == ["error:E404:5"]

    def test_configurable_outputs(self) -> None:
        """Ports 8..15 map to the configurable outputs 0..7."""
        text, _ = emit(self._plan((ir.SetDigital(uid=1, port=9, value=False, span=span_at(5)),)))
        assert blocks(text)[5] == ["set_configurable_digital_out(1, False)", "end", "demo()"]

    def test_analog_out_of_range_is_refused(self) -> None:
        """UR analog outputs take 0..10 V on ports 0..1: 12 V is an error (E450)."""
        _, diags = emit(self._plan((ir.SetAnalog(uid=1, port=0, value=12.0, span=span_at(6)),)))
        assert diags == ["error:E450:6"]

    def test_analog_volts(self) -> None:
        """Analog out in volts becomes the voltage domain and a 0..1 fraction of 10 V."""
        text, _ = emit(self._plan((ir.SetAnalog(uid=1, port=1, value=4.5, span=span_at(6)),)))
        assert blocks(text)[6] == ["set_analog_outputdomain(1, 1)", "set_standard_analog_out(1, 0.450000)", "end", "demo()"]

    def test_fixed_duration_is_exact_for_movel_and_warned_for_movec(self) -> None:
        """`time` maps to t= on movel; movec has no t= so it warns (W409)."""
        m = motion(duration=2.5)
        body = (move(1, L, cart(PICK_POSE), 3, m), move(2, C, cart(PICK_POSE), 4, m, via=cart(PICK_POSE)))
        text, diags = emit(self._plan(body))
        assert blocks(text)[3][0].endswith("a=2.000000, v=0.250000, t=2.5000, r=0.000000)")
        assert diags == ["warning:W409:4"]

    def test_unknown_model_uses_default_speed_with_warning(self) -> None:
        """A robot outside the UR speed table gets the default maximum and a warning."""
        body = (move(1, J, ir.JointTarget(HOME_Q), 3),)
        text, diags = emit(self._plan(body, robot="puma560"))  # no UR model, no controller brand
        assert diags == ["warning:W452:3"]
        assert "v=3.141593" in blocks(text)[3][0]

    def test_missing_record_is_an_error(self) -> None:
        """A move without a planned joint solution is refused, never printed from the IR."""
        body = (move(1, L, cart(PICK_POSE), 3),)
        _, diags = emit(make_plan(body, [], "ur5e"))
        assert diags == ["error:E401:3"]

    @pytest.mark.parametrize("dof", [7, 2])
    def test_not_six_joints_is_an_error(self, dof: int) -> None:
        """movej's q is the six joint positions of a UR arm (URScript manual, movej): a 7-joint
        model or a 2-axis mechanism has no URScript form (E403), as in RAPID and KRL."""
        from backend_fixtures import cart as cart_in, deg, hand_plan, move as move_in

        plan = hand_plan((move_in(1, ir.MotionKind.JOINT, cart_in(ir.Pose())),), {1: (deg(*[0.0] * dof), None)},
                         robot="ur5e", dof=dof)
        result = UrScriptBackend().emit(plan)
        assert [d.code.id for d in result.diagnostics if d.is_error] == ["E403"]
        assert "movej" not in "\n".join(result.files.values())


def _rotvec_pose(values: list[float]) -> np.ndarray:
    """UR's p[x, y, z, rx, ry, rz] as a matrix, converted independently with scipy."""
    m = np.eye(4)
    m[:3, :3] = Rotation.from_rotvec(values[3:]).as_matrix()
    m[:3, 3] = values[:3]
    return m


def _numbers(text: str) -> list[float]:
    return [float(v) for v in text.split(",")]


class TestRoundTrip:
    @pytest.mark.parametrize("robot_name", ["ur5e", "ur10e"])
    def test_poses_and_joints_match_fk(self, robot_name: str) -> None:
        """Poses read back (scipy rotation vectors, set_tcp removed) equal FK of the planned joints."""
        from rmot.sim.robots import load_robot

        robot = load_robot(robot_name)
        qs = sample_joints(robot_name, 9)
        plan = fk_plan(robot_name, qs)
        text, diags = emit(plan)
        assert not [d for d in diags if d.startswith("error")]
        tcp = _rotvec_pose(_numbers(re.search(r"set_tcp\(p\[(.*?)\]\)", text).group(1)))  # type: ignore[union-attr]
        moves = re.findall(r"^\s*(movej|movel|movec)\((.*)\)$", text, re.M)
        assert len(moves) == len(qs)
        for k, (kind, args) in enumerate(moves):
            if kind == "movej":
                q = _numbers(re.match(r"\[(.*?)\]", args).group(1))  # type: ignore[union-attr]
                np.testing.assert_allclose(q, qs[k], atol=1e-6)
                continue
            poses = [_rotvec_pose(_numbers(p)) for p in re.findall(r"p\[(.*?)\]", args)]
            flange = poses[-1] @ np.linalg.inv(tcp)
            want = robot.fk(qs[k])
            np.testing.assert_allclose(flange[:3, 3] * 1000, want[:3, 3] * 1000, atol=0.01)
            angle = Rotation.from_matrix(flange[:3, :3].T @ want[:3, :3]).magnitude()
            assert math.degrees(angle) < 0.001

    def test_tool_read_back_equals_the_tool(self) -> None:
        """set_tcp's rotation vector is the tool's orientation (scipy, independent)."""
        text, _ = emit(demo_plan())
        tcp = _rotvec_pose(_numbers(re.search(r"set_tcp\(p\[(.*?)\]\)", text).group(1)))  # type: ignore[union-attr]
        np.testing.assert_allclose(tcp, GRIPPER_TCP.matrix(), atol=2e-6)


class TestDeterminism:
    def test_two_runs_are_byte_identical(self) -> None:
        """The same plan, built twice, prints the same bytes; -0 never appears."""
        a, _ = emit(demo_plan())
        b, _ = emit(demo_plan())
        assert a == b
        assert "-0.000000," not in a and "-0.000000]" not in a

    def test_registered_in_backends(self) -> None:
        """--target urscript resolves to this backend."""
        assert BACKENDS["urscript"] is UrScriptBackend
