"""DH tables into pinocchio: standard and modified convention, offsets, signs, prismatic joints."""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin

from rmot.sim.robots.dh import DHRow, DHTable, build_model


def rz(t):
    c, s = math.cos(t), math.sin(t)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])


def rx(t):
    c, s = math.cos(t), math.sin(t)
    return np.array([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1.0]])


def tz(d):
    m = np.eye(4)
    m[2, 3] = d
    return m


def tx(a):
    m = np.eye(4)
    m[0, 3] = a
    return m


ROWS = (
    DHRow(d=0.3, a=0.05, alpha=-math.pi / 2, offset=0.2, sign=-1.0),
    DHRow(d=0.1, a=0.4, alpha=0.3, offset=-0.5),
    DHRow(d=0.2, a=0.0, alpha=math.pi / 2, offset=0.7, sign=-1.0, kind="P"),
    DHRow(d=0.25, a=0.1, alpha=-0.4, offset=0.0, kind="R"),
)


def fk_of(table: DHTable, q: np.ndarray) -> np.ndarray:
    model, fid, _ = build_model(table, np.eye(4), "t")
    data = model.createData()
    pin.framesForwardKinematics(model, data, q)
    return data.oMf[fid].homogeneous


def test_standard_dh_with_signs_offsets_and_a_prismatic_joint():
    """The model equals Π Rz(θ) Tz(d) Tx(a) Rx(α), θ = sign·q + offset, d = d + sign·q (prismatic)."""
    for q in np.random.default_rng(0).uniform(-1, 1, (20, 4)):
        expected = np.eye(4)
        for row, v in zip(ROWS, q):
            theta, d = (row.sign * v + row.offset, row.d) if row.kind == "R" else (row.offset, row.d + row.sign * v)
            expected = expected @ rz(theta) @ tz(d) @ tx(row.a) @ rx(row.alpha)
        np.testing.assert_allclose(fk_of(DHTable(ROWS), q), expected, atol=1e-13)


def test_modified_dh_with_signs_offsets_and_a_prismatic_joint():
    """Craig's convention: Π Rx(α_{i-1}) Tx(a_{i-1}) Rz(θ_i) Tz(d_i), α and a stored in row i."""
    for q in np.random.default_rng(1).uniform(-1, 1, (20, 4)):
        expected = np.eye(4)
        for row, v in zip(ROWS, q):
            theta, d = (row.sign * v + row.offset, row.d) if row.kind == "R" else (row.offset, row.d + row.sign * v)
            expected = expected @ rx(row.alpha) @ tx(row.a) @ rz(theta) @ tz(d)
        np.testing.assert_allclose(fk_of(DHTable(ROWS, modified=True), q), expected, atol=1e-13)
