"""The built-in robot library: public kinematic data and datasheet limits of real arms.

Joint values are the controller's (pendant) values; fk() gives the vendor's flange frame in
the vendor's base frame:

ABB      J1..J6 as in a RAPID jointtarget; all zero = calibration position (upper arm up,
         forearm horizontal); base frame on the floor at the J1 axis; flange = tool0 (z out
         of the flange; at zero z along base +x, x down).
KUKA     A1..A6 as on the KCP: A1 > 0 turns clockwise seen from above, A2 = -90° is the
         upper arm upright, A3 = +90° then puts the forearm horizontal (HOME = 0,-90,90,0,0,0);
         A4 and A6 turn the other way round than A1's sense; flange = $FLANGE (at HOME z
         forward, x down: A B C = 0 90 0); base = $ROBROOT on the floor.
Fanuc    J1..J6 as the teach pendant's joint display: J3 is the forearm's angle to the
         horizontal (the J2/J3 interaction), so moving J2 alone keeps the forearm's
         attitude; J3 > 0 raises the forearm. Base = Fanuc world frame, origin on the J1 axis
         at the J2 height (the mounting face is below it). Flange = faceplate (at zero z
         forward, x up: W P R = 180 -90 0).
Yaskawa  S L U R B T in degrees (pulses / pulse-per-degree); U is relative to L; base on the
         mounting face; flange = tool0 (at zero z forward, x up).
Staubli  J1..J6; zero = arm stretched vertically ("candle"); flange z along J6.
UR       the DH θ of UR's table (what PolyScope shows); base = UR Base frame (DH frame 0);
         flange = the tool flange (DH frame 6).
Puma     Corke's joint values (base frame at the shoulder, as the Robotics Toolbox).

Accelerations are not published by the vendors: each is an estimate, the max axis speed
reached in 0.25 s (4 × speed per second). Lengths in m, angles in degrees here (converted by
`robot.Robot`).
"""

from __future__ import annotations

import math

from rmot.compiler.robots.dh import DHRow, DHTable
from rmot.compiler.robots.opw import OpwJointMap, OpwParams
import numpy as np

from rmot.compiler.robots.spec import OPW_TOUCHING, RobotSpec, opw_segments, opw_spec, ur_spec
from rmot.compiler.robots.urik import UrParams

__all__ = ["SPECS"]

H = math.pi / 2


def _acc(speeds: tuple[float, ...]) -> tuple[float, ...]:
    return tuple(4.0 * s for s in speeds)


ABB = OpwJointMap(offset=(0, 0, H, 0, 0, 0))  # J3 = 0: forearm horizontal
KUKA = OpwJointMap(sign=(-1, 1, 1, -1, 1, -1), offset=(0, H, 0, 0, 0, 0))  # A2 = -90°: upright
# Fanuc: J3 is the forearm's angle to the horizontal (J2/J3 interaction), positive up; the
# model variable u3 = J2 + J3 is the relative elbow angle. J4..J6 turn the other way round.
FANUC = OpwJointMap(
    sign=(1, 1, -1, -1, -1, -1), offset=(0, 0, H, 0, 0, 0),
    coupling=((1, 0, 0, 0, 0, 0), (0, 1, 0, 0, 0, 0), (0, 1, 1, 0, 0, 0),
              (0, 0, 0, 1, 0, 0), (0, 0, 0, 0, 1, 0), (0, 0, 0, 0, 0, 1)),
)
YASKAWA = OpwJointMap(sign=(1, 1, -1, -1, -1, -1), offset=(0, 0, H, 0, 0, 0))  # U relative to L
STAUBLI = OpwJointMap()  # zero = arm stretched vertically (the "candle")


