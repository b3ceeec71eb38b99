"""Yaskawa Motoman arms transcribed from ROS-Industrial's motoman support packages.

Each arm's geometry, joint limits, speeds and torque limits are its package's URDF macro
(ros-industrial/motoman, path in `sources`, commit below); the MH5's are Yaskawa's own ROS 2
package (Yaskawa-Global/motoman_ros2_support_packages), because ROS-I's mh5_macro.xacro has no
`base` and no `tool0` frame (without them a URDF's root and last link put INFORM positions
330 mm too high and the tool axis 90 deg off). The OPW lengths are read off the joint
origins: c1 = 0 (the robot frame is ROS-I's `base`, on the S axis at the L-axis height, which
every package places at J1's origin), a1 = J2's forward offset, c2 = J2 to J3, a2 = minus
the forearm's rise to the R axis, c3 = J3 to the B axis along the forearm, c4 = B axis to
`tool0`. Joint values are the pendant's: motoman_driver's MotoROS
(motoman_driver/MotoPlus/CtrlGroup.c, Ros_CtrlGroup_ConvertToRosPos) sends each axis's
pulse count divided by its pulse-per-radian, S L U R B T in order, so the URDF joint values
are the pendant's one to one (`YASKAWA`, library_common.py). tests/robots/test_reference_fk.py
checks every arm against its URDF chain composed independently
(tests/robots/reference_arms_motoman.py).

Not in the library, and why: the GP200R and the ES165 / ES200-120 (their URDFs put L = 0 with
the lower arm horizontal, not the pendant's zero, and the ES velocities are in a separate
yaml), the HC10 family and the MotoMINI (the HC10's T axis is 162 mm off the R axis, not a
spherical wrist; the MotoMINI's T axis stands across the forearm at zero), the MA2010 (its
`tool0` is not turned to Yaskawa's flange frame; the AR2010 is the same arm with one), the
SIA / SDA arms (7 axes) and the MotoPOS positioner.
"""

from __future__ import annotations

import math

from rmot.sim.robots.library_common import ACC_EST, YASKAWA, YASKAWA_CONV, acc_estimate, sources
from rmot.sim.robots.library_rosi import _REACH_EST, _wrist_reach
from rmot.sim.robots.library_rosi_rows import RosiArm
from rmot.sim.robots.opw import OpwParams
from rmot.sim.robots.spec import RobotSpec, capsule_volume, opw_segments, opw_spec

__all__ = ["motoman_arms"]

# Each row's `file`: the package (repository, path, commit); `floor` is minus the height of
# ROS-I's `base` (J2's height) over the mounting face; the payload is the model name's.
_ROSI = "ros-industrial/motoman {} @ 433be15f6a27"
_YASKAWA_ROS2 = "Yaskawa-Global/motoman_ros2_support_packages {} @ 34b884797d61"
# The MH12's capsule radii (library_rosi.py) at its wrist reach; other arms scale them by reach.
_MH12_RADII = (0.13, 0.11, 0.08, 0.08, 0.065, 0.055, 0.04)
_MH12 = OpwParams(a1=0.155, a2=-0.200, b=0.0, c1=0.0, c2=0.614, c3=0.640, c4=0.100)
_MH12_MASS_KG = 130.0  # Yaskawa Motoman MH12 data sheet (library_rosi.py, not re-verified there)


