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
    (225,000 samples of 0.4 ms) a program of 1000 swings of 10 degrees (each at least 0.1 s:
    J1 of the IRB 1600 turns at most 150 deg/s, ABB 3HAC023604-001 as cited in the library) is timed for at most
    the swings that fill the budget, not all 1000 (30k moves took 74 s before E124)."""
    from rmot.compiler.frontend import load_text
    from rmot.compiler.plan import planner, timeline

    body = "".join(f"  move joint joints({10 * (i % 2)}, -10, 10, 0, 90, 0) deg\n" for i in range(1000))
    program = load_text(f"program p on r1 {{\n{body}}}\n", "p.rmot").program
    assert program is not None
    timed: list[int] = []
    real = timeline.time_chain
    monkeypatch.setattr(timeline, "time_chain", lambda *a, **k: timed.append(1) or real(*a, **k))
    plan = planner.plan_program(program, step=0.0004)
    assert [d.code.id for d in plan.diagnostics] == ["E124"]
    assert "or more" in plan.diagnostics[0].message
    assert len(timed) <= 90 / 0.1 + 1 < 1000, len(timed)
