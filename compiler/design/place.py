"""Base placement: where in a region to put a robot so that every given program verifies, and
which such pose is best.

    result = place([program, ...], "r1", {"x": (0.0, 1.0), "y": (-0.5, 0.5), "rz": (-pi, pi)})

The search, in three stages (each measured in tests/benchmarks/bench_place.py):

1. Screening, global: `SCREEN` candidate poses from a Halton sequence over the region (low
   discrepancy: no clumps and no gaps, and the same candidates every run). For each, every
   Cartesian target of the robot's tasks goes through the robot's IK in one batch (the
   requested branch where a move names one); a candidate where any target has no solution
   within the joint limits is out. The survivors are ranked by a motion-time estimate: along
   the targets in program order, the slowest joint's travel over its speed limit (nearest
   solution to the previous one).
2. Verification: the survivors are planned and verified in full in ranked order, exactly as
   `rmot check` does (reach, branches, joint limits, collisions, payload torque), until
   `VERIFY` of them verify; past `VERIFY_CAP` × `VERIFY` tried, only until one verifies. Every
   screen-feasible pose may be checked, up to `VERIFY_BUDGET`: the poses
   ranked first all sit near the work, and a near pose that collides says nothing of a far one.
3. Refinement, local: a compass search from each of the `REFINE_STARTS` best verified poses
   (each coordinate ± a step, halving the step when nothing improves), every trial screened
   then verified.

Objective: "cycle" (default) = the sum of the programs' cycle times, ties (within 1 ms)
broken by the larger worst joint-limit margin, then by the larger worst manipulability;
"margin" = the worst joint-limit margin first, then manipulability, then cycle time.

A move whose frame is the robot's base (the default frame) keeps its target relative to the
base: it moves with the robot. Every other target stays where it is in the world.
What is placed is a `Mover`: the robot's base here, or the track a robot rides on
(compiler/design/place_track.py), each with its own screening and rebasing.
cvxpy is not used: no stage is a convex problem (reachability is a non-convex set of poses and
the cycle time a black box of the planner), see the commit that dropped it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from rmot.lang import ir, ir_tree
from rmot.lang.ir_tree import children, rebuilt
import time

__all__ = ["Candidate", "Mover", "Placement", "halton", "place", "rebase", "world_targets"]

SCREEN = 256
VERIFY = 6
REFINE_ROUNDS = 2
REFINE_STARTS = 3
VERIFY_CAP = 4  # past this many times verify_n poses checked in full, the search stops at the first that verifies
TIE_S = 1e-3
# Policy: at most 256 poses (the default screening sample) are planned and verified in full,
# about 0.3 s each: a search that finds none stays within minutes.
VERIFY_BUDGET = 256


def halton(n: int, dims: int, skip: int = 1) -> np.ndarray:
    """(n, dims) points of the Halton sequence in [0, 1)^dims (bases 2, 3, 5, 7)."""
    bases = (2, 3, 5, 7)[:dims]
    out = np.zeros((n, dims))
    for d, b in enumerate(bases):
        for i in range(n):
            k, f, x = i + skip, 1.0, 0.0
            while k > 0:
                f /= b
                x += f * (k % b)
                k //= b
            out[i, d] = x
    return out


# --------------------------------------------------------------------------- rebasing


def _pose_in(new_inv: ir.Pose, old: ir.Pose, target: ir.Pose) -> ir.Pose:
    return new_inv * (old * target)


def _rebase_move(m: ir.Move, slot: str, old: ir.Pose, new: ir.Pose) -> ir.Move:
    if m.frame.name is None or m.frame.name == slot or not isinstance(m.target, ir.CartesianTarget):
        return m  # base-relative (or a joint target): moves with the robot
    inv = new.inverse()
    target = replace(m.target, pose=_pose_in(inv, old, m.target.pose))
    via = replace(m.via, pose=_pose_in(inv, old, m.via.pose)) if m.via is not None else None
    return replace(m, target=target, via=via, frame=replace(m.frame, pose=inv * m.frame.world))


def _rebase_body(body: tuple[Any, ...], slot: str, old: ir.Pose, new: ir.Pose) -> tuple[Any, ...]:
    out = []
    for instr in body:
        if isinstance(instr, ir.Move):
            instr = _rebase_move(instr, slot, old, new)
        else:  # every body an instruction holds (ir_tree: if arms, proc bodies, loops, ...)
            instr = rebuilt(instr, tuple(_rebase_body(b, slot, old, new) for b in children(instr)))
        out.append(instr)
    return tuple(out)


def rebase(program: ir.Program, slot: str, base: np.ndarray) -> ir.Program:
    """The program with robot `slot` at `base` (4,4) world; world-fixed targets re-expressed."""
    old = program.cell.robot(slot).base
    new = ir.Pose.from_matrix(np.asarray(base, dtype=float))
    robots = tuple(replace(r, base=new) if r.name == slot else r for r in program.cell.robots)
    tasks = tuple(replace(t, body=_rebase_body(t.body, slot, old, new)) if t.robot == slot else t for t in program.tasks)
    return replace(program, cell=replace(program.cell, robots=robots), tasks=tasks)


# --------------------------------------------------------------------------- screening


@dataclass(frozen=True, eq=False)
class Targets:
    """The Cartesian flange targets of a robot's tasks: world-fixed ones (N,4,4) world and
    base-relative ones (M,4,4) base; the branch each asks for; their moves' spans."""

    world: np.ndarray
    relative: np.ndarray
    configs: tuple[ir.Config, ...]
    spans: tuple[Any, ...]


