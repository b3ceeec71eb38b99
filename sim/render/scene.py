"""The cell and the Plan at an instant -> coloured triangles for the pipeline.

Bodies come from the verification scene (rmot.sim.scene), so a picture names and places
every body exactly as the checker does: a fixture by its name, a tool by its name, a link
solid as f"{robot}/{solid.name}". Each body is tessellated once in its own frame; a frame
of the picture only needs the (B, 4, 4) body poses at that instant.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from rmot.lang import ir, ir_tree
from rmot.lang.plan_types import Plan
from rmot.lang.diagnostics import Diagnostic
from rmot.sim.render.tessellate import TriMesh, merge, tessellate
from rmot.sim.render.transform import rotate_vectors, transform_points
from rmot.sim.part_phases import declared_part
from rmot.sim.parts import part_poses, with_part_bodies
from rmot.sim.scene import Body, Scene, build_scene
from rmot.sim.axes_collide import driving_task, mechanism_motion, with_axes

if TYPE_CHECKING:
    from rmot.compiler.plan.robot_model import RobotModel

__all__ = ["HIGHLIGHT", "RenderScene", "body_poses", "prepare", "soup"]

HIGHLIGHT = (0.86, 0.08, 0.06)
FIXTURE = (0.55, 0.62, 0.70)
TOOL = (0.30, 0.31, 0.34)
FLOOR = ((0.80, 0.81, 0.83), (0.72, 0.73, 0.76))  # checker tiles
PATH = (0.05, 0.42, 0.92)
ROBOT_BY_VENDOR = {  # the colours the vendors paint their arms, roughly
    "abb": (0.93, 0.93, 0.91), "kuka": (0.96, 0.45, 0.05), "fanuc": (0.98, 0.80, 0.05),
    "yaskawa": (0.10, 0.35, 0.75), "staubli": (0.98, 0.78, 0.10), "universal robots": (0.62, 0.75, 0.85),
    "ur": (0.62, 0.75, 0.85),
}
ROBOT_DEFAULT = (0.85, 0.55, 0.15)
PART = (0.78, 0.56, 0.30)  # cardboard: parts that tools pick up and put down


@dataclass(frozen=True, eq=False)
class RenderScene:
    """Everything a picture of one program needs that does not change with time.

    names (B,), meshes (B,) in body frames, colors (B, 3); floor a static TriMesh in world
    with per-triangle colours floor_colors (F, 3); paths: the TCP path of each task (N_i, 3)
    in world; bounds (2, 3) of every body over the whole program (for the camera).
    """

    plan: Plan
    scene: Scene
    names: tuple[str, ...]
    meshes: tuple[TriMesh, ...]
    colors: np.ndarray
    floor: TriMesh
    floor_colors: np.ndarray
    paths: tuple[np.ndarray, ...]
    bounds: np.ndarray
    diagnostics: tuple[Diagnostic, ...] = ()
    extent: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))  # (K, 3) points the camera must see


def _tools_used(program: ir.Program) -> dict[str, set[str]]:
    used: dict[str, set[str]] = {}
    for task in program.tasks:
        for instr in ir_tree.walk(task.body):
            if isinstance(instr, ir.Move) and instr.tool.name is not None:
                used.setdefault(task.robot, set()).add(instr.tool.name)
    return used


def _robot_color(robot: object) -> tuple[float, float, float]:
    vendor = str(getattr(robot, "vendor", "")).lower()
    return next((c for key, c in ROBOT_BY_VENDOR.items() if vendor.startswith(key)), ROBOT_DEFAULT)


def _home(robot: RobotModel) -> np.ndarray:
    limits = np.asarray(robot.joint_limits)
    return np.clip(np.zeros(len(limits)), limits[:, 0], limits[:, 1])


def joint_values(plan: Plan, scene: Scene, times: np.ndarray) -> dict[str, np.ndarray]:
    """robot -> (N, dof) joint values at `times` (N,) s; robots without a task stay at zero."""
    out: dict[str, np.ndarray] = {}
    for name, entry in scene.robots.items():
        task = next((tp for tp in plan.tasks if tp.robot == name), None)
        if task is None or task.trajectory.t.size == 0:
            out[name] = np.tile(_home(entry.robot), (len(times), 1))
            continue
        traj = task.trajectory
        out[name] = np.stack([np.interp(times, traj.t, traj.q[:, j]) for j in range(traj.q.shape[1])], axis=1)
    return out


def body_poses(rs: RenderScene, times: np.ndarray) -> np.ndarray:
    """World poses (N, B, 4, 4) of every body at `times` (N,) s."""
    times = np.atleast_1d(np.asarray(times, float))
    q = joint_values(rs.plan, rs.scene, times)
    moving: dict[str, np.ndarray] = {}
    for robot, values in q.items():
        moving.update(rs.scene.poses(robot, values))
    moving.update(part_poses(rs.scene, rs.plan, times, q))  # parts: placed or on a flange
    external = rs.plan.program.cell.external
    driver = driving_task(list(rs.plan.tasks), external)
    if driver is not None and external is not None:  # a robot on a track, fixtures on a positioner
        moving = with_axes(rs.scene, driver, external, times, moving)
    poses = np.empty((len(times), len(rs.names), 4, 4))
    for i, body in enumerate(rs.scene.bodies):
        poses[:, i] = moving[body.name] if body.name in moving else body.local
    return poses


def soup(rs: RenderScene, poses: np.ndarray, highlight: tuple[str, ...] = ()) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Triangles (T, 3, 3), normals (T, 3, 3), colours (T, 3) of the scene with bodies at poses (B, 4, 4)."""
    verts, norms, cols = [rs.floor.vertices], [rs.floor.normals], [rs.floor_colors]
    for i, (name, mesh) in enumerate(zip(rs.names, rs.meshes)):
        pose = poses[i]
        verts.append(transform_points(pose, mesh.vertices))
        norms.append(rotate_vectors(pose, mesh.normals))  # rigid motion: rotate the normals
        color = HIGHLIGHT if name in highlight else rs.colors[i]
        cols.append(np.broadcast_to(np.asarray(color, np.float32), (len(mesh), 3)))
    return np.concatenate(verts), np.concatenate(norms), np.concatenate(cols).astype(np.float32)


