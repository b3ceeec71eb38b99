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
Yaskawa  S L U R B T in degrees (pulses / pulse-per-degree); U is relative to L; base = the
         robot frame on the S axis at the L-axis height (330 mm above the mounting face for
         the GP8: ROS-I motoman `base`); flange = tool0 (at zero z forward, x up).
Staubli  J1..J6; zero = arm stretched vertically ("candle"); base = world frame at the J1/J2
         intersection (375 mm above the mounting face for the TX2-60); flange z along J6.
UR       the DH θ of UR's table (what PolyScope shows); base = UR Base frame (DH frame 0);
         flange = the tool flange (DH frame 6).
Puma     Corke's joint values (base frame at the shoulder, as the Robotics Toolbox).

Every number carries its source in the spec's `sources` (shown by `rmot robots show NAME`):
a vendor data sheet, a vendor's own description (KUKA's kroshu/kuka_robot_descriptions), a
ROS-Industrial support package, or "estimate: how". Each arm's geometry is checked against
an independent reference chain in tests/robots/test_reference_fk.py (reference, path and
commit in tests/robots/reference_arms.py). Accelerations: no vendor publishes its
controller's, so every arm's is an estimate, the max axis speed reached in 0.25 s (4 × speed
per second); KUKA's ROS descriptions (`*_joint_limits.yaml`) give joint accelerations for
planning, not the controller's (`_kuka_accel`), kept in the source text. Inertias and torque
limits: see `dynamics`. Lengths in m, angles in degrees here (converted by `robot.Robot`).
"""

from __future__ import annotations

import math
import re

from rmot.sim.robots.dh import DHRow, DHTable
from rmot.sim.robots.library_common import (
    ABB, ABB_CONV, ACC_EST, FANUC, FANUC_CONV, KROSHU, KUKA, KUKA_CONV, ROSI_ABB, STAUBLI, STAUBLI_CONV,
    UR_CONV, YASKAWA, YASKAWA_CONV, acc_estimate, conventions, kuka_accel_source, sources,
)
from rmot.sim.robots.opw import OpwJointMap, OpwParams
import numpy as np

from rmot.sim.robots.spec import OPW_TOUCHING, RobotSpec, opw_segments, opw_spec, ur_spec
from rmot.sim.robots.urik import UrParams

__all__ = ["SPECS"]

def _abb_kuka() -> list[RobotSpec]:
    """The ABB and KUKA rows of the library. Long on purpose: a table with one entry per arm, each with its cited source beside it."""
    from rmot.sim.robots.kuka_inertia import KUKA_INERTIA  # late: loads subprocess only when this runs
    from rmot.sim.robots.dynamics import INERTIA_METHOD as INERTIA  # late: loads subprocess only when this runs
    from rmot.sim.robots.dynamics import SPREAD_METHOD as SPREAD  # late: loads subprocess only when this runs
    from rmot.sim.robots.dynamics import EFFORT_METHOD as EFFORT  # late: loads subprocess only when this runs

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
            # in 62.5 ms) gives 0.60 s with 10 mm corners, 0.69 s with exact stops
            accel_deg_s2=(4000, 4000, 4000, 5120, 5120, 6720),
            reach=0.580, radii=(0.09, 0.07, 0.055, 0.055, 0.05, 0.045, 0.03),
            rated_payload_kg=3.0, arm_mass_kg=25.0, conventions=ABB_CONV,
            sources=sources(
                geometry=f"ABB 3HAC035960-001 dimension drawing; = {ROSI_ABB} abb_irb120_support/urdf/irb120_3_58_macro.xacro",
                limits="ABB 3HAC035960-001 working range; = the ROS-I URDF", speed="ABB 3HAC035960-001 axis max speeds; = the ROS-I URDF",
                accel=("estimate: from ABB 3HAC035960-001's standard cycle 0.58 s (25/300/25 mm, 1 kg): 16 x the joint "
                       "speed per second gives 0.60 s with 10 mm corners in rmot's timing (tests/plan/test_plan_optimal.py)"),
                reach="ABB 3HAC035960-001: 580 mm", mass=f"ABB 3HAC035960-001: arm 25 kg; {SPREAD}",
                inertia=INERTIA, effort=EFFORT, payload="ABB 3HAC035960-001: 3 kg (the model name IRB 120-3/0.58)"),
        ),
        # ABB IRB 1600, the 1.45 m arm. Geometry and limits as the ROS-I package of the 1.45 m
        # arm (irb1600_8_145): J2 max +120° there, where rmot had +150° (the 1.2 m arm's figure
        # is +110°): the reference for this reach is taken.
        opw_spec(
            name="abb_irb1600", vendor="ABB", model="IRB 1600-6/1.45", source=f"ABB 3HAC023604-001; {ROSI_ABB} irb1600_8_145",
            params=OpwParams(a1=0.150, a2=0.0, b=0.0, c1=0.4865, c2=0.700, c3=0.600, c4=0.065), jmap=ABB,
            limits_deg=((-180, 180), (-90, 120), (-245, 65), (-200, 200), (-115, 115), (-400, 400)),
            speed_deg_s=(150, 160, 170, 320, 400, 460), accel_deg_s2=acc_estimate((150, 160, 170, 320, 400, 460)),
            reach=1.450, radii=(0.15, 0.12, 0.09, 0.09, 0.07, 0.06, 0.045),
            rated_payload_kg=6.0, arm_mass_kg=250.0, conventions=ABB_CONV,
            sources=sources(
                geometry=f"{ROSI_ABB} abb_irb1600_support/urdf/irb1600_8_145_macro.xacro (150/486.5/700/600/65 mm)",
                limits=f"{ROSI_ABB} abb_irb1600_support/urdf/irb1600_8_145_macro.xacro (J2 -90..+120 deg)",
                speed=("ABB 3HAC023604-001 (= ROS-I irb1600_6_12_macro.xacro; ROS-I's 1.45 m file has 180/180/200/400/400/460 "
                       "deg/s: a disagreement not resolved here, the lower figures kept)"), accel=ACC_EST,
                reach="ABB 3HAC023604-001: 1.45 m", mass=f"ABB 3HAC023604-001: arm 250 kg; {SPREAD}",
                inertia=INERTIA, effort=EFFORT, payload="ABB 3HAC023604-001: 6 kg (the model name IRB 1600-6/1.45)"),
        ),
        # ABB Product specification IRB 4600 (3HAC032885-001), variant 60 kg / 2.05 m.
        opw_spec(
            name="abb_irb4600", vendor="ABB", model="IRB 4600-60/2.05", source="ABB 3HAC032885-001",
            params=OpwParams(a1=0.175, a2=-0.175, b=0.0, c1=0.495, c2=0.900, c3=0.960, c4=0.135), jmap=ABB,
            limits_deg=((-180, 180), (-90, 150), (-180, 75), (-400, 400), (-125, 120), (-400, 400)),
            speed_deg_s=(175, 175, 175, 250, 250, 360), accel_deg_s2=acc_estimate((175, 175, 175, 250, 250, 360)),
            reach=2.050, radii=(0.25, 0.2, 0.14, 0.15, 0.12, 0.1, 0.07),
            rated_payload_kg=60.0, arm_mass_kg=425.0, conventions=ABB_CONV,
            sources=sources(
                geometry=f"ABB 3HAC032885-001; = {ROSI_ABB} abb_irb4600_support/urdf/irb4600_60_205_macro.xacro",
                limits="ABB 3HAC032885-001; = the ROS-I URDF", speed="ABB 3HAC032885-001; = the ROS-I URDF", accel=ACC_EST,
                reach="ABB 3HAC032885-001: 2.05 m", mass=f"ABB 3HAC032885-001: arm 412-435 kg by variant, 425 kg taken; {SPREAD}",
                inertia=INERTIA, effort=EFFORT, payload="ABB 3HAC032885-001: 60 kg (the model name IRB 4600-60/2.05)"),
        ),
        # KUKA KR AGILUS sixx specification (PF0030/E), KR 6 R900 sixx: reach 901.5 mm to
        # the wrist root point; dimensions 400/25/455/35/420/80 mm from its working envelope.
        opw_spec(
            name="kuka_kr6_r900", vendor="KUKA", model="KR 6 R900 sixx", source="KUKA KR AGILUS sixx spec PF0030; kroshu kr6_r900_sixx",
            params=OpwParams(a1=0.025, a2=-0.035, b=0.0, c1=0.400, c2=0.455, c3=0.420, c4=0.080), jmap=KUKA,
            limits_deg=((-170, 170), (-190, 45), (-120, 156), (-185, 185), (-120, 120), (-350, 350)),
            speed_deg_s=(360, 300, 360, 381, 388, 615), accel_deg_s2=acc_estimate((360, 300, 360, 381, 388, 615)),
            reach=0.9015, radii=(0.09, 0.08, 0.06, 0.06, 0.05, 0.045, 0.03),
            rated_payload_kg=6.0, arm_mass_kg=52.0, conventions=KUKA_CONV,
            sources=sources(
                geometry=f"KUKA spec PF0030; = {KROSHU} kuka_agilus_support/urdf/kr6_r900_sixx_macro.xacro",
                limits=f"KUKA spec PF0030; = {KROSHU} kr6_r900_sixx_macro.xacro", speed=f"KUKA spec PF0030; = {KROSHU} kr6_r900_sixx_macro.xacro",
                accel=kuka_accel_source(f"{KROSHU} kuka_agilus_support/config/kr6_r900_sixx_joint_limits.yaml max_acceleration",
                                  (1241.4, 394.7, 1800.0, 7623.5, 7766.9, 15377.2)),
                reach="KUKA spec PF0030: 901.5 mm", mass=f"KUKA spec PF0030: arm 52 kg; {SPREAD}",
                inertia=INERTIA, effort=EFFORT, payload="KUKA spec PF0030: rated payload 6 kg"),
        ),
        # KUKA KR 16-2 specification (Spez KR 16-2): reach 1610 mm; 675/260/680/35/670/158 mm.
        # At HOME the A4 axis is 35 mm BELOW A3 (a2 > 0 here), as ROS-I's kr16_2 URDF has it.
        opw_spec(
            name="kuka_kr16", vendor="KUKA", model="KR 16-2", source="KUKA Spez KR 16-2; ROS-I kuka_experimental kr16_2",
            params=OpwParams(a1=0.260, a2=0.035, b=0.0, c1=0.675, c2=0.680, c3=0.670, c4=0.158), jmap=KUKA,
            limits_deg=((-185, 185), (-155, 35), (-130, 154), (-350, 350), (-130, 130), (-350, 350)),
            speed_deg_s=(156, 156, 156, 330, 330, 615), accel_deg_s2=acc_estimate((156, 156, 156, 330, 330, 615)),
            reach=1.610, radii=(0.2, 0.16, 0.11, 0.11, 0.09, 0.07, 0.05),
            rated_payload_kg=16.0, arm_mass_kg=235.0, conventions=KUKA_CONV,
            sources=sources(
                geometry="KUKA Spez KR 16-2; = ros-industrial/kuka_experimental kuka_kr16_support/urdf/kr16_2_macro.xacro (A4 35 mm below A3 at HOME)",
                limits="KUKA Spez KR 16-2; = the ROS-I URDF", speed="KUKA Spez KR 16-2; = the ROS-I URDF",
                accel=kuka_accel_source(f"{KROSHU} kuka_cybertech_support/config/kr16_r1610_2_joint_limits.yaml max_acceleration "
                                  "(the KR 16 R1610-2, same payload and reach class)", (623.1, 257.7, 1178.3, 5318.1, 5115.4, 6878.3)),
                reach="KUKA Spez KR 16-2: 1610 mm", mass=f"KUKA Spez KR 16-2: arm 235 kg; {SPREAD}",
                inertia=INERTIA, effort=EFFORT, payload="KUKA Spez KR 16-2: rated payload 16 kg"),
        ),
        # KUKA KR 210 R2700-2 (KR QUANTEC), all numbers from KUKA's own description: rmot
        # modelled the older KR 210 R2700 prime with the a2 sign wrong and no reference of
        # its own; the R2700-2 has one (geometry, limits, speeds, accelerations, masses, torques).
        opw_spec(
            name="kuka_kr210", vendor="KUKA", model="KR 210 R2700-2", source=f"{KROSHU} kr210_r2700_2",
            params=OpwParams(a1=0.330, a2=-0.115, b=0.0, c1=0.645, c2=1.150, c3=1.220, c4=0.215), jmap=KUKA,
            limits_deg=((-185, 185), (-140, -5), (-120, 168), (-350, 350), (-125, 125), (-350, 350)),
            speed_deg_s=(116.79, 111.45, 112.0, 179.0, 172.0, 220.0), accel_deg_s2=acc_estimate((116.79, 111.45, 112.0, 179.0, 172.0, 220.0)),
            reach=2.700, radii=(0.35, 0.3, 0.2, 0.22, 0.17, 0.13, 0.09),
            rated_payload_kg=210.0, link_mass_kg=(363.07, 232.06, 190.33, 42.411794929, 16.991732133, 6.6),
            effort_nm=(7290.0, 8910.0, 6988.84717, 2274.29199, 1398.30298, 781.554626), conventions=KUKA_CONV,
            link_inertia=KUKA_INERTIA["kuka_kr210"],
            sources=sources(
                geometry=f"{KROSHU} kuka_quantec_support/urdf/kr210_r2700_2_macro.xacro (330/645/1150/115/1220/215 mm)",
                limits=f"{KROSHU} kr210_r2700_2_macro.xacro", speed=f"{KROSHU} kuka_quantec_support/config/kr210_r2700_2_joint_limits.yaml",
                accel=kuka_accel_source(f"{KROSHU} kuka_quantec_support/config/kr210_r2700_2_joint_limits.yaml max_acceleration",
                                  (113.6, 72.4, 147.0, 403.3, 101.1, 107.3)),
                reach="the product name KR 210 R2700-2: 2700 mm (wrist centre 2705 mm)",
                mass=f"{KROSHU} kr210_r2700_2_macro.xacro link_1..link_6 <mass>",
                inertia=f"{KROSHU} kr210_r2700_2_macro.xacro link_1..link_6 <inertial> (rmot.sim.robots.kuka_inertia)",
                effort=f"{KROSHU} kr210_r2700_2_macro.xacro joint <limit effort>",
                payload="the product name KR 210 R2700-2: 210 kg (kroshu README: kr{payload}_r{reach})"),
        ),
    ]


def _fanuc_yaskawa_staubli() -> list[RobotSpec]:
    """The FANUC, Yaskawa and Stäubli rows of the library. Long on purpose: a table with one entry per arm, each with its cited source beside it."""
    from rmot.sim.robots.dynamics import INERTIA_METHOD as INERTIA  # late: loads subprocess only when this runs
    from rmot.sim.robots.dynamics import SPREAD_METHOD as SPREAD  # late: loads subprocess only when this runs
    from rmot.sim.robots.dynamics import EFFORT_METHOD as EFFORT  # late: loads subprocess only when this runs

    return [
        # FANUC LR Mate 200iD data sheet: reach 717 mm. Fanuc's world frame has its origin
        # on the J1 axis at the J2 height (so c1 = 0; the mounting face is 330 mm below);
        # faceplate at (465, 0, 365) mm, W P R = (180, -90, 0) at all joints zero.
        opw_spec(
            name="fanuc_lrmate200id", vendor="FANUC", model="LR Mate 200iD", source="FANUC LR Mate 200iD data sheet",
            params=OpwParams(a1=0.050, a2=-0.035, b=0.0, c1=0.0, c2=0.330, c3=0.335, c4=0.080), jmap=FANUC,
            limits_deg=((-170, 170), (-100, 145), (-140, 205), (-190, 190), (-125, 125), (-360, 360)),
            speed_deg_s=(450, 380, 520, 550, 545, 1000), accel_deg_s2=acc_estimate((450, 380, 520, 550, 545, 1000)),
            reach=0.717, radii=(0.09, 0.08, 0.06, 0.06, 0.05, 0.045, 0.03), flange_rz=math.pi, floor=-0.330,
            rated_payload_kg=7.0, arm_mass_kg=25.0, conventions=FANUC_CONV,
            sources=sources(
                geometry="FANUC LR Mate 200iD data sheet; = ros-industrial/fanuc fanuc_lrmate200id_support/urdf/lrmate200id_macro.xacro",
                limits=("FANUC LR Mate 200iD data sheet (pendant J3 -140..205 deg; ROS-I's -70..205 bounds its URDF joint_3 = J2 + J3, "
                        "a different variable; not re-verified in a FANUC manual)"),
                speed="FANUC LR Mate 200iD data sheet; = the ROS-I URDF", accel=ACC_EST, reach="FANUC data sheet: 717 mm",
                mass=f"FANUC LR Mate 200iD data sheet: arm 25 kg; {SPREAD}", inertia=INERTIA, effort=EFFORT,
                payload="FANUC LR Mate 200iD data sheet: 7 kg"),
        ),
        # FANUC M-20iA data sheet: reach 1811 mm; 525/150/790/250/835/100 mm (world frame at J2
        # height). J5 / J6 ranges ±140 / ±270 deg as ROS-I's m20ia URDF has them (rmot had ±180 / ±450).
        opw_spec(
            name="fanuc_m20ia", vendor="FANUC", model="M-20iA", source="FANUC M-20iA data sheet; ROS-I fanuc m20ia",
            params=OpwParams(a1=0.150, a2=-0.250, b=0.0, c1=0.0, c2=0.790, c3=0.835, c4=0.100), jmap=FANUC,
            limits_deg=((-170, 170), (-100, 160), (-185, 273), (-200, 200), (-140, 140), (-270, 270)),
            speed_deg_s=(195, 175, 180, 360, 360, 550), accel_deg_s2=acc_estimate((195, 175, 180, 360, 360, 550)),
            reach=1.811, radii=(0.2, 0.16, 0.1, 0.12, 0.09, 0.07, 0.05), flange_rz=math.pi, floor=-0.525,
            rated_payload_kg=20.0, arm_mass_kg=250.0, conventions=FANUC_CONV,
            sources=sources(
                geometry="FANUC M-20iA data sheet; = ros-industrial/fanuc fanuc_m20ia_support/urdf/m20ia_macro.xacro",
                limits="ros-industrial/fanuc fanuc_m20ia_support/urdf/m20ia_macro.xacro (J5 +-140, J6 +-270 deg)",
                speed="FANUC M-20iA data sheet; = the ROS-I URDF", accel=ACC_EST, reach="FANUC data sheet: 1811 mm",
                mass=f"FANUC M-20iA data sheet: arm 250 kg; {SPREAD}", inertia=INERTIA, effort=EFFORT,
                payload="FANUC M-20iA data sheet: 20 kg"),
        ),
        # Yaskawa Motoman GP8 specifications (178642-1CD): reach 727 mm; 330/40/345/40/340/80 mm.
        # The robot frame is at the L-axis height, 330 mm above the mounting face (c1 = 0).
        opw_spec(
            name="yaskawa_gp8", vendor="Yaskawa", model="Motoman GP8", source="Yaskawa GP8 spec 178642-1CD; ROS-I motoman gp8",
            params=OpwParams(a1=0.040, a2=-0.040, b=0.0, c1=0.0, c2=0.345, c3=0.340, c4=0.080), jmap=YASKAWA,
            limits_deg=((-170, 170), (-65, 145), (-70, 190), (-190, 190), (-135, 135), (-360, 360)),
            speed_deg_s=(455, 385, 520, 550, 550, 1000), accel_deg_s2=acc_estimate((455, 385, 520, 550, 550, 1000)),
            reach=0.727, radii=(0.09, 0.08, 0.06, 0.06, 0.05, 0.045, 0.03), flange_rz=math.pi, floor=-0.330,
            rated_payload_kg=8.0, arm_mass_kg=32.0, conventions=YASKAWA_CONV,
            sources=sources(
                geometry=("Yaskawa GP8 spec 178642-1CD; = ros-industrial/motoman motoman_gp8_support/urdf/gp8_macro.xacro, "
                          "robot frame = its `base`, 330 mm above the mounting face"),
                limits="Yaskawa GP8 spec 178642-1CD; = the ROS-I URDF", speed="Yaskawa GP8 spec 178642-1CD", accel=ACC_EST,
                reach="Yaskawa GP8 spec: 727 mm", mass=f"Yaskawa GP8 spec: arm 32 kg; {SPREAD}", inertia=INERTIA,
                effort=EFFORT, payload="Yaskawa GP8 spec: 8 kg"),
        ),
        # Stäubli TX2-60 data sheet (D28110804): reach 670 mm between axes 1 and 6;
        # 375/290/310/70 mm, 20 mm offset between the upper arm and the forearm planes. The
        # world frame is at the J1/J2 intersection, 375 mm above the mounting face (c1 = 0).
        opw_spec(
            name="staubli_tx2_60", vendor="Staubli", model="TX2-60", source="Staubli TX2-60 data sheet D28110804; ROS-I staubli tx2_60",
            params=OpwParams(a1=0.0, a2=0.0, b=0.020, c1=0.0, c2=0.290, c3=0.310, c4=0.070), jmap=STAUBLI,
            limits_deg=((-180, 180), (-127.5, 127.5), (-152.5, 152.5), (-270, 270), (-121, 132.5), (-270, 270)),
            speed_deg_s=(435, 385, 500, 995, 1065, 1445), accel_deg_s2=acc_estimate((435, 385, 500, 995, 1065, 1445)),
            reach=0.670, radii=(0.09, 0.08, 0.06, 0.06, 0.05, 0.04, 0.03), floor=-0.375,
            rated_payload_kg=3.5, arm_mass_kg=52.0, conventions=STAUBLI_CONV,
            sources=sources(
                geometry=("Staubli TX2-60 data sheet D28110804; = ros-industrial/staubli_experimental "
                          "staubli_tx2_60_support/urdf/tx2_60_macro.xacro, world frame = its `base`, 375 mm above the mounting face"),
                limits="ros-industrial/staubli_experimental tx2_60_macro.xacro (J3 +-152.5 deg; rmot had +-142.5)",
                speed="ros-industrial/staubli_experimental tx2_60_macro.xacro, 'nominal velocity limits' (J2 385, J3 500 deg/s; rmot had 410, 540)",
                accel=ACC_EST, reach="Staubli TX2-60 data sheet: 670 mm", mass=f"Staubli TX2-60 data sheet: arm 52 kg; {SPREAD}",
                inertia=INERTIA,
                effort=(f"{EFFORT}; not the ROS-I tx2_60_macro.xacro <limit effort> (126, 47, 32, 7, 8, 2 N·m): "
                        "J2's 47 N·m barely holds the stretched arm's rated 3.5 kg against gravity (3.5 kg x 9.81 x 0.67 m "
                        "= 23 N·m before the arm's own links), so those values are not joint ratings"),
                payload="Staubli TX2-60 data sheet: nominal payload 3.5 kg"),
        ),
    ]


def _puma560() -> RobotSpec:
    """Puma 560 in the standard-DH convention of Corke, "A robotics toolbox for MATLAB"
    (IEEE RAM 1996) / Robotics Toolbox `mdl_puma560`: base frame at the shoulder, no tool
    (fkine(qz) = (0.4521, -0.1500, 0.4318) m), joint values = DH θ; limits as in qlim."""
    from rmot.sim.robots.dynamics import EFFORT_METHOD, INERTIA_METHOD, SPREAD_METHOD, spread_mass  # late: loads subprocess only when this runs

    h = math.pi / 2
    rows = (
        DHRow(d=0.0, a=0.0, alpha=h), DHRow(d=0.0, a=0.4318, alpha=0.0),
        DHRow(d=0.15005, a=0.0203, alpha=-h), DHRow(d=0.4318, a=0.0, alpha=h),
        DHRow(d=0.0, a=0.0, alpha=-h), DHRow(d=0.0, a=0.0, alpha=0.0),
    )
    params = OpwParams(a1=0.0, a2=0.0203, b=-0.15005, c1=0.0, c2=0.4318, c3=0.4318, c4=0.0)
    jmap = OpwJointMap(sign=(1, -1, -1, 1, -1, 1), offset=(0, h, -h, 0, 0, 0))
    speeds = (82, 74, 137, 228, 200, 246)  # Unimation Puma 500 series manual (approx.)
    segments = opw_segments(params, (0.1, 0.09, 0.07, 0.07, 0.05, 0.04, 0.03), floor=-0.672)
    return RobotSpec(
        name="puma560", vendor="Unimation", model="PUMA 560", source="Corke 1996, mdl_puma560",
        dh=DHTable(rows), limits_deg=((-160, 160), (-45, 225), (-225, 45), (-110, 170), (-100, 100), (-266, 266)),
        speed_deg_s=speeds, accel_deg_s2=acc_estimate(speeds), reach=0.864, opw=(params, jmap),
        segments=segments, solid_pose=tuple(jmap.from_theta(np.zeros(6)).tolist()),
        extra_adjacent=OPW_TOUCHING, rated_payload_kg=2.5, link_mass_kg=spread_mass(segments, 63.0, 6),
        conventions=conventions("at the shoulder (J2 axis), as Corke's Robotics Toolbox", "DH frame 6 (no tool)",
                          "Corke's qz: all DH θ zero", "the DH θ of Corke's table"),
        sources=sources(
            geometry="Corke, 'A robotics toolbox for MATLAB', IEEE RAM 1996 / Robotics Toolbox mdl_puma560 DH table",
            limits="Robotics Toolbox mdl_puma560 qlim", speed="Unimation Puma 500 series manual (approx.)", accel=ACC_EST,
            reach="estimate: shoulder to wrist centre, 0.4318 + 0.4318 m, rounded up", mass=f"Unimation: arm 63 kg (approx.); {SPREAD_METHOD}",
            inertia=INERTIA_METHOD, effort=EFFORT_METHOD, payload="Unimation PUMA 560: 2.5 kg"),
    )


def _ur() -> list[RobotSpec]:
    """The Universal Robots rows of the library. Long on purpose: a table with one entry per arm, each with its cited source beside it."""
    # Universal Robots, "DH parameters for calculations of kinematics and dynamics"
    # (universal-robots.com/articles/ur/application-installation/dh-parameters-...), e-Series
    # and CB3 tables; speeds and reach from the e-Series data sheets. Shoulder/elbow offsets
    # (lateral steps of the tubes along J2) from UR's ur_description URDFs. Link masses from
    # ur_description config/<model>/physical_parameters.yaml, torque limits from
    # config/<model>/joint_limits.yaml (which cites UR's "Max. joint torques" article).
    from rmot.sim.robots.dynamics import INERTIA_METHOD  # late: loads subprocess only when this runs

    def src(model: str, reach_mm: int, payload: str) -> tuple[tuple[str, str], ...]:
        cfg = f"ros-industrial/universal_robot ur_description/config/{model.lower()}"
        return sources(
            geometry=f"UR DH table for the {model}; = {cfg}/default_kinematics.yaml", limits=f"{cfg}/joint_limits.yaml (+-360 deg)",
            speed=f"{model} data sheet; = {cfg}/joint_limits.yaml", accel=f"{ACC_EST} ({cfg}/joint_limits.yaml: 'acceleration limits are not publicly available')",
            reach=f"{model} data sheet: {reach_mm} mm", mass=f"{cfg}/physical_parameters.yaml shoulder..wrist_3 masses",
            inertia=INERTIA_METHOD, effort=f"{cfg}/joint_limits.yaml max_effort (UR article 'Max. joint torques')",
            payload=f"{model} data sheet: {payload}")

    return [
        ur_spec(name="ur3e", model="UR3e", source="UR DH table; UR3e data sheet",
                params=UrParams(0.15185, -0.24355, -0.2132, 0.13105, 0.08535, 0.0921),
                speed_deg_s=(180, 180, 180, 360, 360, 360), accel_deg_s2=acc_estimate((180, 180, 180, 360, 360, 360)),
                reach=0.500, shoulder_off=0.120, elbow_off=0.093, radii=(0.065, 0.05, 0.045, 0.04, 0.035),
                rated_payload_kg=3.0, link_mass_kg=(2.0, 3.42, 1.26, 0.8, 0.8, 0.35), effort_nm=(56.0, 56.0, 28.0, 12.0, 12.0, 12.0),
                conventions=UR_CONV, sources=src("UR3e", 500, "3 kg")),
        ur_spec(name="ur5e", model="UR5e", source="UR DH table; UR5e data sheet",
                params=UrParams(0.1625, -0.425, -0.3922, 0.1333, 0.0997, 0.0996),
                speed_deg_s=(180,) * 6, accel_deg_s2=acc_estimate((180,) * 6),
                reach=0.850, shoulder_off=0.138, elbow_off=0.131, radii=(0.075, 0.065, 0.055, 0.045, 0.045),
                rated_payload_kg=5.0, link_mass_kg=(3.7, 8.393, 2.275, 1.219, 1.219, 0.1879), effort_nm=(150.0, 150.0, 150.0, 28.0, 28.0, 28.0),
                conventions=UR_CONV, sources=src("UR5e", 850, "5 kg")),
        ur_spec(name="ur10e", model="UR10e", source="UR DH table; UR10e data sheet",
                params=UrParams(0.1807, -0.6127, -0.57155, 0.17415, 0.11985, 0.11655),
                speed_deg_s=(120, 120, 180, 180, 180, 180), accel_deg_s2=acc_estimate((120, 120, 180, 180, 180, 180)),
                reach=1.300, shoulder_off=0.176, elbow_off=0.137, radii=(0.095, 0.08, 0.065, 0.055, 0.05),
                rated_payload_kg=12.5, link_mass_kg=(7.778, 12.93, 3.87, 1.96, 1.96, 0.202), effort_nm=(330.0, 330.0, 150.0, 56.0, 56.0, 56.0),
                conventions=UR_CONV, sources=src("UR10e", 1300, "12.5 kg")),
        ur_spec(name="ur16e", model="UR16e", source="UR DH table; UR16e data sheet",
                params=UrParams(0.1807, -0.4784, -0.36, 0.17415, 0.11985, 0.11655),
                speed_deg_s=(120, 120, 180, 180, 180, 180), accel_deg_s2=acc_estimate((120, 120, 180, 180, 180, 180)),
                reach=0.900, shoulder_off=0.176, elbow_off=0.136, radii=(0.095, 0.08, 0.065, 0.055, 0.05),
                rated_payload_kg=16.0, link_mass_kg=(7.369, 10.45, 4.321, 2.18, 2.033, 0.907), effort_nm=(330.0, 330.0, 150.0, 56.0, 56.0, 56.0),
                conventions=UR_CONV, sources=src("UR16e", 900, "16 kg")),
        # CB3 series (UR3, UR5, UR10): the same conventions; numbers from ur_description's CB3 configs.
        ur_spec(name="ur3", model="UR3", source="UR DH table; UR3 data sheet",
                params=UrParams(0.1519, -0.24365, -0.21325, 0.11235, 0.08535, 0.0819),
                speed_deg_s=(180, 180, 180, 360, 360, 360), accel_deg_s2=acc_estimate((180, 180, 180, 360, 360, 360)),
                reach=0.500, shoulder_off=0.1198, elbow_off=0.0923, radii=(0.065, 0.05, 0.045, 0.04, 0.035),
                rated_payload_kg=3.0, link_mass_kg=(2.0, 3.42, 1.26, 0.8, 0.8, 0.35), effort_nm=(56.0, 56.0, 28.0, 12.0, 12.0, 12.0),
                conventions=UR_CONV, sources=src("UR3", 500, "3 kg")),
        ur_spec(name="ur5", model="UR5", source="UR DH table; UR5 data sheet",
                params=UrParams(0.089159, -0.425, -0.39225, 0.10915, 0.09465, 0.0823),
                speed_deg_s=(180,) * 6, accel_deg_s2=acc_estimate((180,) * 6),
                reach=0.850, shoulder_off=0.13585, elbow_off=0.11935, radii=(0.075, 0.04, 0.055, 0.045, 0.045),  # CB3: d1 89 mm
                rated_payload_kg=5.0, link_mass_kg=(3.7, 8.393, 2.275, 1.219, 1.219, 0.1879), effort_nm=(150.0, 150.0, 150.0, 28.0, 28.0, 28.0),
                conventions=UR_CONV, sources=src("UR5", 850, "5 kg")),
        ur_spec(name="ur10", model="UR10", source="UR DH table; UR10 data sheet",
                params=UrParams(0.1273, -0.612, -0.5723, 0.163941, 0.1157, 0.0922),
                speed_deg_s=(120, 120, 180, 180, 180, 180), accel_deg_s2=acc_estimate((120, 120, 180, 180, 180, 180)),
                reach=1.300, shoulder_off=0.220941, elbow_off=0.171899, radii=(0.095, 0.06, 0.065, 0.055, 0.05),  # CB3: d1 127 mm
                rated_payload_kg=10.0, link_mass_kg=(7.778, 12.93, 3.87, 1.96, 1.96, 0.202), effort_nm=(330.0, 330.0, 150.0, 56.0, 56.0, 56.0),
                conventions=UR_CONV, sources=src("UR10", 1300, "10 kg")),
    ]


def _kroshu(name: str, model: str, pkg: str, stem: str, params: OpwParams, *, limits_deg: tuple[tuple[float, float], ...],
            speed_deg_s: tuple[float, ...], accel_deg_s2: tuple[float, ...], link_mass_kg: tuple[float, ...],
            effort_nm: tuple[float, ...], radii: tuple[float, ...]) -> RobotSpec:
    """A KUKA arm with every number from KUKA's own description (kroshu/kuka_robot_descriptions):
    geometry, limits, speeds and torques from `<pkg>/urdf/<stem>_macro.xacro`, accelerations
    from `<pkg>/config/<stem>_joint_limits.yaml`, link masses from the URDF's <inertial>; the
    rated payload and the nominal reach are the product name's (kroshu README: kr{payload}_r{reach})."""
    found = re.match(r"KR (\d+) R(\d+)", model)
    assert found, model
    payload, reach_mm = float(found.group(1)), float(found.group(2))
    from rmot.sim.robots.kuka_inertia import KUKA_INERTIA  # late: loads subprocess only when this runs

    urdf, limits = f"{KROSHU} {pkg}/urdf/{stem}_macro.xacro", f"{KROSHU} {pkg}/config/{stem}_joint_limits.yaml"
    return opw_spec(
        name=name, vendor="KUKA", model=model, source=f"{KROSHU} {stem}", params=params, jmap=KUKA,
        limits_deg=limits_deg, speed_deg_s=speed_deg_s, accel_deg_s2=acc_estimate(speed_deg_s), reach=reach_mm / 1000, radii=radii,
        rated_payload_kg=payload, link_mass_kg=link_mass_kg, effort_nm=effort_nm, conventions=KUKA_CONV,
        link_inertia=KUKA_INERTIA[name],
        sources=sources(
            geometry=f"{urdf} joint origins", limits=f"{urdf} joint <limit lower/upper>", speed=f"{urdf} joint <limit velocity>",
            accel=kuka_accel_source(f"{limits} max_acceleration", accel_deg_s2),
            reach=f"the product name {model}: nominal {reach_mm:g} mm", mass=f"{urdf} link_1..link_6 <mass>",
            inertia=f"{urdf} link_1..link_6 <inertial> (centre of mass, tensor; rmot.sim.robots.kuka_inertia)",
            effort=f"{urdf} joint <limit effort>", payload=f"the product name {model}: {payload:g} kg"),
    )


