"""Plain helpers for the backend tests: import with `from backend_fixtures import ...`
(pytest puts this folder on sys.path). See conftest.py for the fixtures."""

from __future__ import annotations

import math
import os
import re
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from rmot.backends.base import Backend, EmitResult
from rmot.lang import ir, ir_tree, plan_types
from rmot.lang.diagnostics import Diagnostic
from rmot.lang.source import Pos, SourceFile, Span

DEMO_FILE = SourceFile("demo.rmot", "\n" * 200)


def span_at(line: int) -> Span:
    """A one-character span at column 3 of `line` in demo.rmot."""
    return Span(DEMO_FILE, Pos(line, 3, 0), Pos(line, 4, 0))


FRONT_UP_NOFLIP = ir.Config(ir.Shoulder.FRONT, ir.Elbow.UP, ir.Wrist.NOFLIP)


def motion(speed: float = 0.25, joint: float = 1.0, zone: float = 0.0,
           duration: float | None = None) -> ir.Motion:
    """A Motion in SI units (speed m/s, zone radius m)."""
    return ir.Motion(tcp_speed=speed, tcp_accel=2.0, joint_speed=joint, joint_accel=1.0,
                     zone=ir.Zone(zone), duration=duration)


def cell(robot: str = "abb_irb120", dof: int = 6) -> ir.Cell:
    r1 = ir.RobotInstance("r1", ir.RobotSource(ir.RobotSourceKind.LIBRARY, robot), ir.Pose(), dof)
    return ir.Cell("democell", (r1,))


def hand_plan(body: tuple[ir.Instr, ...], records: dict[int, tuple[np.ndarray, ir.Config | None]],
              *, robot: str = "abb_irb120", dof: int = 6, name: str = "demo",
              durations: dict[int, float] | None = None) -> plan_types.Plan:
    """A Plan built by hand: `records` maps a move's uid to (q_target (dof,), branch).

    Moves of If arms and proc bodies are looked up the same way; a move's record blends with
    its programmed zone and is timed with its own `accel` (a hand plan models no stops and no
    chains). Each record lasts 1 s unless
    `durations` says otherwise; the trajectory is two samples (backends do not read it).
    """
    durations = durations or {}
    recs = []
    t = 0.0
    for node in ir_tree.walk(body):
        if node.uid in records:
            q, branch = records[node.uid]
            d = durations.get(node.uid, 1.0)
            tcp = node.target.pose if isinstance(node, ir.Move) and isinstance(node.target, ir.CartesianTarget) else None
            recs.append(plan_types.InstructionRecord(uid=node.uid, span=node.span, t_start=t, t_end=t + d,
                                                  q_target=np.asarray(q, float), branch=branch, tcp_pose=tcp,
                                                  q_via=np.asarray(q, float) if getattr(node, "via", None) else None,
                                                  blend_radius=node.motion.zone.radius if isinstance(node, ir.Move) else 0.0,
                                                  accel_share=node.motion.joint_accel if isinstance(node, ir.Move) else 1.0))
            t += d
    traj = plan_types.Trajectory(np.array([0.0, max(t, 0.004)]), np.zeros((2, dof)), np.zeros((2, dof)),
                              np.zeros((2, dof)))
    task = ir.Task("main", "r1", body, span=span_at(1))
    program = ir.Program(name, cell(robot, dof), (task,), span=span_at(1))
    return plan_types.Plan(program, (plan_types.TaskPlan(task, "r1", traj, tuple(recs)),))


def deg(*values: float) -> np.ndarray:
    return np.radians(np.array(values, float))


# --------------------------------------------------------------------------- instruction tables

J, L, C = ir.MotionKind.JOINT, ir.MotionKind.LINEAR, ir.MotionKind.CIRCULAR
DOWN = ir.Pose.from_xyz_rpy(0.4, -0.1, 0.3, math.pi, 0, 0)  # the TCP pointing down
Q = deg(10, 20, 30, -100, -50, 200)  # the planned joints of every move of a table row


@dataclass(frozen=True)
class Row:
    """One row of a vendor's instruction table: an IR instruction alone in a program, the lines
    it prints, the declarations it adds and the diagnostic codes it reports (in order)."""

    name: str
    instr: ir.Instr
    lines: tuple[str, ...]
    decls: tuple[str, ...] = ()
    codes: tuple[str, ...] = ()


