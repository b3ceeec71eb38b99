"""Findings in pictures: which bodies to mark, where they touch, and the caption.

A verification finding (a Diagnostic with a time and bodies) becomes a `Marking`: its event
interval, its worst instant, the bodies, the contact point at the worst instant (the middle
of the closest pair of surface points of the first two bodies, from points sampled on their
posed meshes) and a caption "E300 line 41 t=3.41 s 29.4 mm: message".

Findings of one event are merged first (`events`): the same code and bodies over intervals
that touch or nearly touch are one event (the checker may report a long contact in pieces,
e.g. one per move it spans), so a picture is made per event, not per sample interval.

Marking a picture: pixels of a marked body are tinted red; within `radius` of the contact
point they are painted strongly red, so a large fixture shows where it is hit rather than
turning red all over. Robot links and tools (small, and what moved into the contact) are
painted strongly red whole. Rendering only draws: markings never change a finding.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass, replace

import numpy as np

from rmot.lang.diagnostics import Diagnostic
from rmot.sim.render.pipeline import Picture
from rmot.sim.render.scene import HIGHLIGHT, RenderScene
from rmot.sim.render.transform import eye_depth, transform_points

__all__ = ["Marking", "active", "contact_point", "events", "finding_caption", "mark_picture", "markings",
           "worst_instant"]

GAP = 0.25  # s: findings of the same code and bodies closer than this in time are one event
WINDOW = 0.3  # s: a finding is marked this long before and after its interval in animations


@dataclass(frozen=True, eq=False)
class Marking:
    diagnostic: Diagnostic
    t0: float
    t1: float
    worst: float
    bodies: tuple[str, ...]
    caption: str
    contact: np.ndarray | None = None  # (3,) world point at the worst instant
    radius: float = 0.05  # m: the strongly marked region around the contact


def worst_instant(diagnostic: Diagnostic) -> float | None:
    """When the finding is worst: the deepest contact or closest approach where the checker
    recorded it (peak_time_s), else the start of its interval."""
    return diagnostic.peak_time_s if diagnostic.peak_time_s is not None else diagnostic.time_s


def finding_caption(diagnostic: Diagnostic) -> str:
    """'E300 line 41 t=3.41 s 29.4 mm: message' (parts without data are left out)."""
    parts = [diagnostic.code.id]
    if diagnostic.span is not None:
        parts.append(f"line {diagnostic.span.start.line}")
    instant = worst_instant(diagnostic)
    if instant is not None:
        parts.append(f"t={instant:.2f} s")
    if diagnostic.amount is not None:
        parts.append(f"{diagnostic.amount.value:g} {diagnostic.amount.unit}")
    return " ".join(parts) + f": {diagnostic.message}"


def _amount(d: Diagnostic) -> float:
    return abs(d.amount.value) if d.amount is not None else 0.0


def events(diagnostics: Iterable[Diagnostic]) -> tuple[Diagnostic, ...]:
    """Findings with a time merged into events: same code and bodies, intervals within GAP s.

    The event keeps the worst piece's message, amount and worst instant, over the union of
    the intervals. Findings without a time are left out (there is no instant to show).
    """
    timed = sorted((d for d in diagnostics if d.time_s is not None),
                   key=lambda d: (d.code.id, tuple(sorted(d.bodies)), d.time_s))
    out: list[Diagnostic] = []
    for d in timed:
        assert d.time_s is not None  # `timed` holds timed findings only
        prev = out[-1] if out else None
        def end(x: Diagnostic) -> float:
            return x.end_time_s if x.end_time_s is not None else x.time_s  # type: ignore[return-value]
        if (prev is not None and prev.code == d.code and sorted(prev.bodies) == sorted(d.bodies)
                and d.time_s <= end(prev) + GAP):
            worst = d if _amount(d) > _amount(prev) else prev
            merged = replace(worst, time_s=prev.time_s, end_time_s=max(end(prev), end(d)),
                             peak_time_s=worst_instant(worst))
            out[-1] = merged
        else:
            out.append(d)
    return tuple(sorted(out, key=lambda d: (d.time_s, d.code.id)))


def _surface_points(vertices: np.ndarray, spacing: float = 0.01, most: int = 24) -> np.ndarray:
    """Points on triangles (T, 3, 3) about `spacing` m apart (at most `most` per edge)."""
    edge = np.max(np.linalg.norm(vertices - np.roll(vertices, 1, axis=1), axis=2), axis=1)
    pts = [vertices.reshape(-1, 3)]
    for n in np.unique(np.clip(np.ceil(edge / spacing), 1, most).astype(int)):
        if n < 2:
            continue
        i, j = np.meshgrid(np.arange(n + 1), np.arange(n + 1), indexing="ij")
        keep = i + j <= n
        b1, b2 = i[keep] / n, j[keep] / n
        b0 = 1.0 - b1 - b2
        tris = vertices[np.ceil(edge / spacing).clip(1, most).astype(int) == n]
        pts.append((b0[None, :, None] * tris[:, None, 0] + b1[None, :, None] * tris[:, None, 1]
                    + b2[None, :, None] * tris[:, None, 2]).reshape(-1, 3))
    return np.concatenate(pts)


def contact_point(rs: RenderScene, poses: np.ndarray, a: str, b: str) -> np.ndarray | None:
    """The middle of the closest pair of surface points of bodies a and b at poses (B, 4, 4)."""
    from scipy.spatial import cKDTree  # late: scipy is heavy or optional, loaded only where used

    if a not in rs.names or b not in rs.names:
        return None
    ia, ib = rs.names.index(a), rs.names.index(b)
    if len(rs.meshes[ia]) == 0 or len(rs.meshes[ib]) == 0:
        return None
    pa = _surface_points(transform_points(poses[ia], rs.meshes[ia].vertices))
    pb = _surface_points(transform_points(poses[ib], rs.meshes[ib].vertices))
    dist, idx = cKDTree(pb).query(pa)
    k = int(np.argmin(dist))
    return 0.5 * (pa[k] + pb[idx[k]])


def markings(rs: RenderScene, diagnostics: Iterable[Diagnostic]) -> tuple[Marking, ...]:
    """A Marking per event of the findings that name bodies of this scene and have a time."""
    from rmot.sim.render.scene import body_poses  # late: loads pinocchio only when this runs

    out = []
    for d in events(diagnostics):
        bodies = tuple(b for b in d.bodies if b in rs.names)
        assert d.time_s is not None  # events() keeps timed findings only
        t0 = float(d.time_s)
        t1 = float(d.end_time_s) if d.end_time_s is not None else t0
        worst = float(worst_instant(d) or t0)
        contact = None
        if len(bodies) >= 2:
            contact = contact_point(rs, body_poses(rs, np.array([worst]))[0], bodies[0], bodies[1])
        depth = _amount(d) / 1000.0 if d.amount is not None and d.amount.unit == "mm" else 0.0
        out.append(Marking(d, t0, t1, worst, bodies, finding_caption(d), contact, max(0.05, 3.0 * depth)))
    return tuple(out)


def active(marks: Sequence[Marking], time: float, window: float = WINDOW) -> tuple[Marking, ...]:
    """The markings to show at `time` s: those whose interval (widened by `window`) holds it."""
    return tuple(m for m in marks if m.t0 - window - 1e-9 <= time <= m.t1 + window + 1e-9)


def body_owner(rs: RenderScene) -> np.ndarray:
    """(T,) body index of each triangle of scene.soup's output (-1 for the floor)."""
    return np.concatenate([np.full(len(rs.floor), -1)] + [np.full(len(m), i) for i, m in enumerate(rs.meshes)])


