"""Parts over time: where every part of the cell is, and who holds it, at any
instant of a Plan — and what that means for the collision check and the payload.

A part starts at its declared pose in the world. `attach p` (a record on the task's
timeline, at the instant the robot stops before it) fixes p to the robot's flange at the
relative pose it has then; `detach p` leaves it in the world where it is. Between two such
events anywhere in the program (a *phase*) every part is either *placed* (a fixture at a
world pose) or *held* (a body riding on a robot's flange, like a tool). The collision check
of a phase is the ordinary one (sim/collide.py, same no-miss guarantee) on the phase's
samples, over the pairs that involve a part; the pairs without a part are checked once by
sim/verification.py as before.

Contacts a part may make (the only departures from the ordinary check):
  * the tools of the robot that picks it up or puts it down may touch it up to GRIP_TOL
    (2 mm) penetration: a gripper closes on the part (checked at the attach instant too);
  * a part may rest on a fixture (penetration up to REST_TOL, 0.1 mm, as two static bodies
    may touch, collide.STATIC_TOL): a box stands on its infeed or pallet;
  * two parts must keep a gap: touching (distance below collide.CONTACT_TOL, 10 µm) is a
    collision, so a stack with zero gap is found, and one with a gap is clean.
A held part is a body of its robot: checked against fixtures, placed parts, the robot's
links except those of the last joint (the flange), and other robots; never against the
holding robot's tools (their contact is fixed while held and checked at the attach).

Runtime `if`: each variant (an `otherwise` path) replays the main timeline's events before
the `if` and the variant's own after it; it is checked for the pairs of its robot.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from rmot.compiler import ir, plan_types
from rmot.lang.diagnostics import Amount, Diagnostic, Severity
from rmot.lang.record import record
from rmot.sim import codes
from rmot.sim.collide import CONTACT_TOL, PairHit, Timeline, candidate_pairs, check_timeline
from rmot.sim.exact import ExactPair
from rmot.sim.scene import Body, Scene, _local_box, _reach, _shape, _sphere_cover, flange_in_last_joint

__all__ = ["GRIP_TOL", "REST_TOL", "Phase", "PartEvent", "heaviest_held", "part_bodies", "part_events", "part_hits",
           "payload_findings", "phase_scene", "phases", "shape_diagnostics"]

GRIP_TOL = 0.002  # m: a tool may touch the part it grips this deep, and must be this close to attach it
REST_TOL = 1e-4  # m: a part may rest on a fixture (collide.STATIC_TOL)


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
    """[t0, t1]: every part placed (`placed`: name -> world pose (4, 4)) or held (`held`:
    name -> (robot, pose in the flange frame (4, 4)))."""

    t0: float
    t1: float
    placed: dict[str, np.ndarray]
    held: dict[str, tuple[str, np.ndarray]]


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
        for i in ir.walk(tp.task.body):
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
    return entry.base @ np.asarray(entry.robot.fk(q))


def phases(scene: Scene, plan: plan_types.Plan, variant: tuple[str, plan_types.Variant] | None = None,
           diagnostics: list[Diagnostic] | None = None) -> list[Phase]:
    """The phases of the program's time (or of one variant's path): the parts' states between
    events. Attach/detach problems only the plan can show go to `diagnostics` (E330, E331)."""
    parts = {p.name: p for p in scene.cell.parts}
    trajs = _trajectories(plan, variant)
    main = _trajectories(plan, None)
    end = max([float(tr.t[-1]) for tr in trajs.values() if tr.t.size] or [0.0])
    start = float(variant[1].trajectory.t[0]) if variant is not None and variant[1].trajectory.t.size else 0.0
    placed = {name: p.pose.matrix() for name, p in parts.items()}
    held: dict[str, tuple[str, np.ndarray]] = {}
    out: list[Phase] = []
    t_prev = 0.0
    for ev in part_events(plan, variant):
        name = ev.instr.part
        if name not in parts or ev.robot not in scene.robots:
            continue
        if ev.t > t_prev:
            out.append(Phase(t_prev, ev.t, dict(placed), dict(held)))
            t_prev = ev.t
        # before a variant starts its robot follows the main timeline
        flange = _flange(scene, ev.robot, (main if ev.variant == 0 else trajs).get(ev.robot), ev.t)
        if ev.attach:
            if name in held:  # another robot holds it (the front end refuses a task's own, E141)
                if diagnostics is not None:
                    diagnostics.append(Diagnostic(
                        codes.PART_HELD_ELSEWHERE, Severity.ERROR,
                        f"part '{name}' must be released before robot '{ev.robot}' attaches it (robot "
                        f"'{held[name][0]}' still holds it then; put a detach and a sync before this attach)",
                        ev.instr.span, (), ev.t, ev.t, (name,), None, None))
                continue
            world = placed.pop(name)
            held[name] = (ev.robot, np.linalg.inv(flange) @ world)
            if diagnostics is not None:
                diagnostics += _grip_check(scene, ev, flange, world, parts[name])
        else:
            if name not in held or held[name][0] != ev.robot:
                continue
            robot, local = held.pop(name)
            placed[name] = flange @ local
    out.append(Phase(t_prev, max(end, t_prev), dict(placed), dict(held)))
    return [p for p in out if p.t1 >= start - 1e-12]


def _grip_check(scene: Scene, ev: PartEvent, flange: np.ndarray, world: np.ndarray, part: ir.Part) -> list[Diagnostic]:
    """E330: at its attach the part must be within GRIP_TOL of the tool's solid or its TCP;
    E300: the tool must not be inside it deeper than GRIP_TOL."""
    tool_ref = ev.instr.tool
    shape = _part_shape(part)
    if shape is None:
        return []
    pbody = Body(part.name, "fixture", None, shape, world)
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
                           f"tool '{tool_body.name}' must touch part '{part.name}' without entering it deeper than "
                           f"{GRIP_TOL * 1000:g} mm to attach it (penetration {depth:.1f} mm)", ev.instr.span, (),
                           ev.t, ev.t, (tool_body.name, part.name), Amount(round(depth, 3), "mm"), None)]
    nearest = min(d_tcp, d_tool)
    if nearest <= GRIP_TOL:
        return []
    what = f"tool '{tool_ref.name}'" if tool_ref.name else "the flange"
    return [Diagnostic(codes.PART_NOT_TOUCHING, Severity.ERROR,
                       f"part '{part.name}' must be within {GRIP_TOL * 1000:g} mm of {what} or its TCP to be attached "
                       f"(nearest {nearest * 1000:.1f} mm away)", ev.instr.span, (), ev.t, ev.t,
                       (tool_ref.name or f"{ev.robot}/flange", part.name), Amount(round(nearest * 1000, 3), "mm"), None)]


# --------------------------------------------------------------------------- collision


def part_bodies(scene: Scene, phase: Phase) -> list[Body]:
    """The parts as bodies in one phase: placed ones as fixtures, held ones as tool-like solids."""
    out: list[Body] = []
    for part in scene.cell.parts:
        shape = _part_shape(part)
        if shape is None:
            continue
        if part.name in phase.held:
            robot, local = phase.held[part.name]
            entry = scene.robots[robot]
            spheres = _sphere_cover(shape)
            placement = flange_in_last_joint(entry.robot) @ local
            reach = _reach(entry.robot, entry.robot.dof, spheres, placement, entry.prismatic)
            out.append(Body(part.name, "tool", robot, shape, local, joint=int(entry.robot.dof),
                            spheres=spheres, reach=reach, span=part.span))
        else:
            centre, half = _local_box(shape)
            out.append(Body(part.name, "fixture", None, shape, phase.placed[part.name], obb_centre=centre,
                            obb_half=half, span=part.span, spheres=_sphere_cover(shape)))
    return out


_SHAPES: dict[int, Any] = {}


def _part_shape(part: ir.Part, diags: list[Diagnostic] | None = None) -> Any:
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


def shape_diagnostics(cell: ir.Cell) -> list[Diagnostic]:
    """Mesh problems of the cell's parts (E560-E563, W560), as for fixtures."""
    out: list[Diagnostic] = []
    for part in cell.parts:
        _part_shape(part, out)
    return out