def _extent(meshes: tuple[TriMesh, ...], poses: np.ndarray) -> np.ndarray:
    """(K, 3) world corners of each body's box at every pose sample (N, B, 4, 4): what must be seen."""
    points = []
    for i, mesh in enumerate(meshes):
        if len(mesh) == 0:
            continue
        pts = mesh.vertices.reshape(-1, 3)
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        corners = np.array([[(lo, hi)[a][0], (lo, hi)[b][1], (lo, hi)[c][2]] for a in (0, 1) for b in (0, 1) for c in (0, 1)])
        points.append((corners @ np.swapaxes(poses[:, i, :3, :3], 1, 2) + poses[:, i, None, :3, 3]).reshape(-1, 3))
    return np.concatenate(points) if points else np.array([[-1.0, -1.0, 0.0], [1.0, 1.0, 1.0]])


def _floor(bounds: np.ndarray, tile: float = 0.25) -> tuple[TriMesh, np.ndarray]:
    """A checkered floor at z = 0 under the cell (tiles of `tile` m, 0.5 m beyond the bounds)."""
    lo = np.floor((bounds[0, :2] - 0.5) / tile) * tile
    hi = np.ceil((bounds[1, :2] + 0.5) / tile) * tile
    nx, ny = int(round((hi[0] - lo[0]) / tile)), int(round((hi[1] - lo[1]) / tile))
    ix, iy = np.meshgrid(np.arange(nx), np.arange(ny), indexing="ij")
    x0, y0 = lo[0] + ix.ravel() * tile, lo[1] + iy.ravel() * tile
    x1, y1 = x0 + tile, y0 + tile
    zero = np.zeros_like(x0)
    a, b = np.stack([x0, y0, zero], 1), np.stack([x1, y0, zero], 1)
    c, d = np.stack([x1, y1, zero], 1), np.stack([x0, y1, zero], 1)
    tris = np.concatenate([np.stack([a, b, c], 1), np.stack([a, c, d], 1)])
    normals = np.broadcast_to(np.array([0.0, 0.0, 1.0]), tris.shape).copy()
    parity = np.tile((ix.ravel() + iy.ravel()) % 2, 2)
    colors = np.asarray(FLOOR, np.float32)[parity]
    return TriMesh(tris, normals), colors


