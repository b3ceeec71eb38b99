"""The camera: eye point, centre of interest, up vector and vertical view angle.

A pinhole camera as in the classic graphic simulators: the viewing transform takes world
points to eye space (right-handed, the camera looks down its -z axis, +y is up on the
screen); the perspective transform takes eye space to homogeneous clip space, where after
the divide by w the visible volume is x, y in [-1, 1] and depth in [0, 1] (0 at the near
plane, 1 at the far plane).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from rmot.lang.record import record

__all__ = ["Camera", "CameraSpecError", "camera_fields", "parse_camera"]

Vec3 = tuple[float, float, float]

NEAR_MAX = 0.05  # m: the near plane never cuts geometry farther than this from the eye
NEAR_MIN = 0.002  # m: closer than this the depth buffer would lose its precision


class CameraSpecError(ValueError):
    """A `--camera` text that does not describe a camera (message suitable for users)."""


@record(slots=True)
class Camera:
    """A perspective camera; distances in metres, `fov_deg` the vertical view angle in degrees."""

    eye: Vec3
    center: Vec3
    up: Vec3 = (0.0, 0.0, 1.0)
    fov_deg: float = 40.0
    near: float | None = None  # None: fitted to what the camera sees (see `fitted`)
    far: float | None = None

    def __post_init__(self) -> None:
        if not 0.0 < self.fov_deg < 180.0:
            raise CameraSpecError(f"camera fov must be in (0, 180) degrees (got {self.fov_deg})")
        near = NEAR_MAX if self.near is None else self.near
        far = max(near * 2.0, 100.0) if self.far is None else self.far
        if not 0.0 < near < far:
            raise CameraSpecError(f"camera near/far must satisfy 0 < near < far (got {self.near}, {self.far})")
        forward = np.subtract(self.center, self.eye)
        if np.linalg.norm(forward) < 1e-9:
            raise CameraSpecError(f"camera eye and center must differ (both {self.eye})")
        if np.linalg.norm(np.cross(forward, self.up)) < 1e-9 * np.linalg.norm(forward):
            raise CameraSpecError(f"camera up {self.up} must not be parallel to the view direction")

    def view(self) -> np.ndarray:
        """(4, 4) world -> eye transform (the 'look-at' viewing transform)."""
        f = np.subtract(self.center, self.eye).astype(float)
        f /= np.linalg.norm(f)  # viewing direction
        s = np.cross(f, self.up)
        s /= np.linalg.norm(s)  # screen right
        u = np.cross(s, f)  # screen up, orthogonal to both
        m = np.eye(4)
        m[0, :3], m[1, :3], m[2, :3] = s, u, -f  # rows: the eye axes in world coordinates
        m[:3, 3] = -m[:3, :3] @ np.asarray(self.eye, float)  # move the eye to the origin
        return m

    def projection(self, aspect: float) -> np.ndarray:
        """(4, 4) eye -> clip transform; `aspect` = width / height.

        w_clip = -z_eye (distance in front of the eye); after the divide x, y in [-1, 1]
        and z in [0, 1] inside the view volume (near -> 0, far -> 1).
        """
        t = 1.0 / math.tan(math.radians(self.fov_deg) / 2.0)  # cot(fov/2)
        n, f = self.depth_range()
        p = np.zeros((4, 4))
        p[0, 0] = t / aspect
        p[1, 1] = t
        p[2, 2] = -f / (f - n)  # z_clip = f(d - n)/(f - n) with d = -z_eye
        p[2, 3] = -f * n / (f - n)
        p[3, 2] = -1.0  # w_clip = d
        return p

    def depth_range(self) -> tuple[float, float]:
        """(near, far) m; unset planes (not yet `fitted`) fall back to NEAR_MAX and 100 m."""
        near = NEAR_MAX if self.near is None else float(self.near)
        far = max(near * 2.0, 100.0) if self.far is None else float(self.far)
        return near, far

    def fitted(self, points: np.ndarray) -> Camera:
        """This camera with unset near/far planes fitted to the points (..., 3) it must show.

        far: just beyond the deepest point in front of the eye, so nothing drawn is cut at the
        back. near: half the depth of the nearest point in front of the eye, but never more
        than NEAR_MAX (5 cm) and never less than NEAR_MIN (2 mm), so geometry is only cut
        when it comes within a few centimetres of the eye, whatever the scene's size (a box
        1.2 m in front of the eye is drawn even when the rest of the cell is 6 m away).
        Planes given explicitly are kept.
        """
        if self.near is not None and self.far is not None:
            return self
        pts = np.asarray(points, float).reshape(-1, 3)
        view = self.view()
        depth = -(pts @ view[2, :3] + view[2, 3]) if len(pts) else np.zeros(0)
        ahead = depth[depth > 0.0]
        near = self.near
        if near is None:
            near = float(np.clip(0.5 * ahead.min(), NEAR_MIN, NEAR_MAX)) if ahead.size else NEAR_MAX
        far = self.far
        if far is None:
            far = float(ahead.max()) * 1.05 + 0.01 if ahead.size else 1.0
            far = max(far, near * 4.0)
        return replace(self, near=near, far=far)

    def matrix(self, aspect: float) -> np.ndarray:
        """(4, 4) world -> clip: projection . view."""
        return self.projection(aspect) @ self.view()

    @staticmethod
    def framing(bounds: np.ndarray, *, aspect: float = 4.0 / 3.0, fov_deg: float = 40.0,
                azimuth_deg: float = -50.0, elevation_deg: float = 28.0, fill: float = 0.92,
                points: np.ndarray | None = None) -> Camera:
        """The default three-quarter view that frames the whole box `bounds` (2, 3) [min; max].

        The eye looks at the box centre from the given azimuth (from +x about +z) and
        elevation, at the nearest distance where all eight corners (or `points` (K, 3) inside
        the box, for a tighter fit) project within `fill` of the picture's half width and height.
        """
        lo, hi = np.asarray(bounds, float)
        center = (lo + hi) / 2.0
        radius = max(float(np.linalg.norm(hi - lo)) / 2.0, 1e-3)
        az, el = math.radians(azimuth_deg), math.radians(elevation_deg)
        direction = np.array([math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el)])
        corners = np.array([[(lo, hi)[i][0], (lo, hi)[j][1], (lo, hi)[k][2]] for i in (0, 1) for j in (0, 1) for k in (0, 1)])
        if points is not None and len(points):
            corners = np.asarray(points, float).reshape(-1, 3)
        tan_v = math.tan(math.radians(fov_deg) / 2.0)
        tan_h = tan_v * aspect
        right = np.cross(-direction, (0.0, 0.0, 1.0))
        right /= np.linalg.norm(right)
        up = np.cross(right, -direction)
        rel = corners - center  # corner offsets in the view axes: x right, y up, z towards the eye
        x, y, z = rel @ right, rel @ up, rel @ direction

        def fits(d: float) -> bool:
            depth = d - z  # distance in front of the eye
            return bool(np.all(depth > 1e-6) and np.all(np.abs(x) <= fill * tan_h * depth)
                        and np.all(np.abs(y) <= fill * tan_v * depth))

        near_d, far_d = 0.0, radius / (fill * math.sin(math.atan(min(tan_v, tan_h)))) + radius  # far_d always fits
        for _ in range(40):  # bisection on the eye distance
            mid = 0.5 * (near_d + far_d)
            near_d, far_d = (near_d, mid) if fits(mid) else (mid, far_d)
        eye = center + far_d * direction
        return Camera(_vec(eye), _vec(center), fov_deg=fov_deg)  # near/far: fitted per picture


def _vec(a: np.ndarray) -> Vec3:
    return (float(a[0]), float(a[1]), float(a[2]))


_KEYS = {"eye", "center", "up", "fov", "near", "far"}


def camera_fields(text: str) -> dict[str, object]:
    """The settings of a `--camera` text as Camera field values; raises CameraSpecError on bad syntax."""
    fields: dict[str, object] = {}
    for part in filter(None, (p.strip() for p in text.split(";"))):
        key, sep, value = part.partition("=")
        key = key.strip().lower()
        if not sep or key not in _KEYS:
            raise CameraSpecError(f"camera setting must be one of {sorted(_KEYS)} as key=value (got {part!r})")
        numbers = _numbers(key, value)
        if key in ("eye", "center", "up"):
            if len(numbers) != 3:
                raise CameraSpecError(f"camera {key} must be three numbers x,y,z (got {value.strip()!r})")
            fields[key] = tuple(numbers)
        else:
            if len(numbers) != 1:
                raise CameraSpecError(f"camera {key} must be one number (got {value.strip()!r})")
            fields["fov_deg" if key == "fov" else key] = numbers[0]
    return fields


def parse_camera(text: str, default: Camera | None = None) -> Camera:
    """A camera from `eye=x,y,z;center=x,y,z;up=x,y,z;fov=40;near=0.05;far=100` (metres, degrees).

    Missing keys come from `default` (eye and center are required without one).
    Raises CameraSpecError with a message naming the bad key and value.
    """
    fields = camera_fields(text)
    if default is None and not {"eye", "center"} <= fields.keys():
        raise CameraSpecError(f"camera must give eye=x,y,z and center=x,y,z (got {text!r})")
    base = default or Camera(eye=(1.0, 0.0, 0.0), center=(0.0, 0.0, 0.0))
    merged = {name: fields.get(name, getattr(base, name)) for name in ("eye", "center", "up", "fov_deg", "near", "far")}
    return Camera(**merged)  # type: ignore[arg-type]


def _numbers(key: str, value: str) -> list[float]:
    try:
        numbers = [float(v) for v in value.split(",")]
    except ValueError:
        raise CameraSpecError(f"camera {key} must be numbers (got {value.strip()!r})") from None
    if not all(math.isfinite(v) for v in numbers):
        raise CameraSpecError(f"camera {key} must be finite numbers (got {value.strip()!r})")
    return numbers
