"""Clipping triangles against the six planes of the view volume, in homogeneous coordinates.

Sutherland–Hodgman, before the perspective divide: a point (x, y, z, w) is inside when
-w <= x <= w, -w <= y <= w and 0 <= z <= w. Each plane keeps the polygon's inside
vertices and adds a new vertex where an edge crosses it, interpolating the vertex
attributes linearly in clip space (which stays perspective-correct after the divide).
Triangles wholly inside pass through untouched and triangles wholly outside one plane are
dropped, both vectorised; only the few that straddle a plane go through the compiled loop.
"""

from __future__ import annotations

import numpy as np
from numba import njit

__all__ = ["clip_triangles", "plane_distances"]

_MAX_POLY = 9  # a triangle gains at most one vertex per plane: 3 + 6
_MAX_OUT = _MAX_POLY - 2  # fan triangles per clipped polygon


def plane_distances(clip: np.ndarray) -> np.ndarray:
    """Signed distances (..., 6) of clip points (..., 4) to the six planes; >= 0 is inside."""
    x, y, z, w = clip[..., 0], clip[..., 1], clip[..., 2], clip[..., 3]
    return np.stack([w + x, w - x, w + y, w - y, z, w - z], axis=-1)


def clip_triangles(clip: np.ndarray, attrs: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Clip triangles to the view volume.

    clip: (T, 3, 4) homogeneous vertices; attrs: (T, 3, A) per-vertex attributes.
    Returns (clip' (T', 3, 4), attrs' (T', 3, A), source (T',) int index of the input triangle).
    """
    status = _classify(np.ascontiguousarray(clip, np.float64))
    straddle = np.flatnonzero(status == _STRADDLE)
    keep = np.flatnonzero(status == _INSIDE)
    if straddle.size == 0:
        if keep.size == len(clip):
            return clip, attrs, keep  # the usual case: everything in view, nothing to copy
        return clip[keep], attrs[keep], keep
    packed = np.concatenate([clip[straddle], attrs[straddle]], axis=2).astype(np.float64)
    out, src, count = _clip_polygons(np.ascontiguousarray(packed))
    out, src = out[:count], straddle[src[:count]]
    return (
        np.concatenate([clip[keep], out[:, :, :4].astype(clip.dtype)]),
        np.concatenate([attrs[keep], out[:, :, 4:].astype(attrs.dtype)]),
        np.concatenate([keep, src]),
    )


_INSIDE, _STRADDLE, _OUTSIDE = 0, 1, 2


@njit(cache=True)
def _classify(clip: np.ndarray) -> np.ndarray:
    """Per triangle (T, 3, 4): inside all planes, straddling one, or wholly outside one."""
    status = np.empty(clip.shape[0], np.int8)
    for t in range(clip.shape[0]):
        all_in = True
        out = False
        for plane in range(6):
            n_out = 0
            for i in range(3):
                if _distance(clip[t, i], plane) < 0.0:
                    n_out += 1
            all_in = all_in and n_out == 0
            out = out or n_out == 3
        status[t] = _INSIDE if all_in else (_OUTSIDE if out else _STRADDLE)
    return status


@njit(cache=True)
def _distance(v: np.ndarray, plane: int) -> float:
    """Signed distance of one packed vertex to plane 0..5 (same order as plane_distances)."""
    x, y, z, w = v[0], v[1], v[2], v[3]
    if plane == 0:
        return w + x
    if plane == 1:
        return w - x
    if plane == 2:
        return w + y
    if plane == 3:
        return w - y
    if plane == 4:
        return z
    return w - z


@njit(cache=True)
def _clip_polygons(tris: np.ndarray) -> tuple[np.ndarray, np.ndarray, int]:
    """Sutherland–Hodgman for each packed triangle (P, 3, 4 + A); fan-triangulates the result."""
    n_tri, _, width = tris.shape
    out = np.empty((n_tri * _MAX_OUT, 3, width))
    src = np.empty(n_tri * _MAX_OUT, np.int64)
    poly = np.empty((_MAX_POLY + 1, width))
    nxt = np.empty((_MAX_POLY + 1, width))
    count = 0
    for t in range(n_tri):
        n = 3
        poly[:3] = tris[t]
        for plane in range(6):
            m = 0
            for i in range(n):
                a, b = poly[i], poly[(i + 1) % n]
                da, db = _distance(a, plane), _distance(b, plane)
                if da >= 0.0:
                    nxt[m] = a  # an inside vertex is kept
                    m += 1
                if (da >= 0.0) != (db >= 0.0):
                    s = da / (da - db)  # where the edge crosses the plane
                    nxt[m] = a + s * (b - a)
                    m += 1
            n = m
            poly[:n] = nxt[:n]
            if n < 3:
                break
        for k in range(1, n - 1):  # fan around the first vertex
            out[count, 0] = poly[0]
            out[count, 1] = poly[k]
            out[count, 2] = poly[k + 1]
            src[count] = t
            count += 1
    return out, src, count
