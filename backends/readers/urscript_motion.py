"""The motion arithmetic of reading URScript: a movej's joint speed and acceleration shares, and
the target of PolyScope's Direction node moving "Until (distance)".

URScript manual (e-Series): movej's `a`, `v` are the leading axis' acceleration and speed;
`pose_trans(A, B)` is B in A's frame, `pose_sub(A, B)` the difference (A.pos - B.pos,
R_A R_B^-1), `pose_add(A, B)` (A.pos + B.pos, R_B R_A); `get_target_waypoint()` the target of
the move that ran last (PolyScope's Direction node runs right after it).
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable

from rmot.backends.readers.common import number, split_top
from rmot.backends.readers.rapid import num_text
from rmot.backends.readers.urscript_text import block_end
from rmot.lang import ir

__all__ = [
    "DIRECTION_FUNCTION", "DIRECTION_LINES", "direction_target", "kept_direction", "move_arguments", "rest_to_rest_shares",
    "share",
]


def share(ratio: float) -> float | None:
    """A joint speed/acceleration ratio as rmot's %, None for 100 % (the default) or above."""
    pct = round(100.0 * ratio, 3)
    return None if pct >= 99.95 else max(pct, 1.0)


def rest_to_rest_shares(start: tuple[float, ...], joints: tuple[float, ...], v: float, a: float,
                        limits: tuple[tuple[float, ...], tuple[float, ...]]) -> tuple[float | None, float | None]:
    """(joint speed %, joint acceleration %) of a movej from rest at `start` to rest at `joints`
    (deg) whose leading axis runs at `v`, `a` (rad/s, rad/s²): on the joint-space line,
    trapezoidal, the binding joint is the one with the least limit per degree; a triangular
    profile never reaches the speed limit, which stays 100 %."""
    delta = [abs(math.radians(q - q0)) for q, q0 in zip(joints, start)]
    lead = max(delta)
    if lead < 1e-9:
        return None, None
    vmax, amax = limits
    path_speed, path_accel = v / lead, a / lead  # of s in 0..1 along the joint-space line
    moving = [i for i, d in enumerate(delta) if d > 1e-12]
    accel = share(path_accel / min(amax[i] / delta[i] for i in moving))
    triangular = abs(path_speed * path_speed - path_accel) <= 1e-3 * path_accel
    speed = None if triangular else share(path_speed / min(vmax[i] / delta[i] for i in moving))
    return speed, accel


# PolyScope's helper of the Direction node, as it writes it (spaces removed): the point at
# `position_distance` along `direction` (in `feature`'s axes) from the last move's target
DIRECTION_FUNCTION = (
    "defcalculate_point_to_move_towards(feature,direction,position_distance):",
    "localposDir=[direction[0],direction[1],direction[2]]",
    "if(norm(posDir)<1e-6):",
    "returnget_target_waypoint()",
    "end",
    "localdirection_vector_normalized=normalize(posDir)",
    "localdisplacement_pose=p[direction_vector_normalized[0]*position_distance,direction_vector_normalized[1]"
    "*position_distance,direction_vector_normalized[2]*position_distance,0,0,0]",
    "localwanted_displacement_in_base_frame=pose_sub(pose_trans(feature,displacement_pose),feature)",
    "returnpose_add(get_target_waypoint(),wanted_displacement_in_base_frame)",
    "end",
)

# the node's statements (spaces removed), {n} its number: a thread moves, the program waits for it
_DIRECTION_NODE = (
    r"globalmove_thread_flag_{n}=0", r"threadmove_thread_{n}\(\):", r"enter_critical", r"move_thread_flag_{n}=1",
    r"localtowardsPos=calculate_point_to_move_towards\((?P<args>.*)\)", r"movel\(towardsPos,(?P<move>.*)\)",
    r"move_thread_flag_{n}=2", r"exit_critical", r"end", r"move_thread_flag_{n}=0",
    r"move_thread_han_{n}=runmove_thread_{n}\(\)", r"while\(True\):", r"sleep\(1\.0E-10\)",
    r"if\(move_thread_flag_{n}>1\):", r"joinmove_thread_han_{n}", r"break", r"end", r"sync\(\)", r"end",
)
DIRECTION_LINES = len(_DIRECTION_NODE)


