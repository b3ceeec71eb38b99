"""External axes in vendor programs: which axis value goes where, and the frames that ride on a
unit. The values come from the IR (ir.Move.ext: every axis the task drives, at the move's
target); the backends only format them.

Bindings (rmot's defaults; the report's checklist lists them as machine data to check):
  * the task's axes in `with` order (a mechanism's axes in their order) take the vendor's
    external-axis slots in turn: RAPID eax_a, eax_b, ... (robtarget/jointtarget `extax`), KRL
    E1, E2, ... (E6POS/E6AXIS); linear axes in mm, revolute ones in degrees;
  * a mechanism is the RAPID mechanical unit of its name in capitals (`pos` -> "POS").
A controller's world is the robot's base frame with every axis at home, as rmot writes it for
a robot without axes.

A linear or circular move while the track carrying the robot moves is written as the plain
move to a target with the track's new value beside it: each controller carries the arm's base
on the track and interpolates the track with the TCP's path in the (fixed or coordinated) frame,
which is how rmot plans it (compiler/plan/coordinated.py):
  * ABB: the track a mechanical unit of MOC type TRACK, "linear track motion, only used when a
    robot is mounted on the track" (Technical reference manual - System parameters, Motion,
    Single Type, Mechanics); MoveL/MoveC with the robtarget's extax at the new track value;
  * KUKA: the track a ROBROOT kinematic ($EX_KIN ET1 #ERSYS, $ERSYSROOT): "with every motion of
    the ROBROOT kinematic system, the position in space of the robot changes ... the external
    coupling is always switched on" (KUKA Machine Data, $ERSYSROOT, "Frame chain with linear
    unit"); LIN/CIRC to an E6POS with the new E1;
  * Fanuc: the rail an integrated extended axis E1 of the robot's group (Extended Axis Control,
    integrated axis); L/C to a position whose GP1 block holds the new E1.
INFORM (a base axis BC interpolated with MOVL) is refused for now (backends/inform_axes.py).

RAPID (ABB "Technical reference manual - RAPID Instructions, Functions and Data types"):
robtarget.extax / jointtarget.extax (extjoint: eax_a..eax_f, 9E9 for an axis not used);
MoveExtJ "Move one or several mechanical units without TCP" (ToJointPos, Speed [\\T], Zone);
wobjdata [robhold, ufprog, ufmec, uframe, oframe]: ufprog FALSE and ufmec the unit's name for a
work object a unit moves, uframe then in the unit's moving frame.
KRL (KUKA System Software 8.x, Operating and Programming Instructions for System Integrators,
"E6POS", "E6AXIS"; KSS 8.5 "Configuration of Kinematic Systems"): E1..E6 in an E6POS or E6AXIS;
a base on an external kinematic system is `$BASE=EK(MACHINE_DEF[n].ROOT,MACHINE_DEF[n].MECH_TYPE,
offset)`, the offset in the kinematic's flange frame ($ETn_TFLA3 chain).
"""

from __future__ import annotations

import math
from dataclasses import replace

from rmot.backends.conventions import euler_zyx_deg, fmt, fmt_list, position_mm
from rmot.lang import ir, ir_tree
from rmot.lang.axis_motion import task_axes
from rmot.lang.ir_axes import ExtAxis, ExternalAxes

__all__ = ["RAPID_UNUSED", "coordinated", "driven_axes", "fanuc_coord", "fanuc_default_group", "fanuc_groups", "fanuc_in_world", "machine_data",
           "krl_e_axes", "mechanism_index", "rapid_extax", "rapid_wobj", "riding_frame",
           "unit_name", "vendor_values"]
__all__ += ["absolute_turns", "stacked_mechanisms"]

RAPID_UNUSED = "9E+09"  # "no position defined" in an extax / robax slot (RAPID reference, extjoint)
SLOTS = 6  # RAPID eax_a..eax_f, KRL E1..E6


def driven_axes(task: ir.Task, cell: ir.Cell) -> tuple[ExtAxis, ...]:
    """The external axes `task` drives, in slot order (none for a task without)."""
    return task_axes(task, cell.external)


