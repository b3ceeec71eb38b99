"""What a design study starts from: a robot (from a cell, or bare), its base, tool and fixtures,
and the small option languages of the design commands (orientations, regions).

Option text errors raise `OptionError`, which carries its diagnostic code (compiler/design/codes.py);
the CLI renders it as `rmot: error[E80x]: ...` and exits 2.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import Any

import numpy as np

from rmot.lang import ir
from rmot.sim.robots.codes import UNKNOWN_ROBOT
from rmot.compiler.design import codes
from rmot.lang.diagnostics import Diagnostic, Severity
from rmot.compiler.design.reach_draw import FixtureMesh

__all__ = ["OptionError", "Study", "fixture_meshes", "parse_angles", "parse_region", "rotation_rpy", "study_for"]


class OptionError(ValueError):
    """A command-line value that does not parse; the message says what was expected and names
    the option, `code` is its registered diagnostic code."""

    def __init__(self, code: Any, message: str) -> None:
        super().__init__(message)
        self.code = code
        self.message = message

    def diagnostic(self) -> Any:
        """The error as a diagnostic value (no span: the value came from the command line)."""
        return Diagnostic(self.code, Severity.ERROR, self.message, None)


_NUMBER = r"[-+]?(?:[0-9]*\.?[0-9]+)(?:[eE][-+]?[0-9]+)?"
_ANGLE_UNITS = {"deg": math.pi / 180, "rad": 1.0}
_LENGTH_UNITS = {"mm": 1e-3, "cm": 1e-2, "m": 1.0}


def _value(text: str, key: str, units: dict[str, float], option: str) -> float:
    m = re.fullmatch(rf"\s*({_NUMBER})\s*([a-z]+)\s*", text)
    if not m or m.group(2) not in units:
        raise OptionError(codes.OPTION_NUMBER,
                          f"{option} {key} must be a number with a unit ({', '.join(units)}) (got '{text.strip()}')")
    value = float(m.group(1)) * units[m.group(2)]
    if not math.isfinite(value):  # 1e999m parses as inf
        raise OptionError(codes.OPTION_NUMBER, f"{option} {key} must be a finite number (got '{text.strip()}')")
    return value


def rotation_rpy(rx: float, ry: float, rz: float) -> np.ndarray:
    """R = Rz(rz)·Ry(ry)·Rx(rx), the language's convention (lang/REFERENCE.md)."""
    return ir.Pose.from_xyz_rpy(0.0, 0.0, 0.0, rx, ry, rz).matrix()[:3, :3]


def parse_angles(text: str) -> tuple[float, float, float]:
    """'rx=180deg, rz=90deg' -> (rx, ry, rz) rad; keys left out are 0."""
    out = {"rx": 0.0, "ry": 0.0, "rz": 0.0}
    seen = set()
    for part in filter(None, (p.strip() for p in text.split(","))):
        key, eq, value = part.partition("=")
        key = key.strip()
        if not eq or key not in out or key in seen:
            raise OptionError(codes.ORIENTATION_SYNTAX,
                              f"--orientation must be 'any' or keys rx, ry, rz each given once, e.g. rx=180deg (got '{text}')")
        seen.add(key)
        out[key] = _value(value, key, _ANGLE_UNITS, "--orientation")
    return out["rx"], out["ry"], out["rz"]


_REGION_KEYS = {"x": _LENGTH_UNITS, "y": _LENGTH_UNITS, "z": _LENGTH_UNITS, "rz": _ANGLE_UNITS}


def parse_region(text: str) -> dict[str, tuple[float, float]]:
    """'x=0.2m..1.2m, y=-500mm..500mm, rz=-180deg..180deg' -> {key: (lo, hi)} in m / rad.
    x and y are required; z and rz are optional (absent: kept from the cell's pose)."""
    out: dict[str, tuple[float, float]] = {}
    for part in filter(None, (p.strip() for p in text.split(","))):
        key, eq, value = part.partition("=")
        key = key.strip()
        if not eq or key not in _REGION_KEYS or key in out:
            raise OptionError(codes.REGION_SYNTAX,
                              f"--region must list x=LO..HI, y=LO..HI and optionally z=, rz= each once (got '{part}')")
        lo_text, dots, hi_text = value.partition("..")
        if not dots:
            lo_text = hi_text = value  # a single value: fixed
        lo = _value(lo_text, key, _REGION_KEYS[key], "--region")
        hi = _value(hi_text, key, _REGION_KEYS[key], "--region")
        if hi < lo:
            raise OptionError(codes.RANGE_INVERTED, f"--region {key} must go from low to high (got {value.strip()})")
        out[key] = (lo, hi)
    for key in ("x", "y"):
        if key not in out:
            raise OptionError(codes.REGION_SYNTAX, f"--region must give {key}=LO..HI (got '{text}')")
    return out


