"""Numbered tools and frames, stored data left alone, and the brand check.

A cell may give a tool or frame its controller number (`number n`). Fanuc, KRL and INFORM
then select that number and never write the controller's stored tool/frame data unless
`--write-frames`; without a number Fanuc keeps writing UTOOL/UFRAME through PRs, but says
so (W416). A program for a robot of another brand warns W415 at the robot's declaration.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable

import numpy as np
import pytest

from rmot.backends import BACKENDS
from rmot.lang import ir, plan_types
from rmot.sim.robots.library import SPECS
from rmot.lang.source import SourceFile

CELL = """
cell numbered {{
  robot r1 = {robot}
  tool gripper = none tcp pose(z=120mm) mass 1 kg {tool_number} on r1
  tool probe = none tcp pose(x=20mm, z=80mm) on r1
  frame fixt1 = pose(x=700mm, y=100mm, z=250mm, rz=30deg) {frame_number}
}}

program fixt on r1 {{
  tool gripper
  frame fixt1
  speed 200 mm/s
  target home = joints(0, 10, 10, 0, 60, 0) deg
  move joint home
  move linear pose(x=0mm, y=0mm, z=80mm, rx=180deg)
  move linear pose(x=40mm, y=-30mm, z=60mm, rx=180deg) tool probe
}}
"""


def _text(robot: str = "fanuc_m20ia", tool_number: str = "number 3", frame_number: str = "number 2") -> str:
    return CELL.format(robot=robot, tool_number=tool_number, frame_number=frame_number)


@pytest.fixture(scope="module")
def numbered(plan_from_text: Callable[..., plan_types.Plan]) -> plan_types.Plan:
    return plan_from_text(_text(), "numbered.rmot")


@pytest.fixture(scope="module")
def unnumbered(plan_from_text: Callable[..., plan_types.Plan]) -> plan_types.Plan:
    return plan_from_text(_text(tool_number="", frame_number=""), "unnumbered.rmot")


def _codes(result) -> list[str]:  # type: ignore[no-untyped-def]
    return [d.code.id for d in result.diagnostics]


# --------------------------------------------------------------------------- Fanuc

def test_fanuc_selects_numbered_tool_and_frame_and_writes_nothing(numbered: plan_types.Plan) -> None:
    result = BACKENDS["fanuc"]().emit(numbered)
    text = result.files["FIXT.ls"]
    assert "UTOOL_NUM=3 ;" in text and "UFRAME_NUM=2 ;" in text
    assert not re.search(r"UTOOL\[3\]=|UFRAME\[2\]=", text)
    assert "!UTOOL[3] = gripper must hold: ;" in text and "!UFRAME[2] = fixt1 must hold: ;" in text
    assert "UF : 2, UT : 3" in text
    # the unnumbered probe takes the smallest UTOOL no cell tool is given: 1, written (W416)
    assert "UTOOL_NUM=1 ;" in text and "UTOOL[1]=PR[91] ;" in text
    w416 = [d.message for d in result.diagnostics if d.code.id == "W416"]
    assert w416 == ["fanuc: tool 'probe' has no controller number: the program overwrites UTOOL[1] and "
                    "PR[91] (give it `number n` in the cell to select the taught one)"]


def test_fanuc_write_frames_writes_numbered_data(numbered: plan_types.Plan) -> None:
    text = BACKENDS["fanuc"](write_frames=True).emit(numbered).files["FIXT.ls"]
    assert "UTOOL[3]=PR[" in text and "UFRAME[2]=PR[" in text
    assert "must hold" not in text


def test_fanuc_without_numbers_overwrites_and_warns(unnumbered: plan_types.Plan) -> None:
    result = BACKENDS["fanuc"]().emit(unnumbered)
    text = result.files["FIXT.ls"]
    writes = re.findall(r"(UTOOL|UFRAME)\[(\d+)\]=PR\[(\d+)\]", text)
    assert sorted(writes) == [("UFRAME", "1", "93"), ("UTOOL", "1", "91"), ("UTOOL", "2", "92")]
    assert _codes(result).count("W416") == 3
    for d in result.diagnostics:
        if d.code.id == "W416":  # each names the slot and the register it overwrites
            assert re.search(r"overwrites (UTOOL|UFRAME)\[\d\] and PR\[9\d\]", d.message)
            assert d.span is not None and d.span.file.path == "unnumbered.rmot"


# --------------------------------------------------------------------------- KRL

def test_krl_selects_numbered_data(numbered: plan_types.Plan) -> None:
    src = BACKENDS["krl"]().emit(numbered).files["fixt.src"]
    assert "$TOOL=TOOL_DATA[3]" in src and "$LOAD=LOAD_DATA[3]" in src and "$BASE=BASE_DATA[2]" in src
    assert not re.search(r"^\s*(TOOL|BASE|LOAD)_DATA\[\d+\]=", src, re.M)
    assert "; TOOL_DATA[3] must hold gripper: {X 0.000,Y 0.000,Z 120.000" in src
    written = BACKENDS["krl"](write_frames=True).emit(numbered).files["fixt.src"]
    assert re.search(r"^\s*TOOL_DATA\[3\]=\{X 0.000,Y 0.000,Z 120.000", written, re.M)
    assert re.search(r"^\s*BASE_DATA\[2\]=\{X 700.000,Y 100.000,Z 250.000", written, re.M)


# --------------------------------------------------------------------------- INFORM

def _zyx(values: list[float]) -> np.ndarray:
    """X,Y,Z (mm), Rx,Ry,Rz (deg) as a 4x4 with R = Rz·Ry·Rx (INFORM's rectangular form),
    built here from elementary rotations (independent of the backend's conversion)."""
    x, y, z, rx, ry, rz = values
    a, b, c = (math.radians(v) for v in (rz, ry, rx))
    rz_m = np.array([[math.cos(a), -math.sin(a), 0], [math.sin(a), math.cos(a), 0], [0, 0, 1]])
    ry_m = np.array([[math.cos(b), 0, math.sin(b)], [0, 1, 0], [-math.sin(b), 0, math.cos(b)]])
    rx_m = np.array([[1, 0, 0], [0, math.cos(c), -math.sin(c)], [0, math.sin(c), math.cos(c)]])
    m = np.eye(4)
    m[:3, :3] = rz_m @ ry_m @ rx_m
    m[:3, 3] = (x, y, z)
    return m


def _positions(job: str) -> dict[str, list[float]]:
    return {k: [float(v) for v in vals.split(",")] for k, vals in re.findall(r"^(C\d{5})=(.*)$", job, re.M)}


def test_inform_numbered_tool_file_and_user_frame(numbered: plan_types.Plan, unnumbered: plan_types.Plan) -> None:
    """Positions in a numbered frame are written in `///USER n`; composed with the frame's
    pose (from the cell: x 700, y 100, z 250 mm, rz 30 deg) they are the ROBOT positions
    the same program gets without numbers."""
    job = BACKENDS["inform"]().emit(numbered).files["FIXT.JBI"]
    plain = BACKENDS["inform"]().emit(unnumbered).files["FIXT.JBI"]
    assert "///USER 2\n///TOOL 3\n///POSTYPE USER\n///RECTAN\n" in job
    assert "///USER" not in plain and "///TOOL 1" in plain
    frame = _zyx([700.0, 100.0, 250.0, 0.0, 0.0, 30.0])
    mine, theirs = _positions(job), _positions(plain)
    assert mine.keys() == theirs.keys() and len(mine) == 3
    for key in mine:
        np.testing.assert_allclose(frame @ _zyx(mine[key]), _zyx(theirs[key]), atol=2e-3)
    assert "'USER 2 = fixt1" in job and "'TOOL 3 = gripper" in job
    # the unnumbered probe takes the first tool file no cell tool is given
    assert "'TOOL 1 = probe" in job


# --------------------------------------------------------------------------- limits

@pytest.mark.parametrize(("vendor", "tool", "frame", "what"), [
    ("fanuc", "number 11", "number 2", "1..10 for UTOOL"),
    ("fanuc", "number 3", "number 10", "1..9 for UFRAME"),
    ("krl", "number 17", "number 2", "1..16 for TOOL_DATA"),
    ("krl", "number 3", "number 33", "1..32 for BASE_DATA"),
    ("inform", "number 64", "number 2", "0..63 for a tool file"),
    ("inform", "number 3", "number 64", "1..63 for a user frame"),
])
def test_numbers_outside_the_controller_are_refused(plan_from_text: Callable[..., plan_types.Plan], vendor: str,
                                                    tool: str, frame: str, what: str) -> None:
    plan = plan_from_text(_text(tool_number=tool, frame_number=frame), f"range_{vendor}.rmot")
    errors = [d for d in BACKENDS[vendor]().emit(plan).diagnostics if d.is_error]
    assert [d.code.id for d in errors][:1] == ["E410"] and what in errors[0].message


def test_negative_or_fractional_numbers_are_input_errors() -> None:
    from rmot.compiler.frontend import load_text

    for bad in ("number -1", "number 2.5"):
        front = load_text(_text(tool_number=bad), "bad.rmot")
        assert any(d.is_error for d in front.diagnostics), bad


# --------------------------------------------------------------------------- brand

@pytest.mark.parametrize("vendor", ["rapid", "krl", "fanuc", "urscript", "inform", "val3"])
def test_brand_warning_for_every_library_arm(vendor: str) -> None:
    """W415 at the robot's declaration exactly when the library's own vendor field (not the
    backend's name table) differs from the controller maker; arms of no controller maker
    (Unimation's PUMA) are not judged."""
    maker = {"rapid": "ABB", "krl": "KUKA", "fanuc": "FANUC", "urscript": "Universal Robots",
             "inform": "Yaskawa", "val3": "Staubli"}[vendor]
    backend = BACKENDS[vendor]()
    for name, spec in SPECS.items():
        span_file = SourceFile("cell.rmot", "robot r1\n")
        from rmot.lang.source import Pos, Span
        robot = ir.RobotInstance("r1", ir.RobotSource(ir.RobotSourceKind.LIBRARY, name), ir.Pose(), 6,
                                 span=Span(span_file, Pos(1, 1, 0), Pos(1, 6, 5)))
        backend._emission.diagnostics.clear()
        backend.check_brand(robot)
        found = [d for d in backend._emission.diagnostics if d.code.id == "W415"]
        expected = spec.vendor not in (maker, "Unimation")
        assert bool(found) == expected, (vendor, name, spec.vendor)
        if found:
            assert found[0].span is robot.span


def test_compile_write_frames_flag(tmp_path) -> None:  # type: ignore[no-untyped-def]
    """`rmot compile --write-frames` reaches the backends: KRL writes TOOL_DATA[2] of the
    tour's numbered gripper; without the flag it only selects it."""
    from pathlib import Path

    from click.testing import CliRunner

    from rmot.compiler.cli import cli

    tour = str(Path(__file__).parent / "programs" / "tour.rmot")
    for flag, written in (([], False), (["--write-frames"], True)):
        out = tmp_path / ("w" if written else "n")
        result = CliRunner().invoke(cli, ["compile", tour, "--target", "krl", "-o", str(out), *flag])
        assert result.exit_code == 0, result.output
        src = (out / "krl" / "tour.src").read_text(encoding="utf-8")
        assert "$TOOL=TOOL_DATA[2]" in src
        assert bool(re.search(r"^\s*TOOL_DATA\[2\]=\{", src, re.M)) == written
