"""INFORM (.JBI) backend: instruction table, job layout, size splitting, round trip, determinism."""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest
from backend_fixtures import FRONT_UP_NOFLIP, diagnostic_keys, motion, span_at
from backend_fixtures import blocks as shared_blocks
from plans_b import HOME_Q, PICK_POSE, cart, demo_plan, fk_plan, make_plan, move, record, sample_joints

from rmot.backends.inform import InformBackend
from rmot.lang import ir, ir_tree

GOLDEN = Path(__file__).parent / "golden" / "inform"
J, L, C = ir.MotionKind.JOINT, ir.MotionKind.LINEAR, ir.MotionKind.CIRCULAR


def emit(plan: object) -> tuple[dict[str, str], list[str]]:
    result = InformBackend().emit(plan)  # type: ignore[arg-type]
    return result.files, diagnostic_keys(result.diagnostics)


def blocks(text: str) -> dict[int, list[str]]:
    """Source line -> the instruction lines printed under its `'demo.rmot:N` comment (to END)."""
    return shared_blocks(text, "'", stop="END", strip=False)


def positions(text: str) -> dict[str, tuple[int, str, list[float]]]:
    """C name -> (tool number, RCONF text, [X, Y, Z, Rx, Ry, Rz]) from the //POS section."""
    tool, conf, out = 0, "", {}
    for line in text.split("//INST")[0].splitlines():
        if line.startswith("///TOOL "):
            tool = int(line.split()[1])
        elif line.startswith("///RCONF "):
            conf = line.split()[1]
        elif re.match(r"C\d{5}=", line):
            name, values = line.split("=")
            out[name] = (tool, conf, [float(v) for v in values.split(",")])
    return out


TABLE = [
    (3, ["MOVJ C00000 VJ=50.00 PL=0"]),
    (4, ["MOVL C00001 V=500.0 PL=2"]),
    (5, ["MOVL C00002 V=100.0 PL=0"]),
    (6, ["DOUT OT#(1) ON"]),
    (7, ["TIMER T=0.30"]),
    (8, ["PULSE OT#(3) T=0.20"]),
    (9, ["WAIT IN#(2)=ON T=5.00", "JUMP *L001 IF IN#(2)=ON", 'MSG "IN#(2) TIMEOUT"', "PAUSE", "*L001"]),
    (10, ["JUMP *L002 IF IN#(2)=OFF"]),
    (11, ["MOVJ C00003 VJ=100.00 PL=0", "JUMP *L003", "*L002"]),
    (13, ["WAIT IN#(2)=OFF", "*L003"]),
    (14, ["CALL JOB:DEMO_PICK"]),
    (15, ["MOVL C00000 V=100.0 PL=0"]),
    (16, ["DOUT OT#(1) OFF"]),
    (17, ["MOVC C00004 V=100.0", "MOVC C00005 V=100.0", "MOVC C00006 V=100.0 PL=0 FPT"]),
    (19, ['MSG "CYCLE DONE"']),
]


