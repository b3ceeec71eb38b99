"""`move free` lowered at plan time into ordinary joint moves through via points.

For each `move free` (in task order), the program as it stands is planned; the move's start
is the target of the move before it (its joints on the plan), its goal the joints the planner
chose for its target (config honoured). Then:
  1. the start and the goal are checked first: either in collision is a finding naming the
     bodies (E251, E250), and no search is made;
  2. the search (search.py: RRT-Connect, then shortcutting) runs in the free space of that
     instant (space.py: the verifier's bodies, pairs and no-miss segment check), keeping the
     move's clearance except where the start or the goal is already closer than it (a gripper
     at its pick point: there the path must only not come closer than the end already is);
     no path within the sample budget (or the time budget, a safety stop) is E252;
  3. the move becomes joint moves to the via points (named `<target>_via<k>`, the move's own
     speed and acceleration, the span of the `move free`) and the move itself; the via zones
     are tried largest first (VIA_ZONES) and the first whose *timed* path verifies clean in the
     move's time window (the verifier's check with the other robots moving) is kept; `fine`
     is the path the search proved;
  4. a note (W250) at the move lists the via points.

Deterministic: the search's Generator is seeded by a SHA-256 of everything it depends on (the
robot, start, goal, clearance, sample budget, the bodies and where they stand), so the same
input gives the same path on every run and machine; the path found is kept under that key by
the store the caller hands in (the CLI's: the plan cache's `free/` folder), so a second run
does not search again.
"""

from __future__ import annotations

import hashlib
import json
import math
from collections.abc import Callable
from typing import Any, Protocol
from dataclasses import dataclass, replace

import numpy as np

from rmot.lang import ir, ir_tree, plan_types
from rmot.lang.diagnostics import Diagnostic, Severity
from rmot.lang.record import record
from rmot.sim import codes
from rmot.sim.collide import check_timeline
from rmot.sim.corners import corner_findings
from rmot.sim.free.search import path_length, search_path, shorten
from rmot.sim.free.space import FreeSpace, free_space, robot_timeline
from rmot.sim.scene import Scene, build_scene

__all__ = ["VIA_ZONES", "FreeProblem", "PathStore", "FreeResult", "edge_check", "free_problem", "has_free_moves", "lower_free_moves"]

FORMAT = "rmot-free-1"  # in every seed and cache key: a change to the search makes new ones
VIA_ZONES = (0.05, 0.01, 0.0)  # m: zones tried at the via points, largest first; 0 = fine
# m: the shortened path's new segments keep this much more than the clearance, so that the
# zones at its via points (which cut the corners) still keep the clearance; measured on the wall
# cell (tests/free): with 0 the tight path around the wall's end verified only with `fine`
BLEND_ROOM = 0.02
PlanFn = Callable[[ir.Program], plan_types.Plan]


class PathStore(Protocol):
    """Keeps the paths found between runs (the CLI's is compiler/cli/free_cache.py)."""

    def load(self, key: str) -> bytes | None: ...

    def save(self, key: str, data: bytes) -> None: ...


@record
class FreeResult:
    program: ir.Program
    diagnostics: tuple[Diagnostic, ...]


def has_free_moves(program: ir.Program) -> bool:
    return any(isinstance(i, ir.Move) and i.free is not None for t in program.tasks for i in ir_tree.walk(t.body))


def lower_free_moves(program: ir.Program, plan_fn: PlanFn, store: PathStore | None = None) -> FreeResult:
    """The program with every `move free` written as joint moves through the via points its
    search found; the findings and notes of the searches. `store` keeps found paths between
    runs (None: search every time)."""
    diags: list[Diagnostic] = []
    todo: list[tuple[str, int]] = []
    for task in program.tasks:
        top = {i.uid for i in task.body}
        for instr in ir_tree.walk(task.body):
            if not (isinstance(instr, ir.Move) and instr.free is not None):
                continue
            if instr.uid in top:
                todo.append((task.name, instr.uid))
            else:
                diags.append(_finding(codes.FREE_UNSUPPORTED, "a 'move free' must stand in the task's own body, not in "
                                      "a loop, an if or a proc (its via points are found for one start)", instr, task))
    if not todo:
        return FreeResult(program, tuple(diags))
    scene = build_scene(program.cell, _tools_used(program))
    for task_name, uid in todo:
        program, found = _lower_one(program, plan_fn, scene, task_name, uid, store)
        diags += found
    return FreeResult(program, tuple(diags))


def _tools_used(program: ir.Program) -> dict[str, set[str]]:
    from rmot.sim.verification import _tools_used as used  # late: loads pinocchio only when this runs

    return used(program)


