"""Tiny scenes with known answers: z-order, clipping, coverage, perspective-correct interpolation."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rmot.sim.render.camera import Camera
from rmot.sim.render.pipeline import draw, render_triangles
from rmot.sim.render.raster import rasterize, resolve
from rmot.sim.render.shade import Material, Shading

W, H = 96, 72
UNLIT = Material(ambient=1.0, diffuse=0.0, specular=0.0)  # a pixel shows its surface colour exactly
TOP_DOWN = Camera(eye=(0.0, 0.0, 5.0), center=(0.0, 0.0, 0.0), up=(0.0, 1.0, 0.0), fov_deg=40.0, near=0.5, far=20.0)


def square(x0: float, x1: float, y0: float, y1: float, z: float) -> np.ndarray:
    a, b, c, d = (x0, y0, z), (x1, y0, z), (x1, y1, z), (x0, y1, z)
    return np.array([[a, b, c], [a, c, d]], float)


def pixel_rays(camera: Camera, size: tuple[int, int]) -> tuple[np.ndarray, np.ndarray]:
    """World-space ray origin (3,) and unit directions (H, W, 3) through every pixel centre."""
    width, height = size
    view = camera.view()
    tan = np.tan(np.radians(camera.fov_deg) / 2)
    cols, rows = np.meshgrid(np.arange(width) + 0.5, np.arange(height) + 0.5)
    x_ndc, y_ndc = 2 * cols / width - 1, 1 - 2 * rows / height
    d_eye = np.stack([x_ndc * tan * width / height, y_ndc * tan, -np.ones_like(x_ndc)], axis=2)
    d_world = d_eye @ view[:3, :3]  # the eye axes are the rows of the view rotation
    return np.asarray(camera.eye, float), d_world / np.linalg.norm(d_world, axis=2, keepdims=True)


def hits(origin: np.ndarray, dirs: np.ndarray, tri: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Möller–Trumbore for every ray: (t (H, W), min barycentric (H, W), hit point (H, W, 3))."""
    e1, e2 = tri[1] - tri[0], tri[2] - tri[0]
    p = np.cross(dirs, e2)
    det = p @ e1
    s = origin - tri[0]
    u = (p @ s) / det
    q = np.cross(s, e1)
    v = (dirs @ q) / det
    t = (q @ e2) / det
    margin = np.minimum(np.minimum(u, v), 1 - u - v)
    return t, margin, origin + t[..., None] * dirs


class TestDepthOrder:
    def _owner(self, order: tuple[int, int]) -> np.ndarray:
        far_sq, near_sq = square(-1.0, 0.5, -1.0, 0.5, 0.0), square(-0.5, 1.0, -0.5, 1.0, 0.5)
        tris = [far_sq, near_sq]
        verts = np.concatenate([tris[i] for i in order])
        colors = np.concatenate([np.full((2, 3), (1.0, 0.0, 0.0) if i == 0 else (0.0, 1.0, 0.0)) for i in order])
        picture = draw(verts, None, colors, TOP_DOWN, (W, H), material=UNLIT, shading=Shading.FLAT)
        img = picture.color
        return np.where(img[..., 0] > 0.99, 0, np.where(img[..., 1] > 0.99, 1, -1))

    def test_nearer_square_wins_exactly_on_the_overlap_whatever_the_order(self) -> None:
        """Pixel by pixel: the overlap shows the nearer square, each square alone shows itself, in both draw orders."""
        origin, dirs = pixel_rays(TOP_DOWN, (W, H))
        expected = np.full((H, W), -1)
        for index, (sq, z) in enumerate((((-1.0, 0.5, -1.0, 0.5), 0.0), ((-0.5, 1.0, -0.5, 1.0), 0.5))):
            x0, x1, y0, y1 = sq
            t = (z - origin[2]) / dirs[..., 2]
            x, y = origin[0] + t * dirs[..., 0], origin[1] + t * dirs[..., 1]
            expected[(x > x0) & (x < x1) & (y > y0) & (y < y1)] = index  # the later (nearer) square overwrites
        for order in ((0, 1), (1, 0)):
            owner = self._owner(order)
            np.testing.assert_array_equal(owner, expected)
        assert (expected == 1).sum() > 300 and (expected == 0).sum() > 300  # both visible: the test has teeth


class TestClippingInRaster:
    def test_triangle_through_the_near_plane_covers_exactly_its_visible_part(self) -> None:
        """A triangle with a vertex behind the eye is clipped: covered pixels are those whose ray meets it beyond near."""
        camera = Camera(eye=(0.0, 0.0, 0.0), center=(0.0, 0.0, -1.0), up=(0.0, 1.0, 0.0), fov_deg=60.0, near=0.5, far=50.0)
        tri = np.array([[-3.0, -1.0, -6.0], [2.0, -1.5, -4.0], [0.3, 0.8, 2.0]])  # third vertex behind the eye
        picture = draw(tri[None], None, np.ones((1, 3)), camera, (W, H), material=UNLIT, shading=Shading.FLAT)
        covered = picture.frame.covered
        origin, dirs = pixel_rays(camera, (W, H))
        t, margin, point = hits(origin, dirs, tri)
        depth = -point[..., 2]  # distance in front of the eye along -z
        expected = (margin > 0) & (t > 0) & (depth >= camera.near)
        clear = (np.abs(margin) > 1e-3) & (np.abs(depth - camera.near) > 1e-3)  # away from edges and the near plane
        np.testing.assert_array_equal(covered[clear], expected[clear])
        assert expected.sum() > 200 and (~expected).sum() > 200

    @pytest.mark.parametrize("tri", [
        [[0.0, 0.0, 1.0], [1.0, 0.0, 2.0], [0.0, 1.0, 3.0]],  # behind the eye
        [[30.0, 0.0, -5.0], [31.0, 0.0, -5.0], [30.0, 1.0, -5.0]],  # far to the right
        [[0.0, 0.0, -90.0], [1.0, 0.0, -90.0], [0.0, 1.0, -90.0]],  # beyond the far plane
    ], ids=["behind", "right", "beyond-far"])
    def test_triangle_entirely_outside_draws_nothing(self, tri: list[list[float]]) -> None:
        """Outside the view volume: no pixel covered, the image is pure background."""
        camera = Camera(eye=(0.0, 0.0, 0.0), center=(0.0, 0.0, -1.0), up=(0.0, 1.0, 0.0), near=0.5, far=50.0)
        bg = (0.2, 0.4, 0.6)
        picture = draw(np.array([tri]), None, np.ones((1, 3)), camera, (W, H), background=bg)
        assert not picture.frame.covered.any()
        np.testing.assert_array_equal(picture.color, np.broadcast_to(np.float32(bg), (H, W, 3)))


