"""Held parts' payload in the vendor programs: tests/data/parts/stack.rmot picks
two 2 kg cubes with a 1 kg gripper (TCP on the gripper's end face, 100 mm from the flange;
the gripper's own centre of gravity at half the TCP offset, 50 mm, rmot's convention). A
cube is held by its top face, so its centre is 50 mm beyond the TCP: 150 mm from the flange.
By hand: tool + cube = 3 kg at (1 * 50 + 2 * 150) / 3 = 116.667 mm from the flange; the cube
alone is 2 kg at +50 mm in the tool (TCP) frame.

Golden files: tests/backends/golden/<vendor>/parts_stack__<file>, reviewed by hand.
"""

from __future__ import annotations

import re
import warnings
from pathlib import Path

import pytest
from backend_fixtures import check_golden

from rmot.backends import BACKENDS
from rmot.compiler.frontend import load_program
from rmot.compiler.plan import plan_program

STACK = Path(__file__).resolve().parents[1] / "data" / "parts" / "stack.rmot"


@pytest.fixture(scope="module")
def plan():  # type: ignore[no-untyped-def]
    front = load_program(str(STACK))
    assert front.program is not None, [str(d) for d in front.diagnostics]
    return plan_program(front.program)


def _emit(plan, vendor: str):  # type: ignore[no-untyped-def]
    return BACKENDS[vendor]().emit(plan)


@pytest.mark.parametrize("vendor", ["rapid", "krl", "urscript"])
def test_matches_golden_files(plan, vendor: str) -> None:  # type: ignore[no-untyped-def]
    check_golden(vendor, "parts_stack", _emit(plan, vendor).files)


def _after(lines: list[str], marker: str) -> list[str]:
    """The first line after each source comment naming `marker`'s line."""
    return [lines[i + 1].strip() for i, line in enumerate(lines) if line.strip().endswith(marker)]


def _lines_of(source: str) -> dict[str, int]:
    return {w: i + 1 for i, line in enumerate(source.splitlines()) for w in ("attach b1", "detach b1", "attach b2", "detach b2") if line.strip() == w}


def test_rapid_grip_load_changes_at_attach_and_detach(plan) -> None:  # type: ignore[no-untyped-def]
    (text,) = _emit(plan, "rapid").files.values()
    at = _lines_of(STACK.read_text(encoding="utf-8"))
    lines = text.splitlines()
    assert _after(lines, f"stack.rmot:{at['attach b1']}") == ["GripLoad load_b1;"]
    assert _after(lines, f"stack.rmot:{at['detach b1']}") == ["GripLoad load0;"]
    assert _after(lines, f"stack.rmot:{at['attach b2']}") == ["GripLoad load_b2;"]
    decl = re.search(r"PERS loaddata load_b1:=\[([^,]+),\[([^\]]+)\]", text)
    assert decl is not None
    assert float(decl.group(1)) == 2.0
    assert [float(x) for x in decl.group(2).split(",")] == pytest.approx([0.0, 0.0, 50.0])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        from rapidchecker.cli import check_file

        assert [str(e) for e in check_file(text)] == []


def test_krl_load_is_tool_plus_part_and_stays_until_detach(plan) -> None:  # type: ignore[no-untyped-def]
    files = _emit(plan, "krl").files
    src = next(t for n, t in files.items() if n.endswith(".src"))
    dat = next(t for n, t in files.items() if n.endswith(".dat"))
    loads = {m.group(1): (float(m.group(2)), float(m.group(3)))
             for m in re.finditer(r"DECL LOAD (\w+)=\{M ([\d.]+),CM \{X [-\d.]+,Y [-\d.]+,Z ([-\d.]+)", dat)}
    assigned = [loads[name] for name in re.findall(r"\$LOAD=(\w+)", src)]
    masses = [m for m, _ in assigned]
    # tool alone, then tool + b1 for every motion until the detach, then alone, then tool + b2
    assert masses[0] == 1.0 and 3.0 in masses
    first = masses.index(3.0)
    assert assigned[first] == (3.0, pytest.approx(116.667, abs=1e-3))
    runs = [m for i, m in enumerate(masses) if i == 0 or m != masses[i - 1]]
    assert runs == [1.0, 3.0, 1.0, 3.0, 1.0]


def test_urscript_set_payload_at_attach_and_detach(plan) -> None:  # type: ignore[no-untyped-def]
    (text,) = _emit(plan, "urscript").files.values()
    calls = re.findall(r"set_payload\(([\d.]+), \[([^\]]+)\]\)", text)
    values = [(float(m), [float(c) for c in cog.split(",")]) for m, cog in calls]
    assert [m for m, _ in values] == [1.0, 3.0, 1.0, 3.0, 1.0]
    assert values[1][1] == pytest.approx([0.0, 0.0, 0.116667], abs=1e-6)
    assert values[2][1] == pytest.approx([0.0, 0.0, 0.05], abs=1e-6)


@pytest.mark.parametrize("vendor", ["inform", "val3"])
def test_vendors_without_payload_instructions_warn_once_per_part_with_the_numbers(plan, vendor: str) -> None:  # type: ignore[no-untyped-def]
    w = [d for d in _emit(plan, vendor).diagnostics if d.code.id == "W460"]
    assert len(w) == 2  # b1 and b2, each once
    assert all("3.000 kg" in d.message and "[0.0,0.0,116.7] mm" in d.message for d in w)


