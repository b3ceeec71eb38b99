"""Lines drawn over a rendered picture, tested against its z-buffer.

Shared by the TCP-path overlay and the hidden-line SVG: a 3D segment is projected, sampled
every half pixel in screen space (device depth is affine along a projected line, so the
samples' depths interpolate linearly), and each sample is visible when it is no deeper
than the nearest surface at its pixel, within a tolerance in metres along the view ray.
"""

from __future__ import annotations

import numpy as np

from rmot.sim.render.camera import Camera
from rmot.sim.render.raster import Frame
from rmot.sim.render.transform import eye_depth, to_clip, to_screen

__all__ = ["Samples", "sample_segments", "stamp", "visible"]


class Samples:
    """Points along projected segments: xy (M, 2) px, depth (M,) 0..1, segment (M,) int, u (M,) 0..1."""

    def __init__(self, xy: np.ndarray, depth: np.ndarray, segment: np.ndarray, u: np.ndarray) -> None:
        self.xy, self.depth, self.segment, self.u = xy, depth, segment, u


def sample_segments(a: np.ndarray, b: np.ndarray, camera: Camera, size: tuple[int, int], step: float = 0.5) -> Samples:
    """Sample world segments a -> b (S, 3) on screen (size = (W, H) px) every `step` pixels.

    A segment crossing the near plane is cut where it crosses it (in clip space, where the
    cut is linear); a segment wholly in front of it is left out. `u` runs over the kept part.
    """
    width, height = size
    matrix = camera.matrix(width / height)
    ca, cb = to_clip(matrix, np.asarray(a, float)), to_clip(matrix, np.asarray(b, float))
    za, zb = ca[:, 2], cb[:, 2]  # z_clip >= 0: beyond the near plane
    front = (za >= 0.0) | (zb >= 0.0)
    ca, cb, za, zb, index = ca[front], cb[front], za[front], zb[front], np.flatnonzero(front)
    s = np.where(za < 0.0, za / np.where(za - zb == 0.0, 1.0, za - zb), 0.0)  # cut a behind the plane
    ca = np.where((za < 0.0)[:, None], ca + s[:, None] * (cb - ca), ca)
    s = np.where(zb < 0.0, zb / np.where(zb - za == 0.0, 1.0, zb - za), 0.0)
    cb = np.where((zb < 0.0)[:, None], cb + s[:, None] * (ca - cb), cb)
    sa, _ = to_screen(ca, width, height)
    sb, _ = to_screen(cb, width, height)
    length = np.linalg.norm(sb[:, :2] - sa[:, :2], axis=1)
    counts = np.maximum(np.ceil(np.minimum(length, 4.0 * (width + height)) / step).astype(int), 1) + 1
    seg = np.repeat(np.arange(len(sa)), counts)
    start = np.repeat(np.cumsum(counts) - counts, counts)
    u = (np.arange(counts.sum()) - start) / np.repeat(counts - 1, counts).clip(1)
    pts = sa[seg] + u[:, None] * (sb[seg] - sa[seg])  # device depth is affine along the line
    return Samples(pts[:, :2], pts[:, 2], index[seg], u)


def visible(frame: Frame, samples: Samples, camera: Camera, *, tolerance: float = 0.004,
            relative: float = 0.003, neighbourhood: int = 0) -> np.ndarray:
    """(M,) True where a sample lies on screen and in front of (or on) the nearest surface.

    neighbourhood r > 0 compares against the deepest surface within r pixels, so an edge
    lying exactly on a silhouette is not hidden by the surface it bounds.
    """
    height, width = frame.depth.shape
    col = np.floor(samples.xy[:, 0]).astype(int)
    row = np.floor(samples.xy[:, 1]).astype(int)
    on = (col >= 0) & (col < width) & (row >= 0) & (row < height)
    depth = frame.depth
    if neighbourhood > 0:
        depth = _max_filter(depth, neighbourhood)
    surface = np.full(len(col), np.inf, np.float64)
    surface[on] = depth[row[on], col[on]]
    finite = np.isfinite(surface)
    d_surface = np.full(len(col), np.inf)
    near, far = camera.depth_range()
    d_surface[finite] = eye_depth(surface[finite], near, far)
    d_sample = eye_depth(samples.depth, near, far)
    return on & (d_sample <= d_surface * (1.0 + relative) + tolerance)


def _max_filter(depth: np.ndarray, r: int) -> np.ndarray:
    """The largest depth within r pixels (empty pixels count as infinitely deep)."""
    padded = np.pad(depth, r, mode="edge")
    out = depth.copy()
    h, w = depth.shape
    for dy in range(2 * r + 1):
        for dx in range(2 * r + 1):
            np.maximum(out, padded[dy:dy + h, dx:dx + w], out=out)
    return out


def stamp(image: np.ndarray, xy: np.ndarray, color: tuple[float, float, float], radius: int, alpha: float = 1.0) -> None:
    """Paint square dots of half-width `radius` px at points xy (M, 2) into image (H, W, 3) in place."""
    height, width = image.shape[:2]
    col, row = np.floor(xy[:, 0]).astype(int), np.floor(xy[:, 1]).astype(int)
    rgb = np.asarray(color, np.float32)
    mask = np.zeros((height, width), bool)
    for dy in range(-radius, radius + 1):
        for dx in range(-radius, radius + 1):
            r, c = row + dy, col + dx
            ok = (r >= 0) & (r < height) & (c >= 0) & (c < width)
            mask[r[ok], c[ok]] = True
    image[mask] = (1.0 - alpha) * image[mask] + alpha * rgb
