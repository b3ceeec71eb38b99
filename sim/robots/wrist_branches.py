"""Branch names for URDF arms from their geometry: 6R arms with a spherical wrist.

The definitions are those of `rmot.sim.robots.branches`, generalised from DH/OPW
parameters to the model's joint frames and axes (all in the base frame, model values q):

C        the wrist centre: the common point of the J4, J5 and J6 axes.
forward  f(q) = the J1 rotation of f0 = ±(J2 axis × J1 axis) at q = 0, the arm plane's
         horizontal direction (a lateral offset b along the J2 axis does not count). Its sign
         points towards the J2 axis offset a1 when that is > 1 mm, else towards the wrist centre
         at q = 0, else (arms stretched upright at zero) the way a positive J2 motion moves
         the wrist centre.
up       u1 = the J1 axis direction oriented from the base towards the J2 axis (or, when the
         J2 axis lies on the J1 foot's plane, the wrist centre at q = 0).
shoulder (C − p1)·f(q): in front of (≥ 0) or behind the J1 axis along the arm's forward
         direction.
elbow    the wrist centre's side of the lower-arm line through the J2 and J3 axes: with
         w the J2 axis oriented along u1 × f(q), l = (P3 − P2) projected ⊥ w and n = w × l
         (so that n = f when the lower arm points up), elbow = (C − P3)·n; UP when ≥ 0.
wrist    sin(J5) on the joint value, as for every arm.

Other arms keep all-None branches: without a spherical wrist (e.g. UR-style offset wrists,
whose library branches are defined on DH frame 5 rather than on a point of the geometry), or
with non-parallel J2/J3 axes or J2 parallel to J1, there is no wrist centre or lower-arm line
whose sides could be named, and the vendors' configuration data (ABB cfx, KUKA Status, Fanuc
and Yaskawa configuration strings) is defined for the spherical-wrist arm geometry only.
Guessing a name would let a controller pick a different solution than the planned one.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pinocchio as pin

from rmot.lang import ir
from rmot.sim.robots.branches import config_of

__all__ = ["spherical_wrist_branch_fn", "wrist_centre"]

_TOL = 1e-9  # m: the three wrist axes must meet within this at every tested configuration
_PARALLEL = 1e-9  # |sin| between J2 and J3 axes
_CHECK_SAMPLES = 5


def _axis_lines(model: pin.Model, data: pin.Data, axes: np.ndarray, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """q: (6,) -> points (6,3) and unit directions (6,3) of the joint axes in the base frame."""
    pin.forwardKinematics(model, data, q)
    pts = np.array([data.oMi[j].translation for j in range(1, 7)])
    dirs = np.array([data.oMi[j].rotation @ axes[j - 1] for j in range(1, 7)])
    return pts, dirs


def _closest_point(pts: np.ndarray, dirs: np.ndarray) -> tuple[np.ndarray, float] | None:
    """The least-squares common point of lines (k,3)/(k,3) and its largest distance to them;
    None when the lines are (nearly) parallel so that no unique point exists."""
    projs = np.eye(3)[None] - dirs[:, :, None] * dirs[:, None, :]
    a = projs.sum(axis=0)
    if np.linalg.cond(a) > 1e8:
        return None
    c = np.linalg.solve(a, np.einsum("kij,kj->i", projs, pts))
    dist = max(float(np.linalg.norm(p @ (c - x))) for p, x in zip(projs, pts))
    return c, dist


def wrist_centre(model: pin.Model, axes: np.ndarray, q: np.ndarray) -> np.ndarray | None:
    """q: (6,) model values -> (3,) the common point of the J4–J6 axes in m, or None."""
    pts, dirs = _axis_lines(model, model.createData(), axes, np.asarray(q, dtype=float))
    found = _closest_point(pts[3:], dirs[3:])
    return None if found is None or found[1] > _TOL else found[0]


def spherical_wrist_branch_fn(
    model: pin.Model, axes: np.ndarray, prismatic: np.ndarray, limits: np.ndarray
) -> Callable[[np.ndarray], ir.Config] | None:
    """The branch function of a 6R arm with a spherical wrist and parallel J2/J3 axes, else None.

    axes: (6,3) joint axes in the joint frames; prismatic: (6,) bool; limits: (6,2) rad."""
    if model.nq != 6 or np.any(prismatic):
        return None
    data = model.createData()
    rng = np.random.default_rng(0)
    samples = [np.zeros(6)] + [rng.uniform(limits[:, 0], limits[:, 1]) for _ in range(_CHECK_SAMPLES)]
    for q in samples:
        pts, dirs = _axis_lines(model, data, axes, q)
        found = _closest_point(pts[3:], dirs[3:])
        if found is None or found[1] > _TOL or np.linalg.norm(np.cross(dirs[1], dirs[2])) > _PARALLEL \
                or np.linalg.norm(np.cross(dirs[0], dirs[1])) < 1e-6:
            return None
    return _branch_fn(model, data, axes)


def _branch_fn(model: pin.Model, data: pin.Data, axes: np.ndarray) -> Callable[[np.ndarray], ir.Config]:
    pts, dirs = _axis_lines(model, data, axes, np.zeros(6))
    p1, z1 = pts[0], dirs[0]
    centre0 = _closest_point(pts[3:], dirs[3:])[0]  # type: ignore[index]
    def flat(v: np.ndarray) -> np.ndarray:  # the component ⊥ the J1 axis
        return v - (v @ z1) * z1
    # J2 axis point nearest the J1 axis: its offset from J1 is the shoulder offset a1.
    shoulder_pt = _nearest_on_line(pts[1], dirs[1], p1, z1)
    f0 = np.cross(dirs[1], z1)
    f0 = f0 / np.linalg.norm(f0)
    f0 = f0 if _forward_sign(f0, flat(shoulder_pt - p1), flat(centre0 - p1), np.cross(dirs[1], centre0 - pts[1])) >= 0 else -f0
    height = (shoulder_pt - p1) @ z1
    up = z1 if (height if abs(height) > 1e-3 else (centre0 - p1) @ z1) >= 0 else -z1
    r1_0 = data.oMi[1].rotation.copy()
    f_local, up_local = r1_0.T @ f0, r1_0.T @ up  # carried by joint 1's frame

    def branch(q: np.ndarray) -> ir.Config:
        pts, dirs = _axis_lines(model, data, axes, q)
        centre = _closest_point(pts[3:], dirs[3:])
        c = centre[0] if centre is not None else pts[3]
        r1 = data.oMi[1].rotation
        f, u1 = r1 @ f_local, r1 @ up_local
        w = dirs[1] if dirs[1] @ np.cross(u1, f) >= 0 else -dirs[1]
        lower = pts[2] - pts[1]
        lower = lower - (lower @ w) * w
        n = np.cross(w, lower)
        return config_of(float((c - pts[0]) @ f), float((c - pts[2]) @ n), float(np.sin(q[4])))

    return branch


def _forward_sign(f0: np.ndarray, offset: np.ndarray, centre: np.ndarray, j2_velocity: np.ndarray) -> float:
    """+1 when f0 points forward: towards the J2 axis offset (a1), else towards the wrist
    centre at q = 0, else (arms upright at zero, the "candle") the way a positive J2 motion
    moves the wrist centre."""
    for v in (offset, centre, j2_velocity):
        if abs(v @ f0) > 1e-3:
            return float(np.sign(v @ f0))
    return 1.0


def _nearest_on_line(p: np.ndarray, d: np.ndarray, p1: np.ndarray, z1: np.ndarray) -> np.ndarray:
    """The point of line (p, d) nearest line (p1, z1); p itself when they are parallel."""
    cross = np.cross(d, z1)
    if np.linalg.norm(cross) < 1e-9:
        return p
    # Solve for s, t minimising |p + s d − (p1 + t z1)|.
    a = np.array([[d @ d, -(d @ z1)], [d @ z1, -(z1 @ z1)]])
    b = np.array([(p1 - p) @ d, (p1 - p) @ z1])
    s, _ = np.linalg.solve(a, b)
    return p + s * d
