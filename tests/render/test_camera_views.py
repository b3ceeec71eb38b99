"""The default camera shows the work; presets give named views around the working side."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
from render_fixtures import arm3, plan

from rmot.lang import ir
from rmot.sim.render.camera import Camera
from rmot.sim.render.pipeline import depth_frame
from rmot.sim.render.scene import body_poses, prepare, soup
from rmot.sim.render.still import CANDIDATES, default_camera, facing_deg, preset_camera

SIZE = (160, 120)


def robot_share(rs, camera: Camera, time: float) -> float:  # type: ignore[no-untyped-def]
    """Share of the robot's own pixels that stay visible with every body drawn (160 x 120)."""
    vertices, _, _ = soup(rs, body_poses(rs, np.array([time]))[0])
    owner = np.concatenate([np.full(len(rs.floor), -1)] + [np.full(len(m), i) for i, m in enumerate(rs.meshes)])
    robot = np.array([i for i, b in enumerate(rs.scene.bodies) if b.kind != "fixture"])
    mine = np.isin(owner, robot)
    full, source = depth_frame(vertices, camera, SIZE)
    alone, _ = depth_frame(vertices[mine], camera, SIZE)
    seen = (full.tri >= 0) & np.isin(owner[source][np.maximum(full.tri, 0)], robot)
    return seen.sum() / max((alone.tri >= 0).sum(), 1)


def _with_wall(azimuth_deg: float) -> object:
    """The test cell with a 3 x 3 m wall 1.3 m from the robot across the given azimuth."""
    p = plan()
    a = math.radians(azimuth_deg)
    wall = ir.Fixture("wall", ir.Box((0.05, 3.0, 3.0)), ir.Pose.from_xyz_rpy(1.3 * math.cos(a), 1.3 * math.sin(a), 1.5, 0, 0, a))
    cell = dataclasses.replace(p.program.cell, fixtures=p.program.cell.fixtures + (wall,))
    return dataclasses.replace(p, program=dataclasses.replace(p.program, cell=cell))


def test_default_view_does_not_look_through_a_wall() -> None:
    """A wall across the preferred view makes the camera pick another side, where the robot shows."""
    base = prepare(plan(), robots={"r1": arm3()})
    preferred = facing_deg(base) + CANDIDATES[0][0]
    rs = prepare(_with_wall(preferred), robots={"r1": arm3()})
    blocked = Camera.framing(rs.bounds, aspect=4 / 3, azimuth_deg=facing_deg(rs) + CANDIDATES[0][0],
                             elevation_deg=CANDIDATES[0][1], points=rs.extent)
    chosen = default_camera(rs, SIZE)
    assert robot_share(rs, blocked, 1.0) < 0.3  # the wall hides the robot from the preferred side
    assert robot_share(rs, chosen, 1.0) > 0.8


def test_presets_look_from_their_side() -> None:
    rs = prepare(plan(), robots={"r1": arm3()})
    facing = math.radians(facing_deg(rs))
    work = np.array([math.cos(facing), math.sin(facing)])
    for name, check in (("front", lambda d: d[:2] @ work > 0.9), ("top", lambda d: d[2] > 0.99),
                        ("side", lambda d: abs(d[:2] @ work) < 0.1), ("iso", lambda d: 0.5 < d[2] < 0.65)):
        cam = preset_camera(rs, name, SIZE)
        d = np.subtract(cam.eye, cam.center)
        assert check(d / np.linalg.norm(d)), name
