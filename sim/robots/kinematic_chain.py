"""A serial pinocchio model as arrays, for vectorised FK over many configurations.

Pinocchio evaluates one configuration per call; a plan needs thousands. Each joint here is
its placement in the parent joint frame, a unit axis and a kind, and FK of N
configurations is one batched matrix product per joint.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pinocchio as pin

__all__ = ["Chain", "chain_of"]


@dataclass(frozen=True, slots=True, eq=False)
class Chain:
    placements: np.ndarray  # (n,4,4) joint i in joint i-1's frame
    axes: np.ndarray  # (n,3) unit axis in the joint frame
    prismatic: np.ndarray  # (n,) bool

    def joint_frames(self, q: np.ndarray) -> np.ndarray:
        """q: (N,n) model values -> (N,n,4,4): each joint's frame (after its motion) in base.

        In numpy (`joint_frames_vectorised`) until this process has sent fastdls.JOINT_FRAMES's
        threshold of work through it, then with the compiled loop (fastdls.joint_frames_batch,
        numba): the same arithmetic in the same order (the same floats but for the last bit
        of a sine or cosine, numba's vs the interpreter's); numpy spares a small job numba's
        ~0.6 s load. A call counts as at least _CALL_ROWS configurations
        (numpy's cost per call)."""
        from rmot.sim.robots.fastdls import JOINT_FRAMES  # late: loads subprocess only when this runs

        q = np.ascontiguousarray(np.atleast_2d(q), dtype=float)
        if not JOINT_FRAMES.prefer_compiled(max(len(q), _CALL_ROWS)):
            return self.joint_frames_vectorised(q)
        out = np.empty((q.shape[0], q.shape[1], 4, 4))
        JOINT_FRAMES.jit()(self.placements, self.axes, self.prismatic, q, out)
        return out

    def joint_frames_vectorised(self, q: np.ndarray) -> np.ndarray:
        """fastdls.joint_frames_batch's arithmetic over all configurations at once: each 4x4
        product summed left to right as `_mul4` does, each rotation by `_rotation`'s formula
        with the sine and cosine from `math`: the interpreted loop's floats, bit for bit."""
        q = np.atleast_2d(q)
        n_cfg, n = q.shape
        out = np.empty((n_cfg, n, 4, 4))
        t = np.broadcast_to(np.eye(4), (n_cfg, 4, 4))
        motion = np.zeros((n_cfg, 4, 4))
        motion[:, 3, 3] = 1.0
        for i in range(n):
            t = _mul4(t, np.broadcast_to(self.placements[i], (n_cfg, 4, 4)))
            x, y, z = (float(v) for v in self.axes[i])
            if self.prismatic[i]:
                motion[:, :3, :3] = np.eye(3)
                motion[:, 0, 3] = x * q[:, i]
                motion[:, 1, 3] = y * q[:, i]
                motion[:, 2, 3] = z * q[:, i]
            else:
                angles = q[:, i].tolist()
                c = np.array([math.cos(a) for a in angles])
                s = np.array([math.sin(a) for a in angles])
                v = 1.0 - c
                m = motion
                m[:, 0, 0], m[:, 0, 1] = c + x * x * v, x * y * v - z * s
                m[:, 0, 2], m[:, 1, 0] = x * z * v + y * s, y * x * v + z * s
                m[:, 1, 1], m[:, 1, 2] = c + y * y * v, y * z * v - x * s
                m[:, 2, 0], m[:, 2, 1] = z * x * v - y * s, z * y * v + x * s
                m[:, 2, 2] = c + z * z * v
                motion[:, :3, 3] = 0.0
            t = _mul4(t, motion)
            out[:, i] = t
        return out

    def joint_frames_numpy(self, q: np.ndarray) -> np.ndarray:
        """The same product in numpy (the reference the compiled loop is tested against)."""
        q = np.atleast_2d(q)
        n_cfg, n = q.shape
        out = np.empty((n_cfg, n, 4, 4))
        current = np.broadcast_to(np.eye(4), (n_cfg, 4, 4))
        for i in range(n):
            motion = _motion(self.axes[i], q[:, i], bool(self.prismatic[i]))
            current = (current @ self.placements[i]) @ motion
            out[:, i] = current
        return out


_CALL_ROWS = 64  # numpy's overhead per call, in configurations (see joint_frames)


def _mul4(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """(N,4,4) @ (N,4,4), each entry a[i,0] b[0,j] + a[i,1] b[1,j] + a[i,2] b[2,j] + a[i,3] b[3,j]
    summed left to right (fastdls._mul4's order; numpy's matmul may sum in another)."""
    out: np.ndarray = (a[:, :, 0, None] * b[:, None, 0] + a[:, :, 1, None] * b[:, None, 1]
                       + a[:, :, 2, None] * b[:, None, 2] + a[:, :, 3, None] * b[:, None, 3])
    return out


def _motion(axis: np.ndarray, q: np.ndarray, prismatic: bool) -> np.ndarray:
    m = np.zeros((len(q), 4, 4))
    m[:, 3, 3] = 1.0
    if prismatic:
        m[:, 0, 0] = m[:, 1, 1] = m[:, 2, 2] = 1.0
        m[:, :3, 3] = q[:, None] * axis
        return m
    c, s = np.cos(q), np.sin(q)
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    kk = k @ k
    m[:, :3, :3] = np.eye(3) + s[:, None, None] * k + (1 - c)[:, None, None] * kk
    return m


_AXES = {"X": (1.0, 0.0, 0.0), "Y": (0.0, 1.0, 0.0), "Z": (0.0, 0.0, 1.0)}


def chain_of(model: pin.Model) -> Chain:
    """The arrays of a serial model of 1-dof revolute/prismatic joints (raises ValueError)."""
    placements, axes, prismatic = [], [], []
    for jid in range(1, model.njoints):
        if model.parents[jid] != jid - 1:
            raise ValueError("the model is not a serial chain (a joint branches off an earlier link)")
        joint = model.joints[jid]
        short = joint.shortname()
        if joint.nq != 1 or joint.nv != 1:
            raise ValueError(f"joint '{model.names[jid]}' must have one degree of freedom (got {short})")
        if short.startswith(("JointModelR", "JointModelP")) and short[-1] in _AXES and "Unaligned" not in short:
            axis = np.array(_AXES[short[-1]])
        elif "Unaligned" in short:
            axis = np.asarray(joint.extract().axis, dtype=float)
        else:
            raise ValueError(f"joint '{model.names[jid]}' must be revolute or prismatic (got {short})")
        placements.append(model.jointPlacements[jid].homogeneous)
        axes.append(axis / np.linalg.norm(axis))
        prismatic.append(short.startswith("JointModelP"))
    return Chain(np.array(placements), np.array(axes), np.array(prismatic))
