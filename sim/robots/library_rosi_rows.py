"""A library arm of a ROS-Industrial support package as one row of data, and the spec it builds.

The brand modules (library_abb.py, library_fanuc.py, library_motoman.py, library_staubli.py)
list their arms as `RosiArm` rows, one row type for every ROS-I arm: the package's macro file
(repository, path, commit), the OPW lengths read off its joint origins
(as library_rosi.py explains: a1 J2's forward offset from J1, c1 J2's height over the
controller frame, c2 J2 to J3, a2 the forearm's offset, c3 J3 to the wrist centre, c4 the wrist
centre to the flange, b the lateral offset), the bounds and speeds of its <limit> tags, the
rated payload and the arm's mass, each with its source, and the <limit effort> torques where the
package gives them. `rosi_spec` turns an ABB or FANUC row into the RobotSpec with its brand's
joint map, conventions and frames (`RosiBrand`), the way library_rosi.py builds its first arm
of each brand; the Motoman and Stäubli modules build theirs from the same rows with their
brand's capsule radii and mass estimates.
"""

from __future__ import annotations

from dataclasses import replace

from rmot.sim.robots.opw import OpwJointMap, OpwParams
from rmot.sim.robots.spec import RobotSpec, opw_spec
from rmot.lang.record import record

__all__ = ["RosiArm", "RosiBrand", "rosi_spec"]

# Capsule radii (base, column, upper arm, elbow, forearm, wrist, flange) of the IRB 2400 (1.555 m
# wrist reach, library_rosi.py), scaled by each arm's wrist reach: an estimate of the envelope,
# the ROS-I packages give meshes, not radii.
_RADII_2400 = (0.17, 0.14, 0.10, 0.10, 0.08, 0.065, 0.045)
_REACH_2400 = 1.555


@record(kw_only=True)
class RosiArm:
    """One arm: its library name, the vendor's model name, its macro file (repository, path,
    commit), the OPW lengths (m), the joint bounds (deg) and speeds (deg/s) of the file's
    <limit> tags (`rounded`: the file gives decimal radians, here to the nearest 0.5 deg and
    1 deg/s), the rated payload (kg, the model name's unless `payload_source` says otherwise;
    None where neither gives it), the arm's mass (kg) as the data sheet gives it (or, with
    `mass_source`, as a sibling model's stands in for it) or per link from the file's
    <inertial> tags, the mounting face's height in the controller frame (`floor`, m: below zero
    where the controller frame is at J2's height) and the joint torque limits of the file's
    <limit effort> tags (`effort_nm`, N*m; empty where the file has none)."""

    name: str
    model: str
    file: str
    params: OpwParams
    limits_deg: tuple[tuple[float, float], ...]
    speed_deg_s: tuple[float, ...]
    rounded: bool = False
    payload_kg: float | None
    arm_mass_kg: float | None = None
    link_mass_kg: tuple[float, ...] = ()
    floor: float = 0.0
    payload_source: str = ""  # where the payload is not in the model name
    mass_source: str = ""  # where `arm_mass_kg` is not the model's own data sheet value
    effort_nm: tuple[float, ...] = ()


@record
class RosiBrand:
    """What every arm of one maker shares: the vendor name, the joint map (pendant values to the
    closed form's), the conventions `rmot robots show` prints, the flange frame's turn about its
    axis from the OPW one (rad), and what the joint bounds' source adds (Fanuc: how its J3
    bound is read)."""

    vendor: str
    jmap: OpwJointMap
    conventions: tuple[tuple[str, str], ...]
    flange_rz: float = 0.0
    limits_note: str = ""


def _radii(reach: float) -> tuple[float, ...]:
    scale = reach / _REACH_2400
    return tuple(max(0.02, round(r * scale, 3)) for r in _RADII_2400)


def _geometry(arm: RosiArm) -> str:
    p = arm.params
    mm = " ".join(f"{k} {1000 * v:g}" for k, v in
                  (("a1", p.a1), ("a2", p.a2), ("b", p.b), ("c1", p.c1), ("c2", p.c2), ("c3", p.c3), ("c4", p.c4)))
    return f"{arm.file} joint origins (mm: {mm})"


def _mass_source(arm: RosiArm, vendor: str) -> str:
    from rmot.sim.robots.dynamics import SPREAD_METHOD  # late: loads subprocess only when this runs

    if arm.link_mass_kg:
        return f"{arm.file} <inertial> masses of link_1..link_6"
    if arm.mass_source:
        return f"{arm.mass_source}; {SPREAD_METHOD}"
    return (f"{vendor} data sheet of the {arm.model}: {arm.arm_mass_kg:g} kg, recalled, not re-verified here "
            f"(the ROS-I file has no masses); {SPREAD_METHOD}")


def rosi_spec(arm: RosiArm, brand: RosiBrand) -> RobotSpec:
    """The library spec of one row, every number with its source."""
    from rmot.sim.robots.dynamics import EFFORT_METHOD, INERTIA_METHOD  # late: loads subprocess only when this runs
    from rmot.sim.robots.library_common import ACC_EST, acc_estimate, sources  # late: loads subprocess only when this runs
    from rmot.sim.robots.library_rosi import _REACH_EST, _wrist_reach  # late: loads subprocess only when this runs

    reach = _wrist_reach(arm.params)
    unit = "rad, to the nearest 0.5 deg" if arm.rounded else "deg"
    speed_unit = "rad/s, to the nearest deg/s" if arm.rounded else "deg/s"
    spec = opw_spec(
        name=arm.name, vendor=brand.vendor, model=arm.model, source=arm.file, params=arm.params, jmap=brand.jmap,
        limits_deg=arm.limits_deg, speed_deg_s=arm.speed_deg_s, accel_deg_s2=acc_estimate(arm.speed_deg_s),
        reach=reach, radii=_radii(reach), flange_rz=brand.flange_rz, floor=arm.floor, conventions=brand.conventions,
        rated_payload_kg=arm.payload_kg, arm_mass_kg=arm.arm_mass_kg,
        sources=sources(geometry=_geometry(arm), limits=f"{arm.file} ({unit}){brand.limits_note}",
                        speed=f"{arm.file} ({speed_unit})", accel=ACC_EST, reach=_REACH_EST,
                        mass=_mass_source(arm, brand.vendor), inertia=INERTIA_METHOD,
                        effort=f"{arm.file} <limit effort> (N*m)" if arm.effort_nm else EFFORT_METHOD,
                        payload=arm.payload_source or f"the model name {arm.model}: {arm.payload_kg:g} kg"),
    )
    if arm.effort_nm:
        spec = replace(spec, effort_nm=arm.effort_nm)
    return replace(spec, link_mass_kg=arm.link_mass_kg) if arm.link_mass_kg else spec
