"""Coordinated motion in Yaskawa INFORM jobs: the robot's line or arc relative to a turning
station (R1 the slave, S1 the master), written as SMOVL / SMOVC with the station's `+MOVJ`.

The form, from three independent public sources that agree:
  * a job saved by a DX200 controller (rpiRobotics/dx200_motion_progam_exec,
    example_inform/R1-S1-SAMPLE.JBI @ 57e6205e): under `///GROUP1 RB1` / `///GROUP2 ST1` the
    same job holds `MOVL C00002 V=11.0  +MOVJ EC00002 VJ=0.78` (the station at its own speed)
    and `SMOVL C00003 V=11.0  +MOVJ EC00003` (coordinated: the station's part without a
    speed), every C and EC a taught position of its own group;
  * RoboDK's Motoman post processor (RoboDK Inc., Motoman.py settings, as published in
    TetraGenAdmin/TGRoboDKPostProcessors @ c0913043): `SMOVL C00008 BC00008 V=166.7  +MOVJ
    EC00008` "Synchronized motion (for the turntable)" against `MOVL C00008 BC00008 V=166.7
    +MOVJ EC00008 VJ=100.00` "Non synchronized motion";
  * a laser-cladding job generator for a robot with a 2-axis station (a VB.NET program found by
    exact-string search, repository not identified): `SMOVL Cn V=<process speed> PL=n +MOVJ
    ECn ...` for the seam's first point and `SMOVC Cn V=<process speed> ...` for its arc
    points, the process speed written as V= itself, where its uncoordinated station moves
    compute the station's VJ from that speed and the radius instead.
The INFORM instruction list names the master side `+MOVJ`, `+MOVL`, `+MOVC` ("YASKAWA YRC1000
INFORM Language - Part 4: Move Instructions", 9.1 Coordinated Robot Control; a markdown digest
of the manual found by code search, repository not identified), and a summary of the DX200's
functions calls coordinated operation "master-slave relative interpolation" that keeps "the
ideal posture of the tool relative to the workpiece" (https://www.chnfcs.com/manual/
YASKAWA-DX200.html?pagenum=2, 3.2 Coordinated Motion). Assumed from MOVC, not seen on SMOVC
in a source: FPT on an arc's end (continuous arcs, inform.py's circular).

What rmot writes: each C position is the planned TCP in ROBOT coordinates with the station at
the EC values written beside it (the taught pair the controller reads the position relative to
the station from); V= the programmed TCP speed relative to the part, which the plan keeps
(compiler/plan/coordinated.py); the station's +MOVJ without VJ. A coordinated arc's start line
carries the station's values at the move's start, its via the values where the plan passes the
via (InstructionRecord.ext_via), its end the move's end values.

Not vouched for, so refused at the move (E607): a line or arc while the base axis (the track,
BC) moves. No source found says how a Yaskawa controller interpolates a base axis with the TCP
of a MOVL/MOVC/SMOVL (the sources write BC beside such moves but none describes the path).
"""

from __future__ import annotations

import math

from rmot.lang import ir, plan_types

__all__ = ["calibration_line", "is_coordinated", "refusal", "via_pose"]


def is_coordinated(node: ir.Move) -> bool:
    """Whether `node` is written coordinated (SMOVL/SMOVC): its path relative to a moving part."""
    return node.coordinated is not None and node.coordinated.relative()


def refusal(task: ir.Task, moves: list[ir.Move], base: tuple[str, ...]) -> tuple[str, ir.Move] | None:
    """Why the first move of `moves` that INFORM cannot write as planned is refused, and that
    move: a line or arc while the track (a base axis named in `base`) moves."""
    for move in moves:
        coord = move.coordinated
        if coord is None:
            continue
        start, end = dict(coord.start), dict(move.ext)
        moving = [name for name in base if abs(end.get(name, start.get(name, 0.0)) - start.get(name, 0.0)) > 1e-12]
        if coord.relative() and not moving:
            continue
        kind = move.kind.name.lower()
        track = ", ".join(f"'{name}'" for name in moving)
        return (f"task '{task.name}': a {kind} move in frame '{move.frame.name}' while the track carrying the robot "
                f"moves ({track}, the base axis BC) is not written for INFORM: no source vouches for how a Yaskawa "
                "controller interpolates a base "
                "axis with the TCP's path (MOVL/MOVC/SMOVL); move the track before the line (a joint move or 'move "
                "axes') and keep it still during it (a coordinated seam on the positioner is written as SMOVL/SMOVC), "
                "or compile for rapid, krl or fanuc"), move
    return None


def via_pose(node: ir.Move, rec: plan_types.InstructionRecord) -> ir.Pose | None:
    """A circular move's via as INFORM writes it, in the robot's base frame: for a coordinated
    arc, the via as programmed in its frame placed where the frame is when the plan passes it
    (the axes at InstructionRecord.ext_via); else the via's base-frame pose."""
    if node.via is None:
        return None
    if not is_coordinated(node) or rec.ext_via is None:
        return node.via.pose
    assert node.coordinated is not None  # is_coordinated
    names = tuple(name for name, _ in node.ext)
    frame = node.coordinated.part_in_base(names, rec.ext_via[None, :])[0]
    return ir.Pose.from_matrix(frame @ node.via.in_frame.matrix())


def calibration_line(station_in_robot: ir.Pose) -> str:
    """The checklist line of a job with coordinated moves: the controller relates R1 to S1
    through its robot-station calibration, which must equal the cell's station placement (its
    first axis' frame: the axes' common point and their directions)."""
    x, y, z = (1000.0 * v for v in station_in_robot.position)
    rx, ry, rz = (math.degrees(a) for a in station_in_robot.rpy())
    return (f"R1:S1 coordinated (SMOVL/SMOVC, ST1 the master): the robot-station calibration must put ST1's axes' "
            f"common point at X {x:.3f}, Y {y:.3f}, Z {z:.3f} mm, their frame at Rx {rx:.4f}, Ry {ry:.4f}, "
            f"Rz {rz:.4f} deg in the robot's frame (every axis at 0)")