def _finding(code: object, message: str, move: ir.Move, task: ir.Task, severity: Severity = Severity.ERROR,
             bodies: tuple[str, ...] = ()) -> Diagnostic:
    return Diagnostic(code, severity, message, move.span, (), None, None, bodies, None, task.name)  # type: ignore[arg-type]


@dataclass(frozen=True, eq=False)
class FreeProblem:
    """One `move free` ready to search: where it starts and ends, in which free space."""

    task: ir.Task
    move: ir.Move
    record: plan_types.InstructionRecord
    q_start: np.ndarray
    q_goal: np.ndarray
    space: FreeSpace


def free_problem(program: ir.Program, plan_fn: PlanFn, scene: Scene, task_name: str,
                 uid: int) -> FreeProblem | list[Diagnostic]:
    """The search problem of the `move free` `uid`, or the findings that stop it before any
    search (E253 no start, E251 / E250 start or goal in collision; [] when the planner could
    not place the target, which it reports itself)."""
    plan = plan_fn(program)
    task = next(t for t in program.tasks if t.name == task_name)
    move = next(i for i in task.body if i.uid == uid)
    assert isinstance(move, ir.Move)
    tp = next((p for p in plan.tasks if p.task.name == task_name), None)
    rec = tp.record(uid) if tp is not None else None
    if tp is None or rec is None or rec.q_target is None or tp.robot not in scene.robots:
        return []
    q_start = _start_joints(tp, task, uid)
    if q_start is None:
        return [_finding(codes.FREE_UNSUPPORTED, "a 'move free' must not be its task's first move (its "
                         "start is unknown): put a joint move to a joint target before it", move, task)]
    q_goal = np.asarray(rec.q_target, dtype=float)
    space = free_space(scene, plan, tp.robot, rec.t_start)
    blocked = _blocked_ends(space, q_start, q_goal, move, task)
    return blocked or FreeProblem(task, move, rec, q_start, q_goal, space)


def _lower_one(program: ir.Program, plan_fn: PlanFn, scene: Scene, task_name: str, uid: int,
               store: PathStore | None) -> tuple[ir.Program, list[Diagnostic]]:
    problem = free_problem(program, plan_fn, scene, task_name, uid)
    if not isinstance(problem, FreeProblem):
        return program, problem
    task, move, space = problem.task, problem.move, problem.space
    free = move.free
    assert free is not None
    robot = space.scene.robots[space.robot].robot
    key = _key(space, problem.q_start, problem.q_goal, free)
    path, outcome = _cached_path(store, key) if store is not None else (None, None)
    if path is None:
        path, outcome, failure = _search(space, robot, problem.q_start, problem.q_goal, free, key)
        if failure is not None:
            return program, [replace(failure, span=move.span, task=task.name)]
        if store is not None:
            _store_path(store, key, path, outcome)
    vias = [tuple(float(v) for v in q) for q in path[1:-1]]
    return _emit(program, plan_fn, space, task, move, problem.record, vias, path, outcome)


def _start_joints(tp: plan_types.TaskPlan, task: ir.Task, uid: int) -> np.ndarray | None:
    """The joints at the target of the last move before the `move free` (None: none before it)."""
    before: list[int] = []
    for instr in task.body:
        if instr.uid == uid:
            break
        before += [i.uid for i in ir_tree.walk((instr,)) if isinstance(i, ir.Move)]
    for prev in reversed(before):
        r = tp.record(prev)
        if r is not None and r.q_target is not None:
            return np.asarray(r.q_target, dtype=float)
    return None


def _blocked_ends(space: FreeSpace, q_start: np.ndarray, q_goal: np.ndarray, move: ir.Move, task: ir.Task) -> list[Diagnostic]:
    """E251 / E250 when the start or the goal is in collision, naming the bodies."""
    out = []
    for q, code, what in ((q_start, codes.FREE_START_BLOCKED, "start"), (q_goal, codes.FREE_GOAL_BLOCKED, "target")):
        hits = [h for h in space.blocked(q, 0.0) if h.kind == "collision"]
        if hits:
            named = sorted((_moving_first(space, h.a, h.b) + (h.distance,) for h in hits), key=lambda x: (x[2], x[0], x[1]))
            names = ", ".join(f"'{a}' is {-d * 1000:.1f} mm inside '{b}'" for a, b, d in named[:3])
            more = f" (and {len(named) - 3} more)" if len(named) > 3 else ""
            message = f"the {what} of a 'move free' must be free of collision (got: {names}{more}); no path was searched"
            out.append(_finding(code, message, move, task, bodies=named[0][:2]))
    return out


def _moving_first(space: FreeSpace, a: str, b: str) -> tuple[str, str]:
    """The pair with the robot's body first (as the verifier names a collision)."""
    return (a, b) if space.scene.body(a).robot == space.robot else (b, a)


