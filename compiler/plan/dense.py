"""Dense IK along a Cartesian path, with branch continuity.

`follow_path` solves the flange pose at many points of a TCP path, staying on the branch the
move starts on: closed-form robots follow the same closed-form solution (one of `ik_batch`'s
8 columns, unwrapped by 2 pi per revolute joint), other robots take damped Newton steps from the
previous point. The grid is refined (intervals bisected) until

* the TCP at the joint-space midpoint of every interval lies within `tol` of the path, and
* no joint moves more than `_MAX_JUMP` rad within one interval.

An interval that keeps a large joint jump however small it gets is a discontinuity of the
IK branch: the path passes through a singularity (or the branch ceases to exist there); a
path point with no solution on the branch leaves the workspace. Both are failures, returned
as values (`PathFailure`), never exceptions.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rmot.compiler.plan.cartesian import CartesianPath
from rmot.compiler.plan.robot_model import RobotModel

__all__ = ["DensePath", "PathFailure", "follow_path", "newton_ik"]

_START_STEP = 0.002  # m between initial samples
_START_ANGLE = np.radians(1.0)  # rad of orientation change between initial samples
_MAX_JUMP = 0.05  # rad (or m) per interval
_MIN_DU = 1e-7  # intervals shorter than this (fraction of the path) are not split further
_MAX_ROUNDS = 30


@dataclass(frozen=True, eq=False)
class DensePath:
    """u (M,) path fractions, q (M, dof) joints, tcp (M, 3) TCP positions (m)."""

    u: np.ndarray
    q: np.ndarray
    tcp: np.ndarray


@dataclass(frozen=True, eq=False)
class PathFailure:
    """Why a path cannot be followed: kind is 'singular', 'unreachable' or 'limit'."""

    kind: str
    message: str
    u: float
    position: np.ndarray  # TCP (3,) m where it happens


def newton_ik(robot: RobotModel, target: np.ndarray, seed: np.ndarray, iters: int = 20) -> np.ndarray | None:
    """Damped-least-squares Newton iterations from seed to the flange pose target (4, 4)."""
    q = seed.astype(float).copy()
    for _ in range(iters):
        err = _pose_error(robot.fk(q), target)
        if np.max(np.abs(err)) < 1e-11:
            return q
        jac = robot.jacobian(q)
        q = q + jac.T @ np.linalg.solve(jac @ jac.T + 1e-10 * np.eye(6), err)
    err = _pose_error(robot.fk(q), target)
    return q if np.max(np.abs(err)) < 1e-8 else None


def _pose_error(current: np.ndarray, target: np.ndarray) -> np.ndarray:
    """(6,) [position error, rotation vector of target * current^T], both in the base frame."""
    rot = target[:3, :3] @ current[:3, :3].T
    angle = np.arccos(np.clip((np.trace(rot) - 1) / 2, -1.0, 1.0))
    axis = np.array([rot[2, 1] - rot[1, 2], rot[0, 2] - rot[2, 0], rot[1, 0] - rot[0, 1]])
    w = axis * (0.5 if angle < 1e-9 else angle / (2 * np.sin(angle)))
    return np.concatenate([target[:3, 3] - current[:3, 3], w])


class _Solver:
    """Solves flange poses near a reference solution on one branch."""

    def __init__(self, robot: RobotModel, tool_inv: np.ndarray, path: CartesianPath, q_start: np.ndarray):
        self.robot, self.tool_inv, self.path = robot, tool_inv, path
        self.revolute = np.array([t == "R" for t in robot.joint_types])
        self.column: int | None = None
        # The raw closed form (not wrapped into the limits) when the robot offers it: this
        # module unwraps by 2 pi itself and reports limit crossings as such.
        self._batch = getattr(robot, "ik_closed_form", None) or robot.ik_batch
        if robot.has_closed_form:
            cands = self._batch(self._flange(np.array([0.0])))[0]
            dist = np.max(np.abs(self._unwrap(cands, q_start[None, :])[:, :] - q_start), axis=1)
            dist = np.where(np.isnan(dist), np.inf, dist)
            if np.min(dist) < 1e-6:
                self.column = int(np.argmin(dist))

    def _flange(self, u: np.ndarray) -> np.ndarray:
        return self.path.poses(u) @ self.tool_inv

    def _unwrap(self, q: np.ndarray, ref: np.ndarray) -> np.ndarray:
        """Shift revolute joints by multiples of 2 pi to the value nearest ref."""
        shift = np.round((ref - q) / (2 * np.pi)) * 2 * np.pi
        return np.where(self.revolute, q + shift, q)

    def _unwrap_chain(self, sols: np.ndarray, q_start: np.ndarray) -> np.ndarray:
        """Sequential unwrap, vectorised: each row shifted by whole turns to continue from the
        row before (the first from q_start); rows from the first NaN row on are NaN. Row i's
        shift is a whole number of turns, the previous row's plus the turns nearest to the
        step between the raw rows: the same integers the row-by-row unwrap finds."""
        out = sols.copy()
        nan_rows = np.flatnonzero(np.isnan(sols[:, 0]))
        n = int(nan_rows[0]) if nan_rows.size else len(sols)
        out[n:] = np.nan
        if n == 0:
            return out
        raw = sols[:n]
        prev = np.vstack([q_start[None, :], raw[:-1]])
        turns = np.cumsum(np.round((prev - raw) / (2 * np.pi)), axis=0)
        out[:n] = np.where(self.revolute, raw + turns * 2 * np.pi, raw)
        return out

    def solve(self, u: np.ndarray, ref: np.ndarray) -> np.ndarray:
        """Joints (N, dof) at path fractions u (N,), each near ref (N, dof); NaN rows: none."""
        poses = self._flange(u)
        if self.column is not None:
            sols = self._batch(poses)[:, self.column, :]
            return self._unwrap(sols, ref)
        out = np.full(ref.shape, np.nan)
        for i, (pose, seed) in enumerate(zip(poses, ref)):
            q = newton_ik(self.robot, pose, seed)
            if q is not None:
                out[i] = q
        return out

    def solve_chain(self, u: np.ndarray, q_start: np.ndarray) -> np.ndarray:
        """Joints (N, dof) along increasing u, each solved near its predecessor."""
        if self.column is not None:
            sols = self._batch(self._flange(u))[:, self.column, :]
            return self._unwrap_chain(sols, q_start)
        out = np.full((len(u), q_start.shape[0]), np.nan)
        prev = q_start
        for i, pose in enumerate(self._flange(u)):
            q = newton_ik(self.robot, pose, prev, iters=8)
            if q is None:
                break
            out[i] = prev = q
        return out


def follow_path(
    robot: RobotModel, path: CartesianPath, tool_inv: np.ndarray, q_start: np.ndarray, tol: float = 5e-5
) -> DensePath | PathFailure:
    """Joints along `path` from q_start (dof,) on its branch; tool_inv = inv(tool.tcp) (4, 4)."""
    solver = _Solver(robot, tool_inv, path, q_start)
    n = int(max(path.length / _START_STEP, path.angle / _START_ANGLE, 1)) + 1
    u = np.linspace(0.0, 1.0, n)
    q = solver.solve_chain(u, q_start)
    q[0] = q_start
    bad_row = _first_nan(q)
    if bad_row is not None:
        return _unreachable(robot, path, tool_inv, float(u[bad_row]))
    for _ in range(_MAX_ROUNDS):
        split = _intervals_to_split(robot, path, tool_inv, u, q, tol)
        if not split.any():
            break
        small = (u[1:] - u[:-1]) < _MIN_DU
        if np.any(split & small):
            k = int(np.argmax(split & small))
            return _singular(robot, path, q[k], q[k + 1], float(u[k]))
        u, q, failure = _bisect(robot, solver, path, tool_inv, u, q, split)
        if failure is not None:
            return failure
    limit = _limit_failure(robot, path, u, q)
    if limit is not None:
        return limit
    tcp = path.positions(u)
    return DensePath(u, q, tcp)


def _first_nan(q: np.ndarray) -> int | None:
    rows = np.flatnonzero(np.isnan(q).any(axis=1))
    return int(rows[0]) if rows.size else None


def _intervals_to_split(
    robot: RobotModel, path: CartesianPath, tool_inv: np.ndarray, u: np.ndarray, q: np.ndarray, tol: float
) -> np.ndarray:
    """(M-1,) bool: intervals whose joint jump or midpoint path deviation is too large."""
    jump = np.max(np.abs(np.diff(q, axis=0)), axis=1)
    mid = 0.5 * (q[1:] + q[:-1])
    tcp = (robot.fk_batch(mid) @ np.linalg.inv(tool_inv))[:, :3, 3]
    return (jump > _MAX_JUMP) | (path.deviation(u[:-1], u[1:], tcp) > tol)


def _bisect(robot: RobotModel, solver: _Solver, path: CartesianPath, tool_inv: np.ndarray, u: np.ndarray,
            q: np.ndarray, split: np.ndarray) -> tuple[np.ndarray, np.ndarray, PathFailure | None]:
    """Insert the midpoints of the split intervals; returns (u, q, failure or None)."""
    idx = np.flatnonzero(split)
    u_mid = 0.5 * (u[idx] + u[idx + 1])
    q_mid = solver.solve(u_mid, q[idx])
    bad = np.flatnonzero(np.isnan(q_mid).any(axis=1))
    if bad.size:
        return u, q, _unreachable(robot, path, tool_inv, float(u_mid[bad[0]]))
    u_new = np.insert(u, idx + 1, u_mid)
    q_new = np.insert(q, idx + 1, q_mid, axis=0)
    return u_new, q_new, None


def _fmt_mm(p: np.ndarray) -> str:
    """A TCP position (m) as users read it: millimetres in the robot's base frame."""
    return "(" + ", ".join(f"{v * 1e3:.1f}" for v in p) + ") mm in the robot base frame"


