"""Stäubli arms transcribed from ROS-Industrial's staubli and staubli_experimental packages.

Each arm's geometry, joint limits and speeds are its package's URDF macro (repository, path
and commit in `sources`). The OPW lengths are read off the joint origins: c1 = 0 (the world
frame is ROS-I's `base`, at J1's origin, where J2's axis crosses it), a1 = J2's forward
offset, b = the lateral offset of the forearm's plane (J3's origin along y), c2 = J2 to J3,
a2 = 0, c3 = J3 to J5, c4 = J5 to the flange (`tool0` = link_6 turned back and forth about y,
z along J6). Joint values are VAL3's: staubli_val3_driver's toJointArrayRad.pgx sends
herej()'s j1..j6 times pi/180, so the URDF joint values are the pendant's one to one
(`STAUBLI`, library_common.py). tests/robots/test_reference_fk.py checks every arm against
its URDF chain composed independently (tests/robots/reference_arms_staubli.py).

Every arm of the packages is here (the gazebo packages repeat the support packages' arms).
"""

from __future__ import annotations

from rmot.sim.robots.library_common import ACC_EST, STAUBLI, STAUBLI_CONV, acc_estimate, sources
from rmot.sim.robots.library_rosi import _REACH_EST, _wrist_reach
from rmot.sim.robots.library_rosi_rows import RosiArm
from rmot.sim.robots.opw import OpwParams
from rmot.sim.robots.spec import RobotSpec, opw_spec

__all__ = ["staubli_arms"]

# Each row's `file`: the package (repository, path, commit); `floor` is minus the height of
# ROS-I's `base` (J1's origin, J2's height) over the mounting face; `link_mass_kg` the URDF's
# link_1..link_6 <inertial> masses (none where it has none).
_ROSI = "ros-industrial/staubli {} @ 367d92ec7432"
_EXPERIMENTAL = "ros-industrial/staubli_experimental {} @ 256a71acea21"
# The TX60L's capsule radii (library_rosi.py) at its wrist reach; other arms scale them by reach.
_TX60L_RADII = (0.09, 0.08, 0.06, 0.06, 0.05, 0.04, 0.03)
_TX60L_REACH = 0.85
# The TX2 arms' packages give no masses: each takes its TX predecessor's of the same lengths.
_SAME_LENGTHS = {"staubli_tx2_60l": "staubli_tx60l", "staubli_tx2_90": "staubli_tx90",
                 "staubli_tx2_90l": "staubli_tx90l", "staubli_tx2_90xl": "staubli_tx90xl"}
_TX60L_MASSES = (6.99103376, 5.21353, 4.52768, 3.48055, 0.16254714, 0.0082)  # tx60l_macro.xacro <inertial>


