"""External axes in Yaskawa INFORM jobs: a track as the robot's base axis, a positioner as a
station, their positions in encoder pulses at the scale the cell declares.

An INFORM job writes base-axis and station-axis positions as encoder pulses (`BCnnnnn=` and
`ECnnnnn=` lines under `///POSTYPE PULSE` / `///PULSE`); the pulses per mm or per degree are
machine data of the controller (the axis' gear ratio and encoder), which a cell states as
`inform(pulses_per_mm=N)` (linear) or `inform(pulses_per_deg=N)` (revolute) after the axis'
accel. Without it, a track's base axis is written in mm under the rectangular form (a traveling
axis' position is mm data as well as pulses: see base_value), and a revolute station axis, whose
positions are pulses only, at ASSUMED_PULSES_PER_DEG with W610 and "ASSUMED" in the header's
checklist; a revolute base axis or a linear station axis without it is refused (E607).

The job's form (DX100/DX200/YRC1000 "Job data format" of the offline-teaching interface;
INFORM manual, "MOVJ/MOVL: additional items BC (base axis) and EC (station axis)" and
"Coordinated control of two groups: +MOVJ"):
  * `///NPOS C,BC,EC,P,BP,EX`: the counts of robot, base and station positions and of the P,
    BP, EX variables the job declares;
  * `BCnnnnn=p` (one value per base axis) and `ECnnnnn=p1,p2` (one per station axis) after
    the robot's `C` positions, under `///POSTYPE PULSE` and `///PULSE`;
  * `///GROUP1 RB1,BS1` (the robot and its base axis: one control group, one interpolation, so
    the carriage starts and stops with the arm) and `///GROUP2 ST1` (the station, its own group);
  * a move `MOVJ Cn BCn VJ=v +MOVJ ECn VJ=v` (`MOVL Cn BCn V=v ... +MOVJ ECn VJ=v`): the
    robot group's move with its base axis, then the station group's move started with it.
Witnesses of the form, found by exact-string search of public source (job generators and the
notes of a welding cell with a base axis and a station; repositories not identified):
`///NPOS n,n,n,0,0,0` with `BC00000=878036`, `EC00001=45886,0`, `///GROUP1 RB1,BS1`,
`///GROUP2 ST1` and `MOVJ C# BC# VJ=... +MOVJ EC# VJ=...`; `///NPOS 1,0,1,1,0,1` for a job
holding C00000, EC00000=0,0, P00000 and EX00000 (the count order C, BC, EC, P, BP, EX) under
`///GROUP1 RB1` / `///GROUP2 ST1`; `MOVJ C%05d BC%05d VJ=...` beside `BC%05d=%ld,%ld` lines.
RoboDK's Motoman post processor (RoboDK Inc., its settings file) writes the same forms:
`MOVL C00008 BC00008 V=166.7 +MOVJ EC00008 VJ=100.00` ("non synchronized motion (for the
turntable)", its default; `SMOVL ... +MOVJ EC00008` would synchronise it) and asks the user for
`PULSES_X_DEG` of each external axis, as rmot asks for `inform(pulses_per_...)`.

Positions: `C` is the TCP in ROBOT coordinates, the arm's own base frame, which rides on the
carriage at the move's BC value (rmot's planned TCP in the base frame: exact for any base-axis
direction); the station's axes stand at EC. rmot plans arm, base and station
time-synchronously; the station as its own group moves at its own VJ (% of its maximum speed),
so it starts with the arm but may end earlier or later (W604, once per task). A line or arc
relative to the turning station is the robot as its slave, SMOVL / SMOVC with the station's
`+MOVJ ECn` and no VJ (backends/inform_coordinated.py, its sources there).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from rmot.backends import codes
from rmot.backends.base import Backend, TaskContext
from rmot.backends.ext_axes import absolute_turns, driven_axes
from rmot.backends.inform_coordinated import calibration_line, is_coordinated, refusal
from rmot.lang import ir, ir_tree, plan_types
from rmot.lang.ir_axes import ExtAxis

__all__ = ["InformAxes", "inform_axes", "task_axes", "warn_pulse_rounding"]

PULSE_TOLERANCE_MM = 0.01  # whole-pulse rounding of external axes beyond this warns (W605)
# The station-axis scale written when the cell declares none: 100000 pulses per axis revolution,
# the fallback Visual Components' Yaskawa post processor (v1.05, `ppr.append(100000)`) writes
# with "WARNING! Using pulses but PPR/PZ data is invalid! Using default PPR/PZ values."; rmot
# writes it only with W610 and the header's checklist naming the value to confirm.
ASSUMED_PULSES_PER_DEG = 100000.0 / 360.0


@dataclass
class InformAxes:
    """A task's INFORM axes: the base axes (its track, BS1) and the station axes (its
    positioner, ST1); the pulse values each job collects (BC and EC lines, in order)."""

    base: tuple[ExtAxis, ...]
    station: tuple[ExtAxis, ...]
    station_origin: tuple[float, float, float] = (0.0, 0.0, 0.0)  # the point its axes pass through (world, m)
    coordinated: ir.Pose | None = None  # SMOVL/SMOVC written: the station's base in the robot's frame
    bc: list[str] = field(default_factory=list)
    ec: list[str] = field(default_factory=list)

    def fresh(self) -> InformAxes:
        """The same axes with no positions yet (one per job)."""
        return InformAxes(self.base, self.station, self.station_origin, self.coordinated)

    def groups(self) -> list[str]:
        robot = "///GROUP1 RB1,BS1" if self.base else "///GROUP1 RB1"
        return [robot] + (["///GROUP2 ST1"] if self.station else [])

    def npos(self, c: int, p: int) -> str:
        return f"///NPOS {c},{len(self.bc)},{len(self.ec)},{p},0,0"

    def base_in_mm(self) -> bool:
        """The base axes are written in mm (rectangular base-axis data), not pulses: a track
        whose cell declares no pulse scale (see base_value)."""
        return bool(self.base) and all(a.pulses is None for a in self.base)

    def pulse_lines(self) -> list[str]:
        """The BC and EC lines after the robot's C positions: BC in mm right after them while
        the rectangular form is in effect (base_in_mm), else under `///POSTYPE PULSE`."""
        bc = [f"BC{k:05d}={v}" for k, v in enumerate(self.bc)]
        ec = [f"EC{k:05d}={v}" for k, v in enumerate(self.ec)]
        in_mm, pulsed = (bc, ec) if self.base_in_mm() else ([], bc + ec)
        return in_mm + (["///POSTYPE PULSE", "///PULSE"] + pulsed if pulsed else [])

    def operands(self, line: str, values: dict[str, float], vj: str | None) -> str:
        """A robot move line `MOVx Cn ...` with the base operand after its C position and the
        station's `+MOVJ ECn VJ=v` after it (every move states both: an axis not moved keeps
        its value, which the move restates), the axes at `values` (SI, by name). `vj` None: a
        coordinated move (coordinated_lines), `SMOVx ... +MOVJ ECn` without the station's speed."""
        if not line.startswith("MOV"):
            return line
        if self.base:
            self.bc.append(",".join(base_value(a, values[a.name]) for a in self.base))
            word, c, rest = line.split(" ", 2)
            line = f"{word} {c} BC{len(self.bc) - 1:05d} {rest}"
        if self.station:
            self.ec.append(",".join(str(pulses(a, values[a.name])) for a in self.station))
            line += f" +MOVJ EC{len(self.ec) - 1:05d}" + ("" if vj is None else f" VJ={vj}")
        return "S" + line if vj is None else line

    def coordinated_lines(self, lines: list[str], node: ir.Move, rec: plan_types.InstructionRecord) -> list[str]:
        """A coordinated move's lines (inform_coordinated.py): each MOVL / MOVC line as SMOVL /
        SMOVC with the axes where its C position is taken: a circular move's start line (the
        previous target) at the move's start values, its via at the plan's values at the via
        (InstructionRecord.ext_via), its end and a line's target at the move's end values."""
        assert node.coordinated is not None  # only coordinated moves come here
        values = [dict(node.ext)]
        if node.kind is ir.MotionKind.CIRCULAR and rec.ext_via is not None:
            via = dict(zip((n for n, _ in node.ext), (float(v) for v in rec.ext_via), strict=True))
            values = [dict(node.coordinated.start), via, dict(node.ext)]
        moves = [k for k, line in enumerate(lines) if line.startswith("MOV")]
        at = dict(zip(moves, values[len(values) - len(moves):], strict=True))
        return [self.operands(line, at[k], None) if k in at else line for k, line in enumerate(lines)]

    def rounding_mm(self, node: ir.Move, tcp: tuple[float, float, float]) -> float:
        """A bound on how far writing whole pulses moves the TCP (world, m) of `node` relative
        to the part: the base axes' rounding itself, plus each station axis' rounding (an angle
        times the TCP's distance from the station's axes, which all pass through its base
        point: a positioner's axes are stacked without offsets)."""
        values = dict(node.ext)
        reach_mm = 1000.0 * math.dist(tcp, self.station_origin)
        total = 0.0
        for axis in self.base + self.station:
            shown = values[axis.name] * 1000.0 if axis.linear else math.degrees(values[axis.name])
            error = abs(written(axis, values[axis.name]) - shown)
            total += error if axis.linear else math.radians(error) * reach_mm
        return total

    def checklist(self) -> list[str]:
        """The machine data the job assumes, for a person to compare with the controller."""
        lines = ["machine data assumed: C in ROBOT coordinates (the arm's base on the carriage)"]
        for group, axes in (("R1+B1 base BS1", self.base), ("S1 station ST1", self.station)):
            for k, a in enumerate(axes):
                unit = a.unit()
                what = f"{group} axis {k + 1} = {a.name}: {'linear along' if a.linear else 'revolute about'} " \
                       f"{'xyz'[a.direction.index(1.0)]}, " + (f"moves {a.mass:g} kg, " if a.mass else "")
                if a.pulses is None and a.linear:
                    lines.append(what + "BC in mm (rectangular base-axis data), 0 mm at its 0, + = + mm")
                else:
                    assumed = " ASSUMED (not declared): confirm" if a.pulses is None else ""
                    lines.append(what + f"{scale(a):g} pulses/{unit}{assumed}, 0 pulses at 0 {unit}, + pulses = + {unit}")
                lines += absolute_turns(a, f"{group} axis {k + 1}")
        return lines + ([calibration_line(self.coordinated)] if self.coordinated is not None else [])

    def assumed(self) -> tuple[ExtAxis, ...]:
        """The station axes written at the assumed scale (ASSUMED_PULSES_PER_DEG)."""
        return tuple(a for a in self.station if a.pulses is None)


