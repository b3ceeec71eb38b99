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

from typing import NamedTuple

from rmot.sim.robots.library_common import ACC_EST, STAUBLI, STAUBLI_CONV, acc_estimate, sources
from rmot.sim.robots.library_rosi import _REACH_EST, _wrist_reach
from rmot.sim.robots.opw import OpwParams
from rmot.sim.robots.spec import RobotSpec, opw_spec

__all__ = ["staubli_arms"]

_REPOS = {"staubli_rx160_support": ("ros-industrial/staubli", "367d92ec7432")}
_EXPERIMENTAL = ("ros-industrial/staubli_experimental", "256a71acea21")
# The TX60L's capsule radii (library_rosi.py) at its wrist reach; other arms scale them by reach.
_TX60L_RADII = (0.09, 0.08, 0.06, 0.06, 0.05, 0.04, 0.03)
_TX60L_REACH = 0.85
# The TX2 arms' packages give no masses: each takes its TX predecessor's of the same lengths.
_SAME_LENGTHS = {"staubli_tx2_60l": "staubli_tx60l", "staubli_tx2_90": "staubli_tx90",
                 "staubli_tx2_90l": "staubli_tx90l", "staubli_tx2_90xl": "staubli_tx90xl"}
_TX60L_MASSES = (6.99103376, 5.21353, 4.52768, 3.48055, 0.16254714, 0.0082)  # tx60l_macro.xacro <inertial>


class _S(NamedTuple):
    """One arm's row: the URDF's numbers (lengths m, degrees, deg/s, N*m) and its link_1..link_6
    <inertial> masses (kg; None where the URDF has none)."""

    name: str
    model: str
    path: str
    base_a1_b_c2_c3_c4: tuple[float, ...]
    limits_deg: tuple[tuple[float, float], ...]
    speed_deg_s: tuple[float, ...]
    effort_nm: tuple[float, ...]
    link_mass_kg: tuple[float, ...] | None


_ROWS = (
    _S("staubli_tx60", "TX60", "staubli_tx60_support/urdf/tx60_macro.xacro", (0.375, 0, 0.02, 0.29, 0.31, 0.07),
       ((-180, 180), (-127.5, 127.5), (-142.5, 142.5), (-270, 270), (-122.5, 132.5), (-270, 270)),
       (435, 410, 540, 995, 1065, 1445),
       (126, 71, 38, 7, 8, 2),
       (6.99103376, 4.29177, 4.52768, 2.16976, 0.16254714, 0.0082)),
    _S("staubli_tx2_60l", "TX2-60L", "staubli_tx2_60_support/urdf/tx2_60l_macro.xacro", (0.375, 0, 0.02, 0.4, 0.45, 0.07),
       ((-180, 180), (-127.5, 127.5), (-152.5, 152.5), (-270, 270), (-121, 132.5), (-270, 270)),
       (435, 385, 500, 995, 1065, 1445),
       (126, 47, 32, 7, 8, 2),
       None),
    _S("staubli_tx90", "TX90", "staubli_tx90_support/urdf/tx90_macro.xacro", (0.478, 0.05, 0.05, 0.425, 0.425, 0.1),
       ((-180, 180), (-130, 147.5), (-145, 145), (-270, 270), (-115, 140), (-270, 270)),
       (400, 400, 430, 540, 475, 760),
       (318, 166, 76, 34, 29, 11),
       (16.934564, 12.98711, 7.50151, 4.54015, 0.56876, 0.03098)),
    _S("staubli_tx90l", "TX90L", "staubli_tx90_support/urdf/tx90l_macro.xacro", (0.478, 0.05, 0.05, 0.5, 0.55, 0.1),
       ((-180, 180), (-130, 147.5), (-145, 145), (-270, 270), (-115, 140), (-270, 270)),
       (400, 390, 420, 540, 475, 760),
       (318, 130, 65, 34, 29, 11),
       (16.934564, 14.350897, 7.501506, 6.420429, 0.56876, 0.030977)),
    _S("staubli_tx90xl", "TX90XL", "staubli_tx90_support/urdf/tx90xl_macro.xacro", (0.478, 0.05, 0.05, 0.65, 0.65, 0.1),
       ((-180, 180), (-130, 147.5), (-145, 145), (-270, 270), (-115, 140), (-270, 270)),
       (400, 350, 410, 540, 475, 760),
       (318, 90, 53, 34, 29, 11),
       (16.934564, 17.789372, 7.501506, 7.9168, 0.56876, 0.030977)),
    _S("staubli_tx2_90", "TX2-90", "staubli_tx2_90_support/urdf/tx2_90_macro.xacro", (0.478, 0.05, 0.05, 0.425, 0.425, 0.1),
       ((-180, 180), (-130, 147.5), (-145, 145), (-270, 270), (-115, 140), (-270, 270)),
       (265, 210, 315, 450, 370, 630),
       (318, 166, 76, 34, 29, 11),
       None),
    _S("staubli_tx2_90l", "TX2-90L", "staubli_tx2_90_support/urdf/tx2_90l_macro.xacro", (0.478, 0.05, 0.05, 0.5, 0.55, 0.1),
       ((-180, 180), (-130, 147.5), (-145, 145), (-270, 270), (-115, 140), (-270, 270)),
       (225, 180, 270, 450, 370, 630),
       (318, 130, 65, 34, 29, 11),
       None),
    _S("staubli_tx2_90xl", "TX2-90XL", "staubli_tx2_90_support/urdf/tx2_90xl_macro.xacro", (0.478, 0.05, 0.05, 0.65, 0.65, 0.1),
       ((-180, 180), (-130, 147.5), (-145, 145), (-270, 270), (-115, 140), (-270, 270)),
       (200, 170, 240, 420, 360, 630),
       (318, 90, 53, 34, 29, 11),
       None),
    _S("staubli_rx160", "RX160", "staubli_rx160_support/urdf/rx160_macro.xacro", (0.55, 0.15, 0, 0.825, 0.625, 0.11),
       ((-160, 160), (-137.5, 137.5), (-150, 150), (-270, 270), (-105, 120), (-270, 270)),
       (200, 200, 255, 315, 360, 870),
       (692, 574, 242, 58, 29, 29),
       (45.357763, 51.266495, 19.754401, 15.287896, 0.548088, 0.038484)),
    _S("staubli_rx160l", "RX160L", "staubli_rx160_support/urdf/rx160l_macro.xacro", (0.55, 0.15, 0, 0.825, 0.925, 0.11),
       ((-160, 160), (-137.5, 137.5), (-150, 150), (-270, 270), (-105, 120), (-270, 270)),
       (200, 200, 255, 315, 360, 870),
       (692, 574, 242, 58, 29, 29),
       (45.357763, 51.266495, 19.754401, 27.640019, 0.548088, 0.038484)),
)


