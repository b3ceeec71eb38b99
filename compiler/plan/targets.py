"""Targets: one joint solution per move target, with the IK branch chosen as a programmer expects.

Rules (LANGUAGE.md "Motion"):
* A joint target is used as written (checked against the joint limits).
* A pose target of a **joint** move takes the branch `config(...)` names (None fields free);
  among the allowed solutions the one nearest the current joints. If no `config` field is
  named and the nearest solution lies on another branch than the current joints, the move is
  planned (the programmer asked for a joint move) but warned about (W220), naming the branch
  change and the `config(...)` that makes it explicit: never a *silent* flip.
* A pose target of a **linear or circular** move must lie on the current branch (a Cartesian
  path cannot change branch); a `config(...)` that differs from the current branch, or a target
  reachable only on another branch, is an error (E222) saying which branch changes and how to
  fix it (insert a joint move with that config before the move).
* `config(jN=n)` fixes joint N's turn at the target: turn n = q in
  [n*360 - 180, n*360 + 180) deg (ir.turn_of). Only on a joint whose range spans more than
  360 deg (E172) and only a turn that meets the joint's limits (E173). A joint move takes the
  nearest solution on those turns (E174 when none is); a linear or circular move follows its
  path, so the path's end must be on them (E174 otherwise, checked in segments.py).
* The initial joints of a task: the first move's target — its joint values, or its IK solution
  (respecting config) nearest the "home" joints (all zeros clamped into the joint limits).
  The first move therefore takes no time: the robot is assumed to start there.
* The motion *to* that first target is not planned: the vendor program makes it from wherever
  the robot stands. Only a joint move to a joint target reaches a known joint state from any
  start (RAPID MoveAbsJ, KRL PTP to an axis position); any other first move (linear, circular,
  or a joint move to a pose, whose IK branch at the start is a guess) is warned about (W224).

Everything returns values: (q or None, [Finding]) with user-facing messages.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence

import numpy as np

from rmot.lang import ir
from rmot.lang.ir_tree import Runs, flow
from rmot.compiler.plan import codes
from rmot.lang.diagnostics import Code, Severity
from rmot.compiler.plan.robot_model import RobotModel
from rmot.lang.record import record

__all__ = [
    "Finding", "branch_changes", "flange_target", "home_joints", "initial_joints", "off_turns",
    "solve_target", "unknown_starts",
]


@record
class Finding:
    code: Code
    severity: Severity
    message: str


def flange_target(move: ir.Move, target: ir.CartesianTarget | None = None) -> np.ndarray:
    """The flange pose (4, 4) in the robot base for a TCP target: target * inv(tool.tcp)."""
    t = target if target is not None else move.target
    assert isinstance(t, ir.CartesianTarget)
    return t.pose.matrix() @ move.tool.tcp.inverse().matrix()


def home_joints(robot: RobotModel) -> np.ndarray:
    """All zeros clamped into the joint limits (dof,)."""
    lim = robot.joint_limits
    return np.clip(np.zeros(lim.shape[0]), lim[:, 0], lim[:, 1])


def branch_changes(old: ir.Config, new: ir.Config) -> list[tuple[str, str, str]]:
    """[(field, old value, new value)] for every set field that differs."""
    out = []
    for name in ("shoulder", "elbow", "wrist"):
        a, b = getattr(old, name), getattr(new, name)
        if a is not None and b is not None and a != b:
            out.append((name, a.value, b.value))
    return out


def _merge(base: ir.Config, override: ir.Config) -> ir.Config:
    return ir.Config(
        override.shoulder or base.shoulder, override.elbow or base.elbow, override.wrist or base.wrist
    )


def _config_text(changes: list[tuple[str, str, str]]) -> str:
    return "config(" + ", ".join(f"{f}={new}" for f, _, new in changes) + ")"


def _change_text(changes: list[tuple[str, str, str]]) -> str:
    return " and ".join(f"the {f} from {old} to {new}" for f, old, new in changes)


def check_joint_values(robot: RobotModel, values: tuple[float, ...]) -> tuple[np.ndarray | None, list[Finding]]:
    """A joint target as an array, or a finding for a wrong count or a limit excess."""
    dof = robot.dof
    if len(values) != dof:
        msg = f"a joint target must have {dof} values for this robot (got {len(values)})"
        return None, [Finding(codes.DOF_MISMATCH, Severity.ERROR, msg)]
    q = np.asarray(values, dtype=float)
    lim = robot.joint_limits
    for j in range(dof):
        if not lim[j, 0] - 1e-9 <= q[j] <= lim[j, 1] + 1e-9:
            rev = robot.joint_types[j] == "R"
            f, unit = (np.degrees, "deg") if rev else ((lambda x: x * 1e3), "mm")
            msg = (f"joint {j + 1} must be within [{f(lim[j, 0]):.1f}, {f(lim[j, 1]):.1f}] {unit} "
                   f"(got {f(q[j]):.1f} {unit})")
            return None, [Finding(codes.JOINT_TARGET_LIMIT, Severity.ERROR, msg)]
    return q, []


def _no_solution(robot: RobotModel, flange: np.ndarray, seed: np.ndarray, result: object) -> Finding:
    """The error for a pose with no solution at all (unreachable or out of limits)."""
    status = getattr(result, "status", None)
    name = getattr(status, "name", "")
    text = getattr(result, "message", "") or "no IK solution"
    if name == "OUT_OF_LIMITS":
        return Finding(codes.TARGET_LIMITS, Severity.ERROR, f"target must be reachable within the joint limits ({text})")
    dist = float(getattr(result, "distance", 0.0) or 0.0)
    where = f"{dist * 1e3:.1f} mm outside the workspace" if dist > 0 else text
    return Finding(codes.TARGET_UNREACHABLE, Severity.ERROR, f"target must be within the robot's reach ({where})")


def solve_target(
    robot: RobotModel, move: ir.Move, q_now: np.ndarray
) -> tuple[np.ndarray | None, list[Finding]]:
    """The joints (dof,) at the move's target, chosen by the branch rules above."""
    if isinstance(move.target, ir.JointTarget):
        return check_joint_values(robot, move.target.values)
    bad = turn_range_findings(robot, move.config.turns)
    if bad:
        return None, bad
    flange = flange_target(move)
    current = robot.branch(q_now)
    if _any_config(move.config) and not _any_config(current):
        msg = (f"config({move.config}) needs an arm with branch names (a 6R arm with a spherical wrist); "
               f"robot '{robot.name}' has none, so no branch can be chosen: drop the config")
        return None, [Finding(codes.CONFIG_WITHOUT_BRANCHES, Severity.ERROR, msg)]
    if move.kind is ir.MotionKind.JOINT:
        return _solve_joint_move(robot, move, flange, q_now, current)
    return _solve_cartesian(robot, move, flange, q_now, current)


