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

from dataclasses import dataclass
from enum import Enum

import numpy as np

__all__ = ["DEFAULT_LIGHTS", "Light", "Material", "Shading", "shade"]


class Shading(Enum):
    FLAT = "flat"
    GOURAUD = "gouraud"
    PHONG = "phong"


@dataclass(frozen=True, slots=True)
class Light:
    """A directional light: `direction` points from the scene towards the light (world frame)."""

    direction: tuple[float, float, float]
    intensity: float = 1.0


@dataclass(frozen=True, slots=True)
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


def _unit(v: np.ndarray) -> np.ndarray:
    """Rows of v (N, 3) scaled to unit length (zero rows stay zero)."""
    length = np.sqrt(np.einsum("ij,ij->i", v, v))
    length[length == 0.0] = 1.0
    return v / length[:, None]


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.einsum("ij,ij->i", a, b)


def shade(normals: np.ndarray, positions: np.ndarray, colors: np.ndarray, eye: np.ndarray,
          lights: tuple[Light, ...] = DEFAULT_LIGHTS, material: Material = Material()) -> np.ndarray:
    """Lit colours (N, 3) in 0..1 of surface points (N, 3) with normals (N, 3) and colours (N, 3)."""
    n = _unit(np.asarray(normals, np.float32).reshape(-1, 3))
    v = _unit(np.asarray(eye, np.float32) - np.asarray(positions, np.float32).reshape(-1, 3))
    n *= np.sign(_dot(n, v) + np.float32(1e-30))[:, None]  # two-sided: the side the eye sees
    diffuse = np.zeros(len(n), np.float32)
    specular = np.zeros(len(n), np.float32)
    for light in lights:
        l = np.asarray(light.direction, np.float32)
        l = l / np.linalg.norm(l)
        n_dot_l = n @ l
        diffuse += light.intensity * np.maximum(n_dot_l, 0.0)  # Lambert's cosine law
        if material.specular > 0.0:
            if material.blinn:
                cos_spec = _dot(n, _unit(v + l))  # n.h, h the half vector
            else:
                cos_spec = _dot(2.0 * n_dot_l[:, None] * n - l, v)  # r.v, r the mirrored light
            cos_spec[n_dot_l <= 0.0] = 0.0  # no highlight on the unlit side
            specular += light.intensity * np.maximum(cos_spec, 0.0) ** np.float32(material.shininess)
    out = np.asarray(colors, np.float32).reshape(-1, 3) * (material.ambient + material.diffuse * diffuse)[:, None]
    out += material.specular * specular[:, None]
    return np.clip(out, 0.0, 1.0, out=out)
