"""Parts over time: what the parts' phases (sim/part_phases.py: where every part is and who
holds it between attach/detach events, feeders presenting theirs) mean for the collision
check, the payload and the pictures.

The collision check of a phase is the ordinary one (sim/collide.py, same no-miss guarantee)
on the phase's samples, over the pairs that involve a part; the pairs without a part are
checked once by sim/verification.py as before.

Contacts a part may make (the only departures from the ordinary check):
  * the tools of the robot that picks it up or puts it down may touch it up to GRIP_TOL
    (2 mm) penetration: a gripper closes on the part (checked at the attach instant too);
  * a part may rest on a fixture (penetration up to REST_TOL, 0.1 mm, as two static bodies
    may touch, collide.STATIC_TOL): a box stands on its infeed or pallet;
  * a part may rest on parts the same way, side by side or stacked: placed parts may touch up
    to REST_TOL, and a carried part may touch placed ones up to REST_TOL in the run of contact
    that ends where it is put down (or starts where it is picked up). Touching anywhere else
    on its way is a collision of depth 0; deeper than REST_TOL is a collision naming both
    parts and the depth.
A held part is a body of its robot: checked against fixtures, placed parts, the robot's
links except those of the last joint (the flange), and other robots; never against the
holding robot's tools (their contact is fixed while held and checked at the attach).

Runtime `if`: each variant (an `otherwise` path) replays the main timeline's events before
the `if` and the variant's own after it; it is checked for the pairs of its robot.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from rmot.lang import ir, ir_tree, plan_types
from rmot.lang.ir_tree import describe_iteration, iteration_paths
from rmot.lang.diagnostics import Amount, Diagnostic, Severity
from rmot.lang.record import record
from rmot.lang.source import Span
from rmot.sim import codes
from rmot.sim.collide import CONTACT_TOL, PairHit, Timeline, candidate_pairs, check_timeline
from rmot.sim.part_phases import (
    GRIP_TOL, REST_TOL, Phase, PartEvent, declared_part, part_events, part_shape, phases,
)
from rmot.sim.scene import Body, Scene, _local_box, _reach, _sphere_cover, flange_in_last_joint

__all__ = ["GRIP_TOL", "REST_TOL", "Phase", "PartEvent", "Placement", "absent_pose", "is_absent", "part_bodies",
           "part_events", "part_hits", "placements",
           "payload_findings", "phase_scene", "phases", "shape_diagnostics"]

# --------------------------------------------------------------------------- collision


def part_bodies(scene: Scene, phase: Phase) -> list[Body]:
    """The parts there are in one phase as bodies: placed ones as fixtures, held ones as
    tool-like solids (a feeder's parts once presented, each named by its ordinal)."""
    declared = {p.name: (k, p) for k, p in enumerate(scene.cell.parts)}
    out: list[Body] = []
    for name in sorted([*phase.placed, *phase.held], key=lambda n: _order(declared, n)):
        part = declared[declared_part(name)][1]
        shape = part_shape(part)
        if shape is None:
            continue
        if name in phase.held:
            robot, local = phase.held[name]
            entry = scene.robots[robot]
            spheres = _sphere_cover(shape)
            placement = flange_in_last_joint(entry.robot) @ local
            reach = _reach(entry.robot, entry.robot.dof, spheres, placement, entry.prismatic)
            out.append(Body(name, "tool", robot, shape, local, joint=int(entry.robot.dof),
                            spheres=spheres, reach=reach, span=part.span))
        else:
            centre, half = _local_box(shape)
            out.append(Body(name, "fixture", None, shape, phase.placed[name], obb_centre=centre,
                            obb_half=half, span=part.span, spheres=_sphere_cover(shape)))
    return out


def _order(declared: dict[str, tuple[int, ir.Part]], name: str) -> tuple[int, int]:
    """Cell order, then a feeder's parts by ordinal (`infeed#2` before `infeed#10`)."""
    ordinal = name.partition("#")[2]
    return declared[declared_part(name)][0], int(ordinal) if ordinal else 0


def shape_diagnostics(cell: ir.Cell) -> list[Diagnostic]:
    """Mesh problems of the cell's parts (E560-E563, W560), as for fixtures."""
    out: list[Diagnostic] = []
    for part in cell.parts:
        part_shape(part, out)
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
    out: list[tuple[Scene, PairHit]] = []
    for k, phase in enumerate(phase_list):
        sub = _slice(timeline, phase.t0, phase.t1)
        if sub is None:
            continue
        names = set(phase.placed) | set(phase.held)
        pscene = phase_scene(scene, phase)
        pairs = [(a, b) for a, b in candidate_pairs(pscene, only_robot=only_robot)
                 if (a.name in names or b.name in names) and (k == 0 or a.moves or b.moves)]
        if only_robot is None:  # where the parts start or arrive: overlaps with fixtures or each other (W300)
            new = names if k == 0 else phase.presented
            still = [b for b in pscene.bodies if b.kind == "fixture"]
            pairs += [(a, b) for i, a in enumerate(still) for b in still[i + 1:] if a.name in new or b.name in new]
        part_part = [(a, b) for a, b in pairs if a.name in names and b.name in names]
        others = [(a, b) for a, b in pairs if not (a.name in names and b.name in names)]
        hits = check_timeline(pscene, sub, others, clearance)
        ends = (float(sub.t[0]), float(sub.t[-1]))
        hits = [h for h in hits if _counts(pscene, h, names) and not _resting_approach(pscene, h, ends, names)]
        hits += _part_part_hits(pscene, sub, part_part, phase, clearance)
        out += [(pscene, h) for h in hits]
    return _merge(out)


def _part_part_hits(scene: Scene, sub: Timeline, pairs: list[tuple[Body, Body]], phase: Phase,
                    clearance: float) -> list[PairHit]:
    """Two parts may rest on each other, side by side or stacked: contact up to REST_TOL deep.
    A carried part touching a placed one is a collision (depth 0 when it only touches), except
    in the run of contact that is its own place or pick: the run that ends at the sample where
    it is put down (it slides down beside its neighbour, onto the layer below) or starts where
    it is picked up, and a feeder's part arriving beside one just taken. Deeper than REST_TOL
    is a collision everywhere."""
    ends = (float(sub.t[0]), float(sub.t[-1]))
    out: list[PairHit] = []
    resting: set[tuple[str, str]] = set()  # pairs that come to rest on each other at a place or pick
    # the threshold -REST_TOL: a part sliding down along its neighbour's face (distance 0) is
    # certified in steps of REST_TOL of motion, not bisected to CONTACT_TOL at every sample
    for h in check_timeline(scene, sub, pairs, -REST_TOL):
        if h.kind == "static" or h.distance < -REST_TOL:
            out.append(replace(h, kind="static" if h.kind == "static" else "collision"))
        elif not _at_own_event(h, phase, ends):
            out.append(replace(h, kind="collision", distance=min(h.distance, -0.0)))
        else:
            resting.add((h.a, h.b))
    if clearance > CONTACT_TOL:  # the approach of a part set down against another is the place itself
        moving = [(a, b) for a, b in pairs if a.moves or b.moves]
        out += [h for h in check_timeline(scene, sub, moving, clearance)
                if h.kind == "clearance" and h.distance >= CONTACT_TOL
                and not ((h.a, h.b) in resting and _at_own_event(h, phase, ends, loose=True))]
    return out


def _at_own_event(hit: PairHit, phase: Phase, ends: tuple[float, float], loose: bool = False) -> bool:
    """The run starts at the phase's first sample and one of the two parts was picked up or
    arrived then, or ends at its last sample and one of them is put down then (`loose`: an
    approach that leads into such a run may stop short of the sample, where the contact run
    takes over)."""
    pair = {hit.a, hit.b}
    if loose:
        return bool(pair & (phase.picked | phase.presented | phase.put))
    starts = hit.t0 <= ends[0] + 1e-9 and bool(pair & (phase.picked | phase.presented))
    return starts or (hit.t1 >= ends[1] - 1e-9 and bool(pair & phase.put))


def _counts(scene: Scene, hit: PairHit, names: set[str]) -> bool:
    """False for the contacts a part may make: a gripper on its part, a part resting on a fixture."""
    if hit.kind == "clearance":
        return True
    a, b = scene.body(hit.a), scene.body(hit.b)
    part, other = (a, b) if a.name in names else (b, a)
    if other.kind == "tool" and other.name not in names:
        return hit.distance < -GRIP_TOL
    if other.kind == "fixture" and other.name not in names:
        return hit.distance < -REST_TOL if hit.kind != "static" else True
    return True


def _resting_approach(scene: Scene, hit: PairHit, ends: tuple[float, float], names: set[str]) -> bool:
    """A clearance approach that is the pick or the place itself: a tool near a part (it grips
    it), or a part near a fixture in a run that starts or ends at the phase's first or last
    sample, its attach or detach (it is lifted off or set down on its support). Not reported
    under --clearance."""
    if hit.kind != "clearance":
        return False
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


def _by_ordinal(scene: Scene, plan: plan_types.Plan, robot: str, variant: plan_types.Variant | None, t: float,
                held: list[str]) -> list[str]:
    """The parts `held` (declared names) by `robot` at `t` as findings name them: a feeder's
    part by its ordinal (`carton#7`, the one the robot holds then, from the phases), others as
    declared."""
    feeders = {p.name for p in scene.cell.parts if p.feeder}
    if not feeders.intersection(held):
        return list(held)
    phase_list = phases(scene, plan, (robot, variant)) if variant is not None else _program_phases(scene, plan)
    now = [ph for ph in phase_list if ph.t0 <= t + 1e-12][-1:] or phase_list[:1]
    ordinals = sorted((n for ph in now for n, (r, _) in ph.held.items() if r == robot and "#" in n), key=lambda n: (len(n), n))
    out = []
    for n in held:
        mine = next((o for o in ordinals if declared_part(o) == n), None)
        if mine is not None:
            ordinals.remove(mine)
        out.append(mine or n)
    return out


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
        moves = {i.uid: i for i in ir_tree.walk(tp.task.body) if isinstance(i, ir.Move)}
        iterations = iteration_paths(tp.task.body)
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
                    named = _by_ordinal(scene, plan, tp.robot, variant, r.t_start, held)
                    what += [f"part '{name}' {parts[n].mass:g} kg" for n, name in zip(held, named)]
                    message = (f"payload {total:g} kg ({' + '.join(what)}) must not exceed robot '{tp.robot}''s "
                               f"rated payload {rated:g} kg")
                    path = iterations.get(r.uid)
                    if path:
                        message += f" (in iteration {describe_iteration(path)})"
                    if variant is not None:
                        message += f" (on the path through the '{variant.arm}' arm of an if)"
                    if (r.uid, message.split(" (on the path")[0]) not in seen:
                        seen.add((r.uid, message.split(" (on the path")[0]))
                        out.append(Diagnostic(codes.PAYLOAD_EXCEEDED, Severity.ERROR, message, move.span, (), r.t_start,
                                              r.t_end, (tp.robot,), Amount(round(total - rated, 6), "kg"), tp.task.name))
                over_before = over
    return out


# --------------------------------------------------------------------------- pictures


def with_part_bodies(scene: Scene, plan: plan_types.Plan | None = None) -> Scene:
    """`scene` plus every part as a body at its starting pose (what a picture draws; where it
    is at an instant comes from part_poses). With the `plan`, a feeder is drawn as the parts it
    gives (`carton#1`, `carton#2`, ...: every part any phase has), each only while it exists."""
    names = {p.name: p.pose.matrix() for p in scene.cell.parts if plan is None or not p.feeder}
    if plan is not None:
        spots = {p.name: p.pose.matrix() for p in scene.cell.parts}
        for phase in _program_phases(scene, plan):
            for name in [*phase.placed, *phase.held]:
                names.setdefault(name, spots[declared_part(name)])
    start = Phase(0.0, 0.0, names, {})
    return replace(scene, bodies=scene.bodies + tuple(part_bodies(scene, start)))


_PHASES: dict[tuple[int, int], tuple[Scene, plan_types.Plan, list[Phase]]] = {}


def _program_phases(scene: Scene, plan: plan_types.Plan) -> list[Phase]:
    """phases(scene, plan), computed once per (scene, plan) for the pictures. The phases do not
    depend on the scene's part bodies, so a scene and the same scene with its parts share them."""
    key = (id(scene.cell), id(plan))
    cached = _PHASES.get(key)
    if cached is None or cached[0].cell is not scene.cell or cached[1] is not plan:
        _PHASES.clear()  # one program at a time: keep the cache small
        cached = (scene, plan, phases(scene, plan))
        _PHASES[key] = cached
    return cached[2]


def absent_pose(spot: np.ndarray) -> np.ndarray:
    """The pose of a part that does not exist at an instant (a feeder's part not yet presented):
    the body shrunk to the point `spot` (4, 4) stands at, so it covers no pixel and no view."""
    pose = np.zeros((4, 4))
    pose[:, 3] = spot[:, 3]
    return pose


def is_absent(pose: np.ndarray) -> bool:
    """Whether a body pose (4, 4) is absent_pose's: a body shrunk to a point."""
    return not np.any(pose[:3, :3])


def part_poses(scene: Scene, plan: plan_types.Plan, times: np.ndarray,
               q: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """part name -> (N, 4, 4) world poses at `times` (N,): placed where they lie, held ones on
    their robot's flange (q: robot -> (N, dof) joint values at `times`); a feeder's part before
    it is presented has absent_pose. Declared parts and every feeder part by ordinal."""
    if not scene.cell.parts:
        return {}
    phase_list = _program_phases(scene, plan)
    n = len(times)
    starts = np.array([ph.t0 for ph in phase_list])
    which = np.clip(np.searchsorted(starts, times, side="right") - 1, 0, len(phase_list) - 1)
    flanges = {r: scene.robots[r].base @ np.asarray(scene.robots[r].robot.fk_batch(v)) for r, v in q.items()
               if r in scene.robots and any(r == h[0] for ph in phase_list for h in ph.held.values())}
    spots = {p.name: p.pose.matrix() for p in scene.cell.parts}
    out = {name: np.tile(spot, (n, 1, 1)) for name, spot in spots.items()}
    for ph in phase_list:
        for name in [*ph.placed, *ph.held]:
            if name not in out:
                out[name] = np.tile(absent_pose(spots[declared_part(name)]), (n, 1, 1))
    for k, ph in enumerate(phase_list):
        mask = which == k
        if not mask.any():
            continue
        for name, world in ph.placed.items():
            out[name][mask] = world
        for name, (robot, local) in ph.held.items():
            out[name][mask] = flanges[robot][mask] @ local
    return out


@record
class Placement:
    """A part put down: `name` (a feeder's by ordinal, `carton#7`), its world pose (4, 4) from
    then on, the instant `t` s of its detach, the detach's source `span` and the loop iteration
    it ran in (`layer = 1, row = 0`; '' outside loops)."""

    name: str
    pose: np.ndarray
    t: float
    span: Span | None
    iteration: str = ""


def placements(scene: Scene, plan: plan_types.Plan) -> list[Placement]:
    """Every part put down on the main timeline, in the order they were put down (what
    `rmot report` lists): where each stays, when and by which `detach`."""
    phase_list = _program_phases(scene, plan)
    events = [e for e in part_events(plan) if not e.attach]
    paths = {tp.robot: iteration_paths(tp.task.body) for tp in plan.tasks}
    out: list[Placement] = []
    for k, phase in enumerate(phase_list[:-1]):
        after = phase_list[k + 1]
        for name in sorted(phase.put, key=lambda n: (declared_part(n), len(n), n)):
            ev = next((e for e in events if e.instr.part == declared_part(name) and abs(e.t - phase.t1) <= 1e-9), None)
            path = paths[ev.robot].get(ev.instr.uid) if ev is not None else None
            out.append(Placement(name, after.placed[name], phase.t1, ev.instr.span if ev is not None else None,
                                 describe_iteration(path) if path else ""))
    return out
