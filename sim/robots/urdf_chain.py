"""The arm between two URDF links: `urdf("f.urdf", base="base_link", tip="tool0")`.

The joints on the kinematic path from the base link down to the tip link are the arm; every
other joint (gripper fingers, a second branch, a rail above the base) is locked at 0
clipped into its limits (pinocchio's buildReducedModel merges what it carries into its
parent). The result is re-expressed in the base link's frame, which becomes the robot's
base frame; the tip link's frame is the flange.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

__all__ = ["chain_joints", "reduce_to_chain"]


def _body_frame(model: pin.Model, link: str) -> int:
    for i, f in enumerate(model.frames):
        if f.name == link and f.type == pin.FrameType.BODY:
            return i
    names = sorted(f.name for f in model.frames if f.type == pin.FrameType.BODY)
    raise ValueError(f"no link named '{link}' (links: {', '.join(names)})")


def chain_joints(model: pin.Model, base: str | None, tip: str) -> list[int]:
    """The joint ids from base (exclusive) down to tip, in order; ValueError if tip is not below base."""
    jt = model.frames[_body_frame(model, tip)].parentJoint
    jb = 0 if base is None else model.frames[_body_frame(model, base)].parentJoint
    path = []
    j = jt
    while j != jb:
        if j == 0:
            raise ValueError(f"link '{tip}' must be below link '{base}' in the URDF tree (it is not)")
        path.append(j)
        j = model.parents[j]
    return path[::-1]


def reduce_to_chain(model: pin.Model, geoms: pin.GeometryModel, base: str | None, tip: str | None) -> tuple[pin.Model, pin.GeometryModel]:
    if tip is None:
        raise ValueError("urdf(..., base=...) needs tip= too")
    chain = chain_joints(model, base, tip)
    if not chain:
        raise ValueError(f"no movable joint between links '{base}' and '{tip}'")
    lock = [j for j in range(1, model.njoints) if j not in chain]
    q_ref = np.clip(pin.neutral(model), model.lowerPositionLimit, model.upperPositionLimit)
    if lock:
        model, geoms = pin.buildReducedModel(model, geoms, lock, q_ref)
    if base is not None:
        data = model.createData()
        pin.framesForwardKinematics(model, data, pin.neutral(model))
        m_inv = data.oMf[_body_frame(model, base)].inverse()
        for j in range(1, model.njoints):
            if model.parents[j] == 0:
                model.jointPlacements[j] = m_inv * model.jointPlacements[j]
        for f in model.frames:
            if f.parentJoint == 0:
                f.placement = m_inv * f.placement
        for g in geoms.geometryObjects:
            if g.parentJoint == 0:
                g.placement = m_inv * g.placement
    return model, geoms
