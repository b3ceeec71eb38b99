"""One meaning per construct on every controller: wait timeouts stop the program, accelerations
warn only when programmed, ports are checked against a documented range, payloads sit half way
to the TCP, each warning code means one thing, native blocks name the six controllers."""

from __future__ import annotations

import re

import pytest
from backend_fixtures import DOWN, FRONT_UP_NOFLIP, Q, cart, hand_plan, span_at

from rmot.backends import BACKENDS, codes, controllers, targets
from rmot.backends.base import DEFAULT_JOINT_ACCEL, DEFAULT_TCP_ACCEL, EmitResult
from rmot.lang import ir, ir_tree
from rmot.compiler.passes.modal import DEFAULT_MODAL

ROBOT = {"rapid": "abb_irb120", "krl": "kuka_kr16", "fanuc": "fanuc_lrmate200id", "urscript": "ur5e",
         "inform": "yaskawa_gp8", "val3": "staubli_tx2_60"}
L, J = ir.MotionKind.LINEAR, ir.MotionKind.JOINT


def motion(tcp_accel: float = DEFAULT_TCP_ACCEL, joint_accel: float = DEFAULT_JOINT_ACCEL) -> ir.Motion:
    return ir.Motion(tcp_speed=0.25, tcp_accel=tcp_accel, joint_speed=1.0, joint_accel=joint_accel,
                     zone=ir.Zone(0.0))


def move(uid: int, kind: ir.MotionKind = L, tool: ir.ToolRef = ir.ToolRef(None), **accel: float) -> ir.Move:
    return ir.Move(uid=uid, kind=kind, target=cart(DOWN, name=f"p{uid}"), via=None, motion=motion(**accel),
                   tool=tool, frame=ir.FrameRef(None), span=span_at(10 + uid))


def emit(target: str, body: tuple[ir.Instr, ...]) -> EmitResult:
    records = {n.uid: (Q, FRONT_UP_NOFLIP) for n in ir_tree.walk(body) if isinstance(n, ir.Move)}
    return BACKENDS[target]().emit(hand_plan(body, records, robot=ROBOT[target]))


def ids(result: EmitResult) -> list[str]:
    return [d.code.id for d in result.diagnostics]


def text(result: EmitResult) -> str:
    return "\n".join(result.files.values())


# --------------------------------------------------------------------------- 1. timeouts

WAIT = ir.WaitInput(uid=1, condition=ir.InputCondition(port=2, value=True), timeout=5.0, span=span_at(3))
# the vendor's stop after an unmet wait, in order (RAPID: WaitDI\MaxTime without \TimeFlag raises
# ERR_WAIT_MAXTIME, which stops an unhandled program)
STOPS = {
    "rapid": [r"WaitDI di2, 1\\MaxTime:=5\.000;"],
    "krl": [r"IF NOT \(\$IN\[2\]==TRUE\) THEN", r"HALT ; timeout"],
    "fanuc": [r"WAIT DI\[2\]=ON TIMEOUT,LBL\[1\]", r"LBL\[1\]", r"ABORT"],
    "urscript": [r"if not \(get_standard_digital_in\(2\) == True\):", r'popup\(".*", title="rmot", error=True, '
                 r"blocking=True\)", r"halt"],
    "inform": [r"WAIT IN#\(2\)=ON T=5\.00", r"JUMP \*L001 IF IN#\(2\)=ON", r'MSG "IN#\(2\) TIMEOUT"', r"PAUSE"],
    "val3": [r"bOk = watch\(dIn\[2\] == true, 5\.0000\)", r"if !bOk", r'popUpMsg\(".*"\)', r"stopMove\(\)",
             r"resetMotion\(\)", r"return"],
}


@pytest.mark.parametrize("target", controllers())
def test_timed_out_wait_stops_the_program(target: str) -> None:
    """A wait that times out stops the program (with a message where the vendor has one)."""
    lines = [ln.strip() for ln in text(emit(target, (WAIT,))).splitlines()]
    at = 0
    for pattern in STOPS[target]:
        at = next(i for i in range(at, len(lines)) if re.fullmatch(r"(\d+:\s+)?" + pattern + r"( ;)?", lines[i]))
    assert at > 0


# --------------------------------------------------------------------------- 2. accelerations

def test_default_accelerations_are_the_front_ends() -> None:
    """The backend's notion of "not programmed" is the front end's default modal state."""
    assert (DEFAULT_TCP_ACCEL, DEFAULT_JOINT_ACCEL) == (DEFAULT_MODAL.tcp_accel, DEFAULT_MODAL.joint_accel)


