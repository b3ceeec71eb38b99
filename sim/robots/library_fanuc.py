"""FANUC arms of ROS-Industrial's `fanuc` and `fanuc_experimental` support packages.

Each row is one macro file (repository, path and commit in `file`), read as library_rosi.py
reads the M-16iB/20: the OPW lengths off its joint origins (every joint's rpy is zero, J1..J6
turn about +z, +y, -y, -x, -y, -x of base_link), the joint bounds and speeds off its <limit>
tags, tool0 turned (180 deg, -90 deg, 0) from link_6 (the faceplate: z forward, x up at
zero), the controller's world frame at the ROS-I `base` frame, on J1 at the J2 height (`floor`
is the mounting face below it). The pendant's J3 is the forearm's angle to the horizontal: the
URDF's joint_3 = J2 + J3 (ros-industrial/fanuc fanuc_driver, J23_factor = 1).
tests/robots/reference_arms_fanuc.py holds each file's chain as published;
tests/robots/test_reference_fk.py composes it independently and compares.

Not here: the 5-axis arms (LR Mate 200iC/5H, /5HS, 200iD/4SH, /7H, M-430iA/2F) and the
LR Mate 200iC/5F file (no joint_6), M-430iA/2P and CRX-10iA/L (no spherical wrist: OPW does not
apply), M-900iB/700 (a parallel-link file with xacro conditions). Where the package file has
no masses and the variant's own data sheet mass is not at hand, `mass_source` says whose mass
stands in for it.
"""

from __future__ import annotations

from rmot.sim.robots.library_rosi_rows import RosiArm, RosiBrand, rosi_spec
from rmot.sim.robots.opw import OpwParams
from rmot.sim.robots.spec import RobotSpec
import math

__all__ = ["fanuc_arms"]

_FANUC = "ros-industrial/fanuc {} @ 8fee5e30e535"
_FANUC_EXPERIMENTAL = "ros-industrial/fanuc_experimental {} @ 39929f69abd6"

# The URDF bounds joint_3 (J2 + J3) with the data sheet's J3 range, as for the M-16iB/20 and
# M-20iA: taken as the pendant's J3 range.
_J3_NOTE = "; J3 as the URDF bounds its joint_3, taken as the pendant J3 range as for the M-16iB/20"