_ARMS = (
    RosiArm(
        name="yaskawa_gp4", model="Motoman GP4", file=_ROSI.format("motoman_gp4_support/urdf/gp4_macro.xacro"),
        params=OpwParams(a1=0, a2=-0.015, b=0.0, c1=0.0, c2=0.26, c3=0.29, c4=0.072), floor=-0.33,
        limits_deg=((-170, 170), (-110, 130), (-65, 200), (-200, 200), (-123, 123), (-455, 455)),
        speed_deg_s=(465, 465, 525, 565, 565, 1000),
        effort_nm=(220.5, 305.76, 95.55, 48.02, 38.42, 16.46), payload_kg=4,
    ),
    RosiArm(
        name="yaskawa_gp7", model="Motoman GP7", file=_ROSI.format("motoman_gp7_support/urdf/gp7_macro.xacro"),
        params=OpwParams(a1=0.04, a2=-0.04, b=0.0, c1=0.0, c2=0.445, c3=0.44, c4=0.08), floor=-0.33,
        limits_deg=((-170, 170), (-65, 145), (-70, 190), (-190, 190), (-135, 135), (-360.6, 360.6)),
        speed_deg_s=(375, 315, 410, 550, 550, 1001.8),
        effort_nm=(212.66, 205.8, 106.82, 55.86, 32.68, 22.54), payload_kg=7,
    ),
    RosiArm(
        name="yaskawa_gp12", model="Motoman GP12", file=_ROSI.format("motoman_gp12_support/urdf/gp12_macro.xacro"),
        params=OpwParams(a1=0.155, a2=-0.2, b=0.0, c1=0.0, c2=0.614, c3=0.64, c4=0.1), floor=-0.45,
        limits_deg=((-170, 170), (-90, 155), (-85, 150), (-200, 200), (-150, 150), (-455, 455)),
        speed_deg_s=(259.9, 229.9, 260, 469.9, 469.8, 699.8),
        effort_nm=(926.1, 1029.0, 551.25, 89.96, 67.03, 33.3), payload_kg=12,
    ),
    RosiArm(
        name="yaskawa_gp25", model="Motoman GP25", file=_ROSI.format("motoman_gp25_support/urdf/gp25_macro.xacro"),
        params=OpwParams(a1=0.15, a2=-0.2, b=0.0, c1=0.0, c2=0.76, c3=0.795, c4=0.1), floor=-0.505,
        limits_deg=((-180, 180), (-105, 155), (-86, 160), (-200, 200), (-155, 150), (-455, 455)),
        speed_deg_s=(210, 210, 265, 420, 420, 885),
        effort_nm=(3087.0, 3087.0, 926.1, 88.2, 70.56, 50.31), payload_kg=25,
    ),
    RosiArm(
        name="yaskawa_gp35l", model="Motoman GP35L", file=_ROSI.format("motoman_gp35l_support/urdf/gp35l_macro.xacro"),
        params=OpwParams(a1=0.145, a2=-0.21, b=0.0, c1=0.0, c2=1.15, c3=1.225, c4=0.175), floor=-0.54,
        limits_deg=((-180, 180), (-90, 135), (-80, 206), (-360, 360), (-125, 125), (-360, 360)),
        speed_deg_s=(180, 140, 178, 250, 250, 360),
        effort_nm=(5516.2, 7060.7, 3089.0, 926.7, 794.3, 375.0), payload_kg=35,
    ),
    RosiArm(
        name="yaskawa_gp50", model="Motoman GP50", file=_ROSI.format("motoman_gp50_support/urdf/gp50_macro.xacro"),
        params=OpwParams(a1=0.145, a2=-0.21, b=0.0, c1=0.0, c2=0.87, c3=1.025, c4=0.175), floor=-0.54,
        limits_deg=((-180, 180), (-90, 135), (-80, 206), (-360, 360), (-125, 125), (-360, 360)),
        speed_deg_s=(180, 178, 178, 250, 250, 360),
        effort_nm=(5516.0, 7060.0, 3089.0, 926.0, 794.0, 375.0), payload_kg=50,
    ),
    RosiArm(
        name="yaskawa_gp70l", model="Motoman GP70L", file=_ROSI.format("motoman_gp70l_support/urdf/gp70l_macro.xacro"),
        params=OpwParams(a1=0.32, a2=-0.235, b=0.0, c1=0.0, c2=1.165, c3=1.225, c4=0.175), floor=-0.54,
        limits_deg=((-180, 180), (-90, 155), (-80, 90), (-360, 360), (-125, 125), (-360, 360)),
        speed_deg_s=(180, 123, 160, 230, 230, 350),
        effort_nm=(3983.9, 10174.4, 5148.4, 823.7, 794.3, 333.4), payload_kg=70,
    ),
    RosiArm(
        name="yaskawa_gp88", model="Motoman GP88", file=_ROSI.format("motoman_gp88_support/urdf/gp88_macro.xacro"),
        params=OpwParams(a1=0.32, a2=-0.21, b=0.0, c1=0.0, c2=0.87, c3=1.025, c4=0.175), floor=-0.54,
        limits_deg=((-180, 180), (-90, 155), (-80, 90), (-360, 360), (-125, 125), (-360, 360)),
        speed_deg_s=(170, 140, 160, 230, 230, 350),
        effort_nm=(4903.32, 7353.05, 3432.33, 978.21, 794.34, 375.1), payload_kg=88,
    ),
    RosiArm(
        name="yaskawa_gp110", model="Motoman GP110", file=_ROSI.format("motoman_gp110_support/urdf/gp110_macro.xacro"),
        params=OpwParams(a1=0.32, a2=-0.235, b=0.0, c1=0.0, c2=0.87, c3=1.02, c4=0.2), floor=-0.54,
        limits_deg=((-180, 180), (-90, 155), (-80, 90), (-360, 360), (-125, 125), (-360, 360)),
        speed_deg_s=(140, 110, 130, 175, 175, 255),
        effort_nm=(4596.87, 11032.48, 5148.49, 1200.33, 1323.9, 823.76), payload_kg=110,
    ),
    RosiArm(
        name="yaskawa_gp180", model="Motoman GP180", file=_ROSI.format("motoman_gp180_support/urdf/gp180_macro.xacro"),
        params=OpwParams(a1=0.325, a2=-0.3, b=0.0, c1=0.0, c2=1.15, c3=1.225, c4=0.225), floor=-0.65,
        limits_deg=((-180, 180), (-60, 76), (-86, 90), (-360, 360), (-130, 130), (-360, 360)),
        speed_deg_s=(125, 115, 125, 182, 175, 265),
        effort_nm=(8237.59, 10419.57, 7453.05, 1671.05, 1081.18, 926.73), payload_kg=180,
    ),
    RosiArm(
        name="yaskawa_gp180_120", model="Motoman GP180-120", file=_ROSI.format("motoman_gp180_support/urdf/gp180_120_macro.xacro"),
        params=OpwParams(a1=0.325, a2=-0.3, b=0.0, c1=0.0, c2=1.15, c3=1.59, c4=0.225), floor=-0.65,
        limits_deg=((-180, 180), (-60, 76), (-86, 90), (-360, 360), (-130, 130), (-360, 360)),
        speed_deg_s=(125, 115, 125, 182, 175, 265),
        effort_nm=(9414.38, 11645.4, 7060.79, 1392.54, 1863.26, 926.73), payload_kg=None,
    ),
    RosiArm(
        name="yaskawa_mh50", model="Motoman MH50", file=_ROSI.format("motoman_mh50_support/urdf/mh50_macro.xacro"),
        params=OpwParams(a1=0.145, a2=-0.21, b=0.0, c1=0.0, c2=0.87, c3=1.025, c4=0.175), floor=-0.54,
        limits_deg=((-180, 180), (-90, 135), (-80, 206), (-360, 360), (-125, 125), (-360, 360)),
        speed_deg_s=(180, 177.8, 178, 250, 250, 360),
        effort_nm=(4903.32, 6276.26, 2745.86, 823.76, 706.08, 333.43), payload_kg=50,
    ),
    RosiArm(
        name="yaskawa_mh110", model="Motoman MH110", file=_ROSI.format("motoman_mh110_support/urdf/mh110_macro.xacro"),
        params=OpwParams(a1=0.32, a2=-0.235, b=0.0, c1=0.0, c2=0.87, c3=1.02, c4=0.2), floor=-0.54,
        limits_deg=((-180, 180), (-90, 155), (-80, 90), (-360, 360), (-125, 125), (-360, 360)),
        speed_deg_s=(140, 110, 130, 175, 175, 255),
        effort_nm=(5516.24, 11645.4, 4167.83, 1200.33, 1176.8, 823.76), payload_kg=110,
    ),
    RosiArm(
        name="yaskawa_ms210", model="Motoman MS210", file=_ROSI.format("motoman_ms210_support/urdf/ms210_macro.xacro"),
        params=OpwParams(a1=0.325, a2=-0.3, b=0.0, c1=0.0, c2=1.15, c3=1.225, c4=0.25), floor=-0.65,
        limits_deg=((-180, 180), (-60, 76), (-147, 90), (-210, 210), (-125, 125), (-210, 210)),
        speed_deg_s=(120, 97, 115, 145, 145, 220),
        effort_nm=(6276.26, 9806.65, 9806.65, 2451.66, 2745.86, 1800.5), payload_kg=210,
    ),
    RosiArm(
        name="yaskawa_ar2010", model="Motoman AR2010", file=_ROSI.format("motoman_ar2010_support/urdf/ar2010_macro.xacro"),
        params=OpwParams(a1=0.15, a2=-0.2, b=0.0, c1=0.0, c2=0.76, c3=1.082, c4=0.1), floor=-0.505,
        limits_deg=((-180, 180), (-105, 155), (-86, 160), (-150, 150), (-135, 90), (-210, 210)),
        speed_deg_s=(210, 210, 220, 435, 435, 700),
        effort_nm=(3087.0, 3087.0, 926.1, 78.4, 67.03, 33.3), payload_kg=None,
    ),
    RosiArm(
        name="yaskawa_hc20", model="Motoman HC20", file=_ROSI.format("motoman_hc20_support/urdf/hc20_macro.xacro"),
        params=OpwParams(a1=0, a2=0, b=0.0, c1=0.0, c2=0.82, c3=0.88, c4=0.2), floor=-0.38,
        limits_deg=((-180, 180), (-180, 180), (-67, 247), (-210, 210), (-180, 180), (-210, 210)),
        speed_deg_s=(80, 80, 120, 130, 180, 180),
        effort_nm=(917.28, 1223.04, 642.88, 368.48, 141.12, 141.12), payload_kg=20,
    ),
    RosiArm(
        name="yaskawa_mh5", model="Motoman MH5", file=_YASKAWA_ROS2.format("motoman_mh5_support/urdf/mh5_macro.xacro"),
        params=OpwParams(a1=0.088, a2=-0.04, b=0.0, c1=0.0, c2=0.31, c3=0.305, c4=0.08), floor=-0.33,
        limits_deg=((-170, 170), (-65, 150), (-70, 190), (-190, 190), (-135, 135), (-360, 360)),
        speed_deg_s=(376, 350, 400, 450, 450, 720),
        effort_nm=(215.6, 176.4, 76.8, 44.7, 18.0, 18.0), payload_kg=5,
    ),
)