def phase_scene(scene: Scene, phase: Phase) -> Scene:
    """`scene` with the phase's part bodies (its always-touching pairs reused: parts add none)."""
    out = replace(scene, bodies=scene.bodies + tuple(part_bodies(scene, phase)))
    out.__dict__["always_touching"] = scene.always_touching
    return out


def part_hits(scene: Scene, timeline: Timeline, phase_list: list[Phase], clearance: float = 0.0,
              only_robot: str | None = None) -> list[tuple[Scene, PairHit]]:
    """Collisions (and clearance approaches) of every pair involving a part, phase by phase;
    a contact that continues across a phase boundary is one hit."""
    names = {p.name for p in scene.cell.parts}
    out: list[tuple[Scene, PairHit]] = []
    for k, phase in enumerate(phase_list):
        sub = _slice(timeline, phase.t0, phase.t1)
        if sub is None:
            continue
        pscene = phase_scene(scene, phase)
        pairs = [(a, b) for a, b in candidate_pairs(pscene, only_robot=only_robot)
                 if (a.name in names or b.name in names) and (k == 0 or a.moves or b.moves)]
        if k == 0 and only_robot is None:  # where the parts start: overlaps with fixtures or each other (W300)
            still = [b for b in pscene.bodies if b.kind == "fixture"]
            pairs += [(a, b) for i, a in enumerate(still) for b in still[i + 1:] if a.name in names or b.name in names]
        part_part = [(a, b) for a, b in pairs if a.name in names and b.name in names]
        others = [(a, b) for a, b in pairs if not (a.name in names and b.name in names)]
        hits = check_timeline(pscene, sub, others, clearance)
        ends = (float(sub.t[0]), float(sub.t[-1]))
        hits = [h for h in hits if _counts(pscene, h) and not _resting_approach(pscene, h, ends)]
        # two parts must not touch: closer than CONTACT_TOL is a collision
        for h in check_timeline(pscene, sub, part_part, max(clearance, CONTACT_TOL)):
            if h.kind == "static" or h.distance < CONTACT_TOL:
                kind = h.kind if h.kind == "static" else "collision"
                depth = h.distance if h.distance < 0.0 else -0.0  # touching: a collision of depth 0
                out.append((pscene, replace(h, kind=kind, distance=depth)))
            elif h.distance < clearance:
                out.append((pscene, h))
        out += [(pscene, h) for h in hits]
    return _merge(out)


