"""Bounds for the broad phase and the no-miss guarantee (see collide.py).

  * joint motion per interval, in the kinematic model's joint space, with the padding for
    the true path's deviation from the linear interpolation of the samples;
  * per pair, weights w with: relative motion of two bodies <= Σ_j |Δq_j| w_j;
  * lower bounds on the distance of two bodies: per block of samples (one sphere per body
    holding it over the block) and per sample (sphere covers against fixture boxes).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from rmot.sim.scene import Body, Scene

if TYPE_CHECKING:
    from rmot.sim.collide import Timeline

__all__ = ["BLOCK", "LazyCentres", "block_bound", "block_spheres", "joint_motion", "lower_bound", "model_abs",
           "model_q", "pair_reach", "world_spheres"]


def joint_motion(scene: Scene, robot: str, timeline: Timeline) -> tuple[np.ndarray, np.ndarray]:
    """(|Δq| (M-1, dof), pad (M-1, dof)) per interval in model joint space; pad bounds how far
    the true path strays from the linear interpolation of the samples: max|qdd|·dt²/8."""
    q = model_q(scene, robot, timeline.q[robot])
    dt = np.diff(timeline.t)
    acc = timeline.accel[robot]
    pad = model_abs(scene, robot, np.maximum(acc[:-1], acc[1:]) * (dt[:, None] ** 2) / 8.0)
    return np.abs(np.diff(q, axis=0)), pad

def pair_reach(scene: Scene, a: Body, b: Body) -> dict[str, np.ndarray]:
    """robot -> (dof,) weights w with: relative motion of a and b <= Σ_j |Δq_j| w_j.

    Bodies of one robot only move relative to each other through the joints between them
    (the joints before both carry them together), so for a pair of one serial robot only
    the joints in (lower joint, upper joint] count, with the upper body's reach."""
    out: dict[str, np.ndarray] = {}
    if a.robot is not None and a.robot == b.robot:
        low, high = (a, b) if a.joint <= b.joint else (b, a)
        mask = np.zeros(scene.robots[a.robot].robot.dof)
        mask[low.joint:high.joint] = 1.0  # joints low.joint+1 .. high.joint (1-based)
        out[a.robot] = high.reach * mask
        return out
    for body in (a, b):
        if body.moves:
            assert body.robot is not None and body.reach is not None  # a moving body is a robot's
            out[body.robot] = out.get(body.robot, 0.0) + body.reach
    return out

_GRAM_SLACK = 1e-6  # m: covers the rounding of the squared-distance expansion in lower_bound
BLOCK = 16  # samples per block of the coarse (block) broad phase


