"""The backends' base fallback for runtime logic: a vendor without its own loop
writing gets every Loop unrolled (the loop variable bound to each value), and var, assignment,
while, stop, general conditions and timeout branches are E165 — never dropped silently.

A minimal Backend subclass stands in for a vendor (the real vendors write these nodes in their
own branches), so the test holds whatever they do.
"""

from __future__ import annotations

from pathlib import Path
from typing import ClassVar

from rmot.backends.base import Backend, TaskContext
from rmot.lang import ir
from rmot.compiler.frontend import load_program
from rmot.compiler.ir_dump import rt_text
from rmot.compiler.plan.planner import plan_program


class _Printer(Backend):
    """One line per leaf instruction: its kind and, for an if, its condition."""

    name: ClassVar[str] = "printer"

    def emit_task(self, ctx: TaskContext) -> dict[str, str]:
        return {"out.txt": "\n".join(self.body(ctx.task.body, ctx)) + "\n"}

    def move(self, node: ir.Move, ctx: TaskContext) -> list[str]:
        return [f"move {node.uid}"]

    def wait_time(self, node: ir.WaitTime, ctx: TaskContext) -> list[str]:
        return [f"wait {node.uid}"]

    def wait_input(self, node: ir.WaitInput, ctx: TaskContext) -> list[str]:
        return [f"wait_input {node.uid}"]

    def if_(self, node: ir.If, ctx: TaskContext) -> list[str]:
        return [f"if {rt_text(node.condition)}", *self.body(node.then, ctx), "endif"]

    def source_comment(self, node: ir.Instr, ctx: TaskContext) -> str | None:
        return None


def _plan(tmp_path: Path, body: str):  # type: ignore[no-untyped-def]
    path = tmp_path / "p.rmot"
    path.write_text(
        "program p on r1 {\n  target home = joints(0, -10, 10, 0, 90, 0) deg\n  move joint home\n"
        f"{body}\n}}\n",
        encoding="utf-8",
    )
    result = load_program(str(path))
    assert result.program is not None, [d.message for d in result.diagnostics]
    return plan_program(result.program)


def test_loops_are_unrolled_with_the_loop_variable_bound(tmp_path: Path) -> None:
    plan = _plan(
        tmp_path,
        """
  var n = 0
  for i in 0 .. 2 {
    for j in 1 .. 3 {
      if n < i * 10 + j { wait 10 ms }
    }
  }
""",
    )

    class _Conditions(_Printer):
        RUNTIME_CONDITIONS: ClassVar[bool] = True

        def var_decl(self, node: ir.VarDecl, ctx: TaskContext) -> list[str]:
            return ["var"]

    result = _Conditions().emit(plan)
    lines = result.files["out.txt"].splitlines()
    conds = [ln for ln in lines if ln.startswith("if ")]
    assert conds == [
        f"if (n < {i * 10 + j})" for i in (0, 1) for j in (1, 2)
    ]  # folded by hand: i*10+j
    assert lines.count("endif") == 4 and not result.has_errors


def test_runtime_nodes_without_a_vendor_handler_are_e165(tmp_path: Path) -> None:
    plan = _plan(
        tmp_path,
        """
  var n = 0
  while in[2] == on { n = n + 1 }
  if in[1] == on and n > 2 { wait 10 ms }
  wait until in[1] == on timeout 1 s else { stop }
""",
    )
    result = _Printer().emit(plan)
    e165 = [d for d in result.diagnostics if d.code.id == "E165"]
    kinds = sorted(d.message.removeprefix("printer: ").split(" must")[0] for d in e165)
    # the assignment is inside the while, whose body is not written at all
    assert kinds == [
        "VarDecl",
        "While",
        "a wait with a timeout branch",
        "an if on a general condition",
    ]
    assert all(d.span is not None for d in e165)
