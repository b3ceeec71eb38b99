"""Two tasks on one Fanuc or Yaskawa controller share no register.

Registers are global on the controller (R-30iB Operator's Manual B-83284EN, "Register
instructions"; YRC1000 INSTRUCTIONS, variables B/I/D/R/P000..): two tasks numbering their loop
state, temporaries, loop offsets, frame setup and wait timers from the same first register would
overwrite each other. The witness reads every register reference out of the written text with
the vendors' own syntax (TP `R[n]`, `PR[n]`, `PR[n,j]`, `TIMER[n]`; INFORM `Bnnn`, `Dnnn`,
`Rnnn`, `Pnnn`), not through the backends' tables.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from backend_fixtures import ROOT, example_plans
from rmot.backends import BACKENDS
from rmot.lang import plan_types
from rmot.compiler.frontend import load_program
from rmot.compiler.plan import plan_program

PROGRAM = Path(__file__).parent / "programs" / "two_tasks.rmot"
_TP_REGISTER = re.compile(r"(?<![A-Z])(R|PR|TIMER)\[(\d+)")
_INFORM_VARIABLE = re.compile(r"\b([BIDRP])(\d{3})\b")


@pytest.fixture(scope="module")
def two_tasks() -> plan_types.Plan:
    front = load_program(str(PROGRAM), project_root=str(ROOT))
    assert front.program is not None, [d.message for d in front.diagnostics]
    return plan_program(front.program)


def _strip_comments(text: str, comment: str) -> str:
    return "\n".join(line.split(comment, 1)[0] for line in text.splitlines())


def tp_registers(text: str) -> set[str]:
    """Every R, PR and TIMER a TP file reads or writes (comments after `!` left out)."""
    body = "\n".join(line for line in text.splitlines() if not line.lstrip(" 0-9:").startswith("!"))
    return {f"{kind}[{n}]" for kind, n in _TP_REGISTER.findall(body)}


def inform_variables(text: str) -> set[str]:
    """Every B/I/D/R/P variable an INFORM job names in its instructions and //POS block."""
    return {f"{kind}{n}" for kind, n in _INFORM_VARIABLE.findall(_strip_comments(text, "'"))}


def _per_task(plan: plan_types.Plan, vendor: str) -> list[set[str]]:
    files = BACKENDS[vendor]().emit(plan).files
    read = tp_registers if vendor == "fanuc" else inform_variables
    out = []
    for task in plan.program.tasks:
        stem = f"_{task.name.upper()}"
        out.append(set().union(*(read(text) for name, text in files.items()
                                 if stem in name.upper())))
    return out


@pytest.mark.parametrize("vendor", ["fanuc", "inform"])
def test_two_tasks_share_no_register(two_tasks: plan_types.Plan, vendor: str) -> None:
    first, second = _per_task(two_tasks, vendor)
    assert first and second  # both tasks keep loop state: the check below can fail
    assert not first & second, sorted(first & second)


@pytest.mark.parametrize("vendor", ["fanuc", "inform"])
def test_handover_tasks_share_no_register(vendor: str) -> None:
    plan = example_plans(["handover"])["handover"]
    first, second = _per_task(plan, vendor)
    assert not first & second, sorted(first & second)


def test_second_task_takes_the_upper_half(two_tasks: plan_types.Plan) -> None:
    """The first task keeps R[1] (a single task's programs are unchanged); the second task's
    registers lie in the upper half of R[1..200]."""
    first, second = _per_task(two_tasks, "fanuc")
    assert "R[1]" in first and not any(r.startswith("R[") and int(r[2:-1]) <= 100 for r in second)