def block_spheres(body: Body, poses: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per block of BLOCK samples, one sphere holding the body at every sample of the block:
    (nB, 3) centres, (nB,) radii (built on the body's single bounding sphere)."""
    assert body.spheres is not None  # moving bodies carry their sphere cover
    centre = body.spheres[:, :3].mean(axis=0)
    radius = float(np.max(np.linalg.norm(body.spheres[:, :3] - centre, axis=1) + body.spheres[:, 3]))
    track = poses[:, :3, :3] @ centre + poses[:, :3, 3]  # (M, 3)
    m = track.shape[0]
    n_blocks = -(-m // BLOCK)
    padded = np.concatenate([track, np.repeat(track[-1:], n_blocks * BLOCK - m, axis=0)])
    blocks = padded.reshape(n_blocks, BLOCK, 3)
    mid = (blocks.max(axis=1) + blocks.min(axis=1)) / 2
    spread = np.sqrt(np.max(np.sum((blocks - mid[:, None]) ** 2, axis=-1), axis=1))
    return mid, spread + radius


def block_bound(a: Body, b: Body, blocks: dict[str, tuple[np.ndarray, np.ndarray]]) -> np.ndarray:
    """(nB,) a lower bound on the pair's distance over each block of samples."""
    if b.kind == "fixture":
        a, b = b, a
    cb, rb = blocks[b.name]
    if a.kind == "fixture":
        return point_box_distance(a, cb) - rb
    ca, ra = blocks[a.name]
    return np.linalg.norm(ca - cb, axis=-1) - ra - rb


def point_box_distance(fixture: Body, points: np.ndarray) -> np.ndarray:
    """Distance from world points (..., 3) to the fixture's bounding box (0 inside)."""
    box = fixture.local.copy()
    box[:3, 3] += box[:3, :3] @ fixture.obb_centre
    local = (points - box[:3, 3]) @ box[:3, :3]
    gap = np.maximum(np.abs(local) - fixture.obb_half, 0.0)
    return np.sqrt(np.einsum("...i,...i->...", gap, gap))


def lower_bound(a: Body, b: Body, pa: np.ndarray, pb: np.ndarray,
                 centres: dict[str, np.ndarray] | None = None, idx: np.ndarray | None = None) -> np.ndarray:
    """(M,) a lower bound on the distance between a and b at every sample (m) — or at the
    samples `idx` only. `centres`: world sphere centres already computed, by body name.

    Computed BOUND_CHUNK samples at a time: a pair of two sphere covers needs (samples, Ka, Kb)
    temporaries, ~0.4 KB a sample for 7 x 7 spheres; each sample's bound is the
    same arithmetic on its own row either way."""
    if b.kind == "fixture":
        a, b, pa, pb = b, a, pb, pa
    count = pb.shape[0] if idx is None else idx.shape[0]
    if count <= BOUND_CHUNK:
        return _lower_bound_rows(a, b, pa, pb, {} if centres is None else centres, idx)
    out = np.empty(count)
    rows = np.arange(count) if idx is None else idx
    for lo in range(0, count, BOUND_CHUNK):
        out[lo:lo + BOUND_CHUNK] = _lower_bound_rows(a, b, pa, pb, {} if centres is None else centres,
                                                     rows[lo:lo + BOUND_CHUNK])
    return out


BOUND_CHUNK = 16_384  # samples per block of lower_bound


def _lower_bound_rows(a: Body, b: Body, pa: np.ndarray, pb: np.ndarray, centres: dict[str, np.ndarray],
                      idx: np.ndarray | None) -> np.ndarray:
    """lower_bound at the samples `idx` (None: all), b moving and a not a fixture unless b is."""
    assert b.spheres is not None  # b moves (of a pair, the fixture is a)
    if b.name in centres:
        centres_b = centres[b.name] if idx is None else centres[b.name][idx]
    else:
        centres_b = world_spheres(b, pb if idx is None else pb[idx])
    if a.kind == "fixture":
        return np.min(point_box_distance(a, centres_b) - b.spheres[:, 3], axis=-1)
    assert a.spheres is not None
    if a.name in centres:
        centres_a = centres[a.name] if idx is None else centres[a.name][idx]
    else:
        centres_a = world_spheres(a, pa if idx is None else pa[idx])
    # |ca - cb|² by one batched product (no (M, Ka, Kb, 3) temporary); its rounding error is
    # at most ~1e-15 m² for a cell of a few metres, so _GRAM_SLACK keeps the bound below
    norm_a = np.einsum("mai,mai->ma", centres_a, centres_a)
    norm_b = np.einsum("mbi,mbi->mb", centres_b, centres_b)
    sq = norm_a[:, :, None] + norm_b[:, None, :] - 2.0 * np.matmul(centres_a, centres_b.transpose(0, 2, 1))
    dist = np.sqrt(np.maximum(sq, 0.0)) - (a.spheres[:, None, 3] + b.spheres[None, :, 3])
    return np.min(dist.reshape(dist.shape[0], -1), axis=1) - _GRAM_SLACK


class LazyCentres(dict[str, np.ndarray]):
    """name -> (M, K, 3) world sphere centres, computed for a body when first asked for."""

    def __init__(self, scene: Scene, poses: dict[str, np.ndarray]) -> None:
        super().__init__()
        self._scene, self._poses = scene, poses

    def __contains__(self, name: object) -> bool:
        return name in self._poses and self._poses[name].shape[0] > 1

    def __missing__(self, name: str) -> np.ndarray:
        value = world_spheres(self._scene.body(name), self._poses[name])
        self[name] = value
        return value


def world_spheres(body: Body, poses: np.ndarray) -> np.ndarray:
    """(M, K, 3) sphere centres in world."""
    assert body.spheres is not None
    return np.matmul(body.spheres[None, :, :3], poses[:, :3, :3].transpose(0, 2, 1)) + poses[:, None, :3, 3]


def model_q(scene: Scene, robot: str, q: np.ndarray) -> np.ndarray:
    """Controller joint values -> the kinematic model's (a linear map: Fanuc's J2/J3 coupling);
    the reach bounds are per model joint."""
    to_model = getattr(scene.robots[robot].robot, "to_model", None)
    return np.asarray(to_model(q)) if to_model is not None else q


def model_abs(scene: Scene, robot: str | None, v: np.ndarray) -> np.ndarray:
    """Bound on |model-space vector| from |controller-space vector| v (..., dof): |C| v."""
    entry = scene.robots[robot]  # type: ignore[index]
    coupling = np.abs(model_q(scene, entry.name, np.eye(entry.robot.dof)))  # row k = C e_k
    return v @ coupling


