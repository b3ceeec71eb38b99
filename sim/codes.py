"""Diagnostic codes of the verification stage (sim).

E3xx/W3xx are verification findings; E56x/W56x are broken mesh files (the E5xx "files"
range is shared with the front end, so the sim keeps to the 56x block).
"""

from __future__ import annotations

from rmot.lang.diagnostics import Code

__all__ = [
    "COLLISION", "SELF_COLLISION", "ROBOT_COLLISION", "STATIC_CONTACT", "CLEARANCE",
    "JOINT_POSITION", "JOINT_VELOCITY", "JOINT_ACCEL", "JOINT_TORQUE",
    "MESH_MISSING", "MESH_UNREADABLE", "MESH_EMPTY", "MESH_TRUNCATED", "MESH_NOT_WATERTIGHT",
    "ROBOT_UNAVAILABLE", "RENDER_UNAVAILABLE",
]

COLLISION = Code("E300", "collision", "a robot link or tool touches a fixture")
SELF_COLLISION = Code("E301", "self-collision", "two non-adjacent solids of one robot (or its tool) touch")
ROBOT_COLLISION = Code("E302", "robot-collision", "two robots touch on the shared timeline")
JOINT_POSITION = Code("E310", "joint-position-limit", "a joint leaves its position range")
JOINT_VELOCITY = Code("E311", "joint-velocity-limit", "a joint moves faster than its velocity limit")
JOINT_ACCEL = Code("E312", "joint-acceleration-limit", "a joint accelerates beyond its limit")
JOINT_TORQUE = Code("E313", "joint-torque-limit", "inverse dynamics needs more torque than a joint's limit")
ROBOT_UNAVAILABLE = Code("E320", "robot-model-unavailable", "the robot model could not be loaded for verification")

STATIC_CONTACT = Code("W300", "static-contact", "two bodies that never move overlap (a cell modelling issue)")
CLEARANCE = Code("W301", "clearance", "a body comes closer to another than the requested clearance")
RENDER_UNAVAILABLE = Code("W310", "render-unavailable", "a finding image could not be rendered")

MESH_MISSING = Code("E560", "mesh-missing", "a mesh file does not exist")
MESH_UNREADABLE = Code("E561", "mesh-unreadable", "a mesh file cannot be parsed")
MESH_EMPTY = Code("E562", "mesh-empty", "a mesh file has no triangles")
MESH_TRUNCATED = Code("E563", "mesh-truncated", "a mesh file ends before its declared points or polygons")
MESH_NOT_WATERTIGHT = Code("W560", "mesh-not-watertight", "a mesh is not a closed manifold surface")

# parts that tools pick up and put down
PART_NOT_TOUCHING = Code("E330", "part-not-touching", "attach of a part farther than 2 mm from the tool's solid and its TCP")
PART_HELD_ELSEWHERE = Code("E331", "part-held-elsewhere", "attach of a part another robot still holds")
PAYLOAD_EXCEEDED = Code("E332", "payload-exceeded", "tool mass plus held parts beyond the robot's rated payload")
PART_GRIP_DEPTH = Code("E333", "part-grip-depth", "a tool enters the part it attaches deeper than 2 mm")
__all__ += ["PART_NOT_TOUCHING", "PART_HELD_ELSEWHERE", "PAYLOAD_EXCEEDED", "PART_GRIP_DEPTH"]

# blended corners: the region a controller may drive (sim/corners.py)
CORNER_SPHERE = Code("W340", "corner-zone-sphere",
                     "a fixture lies inside a blended corner's zone sphere, where the controller's corner path may run")
CORNER_BOUND = Code("W341", "corner-controller-bound",
                    "a fixture lies within the corner bound of Fanuc CNT / KRL C_PTP (half the shorter neighbouring segment)")
__all__ += ["CORNER_SPHERE", "CORNER_BOUND"]
JOINT_TORQUE_ESTIMATE = Code("W342", "joint-torque-estimate",
                             "inverse dynamics needs more torque than a joint's estimated rating (the vendor publishes none)")
__all__ += ["JOINT_TORQUE_ESTIMATE"]

# `move free`: the joint-space search that finds its path (sim/free/)
FREE_GOAL_BLOCKED = Code("E250", "free-goal-in-collision",
                         "the target of a 'move free' is in collision (or closer than its clearance)")
FREE_START_BLOCKED = Code("E251", "free-start-in-collision", "a 'move free' starts in collision")
FREE_NO_PATH = Code("E252", "free-no-path", "the search found no collision-free path within its budget")
FREE_UNSUPPORTED = Code("E253", "free-placement",
                        "a 'move free' that is a task's first move, or inside a loop, if or proc")
FREE_PATH = Code("W250", "free-path", "the via points a 'move free' inserted (a note)")
__all__ += ["FREE_GOAL_BLOCKED", "FREE_START_BLOCKED", "FREE_NO_PATH", "FREE_UNSUPPORTED", "FREE_PATH"]

FEEDER_EMPTY = Code("E334", "feeder-empty", "attach from a feeder whose `count` parts have all been taken")
__all__ += ["FEEDER_EMPTY"]

# bodies that external axes carry (sim/axes_collide.py)
AXES_PATHS_UNCHECKED = Code("W602", "ext-paths-unchecked",
                            "collisions of bodies external axes carry are not checked on the other paths of an if or while")
AXES_SAMPLED = Code("W603", "ext-sampled-check",
                    "a note: bodies external axes carry are checked at every sample, without the no-miss bound")
__all__ += ["AXES_PATHS_UNCHECKED", "AXES_SAMPLED"]
