"""Joint turns fixed by `config(j6=n)` reach every vendor's file.

For each vendor, a program moves J6 to turn -1, then turn +1 (a joint move and a linear move
that keeps it), then back to turn -1, on an arm whose J6 range allows both turns. The
emitted configuration data is decoded here with a decoder written from the vendor's own
documented rule (not the backend's code), and must select exactly the planned J6 value among
all its 360-degree equivalents inside the joint limits: what the controller moves to is what
was verified. Turn n means q in [n*360 - 180, n*360 + 180) deg (lang/REFERENCE.md section 6).

The decoders:
* ABB confdata cf6 = the quadrant of axis 6, q in [cf6*90, cf6*90 + 90) deg (ABB Technical
  reference manual RAPID Instructions, Functions and Data types, "confdata": cf6 "the current
  quadrant of axis 6, expressed as a positive or negative integer"; quadrant 0 is 0..90 deg).
* KUKA E6POS Turn T: bit 5 set when axis 6 is negative (KUKA System Software 8.x Operating
  and Programming Instructions for System Integrators, "Status and Turn": bit n of Turn is
  1 for an axis angle < 0 deg, 0 for >= 0 deg).
* Fanuc CONFIG 'F|N U|D T|B, t4, t5, t6': t6 = the turn number of J6, 0 for (-180, 180] deg
  and +-1 per further revolution (R-30iB Operator's Manual, "Configuration": turn numbers of
  the wrist axes).
* Yaskawa `///RCONF l,m,n,o,p,q`: p = 0 for "T < 180", 1 for "T >= 180" (DX100 Options
  "Interface with an Easy Offline Teaching System" 156191-1CD section 4.1, RCONF), read as the
  magnitude: 1 when T lies outside -180 < T <= 180 deg (the literal signed reading would give
  -300 and +60 the same flag, which could not select a position).
* Staubli VAL3 and URScript joint moves carry the joint values themselves (VAL3 `jointRx` in
  degrees, URScript `movej` lists in radians): the value is read and its turn computed; their
  linear moves carry no turn (a Cartesian path runs on from the current joints, as planned).

J6 ranges (the library's cited sources): IRB 120 +-400 deg (ABB 3HAC035960-001), KR 6 R900
+-350 deg (KUKA spec PF0030), LR Mate 200iD +-360 deg (FANUC LR Mate 200iD data sheet), GP8
+-360 deg (Yaskawa GP8 spec 178642-1CD), TX2-60 +-270 deg (staubli_experimental
tx2_60_macro.xacro), UR5e +-360 deg (ur_description joint_limits.yaml).
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from functools import partial

import pytest
from rmot.backends import BACKENDS
from rmot.lang import ir, ir_tree
from rmot.compiler.frontend import load_text
from rmot.compiler.plan import plan_program

WANTED = (-1, 1, 1, -1)  # J6 turn at each move's target, in program order

# vendor -> (robot, z of the targets in the base frame, J6 offset of the two poses)
ARMS = {
    "rapid": ("abb_irb120", 300, 60),
    "krl": ("kuka_kr6_r900", 300, 60),
    "fanuc": ("fanuc_lrmate200id", 300, 60),
    "inform": ("yaskawa_gp8", 300, 60),
    "val3": ("staubli_tx2_60", 0, 150),  # J6 +-270: turn -1 is [-270, -180), turn 1 [180, 270]
    "urscript": ("ur5e", 300, 60),
}


def program(robot: str, z: int, rz: int) -> str:
    return f"""cell c {{
  robot r1 = {robot}
}}
program turns on r1 {{
  target a = pose(x=400mm, z={z}mm, ry=180deg) * pose(rz={rz}deg)
  target b = pose(x=400mm, y=100mm, z={z}mm, ry=180deg) * pose(rz=-{rz}deg)
  move joint a config(j6=-1)
  move joint b config(j6=1)
  move linear shift(b, z=-50mm)
  move joint a config(j6=-1)
}}
"""


def planned_and_emitted(vendor: str) -> tuple[list[float], list[float], dict[str, str]]:
    """(planned J6 in deg per move, the J6 limits in deg, the emitted files)."""
    robot, z, rz = ARMS[vendor]
    front = load_text(program(robot, z, rz), "turns.rmot")
    assert front.program is not None, [d.message for d in front.diagnostics]
    plan = plan_program(front.program)
    assert not [d for d in plan.diagnostics if d.is_error], [d.message for d in plan.diagnostics]
    tp = plan.tasks[0]
    moves = [n for n in ir_tree.walk(tp.task.body) if isinstance(n, ir.Move)]
    q6 = []
    for m in moves:
        rec = tp.record(m.uid)
        assert rec is not None and rec.q_target is not None
        q6.append(math.degrees(float(rec.q_target[5])))
    from rmot.sim.robots.library import SPECS

    result = BACKENDS[vendor]().emit(plan)
    assert not result.has_errors, [d.message for d in result.diagnostics if d.is_error]
    return q6, list(SPECS[robot].limits_deg[5]), result.files


def turn(q_deg: float) -> int:
    """The reference's definition, written out: q in [n*360 - 180, n*360 + 180)."""
    n = 0
    while q_deg >= n * 360 + 180:
        n += 1
    while q_deg < n * 360 - 180:
        n -= 1
    return n