_ARMS = (
    RosiArm(
        name="fanuc_cr7ia", model="CR-7iA",
        file=_FANUC.format("fanuc_cr7ia_support/urdf/cr7ia_macro.xacro"),
        params=OpwParams(a1=0.05, a2=-0.035, b=0.0, c1=0.0, c2=0.33, c3=0.335, c4=0.08),
        limits_deg=((-170, 170), (-66, 100), (-129.5, 244), (-190, 190), (-120, 120), (-360, 360)),
        speed_deg_s=(450, 380, 520, 550, 545, 1000), rounded=True, payload_kg=7.0,
        floor=-0.457,
        arm_mass_kg=53.0,
    ),
    RosiArm(
        name="fanuc_cr35ia", model="CR-35iA",
        file=_FANUC.format("fanuc_cr35ia_support/urdf/cr35ia_macro.xacro"),
        params=OpwParams(a1=0.15, a2=-0.15, b=0.0, c1=0.0, c2=0.79, c3=0.86, c4=0.1),
        limits_deg=((-170, 170), (-45, 120), (-123, 135), (-200, 200), (-110, 110), (-450, 450)),
        speed_deg_s=(180, 180, 200, 350, 350, 400), rounded=True, payload_kg=35.0,
        floor=-1.18,
        arm_mass_kg=990.0,
    ),
    RosiArm(
        name="fanuc_lrmate200ib", model="LR Mate 200iB",
        file=_FANUC.format("fanuc_lrmate200ib_support/urdf/lrmate200ib_macro.xacro"),
        params=OpwParams(a1=0.15, a2=-0.075, b=0.0, c1=0.0, c2=0.25, c3=0.29, c4=0.08),
        limits_deg=((-160, 160), (-33, 152), (-150, 165), (-190, 190), (-120, 120), (-360, 360)),
        speed_deg_s=(180, 180, 225, 400, 330, 480), rounded=True, payload_kg=5.0,
        payload_source="FANUC LR Mate 200iB data sheet: 5 kg, recalled, not re-verified here",
        floor=-0.35,
        arm_mass_kg=37.0,
    ),
    RosiArm(
        name="fanuc_lrmate200ic", model="LR Mate 200iC",
        file=_FANUC.format("fanuc_lrmate200ic_support/urdf/lrmate200ic_macro.xacro"),
        params=OpwParams(a1=0.075, a2=-0.075, b=0.0, c1=0.0, c2=0.3, c3=0.32, c4=0.08),
        limits_deg=((-170, 170), (-60, 140), (-142, 230), (-190, 190), (-120, 120), (-360, 360)),
        speed_deg_s=(350, 350, 400, 450, 450, 720), rounded=True, payload_kg=5.0,
        payload_source="FANUC LR Mate 200iC data sheet: 5 kg, recalled, not re-verified here",
        floor=-0.33,
        arm_mass_kg=27.0,
    ),
    RosiArm(
        name="fanuc_lrmate200id7l", model="LR Mate 200iD/7L",
        file=_FANUC.format("fanuc_lrmate200id_support/urdf/lrmate200id7l_macro.xacro"),
        params=OpwParams(a1=0.05, a2=-0.035, b=0.0, c1=0.0, c2=0.44, c3=0.42, c4=0.08),
        limits_deg=((-170, 170), (-100, 145), (-70, 213), (-190, 190), (-125, 125), (-360, 360)),
        speed_deg_s=(370, 310, 410, 550, 545, 1000), rounded=False, payload_kg=7.0,
        floor=-0.33,
        arm_mass_kg=27.0,
    ),
    RosiArm(
        name="fanuc_m6ib", model="M-6iB",
        file=_FANUC.format("fanuc_m6ib_support/urdf/m6ib_macro.xacro"),
        params=OpwParams(a1=0.15, a2=-0.1, b=0.0, c1=0.0, c2=0.6, c3=0.615, c4=0.1),
        limits_deg=((-170, 170), (-90, 160), (-170, 170), (-190, 190), (-140, 140), (-360, 360)),
        speed_deg_s=(150, 160, 170, 400, 400, 520), rounded=True, payload_kg=6.0,
        floor=-0.45,
        arm_mass_kg=135.0,
    ),
    RosiArm(
        name="fanuc_m10ia", model="M-10iA",
        file=_FANUC.format("fanuc_m10ia_support/urdf/m10ia_macro.xacro"),
        params=OpwParams(a1=0.15, a2=-0.2, b=0.0, c1=0.0, c2=0.6, c3=0.64, c4=0.1),
        limits_deg=((-180, 180), (-90, 160), (-180, 264), (-189.5, 189.5), (-189.5, 189.5), (-360, 360)),
        speed_deg_s=(210, 190, 210, 400, 400, 600), rounded=True, payload_kg=10.0,
        floor=-0.45,
        arm_mass_kg=130.0,
    ),
    RosiArm(
        name="fanuc_m10ia7l", model="M-10iA/7L",
        file=_FANUC.format("fanuc_m10ia_support/urdf/m10ia7l_macro.xacro"),
        params=OpwParams(a1=0.15, a2=-0.2, b=0.0, c1=0.0, c2=0.6, c3=0.86, c4=0.1),
        limits_deg=((-170, 170), (-90, 160), (-180, 267), (-189.5, 189.5), (-189.5, 189.5), (-360, 360)),
        speed_deg_s=(230, 225, 230, 430, 430, 630), rounded=True, payload_kg=7.0,
        floor=-0.45,
        arm_mass_kg=130.0,
    ),
    RosiArm(
        name="fanuc_m20ia10l", model="M-20iA/10L",
        file=_FANUC.format("fanuc_m20ia_support/urdf/m20ia10l_macro.xacro"),
        params=OpwParams(a1=0.15, a2=-0.25, b=0.0, c1=0.0, c2=0.79, c3=1.04, c4=0.1),
        limits_deg=((-185, 185), (-100, 160), (-185, 275.5), (-200, 200), (-140, 140), (-270, 270)),
        speed_deg_s=(195, 175, 180, 400, 400, 600), rounded=True, payload_kg=10.0,
        floor=-0.525,
        arm_mass_kg=250.0,
    ),
    RosiArm(
        name="fanuc_m20ib25", model="M-20iB/25",
        file=_FANUC.format("fanuc_m20ib_support/urdf/m20ib25_macro.xacro"),
        params=OpwParams(a1=0.075, a2=-0.12, b=0.0, c1=0.0, c2=0.905, c3=0.865, c4=0.1),
        limits_deg=((-180, 180), (-100, 140), (-149, 320), (-200, 200), (-145, 145), (-270, 270)),
        speed_deg_s=(205, 205, 260, 415, 415, 880), rounded=False, payload_kg=25.0,
        floor=-0.65,
        arm_mass_kg=210.0,
    ),
    RosiArm(
        name="fanuc_m710ic45m", model="M-710iC/45M",
        file=_FANUC.format("fanuc_m710ic_support/urdf/m710ic45m_macro.xacro"),
        params=OpwParams(a1=0.15, a2=-0.17, b=0.0, c1=0.0, c2=1.15, c3=1.295, c4=0.175),
        limits_deg=((-180, 180), (-90, 135), (-160, 280), (-400, 400), (-125, 125), (-400, 400)),
        speed_deg_s=(180, 180, 180, 250, 250, 360), rounded=False, payload_kg=45.0,
        floor=-0.565,
        arm_mass_kg=570.0,
    ),
    RosiArm(
        name="fanuc_m710ic50", model="M-710iC/50",
        file=_FANUC.format("fanuc_m710ic_support/urdf/m710ic50_macro.xacro"),
        params=OpwParams(a1=0.15, a2=-0.17, b=0.0, c1=0.0, c2=0.87, c3=1.016, c4=0.175),
        limits_deg=((-180, 180), (-90, 135), (-160, 280), (-360, 360), (-125, 125), (-360, 360)),
        speed_deg_s=(175, 175, 175, 250, 250, 355), rounded=True, payload_kg=50.0,
        floor=-0.565,
        arm_mass_kg=560.0,
    ),
    RosiArm(
        name="fanuc_m900ia260l", model="M-900iA/260L",
        file=_FANUC.format("fanuc_m900ia_support/urdf/m900ia260l_macro.xacro"),
        params=OpwParams(a1=0.37, a2=-0.2, b=0.0, c1=0.0, c2=1.05, c3=1.705, c4=0.27),
        limits_deg=((-180, 180), (-75, 75), (-121.5, 90), (-360, 360), (-125, 125), (-360, 360)),
        speed_deg_s=(100, 105, 95, 120, 120, 200), rounded=True, payload_kg=260.0,
        floor=-0.95,
        arm_mass_kg=1800.0,
    ),
    RosiArm(
        name="fanuc_r1000ia80f", model="R-1000iA/80F",
        file=_FANUC.format("fanuc_r1000ia_support/urdf/r1000ia80f_macro.xacro"),
        params=OpwParams(a1=0.32, a2=-0.225, b=0.0, c1=0.0, c2=0.87, c3=1.015, c4=0.175),
        limits_deg=((-180, 180), (-90, 155), (-180, 180), (-360, 360), (-125, 125), (-360, 360)),
        speed_deg_s=(170, 140, 160, 230, 230, 350), rounded=True, payload_kg=80.0,
        floor=-0.45,
        arm_mass_kg=620.0,
    ),
    RosiArm(
        name="fanuc_r2000ib210f", model="R-2000iB/210F",
        file=_FANUC_EXPERIMENTAL.format("fanuc_r2000ib_support/urdf/r2000ib210f_macro.xacro"),
        params=OpwParams(a1=0.312, a2=-0.225, b=0.0, c1=0.0, c2=1.075, c3=1.28, c4=0.235),
        limits_deg=((-180, 180), (-60, 76), (-132, 230), (-360, 360), (-125, 125), (-360, 360)),
        speed_deg_s=(95, 90, 95, 120, 120, 190), rounded=False, payload_kg=210.0,
        floor=-0.67,
        arm_mass_kg=1240.0,
    ),
    RosiArm(
        name="fanuc_r2000ic165f", model="R-2000iC/165F",
        file=_FANUC_EXPERIMENTAL.format("fanuc_r2000ic_support/urdf/r2000ic165f_macro.xacro"),
        params=OpwParams(a1=0.312, a2=-0.225, b=0.0, c1=0.0, c2=1.075, c3=1.28, c4=0.215),
        limits_deg=((-185, 185), (-60, 76), (-132, 180), (-360, 360), (-125, 125), (-360, 360)),
        speed_deg_s=(130, 115, 125, 180, 180, 260), rounded=False, payload_kg=165.0,
        floor=-0.67,
        arm_mass_kg=1090.0,
    ),
    RosiArm(
        name="fanuc_r2000ic210l", model="R-2000iC/210L",
        file=_FANUC_EXPERIMENTAL.format("fanuc_r2000ic_support/urdf/r2000ic210l_macro.xacro"),
        params=OpwParams(a1=0.312, a2=-0.225, b=0.0, c1=0.0, c2=1.075, c3=1.73, c4=0.24),
        limits_deg=((-185, 185), (-60, 76), (-121, 180), (-360, 360), (-125, 125), (-360, 360)),
        speed_deg_s=(105, 90, 85, 120, 120, 200), rounded=False, payload_kg=210.0,
        floor=-0.67,
        arm_mass_kg=1110.0,
    ),
    RosiArm(
        name="fanuc_lrmate200i", model="LR Mate 200i",
        file=_FANUC.format("fanuc_lrmate200i_support/urdf/lrmate200i_macro.xacro"),
        params=OpwParams(a1=0.15, a2=-0.075, b=0.0, c1=0.0, c2=0.25, c3=0.29, c4=0.08),
        limits_deg=((-160, 160), (-33, 152), (-149.5, 165), (-190, 190), (-119.5, 119.5), (-360, 360)),
        speed_deg_s=(180, 180, 225, 400, 330, 480), rounded=True, payload_kg=3.0,
        floor=-0.35,
        arm_mass_kg=37.0,
        payload_source="FANUC LR Mate 200i data sheet: 3 kg, recalled, not re-verified here",
        mass_source="estimate: the LR Mate 200iB's 37 kg (data sheet, recalled; the same lengths in the ROS-I files)",
    ),
    RosiArm(
        name="fanuc_lrmate200ib3l", model="LR Mate 200iB/3L",
        file=_FANUC.format("fanuc_lrmate200ib_support/urdf/lrmate200ib3l_macro.xacro"),
        params=OpwParams(a1=0.15, a2=-0.075, b=0.0, c1=0.0, c2=0.25, c3=0.45, c4=0.08),
        limits_deg=((-160, 160), (-33, 152), (-125, 165), (-190, 190), (-120, 120), (-360, 360)),
        speed_deg_s=(140, 150, 160, 400, 330, 480), rounded=True, payload_kg=3.0,
        floor=-0.35,
        arm_mass_kg=37.0,
        mass_source="estimate: the LR Mate 200iB's 37 kg (data sheet, recalled; the same arm with a 160 mm longer forearm)",
    ),
    RosiArm(
        name="fanuc_lrmate200ic5l", model="LR Mate 200iC/5L",
        file=_FANUC.format("fanuc_lrmate200ic_support/urdf/lrmate200ic5l_macro.xacro"),
        params=OpwParams(a1=0.075, a2=-0.075, b=0.0, c1=0.0, c2=0.4, c3=0.41, c4=0.08),
        limits_deg=((-170, 170), (-90, 140), (-148, 230), (-190, 190), (-120, 120), (-360, 360)),
        speed_deg_s=(270, 270, 270, 450, 450, 720), rounded=True, payload_kg=5.0,
        floor=-0.33,
        arm_mass_kg=29.0,
    ),
    RosiArm(
        name="fanuc_lrmate200id4s", model="LR Mate 200iD/4S",
        file=_FANUC.format("fanuc_lrmate200id_support/urdf/lrmate200id4s_macro.xacro"),
        params=OpwParams(a1=0.0, a2=-0.02, b=0.0, c1=0.0, c2=0.26, c3=0.29, c4=0.07),
        limits_deg=((-170, 170), (-110, 120), (-69, 205), (-190, 190), (-120, 120), (-360, 360)),
        speed_deg_s=(460, 460, 520, 560, 560, 900), rounded=False, payload_kg=4.0,
        floor=-0.33,
        arm_mass_kg=20.0,
    ),
    RosiArm(
        name="fanuc_lrmate200id4sc", model="LR Mate 200iD/4SC",
        file=_FANUC.format("fanuc_lrmate200id_support/urdf/lrmate200id4sc_macro.xacro"),
        params=OpwParams(a1=0.0, a2=-0.02, b=0.0, c1=0.0, c2=0.26, c3=0.29, c4=0.08),
        limits_deg=((-170, 170), (-110, 120), (-69, 205), (-190, 190), (-118, 118), (-360, 360)),
        speed_deg_s=(460, 460, 520, 560, 560, 900), rounded=False, payload_kg=4.0,
        floor=-0.33,
        arm_mass_kg=20.0,
        mass_source="estimate: the LR Mate 200iD/4S's 20 kg (data sheet, recalled; its clean-room version)",
    ),
    RosiArm(
        name="fanuc_lrmate200id7lc", model="LR Mate 200iD/7LC",
        file=_FANUC.format("fanuc_lrmate200id_support/urdf/lrmate200id7lc_macro.xacro"),
        params=OpwParams(a1=0.05, a2=-0.035, b=0.0, c1=0.0, c2=0.44, c3=0.42, c4=0.092),
        limits_deg=((-170, 170), (-100, 145), (-70, 213), (-190, 190), (-125, 125), (-360, 360)),
        speed_deg_s=(370, 310, 410, 550, 545, 1000), rounded=False, payload_kg=7.0,
        floor=-0.33,
        arm_mass_kg=27.0,
        mass_source="estimate: the LR Mate 200iD/7L's 27 kg (data sheet, recalled; its clean-room version)",
    ),
    RosiArm(
        name="fanuc_m6ib6s", model="M-6iB/6S",
        file=_FANUC.format("fanuc_m6ib_support/urdf/m6ib6s_macro.xacro"),
        params=OpwParams(a1=0.15, a2=-0.1, b=0.0, c1=0.0, c2=0.36, c3=0.43, c4=0.1),
        limits_deg=((-170, 170), (-90, 160), (-155, 155), (-190, 190), (-140, 140), (-360, 360)),
        speed_deg_s=(200, 200, 260, 400, 400, 720), rounded=True, payload_kg=6.0,
        floor=-0.45,
        arm_mass_kg=135.0,
        mass_source="estimate: the M-6iB's 135 kg (data sheet, recalled; the same base with shorter arms, so an upper bound)",
    ),
    RosiArm(
        name="fanuc_cr7ial", model="CR-7iA/L",
        file=_FANUC.format("fanuc_cr7ia_support/urdf/cr7ial_macro.xacro"),
        params=OpwParams(a1=0.05, a2=-0.035, b=0.0, c1=0.0, c2=0.44, c3=0.42, c4=0.08),
        limits_deg=((-170, 170), (-66, 100), (-140, 244), (-190, 190), (-120, 120), (-360, 360)),
        speed_deg_s=(370, 310, 410, 550, 545, 1000), rounded=True, payload_kg=7.0,
        floor=-0.457,
        arm_mass_kg=55.0,
    ),
    RosiArm(
        name="fanuc_r2000ic125l", model="R-2000iC/125L",
        file=_FANUC_EXPERIMENTAL.format("fanuc_r2000ic_support/urdf/r2000ic125l_macro.xacro"),
        params=OpwParams(a1=0.312, a2=-0.225, b=0.0, c1=0.0, c2=1.075, c3=1.73, c4=0.215),
        limits_deg=((-185, 185), (-60, 76), (-121, 180), (-360, 360), (-125, 125), (-360, 360)),
        speed_deg_s=(130, 115, 125, 180, 180, 260), rounded=False, payload_kg=125.0,
        floor=-0.67,
        arm_mass_kg=1110.0,
        mass_source="estimate: the R-2000iC/210L's 1110 kg (data sheet, recalled; the same arm lengths)",
    ),
    RosiArm(
        name="fanuc_r2000ic210f", model="R-2000iC/210F",
        file=_FANUC_EXPERIMENTAL.format("fanuc_r2000ic_support/urdf/r2000ic210f_macro.xacro"),
        params=OpwParams(a1=0.312, a2=-0.225, b=0.0, c1=0.0, c2=1.075, c3=1.28, c4=0.215),
        limits_deg=((-185, 185), (-60, 76), (-132, 180), (-360, 360), (-125, 125), (-360, 360)),
        speed_deg_s=(120, 105, 110, 140, 140, 220), rounded=False, payload_kg=210.0,
        floor=-0.67,
        arm_mass_kg=1090.0,
        mass_source="estimate: the R-2000iC/165F's 1090 kg (data sheet, recalled; the same arm lengths)",
    ),
    RosiArm(
        name="fanuc_r2000ic270f", model="R-2000iC/270F",
        file=_FANUC_EXPERIMENTAL.format("fanuc_r2000ic_support/urdf/r2000ic270f_macro.xacro"),
        params=OpwParams(a1=0.312, a2=-0.225, b=0.0, c1=0.0, c2=1.075, c3=1.28, c4=0.24),
        limits_deg=((-185, 185), (-60, 76), (-132, 180), (-360, 360), (-125, 125), (-360, 360)),
        speed_deg_s=(105, 90, 85, 120, 120, 200), rounded=False, payload_kg=270.0,
        floor=-0.67,
        arm_mass_kg=1090.0,
        mass_source="estimate: the R-2000iC/165F's 1090 kg (data sheet, recalled; the same arm lengths with a heavier wrist, so a lower bound)",
    ),
)


def fanuc_arms() -> list[RobotSpec]:
    """The FANUC arms of the ROS-I packages that library_rosi.py and library.py do not hold."""

    from rmot.sim.robots.library_common import FANUC, FANUC_CONV  # late: loads subprocess only when this runs

    brand = RosiBrand(vendor="FANUC", jmap=FANUC, conventions=FANUC_CONV, flange_rz=math.pi, limits_note=_J3_NOTE)
    return [rosi_spec(arm, brand) for arm in _ARMS]
