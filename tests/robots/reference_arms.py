"""Independent reference chains of the library arms, transcribed from other people's data.

Each entry is the kinematic chain of one arm exactly as its reference publishes it (a
ROS-Industrial support package's URDF joint origins and axes, KUKA's own robot descriptions,
Universal Robots' calibration yaml), with the reference named (repository, path, commit) next
to it. Nothing here is read from rmot: the test composes these chains with its own numpy code
and compares them with the library FK.

Conventions of a chain: `controller` is the pose (xyz m, rpy rad, URDF convention
R = Rz(y) Ry(p) Rx(r)) of the vendor controller's base frame in the chain's root link (None:
the root link is the controller frame); `pre` the fixed joints between the root and the first
moving joint; `joints` each moving joint's origin and axis; `tool` the fixed joints from the
last moving link to the vendor flange frame (ROS-I `tool0`, "the all-zeros tool frame" of the
controller).

`mapping` is how the reference's joint values follow from the pendant's, stated from each
reference's driver (never fitted): q_ref = sign * q + offset, then q_ref[2] += j23 * q[1].
"""

from __future__ import annotations

import math
from dataclasses import dataclass

PI = math.pi

Vec = tuple[float, float, float]


@dataclass(frozen=True)
class Mapping:
    sign: tuple[float, ...] = (1.0,) * 6
    offset_deg: tuple[float, ...] = (0.0,) * 6
    j23: float = 0.0  # Fanuc: the URDF's relative J3 = pendant J3 + j23 * pendant J2
    source: str = ""


@dataclass(frozen=True)
class RefArm:
    name: str
    source: str
    controller: tuple[Vec, Vec] | None
    joints: tuple[tuple[Vec, Vec, Vec], ...]
    tool: tuple[tuple[Vec, Vec], ...]
    mapping: Mapping
    pre: tuple[tuple[Vec, Vec], ...] = ()


# ABB: abb_driver (ros-industrial/abb, abb_driver/rapid/ROS_motion_server.mod) sends the
# RAPID jointtarget in radians, one to one.
ABB_MAP = Mapping(source="ros-industrial/abb abb_driver: RAPID joint values one to one (rad)")
# KUKA: kuka_rsi_hw_interface.cpp line 109, joint_position = DEG2RAD * AIPos (A1..A6 as the KCP shows).
KUKA_MAP = Mapping(source="ros-industrial/kuka_experimental kuka_rsi_hw_interface/src/kuka_hardware_interface.cpp: DEG2RAD * AIPos")
# Fanuc: fanuc_driver linkage_transform with J23_factor = 1 (robot_interface_streaming_<model>.launch):
# the URDF joint_3 is the pendant J3 + J2.
FANUC_MAP = Mapping(j23=1.0, source="ros-industrial/fanuc fanuc_driver linkage_transform, J23_factor = 1 (robot_interface_streaming_*.launch)")
# Yaskawa: motoman_driver reports the controller's pulse positions converted to radians, one to one.
YASKAWA_MAP = Mapping(source="ros-industrial/motoman motoman_driver: controller joint positions one to one (rad)")
# Staubli: the uniVAL / VAL3 joint values one to one.
STAUBLI_MAP = Mapping(source="ros-industrial/staubli_experimental: VAL3 joint values one to one (rad)")
# UR: ur_robot_driver publishes PolyScope's joint values one to one.
UR_MAP = Mapping(source="UniversalRobots ur_robot_driver: PolyScope joint values one to one (rad)")


