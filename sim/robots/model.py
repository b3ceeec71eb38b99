"""Robots defined in a cell: a `model` block's DH chain as data, and the Robot built from it.

A `ModelSpec` is plain data in SI units (the front end makes it from the cell's text, see
compiler/passes/lower_model.py). It travels in the IR as a load key, "model:" + canonical
JSON (floats written with repr, so the round trip is exact), and `load_robot` builds the
Robot from that key once per distinct model.

Conventions (lang/REFERENCE.md, "Robot models"):
  * Standard DH (Spong; the convention of the reference article): frame i from frame i-1 is
    Rz(θ_i) Tz(d_i) Tx(a_i) Rx(α_i). Modified DH (Craig), `mdh(...)`: Rx(α_{i-1})
    Tx(a_{i-1}) Rz(θ_i) Tz(d_i), the row of joint i holding α_{i-1}, a_{i-1}.
  * The joint value q is the DH variable minus the written constant: a revolute joint turns
    θ_i = q_i + theta, a prismatic joint slides d_i = d + q_i. The base frame is DH frame 0,
    the flange is `flange` (default identity) in the last DH frame.
  * IK: a 6R arm whose geometry is ortho-parallel with a spherical wrist gets the closed-form
    OPW solver with the library's branch rows (sim/robots/model_opw.py derives the
    parameters and proves them by FK before using them); any other 6R arm with a spherical
    wrist gets the numeric IK and geometric branch names (wrist_branches), as URDF arms do;
    every other chain the numeric IK without branch names.
  * Solids: those the cell gives (`solid(...)`, placed in DH frame i) replace the generated
    ones of their link. Generated: per link a capsule along its joint axis to the foot of the
    next joint's origin (the DH d) and one from there to that origin (the DH a), a short one
    along the axis where both vanish, and a cylinder standing on z = 0 for the base (hanging
    below the shoulder where DH frame 0 is at the J2 height, as a Fanuc's or Yaskawa's is).
    Radii are 5 % of the summed link lengths (at least 15 mm, at most 100 mm), tapering to
    60 % at the flange; an estimate for display and a conservative collision envelope, not
    the vendor's shape. Solids of the same or neighbouring joints, and solids that overlap at
    the model's zero configuration, touch by design and are not checked against each other.
  * Accelerations and speeds are the model's own. Dynamics only where every joint
    line gives its link's `mass`: the mass spread over the link's solids (given or generated)
    by volume, each a uniform solid over its bounding capsule (sim/robots/dynamics
    .link_inertias, the library's estimate); a link with no solid of known extent (a mesh)
    gets its mass as a small sphere at its joint's origin. `torque` gives the joint's rated
    torque (the model's effortLimit); a joint without one is unrated (inf).
"""

from __future__ import annotations

import numpy as np

from rmot.lang import ir
from rmot.lang.model_spec import MAX_JOINTS, MODEL_PREFIX, ModelJointSpec, ModelSpec, model_key, spec_from_key
from rmot.sim.robots.controller import coupling_matrix, in_joint_values
from rmot.sim.robots.dh import DHRow, DHTable, build_model
from rmot.sim.robots.robot import LinkSolid, Robot

__all__ = ["MAX_JOINTS", "ModelJointSpec", "ModelSpec", "MODEL_PREFIX", "model_key", "robot_from_key", "robot_from_model",
           "spec_from_key", "dh_table"]

def dh_table(spec: ModelSpec) -> DHTable:
    """The DH rows in the model variables u = C p (p the joint values; C from `pendant`):
    θᵢ = theta + signᵢ·(pᵢ + p_c − zeroᵢ) is the offset theta − signᵢ·zeroᵢ plus uᵢ."""
    pendant = spec.pendant or ((1.0, 0.0, 0),) * len(spec.joints)
    rows = tuple(DHRow(d=j.d, a=j.a, alpha=j.alpha, offset=j.theta - p[0] * p[1], kind=j.kind)
                 for j, p in zip(spec.joints, pendant))
    return DHTable(rows, modified=spec.modified)


def robot_from_key(key: str) -> Robot:
    return robot_from_model(spec_from_key(key))