def _unreachable(robot: RobotModel, path: CartesianPath, tool_inv: np.ndarray, u: float) -> PathFailure:
    pos = path.positions(np.array([u]))[0]
    flange = path.poses(np.array([u]))[0] @ tool_inv
    exists = True
    if robot.has_closed_form:
        batch = getattr(robot, "ik_closed_form", None) or robot.ik_batch
        exists = bool(np.any(~np.isnan(batch(flange[None])[0, :, 0])))
    if exists:
        return PathFailure(
            "singular", f"the path leaves the start's IK branch at {_fmt_mm(pos)} ({u:.0%} along the path): "
            "it passes a singularity or a branch boundary", u, pos)
    return PathFailure("unreachable", f"the path leaves the workspace at {_fmt_mm(pos)} ({u:.0%} along the path)", u, pos)


def _singular(robot: RobotModel, path: CartesianPath, qa: np.ndarray, qb: np.ndarray, u: float) -> PathFailure:
    pos = path.positions(np.array([u]))[0]
    names = _singularity_kind(robot, qa, qb)
    jump = np.degrees(np.abs(qb - qa))
    j = int(np.argmax(jump))
    return PathFailure(
        "singular",
        f"the path passes through a {names} singularity at {_fmt_mm(pos)} ({u:.0%} along the path): "
        f"joint {j + 1} would jump {jump[j]:.1f} deg at once",
        u, pos,
    )