def _ik(robot: RobotModel, flange: np.ndarray, seed: np.ndarray, config: ir.Config | None):  # type: ignore[no-untyped-def]
    """robot.ik, plus (for robots without a closed form) a local Newton solve from the seed when
    the library's global search finds nothing: the seed is usually close to the target."""
    res = robot.ik(flange, seed=seed, config=config)
    if res.solutions or robot.has_closed_form:
        return res
    from rmot.compiler.plan.dense import newton_ik  # late: loads coal only when this runs

    q = newton_ik(robot, flange, seed, iters=50)
    lim = robot.joint_limits
    if q is None or np.any(q < lim[:, 0] - 1e-9) or np.any(q > lim[:, 1] + 1e-9):
        return res
    if config is not None and branch_changes(robot.branch(q), config):  # the local solve ignores the config
        return res
    return _Local((q,))


@record
class _Local:
    """A stand-in IkResult holding solutions found by the local solve."""

    solutions: tuple[np.ndarray, ...]


def _any_config(c: ir.Config) -> bool:
    return any(v is not None for v in (c.shoulder, c.elbow, c.wrist))


def _solve_joint_move(robot: RobotModel, move: ir.Move, flange: np.ndarray, q_now: np.ndarray,
                      current: ir.Config) -> tuple[np.ndarray | None, list[Finding]]:
    wanted = move.config if _any_config(move.config) else None
    res = _ik(robot, flange, q_now, wanted)
    on_turns = _on_turns(robot, res.solutions, move.config.turns, q_now)
    if res.solutions and not on_turns:
        return None, [_turn_unreached(move.config.turns, res.solutions)]
    if on_turns:
        q = np.asarray(on_turns[0], dtype=float)
        changes = [c for c in branch_changes(current, robot.branch(q)) if getattr(move.config, c[0]) is None]
        if not changes:
            return q, []
        msg = (f"joint move changes {_change_text(changes)} (the nearest solution); "
               f"write {_config_text(changes)} to make the change explicit")
        return q, [Finding(codes.BRANCH_CHANGE_JOINT, Severity.WARNING, msg)]
    if wanted is not None:
        free = _ik(robot, flange, q_now, None)
        if free.solutions:
            other = robot.branch(np.asarray(free.solutions[0]))
            msg = (f"target must be reachable with config({wanted}) (it is reachable only with "
                   f"config({other}); change or drop the config)")
            return None, [Finding(codes.BRANCH_CHANGE, Severity.ERROR, msg)]
    return None, [_no_solution(robot, flange, q_now, res)]


