"""Plots of a planned program: joints against their limits, TCP speed, and the timeline.

    joints    joint positions against the position limits (one panel per joint and task), then
              the external axes the task drives, each named by axis and unit (`rail [mm]`,
              `pos.1 [deg]`) against its range (speeds, accels: against its speed / accel)
    speeds    joint speeds against their limits;  accels  joint accelerations against theirs
    torque    joint torques by inverse dynamics (sim.limits.joint_torques) against the
              model's effort limits, where the robot model has inertias
    tcp       TCP speed in world (a robot on a track: with its carriage) against the programmed
              speed of each linear/circular move, with the planner's W221 slowdowns shaded; on a
              coordinated move (its frame on a turning positioner) the speed relative to that
              frame, which is what its programmed speed means
    timeline  each task's instructions side by side on one time axis: moves, waits, syncs, I/O

matplotlib is imported inside the functions (Agg backend, no display), so importing this
module costs nothing; only `rmot plot` and `rmot report` load it. The limits drawn are the
ones verification checks (the robot library's data, whose sources are cited there), so a
curve crossing a dashed line is a finding of `rmot check`.

Output is deterministic: fixed figure sizes, SVG with a fixed hash salt and no dates, PNG
without a timestamp.
"""

from __future__ import annotations

import io
from dataclasses import dataclass
from typing import Any

import numpy as np

from rmot.lang import ir, ir_tree
from rmot.lang.axis_series import AxisSeries, axis_series, riding_poses, robot_bases
from rmot.lang.plan_types import Plan, TaskPlan

__all__ = ["KINDS", "PlotData", "figure_bytes", "plot_data"]

KINDS = ("joints", "speeds", "accels", "torque", "tcp", "timeline")
LIMIT_STYLE = {"color": "#c62828", "linestyle": "--", "linewidth": 0.9}
MOVE, WAIT, SYNC, IO = "#1565c0", "#ef6c00", "#c62828", "#757575"


@dataclass(frozen=True, eq=False)
class TaskData:
    """What the plots of one task need, in display units (deg, mm) and SI time."""

    name: str
    robot: str
    t: np.ndarray
    q: np.ndarray  # (N, dof) deg (mm for prismatic joints)
    qd: np.ndarray
    qdd: np.ndarray
    q_limits: np.ndarray  # (dof, 2)
    qd_limits: np.ndarray  # (dof,)
    qdd_limits: np.ndarray  # (dof,)
    tau: np.ndarray | None  # (N, dof) N·m, None without an inertia model
    tau_limits: np.ndarray | None
    tcp_speed: np.ndarray  # (N,) mm/s
    programmed: list[tuple[float, float, float]]  # (t0, t1, mm/s) of linear/circular moves
    slowdowns: list[tuple[float, float]]  # W221 intervals
    bars: list[tuple[float, float, str, str]]  # (t0, t1, kind, label)
    prismatic: tuple[bool, ...] = ()  # per joint: a prismatic joint is shown in mm (N), not deg (N·m)
    axes: tuple[AxisSeries, ...] = ()  # the external axes the task drives, by name (lang/axis_series.py)


@dataclass(frozen=True, eq=False)
class PlotData:
    program: str
    tasks: tuple[TaskData, ...]


def _display(robot: Any) -> np.ndarray:
    """Per-joint factor SI -> display: rad -> deg, m -> mm."""
    return np.array([1000.0 if t == "P" else 180.0 / np.pi for t in robot.joint_types])


def _instructions(tp: TaskPlan) -> dict[int, Any]:
    return {i.uid: i for i in ir_tree.walk(tp.task.body)}


def _bar(instr: Any) -> tuple[str, str] | None:
    if isinstance(instr, ir.Move):
        name = getattr(instr.target, "name", None)
        return "move", f"{instr.kind.name.lower()} {name}" if name else instr.kind.name.lower()
    if isinstance(instr, ir.Sync):
        return "sync", f"sync {instr.name}"
    if isinstance(instr, (ir.WaitTime, ir.WaitInput)):
        return "wait", "wait"
    if isinstance(instr, (ir.SetDigital, ir.SetAnalog, ir.Pulse)):
        return "io", "io"
    return None


