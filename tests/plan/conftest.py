"""Fixtures of the planner tests (helpers live in plan_helpers.py)."""

from __future__ import annotations

import pytest


@pytest.fixture(scope="session")
def irb120():  # type: ignore[no-untyped-def]
    """The ABB IRB 120 from the robot library."""
    from rmot.sim.robots import load_robot

    return load_robot("abb_irb120")
