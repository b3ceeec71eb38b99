"""Viewing, perspective and viewport transforms over arrays of points (pure numpy).

world (N, 3) --[Camera.matrix]--> clip (N, 4) --[clip.py]--> clip (N, 4)
    --[divide]--> normalised device coordinates (x, y in -1..1, depth 0..1)
    --[viewport]--> screen (pixels: x right, y down, pixel (i, j) centred at (j+0.5, i+0.5)).
"""

from __future__ import annotations

import numpy as np
from numba import njit

__all__ = ["eye_depth", "rotate_vectors", "to_clip", "to_screen", "transform_points"]


def transform_points(matrix: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Apply a (4, 4) rigid transform to points (..., 3); returns (..., 3)."""
    return _affine(points, matrix[:3, :3], matrix[:3, 3])


def rotate_vectors(matrix: np.ndarray, vectors: np.ndarray) -> np.ndarray:
    """Apply the rotation of a (4, 4) rigid transform to direction vectors (..., 3)."""
    return _affine(vectors, matrix[:3, :3], np.zeros(3))


def to_clip(matrix: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Homogeneous clip coordinates (..., 4) of points (..., 3) under a (4, 4) world -> clip matrix."""
    flat = np.ascontiguousarray(points, np.float64).reshape(-1, 3)
    out = np.empty((flat.shape[0], 4))
    _to_clip(flat, np.ascontiguousarray(matrix, np.float64), out)
    return out.reshape(np.shape(points)[:-1] + (4,))


@njit(cache=True)
def _to_clip(points: np.ndarray, m: np.ndarray, out: np.ndarray) -> None:
    for i in range(points.shape[0]):
        x, y, z = points[i, 0], points[i, 1], points[i, 2]
        for r in range(4):
            out[i, r] = m[r, 0] * x + m[r, 1] * y + m[r, 2] * z + m[r, 3]  # M . [x y z 1]


def _affine(points: np.ndarray, linear: np.ndarray, offset: np.ndarray) -> np.ndarray:
    """points (..., 3) -> linear . p + offset (..., R), column by column.

    Written out rather than with `@`: numpy hands (N, 3) x (3, R) products to a threaded
    BLAS, whose thread start-up costs more than this whole product on one core.
    """
    flat = points.reshape(-1, 3)
    out = np.empty((flat.shape[0], linear.shape[0]))
    for r in range(linear.shape[0]):
        out[:, r] = flat[:, 0] * linear[r, 0] + flat[:, 1] * linear[r, 1] + flat[:, 2] * linear[r, 2] + offset[r]
    return out.reshape(points.shape[:-1] + (linear.shape[0],))


def to_screen(clip: np.ndarray, width: int, height: int) -> tuple[np.ndarray, np.ndarray]:
    """Perspective divide and viewport: clip (..., 4) with w > 0 -> screen (..., 3), 1/w (...,).

    screen[..., 0:2] are pixel coordinates (y down), screen[..., 2] the depth in 0..1.
    1/w is kept for perspective-correct interpolation of attributes.
    """
    flat = np.ascontiguousarray(clip, np.float64).reshape(-1, 4)
    screen = np.empty((flat.shape[0], 3))
    inv_w = np.empty(flat.shape[0])
    _to_screen(flat, float(width), float(height), screen, inv_w)
    shape = np.shape(clip)[:-1]
    return screen.reshape(shape + (3,)), inv_w.reshape(shape)


@njit(cache=True)
def _to_screen(clip: np.ndarray, width: float, height: float, screen: np.ndarray, inv_w: np.ndarray) -> None:
    for i in range(clip.shape[0]):
        q = 1.0 / clip[i, 3]
        inv_w[i] = q
        screen[i, 0] = (clip[i, 0] * q + 1.0) * (0.5 * width)  # the divide, then -1..1 -> 0..W
        screen[i, 1] = (1.0 - clip[i, 1] * q) * (0.5 * height)  # +1 (top) -> row 0
        screen[i, 2] = clip[i, 2] * q  # device depth 0..1


def eye_depth(ndc_depth: np.ndarray, near: float, far: float) -> np.ndarray:
    """Distance in front of the eye (m) from the device depth in 0..1 (inverse of Camera.projection)."""
    return far * near / (far - ndc_depth * (far - near))
