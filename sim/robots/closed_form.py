"""A robot's closed-form IK as data: which kernel (OPW or UR), its parameter arrays, and the
fixed transforms around it, so that the single-pose solver (`fastsolve`) can run the same
kernel inside its own compiled loop instead of calling through a closure.

Calling a ClosedForm is what the closures in `build` and `model_opw` did before: the kernel
of `fastik` on `pre @ poses @ post` (each product only where given), numba loaded only when
the kernel decides to compile (lang/jit.py)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["ClosedForm"]


@dataclass(frozen=True, eq=False)
class ClosedForm:
    """kind "opw": args = fastik.opw_kernel_args(params, joint map); kind "ur": args =
    (d1, a2, a3, d4, d5, d6) as one array. pre / post: (4,4) applied as pre @ pose @ post.
    branch: the arrays of the branch quantities (see `fastsolve`)."""

    kind: str
    args: tuple[np.ndarray, ...]
    pre: np.ndarray | None = None
    post: np.ndarray | None = None
    branch: tuple[np.ndarray, ...] = ()

    def local(self, poses: np.ndarray) -> np.ndarray:
        """The poses in the kernel's frames (numpy's products, as the kernel always got them)."""
        if self.pre is not None:
            poses = self.pre @ poses
        if self.post is not None:
            poses = poses @ self.post
        return poses

    def __call__(self, poses: np.ndarray) -> np.ndarray:
        from rmot.sim.robots import fastik  # late: loads subprocess only when this runs

        local = self.local(poses)
        if self.kind == "opw":
            return fastik.opw_solve(self.args, local)
        return fastik.ur_solve(self.args[0], local)
