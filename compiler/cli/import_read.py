"""What both forms of `rmot import` share: the cell's signals of one robot, one robot's files
read and fitted to that cell (signals, tools, payloads, INFORM configurations), the per-file
summary and the output checks (import_cmd.py: one robot; import_tasks.py: --task, several).
"""

from __future__ import annotations

import math
import sys
from collections.abc import Sequence
from typing import TYPE_CHECKING

import click

from rmot.compiler.cli import EXIT_INPUT
from rmot.lang.atomic import write_text
from rmot.lang.diagnostics import render_all

if TYPE_CHECKING:
    import numpy as np

    from rmot.backends.readers.model import Document, PulsePose
    from rmot.lang import ir
    from rmot.lang.ir import Pose
    from rmot.sim.robots.robot import Robot

__all__ = ["cell_signals", "robot_signals", "read_on_robot", "print_summary", "write_output", "refuse_output_input"]


def _arm(model: str | None) -> Robot | None:
    """The library arm or URDF `model` (the cell's robot or --robot), None where there is none or
    it does not load: a reader then keeps what it would derive from the arm."""
    if not model:
        return None
    from rmot.sim.robots.errors import RobotError  # late: loads coal only when this runs
    from rmot.sim.robots.loader import load_robot  # late: loads coal only when this runs

    try:
        return load_robot(model)
    except RobotError:
        return None


def _wide_joints(robot: Robot) -> tuple[int, ...]:
    """The joints (0-based) whose range spans more than 360°: only those take a turn."""
    return tuple(j for j, (lo, hi) in enumerate(robot.joint_limits.tolist()) if hi - lo > 2 * math.pi + 1e-9)


def _joint_limits(model: str | None) -> tuple[tuple[float, ...], tuple[float, ...]] | None:
    """(speed rad/s, acceleration rad/s^2) of each joint of the arm `model`, None where it does not
    load: a reader then keeps the joint shares it cannot derive."""
    robot = _arm(model)
    return None if robot is None else (tuple(map(float, robot.velocity_limits)), tuple(map(float, robot.accel_limits)))


def _inform_configs(doc: Document, model: str | None, tcp_of: dict[str, Pose]) -> Document:
    """INFORM joint moves configured from their RCONF with the arm's IK (readers/inform_conf.py);
    `doc` as it is for other vendors or where the arm does not load."""
    robot = _arm(model) if doc.vendor == "inform" else None
    if robot is None:
        return doc
    from rmot.backends.readers.inform_conf import resolve_rconf  # late: loads numpy only when this runs

    def ik(flange: np.ndarray) -> tuple[Sequence[np.ndarray], Sequence[ir.Config]]:
        result = robot.ik(flange)
        return result.solutions, result.branches

    return resolve_rconf(doc, ik, tcp_of, _wide_joints(robot))


def _ur_qnear(doc: Document, model: str | None, tcp_of: dict[str, Pose] | None) -> Document:
    """URScript joint moves to `get_inverse_kin(P, qnear=Q)` configured from the arm's solution
    nearest Q (readers/urscript_qnear.py); without the arm (`tcp_of` None: neither a cell nor
    --robot) they keep rmot's rule and say so (W529)."""
    if doc.vendor != "urscript":
        return doc
    from rmot.backends.readers import span_of  # late: loads numpy only when this runs
    from rmot.backends.readers.urscript_qnear import resolve_qnear  # late: loads numpy only when this runs

    robot = _arm(model) if tcp_of is not None else None
    if robot is None:
        return resolve_qnear(doc, None, {}, (), span_of)

    def ik(flange: np.ndarray, seed: np.ndarray) -> tuple[Sequence[np.ndarray], Sequence[ir.Config]]:
        result = robot.ik(flange, seed=seed)
        return result.solutions, result.branches

    return resolve_qnear(doc, ik, tcp_of or {}, _wide_joints(robot), span_of)


def _pulse_pose(model: str | None, found: tuple[object, str, object]) -> PulsePose | None:
    """The TCP pose in the arm's base of joint values (deg) with one of the cell robot's tools,
    by name (None for another name): the arm's forward kinematics times the tool's TCP. None
    where the arm does not load."""
    import numpy as np  # late: loads numpy only when this runs
    from rmot.lang import ir  # late: tests replace it (monkeypatch): read at call time

    cell, robot_name = found[2], found[1]
    assert isinstance(cell, ir.Cell)
    arm = _arm(model)
    if arm is None:
        return None
    tcp_of = {t.name: t.tcp for t in cell.tools if t.robot == robot_name}

    def pose(joints: tuple[float, ...], tool: str) -> ir.Pose | None:
        if tool not in tcp_of or len(joints) != arm.dof:
            return None
        return ir.Pose.from_matrix(arm.fk(np.radians(joints))) * tcp_of[tool]

    return pose


def cell_signals(cell_path: str, robot: str | None) -> tuple[object, str, object] | str:
    """(SignalMap, robot name, ir.Cell) of a cell file, or the error text."""
    from rmot.compiler.frontend import load_program  # late: tests replace it (monkeypatch): read at call time

    result = load_program(cell_path)
    if result.cell is None or any(d.is_error for d in result.diagnostics):
        return render_all([d for d in result.diagnostics if d.is_error]) or f"rmot: {cell_path}: not a cell"
    names = [r.name for r in result.cell.robots]
    chosen = robot or names[0]
    if chosen not in names:
        return f"rmot: --robot must name a robot of the cell ({', '.join(names)}; got {chosen})"
    return robot_signals(result.cell, chosen)


