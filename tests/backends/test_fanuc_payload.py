"""Fanuc TP switches the payload at every attach and detach with `PAYLOAD[i]`.

TP's payload instruction selects payload schedule i (R-30iB Operator's Manual B-83284EN,
"Payload instruction", schedules 1..10); the schedule's mass and centre of gravity are entered on
the controller, and W460 gives them. The witness: the masses are summed here from the cell file's
own numbers (examples/cells/two_arms.rmot: gripper 1.2 kg, gripper2 0.8 kg, block 0.5 kg), and
the programs are read with the TP syntax checker of vendor_validators.py.
"""

from __future__ import annotations

import re

from backend_fixtures import example_plans
from rmot.backends import BACKENDS
from vendor_validators import check_fanuc

GRIPPER, GRIPPER2, BLOCK = 1.2, 0.8, 0.5  # kg, examples/cells/two_arms.rmot


def _emit():  # type: ignore[no-untyped-def]
    return BACKENDS["fanuc"]().emit(example_plans(["handover"])["handover"])


def _switches(text: str) -> list[tuple[str, int]]:
    """(attach|detach, the schedule the next line selects) in program order."""
    lines = [re.sub(r"^\s*\d+:\s+", "", line).rstrip(" ;") for line in text.splitlines()]
    return [(m.group(1), int(n.group(1))) for line, nxt in zip(lines, lines[1:])
            if (m := re.match(r"^!(attach|detach) block", line)) and (n := re.match(r"^PAYLOAD\[(\d+)\]$", nxt))]


def test_each_attach_and_detach_selects_a_payload_schedule() -> None:
    result = _emit()
    assert check_fanuc(dict(result.files)) == []
    for name, text in result.files.items():
        assert _switches(text) == [("attach", 1), ("detach", 2)], name


def test_w460_gives_each_schedule_the_held_load() -> None:
    messages = [d.message for d in _emit().diagnostics if d.code.id == "W460"]
    masses = sorted(float(m) for msg in messages for m in re.findall(r"must hold ([\d.]+) kg", msg))
    assert masses == sorted([GRIPPER + BLOCK, GRIPPER, GRIPPER2 + BLOCK, GRIPPER2])
    for msg in messages:
        k = re.search(r"payload schedule (\d+)", msg)
        assert k is not None and f"PAYLOAD[{k.group(1)}]" in msg