def selected(q_deg: float, limits: list[float], rule: Callable[[float], bool]) -> list[float]:
    """Every q + 360k inside the limits that the decoded configuration data allows."""
    lo, hi = limits
    out = []
    for k in range(-3, 4):
        v = q_deg + 360 * k
        if lo - 1e-6 <= v <= hi + 1e-6 and rule(v):
            out.append(v)
    return out


def one_file(files: dict[str, str], suffix: str) -> str:
    (text,) = [t for n, t in files.items() if n.endswith(suffix)]
    return text


def in_quadrant(cf: int, v: float) -> bool:
    return cf * 90 <= v < cf * 90 + 90


def sign_bit(bit: int, v: float) -> bool:
    return (v < 0) == bool(bit)


def fanuc_turn(t: int, v: float) -> bool:
    return -180 + 360 * t < v <= 180 + 360 * t


def beyond_180(flag: int, v: float) -> bool:
    return (not -180 < v <= 180) == bool(flag)


def rules_rapid(files: dict[str, str]) -> list[Callable[[float], bool]]:
    mod = one_file(files, ".mod")
    cf = {
        n: int(c6)
        for n, c6 in re.findall(
            r"robtarget (\w+):=\[\[[^]]*\],\[[^]]*\],\[-?\d+,-?\d+,(-?\d+),", mod
        )
    }
    names = re.findall(r"Move[JL] (\w+),", mod)
    return [partial(in_quadrant, cf[n]) for n in names]


def rules_krl(files: dict[str, str]) -> list[Callable[[float], bool]]:
    dat, src = one_file(files, ".dat"), one_file(files, ".src")
    t = {n: int(v) for n, v in re.findall(r"E6POS (\w+)=\{[^}]*,T (\d+)", dat)}
    names = re.findall(r"^\s*(?:PTP|LIN) (\w+)", src, re.MULTILINE)
    return [partial(sign_bit, (t[n] >> 5) & 1) for n in names]


def rules_fanuc(files: dict[str, str]) -> list[Callable[[float], bool]]:
    ls = one_file(files, ".ls")
    t6 = {
        int(n): int(t)
        for n, t in re.findall(
            r"P\[(\d+)[^\]]*\]\{\s*GP1:\s*UF[^']*'[^,]*, *-?\d+, *-?\d+, *(-?\d+)'", ls
        )
    }
    order = [int(p) for p in re.findall(r"^\s*\d+:\s*[JL] P\[(\d+)\]", ls, re.MULTILINE)]
    return [partial(fanuc_turn, t6[p]) for p in order]


def rules_inform(files: dict[str, str]) -> list[Callable[[float], bool]]:
    jbi = one_file(files, ".JBI")
    flag, flags = 0, {}
    for line in jbi.splitlines():
        if line.startswith("///RCONF "):
            flag = int(line.split()[1].split(",")[4])
        elif m := re.match(r"(C\d{5})=", line):
            flags[m[1]] = flag
    order = re.findall(r"^MOV[JLC] (C\d{5})", jbi, re.MULTILINE)
    return [partial(beyond_180, flags[c]) for c in order]