def robot_from_model(spec: ModelSpec) -> Robot:
    from rmot.sim.robots.model_opw import opw_solver_for  # late: loads subprocess only when this runs
    from rmot.sim.robots.urdf import _reach  # late: loads subprocess only when this runs
    from rmot.sim.robots.wrist_branches import spherical_wrist_branch_fn  # late: loads subprocess only when this runs

    if not 1 <= len(spec.joints) <= MAX_JOINTS:
        raise ValueError(f"a model must have 1 to {MAX_JOINTS} joints (got {len(spec.joints)})")
    flange = np.array(spec.flange, dtype=float).reshape(4, 4)
    model, fid, link_frames = build_model(dh_table(spec), flange, spec.name)
    limits = np.array([(j.lo, j.hi) for j in spec.joints], dtype=float)
    velocity = np.array([j.speed for j in spec.joints], dtype=float)
    accel = np.array([j.accel for j in spec.joints], dtype=float)
    coupling = None if not spec.pendant else coupling_matrix(tuple(p[0] for p in spec.pendant),
                                                              tuple(p[2] for p in spec.pendant))
    q0 = _zero_in_limits(limits) if coupling is None else coupling @ _zero_in_limits(limits)
    solids = _solids(model, q0, {g.joint for g in spec.solids}) + _given_solids(spec, link_frames)
    common = dict(
        name=spec.name, vendor="cell model", model_name=spec.name, model=model, flange_frame=fid,
        joint_limits=limits, velocity_limits=velocity, accel_limits=accel, reach=0.0, solids=solids,
        adjacent_pairs=_adjacent(model, solids, q0), source="model block in the cell",
        dh_rows=dh_table(spec).rows, dh_modified=spec.modified, controller=spec.controller,
        conventions=_conventions(spec),
    )
    # the closed form and the branch names are derived on the model variables u = C p, then
    # read back in joint values (p = C⁻¹ u); the probe has no coupling so u is its joint value
    model_limits = limits if coupling is None else _model_limits(coupling, limits)
    probe = Robot(**{**common, "joint_limits": model_limits})
    opw = opw_solver_for(probe) if len(spec.joints) == 6 else None
    if opw is not None:
        closed_form, branch_fn, rows = opw
        if coupling is not None:
            in_joints, branch_fn = in_joint_values(closed_form, branch_fn, coupling)
            assert in_joints is not None
            closed_form = in_joints
        robot = Robot(**common, coupling=coupling, closed_form=closed_form, branch_fn=branch_fn, batch_branches=rows)
    else:
        chain = probe._chain
        wrist_fn = spherical_wrist_branch_fn(model, chain.axes, chain.prismatic, model_limits)
        if wrist_fn is not None and coupling is not None:
            wrist_fn = in_joint_values(None, wrist_fn, coupling)[1]
        robot = Robot(**common, coupling=coupling, branch_fn=wrist_fn)
    robot.reach = _reach(robot)
    robot.rated_payload_kg = spec.payload_kg
    if all(j.mass is not None for j in spec.joints):
        _add_dynamics(robot, spec)
    return robot


def _conventions(spec: ModelSpec) -> tuple[tuple[str, str], ...]:
    """What the model declares about its controller (sim/robots/controller.py), as text."""
    if spec.controller is None:
        return ()
    pendant = spec.pendant or ((1.0, 0.0, 0),) * len(spec.joints)
    signs = ", ".join(f"{s:+.0f}" for s, _, _ in pendant)
    zeros = ", ".join(f"{z:g}" for _, z, _ in pendant)
    coupled = [f"J{i} + J{c}" for i, (_, _, c) in enumerate(pendant, 1) if c]
    return (("controller", spec.controller), ("base frame", "DH frame 0 (declared by `controller`)"),
            ("flange frame", "the model's `flange` (declared by `controller`)"),
            ("signs", f"pendant signs ({signs}); zeros ({zeros}) rad or m"),
            ("coupling", "DH variable of " + ", ".join(coupled) if coupled else "none"))


def _model_limits(coupling: np.ndarray, limits: np.ndarray) -> np.ndarray:
    """The box of model variables u = C p over the joint-value box (the probe's sampling range)."""
    lo = np.minimum(coupling, 0.0) @ limits[:, 1] + np.maximum(coupling, 0.0) @ limits[:, 0]
    hi = np.maximum(coupling, 0.0) @ limits[:, 1] + np.minimum(coupling, 0.0) @ limits[:, 0]
    return np.column_stack([lo, hi])


