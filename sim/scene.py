"""The cell model for verification: every body with a stable name, its geometry and its pose.

Body names: a fixture is its name, a tool is its name, a robot link solid is
f"{robot}/{solid.name}". Poses are (4, 4) world transforms of the body's geometry frame.

Each body also carries a conservative bound used by the broad phase (collide.py):
  * moving bodies (links, tools): a set of spheres in the geometry frame whose union
    contains the solid;
  * fixtures: an oriented box (centre pose, half extents) that contains the solid;
and, for moving bodies, `reach[j]`: an upper bound on the distance of any point of the
body from the origin of joint j (config independent: the sum of the joint offsets along the
chain plus the body's own extent), which bounds how far the body can move when q_j changes.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from rmot.lang import ir
from rmot.lang.diagnostics import Diagnostic, Severity
from rmot.sim import codes
from rmot.sim.meshio import MeshData, load_mesh

__all__ = ["Body", "RobotEntry", "Scene", "build_scene", "flange_in_last_joint", "load_robots"]

Shape = ir.Box | ir.Cylinder | ir.Sphere | ir.Capsule | MeshData
# samples per block of Scene.poses (at least fastdls.JOINT_FRAMES's threshold, 25,000)
POSE_CHUNK = 32_768


@dataclass(frozen=True, eq=False)
class Body:
    """One rigid solid. `local`: (4, 4) geometry frame relative to what carries it — the world
    (fixtures), the robot base via solid_poses (links: identity), or the flange (tools)."""

    name: str
    kind: str  # "fixture" | "link" | "tool"
    robot: str | None
    shape: Shape
    local: np.ndarray
    solid_index: int | None = None
    joint: int = 0  # pinocchio joint the body rides on; 0 = static
    spheres: np.ndarray | None = None  # (K, 4) centre xyz + radius, geometry frame
    obb_centre: np.ndarray | None = None  # (3,) centre of the bounding box, geometry frame
    obb_half: np.ndarray | None = None  # (3,) half extents, geometry frame (fixtures)
    reach: np.ndarray | None = None  # (dof,) m, bound on distance from each joint origin
    span: Any = None

    @property
    def moves(self) -> bool:
        return self.kind != "fixture" and self.joint > 0


@dataclass(frozen=True, eq=False)
class RobotEntry:
    name: str
    robot: Any  # rmot.sim.robots.Robot (or any object with the same API)
    base: np.ndarray  # (4, 4) base in world
    prismatic: np.ndarray  # (dof,) bool


@dataclass(frozen=True, eq=False)
class Scene:
    cell: ir.Cell
    robots: Mapping[str, RobotEntry]
    bodies: tuple[Body, ...]
    diagnostics: tuple[Diagnostic, ...] = ()

    @functools.cached_property
    def always_touching(self) -> frozenset[frozenset[str]]:
        """Self pairs never checked: they touch at every configuration (see _always_touching).
        Computed on first use (the renderer builds scenes too and never needs it)."""
        return frozenset().union(*(_always_touching(e, list(self.robot_bodies(name)))
                                   for name, e in self.robots.items()))

    def body(self, name: str) -> Body:
        for b in self.bodies:
            if b.name == name:
                return b
        raise KeyError(name)

    def robot_bodies(self, robot: str) -> tuple[Body, ...]:
        return tuple(b for b in self.bodies if b.robot == robot)

    def poses(self, robot: str, q: np.ndarray) -> dict[str, np.ndarray]:
        """World poses of the robot's bodies for joint samples q: (N, dof) -> {name: (N, 4, 4)}.

        Computed POSE_CHUNK samples at a time into the result arrays, so the robot's
        intermediate frames (all joints, all solids: several times the result) are held for
        one chunk only (2000 moves peaked at 600 MB here). Every sample's pose is
        the same product either way, the same floats; the first chunk is at least the FK
        kernel's compile threshold, so it takes the same (compiled or interpreted) form as
        one call for all samples would."""
        from rmot.sim.robots.fastdls import JOINT_FRAMES  # late: loads coal only when this runs

        entry = self.robots[robot]
        q = np.atleast_2d(np.asarray(q, dtype=np.float64))
        bodies = self.robot_bodies(robot)
        out = {b.name: np.empty((q.shape[0], 4, 4)) for b in bodies}
        has_tool = any(b.kind == "tool" for b in bodies)
        size = max(POSE_CHUNK, JOINT_FRAMES.threshold)
        for lo in range(0, q.shape[0], size) if q.shape[0] else ():
            chunk = q[lo:lo + size]
            solids = np.asarray(entry.robot.solid_poses_batch(chunk))
            flange = np.asarray(entry.robot.fk_batch(chunk)) if has_tool else None
            for b in bodies:
                if b.kind == "link":
                    out[b.name][lo:lo + size] = entry.base @ solids[:, b.solid_index]
                else:
                    out[b.name][lo:lo + size] = entry.base @ flange @ b.local
        return out

    def fixture_pose(self, body: Body) -> np.ndarray:
        return body.local


def load_robots(cell: ir.Cell) -> tuple[dict[str, Any], tuple[Diagnostic, ...]]:
    """Load every robot of the cell through the robot library; failures become diagnostics."""
    from rmot.sim.robots import load_robot  # late: loads coal only when this runs

    robots: dict[str, Any] = {}
    diags: list[Diagnostic] = []
    for inst in cell.robots:
        try:
            robots[inst.name] = load_robot(inst.source.load_key)
        except Exception as exc:  # RobotError, or the library not built yet
            diags.append(Diagnostic(codes.ROBOT_UNAVAILABLE, Severity.ERROR,
                                    f"robot '{inst.name}' must load for verification ({exc})", inst.span))
    return robots, tuple(diags)


def build_scene(cell: ir.Cell, tools_used: Mapping[str, set[str]] | None = None,
                robots: Mapping[str, Any] | None = None) -> Scene:
    """The cell as bodies. `tools_used`: robot -> tool names that are mounted (default: every
    tool of the cell); `robots`: robot name -> Robot (default: loaded from the library)."""
    diags: list[Diagnostic] = []
    if robots is None:
        robots, robot_diags = load_robots(cell)
        diags += robot_diags
    entries: dict[str, RobotEntry] = {}
    bodies: list[Body] = []
    for f in cell.fixtures:
        shape = _shape(f.geometry, diags)
        if shape is not None:
            bodies.append(_fixture_body(f, shape))
    for inst in cell.robots:
        robot = robots.get(inst.name)
        if robot is None:
            continue
        entry = RobotEntry(inst.name, robot, inst.base.matrix(), _prismatic(robot))
        entries[inst.name] = entry
        bodies += _link_bodies(entry, diags)
        for tool in cell.tools:
            used = tools_used is None or tool.name in tools_used.get(inst.name, set())
            if tool.robot == inst.name and tool.geometry is not None and used:
                shape = _shape(tool.geometry, diags)
                if shape is not None:
                    bodies.append(_tool_body(entry, tool, shape))
    return Scene(cell, entries, tuple(bodies), tuple(diags))


_TOUCH_SAMPLES = 64


def _always_touching(entry: RobotEntry, bodies: list[Body]) -> frozenset[frozenset[str]]:
    """Pairs of one robot's solids that touch in every one of a fixed set of configurations
    within the limits (as MoveIt's setup assistant disables "always in collision" pairs):
    they overlap by construction (e.g. a forearm capsule reaching into a spherical wrist's
    flange), so checking them would only report the model, never the program."""
    from rmot.sim.exact import exact_distance  # coal: loaded when a cell is checked  # late: loads coal only when this runs

    robot = entry.robot
    lo, hi = robot.joint_limits[:, 0], robot.joint_limits[:, 1]
    rng = np.random.default_rng(0)  # fixed: the same cell always gives the same pairs
    qs = np.vstack([np.clip(np.zeros(robot.dof), lo, hi), lo + rng.random((_TOUCH_SAMPLES, robot.dof)) * (hi - lo)])
    solids = np.asarray(robot.solid_poses_batch(qs))
    flange = np.asarray(robot.fk_batch(qs))
    poses = {b.name: solids[:, b.solid_index] if b.kind == "link" else flange @ b.local for b in bodies}
    adjacent = {frozenset(p) for p in robot.adjacent_pairs}
    out = set()
    for i, a in enumerate(bodies):
        for b in bodies[i + 1:]:
            if not (a.moves or b.moves) or frozenset((a.solid_index, b.solid_index)) in adjacent:
                continue
            if all(exact_distance(a, b, poses[a.name][k], poses[b.name][k]) <= 0.0 for k in range(len(qs))):
                out.add(frozenset((a.name, b.name)))
    return frozenset(out)


# --------------------------------------------------------------------------- bodies


def _shape(geometry: ir.Geometry, diags: list[Diagnostic]) -> Shape | None:
    if isinstance(geometry, ir.Mesh):
        loaded = load_mesh(geometry)
        if isinstance(loaded, Diagnostic):
            diags.append(loaded)
            return None
        diags += loaded.warnings
        return loaded
    return geometry


def _fixture_body(f: ir.Fixture, shape: Shape) -> Body:
    centre, half = _local_box(shape)
    return Body(f.name, "fixture", None, shape, f.pose.matrix(), obb_centre=centre, obb_half=half,
                span=f.span, spheres=_sphere_cover(shape))


def _link_bodies(entry: RobotEntry, diags: list[Diagnostic]) -> list[Body]:
    robot = entry.robot
    out = []
    for i, solid in enumerate(robot.solids):
        shape = _shape(solid.geometry, diags)
        if shape is None:
            continue
        spheres = _sphere_cover(shape)
        placement = solid.placement.matrix()
        reach = _reach(robot, solid.joint_id, spheres, placement, entry.prismatic)
        out.append(Body(f"{entry.name}/{solid.name}", "link", entry.name, shape, np.eye(4),
                        solid_index=i, joint=int(solid.joint_id), spheres=spheres, reach=reach))
    return out


def _tool_body(entry: RobotEntry, tool: ir.Tool, shape: Shape) -> Body:
    robot = entry.robot
    spheres = _sphere_cover(shape)
    flange_in_joint = flange_in_last_joint(robot)
    placement = flange_in_joint @ tool.geometry_pose.matrix()
    reach = _reach(robot, robot.dof, spheres, placement, entry.prismatic)
    return Body(tool.name, "tool", entry.name, shape, tool.geometry_pose.matrix(), joint=int(robot.dof),
                spheres=spheres, reach=reach, span=tool.span)


def _prismatic(robot: Any) -> np.ndarray:
    return np.array([t == "P" for t in robot.joint_types], dtype=bool)


def _reach(robot: Any, joint: int, spheres: np.ndarray, placement: np.ndarray, prismatic: np.ndarray) -> np.ndarray:
    """reach[j-1]: bound on |p - origin of joint j| for every point p of the body (0 if the
    body is not downstream of joint j). Joint ids are pinocchio's: 1..dof along the chain."""
    model = robot.model
    centres = spheres[:, :3] @ placement[:3, :3].T + placement[:3, 3]
    extent = float(np.max(np.linalg.norm(centres, axis=1) + spheres[:, 3])) if len(spheres) else 0.0
    reach = np.zeros(robot.dof)
    chain = 0.0
    k = joint
    while k > 0:
        if k - 1 < robot.dof:  # a prismatic joint translates every point by exactly |dq|
            reach[k - 1] = 1.0 if prismatic[k - 1] else extent + chain
        chain += float(np.linalg.norm(model.jointPlacements[k].translation))
        if k - 1 < len(prismatic) and prismatic[k - 1]:
            chain += float(np.max(np.abs(robot.joint_limits[k - 1])))
        k = int(model.parents[k])
    return reach


def flange_in_last_joint(robot: Any) -> np.ndarray:
    """The flange in the frame of the last joint, recovered from a solid on that joint
    (solid pose = joint pose * placement, so joint pose = solid pose * placement^-1)."""
    q0 = np.clip(np.zeros(robot.dof), robot.joint_limits[:, 0], robot.joint_limits[:, 1])
    poses = np.asarray(robot.solid_poses(q0))
    for i, solid in enumerate(robot.solids):
        if int(solid.joint_id) == robot.dof:
            joint_pose = poses[i] @ np.linalg.inv(solid.placement.matrix())
            return np.linalg.inv(joint_pose) @ np.asarray(robot.fk(q0))
    # no solid on the last joint: bound the flange offset by the robot's reach (conservative)
    offset = np.eye(4)
    offset[0, 3] = float(getattr(robot, "reach", 1.0))
    return offset


# --------------------------------------------------------------------------- bounds


def _local_box(shape: Shape) -> tuple[np.ndarray, np.ndarray]:
    """(centre (3,), half extents (3,)) of a box containing the shape, in its geometry frame."""
    if isinstance(shape, ir.Box):
        return np.zeros(3), np.asarray(shape.size, dtype=float) / 2
    if isinstance(shape, ir.Sphere):
        return np.zeros(3), np.full(3, shape.radius)
    if isinstance(shape, ir.Cylinder):
        return np.zeros(3), np.array([shape.radius, shape.radius, shape.height / 2])
    if isinstance(shape, ir.Capsule):
        return np.zeros(3), np.array([shape.radius, shape.radius, shape.length / 2 + shape.radius])
    lo, hi = shape.vertices.min(axis=0), shape.vertices.max(axis=0)
    return (lo + hi) / 2, (hi - lo) / 2


def _sphere_cover(shape: Shape) -> np.ndarray:
    """(K, 4) spheres whose union contains the shape: a chain along its longest axis."""
    if isinstance(shape, ir.Sphere):
        return np.array([[0.0, 0.0, 0.0, shape.radius]])
    centre, half = _local_box(shape)
    if isinstance(shape, (ir.Cylinder, ir.Capsule)):
        axis, length = 2, (shape.length if isinstance(shape, ir.Capsule) else shape.height)
        cross = shape.radius
    else:
        axis = int(np.argmax(half))
        length = 2 * half[axis]
        others = [half[i] for i in range(3) if i != axis]
        cross = math.hypot(*others)
    # spheres at spacing s along the axis with radius sqrt(cross^2 + (s/2)^2) cover the prism
    count = max(1, math.ceil(length / max(cross, 1e-9)))
    spacing = length / count
    radius = math.hypot(cross, spacing / 2)
    offsets = np.linspace(-length / 2 + spacing / 2, length / 2 - spacing / 2, count)
    if isinstance(shape, ir.Capsule):  # the caps stick out by `radius` beyond the segment ends
        offsets = np.linspace(-length / 2, length / 2, count + 1)
        radius = math.hypot(cross, spacing / 2) if count else cross
    spheres = np.zeros((len(offsets), 4))
    spheres[:, :3] = centre
    spheres[:, axis] += offsets
    spheres[:, 3] = radius
    return spheres