def world_targets(program: ir.Program, slot: str) -> Targets:
    base = program.cell.robot(slot).base
    world, rel, cfg_w, cfg_r, span_w, span_r = [], [], [], [], [], []
    for task in program.tasks:
        if task.robot != slot:
            continue
        for m in ir_tree.walk(task.body):
            if not isinstance(m, ir.Move) or not isinstance(m.target, ir.CartesianTarget):
                continue
            tcp_inv = m.tool.tcp.inverse()
            for t in (m.target,) + ((m.via,) if m.via is not None else ()):
                flange = t.pose * tcp_inv
                if m.frame.name is None or m.frame.name == slot:
                    rel.append(flange.matrix())
                    cfg_r.append(m.config)
                    span_r.append(m.span)
                else:
                    world.append((base * flange).matrix())
                    cfg_w.append(m.config)
                    span_w.append(m.span)
    return Targets(np.array(world).reshape(-1, 4, 4), np.array(rel).reshape(-1, 4, 4),
                   tuple(cfg_w + cfg_r), tuple(span_w + span_r))


def _branch_ok(robot: Any, sols: np.ndarray, configs: tuple[ir.Config, ...]) -> np.ndarray:
    """(N, 8, dof) -> (N,) bool: a solution exists on the requested branch (any branch if none asked)."""
    exists = np.all(np.isfinite(sols), axis=2)
    rows = getattr(robot, "batch_branches", None)
    ok = exists.any(axis=1)
    if rows is None:
        return ok
    for i, cfg in enumerate(configs):
        if cfg == ir.Config():
            continue
        match = [all(getattr(cfg, f) in (None, getattr(b, f)) for f in ("shoulder", "elbow", "wrist")) for b in rows]
        ok[i] = bool(np.any(exists[i] & np.array(match)))
    return ok


def screen(robot: Any, targets: Targets, base: np.ndarray) -> tuple[np.ndarray, float]:
    """(reachable (N,) bool per target, estimated motion time s) for the robot at `base`."""
    if len(targets.configs) == 0:
        return np.zeros(0, bool), 0.0
    inv = np.linalg.inv(base)
    flange = np.concatenate([inv @ targets.world, targets.relative])
    sols = robot.ik_batch(flange)
    ok = _branch_ok(robot, sols, targets.configs)
    if not ok.all():
        return ok, math.inf
    vmax = np.asarray(robot.velocity_limits)
    q_prev, total = None, 0.0
    for cand in sols:
        good = cand[np.all(np.isfinite(cand), axis=1)]
        if q_prev is None:
            q_prev = good[0]
            continue
        step = np.max(np.abs(good - q_prev) / vmax, axis=1)
        k = int(np.argmin(step))
        total += float(step[k])
        q_prev = good[k]
    return ok, total


class Mover:
    """What a placement moves, and how a candidate pose is screened and applied: the robot's
    base (this class), or a track that carries it (compiler/design/place_track.py).
    `old`: the placed thing's pose in the cell (4, 4) world; `spans`: the screened targets' moves."""

    def __init__(self, programs: list[ir.Program], slot: str, robot: Any) -> None:
        self.slot = slot
        self.robot = robot
        self.old = programs[0].cell.robot(slot).base.matrix()
        self.targets = [world_targets(p, slot) for p in programs]
        self.spans = tuple(s for t in self.targets for s in t.spans)

    def screen(self, pose: np.ndarray) -> tuple[np.ndarray, float]:
        """(reachable per target, estimated motion time) with the placed thing at `pose`."""
        oks, est = [], 0.0
        for t in self.targets:
            ok, e = screen(self.robot, t, pose)
            oks.append(ok)
            est += e
        return (np.concatenate(oks) if oks else np.zeros(0, bool)), est

    def rebase(self, program: ir.Program, pose: np.ndarray) -> ir.Program:
        return rebase(program, self.slot, pose)