class TestTable:
    @pytest.mark.parametrize(("line", "expected"), TABLE, ids=[f"line{r[0]}" for r in TABLE])
    def test_instruction_text(self, line: int, expected: list[str]) -> None:
        """Each IR instruction prints as the INFORM the job-format manual prescribes."""
        files, _ = emit(demo_plan("yaskawa_gp8"))
        found = {**blocks(files["DEMO.JBI"]), **blocks(files["DEMO_PICK.JBI"])}
        assert found[line] == expected

    def test_job_layout(self) -> None:
        """Header pseudo-instructions in the documented order; one job per proc call."""
        files, _ = emit(demo_plan("yaskawa_gp8"))
        assert sorted(files) == ["DEMO.JBI", "DEMO_PICK.JBI"]
        head = files["DEMO.JBI"].splitlines()[:8]
        assert head == ["/JOB", "//NAME DEMO", "//POS", "///NPOS 7,0,0,0,0,0", "///TOOL 1",
                        "///POSTYPE ROBOT", "///RECTAN", "///RCONF 0,0,0,0,0,0,0,0"]
        inst = files["DEMO.JBI"].split("//INST\n")[1].splitlines()[:5]
        assert inst == ["///DATE 2000/01/01 00:00", "///COMM demo", "///ATTR SC,RW", "///GROUP1 RB1", "NOP"]
        assert files["DEMO.JBI"].endswith("\nEND\n")
        assert all(len(line) <= 32 for line in files["DEMO.JBI"].splitlines() if line.startswith("'"))

    def test_circular_uses_previous_target_as_start(self) -> None:
        """MOVC's first point is the previous move's target (C00004 repeats line 15's pose)."""
        files, _ = emit(demo_plan("yaskawa_gp8"))
        pos = positions(files["DEMO.JBI"])
        assert pos["C00004"][2] == positions(files["DEMO_PICK.JBI"])["C00000"][2]

    def test_warnings(self) -> None:
        """Joint targets as Cartesian (W450), other vendors' native (W407); default accel: no W408."""
        _, diags = emit(demo_plan("yaskawa_gp8"))
        assert diags == ["warning:W450:3", "warning:W450:11",
                         "warning:W407:18", "warning:W407:20"]

    def test_matches_golden_files(self) -> None:
        """The demo program's jobs equal the hand-reviewed golden files."""
        files, _ = emit(demo_plan("yaskawa_gp8"))
        for name, text in files.items():
            assert text == (GOLDEN / name).read_text(encoding="utf-8"), name


class TestNearestAndRefused:
    def _plan(self, body: tuple[ir.Instr, ...]) -> object:
        recs = [record(n, 0.0, np.asarray(HOME_Q), FRONT_UP_NOFLIP, PICK_POSE, n.motion.zone.radius)
                for n in ir_tree.walk(body) if isinstance(n, ir.Move)]
        return make_plan(body, recs, "yaskawa_gp8")

    @pytest.mark.parametrize(("m", "expected", "code"), [
        (motion(speed=0.10004), "MOVL C00000 V=100.0 PL=0", "W402"),
        (motion(zone=0.030), "MOVL C00000 V=250.0 PL=2", "W403"),
        (motion(zone=0.1), "MOVL C00000 V=250.0 PL=4", None),
        (motion(duration=3.0), "MOVL C00000 V=250.0 PL=0", "W409"),
    ])
    def test_nearest_faithful_value(self, m: ir.Motion, expected: str, code: str | None) -> None:
        """Values INFORM cannot express take the nearest one with a warning at the move."""
        files, diags = emit(self._plan((move(1, L, cart(PICK_POSE), 4, m),)))
        assert blocks(files["DEMO.JBI"])[4] == [expected]
        assert diags == ([f"warning:{code}:4"] if code else [])

    def test_joint_speed_rounded(self) -> None:
        """VJ has 0.01 % steps: 12.3456 % prints VJ=12.35 with W402."""
        files, diags = emit(self._plan((move(1, J, ir.JointTarget(HOME_Q), 4, motion(joint=0.123456)),)))
        assert blocks(files["DEMO.JBI"])[4] == ["MOVJ C00000 VJ=12.35 PL=0"]
        assert "warning:W402:4" in diags

    def test_circular_without_predecessor_is_refused(self) -> None:
        """An arc's start point must be a preceding move's target: otherwise E451."""
        body = (move(1, C, cart(PICK_POSE), 6, via=cart(PICK_POSE)),)
        recs = [record(body[0], 0.0, np.asarray(HOME_Q), FRONT_UP_NOFLIP, PICK_POSE, q_via=np.asarray(HOME_Q))]
        _, diags = emit(make_plan(body, recs, "yaskawa_gp8"))
        assert "error:E451:6" in diags

    def test_continuous_arcs_share_the_fpt_point(self) -> None:
        """An arc after an arc starts at the first one's FPT end point: via and end only."""
        body = (move(1, L, cart(PICK_POSE), 3), move(2, C, cart(PICK_POSE), 4, via=cart(PICK_POSE)),
                move(3, C, cart(PICK_POSE), 5, via=cart(PICK_POSE)))
        recs = [record(n, 0.0, np.asarray(HOME_Q), FRONT_UP_NOFLIP, PICK_POSE, q_via=np.asarray(HOME_Q)) for n in body]
        files, _ = emit(make_plan(body, recs, "yaskawa_gp8"))
        found = blocks(files["DEMO.JBI"])
        assert found[4] == ["MOVC C00001 V=250.0", "MOVC C00002 V=250.0", "MOVC C00003 V=250.0 PL=0 FPT"]
        assert found[5] == ["MOVC C00004 V=250.0", "MOVC C00005 V=250.0 PL=0 FPT"]

    def test_missing_branch_is_refused(self) -> None:
        """Cartesian positions need the full branch (RCONF): none is an error."""
        body = (move(1, L, cart(PICK_POSE), 4),)
        _, diags = emit(make_plan(body, [record(body[0], 0.0, np.asarray(HOME_Q), None, PICK_POSE)], "yaskawa_gp8"))
        assert "error:E402:4" in diags

    def test_single_task_sync_is_noop_and_bad_port_refused(self) -> None:
        """A single task's sync is a no-op comment (handshakes: test_handshake.py); port 0 (OT# starts at 1) is an error."""
        body = (ir.Sync(uid=1, name="meet", span=span_at(4)), ir.SetDigital(uid=2, port=0, value=True, span=span_at(5)))
        files, diags = emit(self._plan(body))
        assert diags == ["error:E404:5"]
        assert "'sync meet: no-op (single task)" in files["DEMO.JBI"].splitlines()

    def test_long_wait_is_several_timers(self) -> None:
        """TIMER holds 655.35 s at most: a 700 s wait is two exact TIMERs."""
        files, diags = emit(self._plan((ir.WaitTime(uid=1, duration=700.0, span=span_at(4)),)))
        assert blocks(files["DEMO.JBI"])[4] == ["TIMER T=655.35", "TIMER T=44.65"]
        assert diags == []