def _task_data(plan: Plan, tp: TaskPlan, robot: Any, base: np.ndarray, payload: tuple[float, Any]) -> TaskData:
    from rmot.sim.limits import joint_torques  # late: loads subprocess only when this runs

    traj = tp.trajectory
    f = _display(robot)
    instrs = _instructions(tp)
    tau = tau_lim = None
    if getattr(robot, "has_inertia", False) and traj.t.size:
        effort = np.asarray(robot.model.effortLimit, dtype=float)[: robot.dof]
        if np.all(np.isfinite(effort)) and np.all(effort > 0):
            tau, tau_lim = joint_torques(robot, traj, payload[0], payload[1]), effort
    # TCP speed: the active tool's TCP along the samples, differentiated in time
    spans = sorted((r.t_start, r.t_end, r.uid) for r in tp.records if r.variant == 0)
    tcp = np.tile(np.eye(4), (traj.t.size, 1, 1))
    moves = [(t0, t1, instrs[u]) for t0, t1, u in spans if isinstance(instrs.get(u), ir.Move)]
    if moves:
        starts = np.array([m[0] for m in moves])
        which = np.clip(np.searchsorted(starts, traj.t, side="right") - 1, 0, len(moves) - 1)
        for k, (_, _, move) in enumerate(moves):
            tcp[which == k] = move.tool.tcp.matrix()
    tcp_speed = _tcp_speed(plan, tp, robot, base, tcp, moves)
    programmed = [(t0, t1, m.motion.tcp_speed * 1000.0) for t0, t1, m in moves
                  if m.kind in (ir.MotionKind.LINEAR, ir.MotionKind.CIRCULAR) and t1 > t0]
    slowdowns = []
    for d in plan.diagnostics:
        if d.code.id != "W221":
            continue
        if d.time_s is not None:
            slowdowns.append((d.time_s, d.end_time_s if d.end_time_s is not None else d.time_s))
            continue
        for t0, t1, m in moves:  # the move the warning points at
            if d.span is not None and m.span is not None and d.span.start == m.span.start:
                slowdowns.append((t0, t1))
    bars = []
    for t0, t1, uid in spans:
        kind = _bar(instrs.get(uid))
        if kind is not None and (t1 > t0 or kind[0] in ("sync", "io")):
            bars.append((t0, t1, kind[0], kind[1]))
    return TaskData(tp.task.name, tp.robot, traj.t, traj.q * f, traj.qd * f, traj.qdd * f,
                    np.asarray(robot.joint_limits) * f[:, None], np.asarray(robot.velocity_limits) * f,
                    np.asarray(robot.accel_limits) * f, tau, tau_lim, tcp_speed, programmed, slowdowns, bars,
                    tuple(t == "P" for t in robot.joint_types), axis_series(tp, plan.program.cell.external))


def _tcp_speed(plan: Plan, tp: TaskPlan, robot: Any, base: np.ndarray, tcp: np.ndarray, moves: list[Any]) -> np.ndarray:
    """(N,) mm/s: the TCP's speed in world (with the carriage of a robot on a track), and during
    a coordinated move relative to its frame riding on the positioner (the programmed speed's
    meaning), each differentiated in time over the samples of the move and one either side."""
    t = tp.trajectory.t
    if t.size < 2:
        return np.zeros(t.size)
    external = plan.program.cell.external
    riding = robot_bases(tp, external)  # a robot on a track: its base moves
    world = (base if riding is None else riding) @ np.asarray(robot.fk_batch(tp.trajectory.q)) @ tcp
    out: np.ndarray = np.linalg.norm(np.gradient(world[:, :3, 3], t, axis=0), axis=1) * 1000.0
    for t0, t1, move in moves:
        if move.coordinated is None or not move.coordinated.relative():
            continue
        inside = np.flatnonzero((t >= t0) & (t <= t1))
        if inside.size == 0:
            continue
        lo, hi = max(int(inside[0]) - 1, 0), min(int(inside[-1]) + 2, t.size)
        frames = riding_poses(tp, external, move.coordinated.frame, t[lo:hi])
        if frames is None or hi - lo < 2:
            continue
        relative = (np.linalg.inv(frames) @ world[lo:hi])[:, :3, 3]
        out[inside] = (np.linalg.norm(np.gradient(relative, t[lo:hi], axis=0), axis=1) * 1000.0)[inside - lo]
    return out