def joint_values_val3(files: dict[str, str]) -> list[float | None]:
    dtx = one_file(files, ".dtx")
    block = re.search(r'name="jTarget".*?</Data>', dtx, re.DOTALL)
    j6 = (
        {int(k): float(v) for k, v in re.findall(r'key="(\d+)"[^>]*j6="(-?[\d.]+)"', block[0])}
        if block
        else {}
    )
    pgx = files[next(n for n in files if n.endswith("start.pgx"))]
    out: list[float | None] = []
    for kind, k in re.findall(r"move([jl])\((?:jTarget|pTarget)\[(\d+)\]", pgx):
        out.append(j6[int(k)] if kind == "j" else None)
    return out


def joint_values_urscript(files: dict[str, str]) -> list[float | None]:
    script = one_file(files, ".script")
    out: list[float | None] = []
    for kind, args in re.findall(r"move([jl])\((\[[^]]*\]|p\[[^]]*\])", script):
        out.append(math.degrees(float(args.strip("[]").split(",")[5])) if kind == "j" else None)
    return out


@pytest.mark.parametrize("vendor", ["rapid", "krl", "fanuc", "inform"])
def test_configuration_data_selects_the_planned_turn(vendor: str) -> None:
    q6, limits, files = planned_and_emitted(vendor)
    assert [turn(q) for q in q6] == list(WANTED)
    rules = {"rapid": rules_rapid, "krl": rules_krl, "fanuc": rules_fanuc, "inform": rules_inform}[
        vendor
    ](files)
    assert len(rules) == len(q6)
    for q, rule in zip(q6, rules):
        chosen = selected(q, limits, rule)
        assert len(chosen) == 1 and abs(chosen[0] - q) < 1e-6, (q, chosen)
    # the other turn of the same pose, also inside the limits, is refused by the same data
    assert any(len(selected(q, limits, lambda v: True)) > 1 for q in q6)


@pytest.mark.parametrize("vendor", ["val3", "urscript"])
def test_joint_moves_carry_the_planned_turn(vendor: str) -> None:
    q6, _, files = planned_and_emitted(vendor)
    assert [turn(q) for q in q6] == list(WANTED)
    written = (joint_values_val3 if vendor == "val3" else joint_values_urscript)(files)
    assert len(written) == len(q6) and written[2] is None  # the linear move: no joint values
    for q, w in zip(q6, written):
        if w is not None:
            assert abs(w - q) < 1e-3 and turn(w) == turn(q)


def test_turn_definition_matches_the_ir() -> None:
    """ir.turn_of (radians) agrees with the reference's interval, boundaries included."""
    for q in (-540.0, -180.0, -179.999, 0.0, 179.999, 180.0, 359.0, 539.999, 540.0):
        assert ir.turn_of(math.radians(q)) == turn(q), q


@pytest.mark.parametrize("vendor", ["krl", "inform"])
def test_a_turn_beyond_360_the_data_cannot_tell_apart_is_refused(vendor: str) -> None:
    """An IRB 120 (J6 +-400 deg, ABB 3HAC035960-001) written for KRL or INFORM with J6 at 390
    deg: a sign bit or a beyond-180 flag fits 30 deg (KRL) or -330 deg (INFORM) as well, both
    inside the limits, so the backend refuses with E440 rather than write an ambiguous
    position. The same program for RAPID (cf6 = 4, the quadrant) is written."""
    text = """cell c {
  robot r1 = abb_irb120
}
program turns on r1 {
  target home = joints(0, 0, 0, 0, 30, 0) deg
  move joint home
  move joint pose(x=400mm, z=300mm, ry=180deg) * pose(rz=30deg) config(wrist=noflip, j6=1)
}
"""
    front = load_text(text, "turns.rmot")
    assert front.program is not None
    plan = plan_program(front.program)
    assert not [d for d in plan.diagnostics if d.is_error], [d.message for d in plan.diagnostics]
    records = plan.tasks[0].records
    q6 = [math.degrees(float(r.q_target[5])) for r in records if r.q_target is not None]
    assert any(q >= 360 for q in q6), q6
    result = BACKENDS[vendor]().emit(plan)
    errors = [d for d in result.diagnostics if d.is_error]
    assert errors and {d.code.id for d in errors} == {"E440"}
    assert "joint 6 at 390.0 deg" in errors[0].message
    assert not BACKENDS["rapid"]().emit(plan).has_errors
