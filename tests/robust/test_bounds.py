"""Work bounded and linear: planning a loop is linear in its iterations (the timeline's
continuation of each iteration was a new tuple of every later iteration: 60,000 one-millisecond
waits took 53 s to plan, now ~3 s). The witness is the cycle time, which the waits alone fix."""

from __future__ import annotations

import time
from pathlib import Path

from click.testing import CliRunner

from rmot.compiler.cli import cli


def test_a_long_loop_plans_in_linear_time(tmp_path: Path) -> None:
    program = tmp_path / "p.rmot"
    program.write_text("program p on r1 {\n  move joint joints(0, -10, 10, 0, 90, 0) deg\n"
                       "  repeat 60000 { wait 1 ms }\n}\n", encoding="utf-8")
    started = time.process_time()
    result = CliRunner().invoke(cli, ["plan", str(program), "--no-cache"])
    spent = time.process_time() - started
    assert result.exit_code == 0, result.output
    assert "cycle time 60.000 s" in result.output
    assert spent < 25, f"{spent:.1f} s of CPU for 60,000 iterations (quadratic before: 53 s)"


def test_a_program_past_the_sample_budget_is_timed_only_up_to_it(monkeypatch) -> None:  # type: ignore[no-untyped-def]
    """E124 bounds the timeline before the timing of the rest of it: with a budget of 90 s
    (225,000 samples of 0.4 ms) a program of 1000 joint moves between two Cartesian targets
    100 mm apart (which the joint-space lower bound cannot see; each move takes over 0.1 s, the
    planned program says) is timed for at most the moves that fill the budget, not all 1000."""
    from rmot.compiler.frontend import load_text
    from rmot.compiler.plan import planner, timeline

    body = "".join(f"  move joint pose(x={600 + 100 * (i % 2)}mm, y=0mm, z=600mm, ry=180deg)\n" for i in range(1000))
    program = load_text(f"program p on r1 {{\n{body}}}\n", "p.rmot").program
    assert program is not None
    timed: list[int] = []
    real = timeline.time_chain
    monkeypatch.setattr(timeline, "time_chain", lambda *a, **k: timed.append(1) or real(*a, **k))
    plan = planner.plan_program(program, step=0.0004)
    refusal = [d for d in plan.diagnostics if d.code.id == "E124"]  # (and W224: the first move's start is assumed)
    assert len(refusal) == 1 and "or more" in refusal[0].message
    assert len(timed) <= 90 / 0.1 + 1 < 1000, len(timed)


def test_least_duration_is_a_lower_bound_and_refuses_30000_moves_before_timing(monkeypatch) -> None:  # type: ignore[no-untyped-def]
    """The joint-travel bound is below the planned cycle time (the planner is the witness), and
    30,000 plain joint moves are E124 from it without one move timed (74 s before, 4 s now)."""
    from rmot.compiler.frontend import load_text
    from rmot.compiler.plan import planner, timeline
    from rmot.compiler.plan.least_time import least_duration_s
    from rmot.sim.robots import load_robot

    def program(n: int, tail: str = "") -> object:
        body = "".join(f"  move joint joints({25 * (i % 2)}, -10, {10 + 5 * (i % 3)}, 0, 90, 0) deg\n" for i in range(n))
        loaded = load_text(f"program p on r1 {{\n{body}  wait 2 s\n  repeat 3 {{ move joint joints(40, 0, 0, 0, 90, 0) deg }}\n"
                           f"{tail}}}\n", "p.rmot").program
        assert loaded is not None
        return loaded

    small = program(12)
    plan = planner.plan_program(small)  # type: ignore[arg-type]
    bound = least_duration_s(load_robot("abb_irb1600").velocity_limits, small.tasks[0].body)  # type: ignore[attr-defined]
    assert 2.0 < bound <= plan.cycle_time
    stopped = program(12, "  stop\n  wait 100 s\n")
    assert least_duration_s(load_robot("abb_irb1600").velocity_limits, stopped.tasks[0].body) == bound  # type: ignore[attr-defined]
    timed: list[int] = []
    monkeypatch.setattr(timeline, "time_chain", lambda *a, **k: timed.append(1))
    refused = planner.plan_program(program(30_000))  # type: ignore[arg-type]
    assert [d.code.id for d in refused.diagnostics] == ["E124"] and "at least" in refused.diagnostics[0].message
    assert timed == []


def test_linear_moves_bound_from_below_and_30000_are_refused_before_timing(monkeypatch) -> None:  # type: ignore[no-untyped-def]
    """Linear moves between Cartesian targets count their straight TCP travel over the
    programmed speed, less the zones at both ends: below the planned cycle time (the planner is
    the witness, with zones too), and 30,000 of them (10 mm apart at
    250 mm/s, 1200 s) are E124 without one move timed (37 s before)."""
    from rmot.compiler.frontend import load_text
    from rmot.compiler.plan import planner, timeline
    from rmot.compiler.plan.least_time import least_duration_s
    from rmot.sim.robots import load_robot

    def program(n: int, head: str = "", cell: str = "") -> object:
        body = "".join(f"  move linear pose(x={900 + 10 * (i % 2)}mm, y={20 * (i % 3)}mm, z=1000mm, ry=180deg)\n" for i in range(n))
        loaded = load_text(f"{cell}program p on r1 {{\n  move joint joints(0, -10, 10, 0, 90, 0) deg\n{head}{body}}}\n",
                           "p.rmot").program
        assert loaded is not None
        return loaded

    vmax = load_robot("abb_irb1600").velocity_limits
    for head in ("", "  speed 100 mm/s\n  zone 5 mm\n"):
        small = program(12, head)
        plan = planner.plan_program(small)  # type: ignore[arg-type]
        bound = least_duration_s(vmax, small.tasks[0].body)  # type: ignore[attr-defined]
        assert 0.1 < bound <= plan.cycle_time, (head, bound, plan.cycle_time)
    timed: list[int] = []
    monkeypatch.setattr(timeline, "time_chain", lambda *a, **k: timed.append(1))
    refused = planner.plan_program(program(30_000))  # type: ignore[arg-type]
    assert [d.code.id for d in refused.diagnostics] == ["E124"] and "at least" in refused.diagnostics[0].message
    assert timed == []