def robot_signals(cell: ir.Cell, robot: str) -> tuple[object, str, object]:
    """(SignalMap, robot, cell): the named signals of the cell's `robot` (and the shared ones)."""
    from rmot.backends.readers.writer import SignalMap  # late: loads numpy only when this runs
    from rmot.lang import ir  # late: tests replace it (monkeypatch): read at call time

    kinds = {ir.IoDirection.DIGITAL_OUT: 0, ir.IoDirection.DIGITAL_IN: 1, ir.IoDirection.ANALOG_OUT: 2,
             ir.IoDirection.GROUP_IN: 3}
    tables: list[list[tuple[str, int]]] = [[], [], [], []]
    for s in cell.io:
        if s.direction in kinds and s.robot in (None, robot):
            tables[kinds[s.direction]].append((s.name.upper(), s.port))
    return SignalMap(*(tuple(t) for t in tables)), robot, cell


def read_on_robot(files: list[str], cell: str | None, found: tuple[object, str, object] | None,
                   model: str | None, pulses_per_degree: tuple[float, ...] | None = None) -> Document:
    """The files read for one robot: with a cell (`found`: its signals, robot, ir.Cell), named
    signals resolved, tools and payloads matched to that robot's, INFORM configurations solved;
    `pulses_per_degree`: the arm's scales (INFORM pulse positions read as joints)."""
    from rmot.backends.readers import read_files, span_of  # late: loads numpy only when this runs
    from rmot.backends.readers.axes import resolve_axes  # late: loads numpy only when this runs
    from rmot.backends.readers.payload import cell_parts, match_payloads  # late: loads numpy only when this runs
    from rmot.backends.readers.writer import SignalMap, match_tools, resolve_signals  # late: loads numpy only when this runs
    from rmot.lang import ir  # late: tests replace it (monkeypatch): read at call time

    if found is not None:
        cell_ir = found[2]
        assert isinstance(cell_ir, ir.Cell)
        model = cell_ir.robot(found[1]).source.ref
    # TCP poses of joint positions: INFORM pulse positions read with scales, TP joint-form positions
    joint_form = pulses_per_degree is not None or any(f.lower().endswith(".ls") for f in files)
    pulse_pose = _pulse_pose(model, found) if joint_form and found is not None else None
    doc = read_files(files, model=model, limits=_joint_limits(model), pulses_per_degree=pulses_per_degree,
                     pulse_pose=pulse_pose)
    if cell is None or found is None:
        tools = {t.name: t.tcp for t in doc.tools} if model else None  # the stub cell's tools: the files' own
        return resolve_axes(_ur_qnear(doc, model, tools), None, "r1", span_of)  # a stub cell declares no mechanism: W523
    signals, robot_name, cell_ir = found
    assert isinstance(signals, SignalMap) and isinstance(cell_ir, ir.Cell)
    doc = resolve_signals(doc, signals, span_of)
    doc = match_tools(doc, tuple((t.name, t.tcp) for t in cell_ir.tools if t.robot == robot_name))
    doc = match_payloads(doc, cell_parts(cell_ir),
                         tuple((t.tcp, t.mass) for t in cell_ir.tools if t.robot == robot_name), span_of)
    doc = _inform_configs(doc, model, {t.name: t.tcp for t in cell_ir.tools if t.robot == robot_name})
    doc = _ur_qnear(doc, model, {t.name: t.tcp for t in cell_ir.tools if t.robot == robot_name})
    return resolve_axes(doc, cell_ir, robot_name, span_of)


def refuse_output_input(path: str, inputs: tuple[str, ...]) -> None:
    """Exit 2 (E564) before any work when OUT is one of the vendor files (it would be replaced)."""
    from rmot.compiler.cli.oserrors import output_is_input  # late: optional, tried where used

    same = output_is_input("program", path, inputs)
    if same is not None:
        click.echo(same, err=True)
        sys.exit(EXIT_INPUT)


def write_output(what: str, path: str, text: str, inputs: tuple[str, ...]) -> None:
    """Write `path` atomically; one of the vendor files (E564) or unwritable (E520): exit 2."""
    from rmot.compiler.cli.oserrors import output_failed  # late: optional, tried where used

    refuse_output_input(path, inputs)
    try:
        write_text(path, text)
    except OSError as exc:
        click.echo(output_failed(what, path, exc), err=True)
        sys.exit(EXIT_INPUT)


def print_summary(doc: Document) -> None:
    """Per file: how many instructions were imported and kept native, all and motion and I/O."""
    from rmot.backends.readers.counts import motion_io_counts  # late: loads numpy only when this runs

    motion_io = motion_io_counts(doc)
    for c in doc.counts:
        total = c.imported + c.native
        share = 100.0 * c.imported / total if total else 100.0
        moved, kept = motion_io.get(c.path, (0, 0))
        io_share = 100.0 * moved / (moved + kept) if moved + kept else 100.0
        click.echo(f"{c.path}: {c.imported} imported, {c.native} kept native ({share:.1f} % imported); "
                   f"motion and I/O: {moved} imported, {kept} kept native ({io_share:.1f} %)")