def _kroshu_arms() -> list[RobotSpec]:
    """More KUKA arms, each from KUKA's own description; see `_kroshu`. Long on purpose: a table with one entry per arm, each with its cited source beside it."""
    return [
        _kroshu("kuka_kr4_r600", "KR 4 R600", "kuka_agilus_support", "kr4_r600",
                OpwParams(a1=0.0, a2=-0.02, b=0.0, c1=0.33, c2=0.29, c3=0.31, c4=0.075),
                limits_deg=((-170.0, 170.0), (-195.0, 40.0), (-115.0, 150.0), (-185.0, 185.0), (-120.0, 120.0), (-350.0, 350.0)),
                speed_deg_s=(336.0, 336.0, 487.5, 600.0, 529.1, 800.0), accel_deg_s2=(1674.0, 570.2, 1143.1, 1723.0, 2019.1, 4392.5),
                link_mass_kg=(4.389, 7.3011, 2.6794, 2.3085, 1.2008, 0.2348), effort_nm=(119.016, 105.851498, 54.314962, 11.811609, 12.327795, 6.916321),
                radii=(0.075, 0.06, 0.041, 0.041, 0.034, 0.026, 0.02)),
        _kroshu("kuka_kr6_r700_2", "KR 6 R700-2", "kuka_agilus_support", "kr6_r700_2",
                OpwParams(a1=0.025, a2=-0.025, b=0.0, c1=0.4, c2=0.335, c3=0.365, c4=0.09),
                limits_deg=((-170.0, 170.0), (-190.0, 45.0), (-120.0, 156.0), (-185.0, 185.0), (-120.0, 120.0), (-350.0, 350.0)),
                speed_deg_s=(360.0, 300.0, 360.0, 450.0, 450.0, 540.0), accel_deg_s2=(1132.1, 274.4, 651.4, 8228.8, 6733.1, 13587.7),
                link_mass_kg=(8.416, 15.5659, 5.303, 4.613, 1.6128, 0.734), effort_nm=(186.0, 168.9373, 81.493186, 48.879868, 40.135638, 27.358196),
                radii=(0.09, 0.072, 0.05, 0.05, 0.041, 0.032, 0.023)),
        _kroshu("kuka_kr6_r900_2", "KR 6 R900-2", "kuka_agilus_support", "kr6_r900_2",
                OpwParams(a1=0.025, a2=-0.025, b=0.0, c1=0.4, c2=0.455, c3=0.42, c4=0.09),
                limits_deg=((-170.0, 170.0), (-190.0, 45.0), (-120.0, 156.0), (-185.0, 185.0), (-120.0, 120.0), (-350.0, 350.0)),
                speed_deg_s=(360.0, 300.0, 360.0, 450.0, 450.0, 540.0), accel_deg_s2=(1305.9, 379.3, 1399.3, 7026.7, 6817.6, 13587.7),
                link_mass_kg=(8.416, 16.7929, 5.988, 4.699853, 1.6128, 0.734), effort_nm=(334.8, 260.65653, 137.827375, 43.282069, 45.669607, 23.293921),
                radii=(0.112, 0.09, 0.062, 0.062, 0.05, 0.039, 0.028)),
        _kroshu("kuka_kr10_r900_2", "KR 10 R900-2", "kuka_agilus_support", "kr10_r900_2",
                OpwParams(a1=0.025, a2=-0.025, b=0.0, c1=0.4, c2=0.455, c3=0.42, c4=0.09),
                limits_deg=((-170.0, 170.0), (-190.0, 45.0), (-120.0, 156.0), (-185.0, 185.0), (-120.0, 120.0), (-350.0, 350.0)),
                speed_deg_s=(300.0, 225.0, 330.0, 360.0, 360.0, 433.0), accel_deg_s2=(924.0, 118.5, 821.5, 3830.0, 2825.1, 7188.0),
                link_mass_kg=(8.416, 16.7929, 6.075, 4.586853, 1.6128, 0.734), effort_nm=(318.06, 251.505808, 154.907041, 50.640398, 41.613521, 28.03861),
                radii=(0.112, 0.09, 0.062, 0.062, 0.05, 0.039, 0.028)),
        _kroshu("kuka_kr10_r1100_2", "KR 10 R1100-2", "kuka_agilus_support", "kr10_r1100_2",
                OpwParams(a1=0.025, a2=-0.025, b=0.0, c1=0.4, c2=0.56, c3=0.515, c4=0.09),
                limits_deg=((-170.0, 170.0), (-190.0, 45.0), (-120.0, 156.0), (-185.0, 185.0), (-120.0, 120.0), (-350.0, 350.0)),
                speed_deg_s=(300.0, 225.0, 330.0, 360.0, 360.0, 433.0), accel_deg_s2=(576.7, 98.8, 153.9, 3236.9, 2820.9, 7188.0),
                link_mass_kg=(8.416, 17.8369, 6.075, 5.162381, 1.6128, 0.734), effort_nm=(288.36, 311.99662, 119.758982, 46.080276, 41.613521, 28.03861),
                radii=(0.137, 0.109, 0.075, 0.075, 0.062, 0.048, 0.034)),
        _kroshu("kuka_kr16_r1610_2", "KR 16 R1610-2", "kuka_cybertech_support", "kr16_r1610_2",
                OpwParams(a1=0.16, a2=-0.15, b=0.0, c1=0.52, c2=0.78, c3=0.655, c4=0.153),
                limits_deg=((-185.0, 185.0), (-185.0, 65.0), (-138.0, 175.0), (-350.0, 350.0), (-130.0, 130.0), (-350.0, 350.0)),
                speed_deg_s=(200.0, 175.0, 190.0, 430.0, 430.0, 630.0), accel_deg_s2=(623.1, 257.7, 1178.3, 5318.1, 5115.4, 6878.3),
                link_mass_kg=(84.207, 55.581, 35.648, 14.628, 1e-06, 1e-06), effort_nm=(1844.4, 1634.537111, 814.412882, 251.630433, 241.424767, 105.58296),
                radii=(0.2, 0.16, 0.11, 0.11, 0.09, 0.07, 0.05)),
        _kroshu("kuka_kr20_r1810_2", "KR 20 R1810-2", "kuka_cybertech_support", "kr20_r1810_2",
                OpwParams(a1=0.16, a2=-0.15, b=0.0, c1=0.52, c2=0.78, c3=0.86, c4=0.153),
                limits_deg=((-185.0, 185.0), (-185.0, 65.0), (-138.0, 175.0), (-350.0, 350.0), (-130.0, 130.0), (-350.0, 350.0)),
                speed_deg_s=(200.0, 171.59, 190.0, 430.0, 430.0, 630.0), accel_deg_s2=(487.0, 125.0, 520.8, 4083.7, 3905.8, 6385.1),
                link_mass_kg=(84.207, 55.407, 35.648, 16.428, 1e-06, 1e-06), effort_nm=(1809.6, 1569.10108, 792.65294, 249.072792, 238.867125, 104.6412),
                radii=(0.225, 0.18, 0.124, 0.124, 0.101, 0.079, 0.056)),
        _kroshu("kuka_kr30_r2100", "KR 30 R2100", "kuka_iontec_support", "kr30_r2100",
                OpwParams(a1=0.175, a2=-0.05, b=0.0, c1=0.575, c2=0.89, c3=1.035, c4=0.185),
                limits_deg=((-185.0, 185.0), (-175.0, 60.0), (-120.0, 165.0), (-180.0, 180.0), (-125.0, 125.0), (-350.0, 350.0)),
                speed_deg_s=(180.0, 165.0, 180.0, 250.0, 250.0, 360.0), accel_deg_s2=(476.9, 161.0, 221.3, 1255.9, 1135.7, 932.6),
                link_mass_kg=(172.735, 108.86, 76.987, 36.937065, 16.209, 3.62), effort_nm=(5640.0, 4203.66504, 1426.51367, 483.452545, 441.424347, 259.541595),
                radii=(0.261, 0.209, 0.144, 0.144, 0.117, 0.091, 0.065)),
        _kroshu("kuka_kr50_r2500", "KR 50 R2500", "kuka_iontec_support", "kr50_r2500",
                OpwParams(a1=0.175, a2=-0.05, b=0.0, c1=0.575, c2=1.29, c3=1.035, c4=0.185),
                limits_deg=((-185.0, 185.0), (-175.0, 60.0), (-120.0, 170.0), (-180.0, 180.0), (-125.0, 125.0), (-350.0, 350.0)),
                speed_deg_s=(175.0, 157.98, 175.0, 250.0, 250.0, 360.0), accel_deg_s2=(284.0, 44.3, 77.2, 984.1, 849.5, 1021.5),
                link_mass_kg=(175.205, 131.16, 76.987, 36.937065, 16.209, 3.62), effort_nm=(5528.892, 5104.349811, 1441.877917, 535.609199, 483.521522, 338.503348),
                radii=(0.311, 0.249, 0.171, 0.171, 0.14, 0.109, 0.078)),
        _kroshu("kuka_kr210_r3100_2", "KR 210 R3100-2", "kuka_quantec_support", "kr210_r3100_2",
                OpwParams(a1=0.33, a2=-0.115, b=0.0, c1=0.645, c2=1.35, c3=1.42, c4=0.24),
                limits_deg=((-185.0, 185.0), (-140.0, -5.0), (-120.0, 168.0), (-350.0, 350.0), (-122.5, 122.5), (-350.0, 350.0)),
                speed_deg_s=(105.0, 94.0, 100.0, 136.0, 129.0, 206.0), accel_deg_s2=(83.9, 29.6, 75.3, 396.7, 402.3, 453.4),
                link_mass_kg=(367.37, 250.56, 206.53, 47.942846, 23.687645, 12.245719), effort_nm=(7290.0, 8910.0, 7251.2876, 2356.12598, 2358.44531, 1508.75476),
                radii=(0.386, 0.309, 0.212, 0.212, 0.174, 0.135, 0.096)),
        _kroshu("kuka_kr8_r1440_2_arc_hw", "KR 8 R1440-2 arc HW", "kuka_cybertech_support", "kr8_r1440_2_arc_hw",
                OpwParams(a1=0.17, a2=-0.21, b=0.0, c1=0.425, c2=0.61, c3=0.627, c4=0.08),
                limits_deg=((-170.0, 170.0), (-185.0, 65.0), (-119.0, 181.0), (-165.0, 165.0), (-115.0, 140.0), (-350.0, 350.0)),
                speed_deg_s=(220.0, 210.0, 270.0, 430.0, 430.0, 628.57), accel_deg_s2=(731.6, 568.8, 399.3, 2732.4, 2804.8, 12314.9),
                link_mass_kg=(67.4, 29.18, 28.122242, 17.669, 2.75, 0.8), effort_nm=(1296.0, 1275.587216, 248.615275, 44.044316, 34.357459, 36.6552),
                radii=(0.179, 0.143, 0.098, 0.098, 0.081, 0.063, 0.045)),
        _kroshu("kuka_kr150_r3100_2", "KR 150 R3100-2", "kuka_quantec_support", "kr150_r3100_2",
                OpwParams(a1=0.33, a2=-0.115, b=0.0, c1=0.645, c2=1.35, c3=1.42, c4=0.215),
                limits_deg=((-185.0, 185.0), (-140.0, -5.0), (-120.0, 168.0), (-350.0, 350.0), (-125.0, 125.0), (-350.0, 350.0)),
                speed_deg_s=(105.0, 107.0, 114.0, 190.0, 180.0, 260.0), accel_deg_s2=(106.2, 66.3, 223.4, 748.7, 323.7, 330.1),
                link_mass_kg=(363.07, 250.56, 199.93, 42.411795, 16.991732, 6.6), effort_nm=(7290.0, 8910.0, 7538.746234, 2431.250529, 1460.560852, 892.539),
                radii=(0.386, 0.309, 0.212, 0.212, 0.174, 0.135, 0.096)),
        _kroshu("kuka_kr240_r2900_2", "KR 240 R2900-2", "kuka_quantec_support", "kr240_r2900_2",
                OpwParams(a1=0.33, a2=-0.115, b=0.0, c1=0.645, c2=1.35, c3=1.22, c4=0.24),
                limits_deg=((-185.0, 185.0), (-140.0, -5.0), (-120.0, 168.0), (-350.0, 350.0), (-122.5, 122.5), (-350.0, 350.0)),
                speed_deg_s=(103.0, 94.0, 100.0, 170.0, 129.0, 206.0), accel_deg_s2=(86.4, 36.9, 97.8, 290.0, 294.7, 357.1),
                link_mass_kg=(367.37, 250.56, 191.53, 47.942846, 23.687645, 12.245719), effort_nm=(7290.0, 9240.0, 7295.422365, 2323.710367, 2326.033088, 1492.86251),
                radii=(0.361, 0.289, 0.199, 0.199, 0.162, 0.126, 0.09)),
        _kroshu("kuka_kr300_r2700_2", "KR 300 R2700-2", "kuka_quantec_support", "kr300_r2700_2",
                OpwParams(a1=0.33, a2=-0.115, b=0.0, c1=0.645, c2=1.15, c3=1.22, c4=0.24),
                limits_deg=((-185.0, 185.0), (-140.0, -5.0), (-120.0, 168.0), (-350.0, 350.0), (-122.5, 122.5), (-350.0, 350.0)),
                speed_deg_s=(105.0, 101.0, 107.0, 140.0, 113.0, 180.0), accel_deg_s2=(86.3, 34.4, 23.8, 140.3, 143.8, 222.1),
                link_mass_kg=(367.37, 232.06, 191.53, 47.942846, 23.687645, 12.245719), effort_nm=(7290.0, 9600.03, 7087.143423, 2258.878887, 2261.206601, 1461.07811),
                radii=(0.336, 0.269, 0.185, 0.185, 0.151, 0.118, 0.084)),
        _kroshu("kuka_kr500_r2800_2", "KR 500 R2800-2", "kuka_fortec_support", "kr500_r2800_2",
                OpwParams(a1=0.5, a2=-0.15, b=0.0, c1=0.8, c2=1.25, c3=1.0395, c4=0.286),
                limits_deg=((-185.0, 185.0), (-130.0, 5.0), (-110.0, 162.0), (-350.0, 350.0), (-120.0, 120.0), (-350.0, 350.0)),
                speed_deg_s=(100.0, 79.54, 90.0, 90.0, 100.0, 163.0), accel_deg_s2=(80.6, 44.7, 36.0, 225.0, 227.3, 258.7),
                link_mass_kg=(587.48, 318.2, 287.76, 91.737, 46.6909, 23.3927), effort_nm=(13440.0, 18360.0, 11026.99304, 5359.094619, 5363.939646, 3112.650243),
                radii=(0.348, 0.278, 0.191, 0.191, 0.157, 0.122, 0.087)),
    ]


def _rosi_arms() -> list[RobotSpec]:
    from rmot.sim.robots.library_rosi import rosi_arms  # the arms of ROS-I's support packages  # late: loads subprocess only when this runs
    from rmot.sim.robots.library_abb import abb_arms  # ROS-I's further ABB arms  # late: loads subprocess only when this runs
    from rmot.sim.robots.library_fanuc import fanuc_arms  # ROS-I's further FANUC arms  # late: loads subprocess only when this runs

    return rosi_arms() + abb_arms() + fanuc_arms()


def _motoman_staubli_arms() -> list[RobotSpec]:
    from rmot.sim.robots.library_motoman import motoman_arms  # ROS-I's Motoman support packages  # late: loads subprocess only when this runs
    from rmot.sim.robots.library_staubli import staubli_arms  # ROS-I's Stäubli support packages  # late: loads subprocess only when this runs

    return motoman_arms() + staubli_arms()


SPECS: dict[str, RobotSpec] = {
    s.name: s for s in _abb_kuka() + _fanuc_yaskawa_staubli() + [_puma560()] + _ur() + _kroshu_arms() + _rosi_arms() + _motoman_staubli_arms()
}
