"""Shared fixtures for the backend tests (also used by test_urscript/inform/val3/neutral).

For the other backends helper — the names to reuse:
  * `plan_from_text` (fixture): a function `(text: str, path: str = "test.rmot") -> plan_types.Plan`
    that compiles .rmot text through the real front end (`rmot.compiler.frontend.load_text`)
    and planner (`rmot.compiler.plan.plan_program`); it fails the test with the rendered
    diagnostics if either reports an error.
  * `hand_plan(...)` (plain function, import with `from backend_fixtures import hand_plan`
    (a plain module in this folder) or use the `hand` fixture): builds a Plan by hand from IR instructions and per-uid joint
    solutions, for tests that must not depend on the planner.
  * `span_at(line)`: a Span on a fake file `demo.rmot` at that line.
"""

from __future__ import annotations

from collections.abc import Callable

import pytest
from backend_fixtures import hand_plan

from rmot.lang import plan_types


@pytest.fixture
def hand() -> Callable[..., plan_types.Plan]:
    return hand_plan


@pytest.fixture(scope="session")
def plan_from_text() -> Callable[..., plan_types.Plan]:
    """Compile .rmot text to a Plan through the real front end and planner (session-wide, so
    module-scoped fixtures can use it; each text is planned once per session)."""
    from rmot.compiler.frontend import load_text
    from rmot.compiler.plan import plan_program
    from rmot.lang.diagnostics import render_all

    cache: dict[tuple[str, str], plan_types.Plan] = {}

    def build(text: str, path: str = "test.rmot") -> plan_types.Plan:
        if (text, path) in cache:
            return cache[(text, path)]
        front = load_text(text, path)
        errors = [d for d in front.diagnostics if d.is_error]
        assert front.program is not None and not errors, render_all(errors)
        plan = plan_program(front.program)
        errors = [d for d in plan.diagnostics if d.is_error]
        assert not errors, render_all(errors)
        cache[(text, path)] = plan
        return plan

    return build