def vendor_values(node: ir.Move, axes: tuple[ExtAxis, ...]) -> tuple[float, ...]:
    """The axis values at `node`'s target in the vendors' units: mm (linear) or deg (revolute)."""
    values = dict(node.ext)
    return tuple(values[a.name] * 1000.0 if a.linear else math.degrees(values[a.name]) for a in axes)


def rapid_extax(node: ir.Move, axes: tuple[ExtAxis, ...]) -> str:
    """The `extax` of a robtarget or jointtarget: eax_a..eax_f."""
    values = [fmt(v, 3) for v in vendor_values(node, axes)]
    return "[" + ",".join(values + [RAPID_UNUSED] * (SLOTS - len(values))) + "]"


def krl_e_axes(node: ir.Move, axes: tuple[ExtAxis, ...]) -> str:
    """`,E1 v,...,E6 v` of an E6POS or E6AXIS (0 for a slot no axis takes, as KRL declares it)."""
    values = list(vendor_values(node, axes)) + [0.0] * (SLOTS - len(axes))
    return "".join(f",E{k + 1} {fmt(v, 4)}" for k, v in enumerate(values))


def unit_name(mechanism: str) -> str:
    return mechanism.upper()


def riding_frame(frame: ir.FrameRef, external: ExternalAxes | None) -> tuple[str, ir.Pose] | None:
    """(mechanism, the frame in the mechanism's flange frame) for a frame that rides on one."""
    if frame.name is None or external is None:
        return None
    mount = external.mount(frame.name)
    if mount is None or mount.kind != "frame":
        return None
    return mount.mechanism, mount.local


def mechanism_index(mechanism: str, cell: ir.Cell) -> int:
    """KRL's MACHINE_DEF index of a mechanism: 1 is the robot, mechanisms follow in cell order."""
    assert cell.external is not None
    return 2 + [m.name for m in cell.external.mechanisms].index(mechanism)


def rapid_wobj(frame: ir.FrameRef, robot: ir.RobotInstance, cell: ir.Cell) -> str:
    """A wobjdata literal for a task with external axes: on a unit, `ufprog` FALSE, `ufmec` the
    unit and uframe in its moving frame; else fixed, uframe in the controller's world (the
    robot's base frame with the axes at home)."""
    riding = riding_frame(frame, cell.external)
    if riding is not None:
        mechanism, local = riding
        return f'[FALSE,FALSE,"{unit_name(mechanism)}",{_pose(local)},[[0,0,0],[1,0,0,0]]]'
    return f'[FALSE,TRUE,"",{_pose(robot.base.inverse() * frame.world)},[[0,0,0],[1,0,0,0]]]'


def _xyzabc(pose: ir.Pose, fanuc: bool = False) -> str:
    """{X, Y, Z, A, B, C} in mm and degrees, KUKA's frame (A, B, C about z, y, x), or Fanuc's
    {X, Y, Z, W, P, R} (W, P, R about x, y, z: the same angles in the other order)."""
    a, b, c = euler_zyx_deg(pose)
    names, angles = ("XYZWPR", (c, b, a)) if fanuc else ("XYZABC", (a, b, c))
    return "{" + ",".join(f"{k} {fmt(v, 3)}" for k, v in zip(names, (*position_mm(pose), *angles))) + "}"


def _pose(pose: ir.Pose) -> str:
    """[[x,y,z],[q1,q2,q3,q4]] in mm and a w-first quaternion (RAPID pose)."""
    return f"[[{fmt_list(position_mm(pose), 3)}],[{fmt_list(pose.quaternion, 6)}]]"


