"""Collisions of what external axes move: a robot on a track, fixtures on a positioner.

A body rides on a mechanism when its robot rides on a track or the fixture is mounted `on` a
mechanism (lang/ir_axes.py). Its world pose at time t is its pose with the axes at home
(what the scene holds) moved by the mechanism's motion since home:
    pose(t) = flange(axes(t)) * flange(home)^-1 * pose_home(t).
Two bodies on the same mechanism keep their relative pose, so their pair stays with the
general check (sim/collide.py); every pair of bodies on different mechanisms (or one on a
mechanism and one not) is checked here instead, at every sample of the shared timeline.

The check is sampled: the exact signed distance (coal) at each sample where a sphere bound
does not already clear the pair. Between two samples a body moves by at most its speed times
the step (4 ms): a track at 1.5 m/s moves 6 mm, so a contact shallower than that between two
samples can be missed (the general check's swept bound is not applied here).
"""

from __future__ import annotations

import numpy as np

from rmot.lang.axis_motion import axis_samples, task_axes
from rmot.lang.ir_axes import ExternalAxes
from rmot.lang.plan_types import TaskPlan
from rmot.sim.collide import PairHit, Timeline, _runs
from rmot.sim.exact import ExactPair
from rmot.sim.scene import Body, Scene

__all__ = ["axis_collisions", "axis_pairs", "body_groups", "driving_task", "mechanism_motion", "with_axes"]


def body_groups(scene: Scene, external: ExternalAxes | None) -> dict[str, str]:
    """Body name -> the mechanism that carries it (bodies no mechanism carries are absent)."""
    if external is None:
        return {}
    groups: dict[str, str] = {}
    for body in scene.bodies:
        mount = external.mount(body.robot if body.robot is not None else body.name)
        if mount is not None and mount.kind in ("robot", "fixture"):
            groups[body.name] = mount.group()
    return groups


def axis_pairs(pairs: list[tuple[Body, Body]], groups: dict[str, str]) -> tuple[list[tuple[Body, Body]], list[tuple[Body, Body]]]:
    """(pairs the general check keeps, pairs whose relative pose the axes change)."""
    keep: list[tuple[Body, Body]] = []
    moved: list[tuple[Body, Body]] = []
    for a, b in pairs:
        (moved if groups.get(a.name) != groups.get(b.name) else keep).append((a, b))
    return keep, moved


def axis_collisions(scene: Scene, timeline: Timeline, pairs: list[tuple[Body, Body]], tp: TaskPlan,
                    external: ExternalAxes, clearance: float) -> list[PairHit]:
    """Every collision (and approach closer than `clearance`) of the pairs the axes move."""
    if not pairs:
        return []
    poses: dict[str, np.ndarray] = {}
    for robot, q in timeline.q.items():
        poses.update(scene.poses(robot, q))
    poses = with_axes(scene, tp, external, timeline.t, poses)
    hits: list[PairHit] = []
    m = timeline.t.shape[0]
    for a, b in pairs:
        pa, pb = np.broadcast_to(poses[a.name], (m, 4, 4)), np.broadcast_to(poses[b.name], (m, 4, 4))
        gap = np.linalg.norm(pa[:, :3, 3] - pb[:, :3, 3], axis=1) - _radius(a) - _radius(b)
        near = np.flatnonzero(gap <= clearance)
        exact = ExactPair(a, b)
        dists = np.array([exact.distance(np.ascontiguousarray(pa[i]), np.ascontiguousarray(pb[i]), clearance) for i in near])
        free = np.ones(m, dtype=bool)
        free[near] = False
        hits += _runs(a, b, timeline.t[near], dists.reshape(-1), timeline.t[free], clearance)
    return hits


def with_axes(scene: Scene, tp: TaskPlan, external: ExternalAxes, times: np.ndarray,
              poses: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """`poses` (body -> (M, 4, 4) at `times`, robot bodies with their base at home; fixtures may
    be absent) with every body a mechanism carries moved by its mechanism's motion since home."""
    groups = body_groups(scene, external)
    motion = mechanism_motion(times, tp, external)
    out = dict(poses)
    for body in scene.bodies:
        if body.kind == "fixture" and body.name not in out:
            out[body.name] = body.local[None]
        if body.name in groups:
            out[body.name] = motion[groups[body.name]] @ out[body.name]
    return out


def mechanism_motion(times: np.ndarray, tp: TaskPlan, external: ExternalAxes) -> dict[str, np.ndarray]:
    """Mechanism -> (M, 4, 4): flange(axes(t)) * flange(home)^-1 at each of `times`; and
    `name#k` -> the same for the frame axis k carries (the solids on an inner axis)."""
    axes = task_axes(tp.task, external)
    values = axis_samples(tp, axes, times)
    column = {a.name: k for k, a in enumerate(axes)}
    out: dict[str, np.ndarray] = {}
    for mech in external.mechanisms:
        rows = [tuple(values[i, column[a.name]] if a.name in column else a.home for a in mech.axes)
                for i in range(times.shape[0])]
        carrier = out.get(mech.on) if mech.on is not None else None  # declared before: already here
        for through in (None, *range(1, len(mech.axes))):
            home_inv = mech.flange(mech.home(), through).inverse()
            key = mech.name if through is None else f"{mech.name}#{through}"
            own = np.array([(mech.flange(r, through) * home_inv).matrix() for r in rows]) if rows else np.zeros((0, 4, 4))
            out[key] = own if carrier is None else carrier @ own
    return out


def _radius(body: Body) -> float:
    """A sphere about the body's geometry origin that holds the body."""
    if body.spheres is not None and len(body.spheres):
        s = np.asarray(body.spheres)
        return float(np.max(np.linalg.norm(s[:, :3], axis=1) + s[:, 3]))
    if body.obb_half is not None and body.obb_centre is not None:
        return float(np.linalg.norm(body.obb_centre) + np.linalg.norm(body.obb_half))
    return float("inf")


def driving_task(tasks: list[TaskPlan], external: ExternalAxes | None) -> TaskPlan | None:
    """The task that drives the cell's external axes (a program with `with` has one task)."""
    return next((tp for tp in tasks if task_axes(tp.task, external)), None)

