"""The rasteriser against an independent ray-cast of the same scene, pixel by pixel.

Each scene is a few boxes (possibly turned about z) on a floor. The test builds their
triangles itself (12 per box, 2 for the floor), renders them with the pipeline's visibility
buffer, and casts one ray per pixel centre with a slab test against each box and a plane
test against the floor: the nearest object must be the one the rasteriser shows, except on
pixels whose 3 x 3 neighbourhood in the ray-cast holds more than one object (edge pixels,
where a centre a hair inside one object may rasterise to its neighbour).

The scenes include two that once rendered wrong: a box 1.2 m in front of the eye with the rest
of the scene 6 m away (the near plane once followed the scene's size and cut the box away), and a
table seen from close by (the floor showed through its front face). The floor triangles are
large and cross the near plane and pass behind the eye, so clipping is exercised too.
"""

from __future__ import annotations

import math
import re

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from rmot.sim.render.camera import Camera, parse_camera
from rmot.sim.render.pipeline import depth_frame
from rmot.sim.render.svg import wireframe_svg

SIZE = (96, 72)
FLOOR_HALF = 30.0  # m: a 60 x 60 m floor of two triangles, reaching far behind every eye


class Box:
    """A box of half sizes `half` centred at `center`, turned by `yaw` rad about +z."""

    def __init__(self, center: tuple[float, float, float], size: tuple[float, float, float], yaw: float = 0.0) -> None:
        self.center = np.asarray(center, float)
        self.half = np.asarray(size, float) / 2.0
        c, s = math.cos(yaw), math.sin(yaw)
        self.rot = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])  # box axes as columns

    def triangles(self) -> np.ndarray:
        """12 outward-facing triangles (12, 3, 3) in world coordinates."""
        h = self.half
        corner = lambda i, j, k: self.center + self.rot @ (np.array([i, j, k]) * h)  # noqa: E731
        faces = []
        for axis in range(3):
            for sign in (-1.0, 1.0):
                u, v = [a for a in range(3) if a != axis]
                quad = []
                for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                    p = [0.0, 0.0, 0.0]
                    p[axis], p[u], p[v] = sign, a, b
                    quad.append(corner(*p))
                faces += [[quad[0], quad[1], quad[2]], [quad[0], quad[2], quad[3]]]
        return np.array(faces)

    def hit(self, origin: np.ndarray, dirs: np.ndarray) -> np.ndarray:
        """Ray parameter (H, W) of the entry point of each ray (inf where it misses): slab test."""
        o = self.rot.T @ (origin - self.center)
        d = dirs @ self.rot  # directions in the box frame
        with np.errstate(divide="ignore", invalid="ignore"):
            t1 = (-self.half - o) / d
            t2 = (self.half - o) / d
        lo = np.nanmax(np.minimum(t1, t2), axis=-1)
        hi = np.nanmin(np.maximum(t1, t2), axis=-1)
        return np.where((lo <= hi) & (lo > 0.0), lo, np.inf)