@pytest.mark.parametrize("target", controllers())
def test_default_acceleration_gives_no_warning(target: str) -> None:
    """Moves at the default accelerations ask for nothing: no W408 on any vendor."""
    result = emit(target, (move(1, J), move(2, L)))
    assert "W408" not in ids(result)


@pytest.mark.parametrize(("target", "warned"), [("rapid", 1), ("fanuc", 1), ("inform", 1), ("val3", 1),
                                                ("krl", 0), ("urscript", 0)])
def test_programmed_tcp_acceleration(target: str, warned: int) -> None:
    """A non-default TCP acceleration: W408 once per task where the vendor cannot express it."""
    result = emit(target, (move(1, L, tcp_accel=0.5), move(2, L, tcp_accel=0.7)))
    assert ids(result).count("W408") == warned


@pytest.mark.parametrize("target", ["rapid", "fanuc", "inform", "val3", "krl", "urscript"])
def test_programmed_joint_acceleration(target: str) -> None:
    """A joint move at 50 % acceleration: VAL3 mdesc, KRL $ACC_AXIS, URScript a=, RAPID AccSet,
    Fanuc ACC and INFORM ACC=/DEC= carry it (no W408)."""
    assert ids(emit(target, (move(1, J, joint_accel=0.5),))).count("W408") == 0


@pytest.mark.parametrize(("target", "form"), [("rapid", "AccSet 50, 100;"), ("fanuc", " CNT100 ACC50"),
                                              ("inform", " ACC=50 DEC=50")])
def test_joint_acceleration_share_is_written(target: str, form: str) -> None:
    """The vendors' own forms of an acceleration share: RAPID AccSet Acc (20..100 %, ABB RAPID
    reference), Fanuc motion option ACC (0..150 %, R-30iB Operator's Manual), INFORM ACC=/DEC=
    (20..100 %, YRC1000 INFORM manual); before the fix they were dropped with W408."""
    out = text(emit(target, (move(1, J, joint_accel=0.5), move(2, J))))
    assert form in out or form.replace(" CNT100", " FINE") in out, out


@pytest.mark.parametrize("target", ["rapid", "inform"])
def test_joint_acceleration_share_below_the_vendor_range_warns(target: str) -> None:
    """10 % is below AccSet's and ACC='s 20 %: not expressed, W408."""
    assert ids(emit(target, (move(1, J, joint_accel=0.1),))).count("W408") == 1


# --------------------------------------------------------------------------- 3. ports

def _port_instrs(port: int) -> tuple[ir.Instr, ...]:
    cond = ir.InputCondition(port=port, value=True)
    return (ir.SetDigital(uid=1, port=port, value=True, span=span_at(3)),
            ir.Pulse(uid=2, port=port, duration=0.2, span=span_at(4)),
            ir.WaitInput(uid=3, condition=cond, span=span_at(5)),
            ir.If(uid=4, condition=cond, then=(ir.WaitTime(uid=5, duration=1.0),), span=span_at(6)))


@pytest.mark.parametrize("target", controllers())
def test_every_vendor_documents_a_port_range(target: str) -> None:
    """DIGITAL_PORTS is the vendor's own (inclusive, non-empty) range."""
    low, high = BACKENDS[target].DIGITAL_PORTS
    assert 0 <= low < high


@pytest.mark.parametrize("target", controllers())
def test_ports_at_the_bounds_are_accepted(target: str) -> None:
    """The first and last port of DIGITAL_PORTS print without E404."""
    for port in BACKENDS[target].DIGITAL_PORTS:
        assert "E404" not in ids(emit(target, _port_instrs(port)))


@pytest.mark.parametrize("target", controllers())
def test_ports_outside_the_range_are_refused(target: str) -> None:
    """One past either bound is E404 for every I/O instruction (set, pulse, wait, if)."""
    low, high = BACKENDS[target].DIGITAL_PORTS
    for port in (low - 1, high + 1):
        assert ids(emit(target, _port_instrs(port))).count("E404") == 4, port


@pytest.mark.parametrize(("target", "port"), [("krl", 0), ("krl", 5000), ("fanuc", 0), ("fanuc", 5000)])
def test_krl_and_fanuc_refuse_out_of_range_outputs(target: str, port: int) -> None:
    """$OUT[0], $OUT[5000], DO[0], DO[5000] are not written (E404)."""
    result = emit(target, (ir.SetDigital(uid=1, port=port, value=True, span=span_at(3)),))
    assert ids(result) == ["E404"]
    assert f"[{port}]" not in text(result)


# --------------------------------------------------------------------------- 4. payload

TOOL = ir.ToolRef("gun", ir.Pose((0.02, -0.04, 0.2)), 2.0)