def machine_data(cell: ir.Cell, robot: ir.RobotInstance, axes: tuple[ExtAxis, ...], vendor: str,
                 coordinated_pair: bool = False) -> list[str]:
    """The controller configuration the program assumes, as checklist lines for its header: rmot
    cannot read the controller, so the numbers it planned with are printed for a person to
    compare with the machine data (RAPID: the MOC mechanical units; KRL: $EX_KIN / $ETn and
    MACHINE_DEF; KSS 8.5 "Configuration of Kinematic Systems")."""
    if cell.external is None or not axes:
        return []
    world = robot.base.inverse()  # the controller's world: the arm's base with every axis at home
    lines = ["machine data assumed (check on the controller): world = the robot base with every axis at home"]
    slots = {a.name: k for k, a in enumerate(axes)}  # RAPID eax_*, KRL E*: the task's axes in `with` order
    mechanisms = list(cell.external.mechanisms)
    if vendor != "fanuc":  # Fanuc numbers groups and rail axes in cell order, as fanuc_groups writes them
        mechanisms.sort(key=lambda m: min((slots[a.name] for a in m.axes if a.name in slots), default=len(slots)))
    rail, group = 0, 1
    for mech in mechanisms:
        mine = [a for a in mech.axes if a in axes]
        if not mine:
            continue
        base = world * mech.base
        where = f"base at {_pose(base) if vendor == 'rapid' else _xyzabc(base, vendor == 'fanuc')} in world"
        if vendor == "rapid":
            kind = "TRACK (carries the robot)" if mech.kind == "track" else "rotating/linear unit, coordinated work objects"
            lines.append(f'unit "{unit_name(mech.name)}": MOC type {kind}, {where}')
        elif vendor == "fanuc":
            group += mech.kind != "track"
            pair = f"the leader of the coordinated pair (CD_PAIR leader GP{group}, follower GP1, calibrated)" if coordinated_pair \
                else "not coordinated"
            kind = "extended axes of group 1 (integrated rail)" if mech.kind == "track" else f"motion group {group}, {pair}"
            lines.append(f"{mech.name}: {kind}, {where}")
        else:
            index = mechanism_index(mech.name, cell)
            coupled = ", LIN/CIRC mathematically coupled to it ($BASE=EK follows the kinematic)" if coordinated_pair else ""
            kind = "$ERSYSROOT/$ROBROOT on the carriage (mathematically coupled)" if mech.kind == "track" \
                else f"$ETn external kinematic, EK() bases{coupled}"
            lines.append(f"{mech.name}: MACHINE_DEF[{index}], {kind}, {where}")
        for axis in mine:
            slot = slots[axis.name] + 1
            name = f"eax_{'abcdef'[slot - 1]}" if vendor == "rapid" else f"E{slot}"
            if vendor == "fanuc":
                rail += mech.kind == "track"
                name = f"GP1 E{rail}" if mech.kind == "track" else f"GP{group} J{mine.index(axis) + 1}"
            direction = "xyz"[axis.direction.index(1.0)]
            lines.append(f"  {name} = {axis.name}: {'linear along' if axis.linear else 'revolute about'} {direction}, "
                         f"[{axis.shown(axis.low)}, {axis.shown(axis.high)}], {axis.shown(axis.speed)}/s, "
                         f"{axis.shown(axis.accel)}/s^2" + (f", moves {axis.mass:g} kg" if axis.mass else ""))
            lines += absolute_turns(axis, name)
    return lines


def stacked_mechanisms(cell: ir.Cell, node: ir.Move) -> str:
    """The stacked mechanisms (one riding on another) a move drives, as `'p2' on 'rail'`, or
    "": rmot plans and verifies them but writes them for no controller yet (each vendor's
    chained kinematics, KUKA $ETn on $ETm or an ABB unit on a track, are not verified)."""
    external = cell.external
    if external is None:
        return ""
    names = {name for name, _ in node.ext}
    return ", ".join(f"'{m.name}' on '{m.on}'" for m in external.mechanisms
                     if m.on is not None and any(a.name in names for a in m.axes))


def absolute_turns(axis: ExtAxis, name: str) -> list[str]:
    """The checklist line of a revolute axis with more than +-180 deg of range: rmot plans its
    targets as absolute values (a move from -10 to 700 deg turns 710 deg, as programmed), which
    the controller follows only when the axis is a normal one, not an endless / shortest-way
    (modulo) axis."""
    if not axis.beyond_half_turn():
        return []
    return [f"  {name} = {axis.name}: absolute targets, turned through the programmed difference (no "
            f"shortest-way wrap): configure it as a normal axis, not an endless (modulo) one"]