@dataclass(frozen=True, eq=False)
class Study:
    """robot: the loaded Robot; instance: its cell declaration (None for a bare arm); base,
    tcp: (4,4); cell: the ir.Cell (None for a bare arm)."""

    robot: Any
    instance: ir.RobotInstance | None
    base: np.ndarray
    tcp: np.ndarray
    cell: ir.Cell | None
    tool: str | None


def robot_error_code(exc: Any) -> Any:
    """The code of a --robot value the loader refused: an unknown library name (the loader's
    UNKNOWN_ROBOT, E111) is the design commands' E804; a file that does not load keeps the loader's own code."""
    return codes.ROBOT_UNKNOWN if exc.code in (None, UNKNOWN_ROBOT) else exc.code


def study_for(cell: ir.Cell | None, robot_name: str | None, tool: str | None) -> Study:
    """The robot of `cell` named robot_name (default: the cell's only robot), or, without a
    cell, the library robot / URDF file robot_name at the origin. Raises OptionError."""
    from rmot.sim.robots import RobotError, load_robot  # late: loads subprocess only when this runs

    if cell is None:
        if not robot_name:
            raise OptionError(codes.OPTION_MISSING, "--robot must name a library robot or a URDF file when no cell is given")
        if tool:
            raise OptionError(codes.OPTION_MISSING, "--tool needs a cell that declares the tool")
        try:
            robot = load_robot(robot_name)
        except RobotError as exc:
            raise OptionError(robot_error_code(exc), f"--robot: {exc.message}") from None
        return Study(robot, None, np.eye(4), np.eye(4), None, None)
    names = [r.name for r in cell.robots]
    if robot_name is None:
        if len(names) != 1:
            raise OptionError(codes.OPTION_MISSING, f"--robot must name one of the cell's robots ({', '.join(names)})")
        robot_name = names[0]
    if robot_name not in names:
        raise OptionError(codes.ROBOT_UNKNOWN, f"--robot must name a robot of cell '{cell.name}' ({', '.join(names)}) (got '{robot_name}')")
    instance = cell.robot(robot_name)
    try:
        robot = load_robot(instance.source.load_key)
    except RobotError as exc:
        raise OptionError(exc.code or codes.ROBOT_UNKNOWN, f"robot '{robot_name}': {exc.message}") from None
    tcp = np.eye(4)
    if tool is not None:
        tools = {t.name: t for t in cell.tools}
        if tool not in tools:
            raise OptionError(codes.TOOL_UNKNOWN, f"--tool must name a tool of cell '{cell.name}' ({', '.join(tools) or 'none'}) (got '{tool}')")
        if tools[tool].robot != robot_name:
            raise OptionError(codes.TOOL_UNKNOWN, f"--tool '{tool}' must be mounted on '{robot_name}' (it is on '{tools[tool].robot}')")
        tcp = tools[tool].tcp.matrix()
    return Study(robot, instance, instance.base.matrix(), tcp, cell, tool)


def fixture_meshes(cell: ir.Cell | None) -> tuple[list[Any], tuple[Any, ...]]:
    """The cell's fixtures as world triangles + box corners (for drawing), and the mesh
    diagnostics of fixtures that did not load."""
    if cell is None:
        return [], ()
    from rmot.sim.render.tessellate import tessellate  # late: loads PIL only when this runs
    from rmot.sim.scene import build_scene  # late: loads subprocess only when this runs

    scene = build_scene(cell, {}, {})
    out = []
    for body in scene.bodies:
        if body.kind != "fixture":
            continue
        tri = tessellate(body.shape).vertices
        world = tri @ body.local[:3, :3].T + body.local[:3, 3]
        signs = np.array([[(k >> 2) & 1, (k >> 1) & 1, k & 1] for k in range(8)]) * 2 - 1
        local = body.obb_centre + signs * body.obb_half
        corners = local @ body.local[:3, :3].T + body.local[:3, 3]
        out.append(FixtureMesh(body.name, world, corners))
    return out, scene.diagnostics