def _slack(space: FreeSpace, q: np.ndarray, clearance: float) -> float:
    """The clearance a path may keep next to q: the move's, or less where q itself is closer."""
    near = [h.distance for h in space.blocked(q, clearance) if h.kind == "clearance"]
    return min([clearance] + [max(0.0, d * (1 - 1e-6)) for d in near])


def edge_check(space: FreeSpace, q_start: np.ndarray, q_goal: np.ndarray,
               clearance: float) -> Callable[..., bool]:
    """edge_free(qa, qb, margin=0): the segment keeps clearance + margin, less next to the start
    or the goal where they are already closer (_slack)."""
    ends = {q_start.tobytes(): _slack(space, q_start, clearance), q_goal.tobytes(): _slack(space, q_goal, clearance)}

    def edge_free(qa: np.ndarray, qb: np.ndarray, margin: float = 0.0) -> bool:
        c = min(ends.get(qa.tobytes(), clearance + margin), ends.get(qb.tobytes(), clearance + margin))
        return space.segment_free(qa, qb, c)

    return edge_free


def _search(space: FreeSpace, robot: Any, q_start: np.ndarray, q_goal: np.ndarray, free: ir.FreeMotion,
            key: str) -> tuple[list[np.ndarray], dict[str, int], Diagnostic | None]:
    limits = np.asarray(robot.joint_limits, dtype=np.float64)
    lo, hi = limits[:, 0], limits[:, 1]
    scale = 1.0 / np.asarray(robot.velocity_limits, dtype=np.float64)
    edge_free = edge_check(space, q_start, q_goal, free.clearance)

    rng = np.random.default_rng(int(key[:16], 16))
    found = search_path(q_start, q_goal, lo, hi, scale, edge_free, rng, free.samples, free.budget)
    if found.path is None:
        if found.stopped == "time":
            why = (f"its time budget of {free.budget:g} s ran out after {found.samples} of {free.samples} samples "
                   "(a safety stop: raise it with 'budget', or the sample budget decides)")
        else:
            why = f"none within the budget of {free.samples} samples (raise it with 'samples N')"
        message = (f"a 'move free' must find a collision-free path keeping {free.clearance * 1000:g} mm clearance: "
                   f"no path was found: {why}")
        return [], {}, Diagnostic(codes.FREE_NO_PATH, Severity.ERROR, message, None)
    path = shorten([np.asarray(q, dtype=float) for q in found.path], lambda a, b: edge_free(a, b, BLEND_ROOM), rng, scale)
    return path, {"samples": found.samples, "segments": space.edges}, None


def _key(space: FreeSpace, q_start: np.ndarray, q_goal: np.ndarray, free: ir.FreeMotion) -> str:
    """SHA-256 of everything the search depends on: the search's seed and its cache key."""
    h = hashlib.sha256(FORMAT.encode() + b"\0" + space.robot.encode() + b"\0")
    for a in (q_start, q_goal, np.array([free.clearance, float(free.samples)])):
        h.update(np.ascontiguousarray(a, dtype="<f8").tobytes())
    for body in space.scene.bodies:
        h.update(body.name.encode() + b"\0" + body.kind.encode() + repr(body.shape).encode())
        h.update(np.ascontiguousarray(body.local, dtype="<f8").tobytes())
    for name in sorted(space.others):
        h.update(name.encode() + np.ascontiguousarray(space.others[name], dtype="<f8").tobytes())
    h.update(repr(sorted((a.name, b.name) for a, b in space.pairs)).encode())
    return h.hexdigest()


def _cached_path(store: PathStore, key: str) -> tuple[list[np.ndarray] | None, dict[str, int] | None]:
    """A path found before under `key` (None when absent or not a well-formed entry)."""
    data = store.load(key)
    if data is None:
        return None, None
    try:
        doc = json.loads(data.decode("utf-8"))
        if doc.get("key") != key:
            return None, None
        path = [np.asarray(q, dtype=float) for q in doc["path"]]
        outcome = {k: int(v) for k, v in doc["outcome"].items()}
    except (ValueError, KeyError, TypeError, AttributeError, RecursionError):
        return None, None
    if len(path) < 2 or any(q.ndim != 1 or not np.all(np.isfinite(q)) for q in path):
        return None, None
    return path, outcome


def _store_path(store: PathStore, key: str, path: list[np.ndarray], outcome: dict[str, int]) -> None:
    doc = {"key": key, "path": [[float(v) for v in q] for q in path], "outcome": outcome}
    store.save(key, json.dumps(doc, sort_keys=True).encode())


# --------------------------------------------------------------------------- emit


