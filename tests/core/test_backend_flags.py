"""The Backend class flags that replaced the wrappers bolted onto Backend after its class:
PRINTS_LOOPS (a vendor prints `for`/`repeat` as loops; otherwise `lowered_plan` unrolls them
before anything is printed) must agree with the class's Loop printer, checked when the class
is made; RUNTIME_CONDITIONS (a vendor writes and/or/not, analog inputs, variables and timeout
branches; otherwise those are E165)."""

from __future__ import annotations

from pathlib import Path
from typing import ClassVar

import pytest

from rmot.backends import BACKENDS
from rmot.backends.base import Backend, TaskContext
from rmot.lang import ir, ir_tree
from rmot.compiler.frontend import load_program
from rmot.compiler.plan.planner import plan_program


def test_a_loop_printer_without_the_flag_is_refused() -> None:
    with pytest.raises(TypeError, match="PRINTS_LOOPS is False but its Loop printer is its own"):
        class _Own(Backend):
            def loop(self, node: ir.Loop, ctx: TaskContext) -> list[str]:
                return []


def test_the_flag_without_a_loop_printer_is_refused() -> None:
    with pytest.raises(TypeError, match="PRINTS_LOOPS is True but its Loop printer is the unrolling"):
        class _Flag(Backend):
            PRINTS_LOOPS: ClassVar[bool] = True


@pytest.mark.parametrize("target", sorted(BACKENDS))
def test_every_vendor_flag_matches_its_loop_printer(target: str) -> None:
    cls = BACKENDS[target]
    assert cls.PRINTS_LOOPS == (cls.loop is not Backend.loop)
    # the six controller languages print loops and runtime conditions; the data formats not
    controller = target not in ("csv", "json")
    assert cls.PRINTS_LOOPS is controller and cls.RUNTIME_CONDITIONS is controller


class _Seen(Backend):
    """Keeps the task body it was handed."""

    name: ClassVar[str] = "seen"
    bodies: ClassVar[list[tuple[ir.Instr, ...]]] = []

    def emit_task(self, ctx: TaskContext) -> dict[str, str]:
        self.bodies.append(ctx.task.body)
        return {}


def test_a_vendor_that_prints_no_loops_is_handed_the_unrolled_body(tmp_path: Path) -> None:
    path = tmp_path / "p.rmot"
    path.write_text("program p on r1 {\n  target home = joints(0, -10, 10, 0, 90, 0) deg\n"
                    "  move joint home\n  repeat 3 { wait 10 ms }\n}\n", encoding="utf-8")
    result = load_program(str(path))
    assert result.program is not None, [d.message for d in result.diagnostics]
    plan = plan_program(result.program)
    assert any(isinstance(n, ir.Loop) for n in ir_tree.walk(plan.tasks[0].task.body))
    _Seen.bodies.clear()
    _Seen().emit(plan)
    (body,) = _Seen.bodies
    assert not any(isinstance(n, ir.Loop) for n in ir_tree.walk(body))
    assert sum(isinstance(n, ir.WaitTime) for n in ir_tree.walk(body)) == 3  # three iterations