def _radii(p: OpwParams) -> tuple[float, ...]:
    scale = _wrist_reach(p) / _wrist_reach(_MH12)
    return tuple(max(0.02, round(r * scale, 3)) for r in _MH12_RADII)


def _estimated_mass(p: OpwParams, radii: tuple[float, ...], floor: float) -> float:
    """The capsules' volume at the MH12's mass per capsule volume (kg)."""
    def volume(q: OpwParams, r: tuple[float, ...], f: float) -> float:
        return sum(capsule_volume(s) for s in opw_segments(q, r, f))
    return _MH12_MASS_KG * volume(p, radii, floor) / volume(_MH12, _MH12_RADII, -0.450)


_MASS_EST = ("estimate: the capsules' volume at the Motoman MH12's mass per capsule volume (its data sheet's 130 kg, "
             "not re-verified); the ROS-I package gives no masses")


def _spec(row: RosiArm) -> RobotSpec:
    from rmot.sim.robots.dynamics import INERTIA_METHOD, SPREAD_METHOD  # late: loads subprocess only when this runs

    p, where, base = row.params, row.file, -row.floor
    radii = _radii(p)
    mm = "/".join(f"{1000 * v:g}" for v in (base, p.a1, p.c2, -p.a2, p.c3, p.c4))
    payload = ("unknown: the model name does not give it and the ROS-I package has none" if row.payload_kg is None
               else f"the model name {row.model.split()[-1]}: {row.payload_kg:g} kg")
    return opw_spec(
        name=row.name, vendor="Yaskawa", model=row.model, source=where, params=p, jmap=YASKAWA,
        limits_deg=row.limits_deg, speed_deg_s=row.speed_deg_s, accel_deg_s2=acc_estimate(row.speed_deg_s),
        reach=_wrist_reach(p), radii=radii, flange_rz=math.pi, floor=row.floor, effort_nm=row.effort_nm,
        conventions=YASKAWA_CONV, rated_payload_kg=row.payload_kg, arm_mass_kg=_estimated_mass(p, radii, row.floor),
        sources=sources(geometry=f"{where} ({mm} mm: base/a1/c2/a2/c3/c4)", limits=f"{where} (rad, to 0.1 deg)",
                        speed=f"{where} (rad/s, to 0.1 deg/s)", accel=ACC_EST, reach=_REACH_EST,
                        mass=f"{_MASS_EST}; {SPREAD_METHOD}", inertia=INERTIA_METHOD,
                        effort=f"{where} <limit effort> (N*m)", payload=payload),
    )


def motoman_arms() -> list[RobotSpec]:
    """The Motoman arms of ROS-I's motoman packages (and the MH5 of Yaskawa's ROS 2 package)."""
    return [_spec(row) for row in _ARMS]
