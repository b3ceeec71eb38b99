"""The 25/300/25 mm cycle of every library arm with 1 kg: a plausibility check of its data.

The cycle (the industry's "standard cycle", as ABB, FANUC and Yaskawa quote it): from a
point, 25 mm up, 300 mm across, 25 mm down, and back the same way; joint moves, the two top
corners blended (zone 50 mm, which the planner shrinks to half of the 25 mm legs), the bottom
points exact stops. Tool pointing down, 1 kg at a TCP 100 mm along the flange axis. The
points are placed in front of each arm at the first (distance, height) of a small grid, as
fractions of its reach, where every point has an IK solution.

A cycle far off its peers' (an arm 3 x slower than a smaller one of the same class) points
at data that does not mean what it claims (accelerations or torque ratings for another
purpose). Published cycle times to compare with: ABB IRB 120 0.58 s (ABB product
specification 3HAC035960-001, 1 kg, 25 x 300 x 25 mm); others as their data sheets give.

Run:
    .venv/bin/python tests/benchmarks/bench_cycle_arms.py [--arms NAME ...] [--json]
"""

from __future__ import annotations

import argparse
import json
import sys

import numpy as np

from rmot.compiler.cli import stages
from rmot.sim.robots import load_robot
from rmot.sim.robots.library import SPECS

TCP_MM = 100.0
CELL = """cell bench {{
  robot r1 = {arm}{calibration} at pose()
  tool load = sphere(r=20mm) at pose(z={tcp:g}mm) tcp pose(z={tcp:g}mm) mass 1 kg on r1
}}
"""
PROGRAM = """program cycle on r1 {{
  tool load
  zone 50 mm
  target a = pose(x={x:.1f}mm, y={y0:.1f}mm, z={z:.1f}mm, rx=180deg)
  target b = pose(x={x:.1f}mm, y={y1:.1f}mm, z={z:.1f}mm, rx=180deg)
  move joint a zone fine
  move joint shift(a, z=25mm)
  move joint shift(b, z=25mm)
  move joint b zone fine
  move joint shift(b, z=25mm)
  move joint shift(a, z=25mm)
  move joint a zone fine
}}
"""
GRID = [(d, h) for d in (0.6, 0.5, 0.7, 0.4) for h in (0.0, 0.2, -0.2, 0.4)]  # x and z as fractions of reach


def _reachable(robot: object, x: float, z: float) -> bool:
    for y in (-0.15, 0.15):
        for up in (0.0, 0.025):
            pose = np.diag([1.0, -1.0, -1.0, 1.0])
            pose[:3, 3] = (x, y, z + up + TCP_MM / 1000)
            if not robot.ik(pose).solutions:  # type: ignore[attr-defined]
                return False
    return True


def _place(name: str) -> tuple[float, float] | None:
    robot = load_robot(name)
    reach = SPECS[name].reach
    for d, h in GRID:
        if _reachable(robot, d * reach, h * reach):
            return d * reach, h * reach
    return None


def cycle(name: str, calibration: str = "") -> dict[str, object]:
    """The planned cycle (s) of `name`, with the errors the planner reported."""
    where = _place(name)
    if where is None:
        return {"arm": name, "cycle_s": None, "note": "no reachable placement"}
    x, z = where
    text = CELL.format(arm=name, calibration=calibration, tcp=TCP_MM) + PROGRAM.format(
        x=x * 1000, z=z * 1000, y0=-150.0, y1=150.0)
    import tempfile
    from pathlib import Path

    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "cycle.rmot"
        path.write_text(text)
        front = stages.load(str(path), use_cache=False)
        errors = [d.code.id for d in front.diagnostics if d.is_error]
        if front.program is None or errors:
            return {"arm": name, "cycle_s": None, "note": " ".join(errors)}
        plan = stages.plan(front.program, use_cache=False)
    errors = [d.code.id for d in plan.diagnostics if d.is_error]
    return {"arm": name, "cycle_s": round(float(plan.cycle_time), 3), "x_mm": round(x * 1000),
            "z_mm": round(z * 1000), "note": " ".join(errors)}


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--arms", nargs="*", default=sorted(SPECS))
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args(argv)
    rows = [cycle(name) for name in args.arms]
    if args.json:
        print(json.dumps(rows, indent=1))
        return 0
    for row in rows:
        value = "-" if row["cycle_s"] is None else f"{row['cycle_s']:.3f}"
        print(f"{row['arm']:<26} {value:>7} s  {row.get('note', '')}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
