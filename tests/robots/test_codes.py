"""The kinematics diagnostic codes: registered, unique, in E201-E219."""

from __future__ import annotations

from rmot.sim.robots import codes
from rmot.lang.diagnostics import Code, all_codes


def test_codes_are_registered_in_the_kinematics_range():
    """Every code in robots.codes is registered and numbered E201..E219 with a kebab name."""
    ours = [getattr(codes, n) for n in codes.__all__]
    assert all(isinstance(c, Code) and c in all_codes() for c in ours)
    assert all(201 <= int(c.id[1:]) <= 219 and c.id[0] == "E" for c in ours)
    assert len({c.id for c in ours}) == len(ours) and all(c.name == c.name.lower() and " " not in c.name for c in ours)