def test_krl_proc_called_empty_handed_and_holding_prints_two_routines(tmp_path: Path) -> None:
    """The same proc (fixed joint targets) before the attach and while holding b1: KRL writes
    it twice, with the tool's load and with tool + b1; a shared routine would carry one."""
    import shutil

    shutil.copy(STACK.parent / "cell.rmot", tmp_path / "cell.rmot")
    (tmp_path / "p.rmot").write_text("""use cell "cell.rmot"
proc wiggle() {
  move joint joints(0, -90, 90, -90, -90, 0) deg zone fine
  move joint joints(10, -90, 90, -90, -90, 0) deg zone fine
}
program p on r1 {
  tool gripper
  frame world
  move joint joints(0, -90, 90, -90, -90, 0) deg
  wiggle()
  move joint b1 * pose(z=150mm, rx=180deg)
  move linear b1 * pose(z=50mm, rx=180deg) zone fine
  attach b1
  move linear b1 * pose(z=150mm, rx=180deg) zone fine
  wiggle()
  move joint b1 * pose(z=150mm, rx=180deg)
  move linear b1 * pose(z=50mm, rx=180deg) zone fine
  detach b1
}
""", encoding="utf-8")
    front = load_program(str(tmp_path / "p.rmot"))
    assert front.program is not None, [str(d) for d in front.diagnostics]
    files = BACKENDS["krl"]().emit(plan_program(front.program)).files
    src = next(t for n, t in files.items() if n.endswith(".src"))
    routines = re.findall(r"DEF (wiggle\w*)\(", src)
    assert len(routines) == 2
    bodies = [src.split(f"DEF {r}(")[1].split("END")[0] for r in routines]
    assert {frozenset(re.findall(r"\$LOAD=(\w+)", b)) for b in bodies} == {frozenset({"gripper_load"}), frozenset({"gripper_load_b1"})}


def test_krl_moves_inside_a_loop_carry_the_held_part(tmp_path: Path) -> None:
    """A loop's moves after an attach write tool + part as $LOAD, as straight-line moves do
    (the parts walk went through if arms and proc calls only, so a KRL loop's moves
    wrote the bare tool's load while the part hung on it)."""
    program = _holding_program(tmp_path, "")
    files = BACKENDS["krl"]().emit(plan_program(program)).files
    src = next(t for n, t in files.items() if n.endswith(".src"))
    loop = src.split("FOR ")[1].split("ENDFOR")[0]
    assert len(re.findall(r"PTP ", loop)) == 2, loop
    assert re.findall(r"\$LOAD=(\w+)", loop) == ["gripper_load_b1"] * 2, loop


def test_urscript_blocks_keep_the_held_payload(tmp_path: Path) -> None:
    """A loop body and an `if` arm after an attach start with set_tcp and set_payload: the
    payload is tool + part (3 kg at 116.667 mm, the module docstring's hand computation), never
    the tool alone (1 kg), which would stay set after the `if` until the detach (a UR arm's
    payload drives its collision detection: URScript manual, set_payload)."""
    if_arm = """  if in[1] == on {
    move joint joints(5, -90, 90, -90, -90, 0) deg zone fine
  }
"""
    program = _holding_program(tmp_path, if_arm)
    (text,) = BACKENDS["urscript"]().emit(plan_program(program)).files.values()
    calls = re.findall(r"set_payload\(([\d.]+), \[([^\]]+)\]\)", text)
    masses = [float(m) for m, _ in calls]
    assert masses[0] == 1.0 and masses[-1] == 1.0  # before the attach, after the detach
    between = masses[masses.index(3.0): len(masses) - 1]
    assert between and set(between) == {3.0}, masses
    for _, cog in calls[masses.index(3.0): len(masses) - 1]:
        assert [float(c) for c in cog.split(",")] == pytest.approx([0.0, 0.0, 0.116667], abs=1e-6)


def _holding_program(tmp_path: Path, after_loop: str):  # type: ignore[no-untyped-def]
    """A program that holds b1 through a loop, with `after_loop` inserted after the loop (the
    part still held)."""
    import shutil

    shutil.copy(STACK.parent / "cell.rmot", tmp_path / "cell.rmot")
    (tmp_path / "p.rmot").write_text("""use cell "cell.rmot"
program p on r1 {
  tool gripper
  frame world
  move joint joints(0, -90, 90, -90, -90, 0) deg
  move joint b1 * pose(z=150mm, rx=180deg)
  move linear b1 * pose(z=50mm, rx=180deg) zone fine
  attach b1
  move linear b1 * pose(z=150mm, rx=180deg) zone fine
  repeat 2 {
    move joint joints(10, -90, 90, -90, -90, 0) deg zone fine
    move joint joints(0, -90, 90, -90, -90, 0) deg zone fine
  }
""" + after_loop + """  move joint b1 * pose(z=150mm, rx=180deg)
  move linear b1 * pose(z=50mm, rx=180deg) zone fine
  detach b1
}
""", encoding="utf-8")
    front = load_program(str(tmp_path / "p.rmot"))
    assert front.program is not None, [str(d) for d in front.diagnostics]
    return front.program


def test_fanuc_selects_a_payload_schedule_per_load(plan) -> None:  # type: ignore[no-untyped-def]
    """PAYLOAD[i] at each attach and detach (R-30iB "Payload instruction"): one schedule per
    distinct load, W460 once per schedule with the numbers computed by hand above."""
    result = _emit(plan, "fanuc")
    text = "\n".join(result.files.values())
    assert [int(i) for i in re.findall(r"PAYLOAD\[(\d+)\]", text)] == [1, 2, 1, 2]
    w = {int(re.search(r"schedule (\d+)", d.message).group(1)): d.message  # type: ignore[union-attr]
         for d in result.diagnostics if d.code.id == "W460"}
    assert sorted(w) == [1, 2]
    assert "3.000 kg" in w[1] and "[0.0,0.0,116.7] mm" in w[1]
    assert "1.000 kg" in w[2] and "[0.0,0.0,50.0] mm" in w[2]
