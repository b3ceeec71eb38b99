"""Library arms transcribed from ROS-Industrial's support packages, one batch per brand.

Each arm's geometry, joint limits and speeds are its ROS-I package's URDF macro (repository,
path and commit in `sources`); the OPW lengths are read off its joint origins (a1: J2's
forward offset from J1, c1: J2's height over the controller frame, c2: J2 to J3, a2: the
forearm's offset (negative: J4 above J3), c3: J3 to the wrist centre along the forearm, c4:
wrist centre to the flange, b: the lateral offset). Joint values, base and flange frames
follow the vendor conventions of library.py (the pendant mapping each reference's driver
states: tests/robots/reference_arms.py). tests/robots/test_reference_fk.py checks every arm
against the URDF's chain composed independently. Where a number is not in the URDF (reach,
accelerations) it is an estimate, said so in `sources`.
"""

from __future__ import annotations

import math

from rmot.sim.robots.opw import OpwParams
from rmot.sim.robots.spec import RobotSpec, opw_spec

__all__ = ["rosi_arms"]

_ROSI = "ros-industrial"
_REACH_EST = "estimate: a1 + c2 + hypot(a2, c3), the wrist centre's largest distance from the J1 axis (ROS-I geometry)"


def _wrist_reach(p: OpwParams) -> float:
    return p.a1 + p.c2 + math.hypot(p.a2, p.c3)


def rosi_arms() -> list[RobotSpec]:
    """One arm per brand of ROS-Industrial's ABB, Fanuc, Motoman and Stäubli packages."""
    return _abb_fanuc() + _yaskawa_staubli()


def _abb_fanuc() -> list[RobotSpec]:
    from rmot.sim.robots.dynamics import EFFORT_METHOD as EFFORT  # late: loads subprocess only when this runs
    from rmot.sim.robots.dynamics import INERTIA_METHOD as INERTIA  # late: loads subprocess only when this runs
    from rmot.sim.robots.dynamics import SPREAD_METHOD as SPREAD  # late: loads subprocess only when this runs
    from rmot.sim.robots.library_common import (  # late: loads subprocess only when this runs
        ABB,
        ABB_CONV,
        ACC_EST,
        FANUC,
        FANUC_CONV,
        acc_estimate,
        sources,
    )

    irb2400 = OpwParams(a1=0.100, a2=-0.135, b=0.0, c1=0.615, c2=0.705, c3=0.755, c4=0.085)
    m16ib = OpwParams(a1=0.150, a2=-0.100, b=0.0, c1=0.0, c2=0.770, c3=0.740, c4=0.100)
    abb_file = f"{_ROSI}/abb abb_irb2400_support/urdf/irb2400_macro.xacro @ 7f6a1b189991"
    fanuc_file = f"{_ROSI}/fanuc fanuc_m16ib_support/urdf/m16ib20_macro.xacro @ e9bafced8e1f"
    return [
        # ABB IRB 2400: tool0 turned (0, 90°, 0) from link_6, ABB's tool0 (z out of the flange)
        opw_spec(
            name="abb_irb2400", vendor="ABB", model="IRB 2400/16", source=abb_file, params=irb2400, jmap=ABB,
            limits_deg=((-180, 180), (-100, 110), (-60, 65), (-200, 200), (-120, 120), (-400, 400)),
            speed_deg_s=(150, 150, 150, 360, 360, 450), accel_deg_s2=acc_estimate((150, 150, 150, 360, 360, 450)),
            reach=_wrist_reach(irb2400), radii=(0.17, 0.14, 0.10, 0.10, 0.08, 0.065, 0.045), conventions=ABB_CONV,
            rated_payload_kg=16.0, arm_mass_kg=380.0,
            sources=sources(geometry=f"{abb_file} (100/615/705/135/755/85 mm)",
                             limits=f"{abb_file} (rad, to the nearest 0.5 deg)", speed=f"{abb_file} (rad/s)",
                             accel=ACC_EST, reach=_REACH_EST,
                             mass=f"ABB IRB 2400 data sheet: robot 380 kg (not re-verified here); {SPREAD}",
                             inertia=INERTIA, effort=EFFORT, payload="the model name IRB 2400/16: 16 kg"),
        ),
        # FANUC M-16iB/20: world frame at the J2 height (525 mm above base_link, ROS-I `base`)
        opw_spec(
            name="fanuc_m16ib20", vendor="FANUC", model="M-16iB/20", source=fanuc_file, params=m16ib, jmap=FANUC,
            limits_deg=((-170, 170), (-90, 160), (-170, 290), (-200, 200), (-140, 140), (-450, 450)),
            speed_deg_s=(165, 165, 175, 350, 340, 520), accel_deg_s2=acc_estimate((165, 165, 175, 350, 340, 520)),
            reach=_wrist_reach(m16ib), radii=(0.17, 0.14, 0.09, 0.10, 0.08, 0.065, 0.045), flange_rz=math.pi,
            floor=-0.525, conventions=FANUC_CONV, rated_payload_kg=20.0, arm_mass_kg=220.0,
            sources=sources(geometry=f"{fanuc_file} (525/150/770/100/740/100 mm)",
                             limits=(f"{fanuc_file} (J3 -170..290 deg as the URDF bounds its joint_3, taken as the pendant "
                                     "J3 range as for the M-20iA; not re-verified in a FANUC manual)"),
                             speed=f"{fanuc_file} (rad/s)", accel=ACC_EST, reach=_REACH_EST,
                             mass=f"FANUC M-16iB/20 data sheet: mechanical unit 220 kg (not re-verified here); {SPREAD}",
                             inertia=INERTIA, effort=EFFORT, payload="the model name M-16iB/20: 20 kg"),
        ),
    ]