class TestPerspectiveCorrectInterpolation:
    def test_interpolated_world_position_lies_on_each_pixel_ray(self) -> None:
        """Barycentrics are perspective-correct: the interpolated 3D point is where the pixel's ray meets the triangle."""
        camera = Camera(eye=(0.3, -4.0, 2.0), center=(0.0, 0.0, 0.0), fov_deg=50.0)
        tri = np.array([[-2.0, -1.0, 0.0], [2.5, 0.5, -0.5], [-0.5, 3.0, 1.5]])  # strongly slanted
        picture = draw(tri[None], None, np.ones((1, 3)), camera, (W, H))
        position = resolve(picture.frame, tri[None].astype(np.float32))
        origin, dirs = pixel_rays(camera, (W, H))
        _, _, point = hits(origin, dirs, tri)
        covered = picture.frame.covered
        assert covered.sum() > 1000
        err = np.linalg.norm(position[covered] - point[covered], axis=1)
        assert err.max() < 2e-5 * 10  # float32 interpolation of metre-scale coordinates


class TestSupersampling:
    def test_edge_pixels_take_intermediate_values_and_interior_pixels_do_not(self) -> None:
        """4x4 supersampling: pixels cut by the square's edge blend the two colours; the rest stay pure."""
        fg, bg = np.array([1.0, 1.0, 1.0]), (0.0, 0.0, 0.0)
        sq = square(-0.83, 0.91, -0.67, 0.74, 0.0)
        img = render_triangles(sq, None, np.tile(fg, (2, 1)), TOP_DOWN, (W, H), aa=4, material=UNLIT,
                               shading=Shading.FLAT, background=bg)[..., 0].astype(int)
        origin, dirs = pixel_rays(TOP_DOWN, (W, H))
        t = -origin[2] / dirs[..., 2]
        x, y = origin[0] + t * dirs[..., 0], origin[1] + t * dirs[..., 1]
        px = 2 * t * np.tan(np.radians(20)) / H  # metres per pixel on the plane
        inside = np.minimum.reduce([x + 0.83, 0.91 - x, y + 0.67, 0.74 - y])  # signed distance to the border
        assert np.all(img[inside > px] == 255)
        assert np.all(img[inside < -px] == 0)
        edge = np.abs(inside) < 0.3 * px  # the border runs right through these pixels
        assert edge.sum() > 50
        assert np.all((img[edge] > 0) & (img[edge] < 255))


def _cross2(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """z of the cross product of 2D vectors (..., 2)."""
    return u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]


class TestSeams:
    @settings(max_examples=40, deadline=None)
    @given(st.integers(0, 2**32 - 1), st.integers(3, 9))
    def test_a_fan_covers_each_pixel_of_its_polygon_exactly_once(self, seed: int, sides: int) -> None:
        """Triangles sharing edges: no pixel drawn twice, none missed, even with centres exactly on the seams."""
        rng = np.random.default_rng(seed)
        size = 48
        centre = np.array([24.5, 24.5])  # on a pixel centre: seams pass through centres exactly
        angles = (np.arange(sides) + rng.uniform(-0.15, 0.15, sides)) * 2 * np.pi / sides  # gaps < 180 deg
        radius = rng.integers(8, 20, sides)
        ring = np.round(centre + radius[:, None] * np.stack([np.cos(angles), np.sin(angles)], 1) - 0.5) + 0.5
        owners = np.zeros((size, size), int)
        for i in range(sides):
            tri = np.array([[*centre, 0.5], [*ring[i], 0.5], [*ring[(i + 1) % sides], 0.5]])
            owners += rasterize(tri[None], np.ones((1, 3)), size, size).covered
        assert owners.max() <= 1
        # every centre strictly inside one of the fan's triangles (not on its outer edge) is covered
        cols, rows = np.meshgrid(np.arange(size) + 0.5, np.arange(size) + 0.5)
        p = np.stack([cols, rows], 2)
        for i in range(sides):
            a, b, c = centre, ring[i], ring[(i + 1) % sides]
            e = [_cross2(q - o, p - o) for o, q in ((a, b), (b, c), (c, a))]
            sign = np.sign(_cross2(b - a, c - a))
            if sign == 0:
                continue
            strictly = (sign * e[0] > 0) & (sign * e[1] > 0) & (sign * e[2] > 0)
            assert np.all(owners[strictly] == 1)
