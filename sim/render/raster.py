"""Z-buffer rasterisation with perspective-correct barycentrics (numba inner loops).

The rasteriser produces a visibility buffer: for every pixel the depth (0..1) of the
nearest surface, the index of its triangle (-1 for none) and that triangle's
perspective-correct barycentric weights (b1, b2; b0 = 1 - b1 - b2). Attributes are then
interpolated per pixel by `resolve`, so shading costs one evaluation per visible pixel
whatever the overdraw.

Coverage: a pixel belongs to a triangle when its centre is inside it; a centre exactly on
an edge shared by two triangles belongs to exactly one of them (a tie-break on the edge
direction, the 'top-left' rule's role), so no pixel is drawn twice or missed along seams.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import njit

__all__ = ["Frame", "rasterize", "resolve", "resolve_downsampled"]


@dataclass(frozen=True, eq=False)
class Frame:
    """A visibility buffer: depth (H, W) float32 (inf = empty), tri (H, W) int32, bary (H, W, 2) float32."""

    depth: np.ndarray
    tri: np.ndarray
    bary: np.ndarray

    @property
    def covered(self) -> np.ndarray:
        return self.tri >= 0


def rasterize(screen: np.ndarray, inv_w: np.ndarray, width: int, height: int) -> Frame:
    """Scan-convert triangles; screen (T, 3, 3) [x_px, y_px, depth], inv_w (T, 3) = 1/w_clip."""
    depth = np.full((height, width), np.inf, np.float32)
    tri = np.full((height, width), -1, np.int32)
    bary = np.zeros((height, width, 2), np.float32)
    if len(screen):
        _raster(np.ascontiguousarray(screen, np.float64), np.ascontiguousarray(inv_w, np.float64), depth, tri, bary)
    return Frame(depth, tri, bary)


def resolve(frame: Frame, attrs: np.ndarray, empty: np.ndarray | tuple[float, ...] | None = None) -> np.ndarray:
    """Interpolate per-vertex attributes (T, 3, A) at every covered pixel -> (H, W, A) float32;
    pixels with no surface get `empty` (A,) (default 0)."""
    n_attr = attrs.shape[2]
    fill = np.zeros(n_attr, np.float32) if empty is None else np.asarray(empty, np.float32).reshape(n_attr)
    out = np.empty(frame.tri.shape + (n_attr,), np.float32)
    _resolve(frame.tri, frame.bary, np.ascontiguousarray(attrs, np.float32), fill, out)
    return out


def resolve_downsampled(frame: Frame, colors: np.ndarray, k: int, background: tuple[float, float, float]) -> np.ndarray:
    """Per-vertex colours (T, 3, 3) in 0..1 interpolated, box-filtered k x k and rounded to bytes in
    one pass -> (H/k, W/k, 3) uint8."""
    height, width = frame.tri.shape
    out = np.empty((height // k, width // k, 3), np.uint8)
    _resolve_down(frame.tri, frame.bary, np.ascontiguousarray(colors, np.float32), k,
                  np.asarray(background, np.float32), out)
    return out


@njit(cache=True)
def _resolve_down(tri: np.ndarray, bary: np.ndarray, colors: np.ndarray, k: int, background: np.ndarray,
                  out: np.ndarray) -> None:
    weight = 1.0 / (k * k)
    for r in range(out.shape[0]):
        for c in range(out.shape[1]):
            acc0 = acc1 = acc2 = 0.0
            for dr in range(k):
                for dc in range(k):
                    rr, cc = r * k + dr, c * k + dc
                    t = tri[rr, cc]
                    if t < 0:
                        acc0 += background[0]
                        acc1 += background[1]
                        acc2 += background[2]
                        continue
                    b1, b2 = bary[rr, cc, 0], bary[rr, cc, 1]
                    b0 = 1.0 - b1 - b2
                    acc0 += b0 * colors[t, 0, 0] + b1 * colors[t, 1, 0] + b2 * colors[t, 2, 0]
                    acc1 += b0 * colors[t, 0, 1] + b1 * colors[t, 1, 1] + b2 * colors[t, 2, 1]
                    acc2 += b0 * colors[t, 0, 2] + b1 * colors[t, 1, 2] + b2 * colors[t, 2, 2]
            out[r, c, 0] = _byte(acc0 * weight)
            out[r, c, 1] = _byte(acc1 * weight)
            out[r, c, 2] = _byte(acc2 * weight)


@njit(cache=True, inline="always")
def _byte(value: float) -> np.uint8:
    """0..1 -> 0..255, rounded half to even like np.rint (as pipeline.to_uint8)."""
    return np.uint8(min(max(np.rint(value * 255.0), 0.0), 255.0))


@njit(cache=True, inline="always")
def _owns_edge(ax: float, ay: float, bx: float, by: float) -> bool:
    """Tie-break for centres exactly on edge a->b: opposite directions decide oppositely."""
    return (by - ay) < 0.0 or ((by - ay) == 0.0 and (bx - ax) > 0.0)


@njit(cache=True, inline="always")
def _row_span(a: float, k: float, lo: int, hi: int) -> tuple[int, int]:
    """Narrow columns [lo, hi] to where a * (c + 0.5) + k >= 0 may hold (one column of slack)."""
    if a > 0.0:
        lo = max(lo, int(np.floor(-k / a - 0.5)))
    elif a < 0.0:
        hi = min(hi, int(np.ceil(-k / a - 0.5)))
    elif k < 0.0:
        hi = lo - 1  # a horizontal edge with the whole row outside it
    return lo, hi


@njit(cache=True)
def _raster(screen: np.ndarray, inv_w: np.ndarray, depth: np.ndarray, tri: np.ndarray, bary: np.ndarray) -> None:
    height, width = depth.shape
    for t in range(screen.shape[0]):
        x0, y0, z0 = screen[t, 0, 0], screen[t, 0, 1], screen[t, 0, 2]
        x1, y1, z1 = screen[t, 1, 0], screen[t, 1, 1], screen[t, 1, 2]
        x2, y2, z2 = screen[t, 2, 0], screen[t, 2, 1], screen[t, 2, 2]
        q0, q1, q2 = inv_w[t, 0], inv_w[t, 1], inv_w[t, 2]
        area = (x1 - x0) * (y2 - y0) - (y1 - y0) * (x2 - x0)  # twice the signed area
        if area == 0.0 or area != area:
            continue  # degenerate (or NaN) triangles cover nothing
        swapped = area < 0.0
        if swapped:  # orient counter-clockwise so inside means all edge functions >= 0
            x1, y1, z1, q1, x2, y2, z2, q2 = x2, y2, z2, q2, x1, y1, z1, q1
            area = -area
        inv_area = 1.0 / area
        # bounding box of the pixel centres (c + 0.5) that can fall inside
        c0 = max(int(np.ceil(min(x0, x1, x2) - 0.5)), 0)
        c1 = min(int(np.floor(max(x0, x1, x2) - 0.5)), width - 1)
        r0 = max(int(np.ceil(min(y0, y1, y2) - 0.5)), 0)
        r1 = min(int(np.floor(max(y0, y1, y2) - 0.5)), height - 1)
        own0 = _owns_edge(x1, y1, x2, y2)  # edge opposite vertex 0
        own1 = _owns_edge(x2, y2, x0, y0)
        own2 = _owns_edge(x0, y0, x1, y1)
        # edge functions e_i(x, y) = a_i x + b_i y + c_i, affine in the pixel centre
        a0, b0 = -(y2 - y1), x2 - x1
        a1, b1 = -(y0 - y2), x0 - x2
        a2, b2 = -(y1 - y0), x1 - x0
        for r in range(r0, r1 + 1):
            py = r + 0.5
            # the span of this row where all three edge functions can be >= 0 (+-1 column for rounding)
            lo, hi = _row_span(a0, b0 * (py - y1) - a0 * x1, c0, c1)
            lo, hi = _row_span(a1, b1 * (py - y2) - a1 * x2, lo, hi)
            lo, hi = _row_span(a2, b2 * (py - y0) - a2 * x0, lo, hi)
            for c in range(lo, hi + 1):
                px = c + 0.5
                e0 = a0 * (px - x1) + b0 * (py - y1)
                e1 = a1 * (px - x2) + b1 * (py - y2)
                e2 = a2 * (px - x0) + b2 * (py - y0)
                if e0 < 0.0 or e1 < 0.0 or e2 < 0.0:
                    continue
                if (e0 == 0.0 and not own0) or (e1 == 0.0 and not own1) or (e2 == 0.0 and not own2):
                    continue
                l0, l1, l2 = e0 * inv_area, e1 * inv_area, e2 * inv_area  # screen-space weights
                z = l0 * z0 + l1 * z1 + l2 * z2  # device depth is affine in screen space
                if z >= depth[r, c]:
                    continue
                depth[r, c] = z
                tri[r, c] = t
                p0, p1, p2 = l0 * q0, l1 * q1, l2 * q2  # perspective correction: weight by 1/w
                s = 1.0 / (p0 + p1 + p2)
                if swapped:
                    p1, p2 = p2, p1  # back to the caller's vertex order
                bary[r, c, 0] = p1 * s
                bary[r, c, 1] = p2 * s


@njit(cache=True)
def _resolve(tri: np.ndarray, bary: np.ndarray, attrs: np.ndarray, fill: np.ndarray, out: np.ndarray) -> None:
    height, width = tri.shape
    n_attr = attrs.shape[2]
    for r in range(height):
        for c in range(width):
            t = tri[r, c]
            if t < 0:
                out[r, c, :] = fill
                continue
            b1, b2 = bary[r, c, 0], bary[r, c, 1]
            b0 = 1.0 - b1 - b2
            for k in range(n_attr):
                out[r, c, k] = b0 * attrs[t, 0, k] + b1 * attrs[t, 1, k] + b2 * attrs[t, 2, k]
