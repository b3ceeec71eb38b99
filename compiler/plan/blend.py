"""Zones: a chain of moves joined into one joint path, corners blended inside the zone sphere.

At the corner between move A and move B (A's zone radius r > 0), the radius used is
min(r, half of A's TCP path length, half of B's). The blend replaces the part of A inside the
sphere of that radius around the corner (A's target TCP) and the part of B inside it: it
cross-fades in joint space from A's path to B's path,

    q(l) = (1 - w(l)) qA(l) + w(l) qB(l),  w = 3 l^2 - 2 l^3 (smoothstep),  l in [0, 1],

where qA runs along A from the zone entry to the corner and qB along B from the corner to the
zone exit. The blend leaves A tangentially and joins B tangentially, and being a convex
combination of in-limit joints it stays within the joint limits. Its TCP is checked to stay in
the sphere; if it does not, the radius is halved (up to 3 times) before the corner falls back
to an exact stop with a warning (W222).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from rmot.compiler.plan import codes
from rmot.compiler.plan.segments import Segment
from rmot.compiler.plan.targets import Finding
from rmot.lang.diagnostics import Severity
from rmot.compiler.plan.robot_model import RobotModel

__all__ = ["ChainPath", "blend_chain"]

_HALVINGS = 3
_BLEND_STEP = 0.01  # rad between blend samples
_TCP_WEIGHT = 5.0  # TCP length's weight over the joints' in a TCP-parametrised step (see _parameter)


@dataclass(frozen=True, eq=False)
class ChainPath:
    """The joined path: q (M, dof), tcp (M, 3), c (M,) the TCP-time coordinate (s: TCP path
    length over programmed speed, constant along joint moves), ss (M,) the path parameter
    (TCP length along Cartesian moves and the blends between them, joint arc length
    elsewhere, see _parameter), vscale (M,) the share of
    the joint velocity limits at each point (a joint move's joint_speed; the smaller of the two
    moves' in a blend). Per segment: `starts`/`ends`
    chain indexes (end = zone entry when blended), `radii` the blend radius used (m)."""

    q: np.ndarray
    tcp: np.ndarray
    c: np.ndarray
    ss: np.ndarray
    vscale: np.ndarray
    starts: tuple[int, ...]
    ends: tuple[int, ...]
    radii: tuple[float, ...]
    findings: tuple[tuple[int, Finding], ...] = field(default=())
    # (M,) per point: the TCP speed limit (m/s, inf along joint moves) and the TCP path
    # acceleration limit (m/s^2, inf along joint moves). Inside a blend the Cartesian move's
    # (the smaller of the two when both are Cartesian): the TCP never exceeds a programmed speed.
    tcp_speed: np.ndarray | None = None
    tcp_accel: np.ndarray | None = None


def _along(q: np.ndarray, lam: np.ndarray) -> np.ndarray:
    """Points at fractions lam (N,) of the polyline q (M, dof) by joint-space arc length."""
    if len(q) == 1:
        return np.repeat(q, len(lam), axis=0)
    d = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(q, axis=0), axis=1))])
    if d[-1] <= 0:
        return np.repeat(q[:1], len(lam), axis=0)
    x = lam * d[-1]
    return np.stack([np.interp(x, d, q[:, j]) for j in range(q.shape[1])], axis=1)


def _crossing(robot: RobotModel, tool: np.ndarray, qa: np.ndarray, qb: np.ndarray, corner: np.ndarray, r: float) -> np.ndarray:
    """Joints on the joint-space segment qa (outside the sphere) -> qb (inside) whose TCP lies
    on the sphere of radius r around corner (bisection; the segment is short). Single FK calls
    (pinocchio, ~2 us) with the TCP and its distance computed without 4x4 products: a batched
    FK costs more per point than it saves at these sizes (measured)."""
    lo, hi = 0.0, 1.0
    dq = qb - qa
    at_tcp = tool[:3, 3]
    fk = robot.fk
    for _ in range(30):
        mid = 0.5 * (lo + hi)
        m = fk(qa + mid * dq)
        d = m[:3, :3] @ at_tcp + m[:3, 3] - corner  # (flange @ tool) translation - corner
        lo, hi = (mid, hi) if math.sqrt(d @ d) > r else (lo, mid)
    return qa + hi * dq


@dataclass(frozen=True, eq=False)
class _Part:
    """A segment's remaining path: q (M, dof), tcp (M, 3)."""

    q: np.ndarray
    tcp: np.ndarray


def _blend(robot, a: _Part, b: _Part, r: float, tool: np.ndarray):  # type: ignore[no-untyped-def]
    """(A's kept part, blend q (K, dof), blend tcp (K, 3), B's remaining part) or None."""
    corner = a.tcp[-1]
    out_a = np.flatnonzero(np.linalg.norm(a.tcp - corner, axis=1) > r)
    out_b = np.flatnonzero(np.linalg.norm(b.tcp - corner, axis=1) > r)
    if not out_a.size or not out_b.size:
        return None
    k, m = int(out_a[-1]), int(out_b[0])
    q_in = _crossing(robot, tool, a.q[k], a.q[k + 1], corner, r)
    q_out = _crossing(robot, tool, b.q[m], b.q[m - 1], corner, r)
    qa_part = np.vstack([q_in, a.q[k + 1:]])
    qb_part = np.vstack([b.q[:m], q_out])
    span = np.linalg.norm(np.diff(qa_part, axis=0), axis=1).sum() + np.linalg.norm(np.diff(qb_part, axis=0), axis=1).sum()
    lam = np.linspace(0.0, 1.0, max(9, int(span / _BLEND_STEP) + 1))
    w = (3 * lam**2 - 2 * lam**3)[:, None]
    q = (1 - w) * _along(qa_part, lam) + w * _along(qb_part, lam)
    tcp = (robot.fk_batch(q) @ tool)[:, :3, 3]
    if np.max(np.linalg.norm(tcp - corner, axis=1)) > r * (1 + 1e-6) + 1e-9:
        return None
    keep = _Part(np.vstack([a.q[: k + 1], q_in]), np.vstack([a.tcp[: k + 1], tcp[0]]))
    rest = _Part(np.vstack([q_out, b.q[m:]]), np.vstack([tcp[-1], b.tcp[m:]]))
    return keep, q[1:-1], tcp[1:-1], rest


@dataclass
class _Columns:
    """The chain's per-point columns, appended piece by piece so they stay aligned."""
    q: list[np.ndarray] = field(default_factory=list)
    tcp: list[np.ndarray] = field(default_factory=list)
    rate: list[np.ndarray] = field(default_factory=list)
    accel: list[np.ndarray] = field(default_factory=list)
    uniform: list[np.ndarray] = field(default_factory=list)
    factor: list[np.ndarray] = field(default_factory=list)
    by_tcp: list[np.ndarray] = field(default_factory=list)
    count: int = 0

    def add(self, q: np.ndarray, tcp: np.ndarray, rate: float, accel: float, uniform: bool, factor: float,
            by_tcp: bool) -> None:
        n = len(q)
        self.q.append(q)
        self.tcp.append(tcp)
        self.rate.append(np.full(n, rate))
        self.accel.append(np.full(n, accel))
        self.uniform.append(np.full(n, uniform))
        self.factor.append(np.full(n, factor))
        self.by_tcp.append(np.full(n, by_tcp))
        self.count += n


def blend_chain(robot: RobotModel | None, segments: list[Segment]) -> ChainPath:
    """Join a chain of segments (each starting where the previous one ends) into one path."""
    cols = _Columns()
    ends: list[int] = []
    radii: list[float] = []
    findings: list[tuple[int, Finding]] = []
    part = _Part(segments[0].q, segments[0].tcp)
    for i, seg in enumerate(segments):
        blend, used, nxt = None, 0.0, None
        if i + 1 < len(segments):
            nxt = _Part(segments[i + 1].q, segments[i + 1].tcp)
            if not seg.move.motion.zone.is_fine:
                blend, used = _corner(robot, seg, segments[i + 1], part, nxt, findings, i)
        keep = blend[0] if blend is not None else part
        cols.add(keep.q if i == 0 else keep.q[1:], keep.tcp if i == 0 else keep.tcp[1:], seg.tcp_rate,
                 _tcp_accel(seg), False, seg.speed_factor, seg.tcp_rate > 0)
        ends.append(cols.count - 1)
        radii.append(used)
        if blend is not None:
            _, qb, tb, nxt = blend
            after = segments[i + 1]
            both = seg.tcp_rate > 0 and after.tcp_rate > 0
            cols.add(qb, tb, max(seg.tcp_rate, after.tcp_rate), min(_tcp_accel(seg), _tcp_accel(after)), True,
                     min(seg.speed_factor, after.speed_factor), both)
            # the blend's last point joins the next part, whose first point (q_out) is kept; that
            # zone exit has the next move's limits: limits apply per interval as the smaller of its
            # two ends (timing.path_piece), so the blend's limits end exactly at the sphere
            cols.add(nxt.q[:1], nxt.tcp[:1], after.tcp_rate, _tcp_accel(after), True, after.speed_factor, both)
        part = nxt if nxt is not None else part
    return _chain_path(segments, cols, ends, radii, findings)


def _chain_path(segments: list[Segment], cols: _Columns, ends: list[int], radii: list[float],
                findings: list[tuple[int, Finding]]) -> ChainPath:
    """The joined columns as a ChainPath: arc length weighted by the TCP rate, and the path parameter."""
    q, tcp, rate = np.concatenate(cols.q), np.concatenate(cols.tcp), np.concatenate(cols.rate)
    step_rate = np.maximum(rate[1:], rate[:-1])
    c = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(tcp, axis=0), axis=1) * step_rate)])
    # TCP length as the parameter only in all-Cartesian chains: where a joint move joins in,
    # the change of parameter scale at its blends costs more time than it saves (measured)
    all_cartesian = all(s.tcp_rate > 0 for s in segments)
    ss = _parameter(q, tcp, np.concatenate(cols.uniform), np.concatenate(cols.by_tcp) & all_cartesian)
    vscale = np.concatenate(cols.factor)
    starts = [0] + ends[:-1]  # a move starts where the previous one ends (its zone entry)
    with np.errstate(divide="ignore"):
        speed = np.where(rate > 0, 1.0 / np.where(rate > 0, rate, 1.0), np.inf)
    return ChainPath(q, tcp, c, ss, vscale, tuple(starts), tuple(ends), tuple(radii), tuple(findings),
                     speed, np.concatenate(cols.accel))


