"""Branch names (ir.Config) from joint values: the one definition every backend uses.

For every closed-form 6R arm, computed from the controller joint values q (rad):

shoulder  FRONT when the wrist centre (OPW arms; for UR the wrist point p05, the origin of
          DH frame 5) lies in front of the J1 axis, measured along the direction in which
          the arm reaches at J2 = its upright/stretched position, i.e. the J1-rotated
          forward direction of the arm plane. BACK when it lies behind ("overhead": the arm
          reaches over its own J1 axis). The boundary (wrist centre on the J1 axis, or on the
          d4/b cylinder for offset arms) is the shoulder singularity.
          ABB cfx "wrist centre relative to axis 1 in front/behind"; KUKA Status bit 0
          (0 = basic area = FRONT); Fanuc T (toward) / B (back).
elbow     UP when the wrist centre lies in front of the line through the J2 and J3 axes
          (the lower arm), seen with the arm's forward direction, DOWN when behind. The
          boundary is the stretched (or folded) arm, the elbow singularity: for OPW arms at
          θ3 = -ψ3 with θ3 the relative elbow angle from the upright position and
          ψ3 = atan2(a2, c3); for UR at q3 = 0. UP is the usual pose (ABB and KUKA at their
          zero/home, Fanuc and Yaskawa at zero, UR with q3 > 0).
          ABB cfx "relative to lower arm in front" = UP; KUKA Status bit 1 = 1 for UP
          (A3 >= φ, φ the stretched A3 = -ψ3 in KUKA values, about +4.8° on a KR 6 R900;
          KUKA's home A3 = 90° gives Status 2 = 'B010'); Fanuc U/D; Yaskawa RCONF upper/lower
          arm = UP / DOWN. In OPW angles: UP when sin(θ3 + ψ3) > 0.
wrist     FLIP when sin(J5) < 0 on the controller's own J5 value (J5 < 0 for |J5| < 180°),
          NOFLIP otherwise; J5 = 0 is the wrist singularity. This is a statement about the
          controller's J5 sign, not about geometry: ABB cfx "axis 5 negative" = FLIP;
          KUKA Status bit 2 (A5 <= 0) = FLIP; Fanuc and Yaskawa define their flip bit on
          their own J5 sign too, so map FLIP/NOFLIP through the vendor's rule.

URDF arms have no DH table: `wrist_branches` applies these definitions to the joint axes
and frames of 6R URDF arms with a spherical wrist.

At a boundary (|value| <= 1e-12, the singular configuration itself) the branch is FRONT / UP /
NOFLIP, so round-off at an exact singularity cannot flicker the name.
"""

from __future__ import annotations

import math

import numpy as np

from rmot.lang import ir
from rmot.sim.robots.opw import OpwJointMap, OpwParams
from rmot.sim.robots.urik import UrParams, ur_branch_quantities

__all__ = ["config_of", "opw_branch_fn", "ur_branch_fn", "opw_branch_arrays", "ur_branch_arrays"]


_EPS = 1e-12


_CONFIGS = {
    (s, e, w): ir.Config(s, e, w) for s in ir.Shoulder for e in ir.Elbow for w in ir.Wrist
}


def config_of(shoulder: float, elbow: float, j5_sin: float) -> ir.Config:
    return _CONFIGS[(
        ir.Shoulder.FRONT if shoulder >= -_EPS else ir.Shoulder.BACK,
        ir.Elbow.UP if elbow >= -_EPS else ir.Elbow.DOWN,
        ir.Wrist.FLIP if j5_sin < -_EPS else ir.Wrist.NOFLIP,
    )]


def opw_branch_fn(p: OpwParams, jmap: OpwJointMap):  # type: ignore[no-untyped-def]
    """Scalar math (this runs once per IK candidate); `opw_shoulder_elbow` is the same formula."""
    c = jmap._c
    (s2, s3), (o2, o3) = (jmap.sign[1], jmap.sign[2]), (jmap.offset[1], jmap.offset[2])
    a1, c2, k, psi = p.a1, p.c2, p.forearm, p.psi3

    row2 = [(j, float(c[1, j])) for j in range(6) if c[1, j] != 0]
    row3 = [(j, float(c[2, j])) for j in range(6) if c[2, j] != 0]

    def branch(q: np.ndarray) -> ir.Config:
        v = q.tolist()
        t2 = s2 * sum(w * v[j] for j, w in row2) + o2
        t3 = s3 * sum(w * v[j] for j, w in row3) + o3
        front = a1 + c2 * math.sin(t2) + k * math.sin(t2 + t3 + psi)
        return config_of(front, math.sin(t3 + psi), math.sin(v[4]))

    return branch


def ur_branch_fn(p: UrParams):  # type: ignore[no-untyped-def]
    def branch(q: np.ndarray) -> ir.Config:
        shoulder, elbow, wrist = ur_branch_quantities(p, q)
        return config_of(float(shoulder), float(elbow), float(wrist))

    return branch


def opw_branch_arrays(p: OpwParams, jmap: OpwJointMap) -> tuple[np.ndarray, np.ndarray]:
    """`opw_branch_fn`'s numbers as arrays for the compiled solver (fastsolve._branch_code):
    (sign2, sign3, offset2, offset3, a1, c2, forearm, psi3), rows 2 and 3 of the coupling."""
    c = jmap._c
    bpar = np.array([jmap.sign[1], jmap.sign[2], jmap.offset[1], jmap.offset[2], p.a1, p.c2, p.forearm, p.psi3],
                    dtype=float)
    return bpar, np.ascontiguousarray(c[1:3], dtype=float)


def ur_branch_arrays(p: UrParams) -> tuple[np.ndarray, np.ndarray]:
    """`ur_branch_quantities`' numbers (a2, a3, d5) for the compiled solver."""
    return np.array([p.a2, p.a3, p.d5], dtype=float), np.zeros((2, 6))