def _abb_kuka() -> list[RobotSpec]:
    return [
        # ABB Product specification IRB 120 (3HAC035960-001): tool0 at (374, 0, 630) mm in
        # the calibration position, reach 580 mm; link lengths from its dimension drawing.
        opw_spec(
            name="abb_irb120", vendor="ABB", model="IRB 120-3/0.58", source="ABB 3HAC035960-001",
            params=OpwParams(a1=0.0, a2=-0.070, b=0.0, c1=0.290, c2=0.270, c3=0.302, c4=0.072), jmap=ABB,
            limits_deg=((-165, 165), (-110, 110), (-110, 70), (-160, 160), (-120, 120), (-400, 400)),
            speed_deg_s=(250, 250, 250, 320, 320, 420),
            # estimate from ABB IRB 120 product specification standard cycle 0.58 s (25 mm up,
            # 300 mm across, 25 mm down and back, 1 kg): 16 x the joint speed per second (vmax
            # in 62.5 ms) gives 0.60 s with 10 mm corners, 0.69 s with exact stops (issue 11)
            accel_deg_s2=(4000, 4000, 4000, 5120, 5120, 6720),
            reach=0.580, radii=(0.09, 0.07, 0.055, 0.055, 0.05, 0.045, 0.03),
        ),
        # ABB Product specification IRB 1600 (3HAC023604-001), variant 6 kg / 1.45 m.
        opw_spec(
            name="abb_irb1600", vendor="ABB", model="IRB 1600-6/1.45", source="ABB 3HAC023604-001",
            params=OpwParams(a1=0.150, a2=0.0, b=0.0, c1=0.4865, c2=0.700, c3=0.600, c4=0.065), jmap=ABB,
            limits_deg=((-180, 180), (-90, 150), (-245, 65), (-200, 200), (-115, 115), (-400, 400)),
            speed_deg_s=(150, 160, 170, 320, 400, 460), accel_deg_s2=_acc((150, 160, 170, 320, 400, 460)),
            reach=1.450, radii=(0.15, 0.12, 0.09, 0.09, 0.07, 0.06, 0.045),
        ),
        # ABB Product specification IRB 4600 (3HAC032885-001), variant 60 kg / 2.05 m.
        opw_spec(
            name="abb_irb4600", vendor="ABB", model="IRB 4600-60/2.05", source="ABB 3HAC032885-001",
            params=OpwParams(a1=0.175, a2=-0.175, b=0.0, c1=0.495, c2=0.900, c3=0.960, c4=0.135), jmap=ABB,
            limits_deg=((-180, 180), (-90, 150), (-180, 75), (-400, 400), (-125, 120), (-400, 400)),
            speed_deg_s=(175, 175, 175, 250, 250, 360), accel_deg_s2=_acc((175, 175, 175, 250, 250, 360)),
            reach=2.050, radii=(0.25, 0.2, 0.14, 0.15, 0.12, 0.1, 0.07),
        ),
        # KUKA KR AGILUS sixx specification (PF0030/E), KR 6 R900 sixx: reach 901.5 mm to
        # the wrist root point; dimensions 400/25/455/35/420/80 mm from its working envelope.
        opw_spec(
            name="kuka_kr6_r900", vendor="KUKA", model="KR 6 R900 sixx", source="KUKA KR AGILUS sixx spec PF0030",
            params=OpwParams(a1=0.025, a2=-0.035, b=0.0, c1=0.400, c2=0.455, c3=0.420, c4=0.080), jmap=KUKA,
            limits_deg=((-170, 170), (-190, 45), (-120, 156), (-185, 185), (-120, 120), (-350, 350)),
            speed_deg_s=(360, 300, 360, 381, 388, 615), accel_deg_s2=_acc((360, 300, 360, 381, 388, 615)),
            reach=0.9015, radii=(0.09, 0.08, 0.06, 0.06, 0.05, 0.045, 0.03),
        ),
        # KUKA KR 16-2 specification (Spez KR 16-2): reach 1610 mm; 675/260/680/35/670/158 mm.
        opw_spec(
            name="kuka_kr16", vendor="KUKA", model="KR 16-2", source="KUKA Spez KR 16-2",
            params=OpwParams(a1=0.260, a2=-0.035, b=0.0, c1=0.675, c2=0.680, c3=0.670, c4=0.158), jmap=KUKA,
            limits_deg=((-185, 185), (-155, 35), (-130, 154), (-350, 350), (-130, 130), (-350, 350)),
            speed_deg_s=(156, 156, 156, 330, 330, 615), accel_deg_s2=_acc((156, 156, 156, 330, 330, 615)),
            reach=1.610, radii=(0.2, 0.16, 0.11, 0.11, 0.09, 0.07, 0.05),
        ),
        # KUKA KR QUANTEC prime specification, KR 210 R2700 prime: reach 2700 mm;
        # 675/350/1150/41/1200/215 mm.
        opw_spec(
            name="kuka_kr210", vendor="KUKA", model="KR 210 R2700 prime", source="KUKA KR QUANTEC prime spec",
            params=OpwParams(a1=0.350, a2=-0.041, b=0.0, c1=0.675, c2=1.150, c3=1.200, c4=0.215), jmap=KUKA,
            limits_deg=((-185, 185), (-140, -5), (-120, 168), (-350, 350), (-125, 125), (-350, 350)),
            speed_deg_s=(123, 115, 112, 179, 172, 219), accel_deg_s2=_acc((123, 115, 112, 179, 172, 219)),
            reach=2.700, radii=(0.35, 0.3, 0.2, 0.22, 0.17, 0.13, 0.09),
        ),
    ]


