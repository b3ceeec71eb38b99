"""VAL3 backend: application layout, instruction table, data round trip through FK, determinism."""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
from backend_fixtures import FRONT_UP_NOFLIP, diagnostic_keys, motion, span_at
from backend_fixtures import blocks as shared_blocks
from plans_b import (HOME_Q, PICK_POSE, TABLE, cart, demo_plan, fk_plan, make_plan,
                     move, record, sample_joints)

from rmot.backends.val3 import Val3Backend
from rmot.lang import ir, ir_tree

GOLDEN = Path(__file__).parent / "golden" / "val3"
NS = {"d": "http://www.staubli.com/robotics/VAL3/Data/2", "p": "http://www.staubli.com/robotics/VAL3/Program/2"}
J, L, C = ir.MotionKind.JOINT, ir.MotionKind.LINEAR, ir.MotionKind.CIRCULAR


def emit(plan: object) -> tuple[dict[str, str], list[str]]:
    result = Val3Backend().emit(plan)  # type: ignore[arg-type]
    return result.files, diagnostic_keys(result.diagnostics)


def code(pgx: str) -> str:
    """The VAL3 source inside a .pgx file (parsed as XML)."""
    root = ET.fromstring(pgx)
    return root.find("p:Program/p:Code", NS).text  # type: ignore[union-attr,return-value]


def data(dtx: str) -> dict[str, list[dict[str, str]]]:
    """Data name -> the attribute dicts of its values, in key order."""
    root = ET.fromstring(dtx)
    return {d.get("name"): [v.attrib for v in d.findall("d:Value", NS)]  # type: ignore[misc]
            for d in root.findall("d:Datas/d:Data", NS)}


def blocks(text: str) -> dict[int, list[str]]:
    """Source line -> the stripped code lines printed under its `// demo.rmot:N` comment."""
    return shared_blocks(text, "// ", drop=("end",))


TABLE_ROWS = [
    (3, ["movej(jTarget[0], t_gripper, mSpeed[0])"]),
    (4, ["movel(pTarget[0], t_gripper, mSpeed[1])"]),
    (5, ["movel(pTarget[1], t_gripper, mSpeed[2])", "waitEndMove()"]),
    (6, ["dOut[1] = true"]),
    (7, ["delay(0.3000)"]),
    (8, ["dOut[3] = true", "delay(0.2000)", "dOut[3] = false"]),
    (9, ["bOk = watch(dIn[2] == true, 5.0000)", "if !bOk",
         'popUpMsg("wait for dIn[2] == true timed out after 5.000 s")',
         'logMsg("wait for dIn[2] == true timed out after 5.000 s")',
         "stopMove()", "resetMotion()", "return", "endIf"]),
    (10, ["if dIn[2] == true"]),
    (11, ["movej(jTarget[0], t_gripper, mSpeed[3])", "else"]),
    (13, ["wait(dIn[2] == false)", "endIf"]),
    (14, ["call pick()"]),
    (15, ["movel(pTarget[0], t_gripper, mSpeed[2])", "waitEndMove()"]),
    (16, ["dOut[1] = false"]),
    (17, ["movec(pTarget[2], pTarget[0], t_gripper, mSpeed[2])"]),
    (20, ['putln("cycle done")', "waitEndMove()"]),
]