def test_rapid_tooldata_cog_half_way() -> None:
    """RAPID loaddata: 2 kg at (10, -20, 100) mm, half the TCP offset."""
    assert "[2.000,[10.000,-20.000,100.000]," in text(emit("rapid", (move(1, tool=TOOL),)))


def test_krl_load_cog_half_way() -> None:
    """KRL $LOAD: M 2 kg, CM at X 10, Y -20, Z 100 mm."""
    assert "M 2.000,CM {X 10.000,Y -20.000,Z 100.000," in text(emit("krl", (move(1, tool=TOOL),)))


def test_urscript_sets_payload_with_the_tcp() -> None:
    """URScript: set_payload(kg, [m]) right after set_tcp, half the TCP offset."""
    out = text(emit("urscript", (move(1, tool=TOOL),))).splitlines()
    at = next(i for i, ln in enumerate(out) if "set_tcp(" in ln)
    assert out[at + 1].strip() == "set_payload(2.000, [0.010000, -0.020000, 0.100000])"


@pytest.mark.parametrize("target", ["fanuc", "inform", "val3"])
def test_payload_the_program_cannot_carry_warns_once(target: str) -> None:
    """W411 once per tool and task, naming the mass and the centre of gravity to set."""
    result = emit(target, (move(1, tool=TOOL), move(2, tool=TOOL)))
    found = [d for d in result.diagnostics if d.code.id == "W411"]
    assert len(found) == 1
    assert "2.000 kg" in found[0].message and "[10.0,-20.0,100.0] mm" in found[0].message


@pytest.mark.parametrize("target", controllers())
def test_massless_tool_needs_no_payload_warning(target: str) -> None:
    """A tool without mass has nothing to set: no W411."""
    assert "W411" not in ids(emit(target, (move(1, tool=ir.ToolRef("pen", ir.Pose((0, 0, 0.1)))),)))


# --------------------------------------------------------------------------- 5. one meaning per code

@pytest.mark.parametrize(("target", "instr"), [
    ("fanuc", ir.WaitTime(uid=1, duration=0.255)), ("fanuc", ir.Pulse(uid=1, port=1, duration=0.25)),
    ("inform", ir.WaitTime(uid=1, duration=0.255)), ("inform", ir.Pulse(uid=1, port=1, duration=0.255)),
])
def test_time_rounding_is_w412(target: str, instr: ir.Instr) -> None:
    """Rounded times are W412 time-rounded."""
    assert ids(emit(target, (instr,))) == ["W412"]


def test_rapid_massless_tool_is_w413() -> None:
    """RAPID's 0.001 kg stand-in for a massless tool is W413 tool-mass-raised."""
    result = emit("rapid", (move(1, tool=ir.ToolRef("pen", ir.Pose((0, 0, 0.1)))),))
    assert ids(result) == ["W413"]


def test_new_codes_mean_one_thing() -> None:
    """W411, W412, W413 are distinct codes with distinct names."""
    found = [codes.PAYLOAD_NOT_EXPRESSED, codes.TIME_ROUNDED, codes.MASS_RAISED]
    assert len({c.id for c in found}) == len({c.name for c in found}) == 3


# --------------------------------------------------------------------------- 6. native vendors

@pytest.mark.parametrize("vendor", targets())
def test_front_end_accepts_exactly_the_registrys_controllers(vendor: str) -> None:
    """The front end's `native` check reads the backend registry: every controller is
    accepted, a target that is not a controller language (csv, json) is E116."""
    from rmot.compiler.frontend import load_text

    text = f'program p on r1 {{\n  native {vendor} "x"\n}}\n'
    found = {d.code.id for d in load_text(text, "native.rmot").diagnostics if d.is_error}
    assert found == (set() if vendor in controllers() else {"E116"})


@pytest.mark.parametrize("target", controllers())
def test_native_block_only_for_its_own_name(target: str) -> None:
    """A native block prints only under its own controller name; the old aliases are gone."""
    for alias in ("ur", "jbi", "yaskawa", "motoman", "staubli"):
        result = emit(target, (ir.Native(uid=1, vendor=alias, text="ALIAS_TEXT", span=span_at(3)),))
        assert "ALIAS_TEXT" not in text(result)
        assert ids(result) == ["W407"]
    own = emit(target, (ir.Native(uid=1, vendor=target, text="OWN_TEXT", span=span_at(3)),))
    assert "OWN_TEXT" in text(own) and ids(own) == []


def test_e407_is_not_registered() -> None:
    """E407 duplicated the front end's E116 and was unreachable: it is gone."""
    assert not any(getattr(c, "id", None) == "E407" for c in vars(codes).values())
