"""W224: a task's first move must be a joint move to a joint target (the start is unknown)."""

from __future__ import annotations

from pathlib import Path

from click.testing import CliRunner

from rmot.lang import ir
from rmot.compiler.cli import cli
from rmot.compiler.plan import plan_program
from rmot.lang.diagnostics import Severity

from plan_helpers import Counter, Prog, pose, program, span

TOOL_DOWN = dict(rx=180, ry=0, rz=180)
START = pose(300, -150, 300, **TOOL_DOWN)


def _w224(plan) -> list[tuple[int, str | None]]:  # type: ignore[no-untyped-def]
    """(line, task) of every W224."""
    return [(d.span.start.line, d.task) for d in plan.diagnostics if d.code.id == "W224"]


class TestFirstMove:
    def test_linear_first_move_is_warned_at_its_line(self) -> None:
        """A task starting with a linear move: one W224 warning at that move, naming task and kind."""
        p = Prog()
        p.set(1, True)
        first = p.linear(START)
        p.linear(pose(300, 0, 300, **TOOL_DOWN))
        plan = plan_program(program(p.task("weld")))
        assert _w224(plan) == [(first, "weld")]
        d = plan.diagnostics[0]
        assert d.severity is Severity.WARNING and d.time_s == 0.0
        assert d.message.startswith(
            "the first move of task 'weld' must be a joint move to a joint target (got a linear move)")
        assert "move joint home" in d.message

    def test_joint_move_to_joints_is_silent(self) -> None:
        """`move joint <joints>` first: no diagnostic at all, even with Cartesian moves after it."""
        p = Prog()
        p.joint([0, 30, 10, 0, 50, 0])
        p.linear(START)
        p.circular(pose(350, -100, 300, **TOOL_DOWN), pose(300, -50, 300, **TOOL_DOWN))
        assert plan_program(program(p.task())).diagnostics == ()

    def test_joint_move_to_a_pose_is_warned(self) -> None:
        """A joint move to a pose first: W224, since the IK branch at the unknown start is a guess."""
        p = Prog()
        first = p.joint(START)
        p.joint([0, 0, 0, 0, 30, 0])
        plan = plan_program(program(p.task()))
        assert _w224(plan) == [(first, "main")]
        assert "(got a joint move to a pose)" in plan.diagnostics[0].message

    def test_circular_first_move_is_warned(self) -> None:
        """A circular move first: W224 naming a circular move."""
        p = Prog()
        first = p.circular(pose(350, -100, 300, **TOOL_DOWN), START)
        plan = plan_program(program(p.task()))
        assert _w224(plan) == [(first, "main")]
        assert "(got a circular move)" in plan.diagnostics[0].message

    def test_only_the_first_move_counts(self) -> None:
        """A later joint move to a pose after a joint-target start is not W224."""
        p = Prog()
        p.joint([0, 30, 10, 0, 50, 0])
        p.joint(START)
        p.linear(pose(300, 0, 300, **TOOL_DOWN))
        assert _w224(plan_program(program(p.task()))) == []


class TestPaths:
    def test_each_arm_of_a_leading_if_is_a_possible_start(self) -> None:
        """An if before any move: each arm's first move is a start; only the bad one is warned."""
        counter = Counter()
        p, then, otherwise = Prog(counter), Prog(counter), Prog(counter)
        then.joint([0, 30, 10, 0, 50, 0])
        bad = otherwise.linear(START)
        p.if_(then, otherwise)
        p.linear(pose(300, 0, 300, **TOOL_DOWN))
        assert _w224(plan_program(program(p.task()))) == [(bad, "main")]

    def test_an_arm_without_moves_lets_the_next_move_start(self) -> None:
        """If one arm of a leading if has no move, the move after the if can be first too."""
        counter = Counter()
        p, then, otherwise = Prog(counter), Prog(counter), Prog(counter)
        then.joint([0, 30, 10, 0, 50, 0])
        otherwise.set(2, True)
        p.if_(then, otherwise)
        after = p.linear(START)
        assert _w224(plan_program(program(p.task()))) == [(after, "main")]

    def test_first_move_inside_a_proc_call(self) -> None:
        """A leading proc call whose body starts with a linear move: W224 at that move."""
        inner = Prog()
        bad = inner.linear(START)
        call = ir.ProcCall(uid=50, proc="approach", args=(), body=tuple(inner.body), span=span(50))
        task = ir.Task("main", "r1", (call,))
        assert _w224(plan_program(program(task))) == [(bad, "main")]

    def test_every_task_is_checked_on_its_own(self) -> None:
        """Two tasks: only the one starting with a linear move is warned, under its own name."""
        counter = Counter()
        a, b = Prog(counter), Prog(counter)
        a.joint([0, 30, 10, 0, 50, 0])
        bad = b.linear(START)
        plan = plan_program(program(a.task("a", "r1"), b.task("b", "r2"),
                                    robots={"r1": "abb_irb120", "r2": "abb_irb120"}))
        assert _w224(plan) == [(bad, "b")]


SOURCE = """program demo on r1 {{
  target home = joints(0, -20, 30, 0, 50, 0) deg
  speed 250 mm/s
  {first}
  move linear pose(x=900mm, y=-100mm, z=500mm, rx=180deg) zone fine
}}
"""


def _plan_cli(tmp_path: Path, first: str):  # type: ignore[no-untyped-def]
    src = tmp_path / "prog.rmot"
    src.write_text(SOURCE.format(first=first), encoding="utf-8")
    return CliRunner().invoke(cli, ["plan", str(src)]), src


def test_cli_named_joint_target_start_is_silent(tmp_path: Path) -> None:
    """From source: `move joint home` with home = joints(...) plans with nothing on stderr."""
    result, _ = _plan_cli(tmp_path, "move joint home")
    assert result.exit_code == 0, result.output
    assert result.stderr == ""


def test_cli_linear_start_warns_at_its_line_and_exits_0(tmp_path: Path) -> None:
    """From source: a linear first move prints W224 at line 4, col 3; a warning keeps exit 0."""
    result, src = _plan_cli(tmp_path, "move linear pose(x=900mm, y=100mm, z=500mm, rx=180deg)")
    assert result.exit_code == 0, result.output
    assert f"{src}:4:3: warning[W224]: the first move of task 'demo' must be a joint move" in result.stderr
