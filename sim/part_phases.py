"""Where every part is, and who holds it, between the attach/detach events of a Plan: the
*phases* sim/parts.py checks for collisions, and the pictures draw.

A part starts at its declared pose in the world. `attach p` (a record on the task's
timeline, at the instant the robot stops before it) fixes p to the robot's flange at the
relative pose it has then; `detach p` leaves it in the world where it is, for the rest of the
program (every later iteration, move and robot). Between two such events (a *phase*) every
part is either *placed* (a fixture at a world pose) or *held* (a body riding on a flange).

A feeder (`feeder infeed = box(...) at pose(...)`) presents one part at a time at its pose:
the first from the start, the next as soon as the one before has been taken and carried clear
of the spot (the first sample of the carrying robot at which the two solids are farther apart
than collide.CONTACT_TOL; a conveyor pushes the next carton in once the stop is free), and
none after its `count`. `attach infeed` takes the part waiting there; `detach infeed` puts
down the part of that feeder the robot holds. The parts are named by feeder and ordinal in the
order they are taken (`infeed#7`), in every finding and picture.

Problems only the plan can show (attach too far from the tool E330, held by another robot
E331, gripped too deep E333, taken from an empty feeder E334) name the loop iteration of the
attach, as every finding inside a loop does.
"""

from __future__ import annotations

import heapq
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from rmot.lang import ir, ir_tree, plan_types
from rmot.lang.ir_tree import describe_iteration, iteration_paths
from rmot.lang.diagnostics import Amount, Diagnostic, Severity
from rmot.lang.record import record
from rmot.sim import codes
from rmot.sim.collide import CONTACT_TOL, STATIC_TOL
from rmot.sim.exact import ExactPair
from rmot.sim.scene import Body, Scene, _local_box, _shape

__all__ = ["GRIP_TOL", "REST_TOL", "Phase", "PartEvent", "declared_part", "part_events", "part_shape", "phases"]

GRIP_TOL = 0.002  # m: a tool may touch the part it grips this deep, and must be this close to attach it
REST_TOL = STATIC_TOL  # m: a part may rest on a fixture or on another part this deep (two static bodies may touch)


def declared_part(name: str) -> str:
    """The declared part (or feeder) a part is: `infeed#7` -> `infeed` ('#' is never in a name)."""
    return name.partition("#")[0]


@record
class PartEvent:
    t: float
    robot: str
    instr: ir.Attach | ir.Detach
    variant: int = 0
    barriers: int = 0  # `sync`s its task passed before it: orders events of one instant

    @property
    def attach(self) -> bool:
        return isinstance(self.instr, ir.Attach)


@dataclass(frozen=True, eq=False)
class Phase:
    """[t0, t1]: every part there is placed (`placed`: name -> world pose (4, 4)) or held
    (`held`: name -> (robot, pose in the flange frame (4, 4))). `picked`: the parts attached at
    t0, `put`: those detached at t1, `presented`: feeder parts that appeared at t0 (their pick,
    their place and their arrival: the contacts those instants make are not collisions)."""

    t0: float
    t1: float
    placed: dict[str, np.ndarray]
    held: dict[str, tuple[str, np.ndarray]]
    picked: frozenset[str] = frozenset()
    put: frozenset[str] = frozenset()
    presented: frozenset[str] = frozenset()


# --------------------------------------------------------------------------- events


def part_events(plan: plan_types.Plan, variant: tuple[str, plan_types.Variant] | None = None) -> list[PartEvent]:
    """Attach/detach events in time order. At one instant (the simulation takes no time for
    `wait until`, `set` or a sync both tasks reach together) the `sync` barriers decide: an
    event after more barriers of its task comes later; then detach before attach.
    `variant` (robot, Variant): that robot's events follow the variant's path."""
    out: list[PartEvent] = []
    for tp in plan.tasks:
        instrs: dict[int, ir.Instr] = {}
        barriers: dict[int, int] = {}
        passed = 0
        for i in ir_tree.walk(tp.task.body):
            if isinstance(i, ir.Sync):
                passed += 1
            elif isinstance(i, (ir.Attach, ir.Detach)):
                instrs[i.uid], barriers[i.uid] = i, passed
        if not instrs:
            continue
        if variant is not None and variant[0] == tp.robot:
            v = variant[1]
            t_split = float(v.trajectory.t[0]) if v.trajectory.t.size else 0.0
            recs = [r for r in tp.records if r.variant == 0 and r.t_start < t_split - 1e-12]
            recs += [r for r in tp.records if r.variant == v.index]
        else:
            recs = [r for r in tp.records if r.variant == 0]
        for r in recs:
            if r.uid in instrs:
                out.append(PartEvent(float(r.t_start), tp.robot, instrs[r.uid], r.variant, barriers[r.uid]))  # type: ignore[arg-type]
    out.sort(key=lambda e: (round(e.t, 9), e.barriers, e.attach, e.instr.uid))
    return out


