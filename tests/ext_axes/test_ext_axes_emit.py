"""External axes in RAPID and KRL, re-expanded by a witness that is not the backends' code.

Each emitted target is read back from the program text with small regular-expression readers
written from the manuals' data formats (RAPID robtarget / jointtarget / wobjdata literals; KRL
E6POS with A, B, C the rotations about z, y, x), then placed in world through the cell's
mechanisms composed with plain numpy from the cell text's numbers (ext_axes_witness.py, not
rmot.lang.ir_axes): TCP = flange(axis values read from the text) * work object * target.
That must equal the planned TCP (the arm's base on the track at the move's rail value, times
the planned TCP in the base frame) within 0.01 mm. The vendors without external axes refuse the
program with E607 at the first move that drives them. The timing: the move that moves the
track lasts its trapezoid time, and the sampled axis speeds stay within their limits."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from ext_axes_plans import planned
from ext_axes_witness import CELL_HEAD, at, positioner_flange, robot_base, rot

from rmot.backends import BACKENDS
from rmot.lang import ir
from rmot.lang.axis_motion import axis_samples, task_axes
from rmot.compiler.frontend import load_text
from rmot.compiler.plan import plan_program
from rmot.lang.plan_types import Plan

SOURCE = CELL_HEAD + """  frame table = pose(x=1200mm, y=-900mm, z=600mm, rz=30deg) number 3
  tool torch = none tcp pose(z=300mm) mass 1 kg on r1
}
program p on r1 with rail, pos {
  tool torch
  move joint joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg)
  move joint pose(x=80mm, y=30mm, z=50mm, rx=170deg, rz=20deg) frame work ext(rail=1200mm, pos=(20deg, 90deg))
  move linear pose(x=100mm, y=50mm, rx=180deg) frame work speed 100 mm/s
  move axes pos to (-10deg, 180deg)
  move linear pose(x=100mm, y=-50mm, rx=180deg) frame work speed 100 mm/s
  move joint pose(z=100mm, rx=180deg) frame table ext(rail=700mm)
  move joint joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg) ext(rail=0mm, pos=(0deg, 0deg))
}
"""
TOL_M = 1e-5  # 0.01 mm


@pytest.fixture(scope="module")
def plan() -> Plan:
    return planned(SOURCE, "/tmp/ext_axes_emit.rmot")


# ------------------------------------------------------------------ the witness's kinematics


def _quat(q: list[float]) -> np.ndarray:
    w, x, y, z = q
    out = np.eye(4)
    out[:3, :3] = [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                   [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                   [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]
    return out


def planned_tcp_world(plan: Plan, axes_only: bool = False) -> list[np.ndarray]:
    """The planned TCP of each Cartesian move, in world: the base on the track at the move's
    rail value times the planned TCP in the base frame (InstructionRecord.tcp_pose)."""
    tp = plan.tasks[0]
    out = []
    for move in tp.task.body:
        if isinstance(move, ir.Move) and isinstance(move.target, ir.CartesianTarget) and (axes_only or not move.axes_only):
            rec = tp.record(move.uid)
            assert rec is not None and rec.tcp_pose is not None
            out.append(robot_base(dict(move.ext)["rail"] * 1000) @ rec.tcp_pose.matrix())
    return out


# ------------------------------------------------------------------ RAPID

_NUM = r"-?[0-9.E+]+"


def _nums(text: str) -> list[float]:
    return [float(v) for v in re.findall(_NUM, text)]


def rapid_targets(text: str) -> list[np.ndarray]:
    """World TCP of every MoveJ/MoveL robtarget of the module, in program order."""
    data = dict(re.findall(r"CONST robtarget (\w+):=\[(.*)\];", text))
    wobjs = dict(re.findall(r"PERS wobjdata (\w+):=\[(.*)\];", text))
    out = []
    for name, wobj in re.findall(r"Move[JL] (\w+), [^,]+, [^,]+, torch\\WObj:=(\w+);", text):
        trans, rot, _, extax = re.match(r"(\[.*?\]),(\[.*?\]),(\[.*?\]),(\[.*?\])$", data[name]).groups()  # type: ignore[union-attr]
        values = _nums(trans) + _nums(rot)
        target = at(*(v / 1000 for v in values[:3])) @ _quat(values[3:7])
        rail, tilt, turn = _nums(extax)[:3]
        robhold, ufprog, ufmec, rest = re.match(r'(\w+),(\w+),"(\w*)",(.*)', wobjs[wobj]).groups()  # type: ignore[union-attr]
        uf = _nums(rest)[:7]
        uframe = at(*(v / 1000 for v in uf[:3])) @ _quat(uf[3:7])
        if ufprog == "FALSE":  # coordinated: the unit named by ufmec moves the user frame
            assert ufmec == "POS"
            carrier = positioner_flange(tilt, turn)
        else:  # fixed: the controller's world is the arm's base with the track at 0
            assert ufmec == ""
            carrier = robot_base(0.0)
        out.append(carrier @ uframe @ target)
    return out


def test_rapid_targets_re_expand_to_the_planned_tcp(plan: Plan) -> None:
    result = BACKENDS["rapid"]().emit(plan)
    assert not result.has_errors, [d.message for d in result.diagnostics]
    (text,) = result.files.values()
    got, want = rapid_targets(text), planned_tcp_world(plan)
    assert len(got) == len(want) == 4
    for g, w in zip(got, want, strict=True):
        assert np.abs(g[:3, 3] - w[:3, 3]).max() < TOL_M
        assert np.abs(g[:3, :3] - w[:3, :3]).max() < 1e-5  # printed with 6 (RAPID) and 4 (KRL, deg) decimals


def test_rapid_move_ext_j_and_joint_targets(plan: Plan) -> None:
    (text,) = BACKENDS["rapid"]().emit(plan).files.values()
    moves = re.findall(r"^\s*(Move\w+) (\w+)", text, re.M)
    assert [m for m, _ in moves] == ["MoveAbsJ", "MoveJ", "MoveL", "MoveExtJ", "MoveL", "MoveJ", "MoveAbsJ"]
    literals = dict(re.findall(r"CONST jointtarget (\w+):=\[(.*)\];", text))
    ext_j = literals[moves[3][1]]
    robax, extax = re.match(r"\[(.*?)\],\[(.*?)\]$", ext_j).groups()  # type: ignore[union-attr]
    assert robax.split(",") == ["9E+09"] * 6  # the arm is not moved by MoveExtJ
    assert _nums(extax)[:3] == pytest.approx([1200.0, -10.0, 180.0])
    last = literals[moves[6][1]]
    assert _nums(last.split("],[")[1])[:3] == pytest.approx([0.0, 0.0, 0.0])
    assert re.search(r"MoveExtJ \w+, vmax\\T:=[0-9.]+, fine;", text)


# ------------------------------------------------------------------ KRL


def _e6pos(body: str) -> dict[str, float]:
    return {k: float(v) for k, v in re.findall(r"(\w+) (" + _NUM + ")", body)}


def krl_targets(src: str, dat: str) -> list[np.ndarray]:
    """World TCP of every PTP/LIN to an E6POS, in program order (KRL ABC: Rz(A) Ry(B) Rx(C))."""
    data = dict(re.findall(r"DECL E6POS (\w+)=\{(.*)\}", dat))
    frames = dict(re.findall(r"DECL FRAME (\w+)=\{(.*)\}", dat))
    frames |= {f"BASE_DATA[{n}]": value for n, value in re.findall(r"; BASE_DATA\[(\d+)\] must hold \w+: \{(.*)\}", src)}
    out, base = [], None
    for line in src.splitlines():
        line = line.strip()
        if line.startswith("$BASE="):
            base = line
        motion = re.match(r"(PTP|LIN) (\w+)$", line)
        if motion is None or motion.group(2) not in data:
            continue
        p = _e6pos(data[motion.group(2)])
        target = at(p["X"] / 1000, p["Y"] / 1000, p["Z"] / 1000) @ rot("z", p["A"]) @ rot("y", p["B"]) @ rot("x", p["C"])
        assert base is not None
        ek = re.match(r"\$BASE=EK\(MACHINE_DEF\[(\d)\]\.ROOT,MACHINE_DEF\[\d\]\.MECH_TYPE,\{(.*)\}\)", base)
        if ek is not None:
            assert ek.group(1) == "3"  # robot 1, rail 2, pos 3
            f = _e6pos(ek.group(2))
            carrier = positioner_flange(p["E2"], p["E3"])
        else:
            f = _e6pos(frames[base.removeprefix("$BASE=")])
            carrier = robot_base(0.0)
        frame = at(f["X"] / 1000, f["Y"] / 1000, f["Z"] / 1000) @ rot("z", f["A"]) @ rot("y", f["B"]) @ rot("x", f["C"])
        out.append(carrier @ frame @ target)
    return out


def test_krl_targets_re_expand_to_the_planned_tcp(plan: Plan) -> None:
    result = BACKENDS["krl"]().emit(plan)
    assert not result.has_errors, [d.message for d in result.diagnostics]
    src = next(t for n, t in result.files.items() if n.endswith(".src"))
    dat = next(t for n, t in result.files.items() if n.endswith(".dat"))
    got, want = krl_targets(src, dat), planned_tcp_world(plan)
    assert len(got) == len(want) == 4
    for g, w in zip(got, want, strict=True):
        assert np.abs(g[:3, 3] - w[:3, 3]).max() < TOL_M
        assert np.abs(g[:3, :3] - w[:3, :3]).max() < 1e-5  # printed with 6 (RAPID) and 4 (KRL, deg) decimals
    assert "$VEL_EXTAX[3]=100" in src and "$ACC_EXTAX[1]=100" in src
    held = re.search(r"DECL E6AXIS jext=\{(.*)\}", dat)
    assert held is not None and _e6pos(held.group(1))["E3"] == pytest.approx(180.0)


# ------------------------------------------------------------------ Fanuc TP


def fanuc_targets(text: str) -> tuple[list[np.ndarray], list[tuple[float, float, float]]]:
    """World TCP of every J/L move to a Cartesian position (Fanuc W, P, R: Rz(R) Ry(P) Rx(W)),
    and the (E1, GP2 J1, GP2 J2) of each: the rail as the robot group's extended axis, the
    positioner as group 2. UFRAME n's value is read from the header comment that names it, or
    from the position register the program writes it through."""
    header = r"!UFRAME\[(\d+)\] = \w+ must hold: ;\s+\d+:\s+!(X .*?) ;\s+\d+:\s+!(W .*?) ;"
    frames = {int(n): [float(v) for v in re.findall(_NUM, x + " " + w)] for n, x, w in re.findall(header, text)}
    # a frame without a cell number: written through a position register (PR[n,1..6] = X..R)
    written = r"!UFRAME\[(\d+)\] = \w+ ;\s+\d+:\s+PR\[\d+\]=LPOS ;((?:\s+\d+:\s+PR\[\d+,\d\]=\S+ ;){6})"
    frames |= {int(n): [float(v) for v in re.findall(r"PR\[\d+,\d\]=(" + _NUM + ")", body)] for n, body in re.findall(written, text)}
    blocks = dict(re.findall(r"^P\[(\d+)(?::[^\]]*)?\]\{\n(.*?)\n\};", text, re.M | re.S))
    poses, axes = [], []
    for n in re.findall(r"^\s*\d+:\s*[JL] P\[(\d+)\]", text, re.M):
        block = blocks[n]
        gp1, gp2 = block.split("   GP2:")
        if "X =" not in gp1:
            continue
        v = {k: float(x) for k, x in re.findall(r"\b([XYZWPR]|E1) ?= +(" + _NUM + ")", gp1)}
        uf = int(re.search(r"UF : (\d+)", gp1).group(1))  # type: ignore[union-attr]
        frame = np.eye(4)
        if uf:
            x, y, z, w, p, r = frames[uf]
            frame = at(x / 1000, y / 1000, z / 1000) @ rot("z", r) @ rot("y", p) @ rot("x", w)
        target = at(v["X"] / 1000, v["Y"] / 1000, v["Z"] / 1000) @ rot("z", v["R"]) @ rot("y", v["P"]) @ rot("x", v["W"])
        poses.append(robot_base(0.0) @ frame @ target)
        j1, j2 = (float(x) for x in re.findall(r"J\d= +(" + _NUM + ") +deg", gp2))
        axes.append((v["E1"], j1, j2))
    return poses, axes


def test_fanuc_positions_re_expand_to_the_planned_tcp(plan: Plan) -> None:
    result = BACKENDS["fanuc"]().emit(plan)
    assert not result.has_errors, [d.message for d in result.diagnostics if d.is_error]
    (text,) = result.files.values()
    assert "DEFAULT_GROUP\t= 1,1,*,*,*;" in text
    got, axes = fanuc_targets(text)
    want = planned_tcp_world(plan, axes_only=True)  # `move axes` is a J move with the arm held
    assert len(got) == len(want) == 5
    for g, w in zip(got, want, strict=True):
        assert np.abs(g[:3, 3] - w[:3, 3]).max() < TOL_M
        assert np.abs(g[:3, :3] - w[:3, :3]).max() < 1e-4  # W, P, R printed with 3 decimals (deg)
    moves = [m for m in plan.tasks[0].task.body if isinstance(m, ir.Move) and isinstance(m.target, ir.CartesianTarget)]
    for (e1, j1, j2), move in zip(axes, moves, strict=True):
        ext = dict(move.ext)
        assert (e1, j1, j2) == pytest.approx((ext["rail"] * 1000, math.degrees(ext["pos.1"]), math.degrees(ext["pos.2"])),
                                             abs=1e-3)


@pytest.mark.parametrize("vendor", ["urscript", "val3"])  # INFORM: test_ext_axes_inform.py
def test_vendors_without_external_axes_refuse_at_the_first_move(plan: Plan, vendor: str) -> None:
    result = BACKENDS[vendor]().emit(plan)
    errors = [d for d in result.diagnostics if d.is_error]
    assert [d.code.id for d in errors] == ["E607"]
    assert errors[0].span is not None and errors[0].span.start.line == 14  # the first move: every move carries the axes
    assert "rail, pos.1, pos.2" in errors[0].message


# ------------------------------------------------------------------ timing


def test_the_track_move_lasts_its_trapezoid_and_axes_stay_within_limits(plan: Plan) -> None:
    tp = plan.tasks[0]
    moves = [i for i in tp.task.body if isinstance(i, ir.Move)]
    rec = tp.record(moves[1].uid)
    assert rec is not None
    # 1200 mm at 1500 mm/s, 2000 mm/s^2 (the turntable's 90 deg at 180 deg/s, 360 deg/s^2 take 1.0 s)
    assert rec.t_end - rec.t_start == pytest.approx(1.2 / 1.5 + 1.5 / 2.0, abs=plan.step)
    axes = task_axes(tp.task, plan.program.cell.external)
    values = axis_samples(tp, axes)
    dt = np.diff(tp.trajectory.t)
    speed = np.abs(np.diff(values, axis=0)) / dt[:, None]
    limits = np.array([1.5, math.radians(90), math.radians(180)])
    assert np.all(speed.max(axis=0) <= limits * (1 + 1e-6))
    assert speed[:, 0].max() == pytest.approx(1.5, rel=0.01)  # the track's move is long enough to cruise
    assert values[-1] == pytest.approx([0.0, 0.0, 0.0])


def test_the_cycle_time_counts_the_axes(plan: Plan) -> None:
    """Without the axis values (the same arm joints), the program is shorter: the axes' time counts."""
    still = SOURCE.replace(" ext(rail=1200mm, pos=(20deg, 90deg))", "").replace(" ext(rail=700mm)", "")
    front = load_text(still.replace("move axes pos to (-10deg, 180deg)\n", ""), "/tmp/ext_axes_still.rmot")
    assert front.program is not None
    assert plan_program(front.program).cycle_time < plan.cycle_time - 1.0

