"""`move free` against OMPL's RRT-Connect on the same collision model, per cell, in one run.

Cells: a fence between pick and place (tests/free/wall_free.rmot), a shelf (from the lower
compartment to the upper), a machine door (from a table outside through a window in the
machine's front), a narrow passage (between a wall and a beam above it). Per case and planner:
planning time (s, wall clock on this machine), the joint-space path length (rad, Euclidean over
the via points), the via points, and the cycle time of the move once timed (s: the path written
as joint moves through the via points, zones verified as `move free` does).

The peer is OMPL 2 (`pip install ompl`, the `bench` extra): og.RRTConnect then
SimpleSetup.simplifySolution (shortcutting, B-spline smoothing, vertex collapsing), with the
state validity and the motion validity given by rmot's own free space (sim/free/space.py: the
verifier's bodies, pairs and no-miss segment check, clearance relaxed next to the ends exactly
as for rmot's search), its RNG seeded (ompl.util.RNG.setSeed) and a time budget of 60 s.
Without ompl the table has rmot's rows only, and says so. OMPL's seed is process-wide and can
be set only once, so its rows for the later cases depend on what ran before them (two runs of
this script gave OMPL shelf paths of 7.8 and 14.9 rad); rmot's rows do not change.

Run: .venv/bin/python tests/benchmarks/bench_free.py
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

import numpy as np

from rmot.lang import ir
from rmot.compiler import plan_cache
from rmot.compiler.frontend import load_program
from rmot.sim.free import lower
from rmot.sim.free.search import path_length
from rmot.sim.scene import build_scene

HERE = Path(__file__).resolve().parent
CASES = {
    "fence": HERE.parent / "free" / "wall_free.rmot",
    "shelf": HERE / "free_cells" / "shelf.rmot",
    "machine door": HERE / "free_cells" / "door.rmot",
    "narrow passage": HERE / "free_cells" / "passage.rmot",
}
OMPL_SECONDS = 60.0
_SEEDED: list[bool] = []


def _plan(program: ir.Program):  # type: ignore[no-untyped-def]
    return plan_cache.cached_plan(program, use_cache=False)


def _problem(path: Path):  # type: ignore[no-untyped-def]
    program = load_program(str(path)).program
    task = program.tasks[0]
    move = next(i for i in task.body if isinstance(i, ir.Move) and i.free is not None)
    scene = build_scene(program.cell, lower._tools_used(program))
    problem = lower.free_problem(program, _plan, scene, task.name, move.uid)
    assert isinstance(problem, lower.FreeProblem), problem
    return program, problem


def _timed(program: ir.Program, problem, path: list[np.ndarray]) -> float:  # type: ignore[no-untyped-def]
    vias = [tuple(float(v) for v in q) for q in path[1:-1]]
    lowered, _ = lower._emit(program, _plan, problem.space, problem.task, problem.move, problem.record, vias, path, None)
    return float(_plan(lowered).cycle_time)


def rmot_row(path: Path) -> dict[str, object]:
    program, problem = _problem(path)
    t0 = time.perf_counter()
    result = lower.lower_free_moves(program, _plan, None)
    seconds = time.perf_counter() - t0
    body = result.program.tasks[0].body
    vias = [np.asarray(i.target.values) for i in body if isinstance(i, ir.Move) and isinstance(i.target, ir.JointTarget)
            and i.span == problem.move.span and i.uid != problem.move.uid]
    found = not any(d.is_error for d in result.diagnostics)
    full = [problem.q_start, *vias, problem.q_goal]
    return {"planner": "rmot", "seconds": seconds, "found": found, "length": path_length(full) if found else None,
            "vias": len(vias), "cycle": float(_plan(result.program).cycle_time) if found else None}


def ompl_row(path: Path) -> dict[str, object] | None:
    try:
        from ompl import base as ob
        from ompl import geometric as og
        from ompl import util as ou
    except ImportError:
        return None
    ou.setLogLevel(ou.LogLevel.LOG_ERROR)
    if not _SEEDED:  # OMPL's seed is process-wide and may be set once, before its first draw
        ou.RNG.setSeed(1)
        _SEEDED.append(True)
    program, problem = _problem(path)
    space_ = problem.space
    robot = space_.scene.robots[space_.robot].robot
    free = problem.move.free
    edge_free = lower.edge_check(space_, problem.q_start, problem.q_goal, free.clearance)
    dof = robot.dof
    space = ob.RealVectorStateSpace(dof)
    bounds = ob.RealVectorBounds(dof)
    for j in range(dof):
        bounds.setLow(j, float(robot.joint_limits[j, 0]))
        bounds.setHigh(j, float(robot.joint_limits[j, 1]))
    space.setBounds(bounds)
    setup = og.SimpleSetup(space)

    def q_of(state) -> np.ndarray:  # type: ignore[no-untyped-def]
        return np.array([state[j] for j in range(dof)])

    ends = {problem.q_start.tobytes(): problem.q_start, problem.q_goal.tobytes(): problem.q_goal}

    def snap(q: np.ndarray) -> np.ndarray:  # OMPL copies states: give the ends back their identity
        return next((e for e in ends.values() if np.allclose(q, e, atol=1e-12)), q)

    setup.setStateValidityChecker(lambda s: edge_free(snap(q_of(s)), snap(q_of(s))))
    info = setup.getSpaceInformation()

    class Motion(ob.MotionValidator):  # type: ignore[misc]
        def checkMotion(self, a, b, *rest):  # type: ignore[no-untyped-def]
            return edge_free(snap(q_of(a)), snap(q_of(b)))

    validator = Motion(info)
    info.setMotionValidator(validator)
    start, goal = space.allocState(), space.allocState()
    for j in range(dof):
        start[j], goal[j] = float(problem.q_start[j]), float(problem.q_goal[j])
    setup.setStartAndGoalStates(start, goal)
    setup.setPlanner(og.RRTConnect(info))
    t0 = time.perf_counter()
    solved = setup.solve(OMPL_SECONDS)
    found = bool(setup.haveExactSolutionPath())
    if found:
        setup.simplifySolution()
    seconds = time.perf_counter() - t0
    if not found:
        return {"planner": "ompl", "seconds": seconds, "found": False, "length": None, "vias": 0, "cycle": None,
                "status": str(solved)}
    sol = setup.getSolutionPath()
    pts = [snap(q_of(sol.getState(k))) for k in range(sol.getStateCount())]
    pts[0], pts[-1] = problem.q_start, problem.q_goal
    return {"planner": "ompl", "seconds": seconds, "found": True, "length": path_length(pts), "vias": len(pts) - 2,
            "cycle": _timed(program, problem, pts)}


def main() -> None:
    rows = []
    for name, path in CASES.items():
        for row in (rmot_row(path), ompl_row(path)):
            if row is not None:
                rows.append((name, row))
                print(_line(name, row), flush=True)
    if not any(r["planner"] == "ompl" for _, r in rows):
        print("ompl is not installed (pip install ompl, the `bench` extra): rmot's rows only")
    os._exit(0)  # OMPL's nanobind bindings report leaked instances at interpreter exit


def _line(name: str, row: dict[str, object]) -> str:
    def f(v: object, fmt: str) -> str:
        return "-" if v is None else format(v, fmt)
    return (f"| {name} | {row['planner']} | {f(row['seconds'], '.2f')} | {'yes' if row['found'] else 'no'} | "
            f"{f(row['length'], '.3f')} | {row['vias']} | {f(row['cycle'], '.3f')} |")


if __name__ == "__main__":
    print("| case | planner | planning s | found | joint path rad | vias | cycle s |")
    print("|---|---|---|---|---|---|---|")
    sys.exit(main())