def _tcp_paths(plan: Plan, scene: Scene, max_points: int = 1500) -> tuple[np.ndarray, ...]:
    """The TCP of each task's active tool along its trajectory, in world (N_i, 3)."""
    paths = []
    for tp in plan.tasks:
        entry = scene.robots.get(tp.robot)
        traj = tp.trajectory
        if entry is None or traj.t.size < 2:
            continue
        idx = np.unique(np.linspace(0, traj.t.size - 1, min(traj.t.size, max_points)).astype(int))
        flange = np.asarray(entry.robot.fk_batch(traj.q[idx]))
        tcp = _active_tcp(tp, traj.t[idx])  # (N, 4, 4)
        world = entry.base @ flange @ tcp
        external = plan.program.cell.external
        mount = external.mount(tp.robot) if external is not None else None
        if mount is not None and external is not None:  # the arm rides on a track
            world = mechanism_motion(traj.t[idx], tp, external)[mount.mechanism] @ world
        paths.append(world[:, :3, 3])
    return tuple(paths)


def _active_tcp(tp: object, times: np.ndarray) -> np.ndarray:
    """(N, 4, 4) TCP in the flange frame of the move running at each time (flange if none)."""
    moves = {m.uid: m for m in ir_tree.walk(tp.task.body) if isinstance(m, ir.Move)}  # type: ignore[attr-defined]
    spans = sorted((r.t_start, r.uid) for r in tp.records if r.variant == 0 and r.uid in moves)  # type: ignore[attr-defined]
    out = np.tile(np.eye(4), (len(times), 1, 1))
    if not spans:
        return out
    starts = np.array([s for s, _ in spans])
    which = np.clip(np.searchsorted(starts, times, side="right") - 1, 0, len(spans) - 1)
    for k, (_, uid) in enumerate(spans):
        out[which == k] = moves[uid].tool.tcp.matrix()
    return out


def prepare(plan: Plan, samples: int = 24, robots: Mapping[str, object] | None = None) -> RenderScene:
    """Tessellate the program's cell once; bounds cover `samples` instants of the program.

    robots: robot instance name -> Robot (default: loaded from the robot library).
    """
    scene = with_part_bodies(build_scene(plan.program.cell, _tools_used(plan.program), robots), plan)
    names = tuple(b.name for b in scene.bodies)
    meshes = tuple(tessellate(b.shape) for b in scene.bodies)
    colors = np.array([_body_color(scene, b) for b in scene.bodies], np.float32).reshape(-1, 3)
    partial = RenderScene(plan, scene, names, meshes, colors, merge([]), np.zeros((0, 3)), (), np.zeros((2, 3)))
    times = np.linspace(0.0, max(plan.cycle_time, 0.0), samples)
    paths = _tcp_paths(plan, scene)
    extent = np.concatenate([_extent(meshes, body_poses(partial, times)), *paths])
    bounds = np.stack([extent.min(axis=0), extent.max(axis=0)])
    bounds[0, 2] = min(bounds[0, 2], 0.0)  # the floor is part of the view
    floor, floor_colors = _floor(bounds)
    return RenderScene(plan, scene, names, meshes, colors, floor, floor_colors, paths, bounds, scene.diagnostics, extent)


def _body_color(scene: Scene, body: Body) -> tuple[float, float, float]:
    if any(p.name == declared_part(body.name) for p in scene.cell.parts):
        return PART
    kind = body.kind
    if kind == "fixture":
        return FIXTURE
    if kind == "tool":
        return TOOL
    assert body.robot is not None  # neither a fixture nor a tool: a robot's link
    return _robot_color(scene.robots[body.robot].robot)