def unproject(picture: Picture) -> np.ndarray:
    """The world point (kH, kW, 3) under each pixel centre of a picture (NaN where empty)."""
    depth = picture.frame.depth.astype(np.float64)
    height, width = depth.shape
    near, far = picture.camera.depth_range() if picture.camera is not None else (0.05, 100.0)
    cols, rows = np.meshgrid(np.arange(width) + 0.5, np.arange(height) + 0.5)
    x, y = 2.0 * cols / width - 1.0, 1.0 - 2.0 * rows / height
    with np.errstate(invalid="ignore"):
        d = eye_depth(depth, near, far)  # w_clip
        clip = np.stack([x * d, y * d, depth * d, d], axis=2)
    world = clip @ np.linalg.inv(picture.matrix).T
    return world[..., :3] / world[..., 3:4]


def mark_picture(picture: Picture, rs: RenderScene, marks: Sequence[Marking]) -> None:
    """Paint the marked bodies into picture.color in place (see the module docstring);
    the picture must be of scene.soup's triangles."""
    source, color = picture.source, picture.color
    if not marks or len(source) == 0:
        return
    tri = picture.frame.tri
    covered = tri >= 0
    owner = body_owner(rs)[source][np.maximum(tri, 0)]
    owner[~covered] = -1
    red = np.asarray(HIGHLIGHT, np.float32)
    kinds = [getattr(b, "kind", "") for b in rs.scene.bodies]
    position = None
    for m in marks:
        for name in m.bodies:
            i = rs.names.index(name)
            mask = owner == i
            if not mask.any():
                continue
            if kinds[i] != "fixture" or m.contact is None:
                color[mask] = 0.2 * color[mask] + 0.8 * red
                continue
            if position is None:  # the world point under each pixel, for the contact region
                position = unproject(picture)
            near = mask & (np.linalg.norm(position - m.contact, axis=2) <= m.radius)
            color[mask & ~near] = 0.6 * color[mask & ~near] + 0.4 * red
            color[near] = 0.2 * color[near] + 0.8 * red


def verified_markings(rs: RenderScene) -> tuple[tuple[Marking, ...], tuple[Diagnostic, ...]]:
    """Verify the scene's plan (rmot.sim.verify) and mark its findings: (markings, findings).

    A verification that cannot run leaves the pictures unmarked (the caller's `rmot check`
    is where verification problems are reported)."""
    try:
        from rmot.sim import verify  # late: optional, tried where used

        found = tuple(verify(rs.plan).diagnostics)
    except Exception:
        return (), ()
    return markings(rs, found), found