def scale(axis: ExtAxis) -> float:
    """The axis' pulses per mm or per degree: declared, else (a revolute station axis) the
    assumed ASSUMED_PULSES_PER_DEG."""
    return axis.pulses if axis.pulses is not None else ASSUMED_PULSES_PER_DEG


def pulses(axis: ExtAxis, value: float) -> int:
    """The axis' value (SI) in encoder pulses at its scale, rounded to a whole pulse."""
    shown = value * 1000.0 if axis.linear else math.degrees(value)
    return round(shown * scale(axis))


def base_value(axis: ExtAxis, value: float) -> str:
    """A base axis' BC value: whole pulses at its declared scale, or, for a track without one,
    mm with 3 decimals. A traveling axis' position is data in mm as well as in pulses: the
    NX100 "Specifications" of the remote-command target position list "7th axis pulse number
    (mm for traveling axis)"; the DX100 high-speed Ethernet server manual (3.3.17, base position
    variable BP) reads and writes it as "0: pulse value" or "16: base coordinated value"; and
    Visual Components' Yaskawa post (v1.05) writes `BCnnnnn=%.3f` (the track in mm) after the
    C positions of a rectangular (`///RECTAN`) job. The DX100 "Interface with an Easy Offline
    Teaching System" manual (4.1 Job Data Format, RECTAN: `<BCxxxxx> = <1>,<2>,<3>`; 4.3.1.3
    Base Axis: "B1 = X0, Y0, Z0 ... the distance of the axis from the origin of the coordinate
    system of teaching (For the used axes only.)", for ROBOT-type positions from the base
    coordinate system's origin) gives the same reading: one value for a one-axis track, its
    distance from where the base coordinates start (the track's 0, the checklist says so)."""
    if axis.pulses is None and axis.linear:
        return f"{value * 1000.0:.3f}"
    return str(pulses(axis, value))