def _tcp_accel(seg: Segment) -> float:
    """The TCP path acceleration limit of a Cartesian move (m/s^2), inf for a joint move."""
    return float(seg.move.motion.tcp_accel) if seg.tcp_rate > 0 else float("inf")


def _parameter(q: np.ndarray, tcp: np.ndarray, in_blend: np.ndarray, by_tcp: np.ndarray) -> np.ndarray:
    """(M,) path parameter, per step: along Cartesian moves and the blends between them, the
    TCP path length (scaled to joint units, see below); elsewhere the joint arc length.
    A step belongs to a blend (or to the TCP-parametrised part) when its end point does.

    Why TCP length along Cartesian moves: the path is a cubic spline in s, and the spline
    rings where dq/ds jumps. With s = joint arc length, dq/ds is a unit vector whose direction
    jumps where a line meets an arc that turns the tool, and the TCP, far more sensitive to
    the arc's joint motion than to the line's, wobbled by up to 40 % over several mm of the
    line beside the blend. With s = TCP length the jump in dq/ds moves the TCP (its position
    rate is continuous there): the ringing stays in the orientation, to second order. The
    step is hypot(k |dp|, |dq|) with k = 5 x the largest joint step per TCP metre of the
    part: TCP length to within 2 % everywhere, with no change of regime (a parameter that
    switched from TCP to joint length near a singularity, where the joints race, rang into
    huge joint accelerations), and the joint length where the TCP stands still (a pure
    reorientation). Inside a blend sqrt(step^2 + (eps dl)^2) keeps the path smooth (and
    the path with it) even where a blend turns back on itself (step -> 0 at a reversal), yet
    within 2 % of the step elsewhere (eps = 0.2 x the blend's mean step)."""
    step = np.linalg.norm(np.diff(q, axis=0), axis=1)
    flags = by_tcp[1:]
    if np.any(flags):
        along = np.linalg.norm(np.diff(tcp, axis=0), axis=1)
        moving = flags & (along > 1e-9)
        ratio = float(np.max(step[moving] / along[moving])) if np.any(moving) else 0.0
        step = np.where(flags, np.hypot(_TCP_WEIGHT * ratio * along, step), step)
    flags = in_blend[1:]
    edges = np.flatnonzero(np.diff(np.concatenate([[0], flags.astype(int), [0]])))
    for a, b in zip(edges[::2], edges[1::2]):
        floor = 0.2 * step[a:b].mean()
        step[a:b] = np.sqrt(step[a:b] ** 2 + floor**2)
    return np.concatenate([[0.0], np.cumsum(step)])


def _corner(robot, a: Segment, b: Segment, pa: _Part, pb: _Part, findings: list[tuple[int, Finding]], i: int):  # type: ignore[no-untyped-def]
    """The blend at the corner a -> b, halving the radius if the TCP leaves the sphere."""
    tool = a.move.tool.tcp.matrix()
    r = min(a.move.motion.zone.radius, 0.5 * a.tcp_length, 0.5 * b.tcp_length)
    if r <= 1e-6:
        return None, 0.0
    for _ in range(_HALVINGS + 1):
        blend = _blend(robot, pa, pb, r, tool)
        if blend is not None:
            return blend, r
        r *= 0.5
    msg = (f"zone {a.move.motion.zone.radius * 1e3:.1f} mm cannot be blended inside its sphere at this "
           "corner; the robot stops exactly at the target")
    findings.append((i, Finding(codes.BLEND_REDUCED, Severity.WARNING, msg)))
    return None, 0.0