def emit_row(backend: type[Backend], row: Row) -> EmitResult:
    """`backend`'s output for `row.instr` alone, every move in it planned at Q, FRONT_UP_NOFLIP."""
    records = {n.uid: (Q, FRONT_UP_NOFLIP) for n in ir_tree.walk((row.instr,)) if isinstance(n, ir.Move)}
    return backend().emit(hand_plan((row.instr,), records, robot=BRAND_ROBOT.get(backend.name, "abb_irb120")))


# an arm of each vendor's own brand (no W415 in the instruction tables)
BRAND_ROBOT = {"rapid": "abb_irb120", "krl": "kuka_kr6_r900", "fanuc": "fanuc_lrmate200id",
               "urscript": "ur5e", "inform": "yaskawa_gp8", "val3": "staubli_tx2_60"}


# --------------------------------------------------------------------------- sample programs

GRIPPER = ir.ToolRef("gripper", ir.Pose((0.0, 0.0, 0.15)), 1.2)
TABLE = ir.FrameRef("table_top", ir.Pose((0.5, 0.0, 0.015)), ir.Pose((0.5, 0.0, 0.015)))
FLANGE = ir.ToolRef(None)
BASE = ir.FrameRef(None)


def cart(in_frame: ir.Pose, frame: ir.FrameRef = BASE, name: str | None = "p") -> ir.CartesianTarget:
    """A Cartesian target written in `frame` (pose composed into the robot base frame)."""
    return ir.CartesianTarget(frame.pose * in_frame, in_frame, name)


def move(uid: int, kind: ir.MotionKind, target: ir.CartesianTarget | ir.JointTarget, *,
         tool: ir.ToolRef = FLANGE, frame: ir.FrameRef = BASE, via: ir.CartesianTarget | None = None,
         **motion_args: float) -> ir.Move:
    return ir.Move(uid=uid, kind=kind, target=target, via=via, motion=motion(**motion_args), tool=tool,
                   frame=frame, span=span_at(10 + uid))


def sample_program() -> plan_types.Plan:
    """Every instruction kind once (moves of all three kinds, I/O, wait, if, proc, native)."""
    down = ir.Pose.from_xyz_rpy(0.1, 0.2, 0.15, math.pi, 0, 0)
    tgt = cart(down, TABLE, "above")
    via = cart(ir.Pose.from_xyz_rpy(0.15, 0.25, 0.15, math.pi, 0, 0), TABLE, "arc_mid")
    home = ir.JointTarget(tuple(deg(0, -30, 30, 0, 60, 0)), "home")
    J, L, C = ir.MotionKind.JOINT, ir.MotionKind.LINEAR, ir.MotionKind.CIRCULAR
    body = (
        move(1, J, home, joint=0.5),
        move(2, L, tgt, tool=GRIPPER, frame=TABLE, speed=0.1234, zone=0.0075),
        ir.SetDigital(uid=3, port=1, value=True, signal="gripper_close", span=span_at(5)),
        ir.ProcCall(uid=4, proc="pick", args=("above",), span=span_at(6), body=(
            ir.WaitTime(uid=5, duration=0.3, span=span_at(7)),
            move(6, C, tgt, via=via, tool=GRIPPER, frame=TABLE, zone=0.01))),
        ir.If(uid=7, condition=ir.InputCondition(port=2, value=True, signal="part_present"), span=span_at(9),
              then=(ir.Pulse(uid=8, port=3, duration=0.2, span=span_at(10)),),
              otherwise=(ir.WaitInput(uid=9, condition=ir.InputCondition(port=2, value=True), timeout=5.0,
                                      span=span_at(11)),)),
        ir.SetAnalog(uid=10, port=1, value=4.5, span=span_at(12)),
        ir.Native(uid=11, vendor="rapid", text='TPWrite "cycle done";', span=span_at(13)),
        ir.Native(uid=12, vendor="krl", text="HALT", span=span_at(14)),
        ir.Native(uid=13, vendor="fanuc", text="MESSAGE[done]", span=span_at(15)),
        move(14, J, cart(down, TABLE, "above"), tool=GRIPPER, frame=TABLE, speed=0.1, duration=2.5),
    )
    recs = {1: (deg(0, -30, 30, 0, 60, 0), FRONT_UP_NOFLIP), 2: (deg(10, 20, 30, -100, -50, 200), FRONT_UP_NOFLIP),
            6: (deg(-10, 20, 30, 40, 50, 60), FRONT_UP_NOFLIP), 14: (deg(10, 20, 30, -100, -50, 200), FRONT_UP_NOFLIP)}
    return hand_plan(body, recs)


