"""The free space one robot moves in at one instant of a Plan, for the `move free` search.

No second collision model: the bodies are the verifier's (sim/scene.py, with the parts as
sim/parts.py places them in the phase of that instant), the pairs are the verifier's
(collide.candidate_pairs for the robot), and a straight joint segment is certified by the
verifier's own no-miss check (collide.check_timeline on the segment's two ends: conservative
advancement and bisection, so no contact deeper than collide.CONTACT_TOL is missed between
them). The contacts a part may make (a gripper on its part, a part resting on a fixture) are
forgiven as the verifier forgives them (parts._counts).

Other robots stand where they are at that instant (their joints from the Plan); the path is
verified again after it is timed, with the other robots moving (lower.py).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rmot.lang import plan_types
from rmot.lang.record import record
from rmot.sim import parts
from rmot.sim.collide import PairHit, Timeline, candidate_pairs, check_timeline
from rmot.sim.exact import ExactPair
from rmot.sim.scene import Body, Scene

__all__ = ["RESOLUTION", "Contact", "FreeSpace", "free_space", "robot_timeline"]

RESOLUTION = 0.005  # rad (m): the sum of joint steps between the samples of a checked segment


@record
class Contact:
    """The nearest approach of two bodies at a configuration (m; negative = penetration)."""

    a: str
    b: str
    distance: float


@dataclass(eq=False)
class FreeSpace:
    scene: Scene  # the cell's bodies in the phase of the instant (parts placed or held)
    robot: str
    others: dict[str, np.ndarray]  # every other robot's joints at the instant (dof,)
    pairs: list[tuple[Body, Body]]
    edges: int = 0  # segments checked (a measure of the search's work)
    last_blocker: tuple[Body, Body] | None = None

    def contacts(self, q: np.ndarray) -> list[Contact]:
        """Every pair's distance at q, nearest first (what blocks a start or a goal)."""
        poses = self._poses(np.asarray(q, dtype=float)[None])
        out = []
        for a, b in self.pairs:
            d = ExactPair(a, b).distance(poses[a.name][0], poses[b.name][0], np.inf)
            out.append(Contact(a.name, b.name, float(d)))
        out.sort(key=lambda c: (c.distance, c.a, c.b))
        return out

    def blocked(self, q: np.ndarray, clearance: float) -> list[PairHit]:
        """The contacts (and approaches closer than `clearance`) at q that the verifier reports."""
        return self.hits(np.asarray(q, dtype=float), np.asarray(q, dtype=float), clearance)

    def segment_free(self, qa: np.ndarray, qb: np.ndarray, clearance: float) -> bool:
        """The straight joint segment qa -> qb keeps `clearance` (self pairs: no contact).
        The pair that blocked the last segment is tried alone first: most blocked segments of
        a search are blocked by the same obstacle, and that check is a fraction of all pairs'."""
        self.edges += 1
        if self.last_blocker is not None and self.hits(qa, qb, clearance, [self.last_blocker]):
            return False
        found = self.hits(qa, qb, clearance)
        if found:
            names = (found[0].a, found[0].b)
            self.last_blocker = next((p for p in self.pairs if (p[0].name, p[1].name) == names), None)
        return not found

    def hits(self, qa: np.ndarray, qb: np.ndarray, clearance: float,
             pairs: list[tuple[Body, Body]] | None = None) -> list[PairHit]:
        """What the verifier reports on the straight segment qa -> qb: it is sampled so that no
        the joints together move at most RESOLUTION between samples (the numpy broad phase then discards
        most of it at once), and collide.check_timeline proves the rest between the samples."""
        n = 2 + int(np.sum(np.abs(qb - qa)) / RESOLUTION) if qa is not qb else 2
        q = qa + (qb - qa) * np.linspace(0.0, 1.0, n)[:, None]
        found = check_timeline(self.scene, self._timeline(q), self.pairs if pairs is None else pairs, clearance)
        return [h for h in found if h.kind != "static" and self._counts(h)]

    def _counts(self, hit: PairHit) -> bool:
        if not self.scene.cell.parts:
            return True
        names = {p.name for p in self.scene.cell.parts}
        return parts._counts(self.scene, hit, names) if names & {hit.a, hit.b} else True

    def _timeline(self, q: np.ndarray) -> Timeline:
        n = q.shape[0]
        qs = {self.robot: q, **{r: np.tile(v, (n, 1)) for r, v in self.others.items()}}
        return Timeline(np.arange(n, dtype=float), qs, {r: np.zeros_like(v) for r, v in qs.items()})

    def _poses(self, q: np.ndarray) -> dict[str, np.ndarray]:
        poses: dict[str, np.ndarray] = {}
        for r, v in self.others.items():
            poses.update(self.scene.poses(r, v[None]))
        poses.update(self.scene.poses(self.robot, q))
        for body in self.scene.bodies:
            if body.kind == "fixture":
                poses[body.name] = body.local[None]
        return poses


def free_space(scene: Scene, plan: plan_types.Plan, robot: str, t: float) -> FreeSpace:
    """The free space of `robot` at time t of the plan's main timeline."""
    pscene = scene
    if scene.cell.parts:
        phase = next((p for p in parts.phases(scene, plan) if p.t0 <= t <= p.t1), None)
        if phase is not None:
            pscene = parts.phase_scene(scene, phase)
    others = {}
    trajs = {tp.robot: tp.trajectory for tp in plan.tasks}
    for name, entry in scene.robots.items():
        if name == robot:
            continue
        traj = trajs.get(name)
        if traj is None or traj.t.size == 0:
            lo, hi = entry.robot.joint_limits[:, 0], entry.robot.joint_limits[:, 1]
            others[name] = np.clip(np.zeros(entry.robot.dof), lo, hi)
        else:
            others[name] = traj.at(t)
    return FreeSpace(pscene, robot, others, candidate_pairs(pscene, only_robot=robot))


def robot_timeline(plan: plan_types.Plan, scene: Scene, t0: float, t1: float) -> Timeline:
    """Every robot on the main timeline between t0 and t1 (the verifier's resampling on the
    union of their sample times), for verifying a timed path with the other robots moving."""
    from rmot.sim.verification import _timeline  # late: loads pinocchio only when this runs

    trajs = {tp.robot: tp.trajectory for tp in plan.tasks}
    times = np.concatenate([tr.t[(tr.t >= t0 - 1e-9) & (tr.t <= t1 + 1e-9)] for tr in trajs.values()]
                           + [np.array([t0, t1])])
    return _timeline(scene, trajs, np.unique(np.round(times, 9)))
