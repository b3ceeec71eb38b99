"""Proc calls whose routines would print the same share one routine on every vendor; calls
with different targets keep numbered routines (backends/lowering.routine_names,
Backend.routine_key)."""

from __future__ import annotations

import re

import pytest

from rmot.backends import BACKENDS
from rmot.backends.lowering import routine_names
from rmot.lang import ir, plan_types
from rmot.backends import controllers

PROGRAM = """
proc beep() {
  set out[1] = on
  wait 100 ms
  set out[1] = off
}

proc visit(p: pose) {
  move linear p
}

program dedupe on r1 {
  tool gripper
  frame table_top
  speed 250 mm/s
  target home = joints(0, -20, 30, 0, 50, 0) deg
  target a = pose(x=-100mm, y=50mm, z=200mm, rx=180deg)
  target b = pose(x=100mm, y=-50mm, z=150mm, rx=180deg)
  move joint home
  beep()
  move joint a
  beep()
  visit(a)
  visit(b)
  beep()
}
"""
VENDORS = controllers()

# vendor -> (regex of a routine's definition, regex of a call line), {r} = the routine name
SHAPES: dict[str, tuple[str, str]] = {
    "rapid": (r"^  PROC {r}\(\)$", r"^    {r};$"),
    "krl": (r"^DEF {r}\( \)$", r"^  {r}\(\)$"),
    "fanuc": (r"^/PROG  DEDUPE_{R}$", r"CALL DEDUPE_{R} ;$"),
    "urscript": (r"^  def {r}\(\):$", r"^  {r}\(\)$"),
    "inform": (r"^//NAME DEDUPE_{R}$", r"^CALL JOB:DEDUPE_{R}$"),
    "val3": (r'^  <Program name="{r}">$', r"^  call {r}\(\)$"),
}


@pytest.fixture(scope="module")
def plan(plan_from_text) -> plan_types.Plan:  # type: ignore[no-untyped-def]
    return plan_from_text(PROGRAM, "dedupe.rmot")


def count(files: dict[str, str], pattern: str, routine: str) -> int:
    rx = re.compile(pattern.format(r=routine, R=routine.upper()), re.M)
    return sum(len(rx.findall(text)) for text in files.values())


@pytest.mark.parametrize("vendor", VENDORS)
def test_proc_without_pose_is_one_routine(plan: plan_types.Plan, vendor: str) -> None:
    """beep() called 3 times: exactly one routine named `beep` and 3 calls of it."""
    files = BACKENDS[vendor]().emit(plan).files
    define, call = SHAPES[vendor]
    assert count(files, define, "beep") == 1
    assert count(files, call, "beep") == 3
    assert count(files, define, "beep_1") == 0


@pytest.mark.parametrize("vendor", VENDORS)
def test_different_targets_keep_numbered_routines(plan: plan_types.Plan, vendor: str) -> None:
    """visit(a) and visit(b) move to different targets: routines visit_1 and visit_2, one call each."""
    files = BACKENDS[vendor]().emit(plan).files
    define, call = SHAPES[vendor]
    assert [count(files, define, r) for r in ("visit", "visit_1", "visit_2")] == [0, 1, 1]
    assert [count(files, call, r) for r in ("visit_1", "visit_2")] == [1, 1]


@pytest.mark.parametrize("vendor", VENDORS)
def test_deterministic(plan: plan_types.Plan, vendor: str) -> None:
    """Two emissions of the same plan are byte-identical."""
    assert BACKENDS[vendor]().emit(plan).files == BACKENDS[vendor]().emit(plan).files


def test_source_map_points_at_calls_and_proc_body(plan: plan_types.Plan) -> None:
    """Each call line follows its call site's `file:line`; the shared routine's lines point at
    the proc body (lines 3..5), the same for every call."""
    text = BACKENDS["rapid"]().emit(plan).files["dedupe.mod"]
    main = text.split("PROC main()")[1].split("ENDPROC")[0].splitlines()
    call_refs = [main[i - 1].strip() for i, line in enumerate(main) if line.strip() == "beep;"]
    assert call_refs == ["! dedupe.rmot:20", "! dedupe.rmot:22", "! dedupe.rmot:25"]
    beep = text.split("PROC beep()")[1].split("ENDPROC")[0]
    assert re.findall(r"dedupe\.rmot:(\d+)", beep) == ["3", "4", "5"]


def _call(uid: int, proc: str, value: float) -> ir.ProcCall:
    wait = ir.WaitTime(uid=uid + 100, duration=value)
    return ir.ProcCall(uid=uid, proc=proc, args=(), body=(wait,))


class TestRoutineNamesWithKey:
    def test_equal_keys_share_and_variants_number_in_first_call_order(self) -> None:
        """Calls with equal keys share a name; a proc with one variant keeps its bare name."""
        body = (_call(1, "pick", 1.0), _call(2, "place", 0.5), _call(3, "pick", 2.0),
                _call(4, "pick", 1.0), _call(5, "place", 0.5))
        names = routine_names(body, key=lambda c: c.body[0].duration)  # type: ignore[union-attr]
        assert names == {1: "pick_1", 2: "place", 3: "pick_2", 4: "pick_1", 5: "place"}

    def test_without_key_every_call_is_its_own(self) -> None:
        """No key: the old behaviour, one routine per call."""
        body = (_call(1, "pick", 1.0), _call(2, "pick", 1.0))
        assert routine_names(body) == {1: "pick_1", 2: "pick_2"}


def test_same_argument_shares_a_routine(plan_from_text) -> None:  # type: ignore[no-untyped-def]
    """examples/pick_place.rmot calls grasp(nest) 6 times: one RAPID routine `grasp`, 6 calls;
    release() goes to 6 different slots: 6 numbered routines (its loops unrolled, --unroll:
    as vendor loops the release calls are written inline, see test_loops_emitted.py)."""
    from pathlib import Path

    path = Path(__file__).parents[2] / "examples" / "pick_place.rmot"
    files = BACKENDS["rapid"](unroll=True).emit(plan_from_text(path.read_text(encoding="utf-8"), str(path))).files
    define, call = SHAPES["rapid"]
    assert (count(files, define, "grasp"), count(files, call, "grasp")) == (1, 6)
    assert [count(files, define, f"release_{k}") for k in range(1, 8)] == [1, 1, 1, 1, 1, 1, 0]