def _rewritten(program: ir.Program, task: ir.Task, move: ir.Move, vias: list[tuple[float, ...]], zone: float,
               q_goal_branch: ir.Config | None) -> ir.Program:
    """The program with `move` preceded by joint moves to the via points."""
    next_uid = 1 + max(i.uid for t in program.tasks for i in ir_tree.walk(t.body))
    stem = move.target.name or "free"
    motion = replace(move.motion, zone=ir.Zone(zone))
    via_moves = [ir.Move(uid=next_uid + k, kind=ir.MotionKind.JOINT, target=ir.JointTarget(q, f"{stem}_via{k + 1}"),
                         motion=motion, tool=move.tool, frame=move.frame, span=move.span) for k, q in enumerate(vias)]
    last = move
    if q_goal_branch is not None and isinstance(move.target, ir.CartesianTarget):
        c = move.config  # the branch the search planned to, where the program left it free
        last = replace(move, config=replace(c, shoulder=c.shoulder or q_goal_branch.shoulder,
                                            elbow=c.elbow or q_goal_branch.elbow, wrist=c.wrist or q_goal_branch.wrist))
    body: list[ir.Instr] = []
    for instr in task.body:
        body += [*via_moves, last] if instr.uid == move.uid else [instr]
    tasks = tuple(replace(t, body=tuple(body)) if t.name == task.name else t for t in program.tasks)
    return replace(program, tasks=tasks)


def _emit(program: ir.Program, plan_fn: PlanFn, space: FreeSpace, task: ir.Task, move: ir.Move,
          rec: plan_types.InstructionRecord, vias: list[tuple[float, ...]], path: list[np.ndarray],
          outcome: dict[str, int] | None) -> tuple[ir.Program, list[Diagnostic]]:
    free = move.free
    assert free is not None
    if not vias:
        note = "a 'move free' found the straight joint move free: no via points inserted"
        return program, [_finding(codes.FREE_PATH, note, move, task, Severity.NOTE)]
    ends = min(_slack(space, path[0], free.clearance), _slack(space, path[-1], free.clearance))
    chosen, zone = program, 0.0
    for zone in VIA_ZONES:
        chosen = _rewritten(program, task, move, vias, zone, rec.branch)
        if zone == 0.0 or _timed_clean(chosen, plan_fn, space, task.name, move.uid, ends):
            break
    return chosen, [_finding(codes.FREE_PATH, _note(space, vias, zone, path, outcome), move, task, Severity.NOTE)]


def _timed_clean(program: ir.Program, plan_fn: PlanFn, space: FreeSpace, task_name: str, uid: int,
                 clearance: float) -> bool:
    """The timed path through the vias (blends included) verifies clean in the move's window,
    and no fixture lies in a via's zone sphere, where a controller's corner path may run
    (sim/corners.py: W340 would follow at every target)."""
    plan = plan_fn(program)
    if any(d.is_error for d in plan.diagnostics):
        return False
    tp = next(p for p in plan.tasks if p.task.name == task_name)
    task = tp.task
    index = next(k for k, i in enumerate(task.body) if i.uid == uid)
    moves = [i for i in task.body[:index + 1] if isinstance(i, ir.Move)]
    first = next(i for i in reversed(moves[:-1]) if not _is_via(i, moves[-1])) if len(moves) > 1 else moves[0]
    r0, r1 = tp.record(first.uid), tp.record(uid)
    if r0 is None or r1 is None:
        return False
    window = robot_timeline(plan, space.scene, r0.t_end, r1.t_end)
    hits = check_timeline(space.scene, window, space.pairs, clearance)
    if [h for h in hits if h.kind != "static" and space._counts(h)]:
        return False
    span = task.body[index].span
    return not any(d.code == codes.CORNER_SPHERE and d.span == span for d in corner_findings(space.scene, [tp]))


def _is_via(instr: ir.Move, move: ir.Move) -> bool:
    return instr.span == move.span and isinstance(instr.target, ir.JointTarget) and instr.uid > move.uid


def _note(space: FreeSpace, vias: list[tuple[float, ...]], zone: float, path: list[np.ndarray],
          outcome: dict[str, int] | None) -> str:
    robot = space.scene.robots[space.robot].robot
    kinds = robot.joint_types
    points = "; ".join(
        "joints(" + ", ".join(f"{v * 1000:.1f} mm" if kinds[j] == "P" else f"{math.degrees(v):.2f}" for j, v in enumerate(q))
        + (")" if "P" in kinds else ") deg") for q in vias)
    where = "fine" if zone == 0.0 else f"zone {zone * 1000:g} mm"
    found = f", found after {outcome['samples']} samples" if outcome else ""
    return (f"'move free' inserted {len(vias)} via point{'s' * (len(vias) != 1)} ({where}): {points}; "
            f"joint path {path_length(path):.3f} rad{found}")