# --------------------------------------------------------------------------- search


@dataclass(frozen=True, eq=False)
class Candidate:
    """A verified (or failed) base pose: x, y, z (m), rz (rad), and the full check's numbers."""

    base: np.ndarray
    verified: bool
    cycle_time: float
    margin: float
    manipulability: float
    first_error: Any = None

    def key(self, objective: str) -> tuple[float, ...]:
        cyc = round(self.cycle_time / TIE_S)
        if objective == "margin":
            return (-round(self.margin, 6), -self.manipulability, cyc)
        return (cyc, -round(self.margin, 6), -self.manipulability)

    def describe(self) -> str:
        x, y, z = self.base[:3, 3]
        rz = math.degrees(math.atan2(self.base[1, 0], self.base[0, 0]))
        return f"x={x * 1000:.1f}mm, y={y * 1000:.1f}mm, z={z * 1000:.1f}mm, rz={rz:.1f}deg"


@dataclass(frozen=True, eq=False)
class Placement:
    best: Candidate | None
    runners_up: tuple[Candidate, ...]
    screened: int
    screen_feasible: int
    verified_count: int
    failures: tuple[str, ...] = ()  # what fails where, when no pose works
    stats: dict[str, float] = field(default_factory=dict)
    passing: int = 0  # of the verified_count poses checked in full, those that verify (the only ones ranked)


def _base_from(region: dict[str, tuple[float, float]], u: np.ndarray, old: np.ndarray) -> np.ndarray:
    """A base pose from unit coordinates u over the region's axes (x, y, then z, rz if given);
    axes not in the region keep the cell's value; the tilt of the old base is kept."""
    keys = [k for k in ("x", "y", "z", "rz") if k in region]
    vals = {k: region[k][0] + (region[k][1] - region[k][0]) * float(u[i]) for i, k in enumerate(keys)}
    rz0 = math.atan2(old[1, 0], old[0, 0])
    rz = vals.get("rz", rz0)
    c, s = math.cos(rz - rz0), math.sin(rz - rz0)
    turn = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])
    base = np.eye(4)
    base[:3, :3] = turn @ old[:3, :3]
    base[:3, 3] = [vals.get("x", old[0, 3]), vals.get("y", old[1, 3]), vals.get("z", old[2, 3])]
    return base


def _evaluate(programs: list[ir.Program], slot: str, base: np.ndarray, mover: Mover | None = None) -> Candidate:
    from rmot.compiler.plan import plan_program  # late: tests replace it (monkeypatch): read at call time
    from rmot.sim import verify  # late: loads subprocess only when this runs
    from rmot.compiler.design.metrics import program_metrics  # late: loads coal only when this runs

    cycle, margin, manip, first = 0.0, math.inf, math.inf, None
    for program in programs:
        plan = plan_program(rebase(program, slot, base) if mover is None else mover.rebase(program, base))
        report = verify(plan)
        if report.has_errors and first is None:
            first = report.errors[0]
        cycle += float(report.cycle_time or 0.0)
        for m in program_metrics(plan).values():
            if m.robot == slot:
                margin, manip = min(margin, m.margin), min(manip, m.manipulability)
    return Candidate(base, first is None, cycle, margin, manip, first)


def place(programs: list[ir.Program], slot: str, region: dict[str, tuple[float, float]], *,
          objective: str = "cycle", screen_n: int = SCREEN, verify_n: int = VERIFY,
          refine_rounds: int = REFINE_ROUNDS, robot: Any = None, mover: Mover | None = None) -> Placement:
    """The best base pose in `region` (see the module docstring); `mover`: what is placed (default
    the robot's base)."""

    from rmot.sim.robots import load_robot  # late: loads coal only when this runs

    if objective not in ("cycle", "margin"):
        raise ValueError(f"objective must be 'cycle' or 'margin' (got {objective!r})")
    robot = robot or load_robot(programs[0].cell.robot(slot).source.load_key)
    mover = mover or Mover(programs, slot, robot)
    keys = [k for k in ("x", "y", "z", "rz") if k in region]
    t0 = time.perf_counter()
    units = halton(screen_n, len(keys))
    scored, fail_counts = [], np.zeros(len(mover.spans))
    for u in units:
        base = _base_from(region, u, mover.old)
        ok_all, est = mover.screen(base)
        fail_counts += ~ok_all
        if ok_all.all():
            scored.append((est, tuple(u), base))
    t1 = time.perf_counter()
    scored.sort(key=lambda s: (s[0], s[1]))
    evaluated: list[Candidate] = []
    for _, _, base in scored[:VERIFY_BUDGET]:  # down the ranking until verify_n verify (one, past the cap) or none is left
        evaluated.append(_evaluate(programs, slot, base, mover))
        passing = sum(c.verified for c in evaluated)
        if passing >= verify_n or (passing and len(evaluated) >= VERIFY_CAP * verify_n):
            break
    t2 = time.perf_counter()
    evaluated += _refine(programs, slot, region, mover, evaluated, objective, refine_rounds, len(scored), screen_n)
    t3 = time.perf_counter()
    good = _distinct(sorted((c for c in evaluated if c.verified), key=lambda c: c.key(objective)))
    stats = {"screen_s": t1 - t0, "verify_s": t2 - t1, "refine_s": t3 - t2}
    failures = () if good else _failures(mover.spans, fail_counts, screen_n, evaluated)
    if not good and len(scored) > VERIFY_BUDGET:
        failures += (f"checked the first {VERIFY_BUDGET} of the {len(scored)} poses that reach every target in full "
                     "(the budget); a smaller region ranks fewer",)
    return Placement(good[0] if good else None, tuple(good[1:4]), screen_n, len(scored), len(evaluated), failures, stats,
                     sum(c.verified for c in evaluated))