def _yaskawa_staubli() -> list[RobotSpec]:
    from rmot.sim.robots.dynamics import INERTIA_METHOD as INERTIA  # late: loads subprocess only when this runs
    from rmot.sim.robots.dynamics import SPREAD_METHOD as SPREAD  # late: loads subprocess only when this runs
    from rmot.sim.robots.library_common import (ACC_EST, STAUBLI, STAUBLI_CONV, YASKAWA, YASKAWA_CONV,  # late: loads subprocess only when this runs
                                                     acc_estimate, sources)

    mh12 = OpwParams(a1=0.155, a2=-0.200, b=0.0, c1=0.0, c2=0.614, c3=0.640, c4=0.100)
    tx60l = OpwParams(a1=0.0, a2=0.0, b=0.020, c1=0.0, c2=0.400, c3=0.450, c4=0.070)
    motoman_file = f"{_ROSI}/motoman motoman_mh12_support/urdf/mh12_macro.xacro @ 16ddd4361b95"
    staubli_file = f"{_ROSI}/staubli_experimental staubli_tx60_support/urdf/tx60l_macro.xacro @ 12c677d12379"
    return [
        # Yaskawa Motoman MH12: robot frame at the L-axis height (450 mm, ROS-I `base`)
        opw_spec(
            name="yaskawa_mh12", vendor="Yaskawa", model="Motoman MH12", source=motoman_file, params=mh12, jmap=YASKAWA,
            limits_deg=((-170, 170), (-90, 155), (-85, 150), (-180, 180), (-135, 135), (-360, 360)),
            speed_deg_s=(220, 200, 220, 410, 410, 610), accel_deg_s2=acc_estimate((220, 200, 220, 410, 410, 610)),
            reach=_wrist_reach(mh12), radii=(0.13, 0.11, 0.08, 0.08, 0.065, 0.055, 0.04), flange_rz=math.pi,
            floor=-0.450, effort_nm=(648.27, 874.65, 257.25, 74.97, 44.69, 14.80), conventions=YASKAWA_CONV,
            rated_payload_kg=12.0, arm_mass_kg=130.0,
            sources=sources(geometry=f"{motoman_file} (450/155/614/200/640/100 mm)", limits=f"{motoman_file} (rad)",
                             speed=f"{motoman_file} (rad/s)", accel=ACC_EST, reach=_REACH_EST,
                             effort=f"{motoman_file} <limit effort> (N*m)", inertia=INERTIA,
                             mass=f"Yaskawa Motoman MH12 data sheet: 130 kg (not re-verified here); {SPREAD}",
                             payload="the model name MH12: 12 kg"),
        ),
        # Stäubli TX60L: world frame at the J1/J2 intersection (375 mm, ROS-I `base`)
        opw_spec(
            name="staubli_tx60l", vendor="Staubli", model="TX60L", source=staubli_file, params=tx60l, jmap=STAUBLI,
            limits_deg=((-180, 180), (-127.5, 127.5), (-152.5, 152.5), (-270, 270), (-122.5, 132.5), (-270, 270)),
            speed_deg_s=(435, 385, 500, 995, 1065, 1445), accel_deg_s2=acc_estimate((435, 385, 500, 995, 1065, 1445)),
            reach=_wrist_reach(tx60l), radii=(0.09, 0.08, 0.06, 0.06, 0.05, 0.04, 0.03), floor=-0.375,
            effort_nm=(126.0, 47.0, 32.0, 7.0, 8.0, 2.0), conventions=STAUBLI_CONV, rated_payload_kg=2.0,
            link_mass_kg=(6.99103376, 5.21353, 4.52768, 3.48055, 0.16254714, 0.0082),
            sources=sources(geometry=f"{staubli_file} (375/400/450/70 mm, 20 mm lateral offset)",
                             limits=f"{staubli_file} (deg)", speed=f"{staubli_file} (deg/s)", accel=ACC_EST,
                             reach=_REACH_EST, effort=f"{staubli_file}, 'from Staubli instruction manual' (floor mounted)",
                             mass=f"{staubli_file} <inertial> masses of link_1..link_6", inertia=INERTIA,
                             payload="Staubli TX60L data sheet: nominal 2 kg (not re-verified here)"),
        ),
    ]