def _trajectories(plan: plan_types.Plan, variant: tuple[str, plan_types.Variant] | None) -> dict[str, plan_types.Trajectory]:
    trajs = {tp.robot: tp.trajectory for tp in plan.tasks}
    if variant is not None:
        trajs[variant[0]] = variant[1].trajectory
    return trajs


def _flange(scene: Scene, robot: str, traj: plan_types.Trajectory | None, t: float) -> np.ndarray:
    entry = scene.robots[robot]
    if traj is None or traj.t.size == 0:
        q = np.clip(np.zeros(entry.robot.dof), entry.robot.joint_limits[:, 0], entry.robot.joint_limits[:, 1])
    else:
        q = traj.at(t)
    flange: np.ndarray = entry.base @ np.asarray(entry.robot.fk(q))
    return flange


def phases(scene: Scene, plan: plan_types.Plan, variant: tuple[str, plan_types.Variant] | None = None,
           diagnostics: list[Diagnostic] | None = None) -> list[Phase]:
    """The phases of the program's time (or of one variant's path): the parts' states between
    events. Attach problems only the plan can show go to `diagnostics` (E330, E331, E333, E334)."""
    return _Phases(scene, plan, variant, diagnostics).run()


@dataclass
class _Phases:
    """Walks the part events in time order, feeders presenting their parts on the way."""

    scene: Scene
    plan: plan_types.Plan
    variant: tuple[str, plan_types.Variant] | None
    diagnostics: list[Diagnostic] | None
    placed: dict[str, np.ndarray] = field(default_factory=dict)
    held: dict[str, tuple[str, np.ndarray]] = field(default_factory=dict)
    waiting: dict[str, str | None] = field(default_factory=dict)  # feeder -> the part waiting at its pose
    taken: dict[str, int] = field(default_factory=dict)  # feeder -> parts taken so far
    pending: list[tuple[float, str]] = field(default_factory=list)  # heap of (time, feeder): next arrivals
    log: list[tuple[float, str, str]] = field(default_factory=list)  # (t, "attach"|"detach"|"present", part)
    cuts: list[tuple[float, float, dict[str, np.ndarray], dict[str, tuple[str, np.ndarray]]]] = field(default_factory=list)
    t_prev: float = 0.0

    def __post_init__(self) -> None:
        self.parts = {p.name: p for p in self.scene.cell.parts}
        self.trajs = _trajectories(self.plan, self.variant)
        self.main = _trajectories(self.plan, None)
        self.paths = {tp.robot: iteration_paths(tp.task.body) for tp in self.plan.tasks}
        for p in self.scene.cell.parts:
            if not p.feeder:
                self.placed[p.name] = p.pose.matrix()
            elif p.count is None or p.count > 0:
                self.taken[p.name] = 0
                self._present(p.name, 0.0)
            else:
                self.taken[p.name], self.waiting[p.name] = 0, None

    def run(self) -> list[Phase]:
        end = max([float(tr.t[-1]) for tr in self.trajs.values() if tr.t.size] or [0.0])
        start = float(self.variant[1].trajectory.t[0]) if self.variant is not None and self.variant[1].trajectory.t.size else 0.0
        for ev in part_events(self.plan, self.variant):
            if ev.instr.part not in self.parts or ev.robot not in self.scene.robots:
                continue
            self._arrivals(ev.t)
            self._cut(ev.t)
            # before a variant starts its robot follows the main timeline
            flange = _flange(self.scene, ev.robot, (self.main if ev.variant == 0 else self.trajs).get(ev.robot), ev.t)
            if ev.attach:
                self._attach(ev, flange)
            else:
                self._detach(ev, flange)
        self._arrivals(end)
        self.cuts.append((self.t_prev, max(end, self.t_prev), dict(self.placed), dict(self.held)))
        return [self._phase(*c) for c in self.cuts if c[1] >= start - 1e-12]

    def _phase(self, t0: float, t1: float, placed: dict[str, np.ndarray], held: dict[str, tuple[str, np.ndarray]]) -> Phase:
        def at(t: float, kind: str) -> frozenset[str]:
            return frozenset(n for when, k, n in self.log if k == kind and abs(when - t) <= 1e-9)

        return Phase(t0, t1, placed, held, at(t0, "attach"), at(t1, "detach"), at(t0, "present"))

    def _cut(self, t: float) -> None:
        if t > self.t_prev:
            self.cuts.append((self.t_prev, t, dict(self.placed), dict(self.held)))
            self.t_prev = t

    def _arrivals(self, t: float) -> None:
        """Every feeder part that arrives by time t, each starting a phase."""
        while self.pending and self.pending[0][0] <= t + 1e-12:
            when, feeder = heapq.heappop(self.pending)
            self._cut(when)
            self._present(feeder, when)

    def _present(self, feeder: str, t: float) -> None:
        name = f"{feeder}#{self.taken[feeder] + 1}"
        self.placed[name] = self.parts[feeder].pose.matrix()
        self.waiting[feeder] = name
        self.log.append((t, "present", name))

    def _attach(self, ev: PartEvent, flange: np.ndarray) -> None:
        declared = ev.instr.part
        part = self.parts[declared]
        name: str | None = declared
        if part.feeder:
            name = self._take(ev, part)
            if name is None:
                return
        assert name is not None
        if name in self.held:  # another robot holds it (the front end refuses a task's own, E141)
            self._report(codes.PART_HELD_ELSEWHERE, (
                f"part '{name}' must be released before robot '{ev.robot}' attaches it (robot "
                f"'{self.held[name][0]}' still holds it then; put a detach and a sync before this attach)"),
                ev, (name,), None)
            return
        world = self.placed.pop(name)
        local = np.linalg.inv(flange) @ world
        self.held[name] = (ev.robot, local)
        self.log.append((ev.t, "attach", name))
        if part.feeder and (part.count is None or self.taken[declared] < part.count):
            when = self._clear_time(ev, part, local)
            if when is not None:
                heapq.heappush(self.pending, (when, declared))
        if self.diagnostics is not None:
            self.diagnostics += [replace_message(d, self.where(ev)) for d in _grip_check(self.scene, ev, flange, world, part, name)]

    def _take(self, ev: PartEvent, feeder: ir.Part) -> str | None:
        """The part waiting at the feeder (one still on its way is pushed in now); None when the
        feeder has given its `count` parts (E334)."""
        if self.waiting.get(feeder.name) is None:
            coming = [p for p in self.pending if p[1] == feeder.name]
            if not coming:
                self._report(codes.FEEDER_EMPTY, (
                    f"feeder '{feeder.name}' must have a part left to attach (all {feeder.count} of its parts "
                    "have been taken before this attach)"), ev, (feeder.name,), None)
                return None
            self.pending.remove(coming[0])
            heapq.heapify(self.pending)
            self._cut(ev.t)
            self._present(feeder.name, ev.t)
        name = self.waiting[feeder.name]
        self.waiting[feeder.name] = None
        self.taken[feeder.name] += 1
        return name

    def _detach(self, ev: PartEvent, flange: np.ndarray) -> None:
        declared = ev.instr.part
        name = next((n for n, (r, _) in self.held.items() if r == ev.robot and declared_part(n) == declared), None)
        if name is None:
            return
        _, local = self.held.pop(name)
        self.placed[name] = flange @ local
        self.log.append((ev.t, "detach", name))

    def _clear_time(self, ev: PartEvent, part: ir.Part, local: np.ndarray) -> float | None:
        """The first sample after the attach at which the part taken is clear of the feeder's
        next part (their solids farther apart than CONTACT_TOL); None if it never is."""
        shape = part_shape(part)
        traj = (self.main if ev.variant == 0 else self.trajs).get(ev.robot)
        if shape is None or traj is None or traj.t.size == 0:
            return ev.t
        entry = self.scene.robots[ev.robot]
        spot = part.pose.matrix()
        centre, half = _local_box(shape)
        pair = ExactPair(Body("taken", "fixture", None, shape, spot), Body("next", "fixture", None, shape, spot))
        later = np.nonzero(traj.t > ev.t + 1e-12)[0]
        for chunk in np.array_split(later, max(1, later.size // 64)):
            if chunk.size == 0:
                continue
            poses = entry.base @ np.asarray(entry.robot.fk_batch(traj.q[chunk])) @ local
            gaps = np.linalg.norm((poses[:, :3, :3] @ centre + poses[:, :3, 3]) - (spot[:3, :3] @ centre + spot[:3, 3]), axis=1)
            for k, i in enumerate(chunk):
                if gaps[k] > 2 * float(np.linalg.norm(half)) + CONTACT_TOL or pair.distance(poses[k], spot, 0.0) > CONTACT_TOL:
                    return float(traj.t[i])
        return None

    def where(self, ev: PartEvent) -> str:
        """' (in iteration layer = 0, row = 1)' for an instruction inside a loop, else ''."""
        path = self.paths.get(ev.robot, {}).get(ev.instr.uid)
        return f" (in iteration {describe_iteration(path)})" if path else ""

    def _report(self, code: Any, message: str, ev: PartEvent, bodies: tuple[str, ...], amount: Amount | None) -> None:
        if self.diagnostics is not None:
            self.diagnostics.append(Diagnostic(code, Severity.ERROR, message + self.where(ev), ev.instr.span, (), ev.t,
                                               ev.t, bodies, amount, None))


def replace_message(d: Diagnostic, suffix: str) -> Diagnostic:
    """`d` with `suffix` appended to its message (the iteration of the instruction it is about)."""
    return replace(d, message=d.message + suffix) if suffix else d


def _grip_check(scene: Scene, ev: PartEvent, flange: np.ndarray, world: np.ndarray, part: ir.Part,
                name: str) -> list[Diagnostic]:
    """E330: at its attach the part (`name`: a feeder's is named by its ordinal) must be within
    GRIP_TOL of the tool's solid or its TCP; E333: the tool must not be inside it deeper than GRIP_TOL."""
    tool_ref = ev.instr.tool
    shape = part_shape(part)
    if shape is None:
        return []
    pbody = Body(name, "fixture", None, shape, world)
    tcp = flange @ tool_ref.tcp.matrix()
    point = Body("tcp", "fixture", None, ir.Sphere(1e-9), tcp)
    d_tcp = ExactPair(point, pbody).distance(tcp, world, 0.0)
    d_tool = np.inf
    tool_body = next((b for b in scene.bodies if b.kind == "tool" and b.name == tool_ref.name and b.robot == ev.robot), None)
    if tool_body is not None:
        d_tool = ExactPair(tool_body, pbody).distance(flange @ tool_body.local, world, 0.0)
    if tool_body is not None and d_tool < -GRIP_TOL:
        depth = -d_tool * 1000
        return [Diagnostic(codes.PART_GRIP_DEPTH, Severity.ERROR,
                           f"tool '{tool_body.name}' must touch part '{name}' without entering it deeper than "
                           f"{GRIP_TOL * 1000:g} mm to attach it (penetration {depth:.1f} mm)", ev.instr.span, (),
                           ev.t, ev.t, (tool_body.name, name), Amount(round(depth, 3), "mm"), None)]
    nearest = min(d_tcp, d_tool)
    if nearest <= GRIP_TOL:
        return []
    what = f"tool '{tool_ref.name}'" if tool_ref.name else "the flange"
    return [Diagnostic(codes.PART_NOT_TOUCHING, Severity.ERROR,
                       f"part '{name}' must be within {GRIP_TOL * 1000:g} mm of {what} or its TCP to be attached "
                       f"(nearest {nearest * 1000:.1f} mm away)", ev.instr.span, (), ev.t, ev.t,
                       (tool_ref.name or f"{ev.robot}/flange", name), Amount(round(nearest * 1000, 3), "mm"), None)]


_SHAPES: dict[int, Any] = {}


def part_shape(part: ir.Part, diags: list[Diagnostic] | None = None) -> Any:
    """The part's solid (a mesh is loaded once); problems loading it go to `diags`."""
    key = id(part)
    cached = _SHAPES.get(key)
    if cached is None or cached[0] is not part:
        found: list[Diagnostic] = []
        cached = (part, _shape(part.geometry, found), tuple(found))
        _SHAPES[key] = cached
    if diags is not None:
        diags += cached[2]
    return cached[1]