def _distinct(cands: list[Candidate]) -> list[Candidate]:
    out: list[Candidate] = []
    for c in cands:
        if not any(np.allclose(c.base, o.base, atol=1e-9) for o in out):
            out.append(c)
    return out


def _refine(programs: list[ir.Program], slot: str, region: dict[str, tuple[float, float]], mover: Mover,
            evaluated: list[Candidate], objective: str, rounds: int,
            feasible: int, n: int, starts: int = REFINE_STARTS) -> list[Candidate]:
    """Compass search from each of the `starts` best verified poses (the feasible set is often
    disconnected: one start can sit in a worse pocket): ± step on each axis, halving the step
    when nothing improves."""
    good = _distinct(sorted((c for c in evaluated if c.verified), key=lambda c: c.key(objective)))
    out: list[Candidate] = []
    spans = {k: region[k][1] - region[k][0] for k in ("x", "y", "z", "rz") if k in region}
    for start in good[:starts] if rounds > 0 else []:
        best = start
        step = {k: v / (2 * max(n, 1) ** (1 / max(len(spans), 1))) for k, v in spans.items()}
        for _ in range(rounds):
            improved = False
            for key in spans:
                if step[key] <= 0:
                    continue
                for sign in (1, -1):
                    base = _nudge(best.base, key, sign * step[key], region)
                    if base is None or any(np.allclose(base, c.base, atol=1e-9) for c in evaluated + out):
                        continue
                    if not mover.screen(base)[0].all():
                        continue
                    cand = _evaluate(programs, slot, base, mover)
                    out.append(cand)
                    if cand.verified and cand.key(objective) < best.key(objective):
                        best, improved = cand, True
            if not improved:
                step = {k: v / 2 for k, v in step.items()}
    return out


def _nudge(base: np.ndarray, key: str, delta: float, region: dict[str, tuple[float, float]]) -> np.ndarray | None:
    new = base.copy()
    if key == "rz":
        rz = math.atan2(base[1, 0], base[0, 0]) + delta
        lo, hi = region["rz"]
        if not lo - 1e-12 <= rz <= hi + 1e-12:
            return None
        c, s = math.cos(delta), math.sin(delta)
        new[:3, :3] = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]]) @ base[:3, :3]
        return new
    axis = "xyz".index(key)
    new[axis, 3] += delta
    lo, hi = region[key]
    return new if lo - 1e-12 <= new[axis, 3] <= hi + 1e-12 else None


def _failures(spans: tuple[Any, ...], fail_counts: np.ndarray, n: int, evaluated: list[Candidate]) -> tuple[str, ...]:
    """What fails where: the targets unreachable from most sampled poses, and the first
    finding of each fully checked pose."""
    lines = []
    order = np.argsort(-fail_counts, kind="stable")
    seen = set()
    for i in order:
        if fail_counts[i] == 0:
            break
        span = spans[i]
        where = f"{span.path}:{span.start.line}:{span.start.col}" if span is not None else "a target"
        if where in seen:
            continue
        seen.add(where)
        lines.append(f"{where}: target unreachable (no IK solution within the joint limits) from "
                     f"{int(fail_counts[i])} of {n} sampled poses")
        if len(lines) >= 5:
            break
    for c in evaluated[:5]:
        d = c.first_error
        if d is None:
            continue
        where = f"{d.span.path}:{d.span.start.line}:{d.span.start.col}: " if d.span is not None else ""
        lines.append(f"at {c.describe()}: {where}error[{d.code.id}]: {d.message}")
    return tuple(lines)