def _counts(scene: Scene, hit: PairHit) -> bool:
    """False for the contacts a part may make: a gripper on its part, a part resting on a fixture."""
    if hit.kind == "clearance":
        return True
    a, b = scene.body(hit.a), scene.body(hit.b)
    names = {p.name for p in scene.cell.parts}
    part, other = (a, b) if a.name in names else (b, a)
    if other.kind == "tool" and other.name not in names:
        return hit.distance < -GRIP_TOL
    if other.kind == "fixture" and other.name not in names:
        return hit.distance < -REST_TOL if hit.kind != "static" else True
    return True


def _resting_approach(scene: Scene, hit: PairHit, ends: tuple[float, float]) -> bool:
    """A clearance approach that is the pick or the place itself: a tool near a part (it grips
    it), or a part near a fixture in a run that starts or ends at the phase's first or last
    sample, its attach or detach (it is lifted off or set down on its support). Not reported
    under --clearance."""
    if hit.kind != "clearance":
        return False
    names = {p.name for p in scene.cell.parts}
    a, b = scene.body(hit.a), scene.body(hit.b)
    part, other = (a, b) if a.name in names else (b, a)
    if other.name in names:
        return False
    if other.kind == "tool":
        return True
    at_event = hit.t0 <= ends[0] + 1e-9 or hit.t1 >= ends[1] - 1e-9  # the phase's first or last sample
    return other.kind == "fixture" and at_event


