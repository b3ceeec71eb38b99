"""The external axes of a planned task as series a person reads: named by axis, in the units a
program writes them (mm, mm/s, mm/s^2 for a linear axis; deg, deg/s, deg/s^2 for a revolute one).

Positions are `axis_motion.axis_samples` (the one place that decides where an axis is at a
time); speeds and accelerations are their derivatives along the samples (numpy.gradient,
second order inside and at the ends, so a trapezoid's cruise speed is exact and a ramp's acceleration is
reached). The plots, the CSV and JSON files and the report read these series and never
number an axis as an arm joint.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rmot.lang import ir
from rmot.lang.axis_motion import axis_samples, task_axes
from rmot.lang.ir_axes import ExtAxis, ExternalAxes
from rmot.lang.plan_types import TaskPlan

__all__ = ["AxisSeries", "axis_series", "display_factor", "mechanism_of", "move_values", "robot_bases"]


def display_factor(axis: ExtAxis) -> float:
    """SI -> the program's unit: m -> mm, rad -> deg."""
    return 1000.0 if axis.linear else 180.0 / np.pi


def mechanism_of(axis: ExtAxis, external: ExternalAxes) -> str:
    """The name of the mechanism an axis belongs to."""
    return next(m.name for m in external.mechanisms if axis in m.axes)


@dataclass(frozen=True, eq=False)
class AxisSeries:
    """One axis over a task's samples, in display units; `limits` = (low, high), `speed_limit`,
    `accel_limit` as declared in the cell, in the same units."""

    axis: ExtAxis
    t: np.ndarray
    position: np.ndarray
    speed: np.ndarray
    accel: np.ndarray

    @property
    def name(self) -> str:
        return self.axis.name

    @property
    def unit(self) -> str:
        return self.axis.unit()

    @property
    def limits(self) -> tuple[float, float]:
        f = display_factor(self.axis)
        return self.axis.low * f, self.axis.high * f

    @property
    def speed_limit(self) -> float:
        return self.axis.speed * display_factor(self.axis)

    @property
    def accel_limit(self) -> float:
        return self.axis.accel * display_factor(self.axis)


def _series(axis: ExtAxis, t: np.ndarray, values: np.ndarray) -> AxisSeries:
    position = values * display_factor(axis)
    speed, accel = np.zeros(t.shape), np.zeros(t.shape)
    if t.size > 2:  # second order at the ends too: a ramp from rest starts at speed 0
        speed = np.asarray(np.gradient(position, t, edge_order=2), dtype=float)
        accel = np.asarray(np.gradient(speed, t, edge_order=2), dtype=float)
    elif t.size == 2:
        speed = np.asarray(np.gradient(position, t), dtype=float)
    for a in (position, speed, accel):
        a.setflags(write=False)
    return AxisSeries(axis, t, position, speed, accel)


def axis_series(tp: TaskPlan, external: ExternalAxes | None, t: np.ndarray | None = None) -> tuple[AxisSeries, ...]:
    """Every axis `tp`'s task drives, over `t` (default: its trajectory's samples); () without axes."""
    axes = task_axes(tp.task, external)
    if not axes:
        return ()
    times = tp.trajectory.t if t is None else np.asarray(t, dtype=float)
    values = axis_samples(tp, axes, times)
    return tuple(_series(a, times, values[:, k]) for k, a in enumerate(axes))


def move_values(node: ir.Instr | None, axes: tuple[ExtAxis, ...]) -> dict[str, float] | None:
    """A move's axis values at its target in display units, by axis name (None for no move)."""
    if not isinstance(node, ir.Move) or not node.ext:
        return None
    values = dict(node.ext)
    return {a.name: values[a.name] * display_factor(a) for a in axes if a.name in values}


def robot_bases(tp: TaskPlan, external: ExternalAxes | None, t: np.ndarray | None = None) -> np.ndarray | None:
    """(N, 4, 4) world poses of the task's robot base at `t` (default: its samples) when it rides
    on a track the task drives; None when its base stands still."""
    return riding_poses(tp, external, tp.robot, t)


def riding_poses(tp: TaskPlan, external: ExternalAxes | None, body: str, t: np.ndarray | None = None) -> np.ndarray | None:
    """(N, 4, 4) world poses at `t` (default: the task's samples) of `body` (a robot, fixture or
    frame) riding on a mechanism the task drives; None when it stands still."""
    axes = task_axes(tp.task, external)
    if external is None or external.mount(body) is None or not axes:
        return None
    times = tp.trajectory.t if t is None else np.asarray(t, dtype=float)
    values = axis_samples(tp, axes, times)
    out = np.empty((times.shape[0], 4, 4))
    for i, row in enumerate(values):
        pose = external.world(body, {a.name: float(v) for a, v in zip(axes, row)})
        assert pose is not None
        out[i] = pose.matrix()
    return out