class TestSplitting:
    def test_long_program_is_split_into_called_parts(self) -> None:
        """Above 300 instructions the main job calls parts of at most 300 each (W406)."""
        body = tuple(ir.SetDigital(uid=k + 1, port=1 + k % 8, value=bool(k % 2), span=span_at(3))
                     for k in range(700))
        files, diags = emit(make_plan(body, [], "yaskawa_gp8"))
        assert sorted(files) == ["DEMO.JBI", "DEMO_PART1.JBI", "DEMO_PART2.JBI", "DEMO_PART3.JBI"]
        main = files["DEMO.JBI"].split("NOP\n")[1]
        assert [ln for ln in main.splitlines() if not ln.startswith("'")] == [
            "CALL JOB:DEMO_PART1", "CALL JOB:DEMO_PART2", "CALL JOB:DEMO_PART3", "END"]
        counts = [files[f"DEMO_PART{k}.JBI"].count("DOUT") for k in (1, 2, 3)]
        assert counts == [300, 300, 100]
        assert diags == ["warning:W406:1"]


def _rpy_matrix(x: float, y: float, z: float, rx: float, ry: float, rz: float) -> np.ndarray:
    """Yaskawa X, Y, Z (mm), Rx, Ry, Rz (deg): R = Rz(Rz)·Ry(Ry)·Rx(Rx), written out by hand."""
    a, b, c = (math.radians(v) for v in (rx, ry, rz))
    rot_x = np.array([[1, 0, 0], [0, math.cos(a), -math.sin(a)], [0, math.sin(a), math.cos(a)]])
    rot_y = np.array([[math.cos(b), 0, math.sin(b)], [0, 1, 0], [-math.sin(b), 0, math.cos(b)]])
    rot_z = np.array([[math.cos(c), -math.sin(c), 0], [math.sin(c), math.cos(c), 0], [0, 0, 1]])
    m = np.eye(4)
    m[:3, :3] = rot_z @ rot_y @ rot_x
    m[:3, 3] = np.array([x, y, z]) / 1000.0
    return m


