"""Runtime logic in the Fanuc TP, INFORM and VAL3 emitters.

* golden files (hand-reviewed once) of a 3 x 4 x 3 palletiser written with nested `for` and of
  a machine-tending task (counter, `while` on an input, timeout branch, `stop`); the
  independent validators of vendor_validators.py read them too (test_vendor_validators.py
  collects every golden file);
* an independent witness for the vendor loops: a small interpreter per vendor, written here
  from the languages' rules (not the backends' code), runs the emitted counter / register /
  shift arithmetic, re-expands every move's target per iteration and compares it with the
  TCP pose the plan verified for that iteration;
* the unrolled path: a loop whose iterations need another IK branch is written iteration by
  iteration with W420 naming the iteration, and `unroll` forces it.
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest
from backend_fixtures import BRAND_ROBOT, FRONT_UP_NOFLIP, check_golden, hand_plan, span_at
from logic_fixtures_d import (
    BOOL,
    COLS,
    DOWN_Q,
    INT,
    LAYERS,
    ROWS,
    Q,
    const,
    iteration_poses,
    pallet_program,
    tending_program,
    var,
)
from rmot.backends import BACKENDS
from rmot.backends.base import EmitResult
from rmot.lang import ir, ir_tree, plan_types
from vendor_validators import check_fanuc, check_inform, check_val3

VENDORS = ("fanuc", "inform", "val3")
VALIDATE = {"fanuc": check_fanuc, "inform": check_inform, "val3": check_val3}
PLACEMENTS = LAYERS * ROWS * COLS  # 36


def emit(vendor: str, plan: plan_types.Plan, **attrs: object) -> EmitResult:
    backend = BACKENDS[vendor]()
    for k, v in attrs.items():
        setattr(backend, k, v)
    return backend.emit(plan)


def codes(result: EmitResult) -> set[str]:
    return {d.code.id for d in result.diagnostics}


# --------------------------------------------------------------------------- golden files


@pytest.mark.parametrize("vendor", VENDORS)
def test_palletiser_golden_and_valid(vendor: str) -> None:
    plan, _ = pallet_program(vendor)
    result = emit(vendor, plan)
    assert not result.has_errors, [d.message for d in result.diagnostics if d.is_error]
    assert "W420" not in codes(result)  # written as loops
    assert VALIDATE[vendor](result.files) == []
    check_golden(vendor, "logic_pallet", result.files)


@pytest.mark.parametrize("vendor", VENDORS)
def test_tending_golden_and_valid(vendor: str) -> None:
    result = emit(vendor, tending_program(vendor))
    assert not result.has_errors, [d.message for d in result.diagnostics if d.is_error]
    assert VALIDATE[vendor](result.files) == []
    check_golden(vendor, "logic_tending", result.files)


def test_palletiser_loops_are_a_few_moves_not_144() -> None:
    """The 36 placements (4 moves each) are written as one loop nest: each template move once."""
    for vendor, motion in (
        ("fanuc", r"^\s*\d+:\s+[JL] P\["),
        ("inform", r"^MOV[JL] "),
        ("val3", r"^\s*move[jl]\("),
    ):
        plan, _ = pallet_program(vendor)
        text = "\n".join(emit(vendor, plan).files.values())
        assert len(re.findall(motion, text, re.M)) == 5, vendor  # home, 3 template moves, home


# --------------------------------------------------------------------------- the loop witness


def _fanuc_run(
    files: dict[str, str],
    name: str,
    reg: dict[int, float] | None = None,
    pr: dict[int, list[float]] | None = None,
) -> list[tuple[float, float, float] | None]:
    """Execute a TP program's registers, PR elements, labels, jumps and CALLs (inputs and
    waits as satisfied: the main timeline); the destination of every J/L motion: P[n]'s X, Y,
    Z plus PR[i]'s when it carries `Offset,PR[i]` (added element by element in the user frame:
    HandlingTool manual 7.3.13); None for a position in joints."""
    text = files[f"{name}.ls"]
    reg = {} if reg is None else reg
    pr = {} if pr is None else pr
    mn = text.split("/MN\n")[1].split("/POS\n")[0]
    lines = [re.sub(r"^\s*\d+:\s+", "", ln).removesuffix(" ;") for ln in mn.splitlines()]
    points = {
        int(n): tuple(float(v) for v in (x, y, z))
        for n, x, y, z in re.findall(
            r"P\[(\d+)[^\]]*\]\{.*?X =\s*(\S+)\s+mm,\s*Y =\s*(\S+)\s+mm,\s*Z =\s*(\S+)\s+mm",
            text,
            re.S,
        )
    }
    labels = {
        int(m.group(1)): k for k, ln in enumerate(lines) if (m := re.fullmatch(r"LBL\[(\d+)\]", ln))
    }

    def value(tok: str) -> float:
        m = re.fullmatch(r"R\[(\d+)(?::[^\]]*)?\]", tok)
        if m:
            return reg[int(m.group(1))]
        return float(tok.strip("()"))

    def expr(text: str) -> float:
        m = re.fullmatch(
            r"(R\[[^\]]*\]|\(?-?[\d.]+\)?)(?:([-+*/])(R\[[^\]]*\]|\(?-?[\d.]+\)?))?", text
        )
        assert m, text
        a = value(m.group(1))
        if not m.group(2):
            return a
        b = value(m.group(3))
        return {"+": a + b, "-": a - b, "*": a * b, "/": a / b}[m.group(2)]

    out: list[tuple[float, float, float] | None] = []
    k, steps = 0, 0
    while k < len(lines):
        ln, k, steps = lines[k], k + 1, steps + 1
        assert steps < 100_000
        if ln == "ABORT":
            break
        if m := re.fullmatch(r"CALL (\w+)", ln):
            out += _fanuc_run(files, m.group(1), reg, pr)
        elif m := re.fullmatch(r"R\[(\d+)(?::[^\]]*)?\]=(.*)", ln):
            reg[int(m.group(1))] = expr(m.group(2))
        elif m := re.fullmatch(r"PR\[(\d+)\]=LPOS-LPOS", ln):
            pr[int(m.group(1))] = [0.0] * 6
        elif m := re.fullmatch(r"PR\[(\d+),(\d)\]=(.*)", ln):
            pr.setdefault(int(m.group(1)), [0.0] * 6)[int(m.group(2)) - 1] = expr(m.group(3))
        elif m := re.fullmatch(r"IF (R\[[^\]]*\])(<=|<|>=|>|=|<>)([^,]+),JMP LBL\[(\d+)\]", ln):
            a, b = value(m.group(1)), value(m.group(3))
            if {"<=": a <= b, "<": a < b, ">=": a >= b, ">": a > b, "=": a == b, "<>": a != b}[
                m.group(2)
            ]:
                k = labels[int(m.group(4))]
        elif m := re.fullmatch(r"JMP LBL\[(\d+)\]", ln):
            k = labels[int(m.group(1))]
        elif m := re.match(r"[JL] P\[(\d+)[^\]]*\] \S+ \S+(?: Offset,PR\[(\d+)\])?$", ln):
            if int(m.group(1)) not in points:
                out.append(None)
                continue
            p = points[int(m.group(1))]
            d = pr[int(m.group(2))][:3] if m.group(2) else [0.0, 0.0, 0.0]
            out.append((p[0] + d[0], p[1] + d[1], p[2] + d[2]))
    return out


def _inform_run(
    files: dict[str, str],
    name: str,
    d: dict[str, float] | None = None,
    p: dict[str, list[float]] | None = None,
) -> list[tuple[float, float, float]]:
    """Execute a job's D variables (SET/ADD/SUB/MUL/INC), SETE on P variables (0.001 mm),
    labels, JUMP IF and CALL JOB (waits as satisfied, PAUSE ends the run); every MOVJ/MOVL's
    position plus the active SFTON shift (RF: robot coordinates, those of ROBOT positions)."""
    text = files[f"{name}.JBI"]
    d = {} if d is None else d
    p = {} if p is None else p
    body = text.split("NOP\n")[1].splitlines()
    cpos = {
        m.group(1): tuple(float(v) for v in m.group(2).split(",")[:3])
        for m in re.finditer(r"^(C\d{5})=(.*)$", text, re.M)
    }
    labels = {ln: k for k, ln in enumerate(body) if re.fullmatch(r"\*L\d+", ln)}
    shift: list[float] | None = None

    def val(tok: str) -> float:
        return d[tok] if tok[0] in "DBR" else float(tok)

    out, k, steps = [], 0, 0
    while k < len(body):
        ln, k, steps = body[k], k + 1, steps + 1
        assert steps < 100_000
        w = ln.split()
        if not w or ln.startswith("'"):
            continue
        if w[0] == "PAUSE":
            break
        if w[0] == "CALL":
            out += _inform_run(files, w[1].removeprefix("JOB:"), d, p)
        elif w[0] == "SET" and w[1][0] in "DBR":
            d[w[1]] = val(w[2])
        elif w[0] in ("ADD", "SUB", "MUL", "DIV"):
            a, b = d[w[1]], val(w[2])
            d[w[1]] = {"ADD": a + b, "SUB": a - b, "MUL": a * b, "DIV": a / b}[w[0]]
        elif w[0] == "INC":
            d[w[1]] += 1
        elif w[0] == "SETE":
            p.setdefault(w[1], [0.0] * 6)[int(w[2].strip("()")) - 1] = d[w[3]] / 1000.0  # um -> mm
        elif w[0] == "SFTON":
            assert w[2] == "RF"
            shift = p.get(w[1], [0.0] * 6)
        elif w[0] == "SFTOF":
            shift = None
        elif w[0] == "JUMP":
            if m := re.fullmatch(r"JUMP (\*L\d+) IF IN#\(\d+\)=(ON|OFF)", ln):
                if m.group(2) == "ON":  # the main timeline: every awaited input comes
                    k = labels[m.group(1)]
                continue
            m = re.fullmatch(r"JUMP (\*L\d+)(?: IF (\w+)(<=|<|>=|>|=|<>)(\S+))?", ln)
            assert m, ln
            if (
                m.group(2) is None
                or {
                    "<=": d[m.group(2)] <= val(m.group(4)),
                    "<": d[m.group(2)] < val(m.group(4)),
                    ">=": d[m.group(2)] >= val(m.group(4)),
                    ">": d[m.group(2)] > val(m.group(4)),
                    "=": d[m.group(2)] == val(m.group(4)),
                    "<>": d[m.group(2)] != val(m.group(4)),
                }[m.group(3)]
            ):
                k = labels[m.group(1)]
        elif w[0] in ("MOVJ", "MOVL"):
            c = cpos[w[1]]
            s = shift or [0.0] * 3
            out.append((c[0] + s[0], c[1] + s[1], c[2] + s[2]))
    return out


def _val3_run(files: dict[str, str]) -> list[tuple[float, float, float] | None]:
    """Run start()'s `for` loops, the trShift fields and every move to `compose(pTarget[k],
    frame, trShift)` (VAL3 manual, compose: with no rotation, the point translated along the
    frame's axes) or to `pTarget[k]`: the targets in their frame's coordinates (mm); None for
    a movej to joints (jTarget: no Cartesian target to compare)."""
    dtx = next(t for n, t in files.items() if n.endswith(".dtx"))
    ns = {"d": "http://www.staubli.com/robotics/VAL3/Data/2"}
    points = [
        tuple(float(v.get(a)) for a in "xyz")  # type: ignore[arg-type]
        for data in ET.fromstring(dtx).iterfind("d:Datas/d:Data", ns)
        if data.get("name") == "pTarget"
        for v in data
    ]

    def code(name: str) -> list[str]:
        text = next(t for n, t in files.items() if n.endswith(f"/{name}.pgx"))
        return [ln.strip() for ln in text.split("<![CDATA[")[1].split("]]>")[0].splitlines()]

    env: dict[str, float] = {}
    out: list[tuple[float, float, float] | None] = []

    def term(t: str) -> float:
        m = re.fullmatch(r"(?:\((\w+) - (-?\d+)\)|(\w+)) \* (-?[\d.]+)", t)
        if t == "0":
            return 0.0
        assert m, t
        name = m.group(1) or m.group(3)
        return (env[name] - float(m.group(2) or 0)) * float(m.group(4))

    def run(lines: list[str], start: int, stop: int) -> None:
        k = start
        while k < stop:
            ln = lines[k]
            if ln == "return":
                raise StopIteration
            if ln == "if !bOk":  # the timeout branch: not taken on the main timeline
                depth = 1
                while depth:
                    k += 1
                    depth += lines[k].startswith("if ") - (lines[k] == "endIf")
            elif m := re.fullmatch(r"call (\w+)\(\)", ln):
                run(code(m.group(1)), 0, len(code(m.group(1))))
            if m := re.fullmatch(r"for (\w+) = (-?\d+) to (-?\d+)", ln):
                depth, end = 1, k + 1
                while depth:
                    depth += lines[end].startswith("for ") - (lines[end] == "endFor")
                    end += 1
                for v in range(int(m.group(2)), int(m.group(3)) + 1):
                    env[m.group(1)] = v
                    run(lines, k + 1, end - 1)
                k = end
                continue
            elif m := re.fullmatch(r"(trShift\d+)\.([xyz]) = (.*)", ln):
                env[f"{m.group(1)}.{m.group(2)}"] = sum(term(t) for t in m.group(3).split(" + "))
            elif m := re.match(
                r"move[jl]\((?:compose\(pTarget\[(\d+)\], \w+, (trShift\d+)\)|pTarget\[(\d+)\])", ln
            ):
                base = points[int(m.group(1) or m.group(3))]
                sh = [env.get(f"{m.group(2)}.{a}", 0.0) for a in "xyz"] if m.group(2) else [0.0] * 3
                out.append((base[0] + sh[0], base[1] + sh[1], base[2] + sh[2]))
            elif ln.startswith("movej(jTarget["):
                out.append(None)
            k += 1

    main = code("start")
    try:
        run(main, 0, len(main))
    except StopIteration:
        pass
    return out


@pytest.mark.parametrize("vendor", VENDORS)
def test_the_emitted_loop_reaches_every_verified_pose(vendor: str) -> None:
    """The emitted loop, executed by the interpreter above, reaches exactly the TCP poses the
    plan verified for each of the 36 placements (to the printed 0.001 mm)."""
    plan, loop = pallet_program(vendor)
    assert_witness(vendor, plan, loop, emit(vendor, plan).files)


def assert_witness(vendor: str, plan: plan_types.Plan, loop: ir.Loop, files: dict[str, str]) -> None:
    want = iteration_poses(loop, plan)
    assert len(want) == PLACEMENTS * 3
    got: list[tuple[float, float, float] | None]
    if vendor == "fanuc":  # in the move's frame (user frame), home moves first and last
        got = _fanuc_run(files, "PALLET")[1:-1]
        expect = [tuple(v * 1000.0 for v in pose.position) for _, pose in want]
    elif vendor == "inform":  # ROBOT coordinates: the base frame
        got = list(_inform_run(files, "PALLET")[1:-1])
        frame = plan.tasks[0].task.body[0].frame.pose  # type: ignore[union-attr]
        expect = [tuple(v * 1000.0 for v in (frame * pose).position) for _, pose in want]
    else:  # in the frame the points are linked to; joint moves (jTarget) are not compared
        ran = _val3_run(files)[1:-1]
        expect = [tuple(v * 1000.0 for v in pose.position) for _, pose in want]
        assert len(ran) == len(expect) and sum(p is not None for p in ran) >= PLACEMENTS * 2
        expect = [e for e, p in zip(expect, ran) if p is not None]
        got = [p for p in ran if p is not None]
    assert len(got) == len(expect)
    assert np.allclose(np.array(got), np.array(expect), atol=2e-3), (got[:5], expect[:5])


# ------------------------------------------------------------------ unrolled, with the reason


@pytest.mark.parametrize("vendor", VENDORS)
def test_a_loop_needing_another_branch_is_unrolled_naming_the_iteration(vendor: str) -> None:
    """Placement (1, 2, 0) needs elbow down: the loops holding it are written iteration by
    iteration (the outer one first names the iteration), the others stay loops, and the
    mixed program still reaches every verified pose."""
    other = ir.Config(ir.Shoulder.FRONT, ir.Elbow.DOWN, ir.Wrist.NOFLIP)
    plan, loop = pallet_program(vendor, branch_of={(1, 2, 0): other})
    result = emit(vendor, plan)
    notes = [d.message for d in result.diagnostics if d.code.id == "W420"]
    assert len(notes) == 3 and "layer = 1, row = 2, col = 0" in notes[0]
    assert all("unrolled" in n for n in notes)
    assert not result.has_errors
    assert VALIDATE[vendor](result.files) == []
    text = "\n".join(result.files.values())
    moves = len(re.findall(r"^\s*\d+:\s+[JL] P\[|^MOV[JL] |^\s*move[jl]\(", text, re.M))
    # layers 0 and 2 and rows 0, 1, 3 of layer 1 stay loops (3 moves each); row 2 is unrolled
    assert moves == 2 + 2 * 3 + 3 * 3 + COLS * 3
    assert_witness(vendor, plan, loop, result.files)


@pytest.mark.parametrize("vendor", VENDORS)
def test_unroll_forces_every_iteration(vendor: str) -> None:
    plan, _ = pallet_program(vendor)
    result = emit(vendor, plan, unroll=True)
    assert any(d.code.id == "W420" and "--unroll" in d.message for d in result.diagnostics)
    assert not re.search(r"for \w+ = |Offset,PR|SFTON", "\n".join(result.files.values()))


# --------------------------------------------------------------------------- single constructs


def one(vendor: str, *body: ir.Instr) -> EmitResult:
    return emit(vendor, hand_plan(tuple(body), {}, robot=BRAND_ROBOT[vendor]))


def main_lines(vendor: str, result: EmitResult) -> list[str]:
    text = next(t for n, t in result.files.items() if n.endswith((".ls", ".JBI", "/start.pgx")))
    if vendor == "fanuc":
        return [
            re.sub(r"^\s*\d+:\s+", "", ln).removesuffix(" ;")
            for ln in text.split("/MN\n")[1].split("/POS")[0].splitlines()
        ]
    if vendor == "inform":
        return text.split("NOP\n")[1].splitlines()
    return [ln.strip() for ln in text.split("<![CDATA[")[1].split("]]>")[0].splitlines()]


DECL = ir.VarDecl(uid=1, name="n", type=INT, init=const(2), span=span_at(2))


def test_fanuc_arithmetic_is_one_operator_per_line() -> None:
    value = ir.Arith("*", ir.Arith("+", var("n"), const(3), INT), const(-2), INT)
    lines = main_lines(
        "fanuc", one("fanuc", DECL, ir.Assign(uid=2, name="n", value=value, span=span_at(3)))
    )
    assert lines[-2:] == ["R[2:rmot tmp]=R[1:n]+3", "R[1:n]=R[2:rmot tmp]*(-2)"]
    assert all(
        len(re.findall(r"[-+*/](?![^(]*\))", ln.split("=", 1)[1])) <= 1
        for ln in lines
        if ln.startswith("R[")
    )


def test_fanuc_conditions_stay_in_standard_logic() -> None:
    """One IF line for and-only/or-only conditions of at most five comparisons; a mixed one
    becomes a chain of one-comparison jumps (TP standard logic never mixes AND with OR)."""
    ins = [ir.InputCondition(port=k, value=True) for k in range(1, 4)]
    mixed = ir.Logic(
        "or",
        (
            ir.Logic("and", tuple(ins[:2])),
            ir.Compare(ir.CompareOp.GT, ir.AnalogInput(1), ir.Const(4.5, ir.ValueType.NUM)),
        ),
    )
    plain = ir.If(
        uid=2,
        condition=ir.Logic("and", tuple(ins)),
        then=(ir.SetDigital(uid=3, port=1, value=True),),
    )
    lines = main_lines("fanuc", one("fanuc", plain))
    assert "IF DI[1]=OFF OR DI[2]=OFF OR DI[3]=OFF,JMP LBL[1]" in lines
    lines = main_lines(
        "fanuc",
        one(
            "fanuc", ir.If(uid=2, condition=mixed, then=(ir.SetDigital(uid=3, port=1, value=True),))
        ),
    )
    ifs = [ln for ln in lines if ln.startswith("IF ")]
    assert ifs and all(not (" AND " in ln and " OR " in ln) for ln in ifs)
    assert any("AI[1]>4.5" in ln or "AI[1]<=4.5" in ln for ln in ifs)


def test_fanuc_mixed_wait_is_polled_with_a_timer() -> None:
    cond = ir.Logic(
        "or",
        (
            ir.Logic(
                "and",
                (ir.InputCondition(port=1, value=True), ir.InputCondition(port=2, value=True)),
            ),
            ir.InputCondition(port=3, value=True),
        ),
    )
    result = one(
        "fanuc",
        ir.WaitCondition(
            uid=2,
            condition=cond,
            timeout=3.0,
            span=span_at(2),
            on_timeout=(ir.SetDigital(uid=3, port=4, value=True),),
        ),
    )
    assert "W431" in codes(result)
    lines = main_lines("fanuc", result)
    assert (
        "TIMER[10]=START" in lines
        and "IF R[1:rmot tmp]<3,JMP LBL[1]" in lines
        and "DO[4]=ON" in lines
    )
    assert check_fanuc(result.files) == []


def test_analog_inputs_per_vendor() -> None:
    cond = ir.Compare(ir.CompareOp.GT, ir.AnalogInput(2), ir.Const(4.5, ir.ValueType.NUM))
    node = ir.If(
        uid=2, condition=cond, then=(ir.SetDigital(uid=3, port=1, value=True),), span=span_at(2)
    )
    fanuc = one("fanuc", node)
    # AI[n] holds the raw A/D count (FANUC B-63943EN/02 §8.4.14), not volts: refused
    assert fanuc.has_errors and "E470" in codes(fanuc)
    val3 = one("val3", node)
    assert "if aioGet(aIn[2]) > 4.5" in main_lines("val3", val3) and "W455" in codes(val3)
    inform = one("inform", node)
    assert inform.has_errors and "E430" in codes(inform)  # INFORM jobs cannot read it


def test_stop_per_vendor() -> None:
    stop = ir.Stop(uid=2, span=span_at(2))
    assert main_lines("fanuc", one("fanuc", stop))[-1] == "ABORT"
    inform = main_lines("inform", one("inform", stop))
    assert inform[-5:] == ['MSG "STOP"', "PAUSE", "JUMP *L001", "*L001", "END"]
    val3_lines = main_lines("val3", one("val3", stop))
    assert val3_lines[-5:] == ["waitEndMove()", "// demo.rmot:2", "return", "waitEndMove()", "end"]
    # in a called program: INFORM pauses (W432); VAL3 returns through bStop to start()
    call = ir.ProcCall(
        uid=3, proc="fault", args=(), body=(ir.Stop(uid=4, span=span_at(5)),), span=span_at(3)
    )
    assert "W432" in codes(one("inform", call))
    val3 = one("val3", call)
    assert main_lines("val3", val3)[-6:-2] == ["call fault()", "if bStop", "return", "endIf"]
    assert check_val3(val3.files) == []


def test_timeout_branch_runs_and_goes_on() -> None:
    wait = ir.WaitInput(
        uid=2,
        condition=ir.InputCondition(port=1, value=True),
        timeout=2.0,
        span=span_at(2),
        on_timeout=(ir.SetDigital(uid=3, port=5, value=True),),
    )
    fanuc = main_lines("fanuc", one("fanuc", wait))
    k = fanuc.index("WAIT DI[1]=ON TIMEOUT,LBL[1]")
    assert fanuc[k - 1] == "$WAITTMOUT=200" and fanuc[k + 1 : k + 5] == [
        "JMP LBL[2]",
        "LBL[1]",
        "DO[5]=ON",
        "LBL[2]",
    ]
    assert "ABORT" not in fanuc
    inform = main_lines("inform", one("inform", wait))
    k = inform.index("WAIT IN#(1)=ON T=2.00")
    assert inform[k + 1 : k + 4] == ["JUMP *L001 IF IN#(1)=ON", "DOUT OT#(5) ON", "*L001"]
    val3 = main_lines("val3", one("val3", wait))
    k = val3.index("bOk = watch(dIn[1] == true, 2.0000)")
    assert val3[k + 1 : k + 4] == ["if !bOk", "dOut[5] = true", "endIf"]


def test_inform_variables_are_typed_and_listed() -> None:
    flag = ir.VarDecl(uid=2, name="ok", type=BOOL, init=const(True), span=span_at(3))
    num = ir.VarDecl(
        uid=3,
        name="level",
        type=ir.ValueType.NUM,
        init=ir.Const(1.5, ir.ValueType.NUM),
        span=span_at(4),
    )
    lines = main_lines("inform", one("inform", DECL, flag, num))
    assert {
        "'D050 = n",
        "'B050 = ok",
        "'R050 = level",
        "SET D050 2",
        "SET B050 1",
        "SET R050 1.5",
    } <= set(lines)


def test_validators_reject_what_the_new_forms_get_wrong() -> None:
    plan, _ = pallet_program("fanuc")
    files = emit("fanuc", plan).files
    broken = {n: t.replace("Offset,PR[", "Offset PR[") for n, t in files.items()}
    assert any("J/L line" in f for f in check_fanuc(broken))
    plan, _ = pallet_program("inform")
    files = emit("inform", plan).files
    broken = {
        n: re.sub(r"///NPOS (\d+),0,0,1,0,0", r"///NPOS \1,0,0,0,0,0", t) for n, t in files.items()
    }
    assert any("NPOS" in f for f in check_inform(broken))


def test_every_iteration_is_planned_the_same_robot_joints() -> None:
    """The fixture's premise: every move of the loop has a record at Q (what the witness
    compares against is the plan's record, not the IR's target)."""
    plan, loop = pallet_program("val3")
    tp = plan.tasks[0]
    moves = [n for n in ir_tree.walk((loop,)) if isinstance(n, ir.Move)]
    assert all(np.allclose(tp.record(m.uid).q_target, Q) for m in moves)  # type: ignore[union-attr]
    branches = [tp.record(m.uid).branch for m in moves]  # type: ignore[union-attr]
    assert all(b == FRONT_UP_NOFLIP for b in branches)


# --------------------------------------------------------------------------- from .rmot sources


def main_timeline(body: tuple[ir.Instr, ...]) -> list[ir.Move]:
    """The moves the main timeline runs, in order (every loop iteration, procs inlined, no
    timeout branch, up to a stop)."""
    out: list[ir.Move] = []
    for node in body:
        if isinstance(node, ir.Stop):
            break
        if isinstance(node, ir.Move):
            out.append(node)
        elif isinstance(node, ir.Loop):
            for it in node.iterations:
                out += main_timeline(it.body)
        elif isinstance(node, ir.ProcCall):
            out += main_timeline(node.body)
    return out


@pytest.mark.parametrize("vendor", VENDORS)
def test_the_palletizing_example_is_loops_that_reach_every_verified_placement(vendor: str) -> None:
    """examples/palletizing.rmot (3 layers x 4 rows x 3 columns with nested `for`) through the
    real front end and planner: written as loops (the last iteration, whose final move blends
    into the way home, after them), valid, and running every placement the plan verified."""
    from backend_fixtures import example_plans

    plan = example_plans(("palletizing",))["palletizing"]
    result = emit(vendor, plan)
    assert not result.has_errors, [d.message for d in result.diagnostics if d.is_error]
    assert VALIDATE[vendor](result.files) == []
    text = "\n".join(result.files.values())
    assert (
        len(re.findall(r"^\s*\d+:\s+[JL] P\[|^MOV[JL] |^\s*move[jl]\(", text, re.M)) < 80
    )  # not 36 x 8
    tp = plan.tasks[0]
    moves = main_timeline(tp.task.body)
    assert (
        len(moves) == PLACEMENTS * 6 + 2
    )  # per placement: down to the pick, up, down to the slot, up
    recs = [tp.record(m.uid) for m in moves]
    base = [r.tcp_pose for r in recs]  # type: ignore[union-attr]
    framed = [m.frame.pose.inverse() * p for m, p in zip(moves, base)]  # type: ignore[operator]
    if vendor == "fanuc":
        ran = _fanuc_run(result.files, "PALLETIZING")
        expect = framed
    elif vendor == "inform":
        ran = _inform_run(result.files, "PALLETIZING")  # type: ignore[assignment]
        expect = base  # type: ignore[assignment]
    else:
        ran = _val3_run(result.files)
        expect = framed
    assert len(ran) == len(expect)
    pairs = [
        (g, tuple(v * 1000.0 for v in e.position)) for g, e in zip(ran, expect) if g is not None
    ]
    # VAL3 writes a joint move outside a loop's shift as its planned joints (not compared here)
    assert len(pairs) >= sum(m.kind is not ir.MotionKind.JOINT for m in moves) + (
        0 if vendor == "val3" else 70
    )
    assert np.allclose([g for g, _ in pairs], [e for _, e in pairs], atol=2e-3)


@pytest.mark.parametrize("vendor", VENDORS)
def test_the_machine_tending_example_compiles(vendor: str) -> None:
    from backend_fixtures import example_plans

    plan = example_plans(("machine_tending",))["machine_tending"]
    result = emit(vendor, plan)
    assert not result.has_errors, [d.message for d in result.diagnostics if d.is_error]
    assert VALIDATE[vendor](result.files) == []
    text = "\n".join(result.files.values())
    stop = {"fanuc": "ABORT", "inform": "PAUSE", "val3": "bStop = true"}[vendor]
    loop = {"fanuc": "JMP LBL[", "inform": "JUMP *L", "val3": "while "}[vendor]
    assert stop in text and loop in text


def test_a_moving_arc_in_a_loop_is_unrolled_for_tp_and_inform_and_composed_for_val3() -> None:
    """TP's Offset,PR shifts one destination per line and INFORM's MOVC starts from the move
    before it: a loop whose arc moves per iteration is unrolled there (W420, saying why);
    VAL3 composes both the via and the end point."""
    from backend_fixtures import GRIPPER, TABLE, cart, motion
    from rmot.lang.ir import MotionKind

    def body(k: int, uid: int) -> tuple[ir.Instr, ...]:
        x = 0.1 + 0.05 * k
        start = ir.Pose((x, 0.0, 0.1), DOWN_Q)
        via = ir.Pose((x + 0.02, 0.02, 0.1), DOWN_Q)
        end = ir.Pose((x + 0.04, 0.0, 0.1), DOWN_Q)
        lin = ir.Move(
            uid=uid,
            kind=MotionKind.LINEAR,
            target=cart(start, TABLE, "s"),
            motion=motion(),
            tool=GRIPPER,
            frame=TABLE,
            span=span_at(5),
        )
        arc = ir.Move(
            uid=uid + 1,
            kind=MotionKind.CIRCULAR,
            target=cart(end, TABLE, "e"),
            via=cart(via, TABLE, "v"),
            motion=motion(),
            tool=GRIPPER,
            frame=TABLE,
            span=span_at(6),
        )
        return (lin, arc)

    loop = ir.Loop(
        uid=1,
        var="k",
        first=0,
        last=3,
        span=span_at(4),
        iterations=tuple(ir.LoopIteration(value=k, body=body(k, 10 + 2 * k)) for k in range(3)),
    )
    for vendor in VENDORS:
        records = {m.uid: (Q, FRONT_UP_NOFLIP) for m in ir_tree.walk((loop,)) if isinstance(m, ir.Move)}
        result = emit(vendor, hand_plan((loop,), records, robot=BRAND_ROBOT[vendor]))
        notes = [d.message for d in result.diagnostics if d.code.id == "W420"]
        if vendor == "val3":
            assert notes == []
            start = main_lines("val3", result)
            assert any(
                ln.startswith("movec(compose(pTarget[") and ln.count("compose(") == 2
                for ln in start
            )
        else:
            assert len(notes) == 1 and "circular" in notes[0], (vendor, notes)
        assert not result.has_errors and VALIDATE[vendor](result.files) == []
