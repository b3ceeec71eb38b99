"""Pass 5: the program block -> ir.Program with one ir.Task per robot.

Choices (LANGUAGE.md is silent):
  * `program P on r1 { ... }` has one task, named after the program (P), on robot r1.
  * `program P { task r1 {...} task r2 {...} }`: one task per block, named after its robot;
    a robot may have one task. Declarations (target, const, proc, frame) and settings at
    program level are shared by every task; instructions there are errors.
  * `program P { ... }` with neither `on` nor tasks runs on the cell's only robot (an
    error if the cell has several).
  * A file holds at most one program.
"""

from __future__ import annotations

from dataclasses import replace

from rmot.lang import codes_axes, check_codes as codes, ir
from rmot.compiler.passes.context import Entry, Reporter, Scope
from rmot.compiler.passes.lower_body import TaskLowering
from rmot.compiler.passes.lower_axes import check_axis_branches, program_axes, refuse_track_in_tasks
from rmot.compiler.passes.lower_cell import program_feeders
from rmot.compiler.passes.modal import DEFAULT_MODAL, Modal, apply_setting
from rmot.compiler.passes.state import FrontendState
from rmot.lang import ast
from rmot.compiler.passes.scopes import STATEMENT_WORDS

__all__ = ["lower_program"]

_SHARED = (ast.TargetDecl, ast.ConstDecl, ast.FrameDecl, ast.ProcDecl)


def lower_program(state: FrontendState) -> FrontendState:
    if state.main is None:
        return state
    programs = [s for s in state.main.module.body if isinstance(s, ast.ProgramDecl)]
    for extra in programs[1:]:
        state.reporter.error(codes.NO_PROGRAM, "a file must contain at most one program (got a second one)", extra.name.span,
                             (("the first program is here", programs[0].name.span),))
    cell = state.cell
    if not programs or cell is None:
        return state
    prog = programs[0]
    file_scope = state.module_scopes.get(state.main.path, Scope(state.cell_scope))
    procs: list[Entry] = list(state.procs)
    scope = Scope(file_scope)
    state = program_feeders(state, prog, scope)  # a program's own feeders join the cell's parts
    cell = state.cell
    assert cell is not None
    tasks = _lower_tasks(prog, state, scope, procs)
    state = replace(state, procs=tuple(procs))  # with the procs declared inside the program
    if tasks is None:
        return state
    return replace(state, program=ir.Program(prog.name.name, cell, tuple(tasks), span=prog.span))


def _robot(name: ast.Ident, state: FrontendState) -> ir.RobotInstance | None:
    assert state.cell is not None
    for r in state.cell.robots:
        if r.name == name.name:
            return r
    state.reporter.unknown(name.name, "robot", name.span, [r.name for r in state.cell.robots])
    return None


def _lower_tasks(prog: ast.ProgramDecl, state: FrontendState, scope: Scope, procs: list[Entry]) -> list[ir.Task] | None:
    rep = state.reporter
    assert state.cell is not None
    task_decls = [s for s in prog.body if isinstance(s, ast.TaskDecl)]
    where = f"program '{prog.name.name}'"
    if prog.robot is not None or not task_decls:
        for t in task_decls:
            rep.error(codes.MISPLACED, f"a task must not appear in a program on one robot ({where} runs on '{prog.robot.name}')"
                      if prog.robot else "a task must not appear here", t.span)
        robot_name = prog.robot
        if robot_name is None:
            if len(state.cell.robots) != 1:
                rep.error(codes.BAD_TASK, f"{where} must say 'on ROBOT' or hold task blocks (got neither, and cell "
                          f"'{state.cell.name}' has {len(state.cell.robots)} robots)", prog.name.span)
                return None
            robot_name = ast.Ident(state.cell.robots[0].name, prog.name.span)
        robot = _robot(robot_name, state)
        if robot is None:
            return None
        body = tuple(s for s in prog.body if not isinstance(s, (ast.TaskDecl, ast.FeederDecl)))
        lowering = _task_lowering(robot, state, procs)
        lowering.axes = program_axes(prog, robot, state.cell, rep)
        instrs = lowering.run(body, scope, DEFAULT_MODAL, where)
        check_axis_branches(instrs, rep)
        return [ir.Task(prog.name.name, robot.name, instrs, span=prog.span)]
    # several tasks: shared declarations once, then each task with the shared settings
    shared = tuple(s for s in prog.body if isinstance(s, _SHARED))
    settings = tuple(s for s in prog.body if isinstance(s, ast.Setting))
    for ident in prog.axes[:1]:
        rep.error(codes_axes.EXT_PROGRAM_AXES, f"'with' must go with a program on one robot (got task blocks in {where})", ident.span)
    for s in prog.body:
        if not isinstance(s, (*_SHARED, ast.Setting, ast.TaskDecl, ast.FeederDecl)):
            rep.error(codes.MISPLACED, f"{_word(s)} must be inside a task in {where} (it has task blocks)", s.span)
    first_robot = _robot(task_decls[0].robot, state) or state.cell.robots[0] if state.cell.robots else None
    if first_robot is None:
        return None
    _task_lowering(first_robot, state, procs).run(shared, scope, DEFAULT_MODAL, where)
    tasks: list[ir.Task] = []
    seen: dict[str, ast.TaskDecl] = {}
    for t in task_decls:
        if t.robot.name in seen:
            rep.error(codes.BAD_TASK, f"robot '{t.robot.name}' must have one task (got a second one)", t.robot.span,
                      (("its first task is here", seen[t.robot.name].robot.span),))
            continue
        robot = _robot(t.robot, state)
        if robot is None:
            continue
        refuse_track_in_tasks(robot, state.cell, t.robot.span, rep)
        seen[t.robot.name] = t
        lowering = _task_lowering(robot, state, procs)
        modal = _settings(settings, scope, robot, rep)
        instrs = lowering.run(t.body, scope.child(), modal, f"task '{t.robot.name}'")
        tasks.append(ir.Task(t.robot.name, robot.name, instrs, span=t.span))
    return tasks


def _word(s: ast.Stmt) -> str:

    return STATEMENT_WORDS.get(type(s).__name__, "this statement")


def _settings(settings: tuple[ast.Setting, ...], scope: Scope, robot: ir.RobotInstance, rep: Reporter) -> Modal:
    modal = DEFAULT_MODAL
    for s in settings:
        modal = apply_setting(modal, s, scope, robot.name, robot.base, rep)
    return modal


def _task_lowering(robot: ir.RobotInstance, state: FrontendState, procs: list[Entry]) -> TaskLowering:
    assert state.cell is not None
    called = state.called_procs
    return TaskLowering(robot.name, state.robots[robot.name], robot.base, state.cell, state.reporter, procs, called=called)

