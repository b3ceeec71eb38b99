"""Names that cannot collide: a proc or target named like something the vendor's
language defines is renamed with W414; names equal after the vendor's length and case rules
are made unique (W401). Checked on the emitted text: every routine defined once, every call
names a routine the program defines, and no definition takes a built-in's name."""

from __future__ import annotations

import re
from collections.abc import Callable

import pytest

from rmot.backends import BACKENDS
from rmot.lang import plan_types

PROGRAM = """
proc movel() {
  wait 100 ms
}

proc sleep() {
  wait 200 ms
}

proc delay() {
  wait 300 ms
}

proc PickPartFromConveyorBeltNumberOne() {
  wait 400 ms
}

proc pickpartfromconveyorbeltnumbertwo() {
  wait 500 ms
}

program names on r1 {
  movel()
  sleep()
  delay()
  PickPartFromConveyorBeltNumberOne()
  pickpartfromconveyorbeltnumbertwo()
}
"""

# vendor -> (regex of a routine definition, regex of a call), group 1 = the name
SHAPES: dict[str, tuple[str, str]] = {
    "rapid": (r"^  PROC (\w+)\(\)$", r"^    (\w+);$"),
    "krl": (r"^DEF (\w+)\( \)$", r"^  (\w+)\(\)$"),
    "fanuc": (r"^/PROG  (\w+)$", r"CALL (\w+) ;$"),
    "urscript": (r"^  def (\w+)\(\):$", r"^  (\w+)\(\)$"),
    "inform": (r"^//NAME (\w+)$", r"^CALL JOB:(\w+)$"),
    "val3": (r'^  <Program name="(\w+)">$', r"^  call (\w+)\(\)$"),
}
# what each language itself defines with those names (manual function/instruction lists)
BUILTINS = {"rapid": {"movel"}, "krl": set(), "fanuc": set(), "urscript": {"movel", "sleep"},
            "inform": set(), "val3": {"movel", "delay"}}


@pytest.fixture(scope="module")
def plan(plan_from_text: Callable[..., plan_types.Plan]) -> plan_types.Plan:
    return plan_from_text(PROGRAM, "names.rmot")


@pytest.mark.parametrize("vendor", sorted(SHAPES))
def test_routines_unique_and_never_builtins(plan: plan_types.Plan, vendor: str) -> None:
    result = BACKENDS[vendor]().emit(plan)
    assert not result.has_errors
    define, call = SHAPES[vendor]
    text = "\n".join(result.files.values())
    defined = re.findall(define, text, re.M)
    calls = re.findall(call, text, re.M)
    def key(n: str) -> str:  # every one of these controllers compares names case-insensitively
        return n.upper()

    routines = [d for d in defined if key(d) != key(defined[0])] if vendor in ("fanuc", "inform", "krl") else defined
    assert len({key(d) for d in defined}) == len(defined), defined
    assert len(calls) == 5 and {key(c) for c in calls} <= {key(d) for d in defined}, (calls, defined)
    assert len({key(c) for c in calls}) == 5, calls
    assert not {key(d) for d in routines} & {key(b) for b in BUILTINS[vendor]}, routines
    if BUILTINS[vendor]:
        assert "W414" in {d.code.id for d in result.diagnostics}