def _slice(timeline: Timeline, t0: float, t1: float) -> Timeline | None:
    t = timeline.t
    lo = int(np.searchsorted(t, t0 - 1e-9, side="left"))
    hi = int(np.searchsorted(t, t1 + 1e-9, side="right"))
    if hi - lo < 2:
        lo, hi = max(0, min(lo, t.size - 2)), min(t.size, max(hi, lo + 2))
    if hi - lo < 1:
        return None
    sl = slice(lo, hi)
    return Timeline(t[sl], {r: q[sl] for r, q in timeline.q.items()}, {r: a[sl] for r, a in timeline.accel.items()})


def _merge(hits: list[tuple[Scene, PairHit]]) -> list[tuple[Scene, PairHit]]:
    hits = sorted(hits, key=lambda x: (x[1].a, x[1].b, x[1].kind, x[1].t0))
    out: list[tuple[Scene, PairHit]] = []
    for s, h in hits:
        if out:
            ps, p = out[-1]
            if (p.a, p.b, p.kind) == (h.a, h.b, h.kind) and h.t0 <= p.t1 + 1e-9 and h.kind != "static":
                worst = p if p.distance <= h.distance else h
                out[-1] = (ps, replace(p, t1=max(p.t1, h.t1), distance=worst.distance, t_worst=worst.t_worst))
                continue
            if (p.a, p.b) == (h.a, h.b) and h.kind == "static" and p.kind == "static":
                continue
        out.append((s, h))
    return out


# --------------------------------------------------------------------------- payload


def load_at(plan: plan_types.Plan, tp: plan_types.TaskPlan, t: float, parts: dict[str, ir.Part],
            events: list[PartEvent]) -> tuple[float, list[str]]:
    """(mass of the parts robot tp.robot holds at time t, their names)."""
    held: list[str] = []
    for ev in events:
        if ev.t > t + 1e-12:
            break
        if ev.robot != tp.robot:
            continue
        if ev.attach:
            held.append(ev.instr.part)
        elif ev.instr.part in held:
            held.remove(ev.instr.part)
    return sum(parts[n].mass for n in held if n in parts), held


def payload_findings(scene: Scene, plan: plan_types.Plan) -> list[Diagnostic]:
    """E332: the tool's mass plus the held parts' beyond the robot's rated payload, at the
    first move of each run of moves that carry too much (`rated_payload_kg` on the robot;
    None = unknown, not checked), on the main timeline and on each `if` variant's path."""
    parts = {p.name: p for p in scene.cell.parts}
    main_events = part_events(plan)
    out: list[Diagnostic] = []
    seen: set[tuple[int, str]] = set()
    for tp in plan.tasks:
        entry = scene.robots.get(tp.robot)
        rated = getattr(entry.robot, "rated_payload_kg", None) if entry is not None else None
        if rated is None:
            continue
        moves = {i.uid: i for i in ir.walk(tp.task.body) if isinstance(i, ir.Move)}
        paths = [(0, main_events, None)] + [(v.index, part_events(plan, (tp.robot, v)), v) for v in tp.variants]
        for index, events, variant in paths:
            recs = [r for r in tp.records if r.uid in moves and r.variant == index]
            over_before = False
            for r in sorted(recs, key=lambda r: r.t_start):
                move = moves[r.uid]
                parts_mass, held = load_at(plan, tp, r.t_start, parts, events)
                total = move.tool.mass + parts_mass
                over = total > rated + 1e-9
                if over and not over_before:
                    what = [f"tool '{move.tool.name}' {move.tool.mass:g} kg"] if move.tool.name else []
                    what += [f"part '{n}' {parts[n].mass:g} kg" for n in held]
                    message = (f"payload {total:g} kg ({' + '.join(what)}) must not exceed robot '{tp.robot}''s "
                               f"rated payload {rated:g} kg")
                    if variant is not None:
                        message += f" (on the path through the '{variant.arm}' arm of an if)"
                    if (r.uid, message.split(" (on the path")[0]) not in seen:
                        seen.add((r.uid, message.split(" (on the path")[0]))
                        out.append(Diagnostic(codes.PAYLOAD_EXCEEDED, Severity.ERROR, message, move.span, (), r.t_start,
                                              r.t_end, (tp.robot,), Amount(round(total - rated, 6), "kg"), tp.task.name))
                over_before = over
    return out


