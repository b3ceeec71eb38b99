"""What defines a library robot: its DH table in controller joint values, limits, solver, solids.

A spec is plain data. `robot.Robot` builds the pinocchio model from it once.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from rmot.sim.robots.dh import DHTable, rot_z
from rmot.sim.robots.opw import OpwJointMap, OpwParams, opw_dh_table
from rmot.sim.robots.urik import UrParams
from rmot.lang.record import record

__all__ = ["RobotSpec", "Segment", "capsule_volume", "opw_spec", "spread_mass", "ur_spec", "opw_segments",
           "ur_segments"]


@record(slots=True)
class Segment:
    """A capsule around the segment p0-p1 (m, in the base frame at the spec's `solid_pose`),
    moving with joint `joint` (0 = fixed to the base: then a flat-bottomed cylinder)."""

    name: str
    joint: int
    p0: tuple[float, float, float]
    p1: tuple[float, float, float]
    radius: float


def capsule_volume(seg: Segment) -> float:
    """The volume (m^3) of a segment's capsule: a cylinder and two half spheres."""
    length = math.dist(seg.p0, seg.p1)
    return math.pi * seg.radius ** 2 * length + 4.0 / 3.0 * math.pi * seg.radius ** 3


def spread_mass(segments: tuple[Segment, ...], total_kg: float, dof: int) -> tuple[float, ...]:
    """Each moving link's share (1..dof) of `total_kg` spread over all capsules by volume."""
    vols = [capsule_volume(s) for s in segments]
    whole = sum(vols)
    return tuple(total_kg * sum(v for s, v in zip(segments, vols) if s.joint == j) / whole
                 for j in range(1, dof + 1))


@dataclass(frozen=True, slots=True, eq=False)
class RobotSpec:
    name: str
    vendor: str
    model: str
    source: str  # the documents the numbers come from
    dh: DHTable  # in the model variables u = coupling @ q
    limits_deg: tuple[tuple[float, float], ...]
    speed_deg_s: tuple[float, ...]
    accel_deg_s2: tuple[float, ...]
    reach: float  # m, datasheet reach (wrist centre or flange, as the datasheet states)
    flange: tuple[tuple[float, ...], ...] = tuple(map(tuple, np.eye(4)))  # in DH frame n
    coupling: tuple[tuple[float, ...], ...] | None = None
    opw: tuple[OpwParams, OpwJointMap] | None = None
    ur: UrParams | None = None
    segments: tuple[Segment, ...] = ()
    solid_pose: tuple[float, ...] = ()  # controller q (rad) at which `segments` are given
    extra_adjacent: tuple[tuple[str, str], ...] = ()  # solid-name pairs that touch by design
    notes: str = ""
    # --- provenance and dynamics ---
    rated_payload_kg: float | None = None  # the data sheet's rated payload
    link_mass_kg: tuple[float, ...] = ()  # per moving link 1..n; () = no inertias
    effort_nm: tuple[float, ...] = ()  # per joint torque limit; () = estimated by `dynamics`
    # per moving link: centre of mass (3) and inertia tensor about it (Ixx Ixy Ixz Iyy Iyz Izz),
    # base frame at `solid_pose`; () = estimated from the capsules (`dynamics.link_inertias`)
    link_inertia: tuple[tuple[float, ...], ...] = ()
    sources: tuple[tuple[str, str], ...] = ()  # (quantity, where its numbers come from)
    conventions: tuple[tuple[str, str], ...] = ()  # (base / flange / zero / signs / coupling, text)


def _deg(values: tuple[float, ...]) -> tuple[float, ...]:
    return tuple(float(v) for v in values)


def opw_spec(
    *, name: str, vendor: str, model: str, source: str, params: OpwParams, jmap: OpwJointMap,
    limits_deg: tuple[tuple[float, float], ...], speed_deg_s: tuple[float, ...],
    accel_deg_s2: tuple[float, ...], reach: float, radii: tuple[float, ...],
    flange_rz: float = 0.0, floor: float = 0.0, notes: str = "", arm_mass_kg: float | None = None,
    **extra: object,
) -> RobotSpec:
    """A spherical-wrist arm from its OPW lengths and the vendor's joint map.

    radii: (base, column, upper arm, elbow, forearm, wrist, flange) capsule radii in m.
    flange_rz: the vendor flange frame turned about the flange axis from the OPW one (rad).
    floor: z of the mounting face in the base frame (m; below 0 when the vendor's base frame
    sits at the J2 height, as Fanuc's does).
    arm_mass_kg: the data sheet's arm mass, spread over the capsules (`spread_mass`)
    unless `link_mass_kg` is given in `extra`.
    """
    solid_q = tuple(jmap.from_theta(np.zeros(6)).tolist())
    segments = opw_segments(params, radii, floor)
    if arm_mass_kg is not None and "link_mass_kg" not in extra:
        extra["link_mass_kg"] = spread_mass(segments, arm_mass_kg, 6)
    return RobotSpec(
        name=name, vendor=vendor, model=model, source=source, dh=opw_dh_table(params, jmap),
        limits_deg=limits_deg, speed_deg_s=speed_deg_s, accel_deg_s2=accel_deg_s2, reach=reach,
        flange=tuple(map(tuple, rot_z(flange_rz))), coupling=jmap.coupling, opw=(params, jmap),
        segments=segments, solid_pose=solid_q,
        extra_adjacent=OPW_TOUCHING, notes=notes, **extra,  # type: ignore[arg-type]
    )


# Pairs excluded besides consecutive ones: the elbow housing joins upper arm and forearm (the
# J3 limits keep those two apart), and around a compact spherical wrist the forearm end and the flange stub overlap at every J5
# (the J5 limits keep the real flange off the forearm).
OPW_TOUCHING = (("upper_arm", "forearm"), ("forearm", "flange"))


def opw_segments(p: OpwParams, radii: tuple[float, ...], floor: float = 0.0) -> tuple[Segment, ...]:
    """Capsules of an OPW arm standing upright (θ = 0): base, column, upper arm, elbow,
    forearm (along J4), wrist (along J5), flange (along J6, ending inside the flange face)."""
    rb, rc, ru, re, rf, rw, r6 = radii
    x3, z3 = p.a1, p.c1 + p.c2  # J3
    xw, zw = p.a1 + p.a2, z3 + p.c3  # wrist centre
    base_bot = floor
    base_top = floor + 0.45 * (p.c1 - floor)
    fore_start = z3 + max(re, rf) * 0.5 if abs(p.a2) < re else z3
    return (
        Segment("base", 0, (0.0, 0.0, base_bot), (0.0, 0.0, base_top), rb),
        Segment("column", 1, (0.0, 0.0, base_top + rc), (p.a1, 0.0, p.c1), rc),
        Segment("upper_arm", 2, (p.a1, p.b / 2, p.c1), (x3, p.b / 2, z3), ru),
        Segment("elbow", 3, (x3, p.b, z3), (xw, p.b, z3), re),
        Segment("forearm", 4, (xw, p.b, fore_start), (xw, p.b, zw - rw), rf),
        Segment("wrist", 5, (xw, p.b - rw * 0.6, zw), (xw, p.b + rw * 0.6, zw), rw),
        Segment("flange", 6, (xw, p.b, zw + rw * 0.5), (xw, p.b, zw + max(p.c4 - r6, rw * 0.5)), r6),
    )


def ur_segments(p: UrParams, shoulder_off: float, elbow_off: float, radii: tuple[float, ...]) -> tuple[Segment, ...]:
    """Capsules of a UR arm at q = 0 (stretched along -x, J2..J4 axes along -y).

    shoulder_off / elbow_off: the lateral offsets of the upper arm and the elbow step along
    J2's axis (m, from UR's URDF); radii: (base, shoulder, upper arm, forearm, wrist)."""
    rb, rs, ru, rf, rw = radii
    s, f = -shoulder_off, -(shoulder_off - elbow_off)  # y of the upper arm / forearm tubes
    x2, x3, z = p.a2, p.a2 + p.a3, p.d1
    return (
        Segment("base", 0, (0.0, 0.0, 0.0), (0.0, 0.0, 0.5 * p.d1), rb),
        Segment("shoulder", 1, (0.0, 0.0, 0.5 * p.d1 + rs), (0.0, 0.0, z), rs),
        Segment("shoulder_joint", 2, (0.0, 0.0, z), (0.0, s, z), rs),
        Segment("upper_arm", 2, (0.0, s, z), (x2, s, z), ru),
        Segment("elbow", 3, (x2, s, z), (x2, f, z), ru),
        Segment("forearm", 3, (x2, f, z), (x3, f, z), rf),
        Segment("wrist_1", 4, (x3, f, z), (x3, -p.d4, z), rw),
        Segment("wrist_2", 5, (x3, -p.d4, z), (x3, -p.d4, z - p.d5), rw),
        Segment("wrist_3", 6, (x3, -p.d4, z - p.d5), (x3, -p.d4 - p.d6 + rw, z - p.d5), rw),
    )


def ur_spec(
    *, name: str, model: str, source: str, params: UrParams, speed_deg_s: tuple[float, ...],
    accel_deg_s2: tuple[float, ...], reach: float, shoulder_off: float, elbow_off: float,
    radii: tuple[float, ...], limits_deg: tuple[tuple[float, float], ...] | None = None,
    **extra: object,
) -> RobotSpec:
    """A Universal Robots arm: joint values are UR's DH θ (no offsets, no sign changes)."""
    from rmot.sim.robots.dh import DHRow  # late: loads subprocess only when this runs

    rows = tuple(DHRow(d=d, a=a, alpha=al) for d, a, al in params.dh())
    limits = limits_deg or ((-360.0, 360.0),) * 6
    return RobotSpec(
        name=name, vendor="Universal Robots", model=model, source=source, dh=DHTable(rows),
        limits_deg=limits, speed_deg_s=speed_deg_s, accel_deg_s2=accel_deg_s2, reach=reach,
        ur=params, segments=ur_segments(params, shoulder_off, elbow_off, radii),
        solid_pose=(0.0,) * 6, **extra,  # type: ignore[arg-type]
    )

