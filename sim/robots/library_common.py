"""What the library arms of one maker share: the controller's joint mapping (pendant values to
the closed form's variables), the conventions `rmot robots show` prints, and the wording of
each number's source (the accelerations estimate, the (quantity, source) pairs).

Read by robots/library.py (the arms) and robots/library_rosi.py (the arms of ROS-Industrial's
support packages).
"""

from __future__ import annotations

import math

from rmot.sim.robots.opw import OpwJointMap

__all__ = [
    "ABB", "ABB_CONV", "ACC_EST", "FANUC", "FANUC_CONV", "H", "KROSHU", "KUKA", "KUKA_CONV", "ROSI_ABB",
    "STAUBLI", "STAUBLI_CONV", "UR_CONV", "YASKAWA", "YASKAWA_CONV", "acc_estimate", "conventions",
    "kuka_accel_source", "sources",
]

H = math.pi / 2


def acc_estimate(speeds: tuple[float, ...]) -> tuple[float, ...]:
    return tuple(4.0 * s for s in speeds)


ACC_EST = "estimate: 4 x the axis speed per second (the max speed reached in 0.25 s); the vendor publishes none"


def kuka_accel_source(where: str, values: tuple[float, ...]) -> str:
    """The source of a KUKA arm's accelerations: the same estimate as the other vendors'. KUKA's
    ROS descriptions give joint accelerations, but not the controller's: they made a KR 10
    R1100-2 (A2 98.8 deg/s^2) 2.5-3 x slower than an IRB 120, LR Mate 200iD or GP8 of the same
    class on the 25/300/25 mm cycle (tests/benchmarks/bench_cycle_arms.py), and a KR 500 take
    over a second to reach A2's speed."""
    listed = ", ".join(f"{v:g}" for v in values)
    return (f"estimate: 4 x the axis speed per second (the max speed reached in 0.25 s); not {where} "
            f"({listed} deg/s^2), planning limits for another purpose than the controller's")


ROSI_ABB = "ros-industrial/abb_experimental"
KROSHU = "kroshu/kuka_robot_descriptions"


def sources(**kw: str) -> tuple[tuple[str, str], ...]:
    """(quantity, source) pairs in a fixed order: geometry, limits, speed, accel, reach, mass,
    inertia, effort, payload."""
    order = ("geometry", "limits", "speed", "accel", "reach", "mass", "inertia", "effort", "payload")
    assert set(kw) <= set(order), set(kw) - set(order)
    return tuple((k, kw[k]) for k in order if k in kw)


def conventions(base: str, flange: str, zero: str, signs: str, coupling: str = "none") -> tuple[tuple[str, str], ...]:
    return (("base frame", base), ("flange frame", flange), ("joint zero", zero), ("signs", signs), ("coupling", coupling))


ABB_CONV = conventions(
    "ABB base frame on the mounting face at the J1 axis, x forward (ROS-I abb_experimental `base`)",
    "tool0: z out of the flange; at the calibration position z along base +x, x down",
    "all zero = calibration position: upper arm up, forearm horizontal",
    "RAPID jointtarget values (ROS-I abb_driver passes them one to one); J1 > 0 turns counter-clockwise seen from above",
)
KUKA_CONV = conventions(
    "$ROBROOT on the mounting face at the A1 axis (kroshu/kuka_robot_descriptions README: `base` = $ROBROOT)",
    "$FLANGE: at HOME z forward, x down (A B C = 0 90 0); = ROS-I / kroshu `tool0`",
    "A2 = 0 upper arm horizontal forward, A3 = 0 forearm in line with it; HOME = (0, -90, 90, 0, 0, 0)",
    "KCP values (kuka_rsi_hw_interface: DEG2RAD * AIPos); A1, A4, A6 > 0 turn clockwise seen along +z / the arm",
)
FANUC_CONV = conventions(
    "Fanuc world frame on the J1 axis at the J2 height (ROS-I fanuc `base`; the mounting face is below it)",
    "faceplate: at zero z forward, x up (W P R = 180 -90 0); = ROS-I `tool0`",
    "all zero: upper arm up, forearm horizontal",
    "teach pendant joint values; J4..J6 positive the other way round than the URDF axes",
    "J3 is the forearm's angle to the horizontal: model q3 = J2 + J3 (ROS-I fanuc_driver J23_factor = 1)",
)
YASKAWA_CONV = conventions(
    "robot frame on the S axis at the L-axis height (ROS-I motoman `base`; ros-industrial/motoman issue 167)",
    "tool0: at zero z forward, x up",
    "all zero: lower arm up, upper arm horizontal",
    "S L U R B T in degrees (pulses / pulse-per-degree); U relative to L",
)
STAUBLI_CONV = conventions(
    "Stäubli world frame at the J1/J2 intersection (ROS-I staubli_experimental `base`)",
    "flange: z along J6 (ROS-I `tool0`)",
    "all zero = arm stretched vertically (the \"candle\")",
    "VAL3 joint values one to one",
)
UR_CONV = conventions(
    "UR Base frame (DH frame 0; ur_description `base`, x backwards from `base_link`)",
    "tool flange (DH frame 6; ur_description `tool0`)",
    "the DH θ of UR's table (what PolyScope shows): all zero = arm stretched horizontally",
    "PolyScope values one to one",
)


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