def _solve_cartesian(robot: RobotModel, move: ir.Move, flange: np.ndarray, q_now: np.ndarray,
                     current: ir.Config) -> tuple[np.ndarray | None, list[Finding]]:
    kind = move.kind.name.lower()
    explicit = branch_changes(current, move.config)
    if explicit:
        msg = (f"a {kind} move cannot change {_change_text(explicit)}; insert a joint move with "
               f"{_config_text(explicit)} before it")
        return None, [Finding(codes.BRANCH_CHANGE, Severity.ERROR, msg)]
    branch = _merge(current, move.config)
    res = _ik(robot, flange, q_now, branch if _any_config(branch) else None)
    if res.solutions:
        return np.asarray(res.solutions[0], dtype=float), []
    free = _ik(robot, flange, q_now, None)
    if free.solutions:
        changes = branch_changes(current, robot.branch(np.asarray(free.solutions[0])))
        msg = (f"target of a {kind} move must be reachable on the current branch; it needs "
               f"{_change_text(changes) or 'another branch'}: insert a joint move with "
               f"{_config_text(changes) if changes else 'config(...)'} before it")
        return None, [Finding(codes.BRANCH_CHANGE, Severity.ERROR, msg)]
    return None, [_no_solution(robot, flange, q_now, res)]


def initial_joints(robot: RobotModel, body: tuple[ir.Instr, ...]) -> np.ndarray:
    """Where the task starts (see module doc); home if the first target cannot be solved."""
    home = home_joints(robot)
    first = next((i for i in _main_line(body) if isinstance(i, ir.Move)), None)
    if first is None:
        return home
    if isinstance(first.target, ir.JointTarget):
        q, found = check_joint_values(robot, first.target.values)
        return q if q is not None else home
    config = first.config if _any_config(first.config) else None
    res = _ik(robot, flange_target(first), home, config)
    on_turns = _on_turns(robot, res.solutions, first.config.turns, home)
    return np.asarray(on_turns[0], dtype=float) if on_turns else home


def turn_range_findings(robot: object, turns: tuple[tuple[int, int], ...]) -> list[Finding]:
    """E172 for a turn fixed on a joint whose range spans at most 360 deg (its value alone
    fixes its turn), E173 for a turn whose interval misses the joint's limits."""
    lim = robot.joint_limits  # type: ignore[attr-defined]
    out = []
    for j, n in turns:
        lo, hi = float(lim[j, 0]), float(lim[j, 1])
        span = f"[{np.degrees(lo):.1f}, {np.degrees(hi):.1f}] deg"
        if hi - lo <= 2 * np.pi + 1e-9:
            msg = (f"joint {j + 1} must span more than 360 deg for config(j{j + 1}=...) "
                   f"(its limits are {span}: every value has one turn already); "
                   f"drop j{j + 1}={n}")
            out.append(Finding(codes.TURN_RANGE_TOO_SMALL, Severity.ERROR, msg))
            continue
        first, last = ir.turn_of(lo), ir.turn_of(hi)
        if not first <= n <= last:
            msg = (f"joint {j + 1} turn {n} must lie within its limits {span} (turn {n} is "
                   f"[{n * 360 - 180}, {n * 360 + 180}) deg; "
                   f"the limits allow turns {first} to {last})")
            out.append(Finding(codes.TURN_OUTSIDE_LIMITS, Severity.ERROR, msg))
    return out


