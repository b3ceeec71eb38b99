"""What kept a vendor program from loading on its controller, one test each, through the
real front end and planner:

* Fanuc: a circular move's `C P[via]` line does not end the instruction (no ` ;`); only its
  `:  P[to] speed zone ;` continuation does (R-30iB Operator's Manual, circular motion;
  RoboDK's Fanuc_R30iA.py post writes the same two lines).
* KUKA: an approximated PTP is `PTP p C_PTP` with `$APO.CPTP` set before it; C_DIS is for CP
  motions (LIN/CIRC) only (KSS 8.x Programming Instructions for System Integrators, PTP).
* ABB: a target named like a RAPID instruction is not declared under that name (a datum
  named `movel` hides the instruction MoveL in the whole module).
* UR: the .script calls its program after the `def ... end`.
* Yaskawa: a proc's job carries the program's name, so two programs' procs never overwrite
  each other's .JBI on one controller.
* every vendor: where the plan stops (before `wait until`, before `if`) the move printed just
  before is a stop point in the vendor's terms; a move the plan blends past a `set` stays
  blended.
"""

from __future__ import annotations

import re
from collections.abc import Callable

import pytest

from rmot.backends import BACKENDS
from rmot.lang import plan_types

STOPS = """
program stops on r1 {
  tool gripper
  frame table_top
  speed 250 mm/s
  zone 20 mm
  target home = joints(0, -20, 30, 0, 50, 0) deg
  target a = pose(x=-100mm, y=50mm, z=200mm, rx=180deg)
  target b = pose(x=100mm, y=-50mm, z=150mm, rx=180deg)
  move joint home
  move linear a
  move linear b
  wait until in[2] == on
  move linear a
  move linear b
  if in[2] == on {
    move linear a
  }
  move linear b
  set out[1] = on
  move joint home zone fine
}
"""

ARCS = """
program arcs on r1 {
  tool gripper
  frame table_top
  speed 100 mm/s
  target home = joints(0, -20, 30, 0, 50, 0) deg
  target a = pose(x=-100mm, y=0mm, z=200mm, rx=180deg)
  target m = pose(x=0mm, y=80mm, z=200mm, rx=180deg)
  target b = pose(x=100mm, y=0mm, z=200mm, rx=180deg)
  move joint home zone 20 mm
  move joint a zone 20 mm
  move circular via m to b zone 5 mm
  move linear a
}
"""

RESERVED_TARGETS = """
program names on r1 {
  tool gripper
  frame table_top
  target movel = pose(x=-100mm, y=50mm, z=200mm, rx=180deg)
  target MoveJ = pose(x=100mm, y=-50mm, z=150mm, rx=180deg)
  target home = joints(0, -20, 30, 0, 50, 0) deg
  move joint home
  move linear movel
  move joint MoveJ
  move linear movel
}
"""


def _proc_program(name: str, y: str) -> str:
    return f"""
proc approach() {{
  move linear pose(x=0mm, y={y}, z=200mm, rx=180deg)
}}

program {name} on r1 {{
  tool gripper
  frame table_top
  target home = joints(0, -20, 30, 0, 50, 0) deg
  move joint home
  approach()
}}
"""


@pytest.fixture(scope="module")
def stops(plan_from_text: Callable[..., plan_types.Plan]) -> plan_types.Plan:
    return plan_from_text(STOPS, "stops.rmot")


def _text(vendor: str, plan: plan_types.Plan) -> list[str]:
    result = BACKENDS[vendor]().emit(plan)
    assert not result.has_errors, [d.message for d in result.diagnostics if d.is_error]
    return [line.strip() for name, text in sorted(result.files.items()) for line in text.splitlines()]