def fanuc_in_world(node: ir.Move, robot: ir.RobotInstance, cell: ir.Cell) -> ir.Move:
    """A move of a task with external axes, its targets written where a Fanuc controller without
    coordinated motion takes them: a frame fixed in the world keeps its UFRAME (its value in the
    controller's world, the robot base with the axes at home); a frame on a positioner, and the
    robot's own base frame (which the track moves), become UFRAME 0 with the target in world."""
    assert cell.external is not None
    frame = node.frame
    world = robot.base.inverse()
    if frame.name is not None and riding_frame(frame, cell.external) is None:
        return replace(node, frame=ir.FrameRef(frame.name, world * frame.world, frame.world))
    base = cell.external.world(robot.name, dict(node.ext)) or robot.base

    def in_world(t: ir.CartesianTarget | None) -> ir.CartesianTarget | None:
        return None if t is None else replace(t, in_frame=world * base * t.pose)

    target = node.target if isinstance(node.target, ir.JointTarget) else in_world(node.target)
    return replace(node, frame=ir.FrameRef(None), target=target, via=in_world(node.via))  # type: ignore[arg-type]


def fanuc_groups(node: ir.Move, axes: tuple[ExtAxis, ...], cell: ir.Cell, uf: int, ut: int) -> tuple[list[str], list[str]]:
    """(lines ending the GP1 block: a track's axes as the robot group's extended axes E1..;
    the blocks of the other motion groups: each positioner its own group GP2, GP3, ... with J1..)
    (Fanuc .ls /POS format: `E1=  v  mm` after the W, P, R line, `GP2: UF : n, UT : m, J1= v mm`
    blocks, as in controller programs of a robot on a rail with a second group.)"""
    assert cell.external is not None
    values = dict(zip((a.name for a in axes), vendor_values(node, axes)))
    extended: list[str] = []
    blocks: list[str] = []
    for mech in cell.external.mechanisms:
        mine = [a for a in mech.axes if a.name in values]
        if not mine:
            continue
        cells = [f"{fmt(values[a.name], 3):>9}  {'mm' if a.linear else 'deg'}" for a in mine]
        if mech.kind == "track":
            extended += [f"E{len(extended) + k + 1}= {c}" for k, c in enumerate(cells)]
        else:
            group = 2 + len(blocks) // 3
            blocks += [f"   GP{group}:", f"\tUF : {uf}, UT : {ut},\t",
                       "\t" + ",\t".join(f"J{k + 1}= {c}" for k, c in enumerate(cells))]
    return ["\t" + ",\t".join(extended)] if extended else [], blocks


def coordinated(task: ir.Task) -> bool:
    """Whether `task` has a move relative to a moving part (a linear or circular move on a frame
    a moving positioner carries; a move on a fixed frame while the track moves is not one)."""
    return any(isinstance(i, ir.Move) and i.coordinated is not None and i.coordinated.relative() for i in ir_tree.walk(task.body))


def fanuc_coord(node: ir.Move) -> str:
    """` COORD` after the termination of a coordinated L or C move: the follower (the robot,
    group 1) moves relative to the leader (the positioner's group), its path and speed relative
    to the leader's moving frame (FANUC Coordinated Motion Function, Setup and Operations
    Manual, "COORD motion option"). The position is written as every other one of the task:
    group 1 in UFRAME 0 (the world with the axes at home) at the leader's values in its GP2
    block, from which the controller takes the position relative to the leader through the
    calibrated pair; rmot assumes that calibration equals the cell's positioner base.
    A linear or circular move whose frame stays put while only the robot's integrated rail (the
    group's extended axis E1) moves is a plain L or C: the controller interpolates the rail with
    the TCP's path in the user frame (FANUC HandlingTool Setup and Operations Manual, "Extended
    Axis Control", integrated axes)."""
    return " COORD" if node.coordinated is not None and node.coordinated.relative() else ""


def fanuc_default_group(axes: tuple[ExtAxis, ...], cell: ir.Cell) -> str:
    """DEFAULT_GROUP: the robot's group and one per positioner the task drives."""
    assert cell.external is not None
    names = {a.name for a in axes}
    groups = 1 + sum(1 for m in cell.external.mechanisms if m.kind == "positioner" and any(a.name in names for a in m.axes))
    return ",".join(["1"] * groups + ["*"] * (5 - groups))