def _masses(row: _S) -> tuple[tuple[float, ...], str]:
    if row.link_mass_kg is not None:
        return row.link_mass_kg, "<inertial> masses of link_1..link_6"
    twin = _SAME_LENGTHS[row.name]
    given = {r.name: r.link_mass_kg for r in _ROWS}.get(twin) or _TX60L_MASSES
    return given, f"estimate: the {twin} URDF's <inertial> masses (same lengths); this package gives none"


def _spec(row: _S) -> RobotSpec:
    from rmot.sim.robots.dynamics import INERTIA_METHOD

    base, a1, b, c2, c3, c4 = row.base_a1_b_c2_c3_c4
    p = OpwParams(a1=a1, a2=0.0, b=b, c1=0.0, c2=c2, c3=c3, c4=c4)
    scale = _wrist_reach(p) / _TX60L_REACH
    radii = tuple(max(0.02, round(r * scale, 3)) for r in _TX60L_RADII)
    repo, commit = _REPOS.get(row.path.split("/")[0], _EXPERIMENTAL)
    where = f"{repo} {row.path} @ {commit}"
    masses, mass_src = _masses(row)
    mm = "/".join(f"{1000 * v:g}" for v in (base, a1, c2, c3, c4))
    return opw_spec(
        name=row.name, vendor="Staubli", model=row.model, source=where, params=p, jmap=STAUBLI,
        limits_deg=row.limits_deg, speed_deg_s=row.speed_deg_s, accel_deg_s2=acc_estimate(row.speed_deg_s),
        reach=_wrist_reach(p), radii=radii, floor=-base, conventions=STAUBLI_CONV, link_mass_kg=masses,
        effort_nm=row.effort_nm,
        sources=sources(geometry=f"{where} ({mm} mm: base/a1/c2/c3/c4, {1000 * b:g} mm lateral offset)",
                        limits=f"{where} (deg)", speed=f"{where} (deg/s)", accel=ACC_EST, reach=_REACH_EST,
                        mass=f"{where} {mass_src}" if row.link_mass_kg else mass_src, inertia=INERTIA_METHOD,
                        effort=(f"{where} <limit effort> (N*m; J1's 'from Staubli instruction manual', floor "
                                "mounted), as for the TX60L in library_rosi.py"),
                        payload="unknown: not in the ROS-I package"),
    )


def staubli_arms() -> list[RobotSpec]:
    """The Stäubli arms of ROS-I's staubli and staubli_experimental support packages."""
    return [_spec(row) for row in _ROWS]