# vendor -> (regex of a motion line, regex of the wait line, regex of the if line, stop test)
SHAPES: dict[str, tuple[str, str, str, Callable[[str], bool]]] = {
    "rapid": (r"^Move", r"^WaitDI ", r"^IF DInput", lambda m: ", fine," in m),
    "krl": (r"^(PTP|LIN|CIRC) ", r"^WAIT FOR \$IN", r"^IF \$IN",
            lambda m: not re.search(r"C_(DIS|PTP|VEL|ORI)", m)),
    "fanuc": (r"^\d+:\s+[JLC] P\[|^:\s+P\[", r"WAIT DI\[", r"IF DI\[", lambda m: "FINE" in m),
    "urscript": (r"^move[jlc]\(", r"^while not \(get_standard_digital_in\(2\)", r"^if get_standard",
                 lambda m: m.endswith("r=0.000000)") or "r=0.000000," in m),
    "inform": (r"^MOV[JLC] ", r"^WAIT IN#\(2\)", r"^JUMP \*L\d+ IF IN#", lambda m: "PL=0" in m),
}


def _move_before(lines: list[str], where: str, move: str) -> str:
    k = next(i for i, line in enumerate(lines) if re.search(where, line))
    return next(line for line in reversed(lines[:k]) if re.search(move, line))


@pytest.mark.parametrize("vendor", sorted(SHAPES))
def test_move_before_wait_until_is_a_stop_point(stops: plan_types.Plan, vendor: str) -> None:
    """The plan stops before `wait until`: the move printed before the wait stops exactly."""
    move, wait, _, is_stop = SHAPES[vendor]
    line = _move_before(_text(vendor, stops), wait, move)
    assert is_stop(line), line


@pytest.mark.parametrize("vendor", sorted(SHAPES))
def test_move_before_if_is_a_stop_point(stops: plan_types.Plan, vendor: str) -> None:
    """The plan stops before a runtime `if`: the move printed before it stops exactly."""
    move, _, cond, is_stop = SHAPES[vendor]
    line = _move_before(_text(vendor, stops), cond, move)
    assert is_stop(line), line


@pytest.mark.parametrize("vendor", sorted(SHAPES))
def test_move_before_set_stays_blended(stops: plan_types.Plan, vendor: str) -> None:
    """A `set` does not stop the plan: the move before it keeps its zone (no over-stopping)."""
    move, _, _, is_stop = SHAPES[vendor]
    out = {"rapid": r"^SetDO ", "krl": r"^\$OUT\[1\]", "fanuc": r"DO\[1", "urscript": r"^set_standard_digital_out\(1",
           "inform": r"^DOUT OT#\(1\)"}[vendor]
    line = _move_before(_text(vendor, stops), out, move)
    assert not is_stop(line), line


def test_val3_waits_for_the_motion_before_wait_and_if(stops: plan_types.Plan) -> None:
    """VAL3 queues motion: waitEndMove() comes right before the wait and the if."""
    lines = [line for line in _text("val3", stops) if not line.startswith("//")]
    for pattern in (r"^wait\(dIn\[2\]", r"^if dIn\[2\]"):
        k = next(i for i, line in enumerate(lines) if re.search(pattern, line))
        assert lines[k - 1] == "waitEndMove()", lines[k - 2:k + 1]


def test_fanuc_circular_line_is_continued_not_terminated(plan_from_text: Callable[..., plan_types.Plan]) -> None:
    """`C P[via]` carries no ';': the instruction ends on its `: P[to] ... ;` continuation."""
    text = BACKENDS["fanuc"]().emit(plan_from_text(ARCS, "arcs.rmot")).files["ARCS.ls"]
    lines = text.splitlines()
    circ = [k for k, line in enumerate(lines) if re.match(r"^\s*\d+:\s+C P\[\d+\]", line)]
    assert circ, text
    for k in circ:
        assert not lines[k].rstrip().endswith(";"), lines[k]
        assert re.match(r"^\s+:\s+P\[\d+\] \d+mm/sec (FINE|CNT\d+) ;$", lines[k + 1]), lines[k + 1]


def test_krl_blended_ptp_is_c_ptp_with_apo_cptp(plan_from_text: Callable[..., plan_types.Plan]) -> None:
    """A blended joint move is `PTP p C_PTP` after `$APO.CPTP=n` (1..100); never PTP .. C_DIS
    alone (C_DIS only after C_PTP, where the PTP blends into a LIN/CIRC: mxAutomation manual)."""
    result = BACKENDS["krl"]().emit(plan_from_text(ARCS, "arcs.rmot"))
    lines = [line.strip() for line in result.files["arcs.src"].splitlines()]
    ptp = [k for k, line in enumerate(lines) if line.startswith("PTP ")]
    assert not [lines[k] for k in ptp if "C_DIS" in lines[k] and "C_PTP C_DIS" not in lines[k]]
    blended = [k for k in ptp if lines[k].endswith((" C_PTP", " C_PTP C_DIS"))]
    assert blended, lines
    for k in blended:
        setting = next(line for line in reversed(lines[:k]) if line.startswith("$APO.CPTP"))
        assert re.fullmatch(r"\$APO\.CPTP=(\d+)", setting) and 1 <= int(setting.split("=")[1]) <= 100
    assert "W403" in {d.code.id for d in result.diagnostics}