def _on_turns(robot: object, solutions: Sequence[np.ndarray], turns: tuple[tuple[int, int], ...],
              q_now: np.ndarray) -> list[np.ndarray]:
    """The solutions on the fixed turns, nearest to q_now first. A solution on another turn is
    moved onto it by whole turns (a revolute joint is 2 pi periodic) when that stays within
    the limits: a local IK (URDF arms) returns one equivalent only. Without fixed turns: the
    nearest solution alone (the callers read the first one; a UR arm has 512, made on demand)."""
    if not turns:
        return list(solutions[:1])
    on = [q for q in solutions if not off_turns(q, turns)]
    if on or not turns:
        return on
    lim = robot.joint_limits  # type: ignore[attr-defined]
    shifted = []
    for q in solutions:
        s = np.array(q, dtype=float)
        for j, n in turns:
            s[j] += 2 * np.pi * (n - ir.turn_of(float(s[j])))
        inside = np.all(s >= lim[:, 0] - 1e-9) and np.all(s <= lim[:, 1] + 1e-9)
        if inside and not off_turns(s, turns):
            shifted.append(s)
    return sorted(shifted, key=lambda s: float(np.linalg.norm(s - q_now)))


def off_turns(q: np.ndarray, turns: tuple[tuple[int, int], ...]) -> list[tuple[int, int, int]]:
    """[(joint index, wanted turn, actual turn)] for every fixed turn q is not on."""
    return [(j, n, ir.turn_of(float(q[j]))) for j, n in turns if ir.turn_of(float(q[j])) != n]


def _turn_unreached(turns: tuple[tuple[int, int], ...],
                    solutions: Sequence[np.ndarray]) -> Finding:
    wanted = ", ".join(f"joint {j + 1} on turn {n}" for j, n in turns)
    found = ", ".join(
        f"joint {j + 1} on turn{'s' * (len(ts) > 1)} {', '.join(str(t) for t in ts)}"
        for j, _ in turns for ts in [sorted({ir.turn_of(float(q[j])) for q in solutions})])
    msg = (f"target must be reachable with {wanted} within the joint limits "
           f"(its solutions have {found}); change or drop the turn")
    return Finding(codes.TURN_NOT_REACHED, Severity.ERROR, msg)


def _main_line(body: tuple[ir.Instr, ...]) -> Iterator[ir.Instr]:
    """Instructions on the main timeline in order: then-arms of ifs, proc bodies, loops and
    whiles entered; a wait's timeout branch is not on it; it ends at a `stop`."""
    for instr in body:
        if isinstance(instr, ir.Stop):
            return
        runs, bodies = flow(instr)
        if runs is Runs.ONE_OF:
            yield from _main_line(bodies[0])
        elif runs in (Runs.CALL, Runs.ITERATIONS, Runs.REPEATED):
            for sub in bodies:
                yield from _main_line(sub)
        else:  # a leaf, or a wait whose timeout branch is off the main timeline
            yield instr


def unknown_starts(task: ir.Task) -> list[tuple[ir.Move, Finding]]:
    """W224 for every move that can be the task's first motion and is not a joint move to a
    joint target (one per path through runtime ifs that reach a move before any other move)."""
    out = []
    for move in _first_moves(task.body)[0]:
        if move.kind is ir.MotionKind.JOINT and isinstance(move.target, ir.JointTarget):
            continue
        got = ("a joint move to a pose" if move.kind is ir.MotionKind.JOINT
               else f"a {move.kind.name.lower()} move")
        msg = (f"the first move of task '{task.name}' must be a joint move to a joint target (got {got}): "
               "it starts from wherever the robot stands, which rmot cannot verify; start with e.g. "
               "`move joint home` and `target home = joints(...)`")
        out.append((move, Finding(codes.UNKNOWN_START, Severity.WARNING, msg)))
    return out


def _first_moves(body: tuple[ir.Instr, ...]) -> tuple[list[ir.Move], bool]:
    """The moves that can come first on some path through `body`, and whether every path has one."""
    found: list[ir.Move] = []
    for instr in body:
        if isinstance(instr, ir.Move):
            return found + [instr], True
        if isinstance(instr, ir.Stop):
            return found, True  # this path ends without a move
        runs, bodies = flow(instr)
        if runs is Runs.LEAF:
            continue
        if runs is Runs.ONE_OF:
            arms = list(bodies)
        else:  # the bodies one after another (a loop's iterations), run once or maybe not
            arms = [tuple(i for sub in bodies for i in sub)]
            if not runs.sure:  # a while or a timeout branch may not run
                arms.append(())
        results = [_first_moves(arm) for arm in arms]
        found += [m for moves, _ in results for m in moves]
        if all(done for _, done in results):
            return found, True
    return found, False