def _add_dynamics(robot: Robot, spec: ModelSpec) -> None:
    """Link inertias from the masses and the solids, ratings into effortLimit (module doc)."""
    from rmot.sim.robots.dynamics import link_inertias  # late: loads subprocess only when this runs
    from rmot.sim.robots.spec import Segment  # late: loads subprocess only when this runs

    segments = []
    for s in robot.solids:
        if s.joint_id < 1:
            continue
        ends = _bounding_segment(s.placement.matrix(), s.geometry)  # in the solid's joint frame
        if ends is not None:
            p0, p1, r = ends
            segments.append(Segment(s.name, int(s.joint_id), (p0[0], p0[1], p0[2]),
                                    (p1[0], p1[1], p1[2]), float(r)))
    import pinocchio as pin  # late: pinocchio is heavy or optional, loaded only where used

    masses = tuple(float(j.mass or 0.0) for j in spec.joints)
    # a massless link: computed with 1 kg (no division by zero), then left without inertia
    some = tuple(m if m > 0 else 1.0 for m in masses)
    inertias = link_inertias(tuple(segments), some, [np.eye(4)] * len(masses))
    model = robot.model
    for j, (inertia, mass) in enumerate(zip(inertias, masses), start=1):
        model.inertias[j] = inertia if mass > 0 else pin.Inertia.Zero()
    rated = [np.inf if j.torque is None else j.torque for j in spec.joints]
    model.effortLimit = np.array(rated, dtype=float)
    robot.has_inertia = True


# --------------------------------------------------------------------------- solids