def plot_data(plan: Plan) -> PlotData:
    """Everything the plots draw, computed once (robots from the cell, as verification loads them)."""
    from rmot.sim.scene import build_scene  # late: loads coal only when this runs
    from rmot.sim.verification import _payload  # late: loads coal only when this runs

    scene = build_scene(plan.program.cell, {})
    tasks = []
    for tp in plan.tasks:
        entry = scene.robots.get(tp.robot)
        if entry is None:
            continue
        tasks.append(_task_data(plan, tp, entry.robot, np.asarray(entry.base), _payload(scene, tp)))
    return PlotData(plan.program.name, tuple(tasks))


def _figure(rows: int, cols: int, height_per_row: float = 1.25, width: float = 7.5) -> tuple[Any, Any]:
    import matplotlib  # late: matplotlib is heavy or optional, loaded only where used

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # late: matplotlib is heavy or optional, loaded only where used

    fig, axes = plt.subplots(rows, cols, figsize=(width * cols / max(cols, 1) ** 0.3, 0.9 + height_per_row * rows),
                             squeeze=False, sharex="col")
    return fig, axes


def _joint_panels(data: PlotData, quantity: str) -> Any:
    """One panel per joint (rows) and per task (columns), then one per external axis named by
    axis and unit (not for torques); limits dashed in red."""
    dof = max((td.q.shape[1] for td in data.tasks), default=1)
    extra = 0 if quantity == "torque" else max((len(td.axes) for td in data.tasks), default=0)
    fig, axes = _figure(dof + extra, max(len(data.tasks), 1))
    unit = {"joints": "deg", "speeds": "deg/s", "accels": "deg/s²", "torque": "N·m"}[quantity]
    linear = {"joints": "mm", "speeds": "mm/s", "accels": "mm/s²", "torque": "N"}[quantity]  # prismatic joints
    for c, td in enumerate(data.tasks):
        values, lower, upper = _series(td, quantity)
        for j in range(dof):
            ax = axes[j, c]
            if values is None or j >= values.shape[1]:
                ax.text(0.5, 0.5, "no inertia model: torques not known" if quantity == "torque" else "-",
                        ha="center", va="center", transform=ax.transAxes, fontsize=8)
                ax.set_yticks([])
                continue
            ax.plot(td.t, values[:, j], color=MOVE, linewidth=1.0)
            ax.axhline(upper[j], **LIMIT_STYLE)
            ax.axhline(lower[j], **LIMIT_STYLE)
            over = (values[:, j] > upper[j]) | (values[:, j] < lower[j])
            if over.any():
                ax.plot(td.t[over], values[over, j], ".", color=SYNC, markersize=2)
            prismatic = j < len(td.prismatic) and td.prismatic[j]
            ax.set_ylabel(f"J{j + 1} [{linear if prismatic else unit}]", fontsize=8)
            ax.tick_params(labelsize=7)
        if extra:
            _axis_panels(axes[dof:, c], td, quantity)
        axes[0, c].set_title(f"{td.name} on {td.robot}", fontsize=9)
        axes[-1, c].set_xlabel("time [s]", fontsize=8)
    title = {"joints": "joint positions", "speeds": "joint speeds", "accels": "joint accelerations",
             "torque": "joint torques"}[quantity]
    if extra:
        title = title.replace("joint ", "joint and axis ")
    fig.suptitle(f"{data.program}: {title} (dashed: limits)", fontsize=10)
    return fig


def _axis_panels(panels: Any, td: TaskData, quantity: str) -> None:
    """The external axes' rows of a task: `rail [mm]`, `pos.2 [deg/s]`, ... against their limits;
    each panel's SVG group id is `ext-NAME` (the axis' name)."""
    suffix = {"joints": "", "speeds": "/s", "accels": "/s²"}[quantity]
    for k, ax in enumerate(panels):
        if k >= len(td.axes):
            ax.set_yticks([])
            continue
        s = td.axes[k]
        values, limit = {"joints": (s.position, s.limits), "speeds": (s.speed, (-s.speed_limit, s.speed_limit)),
                         "accels": (s.accel, (-s.accel_limit, s.accel_limit))}[quantity]
        ax.plot(s.t, values, color=MOVE, linewidth=1.0)
        ax.axhline(limit[1], **LIMIT_STYLE)
        ax.axhline(limit[0], **LIMIT_STYLE)
        ax.set_ylabel(f"{s.name} [{s.unit}{suffix}]", fontsize=8)
        ax.set_gid(f"ext-{s.name}")
        ax.tick_params(labelsize=7)


