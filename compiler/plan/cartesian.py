"""TCP path geometry of linear and circular moves: position and orientation along u in [0, 1].

Position: a straight line, or the circular arc from the start through the via point to the
end (constant radius). Orientation: SLERP (the shortest rotation) from start to end, for both.
All lengths in metres; quaternions (w, x, y, z).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["CartesianPath", "DegenerateArc", "arc_path", "line_path", "slerp", "matrix_to_quat"]

# Points closer than this are "the same point" for an arc (m); sine of the angle at which
# three points count as collinear.
_COINCIDENT = 1e-4
_COLLINEAR_SIN = 1e-4


class DegenerateArc(ValueError):
    """Raised by arc_path with a user-facing reason (collinear or coincident points)."""


def matrix_to_quat(r: np.ndarray) -> np.ndarray:
    """(3, 3) rotation -> (4,) unit quaternion (w, x, y, z) with w >= 0."""
    tr = np.trace(r)
    if tr > 0:
        s = np.sqrt(tr + 1.0) * 2
        q = [0.25 * s, (r[2, 1] - r[1, 2]) / s, (r[0, 2] - r[2, 0]) / s, (r[1, 0] - r[0, 1]) / s]
    elif r[0, 0] > r[1, 1] and r[0, 0] > r[2, 2]:
        s = np.sqrt(1.0 + r[0, 0] - r[1, 1] - r[2, 2]) * 2
        q = [(r[2, 1] - r[1, 2]) / s, 0.25 * s, (r[0, 1] + r[1, 0]) / s, (r[0, 2] + r[2, 0]) / s]
    elif r[1, 1] > r[2, 2]:
        s = np.sqrt(1.0 + r[1, 1] - r[0, 0] - r[2, 2]) * 2
        q = [(r[0, 2] - r[2, 0]) / s, (r[0, 1] + r[1, 0]) / s, 0.25 * s, (r[1, 2] + r[2, 1]) / s]
    else:
        s = np.sqrt(1.0 + r[2, 2] - r[0, 0] - r[1, 1]) * 2
        q = [(r[1, 0] - r[0, 1]) / s, (r[0, 2] + r[2, 0]) / s, (r[1, 2] + r[2, 1]) / s, 0.25 * s]
    out = np.asarray(q) / np.linalg.norm(q)
    return out if out[0] >= 0 else -out


def _quat_to_matrices(q: np.ndarray) -> np.ndarray:
    """(N, 4) quaternions -> (N, 3, 3) rotations."""
    w, x, y, z = q[:, 0], q[:, 1], q[:, 2], q[:, 3]
    r = np.empty((q.shape[0], 3, 3))
    r[:, 0, 0] = 1 - 2 * (y * y + z * z)
    r[:, 0, 1] = 2 * (x * y - w * z)
    r[:, 0, 2] = 2 * (x * z + w * y)
    r[:, 1, 0] = 2 * (x * y + w * z)
    r[:, 1, 1] = 1 - 2 * (x * x + z * z)
    r[:, 1, 2] = 2 * (y * z - w * x)
    r[:, 2, 0] = 2 * (x * z - w * y)
    r[:, 2, 1] = 2 * (y * z + w * x)
    r[:, 2, 2] = 1 - 2 * (x * x + y * y)
    return r


def slerp(q0: np.ndarray, q1: np.ndarray, u: np.ndarray) -> np.ndarray:
    """Shortest-rotation interpolation: q0, q1 (4,), u (N,) in [0, 1] -> (N, 4)."""
    d = float(np.dot(q0, q1))
    if d < 0:  # q and -q are one rotation: take the short way round
        q1, d = -q1, -d
    d = min(1.0, d)
    theta = np.arccos(d)
    u = np.asarray(u, dtype=float)[:, None]
    if theta < 1e-9:
        out = (1 - u) * q0 + u * q1
    else:
        out = (np.sin((1 - u) * theta) * q0 + np.sin(u * theta) * q1) / np.sin(theta)
    return out / np.linalg.norm(out, axis=1, keepdims=True)


def rotation_angle(q0: np.ndarray, q1: np.ndarray) -> float:
    """The angle (rad) of the shortest rotation from q0 to q1."""
    return float(2 * np.arccos(min(1.0, abs(float(np.dot(q0, q1))))))


@dataclass(frozen=True, eq=False)
class CartesianPath:
    """A TCP path: `positions(u)` (N, 3) and `poses(u)` (N, 4, 4) for u (N,) in [0, 1].

    For an arc, `center`, `radius`, `e1`, `e2` (in-plane unit axes) and `sweep` (rad) are set;
    the point at u is center + radius (cos(u sweep) e1 + sin(u sweep) e2).
    """

    kind: str  # "line" or "arc"
    p0: np.ndarray
    p1: np.ndarray
    q0: np.ndarray
    q1: np.ndarray
    length: float  # m, along the path
    angle: float  # rad, the orientation change
    center: np.ndarray | None = None
    radius: float = 0.0
    e1: np.ndarray | None = None
    e2: np.ndarray | None = None
    sweep: float = 0.0

    def positions(self, u: np.ndarray) -> np.ndarray:
        u = np.asarray(u, dtype=float)
        if self.kind == "line":
            return self.p0 + u[:, None] * (self.p1 - self.p0)
        a = u * self.sweep
        return self.center + self.radius * (np.cos(a)[:, None] * self.e1 + np.sin(a)[:, None] * self.e2)

    def poses(self, u: np.ndarray) -> np.ndarray:
        u = np.asarray(u, dtype=float)
        out = np.tile(np.eye(4), (u.shape[0], 1, 1))
        out[:, :3, :3] = _quat_to_matrices(slerp(self.q0, self.q1, u))
        out[:, :3, 3] = self.positions(u)
        return out

    def distance(self, points: np.ndarray) -> np.ndarray:
        """Distance (m) of points (N, 3) from the path (line segment, or the arc's circle)."""
        if self.kind == "line":
            d = self.p1 - self.p0
            n2 = float(d @ d)
            u = np.clip(((points - self.p0) @ d) / n2, 0, 1) if n2 > 0 else np.zeros(len(points))
            return np.linalg.norm(points - (self.p0 + u[:, None] * d), axis=1)
        rel = points - self.center
        assert self.e1 is not None and self.e2 is not None  # an arc has its plane's axes
        normal = np.cross(self.e1, self.e2)
        h = rel @ normal
        rho = np.linalg.norm(rel - h[:, None] * normal, axis=1)
        return np.sqrt(h * h + (rho - self.radius) ** 2)

    def deviation(self, u0: np.ndarray, u1: np.ndarray, points: np.ndarray) -> np.ndarray:
        """Distance (m) of points (N, 3), each found between path fractions u0 and u1 (N,), from
        the path: for a fixed line or arc, the distance from the whole of it."""
        return self.distance(points)

    def u_at_via(self, via: np.ndarray) -> float:
        """For an arc: the u at which the path passes the via point."""
        rel = via - self.center
        a = np.arctan2(rel @ self.e2, rel @ self.e1) % (2 * np.pi)
        return float(a / self.sweep)


def _pose_parts(t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    return t[:3, 3].copy(), matrix_to_quat(t[:3, :3])


def line_path(t0: np.ndarray, t1: np.ndarray) -> CartesianPath:
    """The straight TCP path from pose t0 (4, 4) to t1 (4, 4)."""
    p0, q0 = _pose_parts(t0)
    p1, q1 = _pose_parts(t1)
    return CartesianPath("line", p0, p1, q0, q1, float(np.linalg.norm(p1 - p0)), rotation_angle(q0, q1))


def arc_path(t0: np.ndarray, via: np.ndarray, t1: np.ndarray) -> CartesianPath:
    """The arc from t0 through the via position (3,) to t1; raises DegenerateArc."""
    p0, q0 = _pose_parts(t0)
    p2, q2 = _pose_parts(t1)
    p1 = np.asarray(via, dtype=float)
    for (a, b, names) in ((p0, p1, "start and via"), (p1, p2, "via and end"), (p0, p2, "start and end")):
        if np.linalg.norm(b - a) < _COINCIDENT:
            raise DegenerateArc(
                f"circular move points must be distinct ({names} are {np.linalg.norm(b - a) * 1e3:.3f} mm apart)"
            )
    a, b = p1 - p0, p2 - p0
    n = np.cross(a, b)
    sin = np.linalg.norm(n) / (np.linalg.norm(a) * np.linalg.norm(b))
    if sin < _COLLINEAR_SIN:
        raise DegenerateArc("circular move points must not be collinear (start, via and end lie on one line)")
    n /= np.linalg.norm(n)
    # Circumcentre of the triangle p0 p1 p2.
    aa, bb = a @ a, b @ b
    center = p0 + (aa * np.cross(b, n) - bb * np.cross(a, n)) / (2 * np.dot(np.cross(a, b), n))
    radius = float(np.linalg.norm(p0 - center))
    e1 = (p0 - center) / radius
    e2 = np.cross(n, e1)
    rel = p2 - center
    sweep = float(np.arctan2(rel @ e2, rel @ e1) % (2 * np.pi))
    return CartesianPath(
        "arc", p0, p2, q0, q2, radius * sweep, rotation_angle(q0, q2), center, radius, e1, e2, sweep
    )
