"""Reach of a robot on a track: the map of the joined chain track + arm over the track's travel.

The carriage slides along the track's one linear axis, so the arm's base at axis value v is
its base at the low end translated by (v - low) along the axis' direction in world
(`Mechanism.flange` composes `base * A(v)`; `Mount.local` then places the arm on the carriage).
Any orientation: forward sampling of (rail value, joint vector) together (`sampled_map` with a
sweep). A fixed orientation: the arm's IK from carriage stations at most one grid step apart,
the point reached when one station reaches it (a point between two stations that only the
exact carriage value reaches may be missed; the caption says the spacing).
The grid covers every point within the arm's reach bound of the segment the base travels.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from rmot.compiler.design.reach import ReachMap, reach_map, sampled_map
from rmot.compiler.design.reach import reach_bound

__all__ = ["TrackSweep", "swept_grid", "swept_map", "swept_slice", "track_sweep"]

MAX_STATIONS = 200  # carriage stations of a fixed-orientation map (a 4 m track at 20 mm)


@dataclass(frozen=True, eq=False)
class TrackSweep:
    """The track a study's robot rides on: its name, range (m), the arm's base at the low end
    (4, 4) world and the world vector the base travels from the low end to the high end."""

    track: str
    low: float
    high: float
    low_base: np.ndarray
    travel: np.ndarray

    def base_at(self, value: float) -> np.ndarray:
        out = self.low_base.copy()
        out[:3, 3] += self.travel * (value - self.low) / (self.high - self.low)
        return out

    def caption(self) -> str:
        return (f"robot on track '{self.track}': reach over its whole travel "
                f"{self.low * 1000:g} .. {self.high * 1000:g} mm (the carriage anywhere on it)")


def track_sweep(cell: Any, robot: str) -> TrackSweep | None:
    """The sweep of `robot` when it rides on a track of `cell`, else None."""
    external = getattr(cell, "external", None)
    if external is None:
        return None
    mount = external.mount(robot)
    mech = None if mount is None else external.mechanism(mount.mechanism)
    if mount is None or mech is None or mech.kind != "track":
        return None
    axis = mech.axes[0]
    low = (mech.flange((axis.low,)) * mount.local).matrix()
    high = (mech.flange((axis.high,)) * mount.local).matrix()
    return TrackSweep(mech.name, axis.low, axis.high, low, high[:3, 3] - low[:3, 3])


def _lattice(lo: float, hi: float, step: float) -> np.ndarray:
    return np.arange(math.floor(lo / step), math.ceil(hi / step) + 1) * step


def swept_slice(sweep: TrackSweep, bound: float, step: float, plane: str, level: float) -> np.ndarray:
    """(N,3) world points of one plane ('xy' at z=level, 'xz' at y=level) covering the reach
    discs of every carriage position, on a lattice of `step`."""
    ends = np.array([sweep.low_base[:3, 3], sweep.low_base[:3, 3] + sweep.travel])
    i, j = (0, 1) if plane == "xy" else (0, 2)
    u = _lattice(ends[:, i].min() - bound, ends[:, i].max() + bound, step)
    v = _lattice(ends[:, j].min() - bound, ends[:, j].max() + bound, step)
    uu, vv = np.meshgrid(u, v, indexing="xy")
    pts = np.zeros((uu.size, 3))
    pts[:, i], pts[:, j] = uu.ravel(), vv.ravel()
    pts[:, 2 if plane == "xy" else 1] = level
    return pts


def _distance_to_travel(points: np.ndarray, sweep: TrackSweep) -> np.ndarray:
    a = sweep.low_base[:3, 3]
    d = sweep.travel
    s = np.clip((points - a) @ d / float(d @ d), 0.0, 1.0)
    out: np.ndarray = np.linalg.norm(points - (a + s[:, None] * d), axis=1)
    return out


def swept_grid(sweep: TrackSweep, bound: float, step: float) -> np.ndarray:
    """(N,3) world points of a cubic lattice within `bound` of the segment the base travels."""
    ends = np.array([sweep.low_base[:3, 3], sweep.low_base[:3, 3] + sweep.travel])
    axes = [_lattice(ends[:, k].min() - bound, ends[:, k].max() + bound, step) for k in range(3)]
    z, y, x = np.meshgrid(axes[2], axes[1], axes[0], indexing="ij")
    pts = np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1)
    return pts[_distance_to_travel(pts, sweep) <= bound + 1e-12]


def stations(sweep: TrackSweep, step: float) -> np.ndarray:
    """Carriage values (m) at most `step` apart from end to end (at most MAX_STATIONS)."""
    n = min(max(2, math.ceil((sweep.high - sweep.low) / step) + 1), MAX_STATIONS)
    return np.linspace(sweep.low, sweep.high, n)


def swept_map(study: Any, sweep: TrackSweep, points: np.ndarray, step: float, rot: np.ndarray | None,
              label: str, samples: int) -> ReachMap:
    """The map of track + arm at `points` (module docstring). Its `base` is the arm's base with the
    carriage in the middle of the travel and its `bound` the arm's bound plus half the travel:
    a circle that holds every point the joined chain reaches (what the drawings centre on)."""
    length = float(np.linalg.norm(sweep.travel))
    middle = sweep.base_at(0.5 * (sweep.low + sweep.high))
    if rot is None:
        scaled = int(samples * min(1.0 + length / max(study_bound(study), 1e-3), 8.0))  # the swept area is larger
        m = sampled_map(study.robot, points, step, base=sweep.low_base, tcp=study.tcp, name=label,
                        samples=scaled, sweep=sweep.travel)
        return replace(m, base=middle, bound=m.bound + 0.5 * length)
    best: ReachMap | None = None
    raw = np.full(len(points), -1.0)
    q = np.full((len(points), study.robot.dof), np.nan)
    for value in stations(sweep, step):
        m = reach_map(study.robot, points, base=sweep.base_at(float(value)), tcp=study.tcp, orientation=rot, name=label)
        score = np.where(m.reached, np.nan_to_num(m.quality) * m.manipulability_max, -1.0)
        better = score > raw
        raw[better], q[better] = score[better], m.q[better]
        best = m
    assert best is not None
    reached = raw >= 0
    top = float(raw[reached].max()) if reached.any() else 0.0
    quality = np.where(reached, raw / top if top > 0 else 0.0, np.nan)
    return replace(best, reached=reached, quality=quality, q=q, base=middle, bound=best.bound + 0.5 * length,
                   manipulability_max=top)


def study_bound(study: Any) -> float:

    return reach_bound(study.robot, study.tcp)