def _joint_points(model, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:  # type: ignore[no-untyped-def]
    """Joint origins (n+1,3) with the flange last, joint frames (n+1,4,4) (index 0 = base)."""
    import pinocchio as pin  # late: pinocchio is heavy or optional, loaded only where used

    data = model.createData()
    pin.forwardKinematics(model, data, q)
    frames = [np.eye(4)] + [data.oMi[j].homogeneous for j in range(1, model.njoints)]
    flange = pin.updateFramePlacement(model, data, model.nframes - 1).homogeneous
    pts = np.array([f[:3, 3] for f in frames[1:]] + [flange[:3, 3]])
    return pts, np.array(frames), flange


def _zero_in_limits(limits: np.ndarray) -> np.ndarray:
    return np.clip(0.0, limits[:, 0], limits[:, 1])


def _given_solids(spec: ModelSpec, link_frames: list[np.ndarray]) -> tuple[LinkSolid, ...]:
    """The cell's `solid(...)` fields: placed in DH frame i, which moves with joint i."""
    out = []
    for k, g in enumerate(spec.solids):
        n = g.numbers
        geom: ir.Geometry
        if g.kind == "box":
            geom = ir.Box((n[0], n[1], n[2]))
        elif g.kind == "cylinder":
            geom = ir.Cylinder(n[0], n[1])
        elif g.kind == "sphere":
            geom = ir.Sphere(n[0])
        elif g.kind == "capsule":
            geom = ir.Capsule(n[0], n[1])
        elif g.kind == "mesh":
            geom = ir.Mesh(g.path, n[0])
        else:
            raise ValueError(f"unknown solid kind '{g.kind}'")
        placement = link_frames[g.joint - 1] @ np.array(g.pose, dtype=float).reshape(4, 4)
        out.append(LinkSolid(f"link_{g.joint}_solid_{k + 1}", g.joint, geom, ir.Pose.from_matrix(placement)))
    return tuple(out)


def _solids(model, q0: np.ndarray, given: set[int] = frozenset()) -> tuple[LinkSolid, ...]:  # type: ignore[no-untyped-def,assignment]
    """Per link i: a capsule along joint i's axis to the foot of the next joint origin (the DH
    d), then one from there to the next joint origin (the DH a); a stub along the axis where
    both are zero. The base: `_base_cylinder`. q0: the model
    variables at which the solids are laid out (the joint values' zero, clipped into the range)."""
    pts, frames, _ = _joint_points(model, q0)
    total = float(sum(np.linalg.norm(pts[i + 1] - pts[i]) for i in range(len(pts) - 1))) + float(np.linalg.norm(pts[0]))
    r0 = min(max(0.05 * total, 0.015), 0.10)
    n = model.nq
    out = [_base_cylinder(pts, r0, r0 * (1.0 - 0.8 / n) if n > 1 else r0)]
    for i in range(n):
        if i + 1 in given:  # the cell gives this link's solids
            continue
        r = r0 * (1.0 - 0.4 * (i + 1) / n)
        frame = frames[i + 1]
        z = frame[:3, 2] if model.joints[i + 1].shortname().endswith("Z") else frame[:3, :3] @ np.array([0.0, 0.0, 1.0])
        p0, p1 = pts[i], pts[i + 1]
        foot = p0 + ((p1 - p0) @ z) * z
        pieces = [(p0, foot), (foot, p1)]
        if i == 0 and abs(p0[2]) < r + 0.002:  # the first link starts at the floor: keep its cap 2 mm above it
            p0 = p0 + (r + 0.002 - p0[2]) * np.array([0.0, 0.0, 1.0])
            pieces[0] = (p0, foot)
        kept = [(a, b) for a, b in pieces if np.linalg.norm(b - a) > 1e-6]
        if not kept:  # a joint on the next one's origin: a stub along its axis
            kept = [(pts[i] - r * z, pts[i] + r * z)]
        for k, (a, b) in enumerate(kept):
            out.append(_capsule(f"link_{i + 1}" + ("" if k == 0 else "_offset"), i + 1, a, b, r, frame))
    return tuple(out)


def _base_cylinder(pts: np.ndarray, r0: float, r2: float) -> LinkSolid:
    """The base: a cylinder of radius r0 and height 2·r0 on the J1 axis, standing on z = 0 of
    DH frame 0. Where that frame is at the shoulder (Fanuc's, Yaskawa's and Stäubli's
    controller frames lie at the J2 height, the mounting face below them) a standing cylinder
    would fill the space the upper arm (radius r2) swings through at the shoulder; there it
    hangs below the shoulder, clear of the upper arm (its turret, link 1's solid, fills
    the column up to the shoulder and touches the base by design)."""
    shoulder = pts[1] if len(pts) > 2 else pts[-1]
    top = 2 * r0 if shoulder[2] >= 2 * r0 + r2 else min(0.0, float(shoulder[2])) - r2 - 0.002
    bottom = 0.0 if top > 0 else top - 2 * r0
    return _capsule("base", 0, np.array([0.0, 0.0, bottom]), np.array([0.0, 0.0, top]), r0, np.eye(4), cylinder=True)


def _capsule(name: str, joint: int, p0: np.ndarray, p1: np.ndarray, radius: float, joint_frame: np.ndarray,
             cylinder: bool = False) -> LinkSolid:
    from rmot.sim.robots.build import _frame_with_z  # late: loads subprocess only when this runs

    axis = p1 - p0
    length = float(np.linalg.norm(axis))
    world = np.eye(4)
    world[:3, :3] = _frame_with_z(axis / length)
    world[:3, 3] = (p0 + p1) / 2
    local = np.linalg.inv(joint_frame) @ world
    geom: ir.Geometry = ir.Cylinder(radius=radius, height=length) if cylinder else ir.Capsule(radius=radius, length=length)
    return LinkSolid(name, joint, geom, ir.Pose.from_matrix(local))


def _segment_distance(a0: np.ndarray, a1: np.ndarray, b0: np.ndarray, b1: np.ndarray) -> float:
    """The smallest distance between segments a0-a1 and b0-b1 (sampled finely; display use)."""
    s = np.linspace(0.0, 1.0, 33)
    pa = a0 + s[:, None] * (a1 - a0)
    pb = b0 + s[:, None] * (b1 - b0)
    return float(np.min(np.linalg.norm(pa[:, None] - pb[None], axis=-1)))


def _adjacent(model, solids: tuple[LinkSolid, ...], q0: np.ndarray) -> tuple[tuple[int, int], ...]:  # type: ignore[no-untyped-def]
    """Solids of the same or neighbouring joints (they meet at the joint between them), and
    those whose bounding capsules overlap at the zero configuration q0 (they touch by design)."""
    _, frames, _ = _joint_points(model, q0)
    ends = [_bounding_segment(frames[s.joint_id] @ s.placement.matrix(), s.geometry) for s in solids]
    pairs = set()
    for i in range(len(solids)):
        for j in range(i + 1, len(solids)):
            near = abs(solids[i].joint_id - solids[j].joint_id) <= 1
            a, b = ends[i], ends[j]
            if near or (a is not None and b is not None and _segment_distance(a[0], a[1], b[0], b[1]) < a[2] + b[2] + 1e-9):
                pairs.add((i, j))
    return tuple(sorted(pairs))


def _bounding_segment(m: np.ndarray, g: ir.Geometry) -> tuple[np.ndarray, np.ndarray, float] | None:
    """A segment and radius whose capsule holds the solid (None for a mesh: unknown extent)."""
    centre, z = m[:3, 3], m[:3, 2]
    if isinstance(g, ir.Capsule):
        return centre - g.length / 2 * z, centre + g.length / 2 * z, g.radius
    if isinstance(g, ir.Cylinder):
        return centre - g.height / 2 * z, centre + g.height / 2 * z, g.radius
    if isinstance(g, ir.Sphere):
        return centre, centre, g.radius
    if isinstance(g, ir.Box):
        return centre, centre, float(np.linalg.norm(g.size)) / 2
    return None