class TestTable:
    @pytest.mark.parametrize(("line", "expected"), TABLE_ROWS, ids=[f"line{r[0]}" for r in TABLE_ROWS])
    def test_instruction_text(self, line: int, expected: list[str]) -> None:
        """Each IR instruction prints as the VAL3 the reference manual prescribes."""
        files, _ = emit(demo_plan("staubli_tx2_60"))
        found = {**blocks(code(files["demo/start.pgx"])), **blocks(code(files["demo/pick.pgx"]))}
        assert found[line] == expected

    def test_application_layout(self) -> None:
        """An SRS application folder: project, data, start, stop and one program per proc call."""
        files, _ = emit(demo_plan("staubli_tx2_60"))
        assert sorted(files) == ["demo/demo.dtx", "demo/demo.pjx", "demo/pick.pgx", "demo/start.pgx", "demo/stop.pgx"]
        project = ET.fromstring(files["demo/demo.pjx"])
        ns = {"j": "http://www.staubli.com/robotics/VAL3/Project/3"}
        assert [p.get("file") for p in project.findall("j:Programs/j:Program", ns)] == ["pick.pgx", "start.pgx", "stop.pgx"]
        assert project.find("j:Database/j:Data", ns).get("file") == "demo.dtx"  # type: ignore[union-attr]

    def test_data_values(self) -> None:
        """mdesc, tool, frame, dio and point data carry the documented fields and units."""
        files, _ = emit(demo_plan("staubli_tx2_60"))
        d = data(files["demo/demo.dtx"])
        assert d["mSpeed"][0] == {"key": "0", "accel": "100.000", "vel": "50.000", "decel": "100.000", "tmax": "9999",
                                  "rmax": "9999", "blend": "off", "leave": "0.000", "reach": "0.000"}
        assert d["mSpeed"][1]["tmax"] == "500.000" and d["mSpeed"][1]["blend"] == "Cartesian"
        assert d["mSpeed"][1]["leave"] == d["mSpeed"][1]["reach"] == "25.000"
        assert d["t_gripper"][0]["fatherId"] == "flange[0]"
        assert d["f_table"][0]["fatherId"] == "world[0]"
        assert d["pTarget"][1]["fatherId"] == "f_table[0]"
        assert d["dOut"][3] == {"key": "3", "link": "BasicIO-1\\%Q3"}
        assert d["jTarget"][0] == {"key": "0", "j1": "0.0000", "j2": "-30.0000", "j3": "30.0000",
                                   "j4": "0.0000", "j5": "60.0000", "j6": "0.0000"}

    def test_warnings(self) -> None:
        """Blocking pulse (W451), other vendors' native blocks (W407); default accel: no W408."""
        _, diags = emit(demo_plan("staubli_tx2_60"))
        assert diags == ["warning:W451:8", "warning:W407:18", "warning:W407:19"]

    def test_matches_golden_files(self) -> None:
        """The demo application equals the hand-reviewed golden files."""
        files, _ = emit(demo_plan("staubli_tx2_60"))
        for name, text in files.items():
            assert text == (GOLDEN / name.replace("/", "__")).read_text(encoding="utf-8"), name


class TestRefusedAndWarned:
    def _plan(self, body: tuple[ir.Instr, ...]) -> object:
        recs = [record(n, 0.0, np.asarray(HOME_Q), FRONT_UP_NOFLIP, PICK_POSE, n.motion.zone.radius)
                for n in ir_tree.walk(body) if isinstance(n, ir.Move)]
        return make_plan(body, recs, "staubli_tx2_60")

    def test_single_task_sync_is_noop_and_analog_warned(self) -> None:
        """A single task's sync is a no-op comment; an analog output is aioSet on an unlinked aOut (W455)."""
        body = (ir.SetAnalog(uid=1, port=1, value=2.5, span=span_at(4)), ir.Sync(uid=2, name="m", span=span_at(5)))
        files, diags = emit(self._plan(body))
        assert diags == ["warning:W455:4"]
        assert "// sync m: no-op (single task)" in code(files["demo/start.pgx"])
        assert blocks(code(files["demo/start.pgx"]))[4] == ["aioSet(aOut[1], 2.5000)"]
        assert data(files["demo/demo.dtx"])["aOut"] == [{"key": "0", "link": ""}, {"key": "1", "link": ""}]

    def test_blend_before_io_warns(self) -> None:
        """A blended move (here the last of a proc) followed by I/O must stop for waitEndMove(): W453."""
        call = ir.ProcCall(uid=3, proc="p", args=(), body=(move(1, L, cart(PICK_POSE), 4, motion(zone=0.01)),), span=span_at(3))
        body = (call, ir.SetDigital(uid=2, port=1, value=True, span=span_at(5)),
                ir.WaitTime(uid=4, duration=1.0, span=span_at(6)))
        files, diags = emit(self._plan(body))
        assert "warning:W453:5" in diags
        assert blocks(code(files["demo/start.pgx"]))[3] == ["call p()", "waitEndMove()"]
        assert blocks(code(files["demo/start.pgx"]))[5] == ["dOut[1] = true"]

    def test_long_names_are_cut_with_a_warning(self) -> None:
        """VAL3 names hold 15 characters: a longer program name is cut and reported (W400)."""
        plan = make_plan((ir.WaitTime(uid=1, duration=1.0, span=span_at(3)),), [], "staubli_tx2_60",
                         name="a_really_long_program_name")
        files, diags = emit(plan)
        assert sorted(files)[0].startswith("a_really_long_p/")
        assert diags == ["warning:W400:1"]