def test_rapid_target_named_like_an_instruction_is_renamed(plan_from_text: Callable[..., plan_types.Plan]) -> None:
    """No datum of the module is named like an instruction the module uses (W414 says so)."""
    result = BACKENDS["rapid"]().emit(plan_from_text(RESERVED_TARGETS, "names.rmot"))
    text = result.files["names.mod"]
    declared = {m.lower() for m in re.findall(r"^\s*(?:CONST|PERS|VAR)\s+\w+\s+(\w+)", text, re.M)}
    used = {m.lower() for m in re.findall(r"^\s+([A-Za-z]\w*)\b(?!\s*:=)", text, re.M)}
    assert {"movel", "movej"} <= used
    assert not declared & used, declared & used
    assert [d.code.id for d in result.diagnostics].count("W414") == 2


def test_urscript_calls_its_program(plan_from_text: Callable[..., plan_types.Plan]) -> None:
    """The last line of the .script calls the program its top-level def defines."""
    (text,) = BACKENDS["urscript"]().emit(plan_from_text(ARCS, "arcs.rmot")).files.values()
    top = re.findall(r"^def (\w+)\(\):$", text, re.M)
    assert len(top) == 1
    assert text.splitlines()[-1] == f"{top[0]}()"


def test_inform_jobs_of_two_programs_do_not_collide(plan_from_text: Callable[..., plan_types.Plan]) -> None:
    """pick and place both call a proc `approach` (different positions): their job files
    have different names, so both programs can be loaded on one controller."""
    pick = BACKENDS["inform"]().emit(plan_from_text(_proc_program("pick", "40mm"), "pick.rmot")).files
    place = BACKENDS["inform"]().emit(plan_from_text(_proc_program("place", "-40mm"), "place.rmot")).files
    assert len(pick) == 2 and len(place) == 2
    assert not set(pick) & set(place), (sorted(pick), sorted(place))
    for files in (pick, place):
        calls = re.findall(r"^CALL JOB:(\w+)$", "".join(files.values()), re.M)
        assert calls and all(f"{c}.JBI" in files for c in calls)


FAST = """
program fast on r1 {
  tool gripper
  frame table_top
  target home = joints(0, -20, 30, 0, 50, 0) deg
  move joint home
  move linear pose(x=-100mm, y=50mm, z=200mm, rx=180deg) speed 3000 mm/s
}
"""


@pytest.mark.parametrize(("vendor", "pattern", "limit"), [
    # the limits as the manuals give them (typed here, not read from the backends)
    ("fanuc", r"L P\[\d+\] (\d+)mm/sec", 2000.0),     # R-30iB: L/C 1..2000 mm/sec
    ("krl", r"\$VEL\.CP=([\d.]+)", 2.0),              # KSS 8.x LIN inline form: 0.001..2 m/s
    ("inform", r"MOVL C\d+ V=([\d.]+)", 1500.0),      # INFORM MOVL V= 0.1..1500.0 mm/s
])
def test_tcp_speed_beyond_the_vendor_is_clamped_at_the_move(plan_from_text: Callable[..., plan_types.Plan],
                                                            vendor: str, pattern: str, limit: float) -> None:
    result = BACKENDS[vendor]().emit(plan_from_text(FAST, "fast.rmot"))
    text = "\n".join(result.files.values())
    speeds = [float(v) for v in re.findall(pattern, text)]
    assert speeds == [limit], speeds
    clamped = [d for d in result.diagnostics if d.code.id == "W417"]
    assert len(clamped) == 1 and clamped[0].span is not None and clamped[0].span.start.line == 7