def _series(td: TaskData, quantity: str) -> tuple[np.ndarray | None, np.ndarray, np.ndarray]:
    if quantity == "joints":
        return td.q, td.q_limits[:, 0], td.q_limits[:, 1]
    if quantity == "speeds":
        return td.qd, -td.qd_limits, td.qd_limits
    if quantity == "accels":
        return td.qdd, -td.qdd_limits, td.qdd_limits
    if td.tau is None or td.tau_limits is None:
        return None, np.zeros(0), np.zeros(0)
    return td.tau, -td.tau_limits, td.tau_limits


def _tcp(data: PlotData) -> Any:
    fig, axes = _figure(len(data.tasks) or 1, 1, height_per_row=2.0)
    for r, td in enumerate(data.tasks):
        ax = axes[r, 0]
        for t0, t1 in td.slowdowns:
            ax.axvspan(t0, max(t1, t0 + 0.02), color=WAIT, alpha=0.25, linewidth=0)
        ax.plot(td.t, td.tcp_speed, color=MOVE, linewidth=1.0, label="TCP speed")
        for k, (t0, t1, v) in enumerate(td.programmed):
            ax.hlines(v, t0, t1, colors="#2e7d32", linestyles="--", linewidth=1.0,
                      label="programmed (linear/circular)" if k == 0 else None)
        if td.slowdowns:
            ax.plot([], [], color=WAIT, alpha=0.4, linewidth=6, label="W221 slowdown")
        ax.set_ylabel("mm/s", fontsize=8)
        ax.set_title(f"{td.name} on {td.robot}", fontsize=9)
        ax.tick_params(labelsize=7)
        ax.legend(fontsize=7, loc="upper right")
    axes[-1, 0].set_xlabel("time [s]", fontsize=8)
    fig.suptitle(f"{data.program}: TCP speed", fontsize=10)
    return fig


def _timeline(data: PlotData) -> Any:
    fig, axes = _figure(1, 1, height_per_row=0.55 * max(len(data.tasks), 1) + 0.8)
    ax = axes[0, 0]
    colors = {"move": MOVE, "wait": WAIT, "sync": SYNC, "io": IO}
    for r, td in enumerate(data.tasks):
        y = len(data.tasks) - 1 - r
        for t0, t1, kind, _label in td.bars:
            width = max(t1 - t0, 0.0)
            if width > 0.0:
                ax.broken_barh([(t0, width)], (y - 0.35, 0.7), facecolors=colors[kind], edgecolors="white", linewidth=0.5)
            else:
                ax.vlines(t0, y - 0.4, y + 0.4, colors=colors[kind], linewidth=1.2)
    ax.set_yticks(range(len(data.tasks)))
    ax.set_yticklabels([f"{td.name} ({td.robot})" for td in reversed(data.tasks)], fontsize=8)
    for kind, color in colors.items():
        ax.plot([], [], color=color, linewidth=6, label={"move": "move", "wait": "wait (time / input)",
                                                           "sync": "sync (waiting for the other task)", "io": "I/O"}[kind])
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.5), ncol=4, frameon=False)
    ax.set_xlabel("time [s]", fontsize=8)
    ax.tick_params(labelsize=7)
    fig.suptitle(f"{data.program}: per-instruction timeline", fontsize=10)
    return fig


def make_figure(data: PlotData, what: str) -> Any:
    """The matplotlib Figure of one plot kind (see KINDS)."""
    if what in ("joints", "speeds", "accels", "torque"):
        return _joint_panels(data, what)
    if what == "tcp":
        return _tcp(data)
    if what == "timeline":
        return _timeline(data)
    raise ValueError(f"plot kind must be one of {', '.join(KINDS)} (got {what!r})")


def figure_bytes(data: PlotData, what: str, fmt: str) -> bytes:
    """One plot kind as PNG or SVG bytes (deterministic)."""
    import matplotlib  # late: matplotlib is heavy or optional, loaded only where used

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # late: matplotlib is heavy or optional, loaded only where used

    if fmt not in ("png", "svg"):
        raise ValueError(f"plot format must be png or svg (got {fmt!r})")
    with matplotlib.rc_context({"svg.hashsalt": "rmot", "svg.fonttype": "path"}):
        fig = make_figure(data, what)
        try:
            fig.tight_layout(rect=(0, 0, 1, 0.96))
            buffer = io.BytesIO()
            metadata = {"Date": None} if fmt == "svg" else {"Software": None}
            fig.savefig(buffer, format=fmt, dpi=100, metadata=metadata)
        finally:
            plt.close(fig)
    return buffer.getvalue()