def _trsf(v: dict[str, str]) -> np.ndarray:
    """VAL3 trsf: x, y, z mm; R = Rx(rx)·Ry(ry)·Rz(rz) in degrees, written out by hand."""
    a, b, c = (math.radians(float(v[k])) for k in ("rx", "ry", "rz"))
    rot_x = np.array([[1, 0, 0], [0, math.cos(a), -math.sin(a)], [0, math.sin(a), math.cos(a)]])
    rot_y = np.array([[math.cos(b), 0, math.sin(b)], [0, 1, 0], [-math.sin(b), 0, math.cos(b)]])
    rot_z = np.array([[math.cos(c), -math.sin(c), 0], [math.sin(c), math.cos(c), 0], [0, 0, 1]])
    m = np.eye(4)
    m[:3, :3] = rot_x @ rot_y @ rot_z
    m[:3, 3] = [float(v[k]) / 1000.0 for k in ("x", "y", "z")]
    return m


def _decode(v: dict[str, str]) -> ir.Config:
    return ir.Config(ir.Shoulder.FRONT if v["shoulder"] == "lefty" else ir.Shoulder.BACK,
                     ir.Elbow.UP if v["elbow"] == "epositive" else ir.Elbow.DOWN,
                     ir.Wrist.NOFLIP if v["wrist"] == "wpositive" else ir.Wrist.FLIP)


class TestRoundTrip:
    @pytest.mark.parametrize("frame", [None, TABLE], ids=["world", "table"])
    def test_points_joints_and_config(self, frame: ir.FrameRef | None) -> None:
        """Points read back (frame · point · tool⁻¹) equal FK of the planned joints; config decodes to the branch."""
        from rmot.sim.robots import load_robot

        robot = load_robot("staubli_tx2_60")
        qs = sample_joints("staubli_tx2_60", 9)
        plan = fk_plan("staubli_tx2_60", qs, **({"frame": frame} if frame else {}))
        files, diags = emit(plan)
        assert not [d for d in diags if d.startswith("error")]
        d = data(files["demo/demo.dtx"])
        src = code(files["demo/start.pgx"])
        tool_inv = np.linalg.inv(_trsf(d["t_gripper"][0]))
        calls = re.findall(r"(movej|movel|movec)\((.*?), t_gripper", src)
        assert len(calls) == len(qs)
        for k, (kind, args) in enumerate(calls):
            rec = plan.tasks[0].records[k]
            idx = [int(i) for i in re.findall(r"\[(\d+)\]", args)]
            if kind == "movej":
                got = [float(d["jTarget"][idx[0]][f"j{j + 1}"]) for j in range(6)]
                np.testing.assert_allclose(got, np.degrees(qs[k]), atol=1e-4)
                continue
            targets = list(zip(idx, [rec.q_via, rec.q_target] if kind == "movec" else [rec.q_target]))
            for i, q in targets:
                point = d["pTarget"][i]
                father = np.eye(4) if point["fatherId"] == "world[0]" else _trsf(d[point["fatherId"][:-3]][0])
                flange = father @ _trsf(point) @ tool_inv
                want = robot.fk(q)
                np.testing.assert_allclose(flange[:3, 3] * 1000, want[:3, 3] * 1000, atol=0.01)
                cos = (np.trace(flange[:3, :3].T @ want[:3, :3]) - 1) / 2
                assert math.degrees(math.acos(min(1.0, cos))) < 0.001
                if q is rec.q_target:
                    assert _decode(point) == robot.branch(q)

    def test_config_agrees_with_staubli_joint_signs(self) -> None:
        """Stäubli defines epositive/wpositive by the signs of J3/J5: the emitted config agrees."""
        from rmot.sim.robots import load_robot

        robot = load_robot("staubli_tx2_60")
        qs = [q for q in sample_joints("staubli_tx2_60", 40, seed=3) if abs(q[2]) > 0.1]
        for q in qs:
            branch = robot.branch(q)
            assert (branch.elbow is ir.Elbow.UP) == (q[2] > 0), np.degrees(q)
            assert (branch.wrist is ir.Wrist.NOFLIP) == (q[4] > 0), np.degrees(q)


class TestDeterminism:
    def test_two_runs_are_byte_identical(self) -> None:
        """Same plan, same bytes in every file of the application."""
        a, _ = emit(demo_plan("staubli_tx2_60"))
        b, _ = emit(demo_plan("staubli_tx2_60"))
        assert a == b
        assert '"-0.000"' not in "".join(a.values()) and '"-0.0000"' not in "".join(a.values())
