"""ABB arms of ROS-Industrial's `abb` and `abb_experimental` support packages.

Each row is one macro file (repository, path and commit in `file`), read as library_rosi.py
reads the IRB 2400: the OPW lengths off its joint origins (every joint's rpy is zero, J1..J6
turn about +z, +y, +y, +x, +y, +x of base_link), the joint bounds and speeds off its <limit>
tags, tool0 turned (0, 90 deg, 0) from link_6 (ABB's tool0, z out of the flange) and the ROS-I
`base` frame at base_link (ABB's base frame). The RAPID joint values are the URDF's one to one
(ros-industrial/abb abb_driver). tests/robots/reference_arms_abb.py holds each file's chain
as published; tests/robots/test_reference_fk.py composes it independently and compares.

Not here: IRB 2400-12/1.55 (the kinematics, bounds and speeds of `abb_irb2400`), IRB 6640 of
abb_irb6600_support (an older description of the IRB 6640-185/2.80 with an 11 mm lateral J2
offset), IRB 4400L-30/2.43 (its tool0 keeps link_6's axes, not ABB's tool0), IRB 52 (the
IRB 1600's geometry with every speed 180 deg/s, a placeholder), IRB 5400 (no joint_1..joint_6
chain, a paint arm with an offset wrist), CRB 15000 GoFa (no spherical wrist: OPW does not
apply).
"""

from __future__ import annotations

from rmot.sim.robots.library_rosi_rows import RosiArm, RosiBrand, rosi_spec
from rmot.sim.robots.opw import OpwParams
from rmot.sim.robots.spec import RobotSpec

__all__ = ["abb_arms"]

_ABB = "ros-industrial/abb {} @ 77db19bdb098"
_ABB_EXPERIMENTAL = "ros-industrial/abb_experimental {} @ 20b9cf86ad27"

