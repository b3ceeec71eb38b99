"""Denavit-Hartenberg tables built into pinocchio models.

A row describes one joint. Standard DH (Spong/Corke): T_i = Rz(θ_i) Tz(d_i) Tx(a_i) Rx(α_i).
Modified DH (Craig): T_i = Rx(α_{i-1}) Tx(a_{i-1}) Rz(θ_i) Tz(d_i), with α_{i-1}, a_{i-1}
stored in row i. For a revolute joint θ_i = sign·q_i + offset; for a prismatic joint
d_i = d + sign·q_i. `sign` and `offset` let the table use the controller's joint values
(pendant zero and direction) while the geometry stays the textbook one: pinocchio's q is
then exactly the controller's q (a coupling such as Fanuc's J2/J3 is applied outside).
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from rmot.lang.record import record

__all__ = ["DHRow", "DHTable", "build_model", "rot_x", "rot_z", "trans"]


@record(slots=True)
class DHRow:
    """One joint: lengths in metres, angles in radians."""

    d: float
    a: float
    alpha: float
    offset: float = 0.0
    sign: float = 1.0
    kind: str = "R"  # 'R' revolute, 'P' prismatic


@record(slots=True)
class DHTable:
    rows: tuple[DHRow, ...]
    modified: bool = False  # False: standard DH; True: Craig's modified DH


def rot_z(t: float) -> np.ndarray:
    c, s = np.cos(t), np.sin(t)
    m = np.eye(4)
    m[:2, :2] = [[c, -s], [s, c]]
    return m


def rot_x(t: float) -> np.ndarray:
    c, s = np.cos(t), np.sin(t)
    m = np.eye(4)
    m[1:3, 1:3] = [[c, -s], [s, c]]
    return m


def trans(x: float, y: float, z: float) -> np.ndarray:
    m = np.eye(4)
    m[:3, 3] = (x, y, z)
    return m


def _split(table: DHTable) -> tuple[list[np.ndarray], list[np.ndarray]]:
    """Per joint i: T_i(q) = before[i] · Motion(sign·q) · after[i] (Motion = Rz or Tz)."""
    before: list[np.ndarray] = []
    after: list[np.ndarray] = []
    for row in table.rows:
        fixed_rot = rot_z(row.offset)  # θ offset (revolute) or the constant θ (prismatic)
        if table.modified:
            before.append(rot_x(row.alpha) @ trans(row.a, 0, 0) @ fixed_rot)
            after.append(trans(0, 0, row.d))
        else:
            before.append(fixed_rot)
            after.append(trans(0, 0, row.d) @ trans(row.a, 0, 0) @ rot_x(row.alpha))
    return before, after


def _se3(m: np.ndarray) -> pin.SE3:
    return pin.SE3(np.ascontiguousarray(m[:3, :3]), np.ascontiguousarray(m[:3, 3]))


def build_model(table: DHTable, flange: np.ndarray, name: str) -> tuple[pin.Model, int, list[np.ndarray]]:
    """A pinocchio model whose q is the table's joint values; a frame 'flange' after the last joint.

    flange: (4,4) the flange in the last DH frame. Returns (model, flange frame id, link
    frames): link_frames[i] is DH frame i+1 expressed in pinocchio joint i+1's frame, so
    geometry known in DH frames can be attached to joints.
    """
    model = pin.Model()
    model.name = name
    before, after = _split(table)
    flip = rot_x(np.pi)  # conjugating by Rx(π) turns Rz(q) into Rz(-q) and Tz(q) into Tz(-q)
    parent, carry = 0, np.eye(4)
    link_frames = []
    for i, row in enumerate(table.rows):
        placement = carry @ before[i]
        pre = flip if row.sign < 0 else np.eye(4)
        joint = pin.JointModelRZ() if row.kind == "R" else pin.JointModelPZ()
        jid = model.addJoint(parent, joint, _se3(placement @ pre), f"joint_{i + 1}")
        model.appendBodyToJoint(jid, pin.Inertia.Zero(), pin.SE3.Identity())
        carry = pre @ after[i]  # pre undoes the flip: flip·Rz(q)·flip = Rz(-q)
        link_frames.append(carry.copy())
        parent = jid
    fid = model.addFrame(pin.Frame("flange", parent, 0, _se3(carry @ flange), pin.FrameType.OP_FRAME))
    return model, fid, link_frames
