"""Viewing, perspective and viewport transforms over arrays of points (pure numpy).

world (N, 3) --[Camera.matrix]--> clip (N, 4) --[clip.py]--> clip (N, 4)
    --[divide]--> normalised device coordinates (x, y in -1..1, depth 0..1)
    --[viewport]--> screen (pixels: x right, y down, pixel (i, j) centred at (j+0.5, i+0.5)).
"""

from __future__ import annotations

import numpy as np

__all__ = ["to_clip", "to_screen", "transform_points", "eye_depth"]


def transform_points(matrix: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Apply a (4, 4) rigid transform to points (..., 3); returns (..., 3)."""
    flat = points.reshape(-1, 3)
    return (flat @ matrix[:3, :3].T + matrix[:3, 3]).reshape(points.shape)


def to_clip(matrix: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Homogeneous clip coordinates (..., 4) of points (..., 3) under a (4, 4) world -> clip matrix."""
    flat = points.reshape(-1, 3)
    out = flat @ matrix[:, :3].T + matrix[:, 3]  # [x y z 1] . M^T without building the 1s
    return out.reshape(points.shape[:-1] + (4,))


def to_screen(clip: np.ndarray, width: int, height: int) -> tuple[np.ndarray, np.ndarray]:
    """Perspective divide and viewport: clip (..., 4) with w > 0 -> screen (..., 3), 1/w (...,).

    screen[..., 0:2] are pixel coordinates (y down), screen[..., 2] the depth in 0..1.
    1/w is kept for perspective-correct interpolation of attributes.
    """
    inv_w = 1.0 / clip[..., 3]
    ndc = clip[..., :3] * inv_w[..., None]  # the divide: device-independent coordinates
    screen = np.empty_like(ndc)
    screen[..., 0] = (ndc[..., 0] + 1.0) * (0.5 * width)  # -1..1 -> 0..W
    screen[..., 1] = (1.0 - ndc[..., 1]) * (0.5 * height)  # +1 (top) -> row 0
    screen[..., 2] = ndc[..., 2]
    return screen, inv_w


def eye_depth(ndc_depth: np.ndarray, near: float, far: float) -> np.ndarray:
    """Distance in front of the eye (m) from the device depth in 0..1 (inverse of Camera.projection)."""
    return far * near / (far - ndc_depth * (far - near))