ARMS: tuple[RefArm, ...] = (
    RefArm(
        name='abb_irb120',
        source='ros-industrial/abb_experimental abb_irb120_support/urdf/irb120_3_58_macro.xacro @ 20b9cf86ad27',
        controller=((0.0, 0.0, 0.0), (0.0, 0.0, 0.0)),
        joints=(
            ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0)),
            ((0.0, 0.0, 0.29), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
            ((0.0, 0.0, 0.27), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
            ((0.0, 0.0, 0.07), (0.0, 0.0, 0.0), (1.0, 0.0, 0.0)),
            ((0.302, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
            ((0.072, 0.0, 0.0), (0.0, 0.0, 0.0), (1.0, 0.0, 0.0)),
        ),
        tool=(((0.0, 0.0, 0.0), (0.0, 0.0, 0.0)), ((0.0, 0.0, 0.0), (0.0, 1.5707963267948966, 0.0))),
        mapping=ABB_MAP,
    ),
    RefArm(
        name='abb_irb1600',
        source='ros-industrial/abb_experimental abb_irb1600_support/urdf/irb1600_8_145_macro.xacro @ 20b9cf86ad27',
        controller=((0.0, 0.0, 0.0), (0.0, 0.0, 0.0)),
        joints=(
            ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0)),
            ((0.15, 0.0, 0.4865), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
            ((0.0, 0.0, 0.7), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
            ((0.3, 0.0, 0.0), (0.0, 0.0, 0.0), (1.0, 0.0, 0.0)),
            ((0.3, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
            ((0.065, 0.0, 0.0), (0.0, 0.0, 0.0), (1.0, 0.0, 0.0)),
        ),
        tool=(((0.0, 0.0, 0.0), (0.0, 0.0, 0.0)), ((0.0, 0.0, 0.0), (0.0, 1.5707963267948966, 0.0))),
        mapping=ABB_MAP,
    ),
    RefArm(
        name='abb_irb4600',
        source='ros-industrial/abb_experimental abb_irb4600_support/urdf/irb4600_60_205_macro.xacro @ 20b9cf86ad27',
        controller=((0.0, 0.0, 0.0), (0.0, 0.0, 0.0)),
        joints=(
            ((0.0, 0.0, 0.495), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0)),
            ((0.175, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
            ((0.0, 0.0, 0.9), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
            ((0.0, 0.0, 0.175), (0.0, 0.0, 0.0), (1.0, 0.0, 0.0)),
            ((0.96, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
            ((0.135, 0.0, 0.0), (0.0, 0.0, 0.0), (1.0, 0.0, 0.0)),
        ),
        tool=(((0.0, 0.0, 0.0), (0.0, 0.0, 0.0)), ((0.0, 0.0, 0.0), (0.0, 1.5707963267948966, 0.0))),
        mapping=ABB_MAP,
    ),
    RefArm(
        name='kuka_kr6_r900',
        source='kroshu/kuka_robot_descriptions kuka_agilus_support/urdf/kr6_r900_sixx_macro.xacro @ 7766e92afcfd',
        controller=None,
        joints=(
            ((0.0, 0.0, 0.4), (0.0, 0.0, 0.0), (0.0, 0.0, -1.0)),
            ((0.025, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
            ((0.455, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
            ((0.0, 0.0, 0.035), (0.0, 0.0, 0.0), (-1.0, 0.0, 0.0)),
            ((0.42, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
            ((0.08, 0.0, 0.0), (0.0, 0.0, 0.0), (-1.0, 0.0, 0.0)),
        ),
        tool=(((0.0, 0.0, 0.0), (0.0, 0.0, 0.0)), ((0.0, 0.0, 0.0), (0.0, 1.5707963267948966, 0.0))),
        mapping=KUKA_MAP,
    ),
    RefArm(
        name='kuka_kr16',
        source='ros-industrial/kuka_experimental kuka_kr16_support/urdf/kr16_2_macro.xacro @ e78bbd15edb2',
        controller=None,
        joints=(
            ((0.0, 0.0, 0.675), (0.0, 0.0, 0.0), (0.0, 0.0, -1.0)),
            ((0.26, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
            ((0.68, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
            ((0.67, 0.0, -0.035), (0.0, 0.0, 0.0), (-1.0, 0.0, 0.0)),
            ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
            ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (-1.0, 0.0, 0.0)),
        ),
        tool=(((0.158, 0.0, 0.0), (0.0, 0.0, 0.0)), ((0.0, 0.0, 0.0), (0.0, 1.5707963267948966, 0.0))),
        mapping=KUKA_MAP,
    ),
    RefArm(
        name='kuka_kr210',
        source='kroshu/kuka_robot_descriptions kuka_quantec_support/urdf/kr210_r2700_2_macro.xacro @ 7766e92afcfd',
        controller=None,
        joints=(
            ((0.0, 0.0, 0.0), (-3.141592653589793, 0.0, 0.0), (0.0, 0.0, 1.0)),
            ((0.33, 0.0, -0.645), (1.5707963267948963, 0.0, 0.0), (0.0, 0.0, 1.0)),
            ((1.15, 0.0, 0.0), (0.0, 0.0, -1.5707963267948963), (0.0, 0.0, 1.0)),
            ((0.115, 0.0, 0.0), (1.5707963267948963, 0.0, 0.0), (0.0, 0.0, 1.0)),
            ((0.0, 0.0, -1.22), (-1.5707963267948963, 0.0, 0.0), (0.0, 0.0, 1.0)),
            ((0.0, 0.0, 0.0), (1.5707963267948963, 0.0, 0.0), (0.0, 0.0, 1.0)),
        ),
        tool=(((0.0, 0.0, -0.215), (0.0, 3.141592653589793, 0.0)),),
        mapping=KUKA_MAP,
    ),
    RefArm(
        name='fanuc_lrmate200id',
        source='ros-industrial/fanuc fanuc_lrmate200id_support/urdf/lrmate200id_macro.xacro @ 8fee5e30e535',
        controller=((0.0, 0.0, 0.33), (0.0, 0.0, 0.0)),
        joints=(
            ((0.0, 0.0, 0.33), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0)),
            ((0.05, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
            ((0.0, 0.0, 0.33), (0.0, 0.0, 0.0), (0.0, -1.0, 0.0)),
            ((0.0, 0.0, 0.035), (0.0, 0.0, 0.0), (-1.0, 0.0, 0.0)),
            ((0.335, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, -1.0, 0.0)),
            ((0.08, 0.0, 0.0), (0.0, 0.0, 0.0), (-1.0, 0.0, 0.0)),
        ),
        tool=(((0.0, 0.0, 0.0), (0.0, 0.0, 0.0)), ((0.0, 0.0, 0.0), (3.141592653589793, -1.5707963267948966, 0.0))),
        mapping=FANUC_MAP,
    ),
    RefArm(
        name='fanuc_m20ia',
        source='ros-industrial/fanuc fanuc_m20ia_support/urdf/m20ia_macro.xacro @ 8fee5e30e535',
        controller=((0.0, 0.0, 0.525), (0.0, 0.0, 0.0)),
        joints=(
            ((0.0, 0.0, 0.525), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0)),
            ((0.15, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
            ((0.0, 0.0, 0.79), (0.0, 0.0, 0.0), (0.0, -1.0, 0.0)),
            ((0.0, 0.0, 0.25), (0.0, 0.0, 0.0), (-1.0, 0.0, 0.0)),
            ((0.835, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, -1.0, 0.0)),
            ((0.1, 0.0, 0.0), (0.0, 0.0, 0.0), (-1.0, 0.0, 0.0)),
        ),
        tool=(((0.0, 0.0, 0.0), (0.0, 0.0, 0.0)), ((0.0, 0.0, 0.0), (3.141592653589793, -1.5707963267948966, 0.0))),
        mapping=FANUC_MAP,
    ),
    RefArm(
        name='yaskawa_gp8',
        source='ros-industrial/motoman motoman_gp8_support/urdf/gp8_macro.xacro @ 433be15f6a27',
        controller=((0.0, 0.0, 0.33), (0.0, 0.0, 0.0)),
        joints=(
            ((0.0, 0.0, 0.33), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0)),
            ((0.04, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
            ((0.0, 0.0, 0.345), (0.0, 0.0, 0.0), (0.0, -1.0, 0.0)),
            ((0.34, 0.0, 0.04), (0.0, 0.0, 0.0), (-1.0, 0.0, 0.0)),
            ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, -1.0, 0.0)),
            ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (-1.0, 0.0, 0.0)),
        ),
        tool=(((0.08, 0.0, 0.0), (3.1415926, -1.570796, 0.0)),),
        mapping=YASKAWA_MAP,
    ),
    RefArm(
        name='staubli_tx2_60',
        source='ros-industrial/staubli_experimental staubli_tx2_60_support/urdf/tx2_60_macro.xacro @ 256a71acea21',
        controller=((0.0, 0.0, 0.375), (0.0, 0.0, 0.0)),
        joints=(
            ((0.0, 0.0, 0.375), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0)),
            ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
            ((0.0, 0.02, 0.29), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
            ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0)),
            ((0.0, 0.0, 0.31), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
            ((0.0, 0.0, 0.07), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0)),
        ),
        tool=(((0.0, 0.0, 0.0), (0.0, -1.5707963267948966, 0.0)), ((0.0, 0.0, 0.0), (0.0, 1.5707963267948966, 0.0))),
        mapping=STAUBLI_MAP,
    ),

    RefArm(
        name='ur3e',
        source="ros-industrial/universal_robot ur_description/config/ur3e/default_kinematics.yaml + ur_description/urdf/inc/ur_macro.xacro @ a7a2c5459b97",
        controller=((0.0, 0.0, 0.0), (0.0, 0.0, PI)),  # base_link-base_fixed_joint: 'base' = the UR controller's Base frame
        pre=(((0.0, 0.0, 0.0), (0.0, 0.0, PI)),),  # base_link-base_link_inertia
        joints=(
            ((0.0, 0.0, 0.15185), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0)),
            ((0.0, 0.0, 0.0), (1.570796327, 0.0, 0.0), (0.0, 0.0, 1.0)),
            ((-0.24355, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0)),
            ((-0.2132, 0.0, 0.13105), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0)),
            ((0.0, -0.08535, -1.750557762378351e-11), (1.570796327, 0.0, 0.0), (0.0, 0.0, 1.0)),
            ((0.0, 0.0921, -1.8890025766262e-11), (1.570796326589793, 3.141592653589793, 3.141592653589793), (0.0, 0.0, 1.0)),
        ),
        tool=(((0.0, 0.0, 0.0), (0.0, -PI / 2, -PI / 2)), ((0.0, 0.0, 0.0), (PI / 2, 0.0, PI / 2))),  # wrist_3-flange, flange-tool0
        mapping=UR_MAP,
    ),
    RefArm(
        name='ur5e',
        source="ros-industrial/universal_robot ur_description/config/ur5e/default_kinematics.yaml + ur_description/urdf/inc/ur_macro.xacro @ a7a2c5459b97",
        controller=((0.0, 0.0, 0.0), (0.0, 0.0, PI)),  # base_link-base_fixed_joint: 'base' = the UR controller's Base frame
        pre=(((0.0, 0.0, 0.0), (0.0, 0.0, PI)),),  # base_link-base_link_inertia
        joints=(
            ((0.0, 0.0, 0.1625), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0)),
            ((0.0, 0.0, 0.0), (1.570796327, 0.0, 0.0), (0.0, 0.0, 1.0)),
            ((-0.425, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0)),
            ((-0.3922, 0.0, 0.1333), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0)),
            ((0.0, -0.0997, -2.044881182297852e-11), (1.570796327, 0.0, 0.0), (0.0, 0.0, 1.0)),
            ((0.0, 0.0996, -2.042830148012698e-11), (1.570796326589793, 3.141592653589793, 3.141592653589793), (0.0, 0.0, 1.0)),
        ),
        tool=(((0.0, 0.0, 0.0), (0.0, -PI / 2, -PI / 2)), ((0.0, 0.0, 0.0), (PI / 2, 0.0, PI / 2))),  # wrist_3-flange, flange-tool0
        mapping=UR_MAP,
    ),
    RefArm(
        name='ur10e',
        source="ros-industrial/universal_robot ur_description/config/ur10e/default_kinematics.yaml + ur_description/urdf/inc/ur_macro.xacro @ a7a2c5459b97",
        controller=((0.0, 0.0, 0.0), (0.0, 0.0, PI)),  # base_link-base_fixed_joint: 'base' = the UR controller's Base frame
        pre=(((0.0, 0.0, 0.0), (0.0, 0.0, PI)),),  # base_link-base_link_inertia
        joints=(
            ((0.0, 0.0, 0.1807), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0)),
            ((0.0, 0.0, 0.0), (1.570796327, 0.0, 0.0), (0.0, 0.0, 1.0)),
            ((-0.6127, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0)),
            ((-0.57155, 0.0, 0.17415), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0)),
            ((0.0, -0.11985, -2.458164590756244e-11), (1.570796327, 0.0, 0.0), (0.0, 0.0, 1.0)),
            ((0.0, 0.11655, -2.390480459346185e-11), (1.570796326589793, 3.141592653589793, 3.141592653589793), (0.0, 0.0, 1.0)),
        ),
        tool=(((0.0, 0.0, 0.0), (0.0, -PI / 2, -PI / 2)), ((0.0, 0.0, 0.0), (PI / 2, 0.0, PI / 2))),  # wrist_3-flange, flange-tool0
        mapping=UR_MAP,
    ),
)

BY_NAME = {a.name: a for a in ARMS}
