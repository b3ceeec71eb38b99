"""Pass 4: the top-level scope of every file (imports, consts, targets, procs) and duplicates.

Scoping (LANGUAGE.md is silent; RAPID/KRL-like):
  * cell scope (robots, fixtures, tools, frames, cell consts)
      <- file scope (what the file imports + its own top-level const/target/proc)
      <- program scope <- task scope <- block scopes (loops, if arms, proc bodies).
  * `import "lib.rmot"` makes the library's own top-level procs, targets and consts visible;
    what the library itself imports is not re-exported.
  * Procs are hoisted (callable before their definition, as in RAPID); consts, targets and
    frames are defined in source order and must be defined before use.
  * Defining a name twice in one scope is an error with a note at the first definition;
    an inner scope may shadow an outer one.
"""

from __future__ import annotations

from dataclasses import replace

from rmot.lang import check_codes as codes
from rmot.compiler.passes.context import Entry, Reporter, Scope
from rmot.compiler.passes.evaluate import eval_expr
from rmot.compiler.passes.state import FrontendState, LoadedModule
from rmot.compiler.passes.values import JointsV, PoseV, article, type_name
from rmot.lang import ast

__all__ = ["declare", "declare_file_scopes", "misplaced", "STATEMENT_WORDS"]

STATEMENT_WORDS = {
    "UseCell": "'use cell'", "Import": "'import'", "CellDecl": "a cell", "ProgramDecl": "a program",
    "TaskDecl": "a task", "RobotDecl": "a robot", "FixtureDecl": "a fixture", "ToolDecl": "a tool declaration",
    "FrameDecl": "a frame declaration", "IoDecl": "an io declaration", "TargetDecl": "a target",
    "ConstDecl": "a const", "ProcDecl": "a proc", "Setting": "a setting", "Move": "a move",
    "SetIo": "'set'", "Pulse": "'pulse'", "WaitTime": "'wait'", "WaitUntil": "'wait until'",
    "For": "a for loop", "Repeat": "'repeat'", "IfStmt": "'if'", "SyncStmt": "'sync'",
    "NativeStmt": "'native'", "CallStmt": "a proc call",
}
STATEMENT_WORDS["ModelDecl"] = "a robot model (it belongs in a cell)"
STATEMENT_WORDS.update({"VarDecl": "a var", "AssignStmt": "an assignment", "StopStmt": "'stop'",
                        "While": "a while loop"})
STATEMENT_WORDS["FeederDecl"] = "a feeder (it belongs in a cell or at a program's top level)"
_ALLOWED_IN = {
    "file": "a file holds use cell, import, cell, program, const, target and proc",
    "cell": "a cell holds robot, fixture, tool, frame, io and const",
    "program": "a program holds settings, declarations and instructions (and tasks when it has no 'on ROBOT')",
}


def declare(scope: Scope, entry: Entry, rep: Reporter) -> bool:
    """Bind entry.name in scope; a second definition in the same scope is an error."""
    first = scope.names.get(entry.name)
    if first is not None:
        rep.error(codes.DUPLICATE, f"'{entry.name}' must be defined once in this scope (got a second {entry.kind})",
                  entry.span, ((f"'{entry.name}' is first defined here", first.span),))
        return False
    scope.names[entry.name] = entry
    return True


def misplaced(stmt: ast.Stmt, where: str, rep: Reporter) -> None:
    what = STATEMENT_WORDS.get(type(stmt).__name__, "this statement")
    kind = "cell" if where.startswith("cell") else "program" if where.startswith(("program", "task", "proc")) else "file"
    rep.error(codes.MISPLACED, f"{what} must not appear in {where} ({_ALLOWED_IN[kind]})", stmt.span)


def declare_procs(body: tuple[ast.Stmt, ...], scope: Scope, rep: Reporter, procs: list[Entry]) -> None:
    for stmt in body:
        if isinstance(stmt, ast.ProcDecl):
            entry = Entry("proc", stmt.name.name, stmt, stmt.name.span, closure=scope)
            if declare(scope, entry, rep):
                procs.append(entry)


def declare_value(stmt: ast.TargetDecl | ast.ConstDecl, scope: Scope, rep: Reporter) -> None:
    value = eval_expr(stmt.value, scope, rep)
    kind = "target" if isinstance(stmt, ast.TargetDecl) else "const"
    if value is None:
        # still claim the name: later uses should not also say "unknown name"
        declare(scope, Entry(kind, stmt.name.name, None, stmt.name.span), rep)
        return
    if kind == "target":
        if not isinstance(value, (PoseV, JointsV)):
            rep.error(codes.WRONG_TYPE, f"target '{stmt.name.name}' must be a pose or joints() (got {article(type_name(value))})",
                      stmt.value.span)
            value = None
        else:
            value = _named(value, stmt.name.name)
    declare(scope, Entry(kind, stmt.name.name, value, stmt.name.span), rep)


def _named(value: PoseV | JointsV, name: str) -> PoseV | JointsV:
    if hasattr(value, "name") and hasattr(value, "__dataclass_fields__"):
        return replace(value, name=name)
    return value


def _file_scope(mod: LoadedModule, state: FrontendState, procs: list[Entry]) -> Scope:
    rep = state.reporter
    scope = Scope(state.cell_scope)
    for path in mod.imports:
        lib = state.module_scopes.get(path)
        if lib is None:
            continue
        for entry in lib.names.values():
            if entry.kind in ("proc", "target", "const"):
                declare(scope, entry, rep)
    declare_procs(mod.module.body, scope, rep, procs)
    for stmt in mod.module.body:
        if isinstance(stmt, (ast.TargetDecl, ast.ConstDecl)):
            declare_value(stmt, scope, rep)
        elif not isinstance(stmt, (ast.ProcDecl, ast.Import, ast.UseCell, ast.CellDecl, ast.ProgramDecl)):
            misplaced(stmt, "a file's top level", rep)
    return scope


def declare_file_scopes(state: FrontendState) -> FrontendState:
    """Libraries first (dependencies before dependents), then the main file."""
    procs: list[Entry] = list(state.procs)
    scopes = dict(state.module_scopes)
    for lib in state.libraries:
        scopes[lib.path] = _file_scope(lib, replace(state, module_scopes=scopes), procs)
    if state.main is not None:
        scopes[state.main.path] = _file_scope(state.main, replace(state, module_scopes=scopes), procs)
    return replace(state, module_scopes=scopes, procs=tuple(procs))