_ARMS = (
    RosiArm(
        name="staubli_tx60", model="TX60", file=_EXPERIMENTAL.format("staubli_tx60_support/urdf/tx60_macro.xacro"),
        params=OpwParams(a1=0, a2=0.0, b=0.02, c1=0.0, c2=0.29, c3=0.31, c4=0.07), floor=-0.375,
        limits_deg=((-180, 180), (-127.5, 127.5), (-142.5, 142.5), (-270, 270), (-122.5, 132.5), (-270, 270)),
        speed_deg_s=(435, 410, 540, 995, 1065, 1445),
        effort_nm=(126, 71, 38, 7, 8, 2), payload_kg=None, link_mass_kg=(6.99103376, 4.29177, 4.52768, 2.16976, 0.16254714, 0.0082),
    ),
    RosiArm(
        name="staubli_tx2_60l", model="TX2-60L", file=_EXPERIMENTAL.format("staubli_tx2_60_support/urdf/tx2_60l_macro.xacro"),
        params=OpwParams(a1=0, a2=0.0, b=0.02, c1=0.0, c2=0.4, c3=0.45, c4=0.07), floor=-0.375,
        limits_deg=((-180, 180), (-127.5, 127.5), (-152.5, 152.5), (-270, 270), (-121, 132.5), (-270, 270)),
        speed_deg_s=(435, 385, 500, 995, 1065, 1445),
        effort_nm=(126, 47, 32, 7, 8, 2), payload_kg=None,
    ),
    RosiArm(
        name="staubli_tx90", model="TX90", file=_EXPERIMENTAL.format("staubli_tx90_support/urdf/tx90_macro.xacro"),
        params=OpwParams(a1=0.05, a2=0.0, b=0.05, c1=0.0, c2=0.425, c3=0.425, c4=0.1), floor=-0.478,
        limits_deg=((-180, 180), (-130, 147.5), (-145, 145), (-270, 270), (-115, 140), (-270, 270)),
        speed_deg_s=(400, 400, 430, 540, 475, 760),
        effort_nm=(318, 166, 76, 34, 29, 11), payload_kg=None, link_mass_kg=(16.934564, 12.98711, 7.50151, 4.54015, 0.56876, 0.03098),
    ),
    RosiArm(
        name="staubli_tx90l", model="TX90L", file=_EXPERIMENTAL.format("staubli_tx90_support/urdf/tx90l_macro.xacro"),
        params=OpwParams(a1=0.05, a2=0.0, b=0.05, c1=0.0, c2=0.5, c3=0.55, c4=0.1), floor=-0.478,
        limits_deg=((-180, 180), (-130, 147.5), (-145, 145), (-270, 270), (-115, 140), (-270, 270)),
        speed_deg_s=(400, 390, 420, 540, 475, 760),
        effort_nm=(318, 130, 65, 34, 29, 11), payload_kg=None, link_mass_kg=(16.934564, 14.350897, 7.501506, 6.420429, 0.56876, 0.030977),
    ),
    RosiArm(
        name="staubli_tx90xl", model="TX90XL", file=_EXPERIMENTAL.format("staubli_tx90_support/urdf/tx90xl_macro.xacro"),
        params=OpwParams(a1=0.05, a2=0.0, b=0.05, c1=0.0, c2=0.65, c3=0.65, c4=0.1), floor=-0.478,
        limits_deg=((-180, 180), (-130, 147.5), (-145, 145), (-270, 270), (-115, 140), (-270, 270)),
        speed_deg_s=(400, 350, 410, 540, 475, 760),
        effort_nm=(318, 90, 53, 34, 29, 11), payload_kg=None, link_mass_kg=(16.934564, 17.789372, 7.501506, 7.9168, 0.56876, 0.030977),
    ),
    RosiArm(
        name="staubli_tx2_90", model="TX2-90", file=_EXPERIMENTAL.format("staubli_tx2_90_support/urdf/tx2_90_macro.xacro"),
        params=OpwParams(a1=0.05, a2=0.0, b=0.05, c1=0.0, c2=0.425, c3=0.425, c4=0.1), floor=-0.478,
        limits_deg=((-180, 180), (-130, 147.5), (-145, 145), (-270, 270), (-115, 140), (-270, 270)),
        speed_deg_s=(265, 210, 315, 450, 370, 630),
        effort_nm=(318, 166, 76, 34, 29, 11), payload_kg=None,
    ),
    RosiArm(
        name="staubli_tx2_90l", model="TX2-90L", file=_EXPERIMENTAL.format("staubli_tx2_90_support/urdf/tx2_90l_macro.xacro"),
        params=OpwParams(a1=0.05, a2=0.0, b=0.05, c1=0.0, c2=0.5, c3=0.55, c4=0.1), floor=-0.478,
        limits_deg=((-180, 180), (-130, 147.5), (-145, 145), (-270, 270), (-115, 140), (-270, 270)),
        speed_deg_s=(225, 180, 270, 450, 370, 630),
        effort_nm=(318, 130, 65, 34, 29, 11), payload_kg=None,
    ),
    RosiArm(
        name="staubli_tx2_90xl", model="TX2-90XL", file=_EXPERIMENTAL.format("staubli_tx2_90_support/urdf/tx2_90xl_macro.xacro"),
        params=OpwParams(a1=0.05, a2=0.0, b=0.05, c1=0.0, c2=0.65, c3=0.65, c4=0.1), floor=-0.478,
        limits_deg=((-180, 180), (-130, 147.5), (-145, 145), (-270, 270), (-115, 140), (-270, 270)),
        speed_deg_s=(200, 170, 240, 420, 360, 630),
        effort_nm=(318, 90, 53, 34, 29, 11), payload_kg=None,
    ),
    RosiArm(
        name="staubli_rx160", model="RX160", file=_ROSI.format("staubli_rx160_support/urdf/rx160_macro.xacro"),
        params=OpwParams(a1=0.15, a2=0.0, b=0, c1=0.0, c2=0.825, c3=0.625, c4=0.11), floor=-0.55,
        limits_deg=((-160, 160), (-137.5, 137.5), (-150, 150), (-270, 270), (-105, 120), (-270, 270)),
        speed_deg_s=(200, 200, 255, 315, 360, 870),
        effort_nm=(692, 574, 242, 58, 29, 29), payload_kg=None, link_mass_kg=(45.357763, 51.266495, 19.754401, 15.287896, 0.548088, 0.038484),
    ),
    RosiArm(
        name="staubli_rx160l", model="RX160L", file=_ROSI.format("staubli_rx160_support/urdf/rx160l_macro.xacro"),
        params=OpwParams(a1=0.15, a2=0.0, b=0, c1=0.0, c2=0.825, c3=0.925, c4=0.11), floor=-0.55,
        limits_deg=((-160, 160), (-137.5, 137.5), (-150, 150), (-270, 270), (-105, 120), (-270, 270)),
        speed_deg_s=(200, 200, 255, 315, 360, 870),
        effort_nm=(692, 574, 242, 58, 29, 29), payload_kg=None, link_mass_kg=(45.357763, 51.266495, 19.754401, 27.640019, 0.548088, 0.038484),
    ),
)


