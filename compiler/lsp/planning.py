"""Plan and verify a document in a separate process, so the editor never waits for it.

`PlanJob` starts one process per (document, version): it runs the front end on the same
text, then the planner and the verification through the same stages and caches as
`rmot check` (compiler/cli/stages.py: the plan cache and the verification cache), and sends
back plain values: the findings as LSP diagnostics and, per move, its times and planned
joints. `cancel()` terminates the process, which is what a change to the text does to the
job of the text before it. Nothing is emitted: no vendor file is ever written.
"""

from __future__ import annotations

import multiprocessing
import os
from typing import Any

from lsprotocol import types as lsp

from rmot.lang import ir
from rmot.lang.record import record

__all__ = ["MovePlan", "PlanJob", "PlanResult", "plan_document"]


@record(slots=True)
class MovePlan:
    """What the plan decided for one move instruction (by its uid)."""

    uid: int
    task: str
    robot: str
    t_start: float  # s from the task's start
    t_end: float
    joints: tuple[float, ...]  # at the target: rad (revolute) or m (prismatic); () if not planned
    joint_types: tuple[str, ...]  # 'R' / 'P' per joint
    branch: str  # the IK branch ("shoulder=front, elbow=up, wrist=noflip"), "" if none
    # the joint closest to an end of its range at the target: (1-based joint, distance in rad
    # or m); (0, 0.0) when the robot's limits are not known here
    limit_margin: tuple[int, float] = (0, 0.0)


@record(slots=True)
class PlanResult:
    diagnostics: tuple[lsp.Diagnostic, ...]  # the plan's and the verification's findings
    moves: tuple[MovePlan, ...]
    cycle_times: tuple[tuple[str, float], ...]  # task -> s
    failed: bool = False  # the front end or a stage refused: diagnostics say why


def plan_document(path: str, text: str) -> PlanResult:
    """Front end -> plan -> verify for `text` as `path` (runs in the worker process)."""
    from rmot.compiler.cli import stages  # late: loads coal only when this runs
    from rmot.compiler.lsp.analysis import analyze  # late: loads coal only when this runs

    analysis = analyze(path, text)
    if analysis.program is None:
        return PlanResult((), (), (), True)
    try:
        planned = stages.plan(analysis.program)
        report = stages.verify(planned)
    except stages.StageError as exc:
        return PlanResult((analysis.to_lsp(exc.diagnostic),), (), (), True)
    moves = []
    for task in planned.tasks:
        types, limits = _robot_data(analysis.program, task.robot)
        for r in task.records:
            if r.q_target is None or r.variant:
                continue
            q = tuple(float(v) for v in r.q_target)
            moves.append(MovePlan(r.uid, task.task.name, task.robot, float(r.t_start), float(r.t_end), q, types,
                                  str(r.branch) if r.branch else "", _limit_margin(q, limits)))
    return PlanResult(tuple(analysis.to_lsp(d) for d in report.diagnostics), tuple(moves),
                      tuple(sorted(report.cycle_times.items())))


def _robot_data(program: ir.Program, robot: str) -> tuple[tuple[str, ...], tuple[tuple[float, float], ...]]:
    """The robot's joint types ('R'/'P') and joint ranges (as the planner loads the robot)."""
    from rmot.sim.robots import load_robot  # late: loads coal only when this runs

    for r in program.cell.robots:
        if r.name == robot:
            try:
                model = load_robot(r.source.ref)
            except Exception:  # a robot this loader cannot give: radians, no ranges shown
                return ("R",) * int(r.dof), ()
            limits = tuple((float(lo), float(hi)) for lo, hi in model.joint_limits)
            return tuple(str(t) for t in model.joint_types), limits
    return (), ()


def _limit_margin(q: tuple[float, ...], limits: tuple[tuple[float, float], ...]) -> tuple[int, float]:
    """(1-based joint, distance) of the joint nearest an end of its range (compiler/design/metrics.py
    computes the same over a whole trajectory)."""
    if len(limits) != len(q):
        return (0, 0.0)
    margins = [min(v - lo, hi - v) for v, (lo, hi) in zip(q, limits)]
    worst = min(range(len(q)), key=lambda j: margins[j])
    return (worst + 1, margins[worst])


def _child(conn: Any, path: str, text: str) -> None:
    os.dup2(2, 1)  # stdout is the server's JSON-RPC channel: anything printed here goes to stderr
    if hasattr(os, "nice"):
        os.nice(10)  # below the server: the next keystroke's front end runs first
    try:
        result = plan_document(path, text)
    except Exception as exc:  # a bug in a stage: one internal-error diagnostic, never a traceback
        from rmot.compiler.cli.stages import internal_error  # late: optional, tried where used
        from rmot.compiler.lsp.analysis import to_lsp  # late: optional, tried where used

        result = PlanResult((to_lsp(internal_error("the planner", exc), os.path.abspath(path)),), (), (), True)
    conn.send(result)
    conn.close()


class PlanJob:
    """One planning process; `result()` blocks until it answers (None if it was cancelled)."""

    def __init__(self, path: str, text: str) -> None:
        context = multiprocessing.get_context("spawn")  # never fork the server's threads
        self._recv, send = context.Pipe(duplex=False)
        self._process = context.Process(target=_child, args=(send, path, text), daemon=True)
        self._process.start()
        send.close()

    def result(self) -> PlanResult | None:
        try:
            value: PlanResult = self._recv.recv()
        except (EOFError, OSError):  # cancelled: the process was terminated
            return None
        finally:
            self._process.join(timeout=5)
        return value

    def cancel(self) -> None:
        if self._process.is_alive():
            self._process.terminate()