_ARMS = (
    RosiArm(
        name="abb_irb120t", model="IRB 120T-3/0.58",
        file=_ABB_EXPERIMENTAL.format("abb_irb120_support/urdf/irb120t_3_58_macro.xacro"),
        params=OpwParams(a1=0.0, a2=-0.07, b=0.0, c1=0.29, c2=0.27, c3=0.302, c4=0.072),
        limits_deg=((-165, 165), (-110, 110), (-110, 70), (-160, 160), (-120, 120), (-400, 400)),
        speed_deg_s=(250, 250, 250, 420, 590, 600), rounded=True, payload_kg=3.0,
        arm_mass_kg=25.0,
    ),
    RosiArm(
        name="abb_irb1200_5_90", model="IRB 1200-5/0.9",
        file=_ABB_EXPERIMENTAL.format("abb_irb1200_support/urdf/irb1200_5_90_macro.xacro"),
        params=OpwParams(a1=0.0, a2=-0.042, b=0.0, c1=0.3991, c2=0.448, c3=0.451, c4=0.082),
        limits_deg=((-170, 170), (-100, 130), (-200, 70), (-270, 270), (-130, 130), (-360, 360)),
        speed_deg_s=(288, 240, 300, 400, 405, 600), rounded=True, payload_kg=5.0,
        link_mass_kg=(11.8419, 17.5394, 7.46365, 2.74436, 0.62953, 0.137),
    ),
    RosiArm(
        name="abb_irb1200_7_70", model="IRB 1200-7/0.7",
        file=_ABB_EXPERIMENTAL.format("abb_irb1200_support/urdf/irb1200_7_70_macro.xacro"),
        params=OpwParams(a1=0.0, a2=-0.042, b=0.0, c1=0.3991, c2=0.35, c3=0.351, c4=0.082),
        limits_deg=((-170, 170), (-100, 135), (-200, 70), (-270, 270), (-130, 130), (-360, 360)),
        speed_deg_s=(288, 240, 300, 400, 405, 600), rounded=True, payload_kg=7.0,
        arm_mass_kg=52.0,
    ),
    RosiArm(
        name="abb_irb1600_6_12", model="IRB 1600-6/1.2",
        file=_ABB_EXPERIMENTAL.format("abb_irb1600_support/urdf/irb1600_6_12_macro.xacro"),
        params=OpwParams(a1=0.15, a2=0.0, b=0.0, c1=0.4865, c2=0.475, c3=0.6, c4=0.065),
        limits_deg=((-180, 180), (-63, 110), (-235, 55), (-200, 200), (-115, 115), (-400, 400)),
        speed_deg_s=(150, 160, 170, 320, 400, 450), rounded=True, payload_kg=6.0,
        arm_mass_kg=250.0,
    ),
    RosiArm(
        name="abb_irb2600_12_165", model="IRB 2600-12/1.65",
        file=_ABB_EXPERIMENTAL.format("abb_irb2600_support/urdf/irb2600_12_165_macro.xacro"),
        params=OpwParams(a1=0.15, a2=-0.115, b=0.0, c1=0.445, c2=0.7, c3=0.795, c4=0.085),
        limits_deg=((-180, 180), (-155, 95), (-155, 75), (-400, 400), (-120, 120), (-400, 400)),
        speed_deg_s=(175, 175, 175, 360, 360, 500), rounded=True, payload_kg=12.0,
        arm_mass_kg=272.0,
    ),
    RosiArm(
        name="abb_irb4600_20_250", model="IRB 4600-20/2.50",
        file=_ABB_EXPERIMENTAL.format("abb_irb4600_support/urdf/irb4600_20_250_macro.xacro"),
        params=OpwParams(a1=0.175, a2=-0.175, b=0.0, c1=0.495, c2=1.095, c3=1.2305, c4=0.085),
        limits_deg=((-180, 180), (-90, 150), (-180, 75), (-400, 400), (-125, 120), (-400, 400)),
        speed_deg_s=(175, 175, 175, 360, 360, 500), rounded=False, payload_kg=20.0,
        arm_mass_kg=435.0,
    ),
    RosiArm(
        name="abb_irb4600_40_255", model="IRB 4600-40/2.55",
        file=_ABB_EXPERIMENTAL.format("abb_irb4600_support/urdf/irb4600_40_255_macro.xacro"),
        params=OpwParams(a1=0.175, a2=-0.175, b=0.0, c1=0.495, c2=1.095, c3=1.27, c4=0.135),
        limits_deg=((-180, 180), (-90, 150), (-180, 75), (-400, 400), (-125, 120), (-400, 400)),
        speed_deg_s=(175, 175, 175, 250, 250, 360), rounded=False, payload_kg=40.0,
        arm_mass_kg=435.0,
    ),
    RosiArm(
        name="abb_irb6600_225_255", model="IRB 6600-225/2.55",
        file=_ABB.format("abb_irb6600_support/urdf/irb6600_225_255_macro.xacro"),
        params=OpwParams(a1=0.32, a2=-0.2, b=0.0, c1=0.78, c2=1.075, c3=1.142, c4=0.2),
        limits_deg=((-180, 180), (-65, 80), (-180, 60), (-300, 300), (-120, 120), (-300, 300)),
        speed_deg_s=(100, 90, 90, 150, 120, 190), rounded=True, payload_kg=225.0,
        arm_mass_kg=1870.0,
    ),
    RosiArm(
        name="abb_irb6640_185_280", model="IRB 6640-185/2.80",
        file=_ABB.format("abb_irb6640_support/urdf/irb6640_185_280_macro.xacro"),
        params=OpwParams(a1=0.32, a2=-0.2, b=0.0, c1=0.78, c2=1.075, c3=1.392, c4=0.2),
        limits_deg=((-170, 170), (-65, 85), (-180, 70), (-300, 300), (-120, 120), (-360, 360)),
        speed_deg_s=(100, 90, 90, 170, 140, 190), rounded=True, payload_kg=185.0,
        arm_mass_kg=1310.0,
    ),
    RosiArm(
        name="abb_irb6650s_125_350", model="IRB 6650S-125/3.50",
        file=_ABB_EXPERIMENTAL.format("abb_irb6650s_support/urdf/irb6650s_125_350_macro.xacro"),
        params=OpwParams(a1=0.6, a2=-0.2, b=0.0, c1=0.63, c2=1.28, c3=1.592, c4=0.2),
        limits_deg=((-180, 180), (-40, 160), (-180, 70), (-300, 300), (-120, 120), (-360, 360)),
        speed_deg_s=(110, 90, 90, 150, 120, 235), rounded=False, payload_kg=125.0,
        arm_mass_kg=2250.0,
    ),
    RosiArm(
        name="abb_irb6650s_90_390", model="IRB 6650S-90/3.90",
        file=_ABB_EXPERIMENTAL.format("abb_irb6650s_support/urdf/irb6650s_90_390_macro.xacro"),
        params=OpwParams(a1=0.6, a2=-0.2, b=0.0, c1=0.63, c2=1.28, c3=2.042, c4=0.2),
        limits_deg=((-180, 180), (-40, 160), (-180, 70), (-300, 300), (-120, 120), (-360, 360)),
        speed_deg_s=(100, 90, 90, 150, 120, 235), rounded=False, payload_kg=90.0,
        arm_mass_kg=2250.0,
    ),
    RosiArm(
        name="abb_irb6700_200_260", model="IRB 6700-200/2.60",
        file=_ABB_EXPERIMENTAL.format("abb_irb6700_support/urdf/irb6700_200_260_macro.xacro"),
        params=OpwParams(a1=0.32, a2=-0.2, b=0.0, c1=0.78, c2=1.125, c3=1.1425, c4=0.2),
        limits_deg=((-170, 170), (-65, 85), (-180, 70), (-300, 300), (-130, 130), (-360, 360)),
        speed_deg_s=(110, 110, 110, 190, 150, 210), rounded=False, payload_kg=200.0,
        arm_mass_kg=1170.0,
    ),
    RosiArm(
        name="abb_irb6700_235_265", model="IRB 6700-235/2.65",
        file=_ABB_EXPERIMENTAL.format("abb_irb6700_support/urdf/irb6700_235_265_macro.xacro"),
        params=OpwParams(a1=0.32, a2=-0.2, b=0.0, c1=0.78, c2=1.135, c3=1.1825, c4=0.2),
        limits_deg=((-170, 170), (-65, 85), (-180, 70), (-300, 300), (-130, 130), (-360, 360)),
        speed_deg_s=(100, 90, 90, 170, 120, 190), rounded=False, payload_kg=235.0,
        arm_mass_kg=1250.0,
    ),
    RosiArm(
        name="abb_irb7600_150_350", model="IRB 7600-150/3.50",
        file=_ABB_EXPERIMENTAL.format("abb_irb7600_support/urdf/irb7600_150_350_macro.xacro"),
        params=OpwParams(a1=0.41, a2=-0.165, b=0.0, c1=0.78, c2=1.075, c3=2.012, c4=0.25),
        limits_deg=((-180, 180), (-60, 85), (-180, 60), (-300, 300), (-100, 100), (-360, 360)),
        speed_deg_s=(100, 60, 60, 100, 100, 190), rounded=False, payload_kg=150.0,
        arm_mass_kg=2450.0,
    ),
)


def abb_arms() -> list[RobotSpec]:
    """The ABB arms of the ROS-I packages that library_rosi.py and library.py do not hold."""
    from rmot.sim.robots.library_common import ABB, ABB_CONV  # late: loads subprocess only when this runs

    brand = RosiBrand(vendor="ABB", jmap=ABB, conventions=ABB_CONV)
    return [rosi_spec(arm, brand) for arm in _ARMS]