def floor_triangles() -> np.ndarray:
    a, b, c, d = [(x * FLOOR_HALF, y * FLOOR_HALF, 0.0) for x, y in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
    return np.array([[a, b, c], [a, c, d]], float)


def floor_hit(origin: np.ndarray, dirs: np.ndarray) -> np.ndarray:
    with np.errstate(divide="ignore", invalid="ignore"):
        t = -origin[2] / dirs[..., 2]
    p = origin + t[..., None] * dirs
    inside = (t > 0.0) & (np.abs(p[..., 0]) <= FLOOR_HALF) & (np.abs(p[..., 1]) <= FLOOR_HALF)
    return np.where(inside, t, np.inf)


def pixel_rays(camera: Camera, size: tuple[int, int]) -> tuple[np.ndarray, np.ndarray]:
    """Eye (3,) and unit ray directions (H, W, 3) through the pixel centres, from the camera's
    definition (eye, centre, up, vertical view angle) alone."""
    width, height = size
    forward = np.subtract(camera.center, camera.eye)
    forward = forward / np.linalg.norm(forward)
    right = np.cross(forward, camera.up)
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    tan = math.tan(math.radians(camera.fov_deg) / 2.0)
    cols, rows = np.meshgrid(np.arange(width) + 0.5, np.arange(height) + 0.5)
    x = (2.0 * cols / width - 1.0) * tan * width / height
    y = (1.0 - 2.0 * rows / height) * tan
    dirs = forward + x[..., None] * right + y[..., None] * up
    return np.asarray(camera.eye, float), dirs / np.linalg.norm(dirs, axis=-1, keepdims=True)


def raycast_hits(boxes: list[Box], camera: Camera, size: tuple[int, int], floor: bool = True) -> np.ndarray:
    """Ray parameter (K, H, W) of every object at every pixel (inf: missed); floor last."""
    origin, dirs = pixel_rays(camera, size)
    return np.stack([b.hit(origin, dirs) for b in boxes] + ([floor_hit(origin, dirs)] if floor else []))


def raycast_ids(boxes: list[Box], camera: Camera, size: tuple[int, int], floor: bool = True) -> np.ndarray:
    """Object id (H, W) of the nearest hit: box i -> i, floor -> len(boxes), nothing -> -1."""
    stack = raycast_hits(boxes, camera, size, floor)
    ids = np.argmin(stack, axis=0)
    return np.where(np.isfinite(stack.min(axis=0)), ids, -1)


def raster_ids(boxes: list[Box], camera: Camera, size: tuple[int, int], floor: bool = True) -> np.ndarray:
    tris = [b.triangles() for b in boxes] + ([floor_triangles()] if floor else [])
    owner = np.concatenate([np.full(len(t), i) for i, t in enumerate(tris)])
    frame, source = depth_frame(np.concatenate(tris), camera, size)
    if len(source) == 0:
        return np.full(frame.tri.shape, -1)
    return np.where(frame.tri >= 0, owner[source[np.maximum(frame.tri, 0)]], -1)


def interior(ids: np.ndarray) -> np.ndarray:
    """Pixels whose 3 x 3 neighbourhood shows one object only."""
    padded = np.pad(ids, 1, mode="edge")
    same = np.ones(ids.shape, bool)
    h, w = ids.shape
    for dy in range(3):
        for dx in range(3):
            same &= padded[dy:dy + h, dx:dx + w] == ids
    return same


def mismatches(boxes: list[Box], camera: Camera, size: tuple[int, int] = SIZE, floor: bool = True) -> tuple[int, np.ndarray]:
    stack = raycast_hits(boxes, camera, size, floor)
    nearest = stack.min(axis=0)
    expected = np.where(np.isfinite(nearest), np.argmin(stack, axis=0), -1)
    got = raster_ids(boxes, camera, size, floor)
    # where two objects' surfaces coincide (equal ray parameters) either may be shown
    t_got = np.take_along_axis(stack, np.maximum(got, 0)[None], axis=0)[0]
    tie = (got >= 0) & (expected >= 0) & (t_got <= nearest * (1.0 + 1e-9) + 1e-9)
    bad = interior(expected) & (got != expected) & ~tie
    return int(bad.sum()), expected


# A cell that once rendered wrong: a 500 x 700 x 780 mm table at x = 480 mm, an LR Mate 200iD base
# (about 160 x 160 mm) standing on it at z = 800 mm, seen from close by.
TABLE = Box((0.48, 0.0, 0.39), (0.5, 0.7, 0.78))
ROBOT_BASE = Box((0.48, 0.0, 0.88), (0.16, 0.16, 0.16))


def cli_camera(text: str, boxes: list[Box]) -> Camera:
    """The camera as `rmot render --camera TEXT` makes it: the text over the default framing."""
    corners = np.concatenate([b.triangles().reshape(-1, 3) for b in boxes])
    bounds = np.stack([corners.min(axis=0), corners.max(axis=0)])
    return parse_camera(text, default=Camera.framing(bounds, points=corners))


CLOSE_VIEW = cli_camera("eye=1.0,-0.9,1.4;center=0.42,0,0.82;fov=70", [TABLE, ROBOT_BASE])


class TestIssueScenes:
    def test_box_near_the_eye_with_the_robot_far_away(self) -> None:
        near_box = Box((1.2 + 0.3, 0.0, 0.45), (0.6, 0.8, 0.9))  # front face 1.2 m in front of the eye
        robot = Box((6.0, 0.5, 0.6), (0.4, 0.4, 1.2))  # the robot 6 m away
        camera = cli_camera("eye=0,0,1;center=6,0,0.6;fov=50", [near_box, robot])
        bad, expected = mismatches([near_box, robot], camera)
        assert (expected == 0).sum() > 500  # the near box fills a good part of the picture
        assert bad == 0

    def test_floor_does_not_show_through_the_table(self) -> None:
        bad, expected = mismatches([TABLE, ROBOT_BASE], CLOSE_VIEW)
        assert (expected == 0).sum() > 600
        assert bad == 0

    def test_svg_draws_no_floor_line_over_the_table(self) -> None:
        """Floor grid lines hidden by the table must not appear in the hidden-line drawing."""
        size = (160, 120)
        xs = np.arange(-2.0, 2.01, 0.25)
        a = np.concatenate([np.stack([xs, np.full_like(xs, -2.0), 0 * xs], 1), np.stack([np.full_like(xs, -2.0), xs, 0 * xs], 1)])
        b = np.concatenate([np.stack([xs, np.full_like(xs, 2.0), 0 * xs], 1), np.stack([np.full_like(xs, 2.0), xs, 0 * xs], 1)])
        boxes = [TABLE, ROBOT_BASE]
        svg = wireframe_svg(np.concatenate([b.triangles() for b in boxes]), CLOSE_VIEW, size,
                            lines=((a, b, "#abc"),), occluders=floor_triangles())
        strokes = re.search(r'id="lines"[^>]*d="([^"]*)"', svg)
        assert strokes is not None  # some floor lines are in view
        ids = raycast_ids(boxes, CLOSE_VIEW, size, floor=False)
        inner = interior(ids) & (ids >= 0)
        inside = interior(inner.astype(int)) & inner  # 2 px away from any box edge
        stray = 0
        for x0, y0, x1, y1 in re.findall(r"M([\d.]+) ([\d.]+)L([\d.]+) ([\d.]+)", strokes.group(1)):
            p0, p1 = np.array([float(x0), float(y0)]), np.array([float(x1), float(y1)])
            for u in np.linspace(0.0, 1.0, 40):
                col, row = (p0 + u * (p1 - p0)).astype(int)
                if 0 <= row < size[1] and 0 <= col < size[0] and inside[row, col]:
                    stray += 1
        assert stray == 0


def _camera_around(target: np.ndarray, distance: float, azimuth: float, elevation: float, fov: float) -> Camera:
    direction = np.array([math.cos(elevation) * math.cos(azimuth), math.cos(elevation) * math.sin(azimuth), math.sin(elevation)])
    eye = target + distance * direction
    return Camera(eye=tuple(eye), center=tuple(target), fov_deg=fov)


box_strategy = st.tuples(
    st.floats(-4.0, 4.0), st.floats(-4.0, 4.0),  # x, y of the centre
    st.floats(0.1, 1.5), st.floats(0.1, 1.5), st.floats(0.1, 2.0),  # sizes
    st.floats(0.0, math.pi),  # yaw
)


@settings(max_examples=25, deadline=None)
@given(boxes=st.lists(box_strategy, min_size=1, max_size=4),
       distance=st.floats(0.6, 14.0), azimuth=st.floats(-math.pi, math.pi), elevation=st.floats(0.05, 1.4),
       fov=st.floats(25.0, 90.0))
def test_random_scenes_match_the_raycast(boxes: list[tuple[float, ...]], distance: float, azimuth: float,
                                         elevation: float, fov: float) -> None:
    solids = [Box((x, y, h / 2.0), (sx, sy, h), yaw) for x, y, sx, sy, h, yaw in boxes]
    target = np.array([boxes[0][0], boxes[0][1], 0.5])
    camera = _camera_around(target, distance, azimuth, elevation, fov)
    eye = np.asarray(camera.eye)
    for b in solids:  # keep the eye out of (and a few centimetres away from) every box
        local = np.abs(b.rot.T @ (eye - b.center)) - b.half
        if np.all(local < 0.1):
            return
    bad, _ = mismatches(solids, camera)
    assert bad == 0


def test_explicit_near_plane_is_kept() -> None:
    """A camera with near/far given keeps them: geometry before the near plane is cut."""
    camera = Camera(eye=(0.0, 0.0, 1.0), center=(5.0, 0.0, 1.0), fov_deg=50.0, near=2.0, far=50.0)
    near_box = Box((1.5, 0.0, 1.0), (0.6, 0.8, 0.9))  # entirely closer than 2 m
    got = raster_ids([near_box], camera, SIZE, floor=False)
    assert (got == 0).sum() == 0
    assert Camera(eye=(0.0, 0.0, 1.0), center=(5.0, 0.0, 1.0)).fitted(near_box.triangles()).near <= 0.05


def test_overlay_line_crossing_the_near_plane_is_cut_not_dropped() -> None:
    """A floor line that starts behind the eye is drawn from where it enters the view, on the
    pixels where the ray-cast sees the floor line (a point of the line projects to its pixel)."""
    from rmot.sim.render.overlay import sample_segments

    camera = Camera(eye=(0.0, 0.0, 1.0), center=(3.0, 0.0, 0.0), fov_deg=60.0).fitted(floor_triangles())
    a, b = np.array([[-2.0, 0.0, 0.0]]), np.array([[6.0, 0.0, 0.0]])  # runs under and behind the eye
    samples = sample_segments(a, b, camera, SIZE)
    on = (samples.xy[:, 0] >= 0) & (samples.xy[:, 0] < SIZE[0]) & (samples.xy[:, 1] >= 0) & (samples.xy[:, 1] < SIZE[1])
    assert on.sum() > 20
    assert np.all((samples.depth[on] >= 0.0) & (samples.depth[on] <= 1.0))
    origin, dirs = pixel_rays(camera, SIZE)
    col, row = samples.xy[on, 0].astype(int), samples.xy[on, 1].astype(int)
    t = floor_hit(origin, dirs)[row, col]
    hit = origin + t[:, None] * dirs[row, col]
    assert np.all(np.abs(hit[:, 1]) < 0.1 * np.maximum(hit[:, 0], 1.0))  # the line y = 0, within a pixel
