"""Illumination: ambient + Lambert diffuse + specular (Blinn–Phong or Phong), two-sided.

    I = ka * C + sum_lights  L_i * (kd * C * max(0, n.l) + ks * max(0, n.h)^shininess)   (Blinn)
                                                    or  ks * max(0, r.v)^shininess     (Phong)

C is the surface colour, n the unit normal turned towards the viewer (thin and open
geometry is lit on the side we see), l the unit direction to the light, v to the eye,
h = (l + v)/|l + v|, r = 2(n.l)n - l. Colours are floats in 0..1 (clipped at 1).

Where it is evaluated decides the look: once per face (flat), once per vertex and
interpolated (Gouraud), or per pixel on interpolated normals (Phong shading).
"""

from __future__ import annotations

from enum import Enum

import numpy as np
from numba import njit

from rmot.lang.record import record

__all__ = ["DEFAULT_LIGHTS", "Light", "Material", "Shading", "shade"]


class Shading(Enum):
    FLAT = "flat"
    GOURAUD = "gouraud"
    PHONG = "phong"


@record(slots=True)
class Light:
    """A directional light: `direction` points from the scene towards the light (world frame)."""

    direction: tuple[float, float, float]
    intensity: float = 1.0


@record(slots=True)
class Material:
    ambient: float = 0.28
    diffuse: float = 0.72
    specular: float = 0.22
    shininess: float = 24.0
    blinn: bool = True  # Blinn's half vector; False uses Phong's reflected ray


DEFAULT_LIGHTS: tuple[Light, ...] = (
    Light((0.35, -0.55, 0.76), 0.85),  # key light: above, on the default camera's side
    Light((-0.6, 0.5, 0.3), 0.3),  # fill from the other side so the shadowed sides are not black
)


def shade(normals: np.ndarray, positions: np.ndarray, colors: np.ndarray, eye: np.ndarray,
          lights: tuple[Light, ...] = DEFAULT_LIGHTS, material: Material = Material()) -> np.ndarray:
    """Lit colours (N, 3) float32 in 0..1 of surface points (N, 3) with normals (N, 3) and colours (N, 3)."""
    directions = np.array([light.direction for light in lights], np.float64).reshape(-1, 3)
    directions /= np.maximum(np.linalg.norm(directions, axis=1, keepdims=True), 1e-300)
    intensities = np.array([light.intensity for light in lights], np.float64)
    out = np.empty((np.asarray(normals).reshape(-1, 3).shape[0], 3), np.float32)
    _shade(np.ascontiguousarray(normals, np.float32).reshape(-1, 3), np.ascontiguousarray(positions, np.float64).reshape(-1, 3),
           np.ascontiguousarray(colors, np.float32).reshape(-1, 3), np.asarray(eye, np.float64), directions, intensities,
           material.ambient, material.diffuse, material.specular, material.shininess, material.blinn, out)
    return out


@njit(cache=True)
def _shade(normals: np.ndarray, positions: np.ndarray, colors: np.ndarray, eye: np.ndarray, directions: np.ndarray,
           intensities: np.ndarray, ka: float, kd: float, ks: float, shininess: float, blinn: bool, out: np.ndarray) -> None:
    """The illumination formula of the module docstring, one point at a time (compiled: no temporaries)."""
    # below this cosine the highlight adds less than 1/1024: skip the pow() (a third of the cost)
    faint = (1.0 / 1024.0) ** (1.0 / shininess)
    for i in range(normals.shape[0]):
        nx, ny, nz = normals[i, 0], normals[i, 1], normals[i, 2]
        length = np.sqrt(nx * nx + ny * ny + nz * nz)
        if length > 0.0:
            nx, ny, nz = nx / length, ny / length, nz / length
        vx, vy, vz = eye[0] - positions[i, 0], eye[1] - positions[i, 1], eye[2] - positions[i, 2]
        length = np.sqrt(vx * vx + vy * vy + vz * vz)
        if length > 0.0:
            vx, vy, vz = vx / length, vy / length, vz / length
        if nx * vx + ny * vy + nz * vz < 0.0:  # two-sided: light the side the eye sees
            nx, ny, nz = -nx, -ny, -nz
        diffuse = 0.0
        specular = 0.0
        for k in range(directions.shape[0]):
            lx, ly, lz = directions[k, 0], directions[k, 1], directions[k, 2]
            n_dot_l = nx * lx + ny * ly + nz * lz
            if n_dot_l <= 0.0:
                continue  # the light is behind the surface: no diffuse, no highlight
            diffuse += intensities[k] * n_dot_l  # Lambert's cosine law
            if ks > 0.0:
                if blinn:  # n.h with h the half vector between light and eye
                    hx, hy, hz = lx + vx, ly + vy, lz + vz
                    hl = np.sqrt(hx * hx + hy * hy + hz * hz)
                    c = (nx * hx + ny * hy + nz * hz) / hl if hl > 0.0 else 0.0
                else:  # r.v with r the light mirrored about n
                    c = (2.0 * n_dot_l * nx - lx) * vx + (2.0 * n_dot_l * ny - ly) * vy + (2.0 * n_dot_l * nz - lz) * vz
                if c > faint:
                    specular += intensities[k] * c ** shininess
        scale = ka + kd * diffuse
        for j in range(3):
            value = colors[i, j] * scale + ks * specular
            out[i, j] = min(max(value, 0.0), 1.0)
