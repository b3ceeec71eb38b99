"""load_robot / list_robots: library names and URDF paths, cached per key."""

from __future__ import annotations

import difflib
import os
from functools import lru_cache

from rmot.sim.robots import codes
from rmot.sim.robots.errors import RobotError
from rmot.sim.robots.robot import Robot
import json

__all__ = ["list_robots", "load_robot", "suggest"]


def list_robots() -> tuple[str, ...]:
    """The library names, sorted."""
    from rmot.sim.robots.library import SPECS  # late: loads subprocess only when this runs

    return tuple(sorted(SPECS))


def suggest(name: str) -> str:
    """"; did you mean 'x'?" for a near miss, else ""."""
    close = difflib.get_close_matches(name.lower(), list_robots(), n=1, cutoff=0.5)
    return f"; did you mean '{close[0]}'?" if close else ""


def load_robot(name_or_path: str) -> Robot:
    """A library robot by name, or a URDF file by path (absolute, or ending in .urdf).
    Raises RobotError (only) for an unknown name or a file that is not a usable arm."""
    key = str(name_or_path)
    if key.startswith("calibrated:"):  # a cell's `robot r1 = NAME speed S % accel A %`
        return _load_calibrated(key)
    if key.startswith(("model:", "urdf-chain:")):  # a cell's model block, a URDF chain between two links
        return _load_keyed(key)
    if key.lower().endswith(".urdf") or os.sep in key:
        return _load_urdf(os.path.abspath(key))
    return _load_library(key)


@lru_cache(maxsize=None)
def _load_calibrated(key: str) -> Robot:
    """ "calibrated:" + JSON [inner key, speed share, acceleration share] (ir.RobotSource)."""

    inner, speed, accel = json.loads(key[len("calibrated:"):])
    return load_robot(inner).calibrated(float(speed), float(accel))


@lru_cache(maxsize=None)
def _load_library(name: str) -> Robot:
    from rmot.sim.robots.build import build_robot  # late: loads subprocess only when this runs
    from rmot.sim.robots.library import SPECS  # late: loads subprocess only when this runs

    spec = SPECS.get(name)
    if spec is None:
        raise RobotError(f"unknown robot '{name}'{suggest(name)} (see `rmot robots list`)", codes.UNKNOWN_ROBOT)
    return build_robot(spec)


@lru_cache(maxsize=None)
def _load_urdf(path: str) -> Robot:
    from rmot.sim.robots.urdf import robot_from_urdf  # late: loads subprocess only when this runs

    return robot_from_urdf(path)


@lru_cache(maxsize=None)
def _load_keyed(key: str) -> Robot:

    if key.startswith("model:"):
        from rmot.sim.robots.model import robot_from_key  # late: loads subprocess only when this runs

        try:
            return robot_from_key(key)
        except ValueError as exc:
            raise RobotError(f"model cannot be built: {exc}", codes.BAD_URDF) from None
    from rmot.sim.robots.urdf import robot_from_urdf  # late: loads subprocess only when this runs

    path, base, tip, *maker = json.loads(key[len("urdf-chain:"):])  # maker: urdf(controller=), when given
    return robot_from_urdf(os.path.abspath(path), base=base, tip=tip, controller=maker[0] if maker else None)