def _fanuc_yaskawa_staubli() -> list[RobotSpec]:
    return [
        # FANUC LR Mate 200iD data sheet: reach 717 mm. Fanuc's world frame has its origin
        # on the J1 axis at the J2 height (so c1 = 0; the mounting face is 330 mm below);
        # faceplate at (465, 0, 365) mm, W P R = (180, -90, 0) at all joints zero.
        opw_spec(
            name="fanuc_lrmate200id", vendor="FANUC", model="LR Mate 200iD", source="FANUC LR Mate 200iD data sheet",
            params=OpwParams(a1=0.050, a2=-0.035, b=0.0, c1=0.0, c2=0.330, c3=0.335, c4=0.080), jmap=FANUC,
            limits_deg=((-170, 170), (-100, 145), (-140, 205), (-190, 190), (-125, 125), (-360, 360)),
            speed_deg_s=(450, 380, 520, 550, 545, 1000), accel_deg_s2=_acc((450, 380, 520, 550, 545, 1000)),
            reach=0.717, radii=(0.09, 0.08, 0.06, 0.06, 0.05, 0.045, 0.03), flange_rz=math.pi, floor=-0.330,
        ),
        # FANUC M-20iA data sheet: reach 1811 mm; 525/150/790/250/835/100 mm (world frame at J2 height).
        opw_spec(
            name="fanuc_m20ia", vendor="FANUC", model="M-20iA", source="FANUC M-20iA data sheet",
            params=OpwParams(a1=0.150, a2=-0.250, b=0.0, c1=0.0, c2=0.790, c3=0.835, c4=0.100), jmap=FANUC,
            limits_deg=((-170, 170), (-100, 160), (-185, 273), (-200, 200), (-180, 180), (-450, 450)),
            speed_deg_s=(195, 175, 180, 360, 360, 550), accel_deg_s2=_acc((195, 175, 180, 360, 360, 550)),
            reach=1.811, radii=(0.2, 0.16, 0.1, 0.12, 0.09, 0.07, 0.05), flange_rz=math.pi, floor=-0.525,
        ),
        # Yaskawa Motoman GP8 specifications (178642-1CD): reach 727 mm; 330/40/345/40/340/80 mm.
        opw_spec(
            name="yaskawa_gp8", vendor="Yaskawa", model="Motoman GP8", source="Yaskawa GP8 spec 178642-1CD",
            params=OpwParams(a1=0.040, a2=-0.040, b=0.0, c1=0.330, c2=0.345, c3=0.340, c4=0.080), jmap=YASKAWA,
            limits_deg=((-170, 170), (-65, 145), (-70, 190), (-190, 190), (-135, 135), (-360, 360)),
            speed_deg_s=(455, 385, 520, 550, 550, 1000), accel_deg_s2=_acc((455, 385, 520, 550, 550, 1000)),
            reach=0.727, radii=(0.09, 0.08, 0.06, 0.06, 0.05, 0.045, 0.03), flange_rz=math.pi,
        ),
        # Stäubli TX2-60 data sheet (D28110804): reach 670 mm between axes 1 and 6;
        # 375/290/310/70 mm, 20 mm offset between the upper arm and the forearm planes.
        opw_spec(
            name="staubli_tx2_60", vendor="Staubli", model="TX2-60", source="Staubli TX2-60 data sheet D28110804",
            params=OpwParams(a1=0.0, a2=0.0, b=0.020, c1=0.375, c2=0.290, c3=0.310, c4=0.070), jmap=STAUBLI,
            limits_deg=((-180, 180), (-127.5, 127.5), (-142.5, 142.5), (-270, 270), (-121, 132.5), (-270, 270)),
            speed_deg_s=(435, 410, 540, 995, 1065, 1445), accel_deg_s2=_acc((435, 410, 540, 995, 1065, 1445)),
            reach=0.670, radii=(0.09, 0.08, 0.06, 0.06, 0.05, 0.04, 0.03),
        ),
    ]


