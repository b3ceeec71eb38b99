"""External axes in INFORM jobs, read back by a witness that is not the backend's code.

The cell of test_ext_axes_emit.py (a KR 16 on a 4 m track, a 2-axis positioner) with each
axis' pulse scale declared. The job is read with small regular expressions written from the
job data format (`///NPOS C,BC,EC,P,BP,EX`, `Cnnnnn=X,Y,Z,Rx,Ry,Rz` in ROBOT coordinates with
R = Rz(Rz) Ry(Ry) Rx(Rx), `BCnnnnn=` / `ECnnnnn=` whole pulses, `MOVx Cn BCn ... +MOVJ ECn`);
each target is re-expanded through the cell composed with plain numpy (ext_axes_witness.py):
the arm's base on the carriage at BC / 200 mm, the part frame on the positioner at EC / scale
degrees. That must equal the planned TCP, in world and in the part frame, within 0.01 mm.
The header is checked against the positions the job defines and the operands it uses."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
from ext_axes_plans import planned as plan_text
from ext_axes_witness import at, robot_base, rot, work_frame
from test_ext_axes_emit import SOURCE

from rmot.backends import BACKENDS
from rmot.lang import ir
from rmot.compiler.frontend import load_text
from rmot.lang.plan_types import Plan

RAIL_PER_MM, TILT_PER_DEG, TURN_PER_DEG = 200.0, 1019.6889, 500.0  # declared below, as machine data
BINDINGS = (("accel 2000 mm/s^2 at", f"accel 2000 mm/s^2 inform(pulses_per_mm={RAIL_PER_MM:g}) at"),
            ("accel 180 deg/s^2,", f"accel 180 deg/s^2 inform(pulses_per_deg={TILT_PER_DEG:g}),"),
            ("accel 360 deg/s^2)", f"accel 360 deg/s^2 inform(pulses_per_deg={TURN_PER_DEG:g}))"))
TOL_M = 1e-5  # 0.01 mm


def with_bindings(source: str, bindings: tuple[tuple[str, str], ...] = BINDINGS) -> str:
    for old, new in bindings:
        assert source.count(old) == 1, old
        source = source.replace(old, new)
    return source


def _plan(source: str) -> Plan:
    return plan_text(source, "/tmp/ext_axes_inform.rmot")


@pytest.fixture(scope="module")
def plan() -> Plan:
    return _plan(with_bindings(SOURCE))


@pytest.fixture(scope="module")
def job(plan: Plan) -> str:
    result = BACKENDS["inform"]().emit(plan)
    assert not result.has_errors, [d.message for d in result.diagnostics if d.is_error]
    assert [d.code.id for d in result.diagnostics if d.code.id in ("W604", "W605")] == ["W604"]  # the station's own VJ, once
    (text,) = result.files.values()
    return text


def _ints(text: str) -> list[int]:
    return [int(v) for v in text.split(",")]


def read_moves(text: str) -> list[tuple[np.ndarray, int, list[int]]]:
    """(the TCP in ROBOT coordinates, BC pulses, EC pulses) of every move line, in order."""
    assert "///USER" not in text and "///POSTYPE USER" not in text  # every C in ROBOT coordinates
    cs = {k: [float(v) for v in vals.split(",")] for k, vals in re.findall(r"^(C\d{5})=(.*)$", text, re.M)}
    bcs = {k: _ints(v) for k, v in re.findall(r"^(BC\d{5})=(.*)$", text, re.M)}
    ecs = {k: _ints(v) for k, v in re.findall(r"^(EC\d{5})=(.*)$", text, re.M)}
    out = []
    for c, bc, ec in re.findall(r"^MOV[JLC] (C\d{5}) (BC\d{5}) .*\+MOVJ (EC\d{5}) VJ=[\d.]+$", text, re.M):
        x, y, z, rx, ry, rz = cs[c]
        pose = at(x / 1000, y / 1000, z / 1000) @ rot("z", rz) @ rot("y", ry) @ rot("x", rx)
        (rail,) = bcs[bc]
        out.append((pose, rail, ecs[ec]))
    return out


def planned(plan: Plan) -> list[tuple[np.ndarray, dict[str, float]]]:
    """(world TCP, axis values) of every move: the base on the track at the move's rail value
    times the planned TCP in the base frame (InstructionRecord.tcp_pose)."""
    tp = plan.tasks[0]
    out = []
    for move in tp.task.body:
        if isinstance(move, ir.Move):
            rec = tp.record(move.uid)
            assert rec is not None and rec.tcp_pose is not None
            ext = dict(move.ext)
            out.append((robot_base(ext["rail"] * 1000) @ rec.tcp_pose.matrix(), ext))
    return out


def test_targets_re_expand_to_the_planned_tcp_in_world_and_part_frame(plan: Plan, job: str) -> None:
    got, want = read_moves(job), planned(plan)
    assert len(got) == len(want) == 7  # every move, `move axes` too (the arm held at its joints)
    for (pose, rail, (tilt, turn)), (world, ext) in zip(got, want, strict=True):
        assert abs(rail - ext["rail"] * 1000 * RAIL_PER_MM) <= 0.5  # whole pulses
        assert abs(tilt - math.degrees(ext["pos.1"]) * TILT_PER_DEG) <= 0.5
        assert abs(turn - math.degrees(ext["pos.2"]) * TURN_PER_DEG) <= 0.5
        tcp = robot_base(rail / RAIL_PER_MM) @ pose
        assert np.abs(tcp[:3, 3] - world[:3, 3]).max() < TOL_M
        assert np.abs(tcp[:3, :3] - world[:3, :3]).max() < 1e-5  # Rx Ry Rz printed with 4 decimals
        part = np.linalg.inv(work_frame(tilt / TILT_PER_DEG, turn / TURN_PER_DEG)) @ tcp
        part_planned = np.linalg.inv(work_frame(math.degrees(ext["pos.1"]), math.degrees(ext["pos.2"]))) @ world
        assert np.abs(part[:3, 3] - part_planned[:3, 3]).max() < TOL_M


def test_the_header_counts_what_the_job_defines_and_uses(job: str) -> None:
    pos, inst = job.split("//INST\n")
    counts = [len(re.findall(rf"^{kind}\d+=", pos, re.M)) for kind in ("C", "BC", "EC", "P", "BP", "EX")]
    npos = re.search(r"^///NPOS (.*)$", pos, re.M)
    assert npos is not None and [int(v) for v in npos.group(1).split(",")] == counts
    assert counts == [7, 7, 7, 0, 0, 0]  # no circular move: one C, BC and EC per move
    defined = set(re.findall(r"^((?:B|E)?C\d{5})=", pos, re.M))
    used = set(re.findall(r"\b((?:B|E)?C\d{5})\b", inst))
    assert used == defined
    # the robot with its base axis in group 1, the station in group 2 (before NOP)
    head = inst.split("NOP\n")[0].splitlines()
    assert head[-2:] == ["///GROUP1 RB1,BS1", "///GROUP2 ST1"]
    for line in re.findall(r"^MOV.*$", inst, re.M):
        assert re.fullmatch(r"MOV[JLC] C\d{5} BC\d{5} (VJ|V)=[\d.]+( PL=\d)?( ACC=\d+ DEC=\d+)?( FPT)? \+MOVJ EC\d{5} VJ=[\d.]+", line), line


def test_a_track_alone_is_group_one_with_its_base_axis() -> None:
    source = with_bindings(SOURCE, BINDINGS[:1]).replace("with rail, pos", "with rail")
    source = re.sub(r" ext\(rail=(\d+mm), pos=\([^)]*\)\)", r" ext(rail=\1)", source)
    source = "\n".join(ln for ln in source.splitlines() if "frame work" not in ln and "move axes" not in ln)
    result = BACKENDS["inform"]().emit(_plan(source))
    assert not result.has_errors, [d.message for d in result.diagnostics if d.is_error]
    (text,) = result.files.values()
    assert "///GROUP1 RB1,BS1\nNOP" in text and "EC0" not in text and "+MOVJ" not in text
    assert re.search(r"^///NPOS (\d+),\1,0,0,0,0$", text, re.M)


ASSUMED_PER_DEG = 100000 / 360  # Visual Components' Yaskawa post's fallback: 100000 pulses per turn


def _bc_values(text: str) -> tuple[dict[str, float], str]:
    """The BC values and the data form (///RECTAN or ///PULSE) they stand under."""
    pos = text.split("//INST")[0].splitlines()
    form, found, forms = "", {}, set()
    for ln in pos:
        if ln in ("///RECTAN", "///PULSE"):
            form = ln
        m = re.fullmatch(r"(BC\d{5})=(-?[\d.]+)", ln)
        if m:
            found[m.group(1)] = float(m.group(2))
            forms.add(form)
    assert len(forms) == 1, forms
    return found, forms.pop()


def test_no_declared_scale_writes_the_track_in_mm_and_the_station_at_the_flagged_assumed_scale() -> None:
    """Without inform(...) the job still compiles: the track's BC in mm under ///RECTAN, the
    station's EC in pulses at 100000 per turn, flagged W610 and in the header checklist; the
    targets re-expand from the job's text to the planned TCP in world within 0.01 mm."""
    plan = _plan(SOURCE)
    result = BACKENDS["inform"]().emit(plan)
    assert not result.has_errors, [d.message for d in result.diagnostics if d.is_error]
    (w610,) = [d for d in result.diagnostics if d.code.id == "W610"]
    assert "'pos.1', 'pos.2'" in w610.message and w610.span is not None and w610.span.start.line == 14
    (text,) = result.files.values()
    bcs, form = _bc_values(text)
    assert form == "///RECTAN"
    assert "ASSUMED (not declared): c" in text and "BC in mm (rectan" in text
    moves = re.findall(r"^MOV[JLC] (C\d{5}) (BC\d{5}) .*\+MOVJ (EC\d{5}) VJ=[\d.]+$", text, re.M)
    cs = {k: [float(v) for v in vals.split(",")] for k, vals in re.findall(r"^(C\d{5})=(.*)$", text, re.M)}
    ecs = {k: _ints(v) for k, v in re.findall(r"^(EC\d{5})=(.*)$", text, re.M)}
    want = planned(plan)
    assert len(moves) == len(want) == 7
    for (c, bc, ec), (world, ext) in zip(moves, want, strict=True):
        assert bcs[bc] == pytest.approx(ext["rail"] * 1000, abs=5e-4)
        tilt, turn = ecs[ec]
        assert abs(tilt - math.degrees(ext["pos.1"]) * ASSUMED_PER_DEG) <= 0.5
        assert abs(turn - math.degrees(ext["pos.2"]) * ASSUMED_PER_DEG) <= 0.5
        x, y, z, rx, ry, rz = cs[c]
        tcp = robot_base(bcs[bc]) @ at(x / 1000, y / 1000, z / 1000) @ rot("z", rz) @ rot("y", ry) @ rot("x", rx)
        assert np.abs(tcp[:3, 3] - world[:3, 3]).max() < TOL_M


def test_a_declared_track_scale_keeps_the_pulse_form() -> None:
    result = BACKENDS["inform"]().emit(_plan(with_bindings(SOURCE, BINDINGS[:1])))
    assert not result.has_errors
    (text,) = result.files.values()
    bcs, form = _bc_values(text)
    assert form == "///PULSE" and bcs["BC00001"] == 1200 * RAIL_PER_MM
    assert [d.code.id for d in result.diagnostics].count("W610") == 1  # the station still assumed


@pytest.mark.parametrize("binding, code, at_text, message", [
    ("inform(pulses_per_mm=0)", "E608", "0)", "pulses_per_mm of axis 'rail' must be a finite number > 0 (got 0)"),
    ("inform(pulses_per_mm=-200)", "E608", "-200)", "pulses_per_mm of axis 'rail' must be a finite number > 0 (got -200)"),
    ("inform(pulses_per_deg=200)", "E608", "inform(", "binding of axis 'rail' must be inform(pulses_per_mm=N)"),
    ("inform(200)", "E608", "inform(", "binding of axis 'rail' must be inform(pulses_per_mm=N)"),
    # non-finite and absurd numbers never reach the binding: the front end refuses them where written
    ("inform(pulses_per_mm=1e999)", "E013", "1e999", "must fit a 64-bit float"),
    ("inform(pulses_per_mm=1e308*10)", "E125", "1e308", "must be at most 1e+09"),
])
def test_a_bad_scale_is_a_located_error(binding: str, code: str, at_text: str, message: str) -> None:
    source = with_bindings(SOURCE, ((BINDINGS[0][0], f"accel 2000 mm/s^2 {binding} at"),))
    front = load_text(source, "/tmp/bad_scale.rmot")
    errors = [d for d in front.diagnostics if d.is_error]
    assert errors and errors[0].code.id == code, [d.message for d in errors]
    assert {d.code.id for d in errors} <= {code, "E608"}  # a number the lexer refused reads as 0 after
    assert message in errors[0].message
    span = errors[0].span
    assert span is not None and span.start.line == 2
    assert source.splitlines()[1][span.start.col - 1:].startswith(at_text)


def test_a_coarse_scale_warns_that_whole_pulses_move_the_target() -> None:
    """At 0.25 pulses/deg the turn's 90 deg is 22.5 pulses, written 22 (88 deg): the part turns
    2 deg away, far more than 0.01 mm at the torch; the first move (every axis at 0) is exact."""
    coarse = ((BINDINGS[2][0], "accel 360 deg/s^2 inform(pulses_per_deg=0.25))"),)
    result = BACKENDS["inform"]().emit(_plan(with_bindings(with_bindings(SOURCE, BINDINGS[:2]), coarse)))
    warned = [d for d in result.diagnostics if d.code.id == "W605"]
    assert len(warned) == 1 and warned[0].span is not None and warned[0].span.start.line == 15  # pos.2 = 90 deg
    assert not result.has_errors


def test_a_loop_in_a_numbered_frame_shifts_in_robot_coordinates() -> None:
    """With external axes every position is in ROBOT coordinates, so a loop's shift is too
    (RF, no user frame the job would need stored): 50 mm along the frame's x, turned 30 deg
    about z, is (50 cos 30, 50 sin 30) = (43.301, 25.000) mm in 0.001 mm steps."""
    source = with_bindings(SOURCE, BINDINGS[:1]).split("program p")[0] + """program p on r1 with rail {
  move joint joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg) ext(rail=700mm)
  for i in 0 .. 3 {
    move linear pose(x=i*50mm, z=100mm, rx=180deg) frame table
  }
}
"""
    source = re.sub(r"  positioner pos = .*?at pose\(x=1800mm, z=700mm\)\n", "", source, flags=re.S)
    source = "\n".join(ln for ln in source.splitlines() if "on pos" not in ln and "pos *" not in ln)
    result = BACKENDS["inform"]().emit(_plan(source))
    assert not result.has_errors, [d.message for d in result.diagnostics if d.is_error]
    (text,) = result.files.values()
    assert "UF#" not in text and "///USER" not in text and "SFTON P050 RF" in text
    steps = [int(v) for v in re.findall(r"^MUL D\d+ (-?\d+)$", text, re.M)]
    assert steps == [round(50000 * math.cos(math.radians(30))), round(50000 * math.sin(math.radians(30)))]


def test_two_positioners_are_refused_one_station_group() -> None:
    second = ("  fixture jig", "  positioner turn = axes(revolute(axis z, range(-180deg, 180deg)) speed 90 deg/s "
              "accel 180 deg/s^2 inform(pulses_per_deg=100)) at pose(x=-1500mm, z=600mm)\n  fixture jig")
    source = with_bindings(SOURCE, (*BINDINGS, second, ("with rail, pos", "with rail, pos, turn")))
    result = BACKENDS["inform"]().emit(_plan(source))
    errors = [d for d in result.diagnostics if d.is_error]
    assert [d.code.id for d in errors] == ["E607"] and not result.files
    assert "at most one positioner" in errors[0].message and "pos, turn" in errors[0].message


def test_a_track_alone_without_its_scale_is_all_rectangular_and_unflagged() -> None:
    """No station: nothing is assumed (no W610), and the job has no pulse data at all."""
    source = SOURCE.replace("with rail, pos", "with rail")
    source = re.sub(r" ext\(rail=(\d+mm), pos=\([^)]*\)\)", r" ext(rail=\1)", source)
    source = "\n".join(ln for ln in source.splitlines() if "frame work" not in ln and "move axes" not in ln)
    result = BACKENDS["inform"]().emit(_plan(source))
    assert not result.has_errors and "W610" not in [d.code.id for d in result.diagnostics]
    (text,) = result.files.values()
    bcs, form = _bc_values(text)
    assert form == "///RECTAN" and "///PULSE" not in text and list(bcs.values()) == [0.0, 700.0, 0.0]