def written(axis: ExtAxis, value: float) -> float:
    """The value (mm or degrees) the job's BC/EC text stands for."""
    if axis.pulses is None and axis.linear:
        return round(value * 1000.0, 3)
    return pulses(axis, value) / scale(axis)


def inform_axes(task: ir.Task, cell: ir.Cell, axes: tuple[ExtAxis, ...]) -> InformAxes | str:
    """The task's axes as INFORM's base and station groups, or why they cannot be written: more
    than one positioner (one station group, ST1), or an axis without its pulse scale that is
    neither a track's linear axis (written in mm) nor a revolute station axis (written at the
    assumed scale, W610). With a coordinated move (SMOVL/SMOVC) it holds the station's base in
    the robot's frame, for the robot-station calibration line of the checklist."""
    assert cell.external is not None
    names = {a.name for a in axes}
    used = [m for m in cell.external.mechanisms if any(a.name in names for a in m.axes)]
    missing = [a for m in used for a in m.axes if a.pulses is None and (m.kind == "track") != a.linear]
    if missing:
        what = ", ".join(f"'{a.name}' (line {a.span.start.line if a.span else '?'}): "
                         f"inform(pulses_per_{a.unit()}=N)" for a in missing)
        return (f"task '{task.name}' drives external axes whose encoder pulse scale INFORM needs "
                f"(a revolute base axis or a linear station axis is written in pulses, machine data); "
                f"declare it after each axis' accel: {what}")
    stations = [m for m in used if m.kind != "track"]
    if len(stations) > 1:
        return (f"task '{task.name}' must drive at most one positioner for INFORM (one station group ST1; "
                f"got {', '.join(m.name for m in stations)})")
    base = tuple(a for m in used if m.kind == "track" for a in m.axes)
    origin = stations[0].base.position if stations else (0.0, 0.0, 0.0)
    coordinated = any(is_coordinated(n) for n in ir_tree.walk(task.body) if isinstance(n, ir.Move))
    in_robot = cell.robot(task.robot).base.inverse() * stations[0].base if coordinated and stations else None
    return InformAxes(base, tuple(a for m in stations for a in m.axes), origin, in_robot)