def _decode_rconf(text: str) -> tuple[ir.Shoulder, ir.Elbow, bool, tuple[int, int, int]]:
    """(shoulder, elbow, flip, (R, T, S turn flags)) from `///RCONF l,m,n,o,p,q,...`."""
    bits = [int(b) for b in text.split(",")]
    return (ir.Shoulder.FRONT if bits[2] == 0 else ir.Shoulder.BACK,
            ir.Elbow.UP if bits[1] == 0 else ir.Elbow.DOWN, bits[0] == 0, (bits[3], bits[4], bits[5]))


def _yaskawa_flip(r_deg: float) -> bool:
    """NX100 manual: Flip for -90 < R <= 90, 270 < R <= 360, -360 < R <= -270."""
    return -90 < r_deg <= 90 or 270 < r_deg <= 360 or -360 < r_deg <= -270


class TestRoundTrip:
    @pytest.mark.parametrize("robot_name", ["yaskawa_gp8", "abb_irb120"])
    def test_positions_and_rconf_match_fk_and_branch(self, robot_name: str) -> None:
        """Each position read back (minus the tool) is FK of its planned joints; RCONF decodes to the branch."""
        from rmot.sim.robots import load_robot
        from plans_b import GRIPPER_TCP

        robot = load_robot(robot_name)
        qs = sample_joints(robot_name, 9)
        plan = fk_plan(robot_name, qs)
        files, diags = emit(plan)
        assert not [d for d in diags if d.startswith("error")]
        pos = positions(files["DEMO.JBI"])
        inst = [ln for ln in files["DEMO.JBI"].splitlines() if ln.startswith("MOV")]
        tool_inv = np.linalg.inv(GRIPPER_TCP.matrix())
        # each move's last C is its target; circular moves' middle C is the via
        checks: list[tuple[str, np.ndarray]] = []
        k = 0
        for rec in plan.tasks[0].records:
            names = [ln.split()[1] for ln in inst[k:k + (3 if rec.q_via is not None else 1)]]
            k += len(names)
            checks.append((names[-1], rec.q_target))
            if rec.q_via is not None:
                checks.append((names[1], rec.q_via))
        assert k == len(inst)
        for name, q in checks:
            tool, conf, values = pos[name]
            assert tool == 1
            flange = _rpy_matrix(*values) @ tool_inv
            want = robot.fk(q)
            np.testing.assert_allclose(flange[:3, 3] * 1000, want[:3, 3] * 1000, atol=0.01)
            cos = (np.trace(flange[:3, :3].T @ want[:3, :3]) - 1) / 2
            assert math.degrees(math.acos(min(1.0, cos))) < 0.001
            shoulder, elbow, flip, turns = _decode_rconf(conf)
            branch = robot.branch(q)
            assert (shoulder, elbow) == (branch.shoulder, branch.elbow)
            assert flip == _yaskawa_flip(math.degrees(q[3]))
            assert turns == tuple(int(not -180 < math.degrees(q[i]) <= 180) for i in (3, 5, 0))


class TestJointTargetsAsCartesian:
    def test_rconf_selects_exactly_the_planned_joints(self) -> None:
        """Among every IK solution of a position (all branches and turns), the RCONF matches only the planned joints."""
        from rmot.backends.inform_text import rconf
        from rmot.sim.robots import load_robot

        robot = load_robot("yaskawa_gp8")
        for q in sample_joints("yaskawa_gp8", 12, seed=11):
            want = rconf(robot.branch(q), q)
            result = robot.ik(robot.fk(q))
            matches = [s for s in result.solutions if rconf(robot.branch(s), s) == want]
            assert len(matches) == 1, (np.degrees(q), [np.degrees(m) for m in matches])
            np.testing.assert_allclose(matches[0], q, atol=1e-6)


class TestDeterminism:
    def test_two_runs_are_byte_identical(self) -> None:
        """Same plan, same bytes (fixed ///DATE, fixed formatting, no -0)."""
        a, _ = emit(demo_plan("yaskawa_gp8"))
        b, _ = emit(demo_plan("yaskawa_gp8"))
        assert a == b
        assert not re.search(r"[=,]-0\.0+(,|$)", "\n".join(a.values()), re.M)
