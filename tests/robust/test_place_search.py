"""`rmot place` checks poses down its ranking until one verifies (the poses ranked first all sit
near the work; a search that gave up after 24 of them reported "no pose verifies" for a cell
where a farther pose verifies clean), and ranks by the objective only among verified poses.
The witness is a stand-in for the full check that says which poses verify."""

from __future__ import annotations

from typing import Any

import numpy as np

from rmot.compiler.frontend import load_text
from rmot.compiler.design import place as place_mod


def _program() -> Any:
    text = ("program p on r1 {\n  move joint joints(0, -10, 10, 0, 90, 0) deg\n"
            "  move linear pose(x=700mm, y=0mm, z=600mm, ry=180deg) frame world\n}\n")
    program = load_text(text, "p.rmot").program
    assert program is not None
    return program


def test_place_checks_past_the_first_ranked_poses_until_one_verifies(monkeypatch) -> None:  # type: ignore[no-untyped-def]
    checked: list[np.ndarray] = []

    def full_check(programs: Any, slot: str, base: np.ndarray, mover: Any = None) -> place_mod.Candidate:
        checked.append(base)  # only the 30th pose checked verifies; the failing ones have the "best" cycle time
        ok = len(checked) == 30
        return place_mod.Candidate(base, ok, 2.0 if ok else 0.0, 0.1, 0.1)

    monkeypatch.setattr(place_mod, "_evaluate", full_check)
    found = place_mod.place([_program()], "r1", {"x": (-0.1, 0.1), "y": (-0.1, 0.1)}, screen_n=64, refine_rounds=0)
    assert found.screen_feasible >= 30
    assert found.best is not None and found.best.verified and found.best.cycle_time == 2.0
    assert np.array_equal(found.best.base, checked[29])
    assert found.verified_count == 30 and found.passing == 1
    assert all(c.verified for c in found.runners_up)


def test_place_that_finds_none_checks_every_reachable_pose_within_its_budget(monkeypatch) -> None:  # type: ignore[no-untyped-def]
    checked: list[np.ndarray] = []
    monkeypatch.setattr(place_mod, "_evaluate", lambda programs, slot, base, mover=None: checked.append(base) or
                        place_mod.Candidate(base, False, 0.0, 0.1, 0.1))
    monkeypatch.setattr(place_mod, "VERIFY_BUDGET", 40)
    found = place_mod.place([_program()], "r1", {"x": (-0.1, 0.1), "y": (-0.1, 0.1)}, screen_n=64, refine_rounds=0)
    assert found.best is None and found.passing == 0
    assert len(checked) == min(40, found.screen_feasible) == 40
    assert any("the budget" in line for line in found.failures)