def heaviest_held(scene: Scene, plan: plan_types.Plan, tp: plan_types.TaskPlan) -> tuple[float, np.ndarray | None]:
    """(mass, centre of gravity in the flange frame (3,)) of the heaviest set of parts the task's
    robot holds in any phase of the main timeline (each part at its own centroid)."""
    best: tuple[float, np.ndarray | None] = (0.0, None)
    parts = {p.name: p for p in scene.cell.parts}
    for phase in phases(scene, plan):
        mine = [(parts[n], local) for n, (robot, local) in phase.held.items() if robot == tp.robot and n in parts]
        mass = sum(p.mass for p, _ in mine)
        if mass > best[0]:
            cog = sum((p.mass * (local @ np.append(_centre(p), 1.0))[:3] for p, local in mine), np.zeros(3)) / mass
            best = (mass, cog)
    return best


def _centre(part: ir.Part) -> np.ndarray:
    shape = _part_shape(part)
    if shape is None:
        return np.zeros(3)
    return _local_box(shape)[0]


# --------------------------------------------------------------------------- pictures


def with_part_bodies(scene: Scene) -> Scene:
    """`scene` plus every part as a body at its starting pose (what a picture draws; where it
    is at an instant comes from part_poses)."""
    start = Phase(0.0, 0.0, {p.name: p.pose.matrix() for p in scene.cell.parts}, {})
    return replace(scene, bodies=scene.bodies + tuple(part_bodies(scene, start)))


_PHASES: dict[tuple[int, int], tuple[Scene, plan_types.Plan, list[Phase]]] = {}


def part_poses(scene: Scene, plan: plan_types.Plan, times: np.ndarray,
               q: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """part name -> (N, 4, 4) world poses at `times` (N,): placed where they lie, held ones on
    their robot's flange (q: robot -> (N, dof) joint values at `times`)."""
    if not scene.cell.parts:
        return {}
    key = (id(scene), id(plan))
    cached = _PHASES.get(key)
    if cached is None or cached[0] is not scene or cached[1] is not plan:
        _PHASES.clear()  # one program at a time: keep the cache small
        cached = (scene, plan, phases(scene, plan))
        _PHASES[key] = cached
    phase_list = cached[2]
    n = len(times)
    starts = np.array([ph.t0 for ph in phase_list])
    which = np.clip(np.searchsorted(starts, times, side="right") - 1, 0, len(phase_list) - 1)
    flanges = {r: scene.robots[r].base @ np.asarray(scene.robots[r].robot.fk_batch(v)) for r, v in q.items()
               if r in scene.robots and any(r == h[0] for ph in phase_list for h in ph.held.values())}
    out = {p.name: np.tile(p.pose.matrix(), (n, 1, 1)) for p in scene.cell.parts}
    for k, ph in enumerate(phase_list):
        mask = which == k
        if not mask.any():
            continue
        for name, world in ph.placed.items():
            out[name][mask] = world
        for name, (robot, local) in ph.held.items():
            out[name][mask] = flanges[robot][mask] @ local
    return out