def routine_lines(text: str, start: str, end: str) -> list[str]:
    """The stripped, non-comment lines between the line `start` and the next line `end`."""
    lines = [ln.strip() for ln in text.splitlines()]
    i = lines.index(start)
    j = lines.index(end, i)
    return [ln for ln in lines[i + 1:j] if ln and not ln.startswith(("!", ";"))]


def handshake_missing(plan: plan_types.Plan) -> bool:
    """A multi-task program whose cell lacks some syncing robot's "sync" signals: the I/O
    handshake vendors then refuse its syncs (E409)."""
    from rmot.backends.handshake import handshake_ports

    program = plan.program
    return len(program.tasks) > 1 and any(
        handshake_ports(program.cell, t.robot) is None
        for t in program.tasks if any(isinstance(n, ir.Sync) for n in ir_tree.walk(t.body)))


# --------------------------------------------------------------------------- reading output back


def diagnostic_keys(diagnostics: Iterable[Diagnostic]) -> list[str]:
    """`severity:code:line` per diagnostic (line 0 without a span), in order."""
    return [f"{d.severity.value}:{d.code.id}:{d.span.start.line if d.span else 0}" for d in diagnostics]


def blocks(text: str, marker: str, *, skip: tuple[str, ...] = (), drop: tuple[str, ...] = (),
           stop: str | None = None, strip: bool = True) -> dict[int, list[str]]:
    """Source line -> the lines printed under its `<marker>demo.rmot:N` source comment.

    Left out: empty lines, other comments (starting with `marker`), lines starting with one of
    `skip` and lines equal to one of `drop`; a line equal to `stop` ends the block. `strip`:
    compare lines without their indentation.
    """
    pattern = re.escape(marker) + r"demo\.rmot:(\d+)"
    out: dict[int, list[str]] = {}
    current: list[str] | None = None
    for raw in text.splitlines():
        line = raw.strip() if strip else raw
        m = re.fullmatch(pattern, line)
        if m:
            current = out.setdefault(int(m.group(1)), [])
        elif stop is not None and line == stop:
            current = None
        elif (current is not None and line and not line.startswith((marker.strip(), *skip))
              and line not in drop):
            current.append(line)
    return out


# --------------------------------------------------------------------------- shipped examples and golden files

ROOT = Path(__file__).resolve().parents[2]
GOLDEN = Path(__file__).parent / "golden"
UPDATE_GOLDEN = os.environ.get("RMOT_UPDATE_GOLDEN") == "1"


def example_plans(names: Iterable[str]) -> dict[str, plan_types.Plan]:
    """examples/<name>.rmot through the real front end and planner, per name. The planner is
    reached through the plan cache (the session's folder, tests/conftest.py), so an example the
    command line already planned in this run (`rmot compile` of the same file) is read back
    rather than planned again, and the other way round."""
    from rmot.compiler.frontend import load_program
    from rmot.compiler.plan_cache import cached_plan

    out = {}
    for name in names:
        if name not in _PLANNED:  # plans are immutable: each example is planned once per run
            front = load_program(str(ROOT / "examples" / f"{name}.rmot"))
            assert front.program is not None, [d.message for d in front.diagnostics]
            _PLANNED[name] = cached_plan(front.program)
        out[name] = _PLANNED[name]
    return out


_PLANNED: dict[str, plan_types.Plan] = {}


def check_golden(vendor: str, example: str, files: dict[str, str]) -> None:
    """Each file equals golden/<vendor>/<example>__<file> ('/' in a file name as '__');
    RMOT_UPDATE_GOLDEN=1 rewrites the golden files instead (review the diff by hand)."""
    folder = GOLDEN / vendor
    for name, text in files.items():
        path = folder / f"{example}__{name.replace('/', '__')}"
        if UPDATE_GOLDEN:
            folder.mkdir(parents=True, exist_ok=True)
            path.write_text(text, encoding="utf-8")
        assert path.read_text(encoding="utf-8") == text, f"{path.name} differs (regenerate: see check_golden)"