def _singularity_kind(robot: RobotModel, qa: np.ndarray, qb: np.ndarray) -> str:
    """'shoulder', 'wrist' or 'elbow' from which joints jump (6R arms), else 'kinematic'.

    At a shoulder singularity (wrist centre on the J1 axis) joint 1 turns over, dragging the
    wrist joints with it; at a wrist singularity (J5 = 0) only joints 4 and 6 jump.
    """
    if getattr(robot, "dof", 0) != 6:
        return "kinematic"
    jump = np.abs(qb - qa)
    if jump[0] >= max(jump[1], jump[2]) and jump[0] > 0.1 * max(jump[3], jump[5]):
        return "shoulder"
    if jump[3] + jump[5] >= max(jump[1], jump[2]):
        return "wrist"
    return "elbow"


def _limit_failure(robot: RobotModel, path: CartesianPath, u: np.ndarray, q: np.ndarray) -> PathFailure | None:
    lim = robot.joint_limits
    over = np.maximum(q - lim[:, 1], lim[:, 0] - q)
    if np.all(over <= 1e-9):
        return None
    row, j = _first_over(over)
    pos = path.positions(np.array([u[row]]))[0]
    rev = robot.joint_types[j] == "R"
    conv, unit = (np.degrees, "deg") if rev else ((lambda x: x * 1e3), "mm")
    bound = lim[j, 1] if q[row, j] > lim[j, 1] else lim[j, 0]
    return PathFailure(
        "limit",
        f"joint {j + 1} must stay within its limit {conv(bound):.1f} {unit} along the path "
        f"(reaches {conv(q[row, j]):.1f} {unit} at {_fmt_mm(pos)}, {u[row]:.0%} along the path)",
        float(u[row]), pos,
    )


def _first_over(over: np.ndarray) -> tuple[int, int]:
    rows, cols = np.nonzero(over > 1e-9)
    return int(rows[0]), int(cols[0])