def _puma560() -> RobotSpec:
    """Puma 560 in the standard-DH convention of Corke, "A robotics toolbox for MATLAB"
    (IEEE RAM 1996) / Robotics Toolbox `mdl_puma560`: base frame at the shoulder, no tool
    (fkine(qz) = (0.4521, -0.1500, 0.4318) m), joint values = DH θ; limits as in qlim."""
    h = math.pi / 2
    rows = (
        DHRow(d=0.0, a=0.0, alpha=h), DHRow(d=0.0, a=0.4318, alpha=0.0),
        DHRow(d=0.15005, a=0.0203, alpha=-h), DHRow(d=0.4318, a=0.0, alpha=h),
        DHRow(d=0.0, a=0.0, alpha=-h), DHRow(d=0.0, a=0.0, alpha=0.0),
    )
    params = OpwParams(a1=0.0, a2=0.0203, b=-0.15005, c1=0.0, c2=0.4318, c3=0.4318, c4=0.0)
    jmap = OpwJointMap(sign=(1, -1, -1, 1, -1, 1), offset=(0, h, -h, 0, 0, 0))
    speeds = (82, 74, 137, 228, 200, 246)  # Unimation Puma 500 series manual (approx.)
    return RobotSpec(
        name="puma560", vendor="Unimation", model="PUMA 560", source="Corke 1996, mdl_puma560",
        dh=DHTable(rows), limits_deg=((-160, 160), (-45, 225), (-225, 45), (-110, 170), (-100, 100), (-266, 266)),
        speed_deg_s=speeds, accel_deg_s2=_acc(speeds), reach=0.864, opw=(params, jmap),
        segments=opw_segments(params, (0.1, 0.09, 0.07, 0.07, 0.05, 0.04, 0.03), floor=-0.672),
        solid_pose=tuple(jmap.from_theta(np.zeros(6)).tolist()),
        extra_adjacent=OPW_TOUCHING,
    )


def _ur() -> list[RobotSpec]:
    # Universal Robots, "DH parameters for calculations of kinematics and dynamics"
    # (universal-robots.com/articles/ur/application-installation/dh-parameters-...), e-Series
    # and CB3 tables; speeds and reach from the e-Series data sheets. Shoulder/elbow offsets
    # (lateral steps of the tubes along J2) from UR's ur_description URDFs.
    return [
        ur_spec(name="ur3e", model="UR3e", source="UR DH table; UR3e data sheet",
                params=UrParams(0.15185, -0.24355, -0.2132, 0.13105, 0.08535, 0.0921),
                speed_deg_s=(180, 180, 180, 360, 360, 360), accel_deg_s2=_acc((180, 180, 180, 360, 360, 360)),
                reach=0.500, shoulder_off=0.120, elbow_off=0.093, radii=(0.065, 0.05, 0.045, 0.04, 0.035)),
        ur_spec(name="ur5e", model="UR5e", source="UR DH table; UR5e data sheet",
                params=UrParams(0.1625, -0.425, -0.3922, 0.1333, 0.0997, 0.0996),
                speed_deg_s=(180,) * 6, accel_deg_s2=_acc((180,) * 6),
                reach=0.850, shoulder_off=0.138, elbow_off=0.131, radii=(0.075, 0.065, 0.055, 0.045, 0.045)),
        ur_spec(name="ur10e", model="UR10e", source="UR DH table; UR10e data sheet",
                params=UrParams(0.1807, -0.6127, -0.57155, 0.17415, 0.11985, 0.11655),
                speed_deg_s=(120, 120, 180, 180, 180, 180), accel_deg_s2=_acc((120, 120, 180, 180, 180, 180)),
                reach=1.300, shoulder_off=0.176, elbow_off=0.137, radii=(0.095, 0.08, 0.065, 0.055, 0.05)),
    ]


SPECS: dict[str, RobotSpec] = {s.name: s for s in _abb_kuka() + _fanuc_yaskawa_staubli() + [_puma560()] + _ur()}
