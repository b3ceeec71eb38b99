"""The display pipeline over plain triangle arrays: transform, clip, raster, shade, supersample.

    world triangles (T, 3, 3) --Camera.matrix--> clip (T, 3, 4) --clip_triangles-->
    --to_screen--> screen (T', 3, 3) --rasterize--> visibility buffer --resolve + shade-->
    colour (kH, kW, 3) --box filter k x k--> (H, W, 3) uint8

Each step is a pure function; this module only wires them together.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rmot.sim.render.camera import Camera
from rmot.sim.render.clip import clip_triangles
from rmot.sim.render.raster import Frame, rasterize, resolve, resolve_downsampled
from rmot.sim.render.shade import DEFAULT_LIGHTS, Light, Material, Shading, shade
from rmot.sim.render.transform import to_clip, to_screen

__all__ = ["BACKGROUND", "Picture", "depth_frame", "downsample", "draw", "face_normals", "render_triangles", "to_uint8"]

BACKGROUND = (0.92, 0.93, 0.95)


@dataclass(frozen=True, eq=False)
class Picture:
    """A rendered image at the supersampled resolution, with what the rasteriser saw.

    color (kH, kW, 3) float32 0..1; frame the visibility buffer, its triangle ids indexing
    `source` (T',) -> the input triangle each clipped triangle came from; `matrix` the
    (4, 4) world -> clip matrix used; `scale` = k; `camera` the camera fitted to the
    triangles (Camera.fitted), whose planes overlays must use to compare depths.
    """

    color: np.ndarray
    frame: Frame
    source: np.ndarray
    matrix: np.ndarray
    scale: int
    camera: Camera | None = None  # the camera with the near/far planes this picture used


def face_normals(vertices: np.ndarray) -> np.ndarray:
    """Unit normals (T, 3) of triangles (T, 3, 3) by the right-hand rule (0 for degenerate ones)."""
    n = np.cross(vertices[:, 1] - vertices[:, 0], vertices[:, 2] - vertices[:, 0])
    length = np.linalg.norm(n, axis=1, keepdims=True)
    return n / np.where(length > 0.0, length, 1.0)


def _per_vertex(colors: np.ndarray, n_tri: int) -> np.ndarray:
    colors = np.asarray(colors, np.float32)
    if colors.shape == (n_tri, 3):
        return np.repeat(colors[:, None, :], 3, axis=1)
    if colors.shape == (n_tri, 3, 3):
        return colors
    raise ValueError(f"colors must have shape (T, 3) or (T, 3, 3) with T={n_tri} (got {colors.shape})")


def _vertex_attributes(vertices: np.ndarray, normals: np.ndarray, colors: np.ndarray, eye: np.ndarray,
                       lights: tuple[Light, ...], material: Material, shading: Shading) -> np.ndarray:
    """What gets interpolated across each triangle (T, 3, A): a lit colour, or n|C|p for Phong."""
    n_tri = len(vertices)
    if shading is Shading.PHONG:
        return np.concatenate([normals, colors, vertices], axis=2).astype(np.float32)
    if shading is Shading.FLAT:
        lit = shade(face_normals(vertices), vertices.mean(axis=1), colors.mean(axis=1), eye, lights, material)
        return np.repeat(lit[:, None, :], 3, axis=1)
    rows = (n_tri * 3, 3)  # Gouraud: light each vertex of each triangle
    lit = shade(normals.reshape(rows), vertices.reshape(rows), colors.reshape(rows), eye, lights, material)
    return lit.reshape(n_tri, 3, 3)


def draw(vertices: np.ndarray, normals: np.ndarray | None, colors: np.ndarray, camera: Camera,
         size: tuple[int, int] = (640, 480), aa: int = 1, *, lights: tuple[Light, ...] = DEFAULT_LIGHTS,
         material: Material = Material(), shading: Shading = Shading.GOURAUD,
         background: tuple[float, float, float] = BACKGROUND) -> Picture:
    """Render triangles (T, 3, 3) m with vertex normals (T, 3, 3) (None: face normals) and
    colours (T, 3) or (T, 3, 3) in 0..1 at k = aa times `size` (W, H) pixels."""
    vertices = np.asarray(vertices, np.float64).reshape(-1, 3, 3)
    n_tri = len(vertices)
    if normals is None:
        normals = np.repeat(face_normals(vertices)[:, None, :], 3, axis=1)
    colors = _per_vertex(colors, n_tri)
    width, height = size[0] * aa, size[1] * aa
    camera = camera.fitted(vertices)
    matrix = camera.matrix(size[0] / size[1])
    eye = np.asarray(camera.eye, np.float64)
    attrs = _vertex_attributes(vertices, np.asarray(normals, np.float32), colors, eye, lights, material, shading)
    clipped, attrs, source = clip_triangles(to_clip(matrix, vertices), attrs)
    screen, inv_w = to_screen(clipped, width, height)
    frame = rasterize(screen, inv_w, width, height)
    if shading is not Shading.PHONG:
        return Picture(resolve(frame, attrs, background), frame, source, matrix, aa, camera)
    values = resolve(frame, attrs)  # per-pixel lighting on the interpolated normal
    covered = frame.covered
    image = np.empty((height, width, 3), np.float32)
    image[...] = np.asarray(background, np.float32)
    px = values[covered]
    image[covered] = shade(px[:, 0:3], px[:, 6:9], px[:, 3:6], eye, lights, material)
    return Picture(image, frame, source, matrix, aa, camera)


def downsample(image: np.ndarray, k: int) -> np.ndarray:
    """Box filter: the mean of each k x k block of (kH, kW, C) -> (H, W, C)."""
    if k == 1:
        return image
    total = np.zeros((image.shape[0] // k, image.shape[1] // k) + image.shape[2:], np.float32)
    for dy in range(k):  # sum the k*k sub-sample grids (strided views, no copies)
        for dx in range(k):
            total += image[dy::k, dx::k]
    return total * np.float32(1.0 / (k * k))


def to_uint8(image: np.ndarray) -> np.ndarray:
    """0..1 floats -> 0..255 bytes, rounded to nearest."""
    return np.clip(np.rint(image * 255.0), 0, 255).astype(np.uint8)


def render_triangles(vertices: np.ndarray, normals: np.ndarray | None, colors: np.ndarray, camera: Camera,
                     size: tuple[int, int] = (640, 480), aa: int = 1, lights: tuple[Light, ...] = DEFAULT_LIGHTS,
                     *, material: Material = Material(), shading: Shading = Shading.GOURAUD,
                     background: tuple[float, float, float] = BACKGROUND) -> np.ndarray:
    """The whole pipeline on a triangle soup -> (H, W, 3) uint8 (see `draw` for the arguments).

    With vertex or face lighting the interpolation and the k x k box filter run as one
    pass over the visibility buffer; per-pixel (Phong) lighting goes through `draw`.
    """
    if shading is Shading.PHONG:
        picture = draw(vertices, normals, colors, camera, size, aa, lights=lights, material=material,
                       shading=shading, background=background)
        return to_uint8(downsample(picture.color, aa))
    vertices = np.asarray(vertices, np.float64).reshape(-1, 3, 3)
    if normals is None:
        normals = np.repeat(face_normals(vertices)[:, None, :], 3, axis=1)
    colors = _per_vertex(colors, len(vertices))
    width, height = size[0] * aa, size[1] * aa
    camera = camera.fitted(vertices)
    matrix = camera.matrix(size[0] / size[1])
    lit = _vertex_attributes(vertices, np.asarray(normals, np.float32), colors, np.asarray(camera.eye, np.float64),
                             lights, material, shading)
    clipped, lit, _ = clip_triangles(to_clip(matrix, vertices), lit)
    screen, inv_w = to_screen(clipped, width, height)
    frame = rasterize(screen, inv_w, width, height)
    return resolve_downsampled(frame, lit, aa, background)


def depth_frame(vertices: np.ndarray, camera: Camera, size: tuple[int, int]) -> tuple[Frame, np.ndarray]:
    """Only the visibility buffer of triangles (T, 3, 3) at size (W, H), and the source index (T',).

    A camera without near/far planes is fitted to the triangles; pass an already fitted one
    (Camera.fitted) to compare overlay depths with the same planes.
    """
    vertices = np.asarray(vertices, np.float64).reshape(-1, 3, 3)
    camera = camera.fitted(vertices)
    matrix = camera.matrix(size[0] / size[1])
    clipped, _, source = clip_triangles(to_clip(matrix, vertices), np.zeros((len(vertices), 3, 0), np.float32))
    screen, inv_w = to_screen(clipped, size[0], size[1])
    return rasterize(screen, inv_w, size[0], size[1]), source