def _masses(row: RosiArm) -> tuple[tuple[float, ...], str]:
    if row.link_mass_kg:
        return row.link_mass_kg, "<inertial> masses of link_1..link_6"
    twin = _SAME_LENGTHS[row.name]
    given = {r.name: r.link_mass_kg for r in _ARMS}.get(twin) or _TX60L_MASSES
    return given, f"estimate: the {twin} URDF's <inertial> masses (same lengths); this package gives none"


def _spec(row: RosiArm) -> RobotSpec:
    from rmot.sim.robots.dynamics import INERTIA_METHOD  # late: loads subprocess only when this runs

    p, where, base = row.params, row.file, -row.floor
    scale = _wrist_reach(p) / _TX60L_REACH
    radii = tuple(max(0.02, round(r * scale, 3)) for r in _TX60L_RADII)
    masses, mass_src = _masses(row)
    mm = "/".join(f"{1000 * v:g}" for v in (base, p.a1, p.c2, p.c3, p.c4))
    return opw_spec(
        name=row.name, vendor="Staubli", model=row.model, source=where, params=p, jmap=STAUBLI,
        limits_deg=row.limits_deg, speed_deg_s=row.speed_deg_s, accel_deg_s2=acc_estimate(row.speed_deg_s),
        reach=_wrist_reach(p), radii=radii, floor=row.floor, conventions=STAUBLI_CONV, link_mass_kg=masses,
        effort_nm=row.effort_nm,
        sources=sources(geometry=f"{where} ({mm} mm: base/a1/c2/c3/c4, {1000 * p.b:g} mm lateral offset)",
                        limits=f"{where} (deg)", speed=f"{where} (deg/s)", accel=ACC_EST, reach=_REACH_EST,
                        mass=f"{where} {mass_src}" if row.link_mass_kg else mass_src, inertia=INERTIA_METHOD,
                        effort=(f"{where} <limit effort> (N*m; J1's 'from Staubli instruction manual', floor "
                                "mounted), as for the TX60L in library_rosi.py"),
                        payload="unknown: not in the ROS-I package"),
    )


def staubli_arms() -> list[RobotSpec]:
    """The Stäubli arms of ROS-I's staubli and staubli_experimental support packages."""
    return [_spec(row) for row in _ARMS]