def direction_target(texts: list[str], last: tuple[str, ir.Pose] | None,
                     feature_pose: Callable[[str], ir.Pose | None]) -> tuple[str, ir.Pose, list[str]] | None:
    """(rmot target expression, pose, the movel's other arguments) of a Direction node moving
    until a distance, whose statements (spaces removed) are `texts`, after a move to `last`
    (its expression and pose): the last target moved by `distance` along the unit `direction`
    turned into the base by the feature's rotation, its orientation kept. `feature_pose`
    resolves the feature's text to a pose (or None)."""
    n = re.fullmatch(r"globalmove_thread_flag_(\d+)=0", texts[0]) if texts else None
    if n is None or last is None or len(texts) < DIRECTION_LINES:
        return None
    found = [re.fullmatch(p.replace("{n}", n.group(1)), t) for p, t in zip(_DIRECTION_NODE, texts)]
    call, move = found[4], found[5]
    if any(f is None for f in found) or call is None or move is None:
        return None
    args = split_top(call.group("args"))
    feature = feature_pose(args[0]) if len(args) == 3 else None
    vector = re.fullmatch(r"\[(.*)\]", args[1]) if feature is not None else None
    direction = [number(x) for x in split_top(vector.group(1))] if vector else []
    distance = number(args[2]) if direction else None
    components = [d for d in direction if d is not None]
    if feature is None or distance is None or len(components) != 3:
        return None
    norm = math.sqrt(sum(d * d for d in components))
    expr, pose = last
    if norm < 1e-6:  # PolyScope's helper returns the last target itself
        return expr, pose, split_top(move.group("move"))
    dx, dy, dz = (distance * d / norm for d in components)
    offset = (ir.Pose((0.0, 0.0, 0.0), feature.quaternion) * ir.Pose((dx, dy, dz))).position
    x, y, z = (p + o for p, o in zip(pose.position, offset))
    terms = ", ".join(f"{axis}={num_text(1000.0 * o)}mm" for axis, o in zip("xyz", offset) if abs(o) > 1e-12)
    return (f"shift({expr}, {terms})" if terms else expr), ir.Pose((x, y, z), pose.quaternion), split_top(move.group("move"))


def kept_direction(texts: list[str], heads: list[str], i: int) -> tuple[str, int] | None:
    """(why it stays native, the index after it) of a PolyScope Direction node whose thread
    `thread move_thread_N():` is statement i (statements without spaces, their first words):
    the thread, the `run`, and the program's `while (True):` that waits for it (its end). A node
    moving "Until" tool contact or another condition ends its motion when that holds (no rmot
    form); one moving until a distance, not read by direction_target, starts from the last move's
    target (`get_target_waypoint()`), unknown here (after a block, a call, a native line)."""
    m = re.fullmatch(r"threadmove_thread_(\d+)\(\):", texts[i]) if 0 < i < len(texts) else None
    n = m.group(1) if m else ""
    if m is None or texts[i - 1] != f"globalmove_thread_flag_{n}=0":
        return None
    j = block_end(heads, i)
    if texts[j + 1:j + 4] != [f"move_thread_flag_{n}=0", f"move_thread_han_{n}=runmove_thread_{n}()", "while(True):"]:
        return None
    k = block_end(heads, j + 3)
    waits = texts[j + 4:k]
    if k < len(texts) and any("tool_contact(" in t for t in waits):
        return "a PolyScope Direction node moving until tool contact: a motion that ends on a condition " \
               "has no rmot form", k + 1
    if k >= len(texts) or not any(t == f"if(move_thread_flag_{n}>1):" for t in waits):
        return None
    if sum(t.startswith("if(") for t in waits) > 1:
        return "a PolyScope Direction node moving until a condition: a motion that ends on a condition " \
               "has no rmot form", k + 1
    return "a PolyScope Direction node: it moves from the last move's target (`get_target_waypoint()`), " \
           "not known here (after a block, a call or a native line), or along a feature or direction " \
           "not known here", k + 1


def move_arguments(func: str, kind: str, args: list[str]) -> tuple[list[str], dict[str, str]] | None:
    """(the points, the named arguments a v r t mode) of a move's arguments, positional ones in the
    manual's order (URScript manual, module motion: movej/movel(q, a, v, t, r), movep(pose, a, v, r),
    movec(via, to, a, v, r, mode)); None for another form or a mode other than 0. movep ("Move
    Process. Blend circular (in tool-space) and move linear (in tool-space) to position") is a
    straight line at the tool speed v with a blend of radius r: rmot's linear move with speed and
    zone (the constant-speed timing through the blend is the controller's, rmot plans its own)."""
    named = dict(a.split("=", 1) for a in args if re.match(r"\w+=", a) and not a.startswith("get_"))
    given = [a for a in args if not (re.match(r"\w+=", a) and not a.startswith("get_"))]
    npoints = 2 if kind == "circular" else 1
    points, positional = given[:npoints], given[npoints:]
    order = ("a", "v", "r", "mode") if kind == "circular" else ("a", "v", "r") if func == "movep" else ("a", "v", "t", "r")
    if len(points) != npoints or len(positional) > len(order) or set(named) & set(order[:len(positional)]):
        return None
    named.update(zip(order, positional))
    if set(named) - {"a", "v", "r", "t", "mode"} or named.get("mode", "0") != "0":
        return None
    return points, named
