"""`rmot report`: one offline HTML page with the verdict, findings, pictures, plots and data."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from click.testing import CliRunner

from rmot.compiler.cli import cli
from rmot.compiler.frontend import load_program
from rmot.compiler.plan import plan_program
from rmot.sim import verify
from rmot.sim.report_html import ProgramResult, breakdown, render_report

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.fixture(scope="module")
def collision() -> ProgramResult:
    path = str(EXAMPLES / "collision.rmot")
    plan = plan_program(load_program(path, require_program=True).program)
    checked = verify(plan)
    return ProgramResult(path, plan, tuple(checked.diagnostics), dict(checked.cycle_times))


def test_breakdown_tiles_each_task_timeline() -> None:
    """Moving + waiting + syncs + I/O add up to the task's end (the records cover its timeline),
    and each task's end plus its idle time is the program's cycle time."""
    plan = plan_program(load_program(str(EXAMPLES / "handover.rmot"), require_program=True).program)
    rows = breakdown(plan)
    assert len(rows) == 2
    for row in rows:
        busy = row["move"] + row["wait"] + row["sync"] + row["io"]
        assert busy == pytest.approx(row["total"], abs=3 * plan.step + 1e-9)
        assert row["total"] + row["idle"] == pytest.approx(plan.cycle_time)
    assert max(r["sync"] for r in rows) > 0.5  # someone waits at a sync in the hand-over


def test_page_is_self_contained_and_deterministic(collision: ProgramResult) -> None:
    page, problems = render_report([collision])
    assert problems == ()
    assert "error[E300]" in page and "move linear slot frame pallet" in page  # the finding and its source line
    assert 'src="data:image/png;base64,' in page and page.count('src="data:image/svg+xml;base64,') >= 5
    assert "srcdoc=" in page and "rmotJump" in page
    assert "Cycle-time breakdown" in page and "Robot and cell data used" in page and "abb" in page.lower()
    assert not re.search(r'(src|href)="(https?:)?//', page)  # nothing from the network
    again, _ = render_report([collision])
    assert again == page


def test_a_part_that_fails_becomes_w600(collision: ProgramResult, monkeypatch: pytest.MonkeyPatch) -> None:
    import rmot.sim.plots as plots

    def broken(*args: object, **kwargs: object) -> bytes:
        raise RuntimeError("no plotting today")

    monkeypatch.setattr(plots, "figure_bytes", broken)
    page, problems = render_report([collision])
    assert problems and all(p.code.id == "W600" for p in problems)
    assert "no plotting today" in page and "error[E300]" in page


def test_cli_exit_codes_and_missing_input(tmp_path: Path) -> None:
    out = tmp_path / "r.html"
    result = CliRunner().invoke(cli, ["report", str(EXAMPLES / "collision.rmot"), str(tmp_path / "missing.rmot"), "-o", str(out)])
    assert result.exit_code == 2  # an input error wins over findings
    page = out.read_text(encoding="utf-8")
    assert "not checked" in page and "E501" in page and "error[E300]" in page
    assert f"wrote {out}" in result.output  # the page is written even when an input is missing
    bad = CliRunner().invoke(cli, ["report", str(EXAMPLES / "collision.rmot"), "-o", str(tmp_path / "r.pdf")])
    assert bad.exit_code == 2
