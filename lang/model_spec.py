"""A robot defined in a cell (`model` block) as plain data, and its load key.

The front end (compiler/passes/lower_model.py) makes a ModelSpec from the cell's text; the
IR carries it as a string key, "model:" + canonical JSON (sorted keys, floats written with
repr so the round trip is exact); `sim.robots.load_robot` builds the Robot from that
key (sim/robots/model.py, which states the conventions). No pinocchio here: the front
end imports this module.
"""

from __future__ import annotations

import json
from typing import Any

from rmot.lang.record import record

__all__ = ["MAX_JOINTS", "MODEL_PREFIX", "ModelJointSpec", "ModelSolid", "ModelSpec", "model_key", "model_name", "spec_from_key"]

MAX_JOINTS = 12  # a bound on the chain, far above any serial arm a controller drives
MODEL_PREFIX = "model:"


@record(slots=True)
class ModelJointSpec:
    """One joint: kind 'R' or 'P'; DH a, d in m, alpha, theta in rad; limits in rad (R) or m (P);
    speed in rad/s or m/s; accel in rad/s² or m/s²; optionally the link's mass in kg
    and the motor's rated torque in N·m (N for a prismatic joint), None when not given."""

    kind: str
    a: float
    alpha: float
    d: float
    theta: float
    lo: float
    hi: float
    speed: float
    accel: float
    mass: float | None = None
    torque: float | None = None


@record(slots=True)
class ModelSpec:
    name: str
    modified: bool  # True: Craig's modified DH
    joints: tuple[ModelJointSpec, ...]
    flange: tuple[float, ...] = (1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0)  # (4,4) row-major
    payload_kg: float | None = None
    # solids given in the cell: (joint 1..n, kind, numbers, pose (4,4) row-major in DH frame i);
    # kind box (x, y, z) | cylinder (r, h) | sphere (r,) | capsule (r, length) | mesh (scale,) with `path`
    solids: tuple[ModelSolid, ...] = ()
    # the controller whose pendant values the joint values are (`controller kuka`; None: undeclared)
    # and per joint (sign, zero, coupled_to) from `pendant(...)` ((): every joint (1, 0, 0));
    # see sim/robots/controller.py
    controller: str | None = None
    pendant: tuple[tuple[float, float, int], ...] = ()


@record(slots=True)
class ModelSolid:
    joint: int
    kind: str
    numbers: tuple[float, ...]
    pose: tuple[float, ...]
    path: str = ""


def model_key(spec: ModelSpec) -> str:
    """The load key: "model:" + canonical JSON (sorted keys, repr floats)."""
    data = {
        "name": spec.name, "modified": spec.modified, "flange": list(spec.flange), "payload_kg": spec.payload_kg,
        "joints": [_joint_row(j) for j in spec.joints],
        "solids": [[g.joint, g.kind, list(g.numbers), list(g.pose), g.path] for g in spec.solids],
    }
    if spec.controller is not None:  # only when declared, so an undeclared model's key is as before
        data["controller"] = spec.controller
    if spec.pendant:
        data["pendant"] = [list(p) for p in spec.pendant]
    return MODEL_PREFIX + json.dumps(data, sort_keys=True, separators=(",", ":"))


def _joint_row(j: ModelJointSpec) -> list[object]:
    """A joint's numbers in the key; mass and torque only when given, so that the
    key of a model without them is written as before."""
    row: list[object] = [j.kind, j.a, j.alpha, j.d, j.theta, j.lo, j.hi, j.speed, j.accel]
    if j.mass is not None or j.torque is not None:
        row += [j.mass, j.torque]
    return row


def _numbers(values: list[object]) -> list[Any]:
    return [None if x is None else float(x) for x in values]  # type: ignore[arg-type]


def spec_from_key(key: str) -> ModelSpec:
    """The inverse of model_key (raises ValueError on a key it did not write)."""
    if not key.startswith(MODEL_PREFIX):
        raise ValueError(f"not a model key: {key[:40]!r}")
    data = json.loads(key[len(MODEL_PREFIX):])
    joints = tuple(ModelJointSpec(str(k), *_numbers(rest)) for k, *rest in data["joints"])
    payload = data["payload_kg"]
    solids = tuple(ModelSolid(int(j), str(k), tuple(float(x) for x in n), tuple(float(x) for x in p), str(path))
                   for j, k, n, p, path in data.get("solids", ()))
    controller = data.get("controller")
    pendant = tuple((float(s), float(z), int(c)) for s, z, c in data.get("pendant", ()))
    return ModelSpec(str(data["name"]), bool(data["modified"]), joints, tuple(float(x) for x in data["flange"]),
                     None if payload is None else float(payload), solids,
                     None if controller is None else str(controller), pendant)


def model_name(key: str) -> str:
    """The model's name from its key (for listings)."""
    return str(json.loads(key[len(MODEL_PREFIX):])["name"])