def task_axes(backend: Backend, task: TaskContext, body: tuple[ir.Instr, ...]) -> InformAxes | str | None:
    """The task's base and station axes (None without), or, after the located refusal (E607 at
    the first move that drives them), why they cannot be written; W604 for a station."""
    cell = task.plan.program.cell
    axes = driven_axes(task.task, cell)
    if not axes:
        return None
    found = inform_axes(task.task, cell, axes)
    moves = [n for n in ir_tree.walk(body) if isinstance(n, ir.Move)]
    first = next(n for n in moves if n.ext)
    refused = None if isinstance(found, str) else refusal(task.task, moves, tuple(a.name for a in found.base))
    if refused is not None:
        found, first = refused
    if isinstance(found, str):
        backend.unsupported(codes.EXT_AXES_UNSUPPORTED, found, first.span)
        return found
    if found.assumed():
        axes_named = ", ".join(f"'{a.name}'" for a in found.assumed())
        backend.warn(codes.INFORM_ASSUMED_SCALE, f"station axes {axes_named} declare no pulse scale: "
                     f"EC positions are written at an ASSUMED {ASSUMED_PULSES_PER_DEG:g} pulses/deg "
                     f"(100000 per turn); confirm it with the positioner's gear ratio (pulses per axis "
                     f"turn, parameters RCnG of ALL.PRM) or declare inform(pulses_per_deg=N)", first.span)
    alone = station_alone(moves, found.station)
    if alone is not None:
        backend.warn(codes.INFORM_STATION_SPEED, "the station (GROUP2 ST1) moves at its own VJ "
                     "(+MOVJ): it starts with the arm but may end at another time than the plan's "
                     "time-synchronous move", alone.span)
    return found


def station_alone(moves: list[ir.Move], station: tuple[ExtAxis, ...]) -> ir.Move | None:
    """The first of `moves` (in program order, from the axes' home values) that moves a station
    axis and is not coordinated: the station's `+MOVJ ECn VJ=v` at its own speed (W604); None
    when the station moves only with coordinated moves (SMOVL/SMOVC, the robot's V=) or not."""
    now = {a.name: a.home for a in station}
    for move in moves:
        values = dict(move.ext)
        new = {name: values.get(name, value) for name, value in now.items()}
        if not is_coordinated(move) and any(abs(new[name] - now[name]) > 1e-12 for name in now):
            return move
        now = new
    return None


def warn_pulse_rounding(backend: Backend, node: ir.Move, rec: plan_types.InstructionRecord, axes: InformAxes,
                        ctx: TaskContext) -> None:
    """W605 (once per task) when whole pulses move `node`'s target by more than 0.01 mm."""
    cell = ctx.plan.program.cell
    if rec.tcp_pose is None or "pulse rounding" in ctx.warned:
        return
    base = cell.external.world(ctx.robot.name, dict(node.ext)) if cell.external else None
    bound = axes.rounding_mm(node, ((base or ctx.robot.base) * rec.tcp_pose).position)
    if bound > PULSE_TOLERANCE_MM:
        ctx.warned.add("pulse rounding")
        backend.warn(codes.PULSE_ROUNDING, f"whole encoder pulses move the target by up to {bound:.3g} mm "
                     f"relative to the part (more than {PULSE_TOLERANCE_MM:g} mm): a coarse pulse scale", node.span)
